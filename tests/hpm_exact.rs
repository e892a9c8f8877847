//! HPM slope analysis (paper 001) against exact solutions: a slab on a
//! planar slip surface (global equilibrium fixes Fs), the patch test of
//! uniform stress, layer refinement, and the errors bad input gets.

use dismech::error::DismechError;
use dismech::grid::{parse_esri_ascii, GridCellProblem, GridError, Raster};
use dismech::hpm::HpmError;
use dismech::hpm::*;
use dismech::linsolve::{AggregationSettings, CgSettings, LinearSolver, SparseCholesky};
use dismech::reference::PlanarSlab;
use nalgebra::{Matrix3, Point3, Vector3};
/// The horizontal unit vector at `deg` degrees counter-clockwise from +x.
fn towards_deg(deg: f64) -> (f64, f64) {
    let t = deg.to_radians();
    (t.cos(), t.sin())
}

/// A slab of vertical thickness `thickness` on the plane dipping at `dip`
/// degrees towards the horizontal direction `towards` (degrees from +x),
/// over `rows × columns` cells of 10 m; optional water table at `water`
/// above the slip surface.
fn slab(
    rows: usize,
    columns: usize,
    dip: f64,
    towards: f64,
    thickness: f64,
    water: Option<f64>,
) -> SlopeGrids {
    let (tx, ty) = (towards.to_radians().cos(), towards.to_radians().sin());
    let slope = dip.to_radians().tan();
    // Height falls along the dip direction.
    let plane = move |x: f64, y: f64| 500.0 - slope * (x * tx + y * ty);
    let raster = |offset: f64| {
        Raster::from_fn(columns, rows, 0.0, 0.0, 10.0, move |x, y| {
            Some(plane(x, y) + offset)
        })
        .unwrap()
    };
    SlopeGrids::new(
        NamedRaster::new("ground", raster(thickness)),
        NamedRaster::new("slip", raster(0.0)),
        water.map(|h| NamedRaster::new("water", raster(h))),
    )
    .unwrap()
}

struct Exact {
    weight: f64,
    plan: f64,
}

fn exact_slab(rows: usize, columns: usize, m: &HpmMaterial, h: f64, hw: Option<f64>) -> Exact {
    let plan = (rows * columns) as f64 * 100.0;
    let per_area = match hw {
        None => m.unit_weight * h,
        Some(w) => m.submerged_unit_weight * w + m.unit_weight * (h - w),
    };
    Exact {
        weight: per_area * plan,
        plan,
    }
}

/// `(cA + W(cos β − k_h sin β) tan φ) / (W(sin β + k_h cos β))`.
fn exact_fs(e: &Exact, m: &HpmMaterial, dip: f64, kh: f64) -> f64 {
    PlanarSlab {
        cohesion: m.cohesion,
        friction: m.friction(),
        weight: e.weight,
        plan_area: e.plan,
        dip: dip.to_radians(),
    }
    .safety_factor(kh)
}

fn material() -> HpmMaterial {
    HpmMaterial {
        cohesion: 10.0e3,
        ..HpmMaterial::paper()
    }
}

#[test]
fn planar_slab_fs_is_exact_for_elastic_hpm_and_hovland_static_seismic_and_submerged() {
    let m = material();
    // (dip, towards, k_h, water height above the slip surface)
    let cases = [
        (25.0, 270.0, 0.0, None),
        (18.0, 225.0, 0.0, None),
        (25.0, 270.0, 0.15, None),
        (30.0, 0.0, 0.15, None),
        (25.0, 270.0, 0.0, Some(3.0)),
        (20.0, 200.0, 0.1, Some(6.5)),
    ];
    let (rows, columns, h) = (5, 7, 8.0);
    for (dip, towards, kh, hw) in cases {
        let grids = slab(rows, columns, dip, towards, h, hw);
        let model = HpmModel::new(&grids, &m, &HpmSettings::default()).unwrap();
        let exact_w = exact_slab(rows, columns, &m, h, hw);
        assert!((model.total_weight() - exact_w.weight).abs() < 1e-9 * exact_w.weight);
        let seismic = Seismic {
            coefficient: kh,
            direction: towards_deg(towards),
        };
        // Under a water table the seepage force `γ_w h_w tan β` per unit
        // plan area (γ_w = γ_t − γ_sub) pushes down the dip beside the
        // seismic force, `k_h` times the total weight `γ_t h`: together a
        // seismic coefficient on the submerged weight W' of their sum over
        // W'.
        let plan_weight = exact_w.weight / exact_w.plan;
        let horizontal = kh * m.unit_weight * h
            + hw.map_or(0.0, |w| {
                (m.unit_weight - m.submerged_unit_weight) * w * dip.to_radians().tan()
            });
        let exact = exact_fs(&exact_w, &m, dip, horizontal / plan_weight);
        if let Some(w) = hw {
            // The same Fs from the total weight σ_v = γ_t h, its seismic
            // force and the pore pressure `u = γ_w h_w` on the base:
            // `(c + (σ_v (cos β − k_h sin β) cos β − u) tan φ) /
            // (σ_v (sin β + k_h cos β) cos β)`.
            let (beta, sigma_v) = (dip.to_radians(), m.unit_weight * h);
            let u = (m.unit_weight - m.submerged_unit_weight) * w;
            let normal = sigma_v * (beta.cos() - kh * beta.sin()) * beta.cos() - u;
            let total = (m.cohesion + normal * m.friction())
                / (sigma_v * (beta.sin() + kh * beta.cos()) * beta.cos());
            assert!((total / exact - 1.0).abs() < 1e-12, "{total} vs {exact}");
        }
        let mut solver = HpmSolver::new(&model).unwrap();
        let elastic = solver.elastic(&model, &seismic).unwrap();
        let fs = elastic.safety_factor(&model).unwrap();
        let sliding = elastic.sliding_safety_factor(&model).unwrap();
        let hov = hovland(&model, &seismic, towards_deg(towards))
            .unwrap()
            .safety_factor;
        eprintln!("dip {dip} towards {towards} k_h {kh} water {hw:?}: exact {exact:.5}, HPM stress ratio {fs:.5}, HPM along the sliding direction {sliding:.5}, Hovland {hov:.5}");
        assert!((fs / exact - 1.0).abs() < 0.01, "HPM {fs} vs exact {exact}");
        // The resultant shear of the springs balances the load's component
        // along the plane, which points down the dip.
        let (hx, hy) = elastic.sliding_direction(&model).unwrap();
        let (tx, ty) = (towards.to_radians().cos(), towards.to_radians().sin());
        assert!(
            (hx * ty - hy * tx).abs() < 1e-9 && hx * tx + hy * ty > 0.0,
            "sliding direction ({hx}, {hy}) vs ({tx}, {ty})"
        );
        // Along that direction the sums are those of global equilibrium.
        assert!(
            (sliding / exact - 1.0).abs() < 1e-6,
            "HPM along the sliding direction {sliding} vs exact {exact}"
        );
        assert!(sliding >= fs * (1.0 - 1e-12));
        assert!(
            (hov / exact - 1.0).abs() < 1e-9,
            "Hovland {hov} vs exact {exact}"
        );
    }
}

