//! Trial surfaces truncated at a bedrock raster: on an infinite slope over
//! a planar bedrock parallel to it at depth H, a surface every column of
//! which is truncated gives the infinite-slope Fs at that depth to
//! rounding, and the lowest Fs of a sphere search lies above it and
//! approaches it as the spheres grow; a bedrock on another grid or without
//! data under a column is refused.

use dismech::error::DismechError;
use dismech::grid::GridError;
use dismech::grid::Raster;
use dismech::hpm::NamedRaster;
use dismech::slope::*;

const BETA_DEG: f64 = 30.0;
const DEPTH: f64 = 3.0;
const CELL: f64 = 2.0;

/// A planar slope at β descending towards −y, `n × n` cells of 2 m, the
/// bedrock parallel to it `DEPTH` m below.
fn slope(n: usize) -> Terrain {
    let t = BETA_DEG.to_radians().tan();
    let dem = Raster::from_fn(n, n, 0.0, 0.0, CELL, |_, y| Some(y * t)).unwrap();
    let rock = Raster::from_fn(n, n, 0.0, 0.0, CELL, |_, y| Some(y * t - DEPTH)).unwrap();
    Terrain::new(NamedRaster::new("dem", dem), None)
        .unwrap()
        .with_bedrock(NamedRaster::new("bedrock", rock))
        .unwrap()
}

fn soil() -> SlopeMaterial {
    SlopeMaterial {
        cohesion: 4e3,
        friction_coefficient: 32f64.to_radians().tan(),
        unit_weight: 19e3,
    }
}

/// The infinite-slope Fs of a slab of vertical thickness H on a plane at
/// β: `c / (γ H sin β cos β) + tan φ / tan β`.
fn infinite_slope(m: &SlopeMaterial, depth: f64) -> f64 {
    let b = BETA_DEG.to_radians();
    m.cohesion / (m.unit_weight * depth * b.sin() * b.cos()) + m.friction_coefficient / b.tan()
}

#[test]
fn a_surface_truncated_everywhere_gives_the_infinite_slope_fs() {
    let terrain = slope(40);
    // An ellipsoid whose lower half plunges 10⁵ m: at every cell centre of
    // its footprint it lies far below the bedrock, so each column is the
    // slab between the ground and the bedrock.
    let (xc, yc) = (40.3, 39.1);
    let z = yc * BETA_DEG.to_radians().tan();
    let surface =
        Ellipsoid::new((xc, yc, z), 13.0, 9.0, 1e5, -std::f64::consts::FRAC_PI_2).unwrap();
    let mut columns = Vec::new();
    surface_columns(&terrain, &surface, &mut columns).unwrap();
    assert!(columns.len() > 80, "{} columns", columns.len());
    for k in &columns {
        let (rock, _) = terrain.bedrock_at(k.row, k.column).unwrap();
        assert_eq!(
            k.base, rock,
            "column ({}, {}) not truncated",
            k.row, k.column
        );
    }
    let fs = hovland_columns(
        &columns,
        CELL,
        &soil(),
        &SlopeLoads::default(),
        &SurfaceLimits::default(),
    )
    .unwrap()
    .safety_factor;
    let exact = infinite_slope(&soil(), DEPTH);
    assert!(
        (fs - exact).abs() <= 1e-12 * exact,
        "truncated Fs {fs} against the infinite slope's {exact}"
    );
    // Without the bedrock the same surface reaches 10⁵ m down: another Fs.
    let bare = Terrain::new(terrain.dem().clone(), None).unwrap();
    surface_columns(&bare, &surface, &mut columns).unwrap();
    let deep = hovland_columns(
        &columns,
        CELL,
        &soil(),
        &SlopeLoads::default(),
        &SurfaceLimits::default(),
    )
    .unwrap()
    .safety_factor;
    assert!((deep - exact).abs() > 0.1 * exact, "{deep} {exact}");
}

/// Measured: infinite slope 1.24437; lowest Fs 1.44697, 1.32081, 1.29193
/// for spheres of radius 15, 25 and 40 m (the ends of the slide, where the
/// sphere rises above the bedrock, add strength that shrinks beside the
/// truncated middle as the spheres grow).
#[test]
fn sphere_search_over_a_bedrock_approaches_the_infinite_slope_from_above() {
    let terrain = slope(60);
    let exact = infinite_slope(&soil(), DEPTH);
    let lowest = |radius: f64| {
        let family = SphereGrid::new(
            2,
            Steps::checked("heights", 5.0, 40.0, 8, false).unwrap(),
            Steps::checked("radii", radius, radius, 1, true).unwrap(),
        )
        .unwrap();
        search(
            &terrain,
            &soil(),
            &SlopeLoads::default(),
            &family,
            &SearchSettings::default(),
            |_, _| {},
        )
        .unwrap()
        .lowest_safety_factor()
        .unwrap()
    };
    let fs: Vec<f64> = [15.0, 25.0, 40.0].iter().map(|&r| lowest(r)).collect();
    println!("infinite slope {exact:.5}, lowest Fs by radius 15, 25, 40 m: {fs:?}");
    for w in fs.windows(2) {
        assert!(w[1] < w[0], "{fs:?}");
    }
    assert!(fs.iter().all(|&f| f > exact), "{fs:?} against {exact}");
}

#[test]
fn bedrock_off_the_grid_or_without_data_is_refused() {
    let t = slope(20);
    let other = Raster::from_fn(20, 21, 0.0, 0.0, CELL, |_, _| Some(0.0)).unwrap();
    let e = Terrain::new(t.dem().clone(), None)
        .unwrap()
        .with_bedrock(NamedRaster::new("rock.asc", other))
        .unwrap_err();
    assert!(
        matches!(&e, DismechError::Grid(GridError::Mismatch { file, .. }) if file == "rock.asc"),
        "{e}"
    );
    let holes = Raster::from_fn(20, 20, 0.0, 0.0, CELL, |_, _| None).unwrap();
    let terrain = Terrain::new(t.dem().clone(), None)
        .unwrap()
        .with_bedrock(NamedRaster::new("holes", holes))
        .unwrap();
    let sphere = Sphere::new(20.0, 20.0, 30.0, 25.0).unwrap();
    let mut columns = Vec::new();
    assert_eq!(
        surface_columns(&terrain, &sphere, &mut columns),
        Err(Refusal::NoData)
    );
}
