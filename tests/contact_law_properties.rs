//! Property tests of the spring–dashpot–Coulomb law and of the contact
//! geometry and kinematics that feed it.

use dismech::law::{
    conformance, ContactInput, ContactLaw, Damping, FrictionIntegration, MohrCoulombSpring,
    NormalStiffness, PairProperties, PenaltyCoulomb, PenaltyState, Regime, SpringDashpotCoulomb,
    SpringState, StrengthLaw, TangentLaw,
};
use dismech::math::{rotate, Point, Pose2, Vec2};
use dismech::nalgebra::Vector2;
use dismech::query::manifold::dispatch::contact_2d;
use dismech::query::relative_increment;
use dismech::shape::{AnyShape2, Circle};
use proptest::prelude::*;

fn law(constant: bool, damping: bool, mu: f64) -> SpringDashpotCoulomb {
    let normal = if constant {
        NormalStiffness::Constant(1e7)
    } else {
        NormalStiffness::ContactWidth {
            youngs_modulus: 73.55e6,
            poisson_ratio: 0.3,
            min_width_ratio: 1e-3,
        }
    };
    let damping = if damping {
        Damping::Critical
    } else {
        Damping::None
    };
    SpringDashpotCoulomb::new(normal, 0.25, mu, damping).unwrap()
}

fn pair(width: f64) -> PairProperties {
    PairProperties {
        curvature_radius_a: 0.07,
        curvature_radius_b: 0.05,
        width,
        mass_a: 40.0,
        mass_b: 25.0,
    }
}

fn state(e_n: f64, e_s: f64) -> SpringState<2> {
    let mut s = SpringState::<2>::default();
    s.spring.0 = Vector2::new(e_n, e_s);
    s
}

