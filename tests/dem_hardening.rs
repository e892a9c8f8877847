//! Hostile DEM inputs: time steps the clock cannot take, runs without an
//! end, states written into public fields, a skin that lists every pair.

use dismech::dem::DemSimulation;
use dismech::error::DismechError;
use dismech::explicit::ExplicitError;
use dismech::explicit::{DemSettings, RestCriterion, RunStatus};
use dismech::integrate::ExplicitEuler;
use dismech::law::{Damping, NormalStiffness, SpringDashpotCoulomb};
use dismech::math::{Point, Vec2};
use dismech::scene::{Frame, Scene};
use dismech::shape::Segment;

fn law() -> SpringDashpotCoulomb {
    SpringDashpotCoulomb::new(
        NormalStiffness::Constant(1e6),
        2.0 / 7.0,
        0.5,
        Damping::PerMass {
            normal: 100.0,
            shear: 50.0,
        },
    )
    .unwrap()
}

/// `n` discs of radius 1 cm on a square lattice of pitch 2.1 cm, 45 a
/// row, in an open box 1 m wide.
fn discs(n: usize) -> Scene {
    let mut scene = Scene::new(Frame::open_box(1.0, 1.0).unwrap(), Vec2::new(0.0, -9.8)).unwrap();
    for i in 0..n {
        let centre = Point::new(
            0.02 + 0.021 * (i % 45) as f64,
            0.02 + 0.021 * (i / 45) as f64,
        );
        scene.add_circle(centre, 0.01, 2650.0).unwrap();
    }
    scene
}

fn settings(dt: f64) -> DemSettings {
    DemSettings {
        dt,
        ..DemSettings::default()
    }
}

fn new(
    scene: Scene,
    settings: DemSettings,
) -> dismech::error::Result<DemSimulation<SpringDashpotCoulomb>> {
    DemSimulation::new(scene, law(), ExplicitEuler, settings)
}

/// 5e-324 s was accepted, and the clock never moved.
#[test]
fn subnormal_time_step_is_refused() {
    let err = new(discs(4), settings(5e-324)).unwrap_err();
    assert!(
        matches!(
            err,
            DismechError::InvalidParameter {
                name: "time step dt",
                ..
            }
        ),
        "{err}"
    );
    // The message writes the value short.
    assert!(err.to_string().contains("= 5e-324"), "{err}");
}

/// A run at Δt = 1e-9 s to a 60 s time limit had no bound on its steps.
#[test]
fn run_at_a_tiny_time_step_ends_at_its_step_limit() {
    let mut sim = new(discs(4), settings(1e-9)).unwrap();
    let criterion = RestCriterion {
        max_steps: 1000,
        ..RestCriterion::default()
    };
    let outcome = sim.run_to_rest(&criterion, |_, _| {}).unwrap();
    assert_eq!(outcome.status, RunStatus::StepLimit);
    assert_eq!(outcome.steps, 1000);
    assert_eq!(sim.steps(), 1000);
}

/// A wall-clock limit the user sets ends the run at a check.
#[test]
fn run_ends_at_its_wall_time_limit() {
    let mut sim = new(discs(4), settings(1e-9)).unwrap();
    let criterion = RestCriterion {
        max_wall_time: Some(std::time::Duration::from_millis(20)),
        check_every: 10,
        ..RestCriterion::default()
    };
    let outcome = sim.run_to_rest(&criterion, |_, _| {}).unwrap();
    assert_eq!(outcome.status, RunStatus::WallTimeLimit);
    assert!(outcome.steps < RestCriterion::default().max_steps);
    assert_eq!(outcome.steps % 10, 0);
}

/// `max_steps = 0` would end before the first step.
#[test]
fn zero_step_limit_is_refused() {
    let mut sim = new(discs(4), settings(1e-5)).unwrap();
    let criterion = RestCriterion {
        max_steps: 0,
        ..RestCriterion::default()
    };
    let err = sim.run_to_rest(&criterion, |_, _| {}).unwrap_err();
    assert!(
        matches!(
            err,
            DismechError::InvalidParameter {
                name: "max_steps",
                ..
            }
        ),
        "{err}"
    );
}

