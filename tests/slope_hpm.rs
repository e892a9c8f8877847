//! HPM re-analysis of the most critical surfaces of a slope search (paper
//! 001's HPM on the surface made a raster): the same as a direct HPM run on
//! that raster written to and read from a file, bit for bit; its Fs beside
//! Hovland's on the same surface; ground HPM cannot take refused.

use dismech::error::DismechError;
use dismech::grid::{write_esri_ascii, Raster};
use dismech::hpm::{
    hovland, HpmModel, HpmSettings, HpmSolver, NamedRaster, NonlinearSettings, Seismic, SlopeGrids,
};
use dismech::slope::SlopeError;
use dismech::slope::*;

/// A valley side descending towards −y at about 25° with a bump, 48 × 40
/// cells of 2 m (as in tests/slope_search.rs).
fn valley_dem() -> Raster {
    Raster::from_fn(48, 40, 100.0, 200.0, 2.0, |x, y| {
        let (u, v) = (x - 100.0, y - 200.0);
        let bump = 3.0 * (-((u - 40.0).powi(2) + (v - 40.0).powi(2)) / 150.0).exp();
        Some(0.47 * v + 0.002 * (u - 48.0).powi(2) + bump)
    })
    .unwrap()
}

fn soil() -> SlopeMaterial {
    SlopeMaterial {
        cohesion: 8e3,
        friction_coefficient: 30f64.to_radians().tan(),
        unit_weight: 19e3,
    }
}

fn family() -> SphereGrid {
    SphereGrid::new(
        3,
        Steps::checked("heights", 4.0, 16.0, 4, false).unwrap(),
        Steps::checked("radii", 8.0, 30.0, 6, true).unwrap(),
    )
    .unwrap()
}

fn searched(terrain: &Terrain) -> SearchResult<Sphere> {
    let settings = SearchSettings {
        critical: 3,
        ..SearchSettings::default()
    };
    search(
        terrain,
        &soil(),
        &SlopeLoads::default(),
        &family(),
        &settings,
        |_, _| {},
    )
    .unwrap()
}