/// A pore-pressure ratio on a planar slab: `u = r_u σ_v` on the slip
/// surface (σ_v = γ h, no water table) gives Bishop & Morgenstern's
/// infinite-slope Fs `(c + (cos² β − r_u) σ_v tan φ) / (σ_v sin β cos β)`,
/// static, and with the seismic load `(c + ((cos β − k_h sin β) cos β −
/// r_u) σ_v tan φ) / (σ_v (sin β + k_h cos β) cos β)`: elastic HPM along
/// the sliding direction to 1e-6, Hovland on HPM's columns to 1e-9. Bad
/// pressures and columns are refused, naming the value.
#[test]
fn planar_slab_with_a_pore_pressure_ratio_gives_the_exact_fs() {
    let m = material();
    let (rows, columns, h) = (5, 7, 8.0);
    for (dip, towards, kh, ru) in [
        (25.0, 270.0, 0.0, 0.2),
        (18.0, 225.0, 0.0, 0.35),
        (20.0, 200.0, 0.1, 0.25),
    ] {
        let grids = slab(rows, columns, dip, towards, h, None);
        let mut model = HpmModel::new(&grids, &m, &HpmSettings::default()).unwrap();
        let sigma_v = m.unit_weight * h;
        for k in 0..model.columns.len() {
            model.set_column_pore_pressure(k, ru * sigma_v).unwrap();
        }
        assert!(model
            .column_pore_pressures()
            .iter()
            .all(|&u| u == ru * sigma_v));
        let beta = f64::to_radians(dip);
        let normal = sigma_v * (beta.cos() - kh * beta.sin()) * beta.cos() - ru * sigma_v;
        let exact = (m.cohesion + normal * m.friction())
            / (sigma_v * (beta.sin() + kh * beta.cos()) * beta.cos());
        let seismic = Seismic {
            coefficient: kh,
            direction: towards_deg(towards),
        };
        let elastic = HpmSolver::new(&model)
            .unwrap()
            .elastic(&model, &seismic)
            .unwrap();
        let sliding = elastic.sliding_safety_factor(&model).unwrap();
        let hov = hovland(&model, &seismic, towards_deg(towards))
            .unwrap()
            .safety_factor;
        eprintln!("dip {dip} k_h {kh} r_u {ru}: exact {exact:.5}, HPM along the sliding direction {sliding:.5}, Hovland {hov:.5}");
        assert!(
            (sliding / exact - 1.0).abs() < 1e-6,
            "HPM {sliding} vs exact {exact}"
        );
        assert!(
            (hov / exact - 1.0).abs() < 1e-9,
            "Hovland {hov} vs exact {exact}"
        );
        // The springs carry the effective stress: their normal tractions
        // sum to the effective normal force.
        let springs: f64 = model
            .slip
            .iter()
            .zip(&elastic.tractions)
            .map(|(s, t)| t.normal * s.point.point.area)
            .sum();
        let plan = (rows * columns) as f64 * 100.0;
        let effective = normal * plan / beta.cos();
        assert!(
            (springs / effective - 1.0).abs() < 1e-6,
            "{springs} vs {effective}"
        );
    }
    let mut model = HpmModel::new(
        &slab(2, 2, 20.0, 270.0, 5.0, None),
        &m,
        &HpmSettings::default(),
    )
    .unwrap();
    for (column, pressure, name) in [
        (0, -1.0, "pore pressure u on the slip surface"),
        (0, f64::NAN, "pore pressure u on the slip surface"),
        (0, f64::INFINITY, "pore pressure u on the slip surface"),
        (4, 1.0, "HPM column index"),
    ] {
        match model.set_column_pore_pressure(column, pressure) {
            Err(DismechError::InvalidParameter { name: got, .. }) => assert_eq!(got, name),
            other => panic!("{column} {pressure}: {other:?}"),
        }
    }
    assert!(model.column_pore_pressures().iter().all(|&u| u == 0.0));
}

#[test]
fn planar_slab_slip_springs_balance_the_load_exactly() {
    // Global equilibrium: the slip tractions sum to the applied load.
    let m = material();
    let grids = slab(4, 6, 22.0, 250.0, 6.0, Some(2.0));
    let model = HpmModel::new(&grids, &m, &HpmSettings::default()).unwrap();
    let seismic = Seismic {
        coefficient: 0.15,
        direction: towards_deg(250.0),
    };
    let r = HpmSolver::new(&model)
        .unwrap()
        .elastic(&model, &seismic)
        .unwrap();
    let mut reaction = Vector3::zeros();
    for (s, t) in model.slip.iter().zip(&r.tractions) {
        let p = &s.point;
        // Force of the ground on the soil: against n (into the ground), s, t.
        reaction -=
            (p.point.normal * t.normal + p.s * t.shear[0] + p.t * t.shear[1]) * p.point.area;
    }
    let f = model.loads(&seismic);
    let applied: Vector3<f64> = (0..model.elements.len())
        .map(|e| Vector3::new(f[12 * e], f[12 * e + 1], f[12 * e + 2]))
        .sum();
    assert!(
        (reaction + applied).norm() < 1e-8 * applied.norm(),
        "{reaction} vs {applied}"
    );
}

/// A 4 × 5-column slab 6 m thick dipping 20° with c = 5 kPa, and its exact
/// safety factor.
fn cohesive_planar_slab() -> (HpmModel, f64) {
    let m = HpmMaterial {
        cohesion: 5.0e3,
        ..HpmMaterial::paper()
    };
    let (rows, columns, dip, h) = (4, 5, 20.0, 6.0);
    let grids = slab(rows, columns, dip, 270.0, h, None);
    let model = HpmModel::new(&grids, &m, &HpmSettings::default()).unwrap();
    let exact = exact_fs(&exact_slab(rows, columns, &m, h, None), &m, dip, 0.0);
    (model, exact)
}