/// A NaN written into a particle's public pose was reported as an energy
/// blow-up blaming Δt; an infinite velocity likewise.
#[test]
fn non_finite_particle_state_is_refused_naming_the_particle() {
    let mut scene = discs(4);
    scene.particles[2].pose.position.x = f64::NAN;
    let err = new(scene, settings(1e-5)).unwrap_err();
    assert!(
        matches!(
            err,
            DismechError::Explicit(ExplicitError::InvalidParticle {
                particle: 2,
                name: "position x",
                ..
            })
        ),
        "{err}"
    );
    let mut scene = discs(4);
    scene.particles[1].velocity.y = f64::INFINITY;
    let err = new(scene, settings(1e-5)).unwrap_err();
    assert!(
        matches!(
            err,
            DismechError::Explicit(ExplicitError::InvalidParticle {
                particle: 1,
                name: "velocity y",
                ..
            })
        ),
        "{err}"
    );
}

/// A disc of radius 1e-200 m was refused as "use dt <= 0.000e0 s": its
/// mass underflows to zero.
#[test]
fn disc_whose_mass_underflows_is_refused_for_its_mass() {
    let mut scene = Scene::new(Frame::open_box(1.0, 1.0).unwrap(), Vec2::new(0.0, -9.8)).unwrap();
    scene
        .add_circle(Point::new(0.5, 0.5), 1e-200, 2650.0)
        .unwrap();
    let err = new(scene, settings(1e-5)).unwrap_err();
    assert!(
        matches!(
            err,
            DismechError::Explicit(ExplicitError::InvalidParticle {
                particle: 0,
                name: "mass",
                ..
            })
        ),
        "{err}"
    );
}

/// An infinite external force is refused where it is set.
#[test]
fn infinite_external_force_is_refused() {
    let mut scene = discs(2);
    let err = scene
        .set_external_force(0, Vec2::new(f64::INFINITY, 0.0))
        .unwrap_err();
    assert!(
        matches!(err, DismechError::InvalidParameter { .. }),
        "{err}"
    );
}

/// A box drawn clockwise puts the material outside its walls: the error
/// for the particle "inside" a wall says so.
#[test]
fn clockwise_frame_is_named_in_the_wall_error() {
    let (a, b, c, d) = (
        Point::new(0.0, 1.0),
        Point::new(0.0, 0.0),
        Point::new(1.0, 0.0),
        Point::new(1.0, 1.0),
    );
    let clockwise = Frame::from_walls(vec![
        ("right".into(), Segment::new(d, c)),
        ("bottom".into(), Segment::new(c, b)),
        ("left".into(), Segment::new(b, a)),
    ])
    .unwrap();
    assert!(clockwise.runs_clockwise());
    assert!(!Frame::open_box(1.0, 1.0).unwrap().runs_clockwise());
    let mut scene = Scene::new(clockwise, Vec2::new(0.0, -9.8)).unwrap();
    scene
        .add_circle(Point::new(0.5, 0.5), 0.01, 2650.0)
        .unwrap();
    let err = new(scene, settings(1e-5)).unwrap_err();
    assert!(
        matches!(
            err,
            DismechError::Explicit(ExplicitError::StartsInsideWall {
                clockwise_frame: true,
                ..
            })
        ),
        "{err}"
    );
    assert!(err.to_string().contains("counter-clockwise"), "{err}");
}

/// A skin of 1e6 m listed every pair (19 GB for 20 000 discs) and aborted;
/// it is refused before the list is built, at 2 000 discs as at 20 000.
#[test]
fn skin_as_large_as_the_scene_is_refused_before_the_list_is_built() {
    let skin = DemSettings {
        dt: 1e-5,
        neighbour_skin: Some(1e6),
        ..DemSettings::default()
    };
    let err = new(discs(2000), skin).unwrap_err();
    assert!(
        matches!(
            err,
            DismechError::Explicit(ExplicitError::OutOfMemory { .. })
        ),
        "{err}"
    );
    assert!(
        matches!(
            &err,
            DismechError::Explicit(ExplicitError::OutOfMemory {
                what: dismech::explicit::MemoryUse::NeighbourList {
                    skin: 1e6,
                    particles: 2000,
                    ..
                },
                advice: dismech::explicit::MemoryAdvice::SkinTooWide { .. },
                ..
            })
        ),
        "{err}"
    );
    assert!(err.to_string().contains("skin of 1e6 m"), "{err}");
    // A skin of a few radii is listed.
    let modest = DemSettings {
        neighbour_skin: Some(0.03),
        ..skin
    };
    assert!(new(discs(2000), modest).is_ok());
}
