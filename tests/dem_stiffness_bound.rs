//! A law whose stiffness grows with the overlap (Hertz, `k_n = 1.5 K √δ`)
//! bounds it at the overlap the explicit driver assumes
//! (`DemSettings::stability_overlap`), and a run whose overlaps outgrow
//! that at a time step the law no longer allows is stopped, naming the
//! overlap.

use dismech::dem::DemSimulation;
use dismech::error::DismechError;
use dismech::explicit::ExplicitError;
use dismech::explicit::{
    critical_time_step_at, DemSettings, GoverningMode, OverlapReached, RestCriterion, RunStatus,
};
use dismech::integrate::ExplicitEuler;
use dismech::law::{
    BoundedStiffness, ContactInput, ContactLaw, ContactResponse, Damping, NormalStiffness,
    PairProperties, Regime, SpringDashpotCoulomb, StiffnessBound,
};
use dismech::math::{Point, Vec2};
use dismech::nalgebra::Vector2;
use dismech::scene::{Frame, Scene};

/// Frictionless Hertzian contact: `t_n = K δ^{3/2}`.
#[derive(Debug, Clone, Copy, serde::Serialize)]
struct Hertz {
    coefficient: f64,
}

impl ContactLaw<2> for Hertz {
    type State = ();

    fn evaluate(&self, input: &ContactInput<2>, _: &()) -> ContactResponse<2, ()> {
        let delta = input.overlap.max(0.0);
        let force = Vector2::new(self.coefficient * delta.powf(1.5), 0.0);
        ContactResponse {
            force,
            spring_force: force,
            regime: if delta > 0.0 {
                Regime::Stick
            } else {
                Regime::Open
            },
            state: (),
        }
    }

    fn uses_contact_shape(&self) -> bool {
        false
    }
}

impl BoundedStiffness<2> for Hertz {
    fn stiffness_bound(&self, _pair: &PairProperties, overlap: f64) -> StiffnessBound {
        StiffnessBound {
            normal: 1.5 * self.coefficient * overlap.max(0.0).sqrt(),
            shear: 0.0,
            normal_damping: 0.0,
            shear_damping: 0.0,
            rolling: 0.0,
        }
    }
}

const RADIUS: f64 = 0.05;
/// Brings a disc dropped 5 cm to rest on the floor at about 1 % of its
/// radius of overlap: `m g h = (2/5) K δ^{5/2}`.
const HERTZ: f64 = 4.6e9;

/// A disc 5 cm above the floor of a box.
fn drop() -> Scene {
    let mut scene = Scene::new(Frame::open_box(1.0, 1.0).unwrap(), Vec2::new(0.0, -9.81)).unwrap();
    scene
        .add_circle(Point::new(0.5, RADIUS + 0.05), RADIUS, 2650.0)
        .unwrap();
    scene
}

#[test]
fn the_stable_step_of_a_hertzian_law_falls_as_the_overlap_to_the_minus_one_quarter() {
    let law = Hertz { coefficient: HERTZ };
    let scene = drop();
    let at = |ratio| critical_time_step_at(&scene, &law, ratio).dt;
    // Undamped, dt = 2/ω and ω² ∝ k ∝ √δ.
    let ratio = at(0.05) / at(0.0125);
    assert!((ratio - 0.25f64.powf(0.25)).abs() < 1e-12, "{ratio}");
    // The default setting is the one the driver checks a time step at.
    let limit = at(DemSettings::default().stability_overlap);
    let settings = |dt| DemSettings {
        dt,
        ..DemSettings::default()
    };
    assert!(DemSimulation::new(drop(), law, ExplicitEuler, settings(0.99 * limit)).is_ok());
    match DemSimulation::new(drop(), law, ExplicitEuler, settings(1.01 * limit)) {
        Err(DismechError::Explicit(ExplicitError::UnstableTimeStep {
            limit: l,
            governing,
            overlap,
            ..
        })) => {
            assert_eq!(l, limit);
            // Checked before the run: the mode of the estimate, no overlap
            // reached yet.
            assert_eq!(
                governing,
                critical_time_step_at(&drop(), &law, DemSettings::default().stability_overlap)
                    .governing
            );
            assert!(
                matches!(governing, GoverningMode::Particle { particle: 0, .. }),
                "{governing}"
            );
            assert_eq!(overlap, None);
        }
        other => panic!("{other:?}"),
    }
    for bad in [0.0, -0.1, 1.5, f64::NAN] {
        match DemSimulation::new(
            drop(),
            law,
            ExplicitEuler,
            DemSettings {
                stability_overlap: bad,
                ..settings(0.5 * limit)
            },
        ) {
            Err(DismechError::InvalidParameter { name, .. }) => {
                assert_eq!(name, "stability_overlap")
            }
            other => panic!("{bad}: {other:?}"),
        }
    }
}

