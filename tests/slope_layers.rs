//! Ground as it is for the slope search: strength
//! layers bounded by elevation rasters and the pore-pressure ratio r_u,
//! against the single material, the infinite slope and an independent
//! column sum; bad input refused with typed errors.

use dismech::error::DismechError;
use dismech::grid::GridError;
use dismech::grid::Raster;
use dismech::hpm::NamedRaster;
use dismech::nalgebra::Vector3;
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

fn terrain(dem: &Raster) -> Terrain {
    Terrain::new(NamedRaster::new("valley", dem.clone()), None).unwrap()
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

/// `dem` shifted by `dz` (a layer bottom at a constant depth).
fn below(dem: &Raster, dz: f64, name: &str) -> NamedRaster {
    let values = dem.values().iter().map(|v| v.map(|g| g - dz)).collect();
    let (x0, y0) = dem.lower_left();
    NamedRaster::new(
        name,
        Raster::new(dem.columns(), dem.rows(), x0, y0, dem.cell_size(), values).unwrap(),
    )
}

fn layer(name: &str, bottom: Option<NamedRaster>, material: SlopeMaterial) -> Layer {
    Layer {
        name: name.to_string(),
        bottom,
        material,
    }
}

fn run(t: &Terrain, ground: &(impl ToGround + ?Sized)) -> SearchResult<Sphere> {
    search(
        t,
        ground,
        &SlopeLoads::default(),
        &family(),
        &SearchSettings::default(),
        |_, _| {},
    )
    .unwrap()
}

/// One material, a one-layer `Ground` built from it, and two layers of the
/// same material: the first two bit for bit (the same operations), the
/// third to 1e-12, because the weight `γ t₁ + γ t₂` with
/// `t₁ + t₂ = (g − b₁) + (b₁ − z_b)` rounds differently from `γ (g − z_b)`.
#[test]
fn two_layers_of_one_material_give_the_single_material_result() {
    let dem = valley_dem();
    let t = terrain(&dem);
    let single = run(&t, &soil());
    let one = run(&t, &Ground::from(soil()));
    let two = Ground::layered(vec![
        layer("upper", Some(below(&dem, 3.0, "upper.asc")), soil()),
        layer("lower", None, soil()),
    ])
    .unwrap();
    let two = run(&t, &two);
    assert_eq!(single, one, "a one-layer Ground is the single material");
    assert!(single.counts.evaluated > 100);
    assert_eq!(single.counts, two.counts);
    let mut compared = 0;
    for r in 0..dem.rows() {
        for c in 0..dem.columns() {
            match (single.cell(r, c), two.cell(r, c)) {
                (None, None) => {}
                (Some(a), Some(b)) => {
                    let (fa, fb) = (a.safety_factor, b.safety_factor);
                    assert!((fa - fb).abs() <= 1e-12 * fa, "({r}, {c}): {fa} vs {fb}");
                    compared += 1;
                }
                other => panic!("({r}, {c}): {other:?}"),
            }
        }
    }
    assert!(compared > 200, "{compared} cells");
    let (a, b) = (single.lowest().unwrap(), two.lowest().unwrap());
    assert_eq!(a.trial, b.trial);
    assert!((a.result.safety_factor - b.result.safety_factor).abs() <= 1e-12);
    // Per surface too, against the single material's `hovland_columns`.
    let sphere = Sphere::new(148.0, 245.0, 40.0, 30.0).unwrap();
    let mut cols = Vec::new();
    surface_columns(&t, &sphere, &mut cols).unwrap();
    let lim = SurfaceLimits::default();
    let loads = SlopeLoads::default();
    let a = hovland_columns(&cols, 2.0, &soil(), &loads, &lim).unwrap();
    let b = hovland_ground(&cols, 2.0, &Ground::from(soil()), &loads, &lim).unwrap();
    assert_eq!(a, b);
}

/// A planar slope at β = 30° with a layer boundary parallel to it at a
/// vertical depth H₁ = 2 m, and a planar slip parallel to both at vertical
/// depth z = 5 m, inside the lower layer: every column is the infinite
/// slope's, so Fs = [c₂ + σ_v cos²β tan φ₂] / (σ_v sin β cos β) with the
/// layered vertical stress σ_v = γ₁ H₁ + γ₂ (z − H₁) (strength of the lower
/// layer, weight of both).
#[test]
fn a_planar_slip_in_the_lower_layer_is_the_layered_infinite_slope() {
    let beta = 30f64.to_radians();
    let dem = Raster::from_fn(20, 20, 0.0, 0.0, 2.0, |_, y| Some(y * beta.tan())).unwrap();
    let upper = SlopeMaterial {
        cohesion: 20e3,
        friction_coefficient: 0.9,
        unit_weight: 17e3,
    };
    let lower = SlopeMaterial {
        cohesion: 4e3,
        friction_coefficient: 25f64.to_radians().tan(),
        unit_weight: 21e3,
    };
    let ground = Ground::layered(vec![
        layer("crust", Some(below(&dem, 2.0, "crust.asc")), upper),
        layer("clay", None, lower),
    ])
    .unwrap();
    let (h1, z) = (2.0, 5.0);
    let mut cols = Vec::new();
    for r in 2..18 {
        for c in 2..18 {
            let g = dem.get(r, c).unwrap();
            cols.push(SlipColumn {
                row: r,
                column: c,
                ground: g,
                base: g - z,
                gradient: (0.0, beta.tan()),
                pressure_head: 0.0,
            });
        }
    }
    let got = hovland_ground(
        &cols,
        2.0,
        &ground,
        &SlopeLoads::default(),
        &SurfaceLimits::default(),
    )
    .unwrap();
    let sigma = 17e3 * h1 + 21e3 * (z - h1);
    let (s, c) = beta.sin_cos();
    let fs = (4e3 + sigma * c * c * lower.friction_coefficient) / (sigma * s * c);
    assert!(
        (got.safety_factor - fs).abs() <= 1e-12 * fs,
        "{} vs {fs}",
        got.safety_factor
    );
    // The single lower material would weigh 21e3 z: not the same Fs.
    let alone = hovland_columns(
        &cols,
        2.0,
        &lower,
        &SlopeLoads::default(),
        &SurfaceLimits::default(),
    )
    .unwrap();
    assert!((alone.safety_factor - fs).abs() > 1e-3 * fs);
    println!("layered infinite slope Fs = {fs}");
}

/// The pore-pressure ratio on the infinite slope. The code's convention is
/// Bishop & Morgenstern's (1960): `u = r_u σ_v` with `σ_v = γ z` the
/// vertical stress, so the effective normal stress on the slip plane is
/// `γ z cos²β − r_u γ z` and
/// `Fs = [c + (cos²β − r_u) γ z tan φ] / (γ z sin β cos β)`
/// (`= c/(γ z sin β cos β) + (1 − r_u sec²β) tan φ / tan β`). The form
/// `[c + (1 − r_u) γ z cos²β tan φ] / …` holds for a ratio of the normal
/// stress on the plane (`u = r_u γ z cos²β`), which is not r_u; it is
/// checked here to differ.
#[test]
fn a_constant_ru_on_the_infinite_slope() {
    let beta = 25f64.to_radians();
    let dem = Raster::from_fn(16, 16, 0.0, 0.0, 2.0, |_, y| Some(y * beta.tan())).unwrap();
    let m = SlopeMaterial {
        cohesion: 3e3,
        friction_coefficient: 32f64.to_radians().tan(),
        unit_weight: 20e3,
    };
    let z = 4.0;
    let cols: Vec<SlipColumn> = (2..14)
        .flat_map(|r| (2..14).map(move |c| (r, c)))
        .map(|(r, c)| {
            let g = dem.get(r, c).unwrap();
            SlipColumn {
                row: r,
                column: c,
                ground: g,
                base: g - z,
                gradient: (0.0, beta.tan()),
                pressure_head: 0.0,
            }
        })
        .collect();
    let (s, c) = beta.sin_cos();
    let gz = m.unit_weight * z;
    for ru in [0.0, 0.2, 0.4] {
        let ground = Ground::from(m)
            .with_pore_ratio(PoreRatio::Constant(ru))
            .unwrap();
        let got = hovland_ground(
            &cols,
            2.0,
            &ground,
            &SlopeLoads::default(),
            &SurfaceLimits::default(),
        )
        .unwrap()
        .safety_factor;
        let fs = (m.cohesion + (c * c - ru) * gz * m.friction_coefficient) / (gz * s * c);
        assert!((got - fs).abs() <= 1e-12 * fs, "r_u {ru}: {got} vs {fs}");
        let normal_ratio =
            (m.cohesion + (1.0 - ru) * gz * c * c * m.friction_coefficient) / (gz * s * c);
        if ru > 0.0 {
            assert!((got - normal_ratio).abs() > 1e-3 * fs);
        }
        println!("r_u {ru}: Fs {fs}");
    }
}

/// r_u = 0, constant or as a raster, is the dry search bit for bit.
#[test]
fn ru_zero_is_dry() {
    let dem = valley_dem();
    let t = terrain(&dem);
    let dry = run(&t, &soil());
    let zero = Ground::from(soil())
        .with_pore_ratio(PoreRatio::Constant(0.0))
        .unwrap();
    assert_eq!(dry, run(&t, &zero));
    let zeros = Raster::from_fn(48, 40, 100.0, 200.0, 2.0, |_, _| Some(0.0)).unwrap();
    let raster = Ground::from(soil())
        .with_pore_ratio(PoreRatio::Raster(NamedRaster::new("ru.asc", zeros)))
        .unwrap();
    assert_eq!(dry, run(&t, &raster));
    // And a positive r_u lowers the lowest Fs.
    let wet = Ground::from(soil())
        .with_pore_ratio(PoreRatio::Constant(0.3))
        .unwrap();
    let wet = run(&t, &wet);
    assert!(wet.lowest_safety_factor().unwrap() < dry.lowest_safety_factor().unwrap() - 0.05);
}

/// Hovland on three layers (bottoms that vary, one pinching out above the
/// ground, one above the layer above and clipped), a raster r_u and a
/// seismic load, against a column sum written here from the raw rasters.
#[test]
fn hovland_on_layers_equals_an_independent_column_sum() {
    let dem = valley_dem();
    let t = terrain(&dem);
    let (rows, cols_n) = (dem.rows(), dem.columns());
    let raster = |name: &str, f: &dyn Fn(usize, usize, f64) -> f64| {
        let values = (0..rows * cols_n)
            .map(|k| {
                let (r, c) = (k / cols_n, k % cols_n);
                Some(f(r, c, dem.get(r, c).unwrap()))
            })
            .collect();
        NamedRaster::new(
            name,
            Raster::new(cols_n, rows, 100.0, 200.0, 2.0, values).unwrap(),
        )
    };
    // Layer 1 bottom: 1.5 to 4.5 m deep, above the ground (pinched out)
    // on column 22 and beyond.
    let b1 = raster("b1.asc", &|r, c, g| {
        if c >= 22 {
            g + 1.0
        } else {
            g - 1.5 - 0.1 * ((r + c) % 31) as f64
        }
    });
    // Layer 2 bottom: 6 m deep, but 1 m deep (above layer 1's) on rows < 14.
    let b2 = raster("b2.asc", &|r, _, g| if r < 14 { g - 1.0 } else { g - 6.0 });
    let ru = raster("ru.asc", &|r, c, _| 0.02 * ((r * 7 + c) % 11) as f64);
    let m = [
        SlopeMaterial {
            cohesion: 15e3,
            friction_coefficient: 0.8,
            unit_weight: 17e3,
        },
        SlopeMaterial {
            cohesion: 5e3,
            friction_coefficient: 0.5,
            unit_weight: 19.5e3,
        },
        SlopeMaterial {
            cohesion: 25e3,
            friction_coefficient: 0.7,
            unit_weight: 22e3,
        },
    ];
    let ground = Ground::layered(vec![
        layer("top", Some(b1.clone()), m[0]),
        layer("middle", Some(b2.clone()), m[1]),
        layer("rock", None, m[2]),
    ])
    .unwrap()
    .with_pore_ratio(PoreRatio::Raster(ru.clone()))
    .unwrap();
    let loads = SlopeLoads {
        seismic_coefficient: 0.1,
        water_unit_weight: 9810.0,
    };
    let sphere = Sphere::new(148.0, 245.0, 40.0, 30.0).unwrap();
    let ev = Evaluator::new(&t, &ground, &loads, &SurfaceLimits::default()).unwrap();
    let got = ev.evaluate(&sphere, &mut Vec::new()).unwrap();

    // Independent: the sphere's formula at every cell, the layers clipped
    // from the top down.
    let d = 2.0;
    let mut cols = Vec::new();
    let mut in_layer = [0usize; 3];
    for r in 0..rows {
        for c in 0..cols_n {
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
            let grad = ((x - 148.0) / s2.sqrt(), (y - 245.0) / s2.sqrt());
            let l1 = b1.raster.get(r, c).unwrap().min(g);
            let l2 = b2.raster.get(r, c).unwrap().min(l1);
            let bounds = [(g, l1), (l1, l2), (l2, f64::NEG_INFINITY)];
            let mut sigma = 0.0;
            for (i, &(top, bottom)) in bounds.iter().enumerate() {
                sigma += m[i].unit_weight * (top.min(g) - bottom.max(zb)).max(0.0);
            }
            let i = bounds.iter().position(|&(_, bottom)| bottom < zb).unwrap();
            in_layer[i] += 1;
            let u = ru.raster.get(r, c).unwrap() * sigma;
            cols.push((sigma, grad, u, m[i]));
        }
    }
    assert_eq!(cols.len(), got.columns);
    assert!(
        in_layer.iter().all(|&n| n > 5),
        "bases in each layer: {in_layer:?}"
    );
    let mut plan = Vector3::zeros();
    for &(sigma, (zx, zy), _, _) in &cols {
        let n = Vector3::new(zx, zy, -1.0).normalize();
        let w = Vector3::new(0.0, 0.0, -sigma * d * d);
        let shear = w - n * w.dot(&n);
        plan += Vector3::new(shear.x, shear.y, 0.0);
    }
    let s = plan.normalize();
    let (mut resisting, mut driving, mut weight) = (0.0, 0.0, 0.0);
    for &(sigma, (zx, zy), u, mat) in &cols {
        let wt = sigma * d * d;
        let n = Vector3::new(zx, zy, -1.0).normalize();
        let tv = Vector3::new(s.x, s.y, zx * s.x + zy * s.y).normalize();
        let w = Vector3::new(0.1 * wt * s.x, 0.1 * wt * s.y, -wt);
        let area = d * d * (1.0 + zx * zx + zy * zy).sqrt();
        let normal = (w.dot(&n) - u * area).max(0.0);
        resisting += mat.cohesion * area + normal * mat.friction_coefficient;
        driving += w.dot(&tv);
        weight += wt;
    }
    let fs = resisting / driving;
    assert!(
        (got.safety_factor - fs).abs() <= 1e-12 * fs,
        "{} vs {fs}",
        got.safety_factor
    );
    assert!((got.weight - weight).abs() <= 1e-12 * weight);
    let single = Evaluator::new(&t, &m[1], &loads, &SurfaceLimits::default())
        .unwrap()
        .evaluate(&sphere, &mut Vec::new())
        .unwrap();
    assert!((single.safety_factor - fs).abs() > 1e-3 * fs);
    println!(
        "layered Fs {fs} over {} columns, bases {in_layer:?}",
        cols.len()
    );
}

/// Bad layers and bad r_u: typed errors naming the layer, file and value.
#[test]
fn bad_layers_and_ratios_are_refused_with_typed_errors() {
    let dem = valley_dem();
    let t = terrain(&dem);
    let loads = SlopeLoads::default();
    let lim = SurfaceLimits::default();
    // A bottom on another grid (cell size 3 m).
    let off = NamedRaster::new(
        "off.asc",
        Raster::from_fn(48, 40, 100.0, 200.0, 3.0, |_, _| Some(0.0)).unwrap(),
    );
    let g = Ground::layered(vec![
        layer("sand", Some(off), soil()),
        layer("clay", None, soil()),
    ])
    .unwrap();
    match Evaluator::new(&t, &g, &loads, &lim).unwrap_err() {
        DismechError::Slope(SlopeError::InvalidLayer { layer, problem }) => {
            assert_eq!(layer, "sand");
            let message = problem.to_string();
            assert!(
                message.contains("off.asc") && message.contains("valley"),
                "{message}"
            );
            assert!(
                matches!(&problem, LayerProblem::BottomOffGrid(e) if matches!(**e, DismechError::Grid(GridError::Mismatch { .. }))),
                "{problem:?}"
            );
        }
        e => panic!("{e}"),
    }
    // A bad material in a layer names the layer and the value.
    let weak = SlopeMaterial {
        unit_weight: -5.0,
        ..soil()
    };
    match Ground::layered(vec![
        layer("sand", Some(below(&dem, 2.0, "b.asc")), soil()),
        layer("peat", None, weak),
    ])
    .unwrap_err()
    {
        DismechError::Slope(SlopeError::InvalidLayer { layer, problem }) => {
            assert_eq!(layer, "peat");
            let message = problem.to_string();
            assert!(message.contains("-5"), "{message}");
            assert!(
                matches!(&problem, LayerProblem::Material(e) if matches!(**e, DismechError::InvalidParameter { value, .. } if value == -5.0)),
                "{problem:?}"
            );
        }
        e => panic!("{e}"),
    }
    // A layer other than the last without a bottom; the last with one; none.
    let e = Ground::layered(vec![layer("a", None, soil()), layer("b", None, soil())]).unwrap_err();
    assert!(
        matches!(&e, DismechError::Slope(SlopeError::InvalidLayer { layer, .. }) if layer == "a"),
        "{e}"
    );
    assert!(
        matches!(
            &e,
            DismechError::Slope(SlopeError::InvalidLayer {
                problem: LayerProblem::NoBottom { index: 1, count: 2 },
                ..
            })
        ),
        "{e}"
    );
    let e = Ground::layered(vec![layer("a", Some(below(&dem, 1.0, "a.asc")), soil())]).unwrap_err();
    assert!(
        matches!(&e, DismechError::Slope(SlopeError::InvalidLayer { layer, problem }) if layer == "a" && problem.to_string().contains("a.asc")),
        "{e}"
    );
    assert!(
        matches!(&e, DismechError::Slope(SlopeError::InvalidLayer { problem: LayerProblem::LastHasBottom { bottom }, .. }) if bottom == "a.asc"),
        "{e}"
    );
    assert!(matches!(
        Ground::layered(vec![]).unwrap_err(),
        DismechError::Slope(SlopeError::InvalidLayer { .. })
    ));
    assert!(matches!(
        Ground::layered(vec![]).unwrap_err(),
        DismechError::Slope(SlopeError::InvalidLayer {
            problem: LayerProblem::NoLayer,
            ..
        })
    ));
    // r_u outside [0, 1).
    for v in [1.0, -0.1, f64::NAN, 1.5] {
        match Ground::from(soil())
            .with_pore_ratio(PoreRatio::Constant(v))
            .unwrap_err()
        {
            DismechError::Slope(SlopeError::PoreRatioOutOfRange { value, cell, .. }) => {
                assert!(value.to_bits() == v.to_bits());
                assert_eq!(cell, None);
            }
            e => panic!("{e}"),
        }
    }
    let bad = NamedRaster::new(
        "ru.asc",
        Raster::from_fn(48, 40, 100.0, 200.0, 2.0, |x, y| {
            Some(if x > 150.0 && y > 260.0 { 1.2 } else { 0.1 })
        })
        .unwrap(),
    );
    let err = Ground::from(soil())
        .with_pore_ratio(PoreRatio::Raster(bad))
        .unwrap_err();
    assert!(err.to_string().contains("at row 0, column 25:"), "{err}");
    match err {
        DismechError::Slope(SlopeError::PoreRatioOutOfRange {
            source_name,
            cell,
            value,
        }) => {
            assert_eq!(source_name, "ru.asc");
            assert_eq!(cell, Some((0, 25)));
            assert_eq!(value, 1.2);
        }
        e => panic!("{e}"),
    }
    // An r_u raster on another grid.
    let off = NamedRaster::new(
        "ru_off.asc",
        Raster::from_fn(47, 40, 100.0, 200.0, 2.0, |_, _| Some(0.1)).unwrap(),
    );
    let g = Ground::from(soil())
        .with_pore_ratio(PoreRatio::Raster(off))
        .unwrap();
    assert!(matches!(
        Evaluator::new(&t, &g, &loads, &lim).unwrap_err(),
        DismechError::Grid(GridError::Mismatch { file, .. }) if file == "ru_off.asc"
    ));
    // A water table and r_u together.
    let wet = Terrain::new(
        NamedRaster::new("valley", dem.clone()),
        Some(below(&dem, 2.0, "water.asc")),
    )
    .unwrap();
    let g = Ground::from(soil())
        .with_pore_ratio(PoreRatio::Constant(0.2))
        .unwrap();
    let e = search(
        &wet,
        &g,
        &loads,
        &family(),
        &SearchSettings::default(),
        |_, _| {},
    )
    .unwrap_err();
    match &e {
        DismechError::Slope(SlopeError::PorePressureTwice { water, ratio }) => {
            assert_eq!(water, "water.asc");
            assert!(ratio.contains("0.2"));
        }
        e => panic!("{e}"),
    }
    assert!(e.to_string().contains("water.asc") && e.to_string().contains("0.2"));
}