#[test]
fn planar_slab_nonlinear_fs_is_exact_and_strength_reduction_finds_it() {
    let (model, exact) = cohesive_planar_slab();
    let mut solver = HpmSolver::new(&model).unwrap();
    let settings = NonlinearSettings::default();
    let r = solver
        .nonlinear(&model, &Seismic::none(), 1.0, &settings)
        .unwrap();
    assert!(r.convergence.converged(), "{:?}", r.convergence);
    assert!((r.safety_factor(&model).unwrap() / exact - 1.0).abs() < 0.01);
    assert!((r.sliding_safety_factor(&model).unwrap() / exact - 1.0).abs() < 0.01);
    let srf = strength_reduction(&mut solver, &model, &Seismic::none(), &settings, 0.005).unwrap();
    eprintln!(
        "exact {exact:.4}; strength reduction in [{:.4}, {:.4}]",
        srf.safety_factor, srf.failed_at
    );
    // The uniform slab fails everywhere at once, at F = Fs: the bracket holds it.
    assert!(
        srf.safety_factor <= exact * 1.001 && srf.failed_at >= exact * 0.98,
        "{srf:?}"
    );
}

#[test]
fn a_slab_that_cannot_stand_reports_non_convergence_with_its_residual() {
    let m = HpmMaterial {
        cohesion: 0.0,
        friction_coefficient: 15f64.to_radians().tan(),
        ..HpmMaterial::paper()
    };
    let grids = slab(3, 4, 25.0, 270.0, 5.0, None);
    let model = HpmModel::new(&grids, &m, &HpmSettings::default()).unwrap();
    let settings = NonlinearSettings {
        max_iterations: 200,
        ..NonlinearSettings::default()
    };
    let r = HpmSolver::new(&model)
        .unwrap()
        .nonlinear(&model, &Seismic::none(), 1.0, &settings)
        .unwrap();
    match r.convergence {
        Convergence::NotConverged {
            iterations,
            residual,
        } => {
            assert_eq!(iterations, 200);
            assert!(residual > settings.tolerance);
        }
        other => panic!("a slab at tan φ / tan β = 0.57 converged: {other:?}"),
    }
}

/// Gauss points of every outer face of a box model, with outward normals.
fn outer_faces(model: &HpmModel) -> Vec<(usize, FacePoint)> {
    let (rows, columns, d) = model.grid;
    let mut out = Vec::new();
    for column in &model.columns {
        let (r, c) = column.cell;
        for e in column.elements.clone() {
            let s = &model.elements[e].shape;
            let (x0, y0) = s.origin();
            let (b, t) = (s.bottom(), s.top());
            let mut push = |pts: Vec<FacePoint>, flip: bool| {
                for p in pts {
                    let normal = if flip { -p.normal } else { p.normal };
                    out.push((e, FacePoint { normal, ..p }));
                }
            };
            if c + 1 == columns {
                push(side_face((x0, y0), d, &b, &t, Side::East), false);
            }
            if c == 0 {
                push(side_face((x0 - d, y0), d, &b, &t, Side::East), true);
            }
            if r == 0 {
                push(side_face((x0, y0), d, &b, &t, Side::North), false);
            }
            if r + 1 == rows {
                push(side_face((x0, y0 - d), d, &b, &t, Side::North), true);
            }
            if e + 1 == column.elements.end {
                let top: Vec<FacePoint> = bilinear_face((x0, y0), d, &t)
                    .into_iter()
                    .map(|p| p.point)
                    .collect();
                push(top, true);
            }
            if e == column.elements.start {
                let bottom: Vec<FacePoint> = bilinear_face((x0, y0), d, &b)
                    .into_iter()
                    .map(|p| p.point)
                    .collect();
                push(bottom, false);
            }
        }
    }
    out
}

#[test]
fn patch_test_uniform_stress_gives_the_exact_uniform_strain_in_every_element() {
    let m = HpmMaterial::paper();
    let flat = |z: f64| Raster::from_fn(3, 3, 0.0, 0.0, 10.0, move |_, _| Some(z)).unwrap();
    let grids = SlopeGrids::new(
        NamedRaster::new("ground", flat(12.0)),
        NamedRaster::new("slip", flat(0.0)),
        None,
    )
    .unwrap();
    let model = HpmModel::new(
        &grids,
        &m,
        &HpmSettings {
            layers: 4,
            penalty: 100.0,
            ..HpmSettings::default()
        },
    )
    .unwrap();
    // A uniform stress with every component present (Pa).
    let sigma = Matrix3::new(-50e3, 8e3, 5e3, 8e3, -30e3, -4e3, 5e3, -4e3, -120e3);
    let mut f = vec![0.0; model.dof()];
    for (e, p) in outer_faces(&model) {
        let traction = sigma * p.normal * p.area;
        let n = shape_matrix(&model.elements[e].centre, &p.position);
        let g = n.transpose() * traction;
        for k in 0..12 {
            f[12 * e + k] += g[k];
        }
    }
    // Self-equilibrated tractions on every outer face; the rigid-body modes
    // are removed by holding element 0 (its reaction is zero: the load is
    // balanced and the exact solution has no rotation).
    let mut k = model.free_stiffness();
    let hold = 1e3 * k.diagonal()[0].diagonal().amax();
    for i in 0..6 {
        k.diagonal_mut()[0][(i, i)] += hold;
    }
    let mut solver = SparseCholesky::new();
    solver.factor(&k).unwrap();
    let mut u = f.clone();
    solver.solve_in_place(&k, &mut u).unwrap();
    // Exact strain ε = D⁻¹ σ (engineering shear).
    let d = elasticity(m.youngs_modulus, m.poisson_ratio);
    let s6 = nalgebra::SVector::<f64, 6>::from([
        sigma[(0, 0)],
        sigma[(1, 1)],
        sigma[(2, 2)],
        sigma[(1, 2)],
        sigma[(0, 2)],
        sigma[(0, 1)],
    ]);
    let exact = d.try_inverse().unwrap() * s6;
    for e in 0..model.elements.len() {
        for k in 0..6 {
            let got = u[12 * e + 6 + k];
            assert!(
                (got - exact[k]).abs() <= 1e-8 * exact.amax(),
                "element {e} strain {k}: {got} vs {}",
                exact[k]
            );
        }
    }
    // Element 0 is held with no reaction: the interface springs carry the
    // whole load, so its translation and rotation stay zero.
    for (i, held) in u.iter().take(6).enumerate() {
        assert!(
            held.abs() * hold <= 1e-8 * sigma.amax() * 100.0,
            "reaction at DOF {i}"
        );
    }
}