/// Checked at 0.1 % of the radius, the drop's impact (about 1 %) needs a
/// shorter step than the one taken: the run stops at the check where the
/// overlap outgrew the setting. Checked at the default 5 %, a step half
/// that limit runs, and the overlaps stay within the setting.
#[test]
fn a_run_whose_overlaps_outgrow_the_checked_one_is_stopped_naming_the_overlap() {
    let law = Hertz { coefficient: HERTZ };
    let criterion = RestCriterion {
        max_time: 0.3,
        check_every: 1,
        ..RestCriterion::default()
    };
    let low = 1e-3;
    let dt = 0.9 * critical_time_step_at(&drop(), &law, low).dt;
    let settings = DemSettings {
        dt,
        stability_overlap: low,
        ..DemSettings::default()
    };
    let mut sim = DemSimulation::new(drop(), law, ExplicitEuler, settings).unwrap();
    let result = sim.run_to_rest(&criterion, |_, _| {});
    let message = result.as_ref().err().map(ToString::to_string);
    match result {
        Err(DismechError::Explicit(ExplicitError::UnstableTimeStep {
            dt: taken,
            limit,
            governing,
            overlap: Some(reached),
        })) => {
            assert_eq!(taken, dt);
            let (ratio, particle, target) = sim.largest_overlap_ratio().unwrap();
            assert_eq!(particle, 0);
            assert!(ratio > low, "{ratio}");
            assert_eq!(limit, critical_time_step_at(sim.scene(), &law, ratio).dt);
            assert!(limit < dt);
            assert_eq!(
                governing,
                critical_time_step_at(sim.scene(), &law, ratio).governing
            );
            assert_eq!(
                reached,
                OverlapReached {
                    step: sim.steps(),
                    particle,
                    target,
                    ratio,
                    stability_overlap: low,
                }
            );
            let message = message.unwrap();
            assert!(message.contains("stability_overlap"), "{message}");
        }
        other => panic!("{other:?}"),
    }

    let settings = DemSettings {
        dt: 0.5 * critical_time_step_at(&drop(), &law, 0.05).dt,
        ..DemSettings::default()
    };
    let mut sim = DemSimulation::new(drop(), law, ExplicitEuler, settings).unwrap();
    let mut largest: f64 = 0.0;
    while sim.time() < 0.2 {
        sim.step().unwrap();
        sim.check_overlap_stability().unwrap();
        if let Some((ratio, _, _)) = sim.largest_overlap_ratio() {
            largest = largest.max(ratio);
        }
    }
    assert!(largest > 1e-3 && largest < 0.05, "{largest}");
    // Each contact record carries its overlap.
    assert!(sim.contacts().iter().all(|c| c.overlap > 0.0));
}

/// A linear law's limit does not depend on the overlap: however small the
/// overlap it is checked at, a run is never stopped for outgrowing it.
#[test]
fn a_linear_law_is_not_stopped_for_its_overlaps() {
    let law =
        SpringDashpotCoulomb::new(NormalStiffness::Constant(1e7), 0.25, 0.5, Damping::Critical)
            .unwrap();
    let scene = drop();
    assert_eq!(
        critical_time_step_at(&scene, &law, 1e-9),
        critical_time_step_at(&scene, &law, 1.0)
    );
    let settings = DemSettings {
        dt: 0.5 * critical_time_step_at(&scene, &law, 1e-9).dt,
        stability_overlap: 1e-9,
        ..DemSettings::default()
    };
    let mut sim = DemSimulation::new(scene, law, ExplicitEuler, settings).unwrap();
    let outcome = sim
        .run_to_rest(
            &RestCriterion {
                max_time: 1.0,
                ..RestCriterion::default()
            },
            |_, _| {},
        )
        .unwrap();
    assert_eq!(outcome.status, RunStatus::AtRest);
    assert!(sim.largest_overlap_ratio().unwrap().0 > 1e-9);
}

/// A run resumed from its checkpoint keeps checking its overlaps: the drop
/// checked at 0.1 %, stopped for its impact when run straight, is stopped
/// the same way after a restore before the impact; a checkpoint of a run
/// that checks its stable step is not resumed as one without a bound.
#[test]
fn a_restored_run_keeps_checking_its_overlaps() {
    let law = Hertz { coefficient: HERTZ };
    let low = 1e-3;
    let settings = DemSettings {
        dt: 0.9 * critical_time_step_at(&drop(), &law, low).dt,
        stability_overlap: low,
        ..DemSettings::default()
    };
    let criterion = RestCriterion {
        max_time: 0.3,
        check_every: 1,
        ..RestCriterion::default()
    };
    let mut sim = DemSimulation::new(drop(), law, ExplicitEuler, settings).unwrap();
    for _ in 0..10 {
        sim.step().unwrap();
    }
    assert!(sim.contacts().is_empty(), "still falling");
    let bytes = sim.checkpoint().unwrap();
    let straight = sim.run_to_rest(&criterion, |_, _| {});
    let mut resumed = DemSimulation::restore(law, ExplicitEuler, &bytes).unwrap();
    let again = resumed.run_to_rest(&criterion, |_, _| {});
    assert!(
        matches!(
            straight,
            Err(DismechError::Explicit(
                ExplicitError::UnstableTimeStep { .. }
            ))
        ),
        "{straight:?}"
    );
    assert_eq!(again, straight);
    assert_eq!(resumed.steps(), sim.steps());
    assert!(matches!(
        DemSimulation::restore_unchecked(law, ExplicitEuler, &bytes),
        Err(DismechError::InvalidParameter { .. })
    ));
}
