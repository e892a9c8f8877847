//! The slope search: Hovland per surface against
//! an independent column sum, the parallel search against an exhaustive
//! loop, bit-identical results for any number of threads, the infinite
//! slope's limit, the outputs read back, and bad input refused.

use dismech::error::DismechError;
use dismech::grid::GridError;
use dismech::grid::{read_esri_ascii, Raster};
use dismech::hpm::NamedRaster;
use dismech::nalgebra::Vector3;
use dismech::slope::SlopeError;
use dismech::slope::*;

/// A valley side descending towards −y at about 25° with a bump, 48 × 40
/// cells of 2 m.
fn valley() -> Terrain {
    let dem = Raster::from_fn(48, 40, 100.0, 200.0, 2.0, |x, y| {
        let (u, v) = (x - 100.0, y - 200.0);
        let bump = 3.0 * (-((u - 40.0).powi(2) + (v - 40.0).powi(2)) / 150.0).exp();
        Some(0.47 * v + 0.002 * (u - 48.0).powi(2) + bump)
    })
    .unwrap();
    Terrain::new(NamedRaster::new("valley", dem), None).unwrap()
}

fn soil() -> SlopeMaterial {
    SlopeMaterial {
        cohesion: 8e3,
        friction_coefficient: 30f64.to_radians().tan(),
        unit_weight: 19e3,
    }
}

fn small_grid_family() -> SphereGrid {
    SphereGrid::new(
        3,
        Steps::checked("heights", 4.0, 16.0, 4, false).unwrap(),
        Steps::checked("radii", 8.0, 30.0, 6, true).unwrap(),
    )
    .unwrap()
}

/// (a) Hovland's Fs of a sphere equals a column sum written here from the
/// raw rasters, with the load, normal and tangent as vectors.
#[test]
fn hovland_per_surface_equals_an_independent_column_sum() {
    let dem = valley().dem().raster.clone();
    // A water table 2 m below the ground, and 1 m above it (ponded, taken
    // at the ground) in one corner.
    let values = (0..dem.rows() * dem.columns())
        .map(|k| {
            let (r, c) = (k / dem.columns(), k % dem.columns());
            let (x, y) = dem.cell_centre(r, c);
            let g = dem.get(r, c).unwrap();
            Some(if x > 150.0 && y < 240.0 {
                g + 1.0
            } else {
                g - 2.0
            })
        })
        .collect();
    let water = Raster::new(48, 40, 100.0, 200.0, 2.0, values).unwrap();
    let terrain = Terrain::new(
        NamedRaster::new("valley", dem.clone()),
        Some(NamedRaster::new("water", water.clone())),
    )
    .unwrap();
    let material = soil();
    let loads = SlopeLoads {
        seismic_coefficient: 0.15,
        water_unit_weight: 9810.0,
    };
    let sphere = Sphere::new(148.0, 245.0, 40.0, 30.0).unwrap();
    let evaluator = Evaluator::new(&terrain, &material, &loads, &SurfaceLimits::default()).unwrap();
    let got = evaluator.evaluate(&sphere, &mut Vec::new()).unwrap();

    // Independent: every cell of the raster, the sphere's formula.
    let d = dem.cell_size();
    let mut cols = Vec::new();
    for r in 0..dem.rows() {
        for c in 0..dem.columns() {
            let (x, y) = dem.cell_centre(r, c);
            let g = dem.get(r, c).unwrap();
            let s2 = 30.0f64.powi(2) - ((x - 148.0).powi(2) + (y - 245.0).powi(2));
            if s2 <= 0.0 {
                continue;
            }
            let zb = 40.0 - s2.sqrt();
            if zb >= g {
                continue;
            }
            assert!(r > 0 && c > 0 && r + 1 < dem.rows() && c + 1 < dem.columns());
            let grad = ((x - 148.0) / s2.sqrt(), (y - 245.0) / s2.sqrt());
            let hw = (water.get(r, c).unwrap().min(g) - zb).max(0.0);
            cols.push((g - zb, grad, hw));
        }
    }
    assert_eq!(cols.len(), got.columns);
    let weight = |h: f64| 19e3 * h * d * d;
    let mut plan = Vector3::zeros();
    for &(h, (zx, zy), _) in &cols {
        let n = Vector3::new(zx, zy, -1.0).normalize();
        let w = Vector3::new(0.0, 0.0, -weight(h));
        let shear = w - n * w.dot(&n);
        plan += Vector3::new(shear.x, shear.y, 0.0);
    }
    let s = plan.normalize();
    let (mut resisting, mut driving, mut volume) = (0.0, 0.0, 0.0);
    for &(h, (zx, zy), hw) in &cols {
        let n = Vector3::new(zx, zy, -1.0).normalize();
        let t = Vector3::new(s.x, s.y, zx * s.x + zy * s.y).normalize();
        let w = Vector3::new(0.15 * weight(h) * s.x, 0.15 * weight(h) * s.y, -weight(h));
        let area = d * d * (1.0 + zx * zx + zy * zy).sqrt();
        let normal = (w.dot(&n) - 9810.0 * hw * area).max(0.0);
        resisting += 8e3 * area + normal * 30f64.to_radians().tan();
        driving += w.dot(&t);
        volume += h * d * d;
    }
    let fs = resisting / driving;
    assert!(cols.iter().any(|c| c.2 > 0.0), "some columns under water");
    assert!(
        (got.safety_factor - fs).abs() <= 1e-12 * fs,
        "{} vs {fs}",
        got.safety_factor
    );
    assert!((got.volume - volume).abs() <= 1e-12 * volume);
    assert!((got.direction.0 - s.x).abs() < 1e-12 && (got.direction.1 - s.y).abs() < 1e-12);
    println!("Fs = {fs} over {} columns, {volume:.1} m³", cols.len());
}

