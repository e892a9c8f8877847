//! Limit analysis refuses what it cannot certify or what has no meaning:
//! a loose LP solution, a negative strength, a lattice whose limit load is
//! zero, and a body its dead load cannot be held in.

use dismech::error::DismechError;
use dismech::law::{RigidPlastic, Strength, StrengthLaw};
use dismech::limit::lattice::Lattice;
use dismech::limit::LimitError;
use dismech::limit::{
    analyse, analyse_static, mechanism_uniqueness, LimitModel, LimitStatus, Partner,
};
use dismech::lp::LinearProgramSolver;
use dismech::math::{Point, Vec2};

/// Table 1's rolling U-model (8, 8, 2): 14.5902… at the default tolerance.
const EXACT_8_8_2: f64 = 14.590_220_367;

fn loose(tolerance: f64) -> LinearProgramSolver {
    LinearProgramSolver {
        tolerance,
        ..Default::default()
    }
}

/// At a solver tolerance of 0.1 or 1e-3 Clarabel says `Solved` with
/// primal and dual agreeing at 11.14 and 14.53, below the exact 14.5902:
/// the solution fails the LP's own feasibility conditions and is refused,
/// by both the kinematic and the static analysis.
#[test]
fn loose_solver_tolerance_is_not_certified() {
    let model = Lattice::u_model(8, 8, 2, true).build().unwrap();
    for tolerance in [0.1, 1e-3, 1e-6] {
        for (name, outcome) in [
            ("kinematic", analyse(&model, &mut loose(tolerance))),
            ("static", analyse_static(&model, &mut loose(tolerance))),
        ] {
            match outcome {
                Err(DismechError::Limit(LimitError::UncertifiedOptimum {
                    primal_residual,
                    dual_residual,
                    gap,
                    tolerance: certificate,
                    ..
                })) => {
                    assert_eq!(certificate, dismech::limit::CERTIFICATE_TOLERANCE);
                    assert!(
                        primal_residual.max(dual_residual).max(gap) > certificate,
                        "{name} at {tolerance}"
                    );
                }
                other => panic!("{name} at solver tolerance {tolerance}: {other:?}"),
            }
        }
    }
    let message = analyse(&model, &mut loose(1e-3)).unwrap_err().to_string();
    assert!(
        message.contains("LinearProgramSolver.tolerance"),
        "{message}"
    );
}

/// The uniqueness test solves two more LPs over the optimal face; at a
/// loose solver tolerance their optima fail the optimality conditions as
/// the analysis' own do, and are refused rather than read as the extremes
/// of the face (a wrong spread, a vertex that is no mechanism). At the
/// default tolerance the same test is certified.
#[test]
fn uniqueness_test_at_a_loose_solver_tolerance_is_not_certified() {
    let model = Lattice::u_model(8, 8, 2, true).build().unwrap();
    let r = analyse(&model, &mut LinearProgramSolver::default()).unwrap();
    assert_eq!(r.status, LimitStatus::Collapse);
    for tolerance in [0.1, 1e-3] {
        match mechanism_uniqueness(&model, &mut loose(tolerance), &r) {
            Err(DismechError::Limit(LimitError::UncertifiedOptimum {
                primal_residual,
                dual_residual,
                gap,
                tolerance: certificate,
                ..
            })) => {
                assert_eq!(certificate, dismech::limit::CERTIFICATE_TOLERANCE);
                assert!(
                    primal_residual.max(dual_residual).max(gap) > certificate,
                    "at {tolerance}"
                );
            }
            other => panic!("uniqueness at solver tolerance {tolerance}: {other:?}"),
        }
    }
    let u = mechanism_uniqueness(&model, &mut LinearProgramSolver::default(), &r).unwrap();
    assert!(u.spread.is_finite(), "{}", u.spread);
}

/// A tolerance the certificate accepts gives the exact load, from above
/// by the kinematic LP and from below by the static one.
#[test]
fn tight_solver_tolerance_is_certified_at_the_exact_load() {
    let model = Lattice::u_model(8, 8, 2, true).build().unwrap();
    for tolerance in [1e-9, 1e-8] {
        let r = analyse(&model, &mut loose(tolerance)).unwrap();
        assert_eq!(r.status, LimitStatus::Collapse);
        assert!((r.load.unwrap() - EXACT_8_8_2).abs() < 1e-6 * EXACT_8_8_2);
        let s = analyse_static(&model, &mut loose(tolerance)).unwrap();
        assert!((s.load.unwrap() - EXACT_8_8_2).abs() < 1e-6 * EXACT_8_8_2);
    }
}

