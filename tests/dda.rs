//! Implicit DDA (paper 003): the return-mapping law, the contact
//! kinematics' derivatives, a patch test, the block on an inclined plane,
//! the exact sliding-block solution, and bad input.

use crate::dda_common;

use dda_common::{material, rect};
use dismech::dda::{
    Block, BlockMaterial, DdaModel, DdaSettings, FrictionIntegration, PenaltyCoulomb, PenaltyState,
    Prescribed,
};
use dismech::error::DismechError;
use dismech::implicit::ImplicitError;
use dismech::integrate::{Newmark, Restarting};
use dismech::kinematics::Affine2;
use dismech::law::{ContactInput, ContactLaw, PairProperties, Regime, TangentLaw};
use dismech::math::{Point, Vec2};
use dismech::query::variation::{
    DofVariation, GapVariation, PairMatrix, PairVector, VertexEdgeContact,
};
use dismech::reference::sliding_block::brute_force_sliding;
use dismech::reference::{compliant_sliding_block, rigid_sliding_block, Shaking};
use nalgebra::{SVector, Vector2};
use proptest::prelude::*;

fn input(overlap: f64, shear: f64) -> ContactInput<2> {
    ContactInput {
        overlap,
        increment: Vector2::new(0.0, shear),
        dt: 1e-3,
        is_new: false,
        pair: PairProperties {
            curvature_radius_a: f64::INFINITY,
            curvature_radius_b: f64::INFINITY,
            width: 0.0,
            mass_a: 1.0,
            mass_b: 1.0,
        },
        rotation: 0.0,
    }
}