/// A bowl-shaped slide (ellipsoidal slip surface) on a plane slope.
fn bowl() -> SlopeGrids {
    let ground = Raster::from_fn(9, 11, 0.0, 0.0, 10.0, |_, y| Some(0.4 * y)).unwrap();
    let slip = Raster::from_fn(9, 11, 0.0, 0.0, 10.0, |x, y| {
        let q = ((x - 45.0) / 40.0).powi(2) + ((y - 55.0) / 50.0).powi(2);
        let g = 0.4 * y;
        Some(if q < 1.0 {
            (g - 12.0 * (1.0 - q).sqrt()).min(g)
        } else {
            g
        })
    })
    .unwrap();
    SlopeGrids::new(
        NamedRaster::new("ground", ground),
        NamedRaster::new("slip", slip),
        None,
    )
    .unwrap()
}

#[test]
fn layer_refinement_3_6_12_converges_in_fs_and_top_displacement() {
    let m = HpmMaterial::paper();
    let grids = bowl();
    let mut fs = Vec::new();
    let mut top = Vec::new();
    for layers in [3, 6, 12] {
        let model = HpmModel::new(
            &grids,
            &m,
            &HpmSettings {
                layers,
                penalty: 100.0,
                ..HpmSettings::default()
            },
        )
        .unwrap();
        let r = HpmSolver::new(&model)
            .unwrap()
            .elastic(&model, &Seismic::none())
            .unwrap();
        fs.push(r.safety_factor(&model).unwrap());
        let surface = r.surface(&model);
        top.push(
            surface
                .iter()
                .map(|p| p.displacement.norm())
                .fold(0.0, f64::max),
        );
    }
    eprintln!("layers 3, 6, 12: Fs {fs:?}, largest surface displacement {top:?} m");
    let change = |v: &[f64], k: usize| (v[k + 1] - v[k]).abs() / v[k + 1].abs();
    assert!(change(&fs, 1) < change(&fs, 0), "Fs {fs:?}");
    assert!(
        change(&top, 1) < change(&top, 0),
        "top displacement {top:?}"
    );
}

/// The bowl under k_h = 0.15 towards 270°, its elastic solution by the
/// sparse Cholesky factor, and PCG settings to a relative residual of
/// 1e-10.
fn bowl_with_direct_solution() -> (HpmModel, Seismic, HpmResult, CgSettings) {
    let model = HpmModel::new(&bowl(), &HpmMaterial::paper(), &HpmSettings::default()).unwrap();
    let seismic = Seismic {
        coefficient: 0.15,
        direction: towards_deg(270.0),
    };
    let direct = HpmSolver::new(&model)
        .unwrap()
        .elastic(&model, &seismic)
        .unwrap();
    let settings = CgSettings {
        relative_tolerance: 1e-10,
        max_iterations: 20_000,
    };
    (model, seismic, direct, settings)
}

/// `‖a − b‖ / ‖a‖`.
fn relative_difference(a: &[f64], b: &[f64]) -> f64 {
    let norm = |v: &mut dyn Iterator<Item = f64>| v.map(|x| x * x).sum::<f64>().sqrt();
    norm(&mut a.iter().zip(b).map(|(x, y)| x - y)) / norm(&mut a.iter().copied())
}

#[test]
fn pcg_with_column_blocks_reproduces_the_direct_elastic_solution() {
    let (model, seismic, direct, settings) = bowl_with_direct_solution();
    let iterative = HpmSolver::iterative(&model, settings)
        .unwrap()
        .elastic(&model, &seismic)
        .unwrap();
    let Convergence::Converged {
        iterations,
        residual,
    } = iterative.convergence
    else {
        panic!("PCG did not converge: {:?}", iterative.convergence);
    };
    let difference = relative_difference(&direct.displacements, &iterative.displacements);
    eprintln!(
        "PCG: {iterations} iterations, residual {residual:e}, relative difference from Cholesky {difference:e}",
    );
    assert!(residual <= 1e-9, "{residual}");
    assert!(difference <= 1e-6, "{difference}");
    let (a, b) = (
        direct.safety_factor(&model).unwrap(),
        iterative.safety_factor(&model).unwrap(),
    );
    assert!((a / b - 1.0).abs() < 1e-6, "{a} vs {b}");
}

/// PCG preconditioned by smoothed-aggregation multigrid (rigid motions,
/// and with the uniform strains) solves the bowl to the displacements of
/// the sparse Cholesky factor, in fewer iterations than the column blocks.
#[test]
fn pcg_with_smoothed_aggregation_reproduces_the_direct_elastic_solution() {
    let (model, seismic, direct, settings) = bowl_with_direct_solution();
    let columns = HpmSolver::iterative(&model, settings)
        .unwrap()
        .elastic(&model, &seismic)
        .unwrap();
    // A coarsest level small enough that the bowl has three levels.
    let aggregation = AggregationSettings {
        max_coarse: 50,
        ..AggregationSettings::default()
    };
    for modes in [6, 12] {
        let mut solver = HpmSolver::multigrid(&model, settings, aggregation, modes).unwrap();
        let levels = solver.linear_solver().preconditioner().level_sizes();
        assert!(levels.len() >= 2, "{levels:?}");
        let iterative = solver.elastic(&model, &seismic).unwrap();
        let (
            Convergence::Converged {
                iterations,
                residual,
            },
            Convergence::Converged {
                iterations: by_columns,
                ..
            },
        ) = (iterative.convergence, columns.convergence)
        else {
            panic!("PCG did not converge: {:?}", iterative.convergence);
        };
        let difference = relative_difference(&direct.displacements, &iterative.displacements);
        eprintln!(
            "{modes} modes, levels {levels:?}: {iterations} iterations (column blocks {by_columns}), residual {residual:e}, relative difference from Cholesky {difference:e}",
        );
        assert!(residual <= 1e-10, "{residual}");
        assert!(difference <= 1e-6, "{difference}");
        assert!(iterations < by_columns, "{iterations} vs {by_columns}");
        let (a, b) = (
            direct.safety_factor(&model).unwrap(),
            iterative.safety_factor(&model).unwrap(),
        );
        assert!((a / b - 1.0).abs() < 1e-6, "{a} vs {b}");
    }
}

