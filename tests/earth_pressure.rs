//! Loads on the walls of the explicit DEM: a constant external force is
//! carried exactly by the wall it pushes on, a regular layout that would
//! start overlapping is refused, and a particle pushed out of the frame
//! stops the run.

use dismech::dem::DemSimulation;
use dismech::error::DismechError;
use dismech::explicit::ExplicitError;
use dismech::explicit::{DemSettings, RestCriterion};
use dismech::integrate::ExplicitEuler;
use dismech::law::{Damping, NormalStiffness, SpringDashpotCoulomb};
use dismech::math::{Point, Vec2};
use dismech::scene::Layout;
use dismech::scene::{Frame, Scene};

use crate::common;

use common::settle;

#[test]
fn external_force_is_carried_by_the_wall_it_pushes_on() {
    // A disc on a frictionless floor pushed against the right wall by a
    // constant force F: at rest the wall carries F and the wall overlap is
    // F / k. (With friction the floor's tangential spring would keep part of
    // F, an indeterminate share.)
    let (r, k, force) = (0.07, 1e7, 2000.0);
    let mut scene = Scene::new(Frame::open_box(1.0, 1.0).unwrap(), Vec2::new(0.0, -9.81)).unwrap();
    scene.add_circle(Point::new(0.9, r), r, 2690.0).unwrap();
    scene.set_external_force(0, Vec2::new(force, 0.0)).unwrap();
    let law = SpringDashpotCoulomb::new(NormalStiffness::Constant(k), 0.25, 0.0, Damping::Critical)
        .unwrap();
    let sim = settle(scene, law, 1e-4);
    let right = sim.scene().frame.index_of("right").unwrap();
    let load = sim.wall_load(right);
    approx::assert_relative_eq!(load.x, force, max_relative = 1e-6);
    let p = &sim.scene().particles[0];
    approx::assert_relative_eq!(p.pose.position.x, 1.0 - r + force / k, max_relative = 1e-9);
}

#[test]
fn external_force_must_be_finite_and_name_an_existing_particle() {
    let mut scene = Scene::new(Frame::open_box(1.0, 1.0).unwrap(), Vec2::new(0.0, -9.81)).unwrap();
    scene
        .add_circle(Point::new(0.5, 0.5), 0.07, 2690.0)
        .unwrap();
    assert!(matches!(
        scene.set_external_force(0, Vec2::new(f64::NAN, 0.0)),
        Err(DismechError::InvalidParameter { .. })
    ));
    assert!(matches!(
        scene.set_external_force(3, Vec2::new(1.0, 0.0)),
        Err(DismechError::NoSuchBody { index: 3, count: 1 })
    ));
}

#[test]
fn layout_that_would_start_overlapping_is_refused() {
    let layout = Layout {
        width: 1.0,
        height: 2.0,
        semi_major: 0.1,
        semi_minor: 0.05,
        angle: 0.0,
        per_row: 6, // pitch 0.167 m < particle width 0.2 m
        staggered: true,
        rows: 4,
        gap: 0.01,
        density: 2690.0,
    };
    match layout.scene(9.81) {
        Err(DismechError::InvalidParameter { value, .. }) => {
            approx::assert_relative_eq!(value, 1.0 / 6.0)
        }
        other => panic!("expected InvalidParameter, got {other:?}"),
    }
}

#[test]
fn particle_pushed_out_of_the_frame_stops_the_run_naming_it() {
    // A floor 1 m long and a disc pushed along it: it slides off the end and
    // falls; the run stops once it is a frame size away.
    let floor = dismech::shape::Segment::new(Point::new(0.0, 0.0), Point::new(1.0, 0.0));
    let frame = Frame::from_walls(vec![("floor".into(), floor)]).unwrap();
    let mut scene = Scene::new(frame, Vec2::new(0.0, -9.81)).unwrap();
    scene
        .add_circle(Point::new(0.5, 0.07), 0.07, 2690.0)
        .unwrap();
    scene
        .add_circle(Point::new(0.2, 0.07), 0.07, 2690.0)
        .unwrap();
    scene.set_external_force(1, Vec2::new(-500.0, 0.0)).unwrap();
    let law =
        SpringDashpotCoulomb::new(NormalStiffness::Constant(1e7), 0.25, 0.5, Damping::Critical)
            .unwrap();
    let mut sim = DemSimulation::new(scene, law, ExplicitEuler, DemSettings::default()).unwrap();
    match sim.run_to_rest(&RestCriterion::default(), |_, _| {}) {
        Err(DismechError::Explicit(ExplicitError::ParticleLeftFrame { body, x, .. })) => {
            assert_eq!(body, 1);
            assert!(x < 0.0, "it left on the side it was pushed to: x = {x}");
        }
        other => panic!("expected ParticleLeftFrame, got {other:?}"),
    }
}