prop_compose! {
    fn any_input()(overlap in -1e-3f64..2e-3, du_n in -1e-4f64..1e-4, du_s in -1e-3f64..1e-3,
                   width in 1e-4f64..0.05, is_new in any::<bool>()) -> ContactInput<2> {
        ContactInput { overlap, increment: Vector2::new(du_n, du_s), dt: 1e-4, is_new, pair: pair(width), rotation: 0.0 }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn law_never_pulls_and_respects_the_coulomb_cap(
        input in any_input(), e_n in 0.0f64..2e4, e_s in -2e4f64..2e4,
        constant in any::<bool>(), damping in any::<bool>(), mu in 0.0f64..1.5
    ) {
        let law = law(constant, damping, mu);
        let r = law.evaluate(&input, &state(e_n, e_s));
        prop_assert!(r.force[0] >= 0.0, "tension {}", r.force[0]);
        prop_assert!(r.spring_force[0] >= 0.0);
        prop_assert!(r.spring_force[1].abs() <= mu * r.spring_force[0] * (1.0 + 1e-12) + 1e-12,
            "|e_s| = {} > mu e_n = {}", r.spring_force[1].abs(), mu * r.spring_force[0]);
        if r.regime == Regime::Slip {
            prop_assert!((r.force[1].abs() - mu * r.spring_force[0]).abs() <= 1e-9 * (1.0 + r.spring_force[0]));
        }
    }

    #[test]
    fn law_gives_zero_force_and_forgets_history_without_overlap(
        mut input in any_input(), e_n in 0.0f64..2e4, e_s in -2e4f64..2e4
    ) {
        input.overlap = -input.overlap.abs();
        let r = law(false, true, 0.5).evaluate(&input, &state(e_n, e_s));
        prop_assert_eq!(r.regime, Regime::Open);
        prop_assert_eq!(r.force, Vector2::zeros());
        prop_assert_eq!(r.state, SpringState::default());
    }

    /// The analytic tangent matches central differences of the force with
    /// respect to the increment, in stick and in slip (away from the switch).
    #[test]
    fn law_tangent_matches_finite_differences(
        mut input in any_input(), e_n in 100.0f64..2e4, e_s in -2e4f64..2e4,
        constant in any::<bool>(), damping in any::<bool>()
    ) {
        input.overlap = input.overlap.abs() + 1e-5;
        input.is_new = false;
        let law = law(constant, damping, 0.4);
        let s = state(e_n, e_s);
        let (r, tangent) = law.evaluate_with_tangent(&input, &s);
        let h = 1e-7;
        for j in 0..2 {
            let mut plus = input;
            let mut minus = input;
            plus.increment[j] += h;
            minus.increment[j] -= h;
            let (rp, rm) = (law.evaluate(&plus, &s), law.evaluate(&minus, &s));
            // Skip differences that straddle a kink: a regime switch, or the
            // no-pull clamp of the normal dashpot.
            let clamped = |f: f64| f == 0.0;
            if rp.regime != r.regime || rm.regime != r.regime || r.regime == Regime::Open
                || clamped(rp.force[0]) != clamped(rm.force[0])
            {
                continue;
            }
            for i in 0..2 {
                let fd = (rp.force[i] - rm.force[i]) / (2.0 * h);
                // Round-off of the difference quotient: ε |f| / h.
                let roundoff = 1e-15 * (rp.force[i].abs() + rm.force[i].abs()) / h;
                let scale = 1.0 + tangent[(i, j)].abs() + fd.abs();
                prop_assert!((fd - tangent[(i, j)]).abs() <= 1e-6 * scale + roundoff,
                    "d f{} / d u{}: analytic {} vs fd {}", i, j, tangent[(i, j)], fd);
            }
        }
    }

    /// Evaluating the pair as (A, B) or as (B, A) gives equal and opposite
    /// world forces (action = reaction), with the geometry flipped by the
    /// dispatcher and the increments from the same body motions.
    #[test]
    fn contact_force_on_a_equals_minus_force_on_b(
        ra in 0.03f64..0.1, rb in 0.03f64..0.1, angle in 0.0f64..std::f64::consts::TAU,
        depth in 1e-5f64..5e-3, dxa in -1e-4f64..1e-4, dya in -1e-4f64..1e-4, dpa in -1e-3f64..1e-3,
        dxb in -1e-4f64..1e-4, dyb in -1e-4f64..1e-4, dpb in -1e-3f64..1e-3
    ) {
        let (a, b) = (AnyShape2::Circle(Circle::new(ra).unwrap()), AnyShape2::Circle(Circle::new(rb).unwrap()));
        let d = ra + rb - depth;
        let pa = Pose2::new(0.3, -0.2, 0.0);
        let pb = Pose2::new(0.3 + d * angle.cos(), -0.2 + d * angle.sin(), 0.0);
        let (inc_a, inc_b) = ((Vec2::new(dxa, dya), dpa), (Vec2::new(dxb, dyb), dpb));
        let law = law(false, true, 0.5);
        let world = |first: (&AnyShape2, &Pose2, (Vec2, f64)), second: (&AnyShape2, &Pose2, (Vec2, f64))| {
            let g = contact_2d(first.0, first.1, second.0, second.1).unwrap().unwrap();
            let du = relative_increment(&g, &first.1.position, (&first.2 .0, first.2 .1), &second.1.position, (&second.2 .0, second.2 .1));
            let input = ContactInput { overlap: g.overlap, increment: du.into(), dt: 1e-4, is_new: false,
                pair: PairProperties { curvature_radius_a: g.curvature_radius_a, curvature_radius_b: g.curvature_radius_b,
                    width: g.width, mass_a: 1.0, mass_b: 1.0 },
                rotation: 0.0 };
            let r = law.evaluate(&input, &state(50.0, 10.0));
            g.normal * r.force[0] - g.tangent() * r.force[1]
        };
        let on_b = world((&a, &pa, inc_a), (&b, &pb, inc_b));
        let on_a = world((&b, &pb, inc_b), (&a, &pa, inc_a));
        prop_assert!((on_a + on_b).norm() <= 1e-9 * (1.0 + on_b.norm()), "{on_a} vs {on_b}");
    }

    /// Moving and turning the whole pair (positions and increments) leaves
    /// the local increments, the forces and the contact width unchanged.
    #[test]
    fn contact_is_invariant_under_rigid_motion_of_the_pair(
        ra in 0.03f64..0.1, rb in 0.03f64..0.1, angle in 0.0f64..std::f64::consts::TAU,
        depth in 1e-5f64..5e-3, turn in 0.0f64..std::f64::consts::TAU, tx in -5.0f64..5.0, ty in -5.0f64..5.0,
        dxb in -1e-4f64..1e-4, dyb in -1e-4f64..1e-4, dpa in -1e-3f64..1e-3, dpb in -1e-3f64..1e-3
    ) {
        let (a, b) = (AnyShape2::Circle(Circle::new(ra).unwrap()), AnyShape2::Circle(Circle::new(rb).unwrap()));
        let d = ra + rb - depth;
        let law = law(false, true, 0.5);
        let evaluate = |rot: f64, shift: Vec2| {
            let ca = Point::from(shift);
            let cb = ca + rotate(&Vec2::new(d * angle.cos(), d * angle.sin()), rot);
            let (pa, pb) = (Pose2 { position: ca, angle: rot }, Pose2 { position: cb, angle: rot });
            let g = contact_2d(&a, &pa, &b, &pb).unwrap().unwrap();
            let inc_b = rotate(&Vec2::new(dxb, dyb), rot);
            let du = relative_increment(&g, &ca, (&Vec2::zeros(), dpa), &cb, (&inc_b, dpb));
            let input = ContactInput { overlap: g.overlap, increment: du.into(), dt: 1e-4, is_new: false,
                pair: PairProperties { curvature_radius_a: g.curvature_radius_a, curvature_radius_b: g.curvature_radius_b,
                    width: g.width, mass_a: 1.0, mass_b: 1.0 },
                rotation: 0.0 };
            let r = law.evaluate(&input, &state(50.0, 10.0));
            (du, r.force, g.width, g.normal * r.force[0] - g.tangent() * r.force[1])
        };
        let (du0, f0, w0, world0) = evaluate(0.0, Vec2::zeros());
        let (du1, f1, w1, world1) = evaluate(turn, Vec2::new(tx, ty));
        for k in 0..2 {
            prop_assert!((du0[k] - du1[k]).abs() <= 1e-12 + 1e-8 * du0[k].abs(), "du {:?} vs {:?}", du0, du1);
            prop_assert!((f0[k] - f1[k]).abs() <= 1e-8 * (1.0 + f0[k].abs()));
        }
        prop_assert!((w0 - w1).abs() <= 1e-9);
        prop_assert!((rotate(&world0, turn) - world1).norm() <= 1e-8 * (1.0 + world0.norm()));
    }
}

#[test]
fn law_rejects_bad_parameters_naming_them() {
    let bad = [
        SpringDashpotCoulomb::new(NormalStiffness::Constant(1e6), 0.25, -0.1, Damping::None),
        SpringDashpotCoulomb::new(NormalStiffness::Constant(1e6), 0.0, 0.5, Damping::None),
        SpringDashpotCoulomb::new(NormalStiffness::Constant(-1.0), 0.25, 0.5, Damping::None),
        SpringDashpotCoulomb::katsuki(73.55e6, 0.5, 0.25, 0.5),
        SpringDashpotCoulomb::new(
            NormalStiffness::Constant(1e6),
            0.25,
            0.5,
            Damping::PerMass {
                normal: -1.0,
                shear: 0.0,
            },
        ),
        SpringDashpotCoulomb::new(
            NormalStiffness::Constant(1e6),
            0.25,
            0.5,
            Damping::PerMass {
                normal: 1.0,
                shear: f64::NAN,
            },
        ),
    ];
    let names = [
        "friction coefficient mu",
        "stiffness ratio s",
        "normal stiffness k_n",
        "Poisson's ratio",
        "normal damping gamma_n",
        "shear damping gamma_s",
    ];
    for (result, name) in bad.into_iter().zip(names) {
        let message = result.unwrap_err().to_string();
        assert!(message.contains(name), "{message} does not name {name}");
    }
}

/// LAMMPS' `gran/hooke` dashpots: `f_n = k_n δ + m_eff γ_n v_n` and, in
/// stick, `f_s = k_s Δs + m_eff γ_s v_s`, with `m_eff = m_a m_b/(m_a + m_b)`
/// between particles and `m_a` against a wall; written out by hand.
#[test]
fn per_mass_dashpots_give_the_effective_mass_times_gamma() {
    let (k_n, ratio, gamma_n, gamma_s, dt) = (1.6e7, 2.0 / 7.0, 2000.0, 1000.0, 1e-4);
    let law = SpringDashpotCoulomb::new(
        NormalStiffness::Constant(k_n),
        ratio,
        0.577,
        Damping::PerMass {
            normal: gamma_n,
            shear: gamma_s,
        },
    )
    .unwrap();
    let (previous_overlap, du_n, du_s) = (2e-5, 1e-6, 2e-7);
    for (mass_b, m_eff) in [(25.0, 40.0 * 25.0 / 65.0), (f64::INFINITY, 40.0)] {
        let input = ContactInput {
            overlap: previous_overlap + du_n,
            increment: Vector2::new(du_n, du_s),
            dt,
            is_new: false,
            pair: PairProperties {
                mass_b,
                ..pair(0.01)
            },
            rotation: 0.0,
        };
        let r = law.evaluate(&input, &state(k_n * previous_overlap, 0.0));
        assert_eq!(r.regime, Regime::Stick);
        let normal = k_n * (previous_overlap + du_n) + m_eff * gamma_n * du_n / dt;
        let shear = ratio * k_n * du_s + m_eff * gamma_s * du_s / dt;
        approx::assert_relative_eq!(r.force[0], normal, max_relative = 1e-12);
        approx::assert_relative_eq!(r.force[1], shear, max_relative = 1e-12);
        // Opening fast: the dashpot would pull, the law clamps at zero.
        let opening = ContactInput {
            overlap: previous_overlap - 1e-5,
            increment: Vector2::new(-1e-5, 0.0),
            ..input
        };
        assert!(k_n * (previous_overlap - 1e-5) - m_eff * gamma_n * 1e-5 / dt < 0.0);
        assert_eq!(
            law.evaluate(&opening, &state(k_n * previous_overlap, 0.0))
                .force[0],
            0.0
        );
    }
}

/// Eq. (19) with r1 = r2 = r and B = r gives πE / (2(1−ν²)(2/3 + 2 ln 4)).
#[test]
fn eq19_stiffness_matches_the_closed_form() {
    let law = law(false, false, 0.5);
    let p = PairProperties {
        curvature_radius_a: 0.07,
        curvature_radius_b: 0.07,
        width: 0.07,
        mass_a: 1.0,
        mass_b: 1.0,
    };
    let expected =
        std::f64::consts::PI * 73.55e6 / (2.0 * (1.0 - 0.09) * (2.0 / 3.0 + 2.0 * 4f64.ln()));
    approx::assert_relative_eq!(law.normal_stiffness(&p), expected, max_relative = 1e-12);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    /// In 3D (normal and two tangents, as the slip springs of a column) the
    /// law keeps ‖e_s‖ ≤ μ e_n and its tangent, including the radial-return
    /// part `μ e_n k_s (I − d dᵀ)/‖e_trial‖`, matches finite differences.
    #[test]
    fn law_in_3d_respects_the_cap_and_its_tangent_matches_finite_differences(
        overlap in 1e-5f64..2e-3, du in prop::array::uniform3(-1e-3f64..1e-3),
        e_n in 100.0f64..2e4, e_s in prop::array::uniform2(-2e4f64..2e4), damping in any::<bool>()
    ) {
        let law = law(true, damping, 0.4);
        let input = dismech::law::ContactInput::<3> {
            overlap, increment: nalgebra::Vector3::new(du[0], du[1], du[2]), dt: 1e-4, is_new: false, pair: pair(0.01),
            rotation: 0.0,
        };
        let mut s = SpringState::<3>::default();
        s.spring.0 = nalgebra::Vector3::new(e_n, e_s[0], e_s[1]);
        let (r, tangent) = law.evaluate_with_tangent(&input, &s);
        let shear = (r.spring_force[1].powi(2) + r.spring_force[2].powi(2)).sqrt();
        prop_assert!(shear <= 0.4 * r.spring_force[0] * (1.0 + 1e-12) + 1e-12);
        let h = 1e-7;
        for j in 0..3 {
            let (mut plus, mut minus) = (input, input);
            plus.increment[j] += h;
            minus.increment[j] -= h;
            let (rp, rm) = (law.evaluate(&plus, &s), law.evaluate(&minus, &s));
            let clamped = |f: f64| f == 0.0;
            if rp.regime != r.regime || rm.regime != r.regime || r.regime == Regime::Open
                || clamped(rp.force[0]) != clamped(rm.force[0]) {
                continue;
            }
            for i in 0..3 {
                let fd = (rp.force[i] - rm.force[i]) / (2.0 * h);
                let roundoff = 1e-15 * (rp.force[i].abs() + rm.force[i].abs()) / h;
                let scale = 1.0 + tangent[(i, j)].abs() + fd.abs();
                prop_assert!((fd - tangent[(i, j)]).abs() <= 1e-5 * scale + roundoff,
                    "3D d f{} / d u{} in {:?}: analytic {} vs fd {}", i, j, r.regime, tangent[(i, j)], fd);
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// Every law of the crate passes the conformance suite (no tension,
    /// open without overlap, within its strength, tangent = central
    /// differences, pure): the spring–dashpot law in 2D and 3D, the DDA
    /// penalty law with return mapping, and the HPM slip spring.
    #[test]
    fn every_law_passes_the_conformance_suite(
        overlap in 1e-6f64..2e-3, du in prop::array::uniform3(-1e-3f64..1e-3),
        e_n in 0.0f64..2e4, e_s in prop::array::uniform2(-2e4f64..2e4), mu in 0.0f64..1.5,
        constant in any::<bool>(), damping in any::<bool>(), is_new in any::<bool>()
    ) {
        let sd = law(constant, damping, mu);
        let input2 = ContactInput { overlap, increment: Vector2::new(du[0] * 0.1, du[1]), dt: 1e-4, is_new, pair: pair(0.01), rotation: 0.0 };
        let violations = conformance::check_all(&sd, &input2, &state(e_n, e_s[0]));
        prop_assert!(violations.is_empty(), "spring-dashpot 2D: {:?}", violations);
        prop_assert!(conformance::open_without_overlap(&sd, &input2, &state(e_n, e_s[0])).is_ok());

        let input3 = ContactInput::<3> { overlap, increment: nalgebra::Vector3::new(du[0] * 0.1, du[1], du[2]), dt: 1e-4, is_new, pair: pair(0.01), rotation: 0.0 };
        let mut s3 = SpringState::<3>::default();
        s3.spring.0 = nalgebra::Vector3::new(e_n, e_s[0], e_s[1]);
        let violations = conformance::check_all(&sd, &input3, &s3);
        prop_assert!(violations.is_empty(), "spring-dashpot 3D: {:?}", violations);

        let penalty = PenaltyCoulomb::new(1e7, mu, FrictionIntegration::ReturnMapping).unwrap();
        let ps = PenaltyState { normal: e_n, shear: e_s[0], regime: Some(Regime::Stick) };
        let violations = conformance::check_all(&penalty, &input2, &ps);
        prop_assert!(violations.is_empty(), "penalty Coulomb: {:?}", violations);
        prop_assert!(conformance::open_without_overlap(&penalty, &input2, &ps).is_ok());

        // The slip spring follows its own displacement history: its normal
        // spring before the step is k_n (overlap − Δu_n).
        let mc = MohrCoulombSpring::new(1e7, 4e6, 2e3, mu).unwrap();
        let mut mc_state = s3;
        mc_state.spring.0[0] = 1e7 * (overlap - input3.increment[0]);
        let violations = conformance::check_all(&mc, &input3, &mc_state);
        prop_assert!(violations.is_empty(), "Mohr-Coulomb spring: {:?}", violations);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// The bonded penalty law (cohesive, bilateral) passes the conformance
    /// checks that apply to a contact that never opens (within its
    /// Mohr–Coulomb strength, tangent = central differences, pure), in
    /// compression and in tension; it carries tension and never opens.
    #[test]
    fn bonded_penalty_law_passes_the_conformance_suite_and_carries_tension(
        overlap in -2e-3f64..2e-3, du in prop::array::uniform2(-1e-3f64..1e-3),
        shear in -2e4f64..2e4, cohesion in 0.0f64..2e4, mu in prop::sample::select(vec![0.0, 0.3, 1.2])
    ) {
        let law = PenaltyCoulomb::bonded_with_friction(1e7, cohesion, mu).unwrap();
        prop_assert!(!law.may_open());
        let input = ContactInput { overlap, increment: Vector2::new(du[0] * 0.1, du[1]), dt: 1e-4, is_new: false, pair: pair(0.01), rotation: 0.0 };
        let state = PenaltyState { normal: 1e7 * overlap, shear, regime: Some(Regime::Stick) };
        let violations = conformance::check_all(&law, &input, &state);
        prop_assert!(violations.is_empty(), "bonded penalty: {:?}", violations);
        let r = law.evaluate(&input, &state);
        prop_assert!(r.regime != Regime::Open);
        let apex = if mu > 0.0 { -cohesion / mu } else { f64::NEG_INFINITY };
        let expected = (1e7 * overlap).max(apex);
        prop_assert!((r.force[0] - expected).abs() <= 1e-14 * expected.abs(), "t_n {} vs {}", r.force[0], expected);
        if mu == 0.0 {
            prop_assert!(r.force[1].abs() <= cohesion * (1.0 + 1e-12));
        }
    }
}

/// The conventional DDA friction (paper 003 Fig. 1) lets the shear exceed
/// the Coulomb limit within a step: the conformance check of the strength
/// catches it, as it should.
#[test]
fn conformance_catches_the_conventional_overshoot() {
    let law = PenaltyCoulomb::new(1e7, 0.5, FrictionIntegration::Conventional).unwrap();
    let input = ContactInput {
        overlap: 1e-4,
        increment: Vector2::new(0.0, 1e-3),
        dt: 1e-3,
        is_new: false,
        pair: PairProperties::rigid(),
        rotation: 0.0,
    };
    let state = PenaltyState {
        normal: 1e3,
        shear: 0.0,
        regime: Some(Regime::Stick),
    };
    let violation = conformance::within_strength(&law, &input, &state).unwrap_err();
    assert_eq!(violation.check, "within_strength");
}

/// The check that a law does without the contact's width and radii of
/// curvature fails a law that says so while its stiffness (eq. 19 of
/// paper 000) reads them, and passes the same law when it says that it
/// reads them.
#[test]
fn the_contact_shape_check_catches_a_law_that_reads_it_unannounced() {
    struct Unannounced(SpringDashpotCoulomb);
    impl ContactLaw<2> for Unannounced {
        type State = SpringState<2>;
        fn evaluate(
            &self,
            input: &ContactInput<2>,
            state: &SpringState<2>,
        ) -> dismech::law::ContactResponse<2, SpringState<2>> {
            self.0.evaluate(input, state)
        }
        fn uses_contact_shape(&self) -> bool {
            false
        }
    }
    let width_law = law(false, true, 0.5);
    assert!(ContactLaw::<2>::uses_contact_shape(&width_law));
    let input = ContactInput {
        overlap: 1e-4,
        increment: Vector2::new(1e-5, 2e-5),
        dt: 1e-4,
        is_new: false,
        pair: pair(0.01),
        rotation: 0.0,
    };
    let history = state(1e3, 2e2);
    assert!(conformance::contact_shape_unused(&width_law, &input, &history).is_ok());
    let violation =
        conformance::contact_shape_unused(&Unannounced(width_law), &input, &history).unwrap_err();
    assert_eq!(violation.check, "contact_shape_unused");
    // A constant stiffness does without them, and says so.
    let constant = law(true, true, 0.5);
    assert!(!ContactLaw::<2>::uses_contact_shape(&constant));
    assert!(conformance::contact_shape_unused(&constant, &input, &history).is_ok());
}

/// A Hertzian normal force with no history, no tangent and no linear
/// strength: a law for the explicit driver alone.
struct Hertz {
    stiffness: f64,
    pulls_when_apart: bool,
}

impl ContactLaw<2> for Hertz {
    type State = ();
    fn evaluate(&self, input: &ContactInput<2>, _: &()) -> dismech::law::ContactResponse<2, ()> {
        let normal = if input.overlap > 0.0 {
            self.stiffness * input.overlap.powf(1.5)
        } else if self.pulls_when_apart {
            -self.stiffness * 1e-9
        } else {
            0.0
        };
        dismech::law::ContactResponse {
            force: Vector2::new(normal, 0.0),
            spring_force: Vector2::new(normal, 0.0),
            state: (),
            regime: if input.overlap > 0.0 || self.pulls_when_apart {
                Regime::Stick
            } else {
                Regime::Open
            },
        }
    }
    fn uses_contact_shape(&self) -> bool {
        false
    }
}

/// A force-only law runs the checks of what it declares: a Hertzian force
/// passes them; the same law pulling at a distance fails
/// `open_without_overlap`, which the force checks include.
#[test]
fn a_force_only_law_runs_the_force_checks() {
    let input = ContactInput {
        overlap: 1e-4,
        increment: Vector2::new(1e-5, 2e-5),
        dt: 1e-4,
        is_new: false,
        pair: pair(0.01),
        rotation: 0.0,
    };
    let hertz = Hertz {
        stiffness: 1e10,
        pulls_when_apart: false,
    };
    assert!(conformance::check_force_law(&hertz, &input, &()).is_empty());
    let sticky = Hertz {
        stiffness: 1e10,
        pulls_when_apart: true,
    };
    let found = conformance::check_force_law(&sticky, &input, &());
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].check, "open_without_overlap");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    /// Every law of the crate passes the conformance suite over histories
    /// it made itself, along random loading paths of up to 12 steps (the
    /// strategies a user's law runs with the `proptest` feature): the
    /// spring–dashpot law in 2D and 3D, the DDA penalty law, the bonded
    /// penalty law and the HPM slip spring.
    #[test]
    fn every_law_passes_the_conformance_suite_along_loading_paths(
        (sd_state, sd_input) in conformance::strategies::history_then_input::<_, 2>(
            law(false, true, 0.6), conformance::strategies::Scales::new(2e-3, 1e-3, pair(0.01)), 1..12),
        (sd3_state, sd3_input) in conformance::strategies::history_then_input::<_, 3>(
            law(true, true, 0.6), conformance::strategies::Scales::new(2e-3, 1e-3, pair(0.01)), 1..12),
        (p_state, p_input) in conformance::strategies::history_then_input::<_, 2>(
            PenaltyCoulomb::new(1e7, 0.6, FrictionIntegration::ReturnMapping).unwrap(),
            conformance::strategies::Scales::new(2e-3, 1e-3, PairProperties::rigid()), 1..12),
        (b_state, b_input) in conformance::strategies::history_then_input::<_, 2>(
            PenaltyCoulomb::bonded_with_friction(1e7, 5e3, 0.6).unwrap(),
            conformance::strategies::Scales::new(2e-3, 1e-3, PairProperties::rigid()), 1..12),
        (mc_state, mc_input) in conformance::strategies::history_then_input::<_, 3>(
            MohrCoulombSpring::new(1e7, 4e6, 2e3, 0.6).unwrap(),
            conformance::strategies::Scales::new(2e-3, 1e-3, PairProperties::rigid()), 1..12),
    ) {
        let v = conformance::check_all(&law(false, true, 0.6), &sd_input, &sd_state);
        prop_assert!(v.is_empty(), "spring-dashpot 2D: {:?}", v);
        let v = conformance::check_all(&law(true, true, 0.6), &sd3_input, &sd3_state);
        prop_assert!(v.is_empty(), "spring-dashpot 3D: {:?}", v);
        let penalty = PenaltyCoulomb::new(1e7, 0.6, FrictionIntegration::ReturnMapping).unwrap();
        let v = conformance::check_all(&penalty, &p_input, &p_state);
        prop_assert!(v.is_empty(), "penalty Coulomb: {:?}", v);
        let bonded = PenaltyCoulomb::bonded_with_friction(1e7, 5e3, 0.6).unwrap();
        let v = conformance::check_all(&bonded, &b_input, &b_state);
        prop_assert!(v.is_empty(), "bonded penalty: {:?}", v);
        let mc = MohrCoulombSpring::new(1e7, 4e6, 2e3, 0.6).unwrap();
        let v = conformance::check_all(&mc, &mc_input, &mc_state);
        prop_assert!(v.is_empty(), "Mohr-Coulomb spring: {:?}", v);
    }
}

/// The loading path's overlaps follow its normal increments, and only its
/// first input is new.
#[test]
fn a_loading_path_moves_its_overlap_by_its_normal_increments() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let strategy = conformance::strategies::loading_path::<2>(
        conformance::strategies::Scales::new(1e-3, 1e-4, PairProperties::rigid()),
        2..20,
    );
    let mut runner = TestRunner::deterministic();
    for _ in 0..100 {
        let path = strategy.new_tree(&mut runner).unwrap().current();
        assert!((2..20).contains(&path.len()));
        assert!(path[0].is_new && path[1..].iter().all(|i| !i.is_new));
        for w in path.windows(2) {
            assert_eq!(w[1].overlap, w[0].overlap + w[1].increment[0]);
        }
        assert!(path
            .iter()
            .all(|i| i.increment.iter().all(|u| u.abs() <= 1e-4)));
    }
}

/// The strategies find what is wrong: the conventional DDA friction
/// overshoots the Coulomb limit within a step, and random loading paths
/// catch it (a failing case, shrunk).
#[test]
fn loading_paths_catch_the_conventional_overshoot() {
    use proptest::test_runner::{Config, TestRunner};
    let law = PenaltyCoulomb::new(1e7, 0.6, FrictionIntegration::Conventional).unwrap();
    let strategy = conformance::strategies::history_then_input::<_, 2>(
        law,
        conformance::strategies::Scales::new(2e-3, 1e-3, PairProperties::rigid()),
        1..12,
    );
    let mut runner = TestRunner::new(Config {
        cases: 500,
        failure_persistence: None,
        ..Config::default()
    });
    let outcome = runner.run(&strategy, |(state, input)| {
        let v = conformance::check_strength_law(&law, &input, &state);
        prop_assert!(v.is_empty(), "{:?}", v);
        Ok(())
    });
    let failure = outcome
        .expect_err("the overshoot was not found")
        .to_string();
    assert!(failure.contains("within_strength"), "{failure}");
}