/// The multigrid whose finest level solves whole grid columns and
/// aggregates squares of columns reproduces the direct solution, in fewer
/// iterations than the element-block multigrid and the column blocks alone,
/// for every side of the aggregates; a side of 0 is refused by name.
#[test]
fn pcg_with_column_multigrid_reproduces_the_direct_elastic_solution() {
    let (model, seismic, direct, settings) = bowl_with_direct_solution();
    let iterations_of = |result: &dismech::hpm::HpmResult| match result.convergence {
        Convergence::Converged { iterations, .. } => iterations,
        other => panic!("PCG did not converge: {other:?}"),
    };
    let by_columns = iterations_of(
        &HpmSolver::iterative(&model, settings)
            .unwrap()
            .elastic(&model, &seismic)
            .unwrap(),
    );
    let aggregation = AggregationSettings {
        max_coarse: 50,
        ..AggregationSettings::default()
    };
    let by_elements = iterations_of(
        &HpmSolver::multigrid(&model, settings, aggregation, 6)
            .unwrap()
            .elastic(&model, &seismic)
            .unwrap(),
    );
    for plan in [1, 2, 3] {
        let mut solver =
            HpmSolver::column_multigrid(&model, settings, aggregation, 6, plan).unwrap();
        let levels = solver.linear_solver().preconditioner().level_sizes();
        let iterative = solver.elastic(&model, &seismic).unwrap();
        let iterations = iterations_of(&iterative);
        let difference = relative_difference(&direct.displacements, &iterative.displacements);
        eprintln!(
            "plan {plan}, levels {levels:?}: {iterations} iterations (element multigrid {by_elements}, column blocks {by_columns}), relative difference from Cholesky {difference:e}",
        );
        assert!(levels.len() >= 2, "{levels:?}");
        assert!(difference <= 1e-6, "{difference}");
        assert!(iterations < by_elements, "{iterations} vs {by_elements}");
        assert!(iterations < by_columns, "{iterations} vs {by_columns}");
        let (a, b) = (
            direct.safety_factor(&model).unwrap(),
            iterative.safety_factor(&model).unwrap(),
        );
        assert!((a / b - 1.0).abs() < 1e-6, "{a} vs {b}");
    }
    let refused = HpmSolver::column_multigrid(&model, settings, aggregation, 6, 0).err();
    assert!(
        matches!(
            &refused,
            Some(DismechError::InvalidParameter { name, .. }) if name.contains("plan")
        ),
        "{refused:?}"
    );
}

/// A first multigrid level whose aggregates or lines do not fit the
/// matrix is refused at setup, naming what is wrong.
#[test]
fn a_line_level_that_does_not_fit_the_matrix_is_refused() {
    use dismech::linsolve::{LineLevel, Preconditioner, SmoothedAggregation, SolveError};
    let model = HpmModel::new(&bowl(), &HpmMaterial::paper(), &HpmSettings::default()).unwrap();
    let stiffness = model.stiffness();
    let elements = model.elements.len();
    let lines: Vec<_> = model.columns.iter().map(|c| c.elements.clone()).collect();
    let setup = |first: LineLevel| {
        let mut amg = SmoothedAggregation::new(
            AggregationSettings {
                max_coarse: 50,
                ..AggregationSettings::default()
            },
            linear_motions(&model, 6).unwrap(),
            6,
        )
        .with_lines(first);
        amg.setup(&stiffness)
    };
    let cases = [
        (
            LineLevel {
                aggregates: vec![0; elements - 1],
                lines: lines.clone(),
            },
            "one per block",
        ),
        (
            LineLevel {
                aggregates: (0..elements).map(|e| if e == 0 { 0 } else { 2 }).collect(),
                lines: lines.clone(),
            },
            "none empty",
        ),
        (
            LineLevel {
                aggregates: vec![0; elements],
                lines: lines[1..].to_vec(),
            },
            "consecutive",
        ),
        (
            LineLevel {
                aggregates: vec![0; elements],
                lines: lines[..lines.len() - 1].to_vec(),
            },
            "covered by the lines",
        ),
    ];
    for (first, what) in cases {
        match setup(first) {
            Err(SolveError::DimensionMismatch { what: said, .. }) => {
                assert!(said.contains(what), "{said} (expected: {what})")
            }
            other => panic!("{what}: {other:?}"),
        }
    }
    // The same columns as lines, with every column its own aggregate, set up.
    let aggregates = model
        .columns
        .iter()
        .enumerate()
        .flat_map(|(g, c)| c.elements.clone().map(move |_| g))
        .collect();
    setup(LineLevel { aggregates, lines }).unwrap();
}

/// A first level that does not fit the matrix is refused even where the
/// matrix is small enough to be factored whole (no level is built): the
/// caller's level is checked, not skipped.
#[test]
fn a_line_level_is_checked_where_the_matrix_is_factored_whole() {
    use dismech::linsolve::{LineLevel, Preconditioner, SmoothedAggregation, SolveError};
    let model = HpmModel::new(&bowl(), &HpmMaterial::paper(), &HpmSettings::default()).unwrap();
    let stiffness = model.stiffness();
    let elements = model.elements.len();
    let mut amg = SmoothedAggregation::new(
        AggregationSettings {
            max_coarse: usize::MAX,
            ..AggregationSettings::default()
        },
        linear_motions(&model, 6).unwrap(),
        6,
    )
    .with_lines(LineLevel {
        aggregates: vec![0; elements + 3],
        lines: model.columns.iter().map(|c| c.elements.clone()).collect(),
    });
    match amg.setup(&stiffness) {
        Err(SolveError::DimensionMismatch {
            what,
            expected,
            found,
        }) => {
            assert!(what.contains("one per block"), "{what}");
            assert_eq!((expected, found), (elements, elements + 3));
        }
        other => panic!("{other:?}"),
    }
}

