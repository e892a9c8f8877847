//! Implicit DDA (paper 003): the return-mapping law, the contact
//! kinematics' derivatives, a patch test, the block on an inclined plane,
//! the exact sliding-block solution, and bad input.

use dismech::contact::{ContactInput, ContactLaw, PairProperties, Regime};
use dismech::dda::{
    Block, BlockMaterial, DdaModel, DdaSettings, FrictionIntegration, PenaltyCoulomb, PenaltyState,
    PlaneState, Prescribed, StepStatus, VertexEdge,
};
use dismech::error::DismechError;
use dismech::math::{Point, Vec2};
use dismech::reproduce::hashimoto_dda::{rigid_sliding_block, Shaking};
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
    }
}

fn material() -> BlockMaterial {
    BlockMaterial {
        density: 2200.0,
        youngs_modulus: 1e9,
        poisson_ratio: 0.25,
        plane: PlaneState::Stress,
    }
}

fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<Point> {
    vec![
        Point::new(x0, y0),
        Point::new(x1, y0),
        Point::new(x1, y1),
        Point::new(x0, y1),
    ]
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
        let r = law.evaluate(&input(overlap, slip), &state);
        let h = 1e-7 * overlap;
        for (k, (dov, ds)) in [(h, 0.0), (0.0, h)].into_iter().enumerate() {
            let plus = law.evaluate(&input(overlap + dov, slip + ds), &state).force;
            let minus = law.evaluate(&input(overlap - dov, slip - ds), &state).force;
            let fd = (plus - minus) / (2.0 * h);
            for row in 0..2 {
                let exact = r.tangent[(row, k)];
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
        let blocks = vec![lower, upper];
        // The lowest vertex of the upper block against the top edge (edge 2) of the lower one.
        let (vertex, _) = (0..4)
            .map(|v| (v, blocks[1].vertex(v).y))
            .fold((0, f64::INFINITY), |b, x| if x.1 < b.1 { x } else { b });
        let p1 = blocks[1].vertex(vertex);
        let (x2, x3) = (blocks[0].vertex(2), blocks[0].vertex(3));
        let xi = (p1 - x2).dot(&(x3 - x2)) / (x3 - x2).norm_squared();
        let contact = VertexEdge { vertex_block: 1, vertex, edge_block: 0, edge: 2, xi, initial_gap: 0.0 };
        let split = |v: &[f64]| (SVector::<f64, 6>::from_column_slice(&v[6..12]), SVector::<f64, 6>::from_column_slice(&v[0..6]));
        let at = |v: &[f64]| { let (dj, dk) = split(v); contact.kinematics(&blocks, &dj, &dk) };
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