/// An ellipsoid with three equal semi-axes is the sphere: the same Fs.
#[test]
fn an_ellipsoid_with_equal_axes_is_the_sphere() {
    let terrain = valley();
    let ev = Evaluator::new(
        &terrain,
        &soil(),
        &SlopeLoads::default(),
        &SurfaceLimits::default(),
    )
    .unwrap();
    let sphere = ev
        .evaluate(
            &Sphere::new(150.0, 250.0, 40.0, 25.0).unwrap(),
            &mut Vec::new(),
        )
        .unwrap();
    let ellipsoid = ev
        .evaluate(
            &Ellipsoid::new((150.0, 250.0, 40.0), 25.0, 25.0, 25.0, 0.7).unwrap(),
            &mut Vec::new(),
        )
        .unwrap();
    assert_eq!(sphere.columns, ellipsoid.columns);
    assert!((sphere.safety_factor - ellipsoid.safety_factor).abs() < 1e-12);
}

/// An Fs and the index of the trial that gave it.
type Ranked = (f64, u64);

/// The lowest Fs per cell and the critical list by a plain loop over every
/// trial of the family.
fn exhaustive<F: TrialFamily>(
    terrain: &Terrain,
    family: &F,
    settings: &SearchSettings,
) -> (Vec<Option<Ranked>>, Vec<Ranked>) {
    let ev = Evaluator::new(terrain, &soil(), &SlopeLoads::default(), &settings.limits).unwrap();
    let cols = terrain.columns();
    let mut minima: Vec<Option<(f64, u64)>> = vec![None; terrain.rows() * cols];
    let mut all = Vec::new();
    let mut columns = Vec::new();
    for i in 0..family.len(terrain) {
        let Ok(surface) = family.trial(terrain, i) else {
            continue;
        };
        let Ok(fs) = ev.evaluate(&surface, &mut columns) else {
            continue;
        };
        all.push((fs.safety_factor, i));
        for k in &columns {
            let m = &mut minima[k.row * cols + k.column];
            if m.is_none_or(|(f, _)| fs.safety_factor < f) {
                *m = Some((fs.safety_factor, i));
            }
        }
    }
    all.sort_by(|a, b| a.partial_cmp(b).unwrap());
    all.truncate(settings.critical);
    (minima, all)
}