/// The nonlinear analysis and the strength reduction by PCG (to a tight
/// residual) find the safety factors of the sparse Cholesky factor: the
/// linear solver is a slot of the analysis, not part of it.
#[test]
fn nonlinear_fs_and_strength_reduction_by_pcg_match_cholesky() {
    let m = HpmMaterial::paper();
    let model = HpmModel::new(&bowl(), &m, &HpmSettings::default()).unwrap();
    let settings = NonlinearSettings::default();
    let cg = CgSettings {
        relative_tolerance: 1e-12,
        max_iterations: 20_000,
    };
    let mut direct = HpmSolver::new(&model).unwrap();
    let mut iterative: HpmIterativeSolver = HpmSolver::iterative(&model, cg).unwrap();
    let a = direct
        .nonlinear(&model, &Seismic::none(), 1.0, &settings)
        .unwrap();
    let b = iterative
        .nonlinear(&model, &Seismic::none(), 1.0, &settings)
        .unwrap();
    assert!(
        a.convergence.converged() && b.convergence.converged(),
        "{:?} {:?}",
        a.convergence,
        b.convergence
    );
    // Most of the slip surface yields: the iteration is far from elastic.
    assert!(a.yielded_area_fraction(&model) > 0.5);
    for (x, y) in [
        (
            a.safety_factor(&model).unwrap(),
            b.safety_factor(&model).unwrap(),
        ),
        (
            a.sliding_safety_factor(&model).unwrap(),
            b.sliding_safety_factor(&model).unwrap(),
        ),
    ] {
        eprintln!("nonlinear Fs: Cholesky {x:.10}, PCG {y:.10}");
        assert!((x / y - 1.0).abs() < 1e-7, "{x} vs {y}");
    }
    // The column multigrid (two levels or more): its hierarchy, built
    // once from the elastic stiffness, serves every iteration of the
    // nonlinear analysis.
    let aggregation = AggregationSettings {
        max_coarse: 50,
        ..AggregationSettings::default()
    };
    let mut multigrid = HpmSolver::column_multigrid(&model, cg, aggregation, 6, 2).unwrap();
    let levels = multigrid.linear_solver().preconditioner().level_sizes();
    assert!(levels.len() >= 2, "{levels:?}");
    let c = multigrid
        .nonlinear(&model, &Seismic::none(), 1.0, &settings)
        .unwrap();
    assert!(c.convergence.converged(), "{:?}", c.convergence);
    let (x, y) = (
        a.safety_factor(&model).unwrap(),
        c.safety_factor(&model).unwrap(),
    );
    eprintln!("nonlinear Fs: Cholesky {x:.10}, column multigrid {y:.10}");
    assert!((x / y - 1.0).abs() < 1e-7, "{x} vs {y}");
    // Strength reduction on the planar slab, whose exact Fs is known
    // (an iteration limit of 300 keeps the failing trials short).
    let (model, exact) = cohesive_planar_slab();
    let settings = NonlinearSettings {
        max_iterations: 300,
        ..settings
    };
    let mut direct = HpmSolver::new(&model).unwrap();
    let mut iterative = HpmSolver::iterative(&model, cg).unwrap();
    let none = Seismic::none();
    let a = strength_reduction(&mut direct, &model, &none, &settings, 0.005).unwrap();
    let b = strength_reduction(&mut iterative, &model, &none, &settings, 0.005).unwrap();
    eprintln!("exact {exact:.4}; Cholesky {a:?}; PCG {b:?}");
    assert!(
        b.safety_factor <= exact * 1.001 && b.failed_at >= exact * 0.98,
        "{b:?}"
    );
    assert!(
        (a.safety_factor / b.safety_factor - 1.0).abs() <= 0.005,
        "{a:?} vs {b:?}"
    );
}

const GRID: &str = "ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 10\nNODATA_value -9999\n";

fn named(name: &str, values: &str) -> NamedRaster {
    NamedRaster::new(
        name,
        parse_esri_ascii(&format!("{GRID}{values}"), name).unwrap(),
    )
}

/// `error` is a [`GridError::Cell`] of the file, row and column `at` with
/// `problem`.
fn assert_cell_error(error: DismechError, at: (&str, usize, usize), problem: GridCellProblem) {
    match error {
        DismechError::Grid(GridError::Cell {
            file,
            row,
            column,
            problem: found,
        }) => {
            assert_eq!((file.as_str(), row, column), at);
            assert_eq!(found, problem);
        }
        e => panic!("{e}"),
    }
}

#[test]
fn bad_grids_get_typed_errors_naming_file_row_and_column() {
    let ground = || named("ground.asc", "10 10 10\n10 10 10\n10 10 10\n");
    // A different grid.
    let other = NamedRaster::new(
        "slip.asc",
        parse_esri_ascii(
            "ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 5\n1 1 1\n1 1 1\n1 1 1\n",
            "slip.asc",
        )
        .unwrap(),
    );
    match SlopeGrids::new(ground(), other, None).unwrap_err() {
        DismechError::Grid(GridError::Mismatch {
            file,
            reference,
            found,
            expected,
        }) => {
            assert_eq!(
                (file.as_str(), reference.as_str()),
                ("slip.asc", "ground.asc")
            );
            assert_eq!((found.rows, found.columns, found.cell_size), (3, 3, 5.0));
            assert_ne!(found, expected);
        }
        e => panic!("{e}"),
    }
    // A hole in the slip surface inside the slide.
    let holed = named("slip.asc", "5 5 5\n5 -9999 5\n5 5 5\n");
    assert_cell_error(
        SlopeGrids::new(ground(), holed, None).unwrap_err(),
        ("slip.asc", 1, 1),
        GridCellProblem::SlipSurfaceHole,
    );
    // No ground data where the slip surface is given.
    let g = named("ground.asc", "10 10 10\n10 10 10\n10 -9999 10\n");
    assert_cell_error(
        SlopeGrids::new(g, named("slip.asc", "5 5 5\n5 5 5\n5 5 5\n"), None).unwrap_err(),
        ("ground.asc", 2, 1),
        GridCellProblem::NoGround,
    );
    // Water table missing over a valid column.
    let w = named("water.asc", "1 1 1\n1 1 -9999\n1 1 1\n");
    assert_cell_error(
        SlopeGrids::new(
            ground(),
            named("slip.asc", "5 5 5\n5 5 5\n5 5 5\n"),
            Some(w),
        )
        .unwrap_err(),
        ("water.asc", 1, 2),
        GridCellProblem::NoWaterTable,
    );
    // Slip surface above the ground everywhere.
    let high = named("slip.asc", "11 11 11\n11 11 11\n11 11 11\n");
    assert!(matches!(
        SlopeGrids::new(ground(), high, None).unwrap_err(),
        DismechError::Hpm(HpmError::NoValidColumn { .. })
    ));
    // NaN in a file is refused with its line and column.
    let nan = parse_esri_ascii(&format!("{GRID}1 1 1\n1 NaN 1\n1 1 1\n"), "slip.asc").unwrap_err();
    assert!(
        matches!(
            nan,
            DismechError::Grid(GridError::Format {
                line: 8,
                column: 3,
                ..
            })
        ),
        "{nan}"
    );
}