#[test]
fn reanalysis_equals_a_direct_hpm_run_on_the_surface_raster_bit_for_bit() {
    let dem = valley_dem();
    let terrain = Terrain::new(NamedRaster::new("valley", dem.clone()), None).unwrap();
    let result = searched(&terrain);
    let nonlinear = NonlinearSettings::default();
    let worst = result.lowest().unwrap();
    let re = hpm_reanalysis(
        &terrain,
        &soil(),
        &SlopeLoads::default(),
        &worst.surface,
        &worst.result,
        &HpmStiffness::default(),
        &HpmSettings::default(),
        Some(&nonlinear),
    )
    .unwrap();

    // The direct run: the sphere's lower half written out by its own
    // formula, both rasters through ESRI ASCII files, HPM's own path.
    let s = worst.surface;
    let slip = Raster::from_fn(48, 40, 100.0, 200.0, 2.0, |x, y| {
        let (dx, dy) = (x - s.x, y - s.y);
        let q = s.radius * s.radius - (dx * dx + dy * dy);
        (q > 0.0).then(|| s.z - q.sqrt())
    })
    .unwrap();
    let dir = std::env::temp_dir().join(format!("dismech_slope_hpm_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (ground_path, slip_path) = (dir.join("ground.asc"), dir.join("slip.asc"));
    write_esri_ascii(&ground_path, &dem).unwrap();
    write_esri_ascii(&slip_path, &slip).unwrap();
    let grids = SlopeGrids::read(&ground_path, &slip_path, None).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    let material = dismech::hpm::HpmMaterial {
        cohesion: 8e3,
        friction_coefficient: 30f64.to_radians().tan(),
        unit_weight: 19e3,
        submerged_unit_weight: 19e3 - 9810.0,
        ..dismech::hpm::HpmMaterial::paper()
    };
    let model = HpmModel::new(&grids, &material, &HpmSettings::default()).unwrap();
    let mut solver = HpmSolver::new(&model).unwrap();
    let seismic = Seismic {
        coefficient: 0.0,
        direction: worst.result.direction,
    };
    let elastic = solver.elastic(&model, &seismic).unwrap();
    let plastic = solver.nonlinear(&model, &seismic, 1.0, &nonlinear).unwrap();

    assert_eq!(re.grids.slip().raster, slip);
    assert_eq!(re.model.elements, model.elements);
    assert_eq!(re.model.slip, model.slip);
    assert_eq!(re.elastic, elastic);
    assert_eq!(re.nonlinear.as_ref(), Some(&plastic));
    assert!(elastic.convergence.converged() && plastic.convergence.converged());
    let fs = |r: &dismech::hpm::HpmResult| r.sliding_safety_factor(&model).unwrap();
    assert_eq!(
        fs(&re.elastic).to_bits(),
        fs(&elastic).to_bits(),
        "elastic Fs"
    );
    assert_eq!(
        re.elastic_maps().unwrap(),
        elastic.maps(&model, &grids).unwrap()
    );

    // HPM's Fs beside Hovland's on the same surface. The search's Hovland
    // takes each column's base at its cell centre; HPM's model (and
    // Hovland's method on its columns) the bilinear surface through the
    // corner heights interpolated from the cell centres (eq. 23), so the
    // two Hovland values differ by the discretisation alone. Measured:
    // Hovland 1.4492 (search) and 1.4442 (HPM's columns), HPM along the
    // sliding direction 1.5753 elastic and 1.6813 nonlinear (173 columns);
    // HPM's springs share the load between the columns, which Hovland's
    // method, with no forces between columns, cannot.
    let hovland_search = worst.result.safety_factor;
    let hovland_model = hovland(&model, &seismic, worst.result.direction)
        .unwrap()
        .safety_factor;
    let (elastic_fs, plastic_fs) = (fs(&elastic), fs(&plastic));
    println!(
        "Hovland (search) {hovland_search:.4}, Hovland (HPM columns) {hovland_model:.4}, HPM elastic {elastic_fs:.4}, HPM nonlinear {plastic_fs:.4}, columns {} / {}",
        worst.result.columns,
        model.columns.len()
    );
    assert!((hovland_model - hovland_search).abs() < 0.01 * hovland_search);
    assert_eq!(model.columns.len(), worst.result.columns);
}

/// Layered ground of one unit weight: each HPM column's slip springs take
/// the strength of the layer the surface crosses at its cell centre (a
/// weak layer 2 m thick over the soil), and the Fs falls below the single
/// soil's; layers of different unit weights and r_u are refused.
#[test]
fn reanalysis_takes_each_layer_s_strength_and_refuses_what_it_cannot() {
    let dem = valley_dem();
    let terrain = Terrain::new(NamedRaster::new("valley", dem.clone()), None).unwrap();
    let result = searched(&terrain);
    let worst = result.lowest().unwrap();
    let shallow = dem.values().iter().map(|v| v.map(|g| g - 2.0)).collect();
    let (x0, y0) = dem.lower_left();
    let bottom = Raster::new(48, 40, x0, y0, 2.0, shallow).unwrap();
    let weak = SlopeMaterial {
        cohesion: 2e3,
        friction_coefficient: 20f64.to_radians().tan(),
        unit_weight: 19e3,
    };
    let layered = |top: SlopeMaterial| {
        Ground::layered(vec![
            Layer {
                name: "topsoil".into(),
                bottom: Some(NamedRaster::new("topsoil.asc", bottom.clone())),
                material: top,
            },
            Layer {
                name: "rock".into(),
                bottom: None,
                material: soil(),
            },
        ])
        .unwrap()
    };
    let run = |ground: &Ground| {
        hpm_reanalysis(
            &terrain,
            ground,
            &SlopeLoads::default(),
            &worst.surface,
            &worst.result,
            &HpmStiffness::default(),
            &HpmSettings::default(),
            None,
        )
    };
    let one = run(&Ground::from(soil())).unwrap();
    let two = run(&layered(weak)).unwrap();
    let strengths = two.model.column_strengths();
    let (mut in_weak, mut in_soil) = (0, 0);
    for (k, column) in two.model.columns.iter().enumerate() {
        let (r, c) = column.cell;
        let base = two.grids.slip().raster.get(r, c).unwrap();
        let expected = if base > bottom.get(r, c).unwrap() {
            in_weak += 1;
            weak
        } else {
            in_soil += 1;
            soil()
        };
        assert_eq!(strengths[k].cohesion, expected.cohesion, "({r}, {c})");
        assert_eq!(strengths[k].friction, expected.friction_coefficient);
    }
    assert!(in_weak > 0 && in_soil > 0, "{in_weak} {in_soil}");
    let fs = |re: &HpmReanalysis| re.elastic.sliding_safety_factor(&re.model).unwrap();
    assert!(fs(&two) < fs(&one), "{} {}", fs(&two), fs(&one));
    assert_eq!(one.elastic.displacements, two.elastic.displacements);

    let heavy = SlopeMaterial {
        unit_weight: 18e3,
        ..weak
    };
    let ratio = Ground::from(soil())
        .with_pore_ratio(PoreRatio::Constant(0.2))
        .unwrap();
    for (ground, words) in [(&layered(heavy), "topsoil 18000"), (&ratio, "r_u")] {
        let e = run(ground).unwrap_err();
        assert!(
            matches!(&e, DismechError::Slope(SlopeError::HpmGround { reason }) if reason.contains(words)),
            "{e}"
        );
    }
}

/// Over a bedrock the slip raster follows the truncated surface: at every
/// cell of the footprint the larger of the surface and the bedrock, so
/// that HPM's columns are the search's columns, with the same bases.
#[test]
fn reanalysis_follows_the_bedrock() {
    let dem = valley_dem();
    let rock = dem.values().iter().map(|v| v.map(|g| g - 3.0)).collect();
    let (x0, y0) = dem.lower_left();
    let rock = Raster::new(48, 40, x0, y0, 2.0, rock).unwrap();
    let terrain = Terrain::new(NamedRaster::new("valley", dem.clone()), None)
        .unwrap()
        .with_bedrock(NamedRaster::new("rock", rock.clone()))
        .unwrap();
    let result = searched(&terrain);
    let worst = result.lowest().unwrap();
    let s = worst.surface;
    let slip = surface_raster(&terrain, &s).unwrap();
    let mut truncated = 0;
    for r in 0..40 {
        for c in 0..48 {
            let (x, y) = dem.cell_centre(r, c);
            let expected = s.base(x, y).map(|(z, _)| {
                let b = rock.get(r, c).unwrap();
                if z < b {
                    truncated += 1;
                    b
                } else {
                    z
                }
            });
            assert_eq!(slip.get(r, c), expected, "cell ({r}, {c})");
        }
    }
    assert!(truncated > 0);
    let mut columns = Vec::new();
    surface_columns(&terrain, &s, &mut columns).unwrap();
    let re = hpm_reanalysis(
        &terrain,
        &soil(),
        &SlopeLoads::default(),
        &s,
        &worst.result,
        &HpmStiffness::default(),
        &HpmSettings::default(),
        None,
    )
    .unwrap();
    let cells: Vec<(usize, usize)> = re.model.columns.iter().map(|c| c.cell).collect();
    let expected: Vec<(usize, usize)> = columns.iter().map(|k| (k.row, k.column)).collect();
    assert_eq!(cells, expected);
    for k in &columns {
        assert_eq!(slip.get(k.row, k.column), Some(k.base));
    }
}

#[test]
fn dry_ground_lighter_than_water_is_reanalysed() {
    // Without a water table the submerged unit weight is never taken: a
    // light dry ground (γ ≤ γ_w) is analysed, not refused; under a water
    // table its submerged unit weight is not positive and it is refused.
    let dem = valley_dem();
    let terrain = Terrain::new(NamedRaster::new("valley", dem.clone()), None).unwrap();
    let result = searched(&terrain);
    let worst = result.lowest().unwrap();
    let light = SlopeMaterial {
        unit_weight: 9e3,
        ..soil()
    };
    let run = |terrain: &Terrain, m: &SlopeMaterial| {
        hpm_reanalysis(
            terrain,
            m,
            &SlopeLoads::default(),
            &worst.surface,
            &worst.result,
            &HpmStiffness::default(),
            &HpmSettings::default(),
            None,
        )
    };
    let re = run(&terrain, &light).unwrap();
    let heavy = run(&terrain, &soil()).unwrap();
    // The same cohesion holds a lighter slide better.
    let fs = |r: &HpmReanalysis| r.elastic.safety_factor(&r.model).unwrap();
    assert!(
        fs(&re).is_finite() && fs(&re) > fs(&heavy),
        "{} {}",
        fs(&re),
        fs(&heavy)
    );
    let deep = Raster::from_fn(48, 40, 100.0, 200.0, 2.0, |_, _| Some(-50.0)).unwrap();
    let wet = Terrain::new(
        NamedRaster::new("valley", dem),
        Some(NamedRaster::new("water", deep)),
    )
    .unwrap();
    assert!(run(&wet, &light).is_err());
}