/// A user's law with the strength it returns.
struct UserLaw(Strength);

impl StrengthLaw for UserLaw {
    fn strength(&self) -> Strength {
        self.0
    }
}

/// A friction −0.5 made a block pushed on a floor collapse at 8e-10; a
/// negative or non-finite strength is refused when the contact is
/// declared, naming the value.
#[test]
fn negative_or_non_finite_strength_is_refused() {
    for (cohesion, friction, bad) in [
        (1.0, -0.5, -0.5),
        (0.0, -0.5, -0.5),
        (-1.0, 0.3, -1.0),
        (f64::NAN, 0.3, f64::NAN),
        (1.0, f64::INFINITY, f64::INFINITY),
    ] {
        let mut m = LimitModel::new(1e-9).unwrap();
        let e = m.add_body(Point::new(0.0, 1.0), 1.0, false).unwrap();
        let floor = m
            .add_support("floor", Point::origin(), Vec2::new(0.0, 1.0), Vec2::zeros())
            .unwrap();
        let law = UserLaw(Strength { cohesion, friction });
        for outcome in [
            m.add_contact(e, Partner::Support(floor), UserLaw(law.0)),
            m.add_contact_at(
                e,
                Partner::Support(floor),
                law,
                Point::origin(),
                Vec2::new(0.0, -1.0),
            ),
        ] {
            match outcome {
                Err(DismechError::InvalidParameter { value, .. }) => {
                    assert!(value.to_bits() == bad.to_bits() || (value.is_nan() && bad.is_nan()))
                }
                other => panic!("c = {cohesion}, μ = {friction}: {other:?}"),
            }
        }
        assert!(m.contacts().is_empty());
    }
}

/// `lattice-limit-load --model l --m 2 --n 1` reported a collapse at
/// P = −9.8e-25: the one element of the loaded column rolls down along its
/// neighbour with nothing dissipated. The rolling L-model with n = 1 is
/// refused, naming n; without rolling it slides at √2 C_p.
#[test]
fn rolling_l_model_of_one_element_per_column_is_refused() {
    for m in [2, 4] {
        match Lattice::l_model(m, 1, true).build() {
            Err(DismechError::InvalidParameter { name, value, .. }) => {
                assert!(name.starts_with("n "), "{name}");
                assert_eq!(value, 1.0);
            }
            other => panic!("m = {m}: {other:?}"),
        }
    }
    let sliding = Lattice::l_model(2, 1, false).build().unwrap();
    let r = analyse(&sliding, &mut LinearProgramSolver::default()).unwrap();
    assert_eq!(r.status, LimitStatus::Collapse);
    assert!((r.load.unwrap() - std::f64::consts::SQRT_2).abs() < 1e-7);
}

