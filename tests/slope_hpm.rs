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
    searched_with(terrain, &soil())
}

fn searched_with(terrain: &Terrain, soil: &SlopeMaterial) -> SearchResult<Sphere> {
    let settings = SearchSettings {
        critical: 3,
        ..SearchSettings::default()
    };
    search(
        terrain,
        soil,
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
    // sliding direction 1.5753 elastic and 1.6800 nonlinear (173 columns);
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
/// soil's; layers of different unit weights are taken (the weights of the
/// layers over each element's height); a pore-pressure ratio puts
/// `u = r_u σ_v` on the slip surface, and is refused beside a water table.
#[test]
fn reanalysis_takes_each_layer_s_strength_and_a_pore_pressure_ratio() {
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
    let run_on = |terrain: &Terrain, ground: &Ground| {
        hpm_reanalysis(
            terrain,
            ground,
            &SlopeLoads::default(),
            &worst.surface,
            &worst.result,
            &HpmStiffness::default(),
            &HpmSettings::default(),
            None,
        )
    };
    let run = |ground: &Ground| run_on(&terrain, ground);
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
    // A lighter weak layer: taken, lighter than the one of the soil's
    // unit weight, with the same springs.
    let light = run(&layered(heavy)).unwrap();
    assert!(light.model.total_weight() < two.model.total_weight());
    assert_eq!(light.model.slip, two.model.slip);
    // A pore-pressure ratio: u = r_u σ_v on the slip surface under each
    // column, σ_v its weight per unit plan area (an independent sum), which
    // lowers the Fs; the weights and springs are those without it.
    let with_ratio = run(&ratio).unwrap();
    assert_eq!(with_ratio.model.elements, one.model.elements);
    for (k, column) in with_ratio.model.columns.iter().enumerate() {
        let sigma_v: f64 = one.model.elements[column.elements.clone()]
            .iter()
            .map(|e| e.weight)
            .sum::<f64>()
            / (2.0 * 2.0);
        for spring in with_ratio.model.slip.iter().filter(|s| s.column == k) {
            assert!(
                (spring.pore_pressure - 0.2 * sigma_v).abs() <= 1e-12 * sigma_v,
                "column {k}: {} {sigma_v}",
                spring.pore_pressure
            );
        }
    }
    assert!(
        fs(&with_ratio) < fs(&one),
        "{} {}",
        fs(&with_ratio),
        fs(&one)
    );
    // With a water table too, r_u is refused as in the search.
    let [_, wet] = dry_and_wet();
    let both = run_on(&wet, &ratio).unwrap_err();
    assert!(
        matches!(
            &both,
            DismechError::Slope(SlopeError::PorePressureTwice { .. })
        ),
        "{both}"
    );
}

/// The bottom of the upper layer `depth` below the valley's ground.
fn bottom_below(depth: f64) -> NamedRaster {
    let dem = valley_dem();
    let values = dem.values().iter().map(|v| v.map(|g| g - depth)).collect();
    let (x0, y0) = dem.lower_left();
    NamedRaster::new(
        "upper.asc",
        Raster::new(48, 40, x0, y0, 2.0, values).unwrap(),
    )
}

/// Two layers: `upper` down to `bottom`, `lower` below.
fn two_layers(upper: SlopeMaterial, bottom: NamedRaster, lower: SlopeMaterial) -> Ground {
    Ground::layered(vec![
        Layer {
            name: "upper".into(),
            bottom: Some(bottom),
            material: upper,
        },
        Layer {
            name: "lower".into(),
            bottom: None,
            material: lower,
        },
    ])
    .unwrap()
}

/// The worst surface of the valley's search on `terrain`, re-analysed on
/// `ground`, elastic and nonlinear at the default settings; the nonlinear
/// analysis must converge.
fn reanalysed(terrain: &Terrain, ground: &Ground) -> dismech::error::Result<HpmReanalysis> {
    reanalysed_with(terrain, &soil(), ground).map(|(re, _)| re)
}

/// [`reanalysed`] for the worst surface of a search with `soil`, with that
/// surface's Hovland Fs.
fn reanalysed_with(
    terrain: &Terrain,
    soil: &SlopeMaterial,
    ground: &Ground,
) -> dismech::error::Result<(HpmReanalysis, f64)> {
    let result = searched_with(terrain, soil);
    let worst = result.lowest().unwrap();
    let re = hpm_reanalysis(
        terrain,
        ground,
        &SlopeLoads::default(),
        &worst.surface,
        &worst.result,
        &HpmStiffness::default(),
        &HpmSettings::default(),
        Some(&NonlinearSettings::default()),
    )?;
    let convergence = re.nonlinear.as_ref().unwrap().convergence;
    assert!(convergence.converged(), "{convergence:?}");
    Ok((re, worst.result.safety_factor))
}

/// Under a water table 3 m down, at unit weights of 18–19 kN/m³ the
/// nonlinear re-analysis of the worst surface once cycled for ever (its
/// residual about 1e-3 after 3 000 iterations) among springs that open
/// and close: a cohesive spring dropped its shear `c` at once as it
/// opened. With the cohesion lost over an opening of `c / k_n`
/// ([`dismech::law::MohrCoulombSpring`]) every unit weight from 16 to
/// 21 kN/m³ converges within 50 iterations, wet (20–25 measured, with the
/// seepage force) and dry (34–44).
#[test]
fn the_wet_valley_s_reanalysis_converges_at_every_unit_weight() {
    for terrain in dry_and_wet() {
        for unit_weight in [16e3, 17e3, 18e3, 18.5e3, 19e3, 19.5e3, 20e3, 21e3] {
            let soil = SlopeMaterial {
                unit_weight,
                ..soil()
            };
            let (re, hovland) = reanalysed_with(&terrain, &soil, &Ground::from(soil)).unwrap();
            let convergence = re.nonlinear.as_ref().unwrap().convergence;
            println!(
                "{unit_weight} N/m³: Hovland {hovland:.4}, HPM elastic {:.4}, {convergence:?}",
                elastic_fs(&re)
            );
            assert!(
                convergence.converged() && convergence.iterations() <= 50,
                "{unit_weight} N/m³: {convergence:?}"
            );
        }
    }
}

/// The valley dry, and under a water table 3 m below its ground (a
/// level one would leave most of the slope dry).
fn dry_and_wet() -> [Terrain; 2] {
    let dem = valley_dem();
    let water = dem.values().iter().map(|v| v.map(|g| g - 3.0)).collect();
    let (x0, y0) = dem.lower_left();
    let water = Raster::new(48, 40, x0, y0, 2.0, water).unwrap();
    [
        Terrain::new(NamedRaster::new("valley", dem.clone()), None).unwrap(),
        Terrain::new(
            NamedRaster::new("valley", dem),
            Some(NamedRaster::new("water", water)),
        )
        .unwrap(),
    ]
}

fn elastic_fs(re: &HpmReanalysis) -> f64 {
    re.elastic.sliding_safety_factor(&re.model).unwrap()
}

/// Two layers of one material, their boundary 4 m down through the slide,
/// dry and under a water table: the one-layer re-analysis bit for bit
/// (every element's weight, every spring, the elastic and nonlinear
/// results).
#[test]
fn equal_layers_give_the_one_layer_reanalysis_bit_for_bit() {
    for terrain in dry_and_wet() {
        let one = reanalysed(&terrain, &Ground::from(soil())).unwrap();
        let two = reanalysed(&terrain, &two_layers(soil(), bottom_below(4.0), soil())).unwrap();
        // The boundary crosses the slide: some columns' bases lie above it.
        let crossed = two
            .model
            .columns
            .iter()
            .filter(|c| {
                let (r, k) = c.cell;
                two.grids.slip().raster.get(r, k).unwrap() > valley_dem().get(r, k).unwrap() - 4.0
            })
            .count();
        assert!(
            crossed > 0 && crossed < two.model.columns.len(),
            "{crossed}"
        );
        assert_eq!(one.model.elements, two.model.elements);
        assert_eq!(one.model.slip, two.model.slip);
        assert_eq!(one.elastic, two.elastic);
        assert_eq!(one.nonlinear, two.nonlinear);
        assert_eq!(elastic_fs(&one).to_bits(), elastic_fs(&two).to_bits());
    }
}

/// A slip surface entirely in the lower layer gives the one-layer result
/// of the lower layer's material (to 1e-12), dry and under a water table:
/// (a) under an upper layer of another strength and the same unit weight
/// whose bottom lies halfway between the ground and the slip surface at
/// every cell of the slide (every column crosses it; its springs take the
/// lower layer's strength); (b) under an upper layer of another strength
/// and unit weight pinched out over the whole slide (its bottom at the
/// ground, or 5 m above it and clipped to it).
#[test]
fn a_slide_in_the_lower_layer_is_that_of_the_lower_layer_alone() {
    let stronger = SlopeMaterial {
        cohesion: 30e3,
        friction_coefficient: 40f64.to_radians().tan(),
        ..soil()
    };
    let other = SlopeMaterial {
        unit_weight: 22e3,
        ..stronger
    };
    let near = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
    let nl = |re: &HpmReanalysis| {
        re.nonlinear
            .as_ref()
            .unwrap()
            .sliding_safety_factor(&re.model)
            .unwrap()
    };
    for terrain in dry_and_wet() {
        let alone = reanalysed(&terrain, &Ground::from(soil())).unwrap();
        let dem = valley_dem();
        let slip = &alone.grids.slip().raster;
        let halfway: Vec<Option<f64>> = (0..40 * 48)
            .map(|i| {
                let (r, c) = (i / 48, i % 48);
                let g = dem.get(r, c).unwrap();
                Some(slip.get(r, c).map_or(g - 100.0, |z| 0.5 * (g + z.min(g))))
            })
            .collect();
        let (x0, y0) = dem.lower_left();
        let halfway = NamedRaster::new(
            "halfway.asc",
            Raster::new(48, 40, x0, y0, 2.0, halfway).unwrap(),
        );
        for (upper, bottom) in [
            (stronger, halfway),
            (other, bottom_below(0.0)),
            (other, bottom_below(-5.0)),
        ] {
            let two = reanalysed(&terrain, &two_layers(upper, bottom, soil())).unwrap();
            assert_eq!(two.model.columns.len(), alone.model.columns.len());
            for (s, t) in two
                .model
                .column_strengths()
                .iter()
                .zip(alone.model.column_strengths())
            {
                assert_eq!(*s, t);
            }
            assert!(near(elastic_fs(&two), elastic_fs(&alone)));
            assert!(near(nl(&two), nl(&alone)));
            for (a, b) in two.model.elements.iter().zip(&alone.model.elements) {
                assert!(near(a.weight, b.weight), "{} {}", a.weight, b.weight);
            }
            for (a, b) in two
                .elastic
                .displacements
                .iter()
                .zip(&alone.elastic.displacements)
            {
                assert!((a - b).abs() <= 1e-12 * b.abs().max(1e-30), "{a} {b}");
            }
        }
    }
}

/// A light upper layer (16 kN/m³) 4 m thick over a heavy lower one
/// (21 kN/m³), of one strength, the boundary crossing the slide: each
/// element weighs the layers over its height (an independent sum per
/// column to 1e-12), between its weights in the all-light and the
/// all-heavy ground, dry and under a water table. On dry ground HPM's
/// elastic sliding Fs lies between the all-light one (higher: the same
/// cohesion holds a lighter slide) and the all-heavy one, the nonlinear
/// Fs likewise (measured 1.63198 > 1.57845 > 1.54657 elastic). Under the
/// water table no such bound holds, and none is asserted: buoyancy and
/// seepage take a larger share of a lighter ground's weight, and change
/// the shallow and the deep elements' shares unequally (measured: elastic
/// 0.91277 all light, 1.09320 all heavy, 1.02555 layered). Each element's
/// buoyancy and seepage force are checked against an independent sum.
#[test]
fn layers_of_other_unit_weights_weigh_each_element_by_its_layers() {
    let light = SlopeMaterial {
        unit_weight: 16e3,
        ..soil()
    };
    let heavy = SlopeMaterial {
        unit_weight: 21e3,
        ..soil()
    };
    for (t, terrain) in dry_and_wet().iter().enumerate() {
        let all_light = reanalysed(terrain, &Ground::from(light)).unwrap();
        let all_heavy = reanalysed(terrain, &Ground::from(heavy)).unwrap();
        let layered = reanalysed(terrain, &two_layers(light, bottom_below(4.0), heavy)).unwrap();
        let model = &layered.model;
        let d = 2.0;
        let gamma_w = if t == 0 { 0.0 } else { WATER_UNIT_WEIGHT };
        let mut both = 0;
        for column in &model.columns {
            let (r, c) = column.cell;
            let boundary = valley_dem().get(r, c).unwrap() - 4.0;
            let (_, _, water) = layered.grids.corners(r, c);
            let hw = water.map(|w| 0.25 * w.iter().sum::<f64>());
            // Independent: the weight of [lo, hi] split at the boundary and
            // the water level, each piece its layer's γ (γ − γ_w below hw).
            let weight_of = |lo: f64, hi: f64| {
                let mut cuts = vec![lo, hi];
                for z in [Some(boundary), hw].into_iter().flatten() {
                    if z > lo && z < hi {
                        cuts.push(z);
                    }
                }
                cuts.sort_by(|a, b| a.partial_cmp(b).unwrap());
                cuts.windows(2)
                    .map(|w| {
                        let mid = 0.5 * (w[0] + w[1]);
                        let g = if mid > boundary { 16e3 } else { 21e3 };
                        let g = if hw.is_some_and(|h| mid < h) {
                            g - gamma_w
                        } else {
                            g
                        };
                        g * (w[1] - w[0]) * d * d
                    })
                    .sum::<f64>()
            };
            let mean = |z: [f64; 4]| 0.25 * z.iter().sum::<f64>();
            for e in column.elements.clone() {
                let element = &model.elements[e];
                let (lo, hi) = (mean(element.shape.bottom()), mean(element.shape.top()));
                let expected = weight_of(lo, hi);
                assert!(
                    (element.weight - expected).abs() <= 1e-12 * expected,
                    "({r}, {c}) element {e}: {} {expected}",
                    element.weight
                );
                let (wl, wh) = (
                    all_light.model.elements[e].weight,
                    all_heavy.model.elements[e].weight,
                );
                assert!(wl <= element.weight && element.weight <= wh);
                // The seepage force: γ_w times the element's volume below
                // the mean water level, down the table's mean slope over
                // the cell (corners (x0, y0), (x0 + d, y0), (x0 + d, y0 + d),
                // (x0, y0 + d)).
                let (buoyancy, expected) = match water {
                    Some(w) => {
                        let below = (hw.unwrap().min(hi) - lo).max(0.0);
                        let buoyancy = WATER_UNIT_WEIGHT * below * d * d;
                        let slope = [
                            ((w[1] + w[2]) - (w[0] + w[3])) / (2.0 * d),
                            ((w[2] + w[3]) - (w[0] + w[1])) / (2.0 * d),
                        ];
                        (buoyancy, [-buoyancy * slope[0], -buoyancy * slope[1]])
                    }
                    None => (0.0, [0.0; 2]),
                };
                assert!(
                    (element.buoyancy - buoyancy).abs() <= 1e-9 * element.weight,
                    "({r}, {c}) element {e}: buoyancy {} {buoyancy}",
                    element.buoyancy
                );
                for (got, want) in element.seepage.iter().zip(expected) {
                    assert!(
                        (got - want).abs() <= 1e-9 * element.weight,
                        "({r}, {c}) element {e}: seepage {:?} {expected:?}",
                        element.seepage
                    );
                }
                if lo < boundary && boundary < hi {
                    both += 1;
                }
            }
        }
        assert!(both > 0, "an element crosses the boundary");
        let (fl, fh, f) = (
            elastic_fs(&all_light),
            elastic_fs(&all_heavy),
            elastic_fs(&layered),
        );
        println!("elastic Fs: all light {fl:.5}, layered {f:.5}, all heavy {fh:.5}");
        if t == 1 {
            continue;
        }
        assert!(fh < f && f < fl, "{fh} {f} {fl}");
        let nl = |re: &HpmReanalysis| {
            re.nonlinear
                .as_ref()
                .unwrap()
                .sliding_safety_factor(&re.model)
                .unwrap()
        };
        let (nl_l, nl_h, nl_f) = (nl(&all_light), nl(&all_heavy), nl(&layered));
        println!("nonlinear Fs: all light {nl_l:.5}, layered {nl_f:.5}, all heavy {nl_h:.5}");
        assert!(nl_h < nl_f && nl_f < nl_l, "{nl_h} {nl_f} {nl_l}");
    }
}

/// Under a water table, a layer whose unit weight is not above γ_w is
/// refused naming the layer (its submerged unit weight would not be
/// positive); dry, it is taken.
#[test]
fn a_layer_lighter_than_water_is_refused_under_a_water_table_naming_it() {
    let floating = SlopeMaterial {
        unit_weight: 9e3,
        ..soil()
    };
    let [dry, wet] = dry_and_wet();
    let ground = two_layers(floating, bottom_below(4.0), soil());
    assert!(reanalysed(&dry, &ground).is_ok());
    let e = reanalysed(&wet, &ground).unwrap_err();
    assert!(
        matches!(&e, DismechError::Slope(SlopeError::InvalidLayer { layer, .. }) if layer == "upper"),
        "{e}"
    );
    assert!(e.to_string().contains("submerged unit weight"), "{e}");
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