fn check_against_exhaustive<F: TrialFamily>(terrain: &Terrain, family: &F) {
    let settings = SearchSettings {
        critical: 7,
        batch: 97,
        ..SearchSettings::default()
    };
    let mut calls = Vec::new();
    let result = search(
        terrain,
        &soil(),
        &SlopeLoads::default(),
        family,
        &settings,
        |d, t| calls.push((d, t)),
    )
    .unwrap();
    let (minima, best) = exhaustive(terrain, family, &settings);
    let n = family.len(terrain);
    assert_eq!(calls.last(), Some(&(n, n)));
    assert!(calls.windows(2).all(|w| w[0].0 < w[1].0));
    let lowest = best[0].0;
    assert!((result.lowest_safety_factor().unwrap() - lowest).abs() <= 1e-9 * lowest);
    assert_eq!(result.lowest().unwrap().trial, best[0].1);
    let listed: Vec<(f64, u64)> = result
        .critical
        .iter()
        .map(|c| (c.result.safety_factor, c.trial))
        .collect();
    assert_eq!(listed, best);
    let raster = result.safety_factor_raster().unwrap();
    for (k, m) in minima.iter().enumerate() {
        let (r, c) = (k / terrain.columns(), k % terrain.columns());
        assert_eq!(raster.get(r, c), m.map(|m| m.0), "cell ({r}, {c})");
        assert_eq!(result.cell(r, c).map(|m| m.trial), m.map(|m| m.1));
    }
    let mapped = minima.iter().flatten().count();
    assert!(mapped > 100, "{mapped} cells mapped");
    println!(
        "{n} trials, {} evaluated, lowest Fs {lowest:.6} (trial {}), {mapped} cells mapped; refused {:?}",
        result.counts.evaluated, best[0].1, result.counts.refused
    );
}

/// (b) The search's minimum and maps equal an exhaustive loop over the same
/// family: Scoops3D's grid and r.slope.stability's random spheres and
/// ellipsoids.
#[test]
fn search_equals_an_exhaustive_scan() {
    let terrain = valley();
    check_against_exhaustive(&terrain, &small_grid_family());
    check_against_exhaustive(
        &terrain,
        &SphereRandom::new(1500, 7, (2.0, 15.0), (8.0, 30.0)).unwrap(),
    );
    check_against_exhaustive(
        &terrain,
        &EllipsoidRandom::new(1500, 11, (0.0, 5.0), (8.0, 25.0), (0.3, 0.8), (3.0, 10.0)).unwrap(),
    );
}

/// (c) Bit-identical results with 1 and 4 threads.
#[test]
fn results_do_not_depend_on_the_threads() {
    let terrain = valley();
    let family = SphereRandom::new(3000, 3, (2.0, 15.0), (8.0, 30.0)).unwrap();
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                search(
                    &terrain,
                    &soil(),
                    &SlopeLoads::default(),
                    &family,
                    &SearchSettings {
                        batch: 500,
                        ..SearchSettings::default()
                    },
                    |_, _| {},
                )
                .unwrap()
            })
    };
    let (one, four) = (run(1), run(4));
    assert_eq!(one, four);
    let bits = |r: &SearchResult<Sphere>| -> Vec<Option<u64>> {
        r.safety_factor_raster()
            .unwrap()
            .values()
            .iter()
            .map(|v| v.map(f64::to_bits))
            .collect()
    };
    assert_eq!(bits(&one), bits(&four));
    assert_eq!(one.critical_csv(), four.critical_csv());
}