#[test]
fn bad_material_values_are_refused_with_their_name_and_value() {
    let grids = slab(2, 2, 20.0, 270.0, 5.0, None);
    for (m, name) in [
        (
            HpmMaterial {
                poisson_ratio: 0.5,
                ..HpmMaterial::paper()
            },
            "Poisson's ratio nu",
        ),
        (
            HpmMaterial {
                cohesion: -1.0,
                ..HpmMaterial::paper()
            },
            "cohesion c",
        ),
        (
            HpmMaterial {
                friction_coefficient: f64::INFINITY,
                ..HpmMaterial::paper()
            },
            "friction coefficient mu = tan(phi)",
        ),
        (
            HpmMaterial {
                friction_coefficient: -1.0,
                ..HpmMaterial::paper()
            },
            "friction coefficient mu = tan(phi)",
        ),
        // γ_t − γ_sub is the pore water's unit weight: not negative.
        (
            HpmMaterial {
                submerged_unit_weight: 18.5e3,
                ..HpmMaterial::paper()
            },
            "submerged unit weight gamma_sub",
        ),
    ] {
        match HpmModel::new(&grids, &m, &HpmSettings::default()).unwrap_err() {
            DismechError::InvalidParameter { name: got, .. } => assert_eq!(got, name),
            e => panic!("{e}"),
        }
    }
    // The same for a weight stratum of a column.
    let mut model = HpmModel::new(&grids, &HpmMaterial::paper(), &HpmSettings::default()).unwrap();
    let heavier_under_water = WeightStratum {
        bottom: None,
        unit_weight: 18e3,
        submerged_unit_weight: 18.5e3,
    };
    match model
        .set_column_strata(&grids, 0, &[heavier_under_water])
        .unwrap_err()
    {
        DismechError::InvalidParameter { name, value, .. } => {
            assert_eq!(name, "HPM weight stratum: submerged unit weight gamma_sub");
            assert_eq!(value, 18.5e3);
        }
        e => panic!("{e}"),
    }
    // An angle is converted once, and refused outside [0, 90) degrees.
    for bad in [90.0, -1.0, f64::NAN] {
        match HpmMaterial::paper()
            .with_friction_angle_deg(bad)
            .unwrap_err()
        {
            DismechError::InvalidParameter { name, .. } => {
                assert_eq!(name, "friction angle phi (degrees)")
            }
            e => panic!("{e}"),
        }
    }
    let m = HpmMaterial::paper().with_friction_angle_deg(22.0).unwrap();
    assert_eq!(m, HpmMaterial::paper());
    assert!(HpmModel::new(
        &grids,
        &HpmMaterial::paper(),
        &HpmSettings {
            layers: 2,
            penalty: 100.0,
            ..HpmSettings::default()
        }
    )
    .is_err());
}

#[test]
fn shape_matrix_moves_a_point_rigidly_for_rotation_dofs() {
    let c = Point3::new(0.0, 0.0, 0.0);
    let mut u = ElementDofs::zeros();
    u[5] = 1e-3; // rotation about z
    let d = displacement_at(&c, &u, &Point3::new(2.0, 0.0, 0.0));
    assert!((d - Vector3::new(0.0, 2e-3, 0.0)).norm() < 1e-15);
}

/// A flat slab (no dip) of 3 × 4 cells, `thickness` m thick.
fn flat_slab(thickness: f64) -> SlopeGrids {
    slab(3, 4, 0.0, 270.0, thickness, None)
}

#[test]
fn empty_hpm_model_is_refused() {
    // One valid cell (its centre's slip surface just under the ground), but
    // every corner's slip height, interpolated from the cells around, lies
    // above the ground and is lowered to it: a column of zero volume.
    let ground = Raster::from_fn(3, 3, 0.0, 0.0, 10.0, |_, _| Some(10.0)).unwrap();
    let slip = Raster::from_fn(3, 3, 0.0, 0.0, 10.0, |x, y| {
        let centre = (x - 15.0).abs() < 1.0 && (y - 15.0).abs() < 1.0;
        Some(if centre { 9.999 } else { 20.0 })
    })
    .unwrap();
    let grids = SlopeGrids::new(
        NamedRaster::new("ground.asc", ground),
        NamedRaster::new("slip.asc", slip),
        None,
    )
    .unwrap();
    assert_eq!(grids.valid_cells(), vec![(1, 1)]);
    match HpmModel::new(&grids, &HpmMaterial::paper(), &HpmSettings::default()) {
        Err(DismechError::Hpm(HpmError::EmptyHpmModel {
            ground,
            slip,
            valid,
        })) => {
            assert_eq!(
                (ground.as_str(), slip.as_str(), valid),
                ("ground.asc", "slip.asc", 1)
            );
        }
        other => panic!("an empty model was not refused: {other:?}"),
    }
}

#[test]
fn nearly_incompressible_elastic_reports_residual() {
    let grids = slab(4, 5, 22.0, 270.0, 6.0, None);
    let nu = 0.4999999999;
    let m = HpmMaterial {
        poisson_ratio: nu,
        ..material()
    };
    let model = HpmModel::new(&grids, &m, &HpmSettings::default()).unwrap();
    let mut solver = HpmSolver::new(&model).unwrap();
    let r = solver.elastic(&model, &Seismic::none()).unwrap();
    // The reported residual is the solve's own: ‖F − K U‖ / ‖F‖.
    let f = model.loads(&Seismic::none());
    let ku = solver.stiffness().multiply(&r.displacements);
    let out: f64 = f.iter().zip(&ku).map(|(a, b)| (a - b).powi(2)).sum();
    let ff: f64 = f.iter().map(|a| a * a).sum();
    let true_residual = (out / ff).sqrt();
    match r.convergence {
        Convergence::NotConverged { residual, .. } => {
            assert!(residual > EQUILIBRIUM_TOLERANCE, "{residual}");
            assert!(
                (residual / true_residual - 1.0).abs() < 1e-9,
                "{residual} vs {true_residual}"
            );
        }
        other => panic!("ν = {nu} reported {other:?}"),
    }
    assert_eq!(
        r.ill_conditioning,
        vec![IllConditioning::NearlyIncompressible { poisson_ratio: nu }]
    );
    assert!(r.ill_conditioning[0].to_string().contains("nu <="));
    // The same slab at the paper's ν solves to within the tolerance and
    // lists nothing.
    let model = HpmModel::new(&grids, &material(), &HpmSettings::default()).unwrap();
    let r = HpmSolver::new(&model)
        .unwrap()
        .elastic(&model, &Seismic::none())
        .unwrap();
    assert!(r.convergence.converged(), "{:?}", r.convergence);
    assert!(r.ill_conditioning.is_empty());
}