/// A weightless element between a smooth plate and the end of a
/// cohesive neighbour that lets it roll away: the plate moves it with
/// nothing dissipated. The load is zero, reported as `ZeroLoad` with
/// `Some(0.0)`, never as a collapse at a round-off value of either sign.
#[test]
fn zero_limit_load_is_not_reported_as_a_collapse() {
    let r = 1.0;
    let s = 2.0 * r * std::f64::consts::FRAC_PI_4.cos();
    let mut m = LimitModel::new(1e-9).unwrap();
    let a = m.add_body(Point::origin(), r, true).unwrap();
    let b = m.add_body(Point::new(-s, s), r, true).unwrap();
    let cohesive = RigidPlastic::cohesive(1.0).unwrap();
    m.add_contact(a, Partner::Body(b), cohesive).unwrap();
    let wall = m
        .add_support(
            "wall",
            Point::new(-s - r, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::zeros(),
        )
        .unwrap();
    m.add_contact(b, Partner::Support(wall), cohesive).unwrap();
    let plate = m
        .add_support(
            "plate",
            Point::new(r, 0.0),
            Vec2::new(-1.0, 0.0),
            Vec2::new(-1.0, 0.0),
        )
        .unwrap();
    m.add_contact(
        a,
        Partner::Support(plate),
        RigidPlastic::cohesive(0.0).unwrap(),
    )
    .unwrap();
    for result in [
        analyse(&m, &mut LinearProgramSolver::default()).unwrap(),
        analyse_static(&m, &mut LinearProgramSolver::default()).unwrap(),
    ] {
        assert_eq!(result.status, LimitStatus::ZeroLoad);
        assert_eq!(result.load, Some(0.0));
        assert!(result.kinematic_load.unwrap().abs() < 1e-8);
    }
}

/// One element of weight 10 touching nothing, with a live load.
fn free_weighted_body(live: Vec2) -> LimitModel {
    let mut m = LimitModel::new(1e-9).unwrap();
    let e = m.add_body(Point::new(0.0, 1.0), 1.0, true).unwrap();
    m.set_load(e, Vec2::new(0.0, -10.0)).unwrap();
    m.set_live_load(e, live, Point::new(0.0, 1.0)).unwrap();
    m
}

/// A weighted body with no contacts has no equilibrium under its weight:
/// whatever else the model holds, both analyses say it collapses under its
/// own loads (`Unbounded`). Here it sits beside an element held between a
/// wall and the plate (locked: the kinematic LP is infeasible), where
/// `analyse` said Locked and `analyse_static` Unbounded.
#[test]
fn weighted_body_without_contacts_is_unbounded_in_both_analyses() {
    let mut m = LimitModel::new(1e-9).unwrap();
    let held = m.add_body(Point::new(0.0, 1.0), 1.0, false).unwrap();
    let free = m.add_body(Point::new(10.0, 10.0), 1.0, false).unwrap();
    let smooth = RigidPlastic::cohesive(0.0).unwrap();
    let wall = m
        .add_support(
            "wall",
            Point::new(-1.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::zeros(),
        )
        .unwrap();
    let plate = m
        .add_support(
            "plate",
            Point::new(1.0, 0.0),
            Vec2::new(-1.0, 0.0),
            Vec2::new(-1.0, 0.0),
        )
        .unwrap();
    m.add_contact(held, Partner::Support(wall), smooth).unwrap();
    m.add_contact(held, Partner::Support(plate), smooth)
        .unwrap();
    let statuses = |m: &LimitModel| {
        [
            analyse(m, &mut LinearProgramSolver::default()).unwrap(),
            analyse_static(m, &mut LinearProgramSolver::default()).unwrap(),
        ]
        .map(|r| (r.status, r.load))
    };
    // Weightless, the free body does not matter: locked.
    assert_eq!(statuses(&m), [(LimitStatus::Locked, None); 2]);
    m.set_load(free, Vec2::new(0.0, -10.0)).unwrap();
    assert_eq!(statuses(&m), [(LimitStatus::Unbounded, None); 2]);

    // With a live load alone: sideways or downwards it cannot hold the
    // weight (a downward live load's multiplier would be −10); upwards it
    // lifts the body at λ = 10.
    for live in [Vec2::new(1.0, 0.0), Vec2::new(0.0, -1.0)] {
        assert_eq!(
            statuses(&free_weighted_body(live)),
            [(LimitStatus::Unbounded, None); 2],
            "live load {live:?}"
        );
    }
    for (status, load) in statuses(&free_weighted_body(Vec2::new(0.0, 1.0))) {
        assert_eq!(status, LimitStatus::Collapse);
        assert!((load.unwrap() - 10.0).abs() < 1e-8);
    }
}

/// A contact of an element with itself was refused as "no body with index
/// 0 (the scene has 1)"; it is refused as what it is, by both ways of
/// declaring a contact.
#[test]
fn contact_of_an_element_with_itself_is_refused_as_such() {
    let mut m = LimitModel::new(1e-9).unwrap();
    let e = m.add_body(Point::new(0.0, 1.0), 1.0, false).unwrap();
    let law = UserLaw(Strength {
        cohesion: 1.0,
        friction: 0.5,
    });
    for outcome in [
        m.add_contact(e, Partner::Body(e), UserLaw(law.0)),
        m.add_contact_at(
            e,
            Partner::Body(e),
            law,
            Point::new(0.0, 0.0),
            Vec2::new(0.0, -1.0),
        ),
    ] {
        let err = outcome.unwrap_err();
        assert_eq!(
            err,
            DismechError::Limit(LimitError::SelfContact { body: e })
        );
        assert!(err.to_string().contains("with itself"), "{err}");
    }
    assert!(m.contacts().is_empty());
}