proptest! {
    /// After the return mapping `|t_s| ≤ μ t_n`, the contact sticks when
    /// the trial is inside the cone, and never pulls.
    #[test]
    fn return_mapping_stays_in_the_cone_and_sticks_inside(
        p in 1e6f64..1e10, mu in 0.0f64..1.5, overlap in -1e-3f64..1e-3,
        old in -1.0f64..1.0, slip in -1e-3f64..1e-3,
    ) {
        let law = PenaltyCoulomb::new(p, mu, FrictionIntegration::ReturnMapping).unwrap();
        let t_n = p * overlap.max(0.0);
        let state = PenaltyState { normal: t_n, shear: old * mu * t_n, regime: Some(Regime::Stick) };
        let r = law.evaluate(&input(overlap, slip), &state);
        prop_assert!(r.force[0] >= 0.0);
        prop_assert!(r.force[1].abs() <= mu * r.force[0] * (1.0 + 1e-12) + 1e-12);
        if overlap <= 0.0 {
            prop_assert_eq!(r.force, SVector::<f64, 2>::zeros());
            prop_assert_eq!(r.regime, Regime::Open);
        } else {
            let trial = state.shear + p * slip;
            if trial.abs() < mu * t_n {
                prop_assert_eq!(r.regime, Regime::Stick);
                prop_assert!((r.force[1] - trial).abs() <= 1e-9 * trial.abs().max(1.0));
            } else {
                prop_assert_eq!(r.regime, Regime::Slip);
            }
        }
    }

    /// The consistent tangent equals a central finite difference of the
    /// updated traction, in LOCK and in CLOSE.
    #[test]
    fn return_mapping_tangent_is_the_derivative(
        p in 1e6f64..1e10, mu in 0.1f64..1.5, overlap in 1e-5f64..1e-3,
        old in -1.0f64..1.0, slip in -1e-3f64..1e-3,
    ) {
        let law = PenaltyCoulomb::new(p, mu, FrictionIntegration::ReturnMapping).unwrap();
        let t_n = p * overlap;
        let state = PenaltyState { normal: t_n, shear: old * mu * t_n, regime: Some(Regime::Stick) };
        let trial = state.shear + p * slip;
        // Stay away from the kink of the cone.
        prop_assume!((trial.abs() - mu * t_n).abs() > 1e-4 * mu * t_n);
        let (r, tangent) = law.evaluate_with_tangent(&input(overlap, slip), &state);
        let h = 1e-7 * overlap;
        for (k, (dov, ds)) in [(h, 0.0), (0.0, h)].into_iter().enumerate() {
            let plus = law.evaluate(&input(overlap + dov, slip + ds), &state).force;
            let minus = law.evaluate(&input(overlap - dov, slip - ds), &state).force;
            let fd = (plus - minus) / (2.0 * h);
            for row in 0..2 {
                let exact = tangent[(row, k)];
                prop_assert!((fd[row] - exact).abs() <= 1e-6 * p, "row {} col {}: fd {} tangent {} ({:?})", row, k, fd[row], exact, r.regime);
            }
        }
    }

    /// The first and second variations of g_n and g_s (eqs. 20–35) equal
    /// central finite differences of g_n and g_s in the twelve unknowns.
    #[test]
    fn contact_variations_match_finite_differences(
        dx in -0.2f64..0.2, gap in -0.01f64..0.01, tilt in -0.3f64..0.3,
        d in proptest::collection::vec(-0.01f64..0.01, 12),
    ) {
        let lower = Block::new(&rect(-1.0, -0.5, 1.0, 0.0), material(), 0).unwrap();
        let (c, s) = (tilt.cos(), tilt.sin());
        let corners: Vec<Point> = [(-0.3, 0.0), (0.3, 0.0), (0.3, 0.4), (-0.3, 0.4)]
            .iter()
            .map(|&(x, y)| Point::new(dx + c * x - s * y, gap + s * x + c * y + 0.3 * tilt.abs()))
            .collect();
        let upper = Block::new(&corners, material(), 1).unwrap();
        let blocks = [lower, upper];
        // The lowest vertex of the upper block against the top edge (edge 2) of the lower one.
        let (vertex, _) = (0..4)
            .map(|v| (v, blocks[1].vertex(v).y))
            .fold((0, f64::INFINITY), |b, x| if x.1 < b.1 { x } else { b });
        let p1 = blocks[1].vertex(vertex);
        let (x2, x3) = (blocks[0].vertex(2), blocks[0].vertex(3));
        let xi = (p1 - x2).dot(&(x3 - x2)) / (x3 - x2).norm_squared();
        let contact = VertexEdgeContact { vertex: p1, reference_a: blocks[1].centroid(), edge: [x2, x3],
            reference_b: blocks[0].centroid(), xi, initial_gap: 0.0 };
        let split = |v: &[f64]| (SVector::<f64, 6>::from_column_slice(&v[6..12]), SVector::<f64, 6>::from_column_slice(&v[0..6]));
        let at = |v: &[f64]| { let (dj, dk) = split(v); twelve(contact.dof_variation(&Affine2, &dj, &Affine2, &dk).unwrap()) };
        let k0 = at(&d);
        let h = 1e-6;
        for i in 0..12 {
            // Unknown i of (d_j, d_k); d holds (d_k, d_j) in block order.
            let slot = if i < 6 { 6 + i } else { i - 6 };
            let mut plus = d.clone();
            plus[slot] += h;
            let mut minus = d.clone();
            minus[slot] -= h;
            let (kp, km) = (at(&plus), at(&minus));
            let fd_gap = (kp.gap - km.gap) / (2.0 * h);
            let fd_shear = (kp.shear - km.shear) / (2.0 * h);
            prop_assert!((fd_gap - k0.grad_gap[i]).abs() < 1e-7, "grad gap {}: {} vs {}", i, fd_gap, k0.grad_gap[i]);
            prop_assert!((fd_shear - k0.grad_shear[i]).abs() < 1e-7, "grad shear {}: {} vs {}", i, fd_shear, k0.grad_shear[i]);
            for j in 0..12 {
                let fd_hg = (kp.grad_gap[j] - km.grad_gap[j]) / (2.0 * h);
                let fd_hs = (kp.grad_shear[j] - km.grad_shear[j]) / (2.0 * h);
                prop_assert!((fd_hg - k0.hess_gap[(j, i)]).abs() < 1e-6, "hess gap {},{}: {} vs {}", j, i, fd_hg, k0.hess_gap[(j, i)]);
                prop_assert!((fd_hs - k0.hess_shear[(j, i)]).abs() < 1e-6, "hess shear {},{}: {} vs {}", j, i, fd_hs, k0.hess_shear[(j, i)]);
            }
        }
    }
}

/// `g_n`, `g_s` and their variations over the twelve unknowns `(d_j, d_k)`.
struct Twelve {
    gap: f64,
    shear: f64,
    grad_gap: SVector<f64, 12>,
    grad_shear: SVector<f64, 12>,
    hess_gap: nalgebra::SMatrix<f64, 12, 12>,
    hess_shear: nalgebra::SMatrix<f64, 12, 12>,
}