/// (d) A planar cohesionless slope: Hovland's Fs of a spherical cap is
/// scale-free (both sums grow as the cube of the size), a function of the
/// cap's angular half-width θ₀ alone, and tends to the infinite slope's
/// tan φ / tan β from above as θ₀ → 0. At a fixed cap depth D (the
/// search's depth range), θ₀ ≈ √(2D/R): the search's lowest Fs falls
/// towards tan φ / tan β as the radius grows.
#[test]
fn planar_cohesionless_slope_tends_to_the_infinite_slope_from_above() {
    let beta = 30f64.to_radians();
    let mu = 25f64.to_radians().tan();
    let infinite = mu / beta.tan();
    let n = 241;
    let dem = Raster::from_fn(n, n, 0.0, 0.0, 0.5, |_, y| Some(y * beta.tan())).unwrap();
    let terrain = Terrain::new(NamedRaster::new("plane", dem), None).unwrap();
    let material = SlopeMaterial {
        cohesion: 0.0,
        friction_coefficient: mu,
        unit_weight: 20e3,
    };
    let mut gaps = Vec::new();
    for radius in [5.0, 10.0, 20.0, 40.0, 80.0] {
        // Centres whose perpendicular distance to the plane is R − D, D in
        // [0.5, 1] m: vertical heights (R − D) / cos β above the ground.
        let family = SphereGrid::new(
            40,
            Steps::checked(
                "heights",
                (radius - 1.0) / beta.cos(),
                (radius - 0.5) / beta.cos(),
                11,
                false,
            )
            .unwrap(),
            Steps::checked("radii", radius, radius, 1, true).unwrap(),
        )
        .unwrap();
        let settings = SearchSettings {
            limits: SurfaceLimits {
                depth: (0.0, 1.2),
                ..SurfaceLimits::default()
            },
            ..SearchSettings::default()
        };
        let result = search(
            &terrain,
            &material,
            &SlopeLoads::default(),
            &family,
            &settings,
            |_, _| {},
        )
        .unwrap();
        let lowest = result.lowest().unwrap();
        let gap = lowest.result.safety_factor / infinite - 1.0;
        println!(
            "R = {radius:5.1} m: lowest Fs {:.6}, Fs/Fs_inf − 1 = {gap:.3e} ({} columns, depth {:.2} m)",
            lowest.result.safety_factor, lowest.result.columns, lowest.result.depth
        );
        gaps.push(gap);
    }
    println!("infinite slope tan φ / tan β = {infinite:.6}");
    assert!(gaps.iter().all(|&g| g > 0.0), "from above: {gaps:?}");
    assert!(gaps.windows(2).all(|w| w[1] < w[0]), "monotone: {gaps:?}");
    assert!(gaps[4] < 2e-3, "gap at R = 80 m: {}", gaps[4]);
}