#[test]
fn stiff_penalty_elastic_reports_residual_and_names_p() {
    let grids = slab(4, 5, 22.0, 270.0, 6.0, None);
    let penalty = 1e12;
    let settings = HpmSettings {
        penalty,
        ..HpmSettings::default()
    };
    let model = HpmModel::new(&grids, &material(), &settings).unwrap();
    let r = HpmSolver::new(&model)
        .unwrap()
        .elastic(&model, &Seismic::none())
        .unwrap();
    assert!(
        matches!(r.convergence, Convergence::NotConverged { residual, .. } if residual > EQUILIBRIUM_TOLERANCE),
        "{:?}",
        r.convergence
    );
    assert_eq!(
        r.ill_conditioning,
        vec![IllConditioning::StiffPenalty { penalty }]
    );
}

#[test]
fn slip_surface_at_the_ground_is_named_when_the_factorization_fails() {
    // 0.1 µm of soil over 10 m cells: the Cholesky factorization fails
    // (a stiffness that is not finite, or not positive definite).
    let grids = slab(3, 4, 22.0, 270.0, 1e-7, None);
    let model = HpmModel::new(&grids, &material(), &HpmSettings::default()).unwrap();
    match HpmSolver::new(&model) {
        Err(DismechError::Hpm(HpmError::IllConditioned { causes, .. })) => {
            assert_eq!(causes.len(), 1, "{causes:?}");
            let IllConditioning::ThinColumn {
                thickness,
                cell_size,
                ..
            } = causes[0]
            else {
                panic!("{causes:?}");
            };
            assert!(thickness < THIN_COLUMN_RATIO * cell_size);
            assert!(causes[0].to_string().contains("slip surface"));
        }
        Err(other) => panic!("{other}"),
        Ok(_) => panic!("a 0.1 µm slab was factored"),
    }
}

#[test]
fn cohesionless_frictionless_fs_is_not_nan_converged() {
    // On flat ground nothing drives: with c = φ = 0 the Fs would be 0 / 0.
    let m = HpmMaterial {
        cohesion: 0.0,
        friction_coefficient: 0.0,
        ..HpmMaterial::paper()
    };
    match HpmModel::new(&flat_slab(6.0), &m, &HpmSettings::default()) {
        Err(DismechError::InvalidParameter { name, value, .. }) => {
            assert!(name.starts_with("cohesion c"), "{name}");
            assert_eq!(value, 0.0);
        }
        other => panic!("c = φ = 0 was accepted: {other:?}"),
    }
    // Either alone is a strength.
    for (cohesion, friction_coefficient) in [(1.0e3, 0.0), (0.0, 20f64.to_radians().tan())] {
        let m = HpmMaterial {
            cohesion,
            friction_coefficient,
            ..HpmMaterial::paper()
        };
        assert!(HpmModel::new(&flat_slab(6.0), &m, &HpmSettings::default()).is_ok());
    }
}

#[test]
fn strength_reduction_without_any_equilibrium_gives_no_factor() {
    // c = 0 and φ = 0.001° under a 25° slope: no factor down to 1e-3 (tan φ
    // × 1000 = 0.017 < tan 25°) holds it.
    let m = HpmMaterial {
        cohesion: 0.0,
        friction_coefficient: 0.001f64.to_radians().tan(),
        ..HpmMaterial::paper()
    };
    let grids = slab(3, 4, 25.0, 270.0, 5.0, None);
    let model = HpmModel::new(&grids, &m, &HpmSettings::default()).unwrap();
    let settings = NonlinearSettings {
        max_iterations: 100,
        ..NonlinearSettings::default()
    };
    let mut solver = HpmSolver::new(&model).unwrap();
    match strength_reduction(&mut solver, &model, &Seismic::none(), &settings, 0.02) {
        Err(DismechError::Hpm(HpmError::StrengthReductionNoEquilibrium { factor })) => {
            assert!(factor < MIN_REDUCTION_FACTOR, "{factor}");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn strength_reduction_without_any_failure_gives_no_factor() {
    // Flat ground: no shear, equilibrium whatever the strength.
    let model = HpmModel::new(&flat_slab(6.0), &material(), &HpmSettings::default()).unwrap();
    let mut solver = HpmSolver::new(&model).unwrap();
    let settings = NonlinearSettings::default();
    match strength_reduction(&mut solver, &model, &Seismic::none(), &settings, 0.02) {
        Err(DismechError::Hpm(HpmError::StrengthReductionNoFailure { factor })) => {
            assert!(factor > MAX_REDUCTION_FACTOR, "{factor}");
        }
        other => panic!("{other:?}"),
    }
}

/// `set_column_strata` weighs a column over the grids the model was built
/// on: grids of other rows, columns or cell size are refused by name (not
/// indexed out of range); the model's own grids are taken.
#[test]
fn column_strata_over_other_grids_are_refused() {
    let m = material();
    let grids = slab(4, 5, 25.0, 270.0, 8.0, None);
    let mut model = HpmModel::new(&grids, &m, &HpmSettings::default()).unwrap();
    let strata = [WeightStratum {
        bottom: None,
        unit_weight: m.unit_weight,
        submerged_unit_weight: m.submerged_unit_weight,
    }];
    let last = model.columns.len() - 1;
    for (other, name) in [
        (slab(2, 5, 25.0, 270.0, 8.0, None), "rows of the grids"),
        (slab(4, 2, 25.0, 270.0, 8.0, None), "columns of the grids"),
    ] {
        let e = model.set_column_strata(&other, last, &strata).unwrap_err();
        assert!(
            matches!(e, DismechError::InvalidParameter { .. }) && e.to_string().contains(name),
            "{e}"
        );
    }
    let weights: Vec<f64> = model.elements.iter().map(|e| e.weight).collect();
    model.set_column_strata(&grids, last, &strata).unwrap();
    let after: Vec<f64> = model.elements.iter().map(|e| e.weight).collect();
    assert_eq!(weights, after);
}