/// The pair's variations with the two bodies' blocks side by side.
fn twelve(v: DofVariation<6, 6>) -> Twelve {
    let grad = |g: &PairVector<6, 6>| {
        let mut out = SVector::<f64, 12>::zeros();
        out.fixed_rows_mut::<6>(0).copy_from(&g.a);
        out.fixed_rows_mut::<6>(6).copy_from(&g.b);
        out
    };
    let hess = |h: &PairMatrix<6, 6>| {
        let mut out = nalgebra::SMatrix::<f64, 12, 12>::zeros();
        out.fixed_view_mut::<6, 6>(0, 0).copy_from(&h.aa);
        out.fixed_view_mut::<6, 6>(0, 6).copy_from(&h.ab);
        out.fixed_view_mut::<6, 6>(6, 0).copy_from(&h.ba);
        out.fixed_view_mut::<6, 6>(6, 6).copy_from(&h.bb);
        out
    };
    Twelve {
        gap: v.gap,
        shear: v.shear,
        grad_gap: grad(&v.grad_gap),
        grad_shear: grad(&v.grad_shear),
        hess_gap: hess(&v.hess_gap),
        hess_shear: hess(&v.hess_shear),
    }
}

fn rotated(points: &[(f64, f64)], angle: f64, shift: Vec2) -> Vec<Point> {
    let (c, s) = (angle.cos(), angle.sin());
    points
        .iter()
        .map(|&(x, y)| Point::new(c * x - s * y + shift.x, s * x + c * y + shift.y))
        .collect()
}

/// A single block under a uniform stress applied as edge tractions
/// `t = σ n` takes exactly the strain `D⁻¹ σ` (one static step; the rigid
/// unknowns held), for a convex and a concave block.
#[test]
fn patch_test_uniform_stress_gives_the_exact_strain() {
    let shapes: [Vec<Point>; 2] = [
        rotated(
            &[(0.0, 0.0), (2.0, 0.1), (2.3, 1.2), (0.8, 1.9), (-0.4, 0.9)],
            0.0,
            Vec2::zeros(),
        ),
        rotated(
            &[
                (0.0, 0.0),
                (2.0, 0.0),
                (2.0, 1.0),
                (1.0, 1.0),
                (1.0, 2.0),
                (0.0, 2.0),
            ],
            0.3,
            Vec2::new(5.0, -1.0),
        ),
    ];
    let sigma = [2.0e6, -1.0e6, 0.7e6];
    for vertices in shapes {
        let mut block = Block::new(&vertices, material(), 0).unwrap();
        for e in 0..block.vertex_count() {
            let (a, b) = (block.vertex(e), block.vertex(e + 1));
            let t = b - a;
            let n = Vec2::new(t.y, -t.x) / t.norm();
            let traction = Vec2::new(
                sigma[0] * n.x + sigma[2] * n.y,
                sigma[2] * n.x + sigma[1] * n.y,
            );
            block.edge_tractions.push((e, traction));
        }
        let rigid = [true, true, true, false, false, false];
        block.prescribed = Some(Prescribed {
            mask: rigid,
            motion: std::sync::Arc::new(|_| [0.0; 6]),
        });
        let d = block.material().elastic_matrix();
        let exact = d.try_inverse().unwrap() * nalgebra::Vector3::from(sigma);
        let law = PenaltyCoulomb::new(1e9, 0.5, FrictionIntegration::ReturnMapping).unwrap();
        let settings = DdaSettings {
            gravity: Vec2::zeros(),
            ..DdaSettings::default()
        };
        let mut model =
            DdaModel::with_integrator(vec![block], law, Restarting(Newmark::dda()), settings)
                .unwrap();
        // A long step makes the inertia term of static DDA vanish (c_a = 2/Δt²).
        model.advance(1e3).unwrap(); // converged (a failed step is an error)
        let strain = model.blocks()[0]
            .displacement
            .fixed_rows::<3>(3)
            .into_owned();
        for k in 0..3 {
            assert!(
                (strain[k] - exact[k]).abs() <= 1e-9 * exact.norm(),
                "{strain} vs {exact}"
            );
        }
        let stress = model.blocks()[0].stress;
        for k in 0..3 {
            assert!((stress[k] - sigma[k]).abs() <= 1e-6 * 2e6, "{stress}");
        }
    }
}