/// The maps and the CSV are written on the DEM's grid and read back.
#[test]
fn maps_and_critical_csv_are_written_on_the_dem_grid() {
    let terrain = valley();
    let result = search(
        &terrain,
        &soil(),
        &SlopeLoads::default(),
        &small_grid_family(),
        &SearchSettings::default(),
        |_, _| {},
    )
    .unwrap();
    let dir = std::env::temp_dir().join(format!("dismech-slope-search-{}", std::process::id()));
    let paths = result.write_maps(&dir, "valley").unwrap();
    assert_eq!(paths.len(), 4);
    let fs = read_esri_ascii(&paths[0]).unwrap();
    assert!(fs.same_grid(&terrain.dem().raster));
    assert_eq!(fs, result.safety_factor_raster().unwrap());
    let depth = read_esri_ascii(&paths[3]).unwrap();
    assert_eq!(depth, result.depth_raster().unwrap());
    let csv_path = dir.join("critical.csv");
    result.write_critical_csv(&csv_path).unwrap();
    let text = std::fs::read_to_string(&csv_path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 1 + 10);
    assert!(lines[0].starts_with("rank,trial,x,y,z,radius,fs,"));
    let fs1: f64 = lines[1].split(',').nth(6).unwrap().parse().unwrap();
    assert_eq!(fs1, result.lowest().unwrap().result.safety_factor);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// (e) Bad input is refused with typed errors naming the value.
#[test]
fn bad_input_is_refused_with_typed_errors() {
    let none = Raster::new(4, 4, 0.0, 0.0, 1.0, vec![None; 16]).unwrap();
    let e = Terrain::new(NamedRaster::new("empty.asc", none), None).unwrap_err();
    assert!(
        matches!(e, DismechError::Slope(SlopeError::NoGroundData { ref file, rows: 4, columns: 4 }) if file == "empty.asc")
    );
    let tiny = Raster::from_fn(2, 5, 0.0, 0.0, 1.0, |_, _| Some(1.0)).unwrap();
    let e = Terrain::new(NamedRaster::new("tiny.asc", tiny), None).unwrap_err();
    assert!(matches!(
        e,
        DismechError::Slope(SlopeError::DemTooSmall {
            rows: 5,
            columns: 2,
            ..
        })
    ));
    assert!(e.to_string().contains("tiny.asc"));
    // NaN in a raster, at construction.
    let e = Raster::new(3, 3, 0.0, 0.0, 1.0, vec![Some(f64::NAN); 9]).unwrap_err();
    assert!(matches!(
        e,
        DismechError::InvalidParameter {
            name: "raster value",
            ..
        }
    ));
    // A water table on another grid.
    let other = Raster::from_fn(48, 40, 0.0, 0.0, 2.0, |_, _| Some(0.0)).unwrap();
    let e = Terrain::new(
        valley().dem().clone(),
        Some(NamedRaster::new("water.asc", other)),
    )
    .unwrap_err();
    assert!(
        matches!(e, DismechError::Grid(GridError::Mismatch { ref file, .. }) if file == "water.asc")
    );
    // Radii.
    let e = Steps::checked("radius range", 0.0, 10.0, 3, true).unwrap_err();
    assert!(
        matches!(e, DismechError::InvalidParameter { name: "radius range", value, .. } if value == 0.0)
    );
    let e = Steps::checked("radius range", -5.0, 10.0, 3, true).unwrap_err();
    assert!(matches!(e, DismechError::InvalidParameter { value, .. } if value == -5.0));
    let e = Steps::checked("radius range", 20.0, 10.0, 3, true).unwrap_err();
    assert!(
        matches!(e, DismechError::Slope(SlopeError::InvalidRange { low, high, .. }) if low == 20.0 && high == 10.0)
    );
    assert!(e.to_string().contains("20") && e.to_string().contains("10"));
    let e = Steps::checked("radius range", 5.0, 10.0, 0, true).unwrap_err();
    assert!(matches!(e, DismechError::InvalidParameter { value, .. } if value == 0.0));
    let e = SphereRandom::new(10, 1, (0.0, 5.0), (f64::NAN, 10.0)).unwrap_err();
    assert!(matches!(e, DismechError::InvalidParameter { value, .. } if value.is_nan()));
    let e = SphereRandom::new(0, 1, (0.0, 5.0), (1.0, 10.0)).unwrap_err();
    assert!(matches!(e, DismechError::InvalidParameter { value, .. } if value == 0.0));
    let e = SphereGrid::new(
        0,
        Steps {
            min: 0.0,
            max: 1.0,
            count: 2,
        },
        Steps {
            min: 1.0,
            max: 2.0,
            count: 2,
        },
    )
    .unwrap_err();
    assert!(matches!(
        e,
        DismechError::InvalidParameter {
            name: "sphere grid stride (cells)",
            ..
        }
    ));
    let e = Sphere::new(0.0, 0.0, 0.0, -1.0).unwrap_err();
    assert!(
        matches!(e, DismechError::InvalidParameter { name: "sphere radius", value, .. } if value == -1.0)
    );
    let e = Sphere::new(f64::NAN, 0.0, 0.0, 1.0).unwrap_err();
    assert!(matches!(
        e,
        DismechError::InvalidParameter {
            name: "sphere centre x",
            ..
        }
    ));
    // Material, loads, limits, settings.
    let terrain = valley();
    let family = small_grid_family();
    let run = |m: SlopeMaterial, l: SlopeLoads, s: SearchSettings| {
        search(&terrain, &m, &l, &family, &s, |_, _| {}).unwrap_err()
    };
    let d = (soil(), SlopeLoads::default(), SearchSettings::default());
    let e = run(
        SlopeMaterial {
            cohesion: f64::NAN,
            ..d.0
        },
        d.1,
        d.2,
    );
    assert!(matches!(
        e,
        DismechError::InvalidParameter {
            name: "cohesion c",
            ..
        }
    ));
    let e = run(
        SlopeMaterial {
            unit_weight: 0.0,
            ..d.0
        },
        d.1,
        d.2,
    );
    assert!(matches!(
        e,
        DismechError::InvalidParameter {
            name: "unit weight gamma",
            ..
        }
    ));
    let e = run(
        d.0,
        SlopeLoads {
            seismic_coefficient: -0.1,
            ..d.1
        },
        d.2,
    );
    assert!(matches!(
        e,
        DismechError::InvalidParameter {
            name: "seismic coefficient k_h",
            ..
        }
    ));
    let e = run(d.0, d.1, SearchSettings { batch: 0, ..d.2 });
    assert!(matches!(
        e,
        DismechError::InvalidParameter {
            name: "search batch (trials)",
            ..
        }
    ));
    let mut limits = SurfaceLimits {
        volume: (100.0, 10.0),
        ..SurfaceLimits::default()
    };
    let e = run(d.0, d.1, SearchSettings { limits, ..d.2 });
    assert!(
        matches!(e, DismechError::Slope(SlopeError::InvalidRange { low, high, .. }) if low == 100.0 && high == 10.0)
    );
    limits.volume = (0.0, f64::NAN);
    let e = run(d.0, d.1, SearchSettings { limits, ..d.2 });
    assert!(matches!(e, DismechError::InvalidParameter { value, .. } if value.is_nan()));
}

/// Surfaces that reach the edge of the grid or cover no-data are refused;
/// so are centres over no-data.
#[test]
fn surfaces_leaving_the_dem_are_refused() {
    let terrain = valley();
    let ev = Evaluator::new(
        &terrain,
        &soil(),
        &SlopeLoads::default(),
        &SurfaceLimits::default(),
    )
    .unwrap();
    // A large sphere reaching the grid's edge.
    let big = Sphere::new(148.0, 240.0, 60.0, 60.0).unwrap();
    assert_eq!(ev.evaluate(&big, &mut Vec::new()), Err(Refusal::LeavesDem));
    // A hole of no data under a sphere that would be fine.
    let dem = terrain.dem().raster.clone();
    let mut values = dem.values().to_vec();
    let (r, c) = (22, 22);
    values[r * dem.columns() + c] = None;
    let holed = Raster::new(48, 40, 100.0, 200.0, 2.0, values).unwrap();
    let holed = Terrain::new(NamedRaster::new("holed", holed), None).unwrap();
    let (x, y) = dem.cell_centre(r, c);
    let sphere = Sphere::new(x, y, dem.get(r, c).unwrap() + 10.0, 18.0).unwrap();
    assert!(ev.evaluate(&sphere, &mut Vec::new()).is_ok());
    let ev2 = Evaluator::new(
        &holed,
        &soil(),
        &SlopeLoads::default(),
        &SurfaceLimits::default(),
    )
    .unwrap();
    assert_eq!(ev2.evaluate(&sphere, &mut Vec::new()), Err(Refusal::NoData));
    let result = search(
        &holed,
        &soil(),
        &SlopeLoads::default(),
        &SphereGrid::new(
            4,
            Steps::checked("h", 2.0, 8.0, 2, false).unwrap(),
            Steps::checked("r", 10.0, 20.0, 2, true).unwrap(),
        )
        .unwrap(),
        &SearchSettings::default(),
        |_, _| {},
    )
    .unwrap();
    assert!(result.counts.refused_for(Refusal::NoData) > 0);
    assert!(result.counts.refused_for(Refusal::CentreOffDem) > 0);
    assert!(result.counts.refused_for(Refusal::LeavesDem) > 0);
    let c = result.counts;
    assert_eq!(c.evaluated + c.refused.iter().sum::<u64>(), c.trials);
}

/// A slope saturated to its surface (the water table above the ground,
/// lowered to it): on the steep rims of a sphere the pore pressure exceeds
/// the columns' normal force, and those columns keep no frictional
/// strength rather than a negative one. Counted negative they cancelled
/// the rest, and the lowest Fs of the search fell to 0.011 where the
/// infinite slope gives about 0.44. Now the lowest (0.432) lies above the
/// saturated infinite slope's at great depth (0.324) and below 1. A
/// family built through its public fields is checked before the search.
#[test]
fn a_saturated_slope_keeps_its_strength_positive_column_by_column() {
    let (rows, columns, d) = (40, 40, 2.0);
    let slope = 30f64.to_radians().tan();
    let dem = Raster::from_fn(rows, columns, 0.0, 0.0, d, |_, y| Some(slope * y)).unwrap();
    let high = Raster::from_fn(rows, columns, 0.0, 0.0, d, |_, y| Some(slope * y + 5.0)).unwrap();
    let terrain = Terrain::new(
        NamedRaster::new("plane", dem),
        Some(NamedRaster::new("water", high)),
    )
    .unwrap();
    let material = SlopeMaterial {
        cohesion: 5e3,
        friction_coefficient: 0.6,
        unit_weight: 19e3,
    };
    let loads = SlopeLoads {
        water_unit_weight: 9810.0,
        ..SlopeLoads::default()
    };
    let family = SphereGrid::new(
        2,
        Steps::checked("heights", 5.0, 20.0, 4, false).unwrap(),
        Steps::checked("radii", 10.0, 40.0, 7, true).unwrap(),
    )
    .unwrap();
    let result = search(
        &terrain,
        &material,
        &loads,
        &family,
        &SearchSettings::default(),
        |_, _| {},
    )
    .unwrap();
    let lowest = result.lowest_safety_factor().unwrap();
    // The infinite slope saturated to its surface, u = γ_w z, at the
    // deepest caps of the family (a few metres): Fs = c / (γ z sin β cos β)
    // + (cos² β − γ_w / γ) tan φ / (sin β cos β), 0.45 at z = 5 m and 0.35
    // as z grows without bound.
    let beta = 30f64.to_radians();
    let (sin, cos) = beta.sin_cos();
    let deep = (cos * cos - 9810.0 / 19e3) * 0.6 / (sin * cos);
    println!("lowest Fs {lowest}, the infinite slope's at great depth {deep}");
    assert!(lowest > deep && lowest < 1.0, "{lowest}");

    let broken = SphereGrid {
        stride: 0,
        ..family
    };
    assert!(matches!(
        search(
            &terrain,
            &material,
            &loads,
            &broken,
            &SearchSettings::default(),
            |_, _| {}
        ),
        Err(DismechError::InvalidParameter { .. })
    ));
    let reversed = SphereRandom {
        radii: (10.0, f64::INFINITY),
        ..SphereRandom::new(10, 1, (5.0, 10.0), (10.0, 20.0)).unwrap()
    };
    assert!(search(
        &terrain,
        &material,
        &loads,
        &reversed,
        &SearchSettings::default(),
        |_, _| {}
    )
    .is_err());
}