/// A block on a fixed plane inclined at β, starting in normal equilibrium:
/// acceleration along the slope after the start-up transient.
fn incline_acceleration(beta_deg: f64, phi_deg: f64) -> (f64, f64) {
    let beta = beta_deg.to_radians();
    let p = 1e9;
    let m = material();
    let g = 9.8;
    let weight = m.density * 0.5 * g;
    let settle = 0.5 * weight * beta.cos() / p;
    let n = Vec2::new(-beta.sin(), beta.cos());
    let mut base = Block::new(
        &rotated(
            &[(-3.0, -0.5), (3.0, -0.5), (3.0, 0.0), (-3.0, 0.0)],
            beta,
            Vec2::zeros(),
        ),
        m,
        0,
    )
    .unwrap();
    base.prescribed = Some(Prescribed::fixed());
    let block = Block::new(
        &rotated(
            &[(-0.5, 0.0), (0.5, 0.0), (0.5, 0.5), (-0.5, 0.5)],
            beta,
            -n * settle,
        ),
        m,
        1,
    )
    .unwrap();
    let law = PenaltyCoulomb::new(
        p,
        phi_deg.to_radians().tan(),
        FrictionIntegration::ReturnMapping,
    )
    .unwrap();
    let settings = DdaSettings {
        gravity: Vec2::new(0.0, -g),
        overlap_tolerance: 1e-4,
        ..DdaSettings::default()
    };
    let mut model = DdaModel::new(vec![base, block], law, settings).unwrap();
    let down = -Vec2::new(beta.cos(), beta.sin());
    let mut samples = Vec::new();
    for step in 1..=300 {
        model.advance(1e-3).unwrap(); // converged (a failed step is an error)
        if step == 100 || step == 300 {
            let b = &model.blocks()[1];
            samples.push((
                Vec2::new(b.velocity[0], b.velocity[1]).dot(&down),
                Vec2::new(b.displacement[0], b.displacement[1]).dot(&down),
            ));
        }
    }
    ((samples[1].0 - samples[0].0) / 0.2, samples[1].1)
}

#[test]
fn block_on_incline_slides_with_g_sin_minus_cos_tan_phi_above_phi() {
    let (beta, phi) = (40.0f64, 30.0f64);
    let (a, _) = incline_acceleration(beta, phi);
    let (b, f) = (beta.to_radians(), phi.to_radians());
    let exact = 9.8 * (b.sin() - b.cos() * f.tan());
    assert!((a - exact).abs() <= 1e-3 * exact, "a = {a}, exact {exact}");
}

#[test]
fn block_on_incline_sticks_below_phi() {
    let (a, s) = incline_acceleration(20.0, 30.0);
    // The elastic shear displacement is m g sin β / (2 p) ≈ 1.8e-6 m.
    let elastic = 2200.0 * 0.5 * 9.8 * 20f64.to_radians().sin() / 2e9;
    assert!(s.abs() <= 3.0 * elastic, "moved {s} m down the slope");
    assert!(a.abs() <= 1e-3, "acceleration {a}");
}

/// Paper 003's input: f = 2 Hz, peak acceleration 1.5 μ g (g = 9.8 m/s²),
/// three cycles.
fn study_shaking(mu: f64) -> Shaking {
    Shaking::with_peak_acceleration(1.5 * mu * 9.8, 2.0, 3.0)
}

/// The event-driven rigid solution against the brute-force integration.
#[test]
fn rigid_sliding_block_solution_matches_a_fine_time_integration() {
    let mu = 36.4f64.to_radians().tan();
    let g = 9.8;
    let shaking = study_shaking(mu);
    let (times, brute) = brute_force_sliding(&shaking, mu, g);
    let exact = rigid_sliding_block(&shaking, mu, g, &times);
    let peak = exact.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(peak > 0.01, "the block slides: peak {peak}");
    let err = exact
        .iter()
        .zip(&brute)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    assert!(err <= 1e-4 * peak, "max difference {err}");
}

/// The compliant sliding block by brute force: steps of 1 µs of
/// `s̈ = −Ω² y + A ω² sin ωt` (velocity first, then position), the elastic
/// part `y` updated by the increment of `s` and returned to `|y| ≤ μ g/Ω²`.
/// Returns the relative displacement every millisecond (times `k · 1e-3`,
/// k = 1, 2, …).
fn brute_force_compliant(shaking: &Shaking, mu: f64, g: f64, omega_c: f64) -> Vec<f64> {
    let (a, w) = (shaking.amplitude, shaking.omega());
    let h = 1e-6;
    let limit = mu * g / (omega_c * omega_c);
    let steps = (shaking.duration / h).round() as usize;
    let (mut s, mut v, mut y) = (0.0f64, 0.0f64, 0.0f64);
    let mut brute = Vec::new();
    for k in 0..steps {
        let t = k as f64 * h;
        v += h * (a * w * w * (w * t).sin() - omega_c * omega_c * y);
        s += h * v;
        y = (y + h * v).clamp(-limit, limit);
        if (k + 1) % 1000 == 0 {
            brute.push(s);
        }
    }
    brute
}

/// The event-driven compliant solution against the brute-force integration
/// (softest contact of the study, 2 Hz), and its rigid limit `Ω → ∞`.
#[test]
fn compliant_sliding_block_matches_a_fine_time_integration() {
    let mu = 36.4f64.to_radians().tan();
    let g: f64 = 9.8;
    let shaking = study_shaking(mu);
    // Ω = √(2 p / m) of a 2 m × 0.25 m block (ρ = 21.56 kN/m³ / g) on its
    // two corner contacts of penalty p = 2e7 N/m.
    let omega_c = (2.0 * 2e7 / (21.56e3 / g * 2.0 * 0.25)).sqrt();
    let brute = brute_force_compliant(&shaking, mu, g, omega_c);
    let times: Vec<f64> = (1..=brute.len()).map(|k| k as f64 * 1e-3).collect();
    let exact = compliant_sliding_block(&shaking, mu, g, omega_c, &times);
    let rigid = rigid_sliding_block(&shaking, mu, g, &times);
    let peak = rigid.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let diff = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
    };
    let err = diff(&exact, &brute);
    assert!(err <= 1e-4 * peak, "max difference {err}");
    // The compliance is visible at this stiffness …
    assert!(diff(&exact, &rigid) > 1e-2 * peak);
    // … and vanishes with it.
    let stiff = compliant_sliding_block(&shaking, mu, g, 1e5, &times);
    let err = diff(&stiff, &rigid);
    assert!(err <= 1e-4 * peak, "max difference {err}");
}

#[test]
fn bad_blocks_and_laws_are_refused_naming_the_block() {
    // A bow tie, three collinear points, a clockwise square.
    let bad: [(&[(f64, f64)], usize); 3] = [
        (&[(0.0, 0.0), (1.0, 1.0), (1.0, 0.0), (0.0, 1.0)], 4),
        (&[(0.0, 0.0), (1.0, 0.0), (2.0, 0.0)], 2),
        (&[(0.0, 1.0), (1.0, 1.0), (1.0, 0.0), (0.0, 0.0)], 1),
    ];
    for (points, index) in bad {
        let vertices: Vec<Point> = points.iter().map(|&(x, y)| Point::new(x, y)).collect();
        match Block::new(&vertices, material(), index) {
            Err(DismechError::InvalidPolygon { block, .. }) => assert_eq!(block, index),
            other => panic!("{other:?}"),
        }
    }
    let incompressible = BlockMaterial {
        poisson_ratio: 0.5,
        ..material()
    };
    assert!(matches!(
        Block::new(&rect(0.0, 0.0, 1.0, 1.0), incompressible, 3),
        Err(DismechError::Implicit(ImplicitError::InvalidBlock {
            block: 3,
            name: "Poisson's ratio",
            ..
        }))
    ));
    for p in [0.0, -1.0, f64::NAN] {
        assert!(matches!(
            PenaltyCoulomb::new(p, 0.5, FrictionIntegration::ReturnMapping),
            Err(DismechError::InvalidParameter { .. })
        ));
    }
    // Block 1 sinks 1 cm into block 0.
    let blocks = vec![
        Block::new(&rect(-1.0, -1.0, 1.0, 0.0), material(), 0).unwrap(),
        Block::new(&rect(-0.5, -0.01, 0.5, 0.5), material(), 1).unwrap(),
    ];
    let law = PenaltyCoulomb::new(1e9, 0.5, FrictionIntegration::ReturnMapping).unwrap();
    match DdaModel::new(blocks, law, DdaSettings::default()) {
        Err(DismechError::Implicit(ImplicitError::BlocksOverlap {
            vertex_block: 1,
            edge_block: 0,
            depth,
            ..
        })) => {
            assert!((depth - 0.01).abs() < 1e-12)
        }
        other => panic!("{other:?}"),
    }
}

/// With no iterations allowed, every step fails: the step is halved down to
/// the bound and the run stops with a status saying what failed.
#[test]
fn a_step_that_cannot_converge_is_reduced_then_reported() {
    let blocks = vec![
        {
            let mut b = Block::new(&rect(-1.0, -1.0, 1.0, 0.0), material(), 0).unwrap();
            b.prescribed = Some(Prescribed::fixed());
            b
        },
        Block::new(&rect(-0.5, 0.0, 0.5, 0.5), material(), 1).unwrap(),
    ];
    let law = PenaltyCoulomb::new(1e9, 0.5, FrictionIntegration::ReturnMapping).unwrap();
    let settings = DdaSettings {
        max_newton: 0,
        max_open_close: 0,
        min_dt_ratio: 1.0 / 8.0,
        ..DdaSettings::default()
    };
    let mut model = DdaModel::new(blocks, law, settings).unwrap();
    match model.advance(1e-3) {
        Err(DismechError::Implicit(ImplicitError::StepFailed {
            dt, time, report, ..
        })) => {
            assert_eq!(report.reductions, 3);
            assert!((dt - 1e-3 / 8.0).abs() < 1e-15);
            assert_eq!(time, 0.0);
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(model.time(), 0.0);
}

/// The sparse analysis is reused while the contact list is unchanged: a
/// resting block needs one symbolic analysis for many steps.
#[test]
fn symbolic_analysis_is_reused_while_the_contacts_are_unchanged() {
    let mut base = Block::new(&rect(-1.0, -1.0, 1.0, 0.0), material(), 0).unwrap();
    base.prescribed = Some(Prescribed::fixed());
    let p = 1e9;
    let settle = 0.5 * 2200.0 * 0.5 * 9.8 / p;
    let block = Block::new(&rect(-0.5, -settle, 0.5, 0.5 - settle), material(), 1).unwrap();
    let law = PenaltyCoulomb::new(p, 0.5, FrictionIntegration::ReturnMapping).unwrap();
    let settings = DdaSettings {
        overlap_tolerance: 1e-4,
        ..DdaSettings::default()
    };
    let mut model = DdaModel::new(vec![base, block], law, settings).unwrap();
    for _ in 0..50 {
        model.advance(1e-3).unwrap();
    }
    assert_eq!(model.symbolic_analyses(), 1);
    // Vertical equilibrium of the block: contact forces = weight + m a_y
    // (the block's own elastic settlement starts a small vibration; as in
    // classic DDA the density is kept, so the mass follows the area).
    let sum: f64 = model.contacts().iter().map(|c| c.force_on_a.y).sum();
    let mass = 2200.0 * model.blocks()[1].area();
    let inertia = mass * model.blocks()[1].acceleration[1];
    assert!(
        (sum - mass * 9.8 - inertia).abs() <= 1e-9 * mass * 9.8,
        "contact forces {sum} against the weight {} and inertia {inertia}",
        mass * 9.8
    );
}

/// A fixed point at the centroid of a block under gravity carries the
/// weight: the block sinks by W / k (static step, rotation and strains
/// unloaded).
#[test]
fn fixed_point_spring_carries_the_weight() {
    let block = Block::new(&rect(0.0, 0.0, 1.0, 0.5), material(), 0).unwrap();
    let centre = block.centroid();
    let law = PenaltyCoulomb::new(1e9, 0.5, FrictionIntegration::ReturnMapping).unwrap();
    let mut model = DdaModel::with_integrator(
        vec![block],
        law,
        Restarting(Newmark::dda()),
        DdaSettings::default(),
    )
    .unwrap();
    let k = 1e8;
    model.add_fixed_point(0, centre, k).unwrap();
    model.advance(1e3).unwrap();
    let weight = 2200.0 * 0.5 * 9.8;
    let v0 = model.blocks()[0].displacement[1];
    assert!((v0 + weight / k).abs() <= 1e-9 * weight / k, "v0 = {v0}");
    assert!(matches!(
        model.add_fixed_point(3, centre, k),
        Err(DismechError::NoSuchBody { index: 3, .. })
    ));
}
