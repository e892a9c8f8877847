//! Prescribed particles in the explicit DEM: bodies of any shape that keep
//! their velocity whatever the contacts push (a fixed polygon incline, a
//! rough base of fixed discs, a plate driven at constant speed).

use dismech::dem::DemSimulation;
use dismech::error::DismechError;
use dismech::explicit::ExplicitError;
use dismech::explicit::{DemSettings, RestCriterion, RunStatus};
use dismech::integrate::ExplicitEuler;
use dismech::law::{Damping, NormalStiffness, SpringDashpotCoulomb};
use dismech::math::{perp, Point, Pose2, Vec2};
use dismech::reference::incline::sliding_acceleration;
use dismech::scene::{Frame, Particle, Scene};
use dismech::shape::{Circle, Polygon, Segment};

const G: f64 = 9.81;

fn law(friction: f64) -> SpringDashpotCoulomb {
    SpringDashpotCoulomb::new(
        NormalStiffness::Constant(1e8),
        0.25,
        friction,
        Damping::Critical,
    )
    .unwrap()
}

fn settings(dt: f64) -> DemSettings {
    DemSettings {
        dt,
        ..DemSettings::default()
    }
}

/// A 0.2 × 0.1 m granite block on a 40° incline (μ = tan 30°), the incline
/// either a wall of the frame or a fixed polygon plate whose top face is
/// the wall's line; returns the block's mean acceleration along the slope
/// from 0.1 s to 0.6 s.
fn block_on_incline(fixed_plate: bool) -> (f64, f64) {
    let beta = 40f64.to_radians();
    let downhill = Vec2::new(beta.cos(), -beta.sin());
    let length = 3.0;
    let top = Point::new(0.0, length * beta.sin());
    let line = Segment::new(top, top + downhill * length);
    let frame = if fixed_plate {
        // Only a floor far below; the incline is a particle.
        Frame::from_walls(vec![(
            "floor".into(),
            Segment::new(Point::new(-10.0, -10.0), Point::new(10.0, -10.0)),
        )])
        .unwrap()
    } else {
        Frame::from_walls(vec![("incline".into(), line)]).unwrap()
    };
    let mut scene = Scene::new(frame, Vec2::new(0.0, -G)).unwrap();
    let centre = top + downhill * 0.6 + perp(&downhill) * 0.05;
    scene
        .add_rectangle(centre, 0.2, 0.1, -beta, 2690.0)
        .unwrap();
    if fixed_plate {
        let thickness = 0.1;
        let middle = top + downhill * (0.5 * length) - perp(&downhill) * (0.5 * thickness);
        scene.particles.push(Particle::fixed(
            Polygon::rectangle(length, thickness).unwrap().into(),
            Pose2::new(middle.x, middle.y, -beta),
        ));
    }
    let dt = 2e-5;
    let mut sim = DemSimulation::new(
        scene,
        law(30f64.to_radians().tan()),
        ExplicitEuler,
        settings(dt),
    )
    .unwrap();
    let mut settled = 0.0;
    for step in 1..=30_000u64 {
        sim.step().unwrap();
        if step == 5_000 {
            settled = sim.scene().particles[0].velocity.dot(&downhill);
        }
    }
    let block = &sim.scene().particles[0];
    let acceleration = (block.velocity.dot(&downhill) - settled) / (25_000.0 * dt);
    (
        acceleration,
        sliding_acceleration(G, beta, 30f64.to_radians().tan()),
    )
}

/// The block slides down a fixed polygon as down a wall: the same
/// acceleration to 1e-6, and the rigid block's `g (sin β − μ cos β)` to
/// 1 % (the contact springs' compliance); the plate has not moved.
#[test]
fn a_block_slides_down_a_fixed_polygon_as_down_a_wall() {
    let (on_wall, exact) = block_on_incline(false);
    let (on_plate, _) = block_on_incline(true);
    assert!(
        (on_plate / on_wall - 1.0).abs() < 1e-6,
        "plate {on_plate} wall {on_wall}"
    );
    assert!(
        (on_plate / exact - 1.0).abs() < 1e-2,
        "{on_plate} vs {exact}"
    );
}

/// A plate driven at 0.5 m/s under a resting block with ample friction
/// keeps its velocity exactly and carries the block along at its speed;
/// the plate is left out of the kinetic energy and the total weight.
#[test]
fn a_driven_plate_keeps_its_velocity_and_carries_a_block() {
    let frame = Frame::from_walls(vec![(
        "floor".into(),
        Segment::new(Point::new(-10.0, -10.0), Point::new(10.0, -10.0)),
    )])
    .unwrap();
    let mut scene = Scene::new(frame, Vec2::new(0.0, -G)).unwrap();
    let block = scene
        .add_rectangle(Point::new(0.0, 0.05), 0.2, 0.1, 0.0, 2690.0)
        .unwrap();
    let speed = Vec2::new(0.5, 0.0);
    scene.particles.push(Particle::prescribed(
        Polygon::rectangle(4.0, 0.1).unwrap().into(),
        Pose2::new(0.0, -0.05, 0.0),
        speed,
        0.0,
    ));
    let weight = scene.total_weight();
    assert!((weight - 0.2 * 0.1 * 2690.0 * G).abs() < 1e-9 * weight);
    let dt = 2e-5;
    let mut sim = DemSimulation::new(scene, law(0.8), ExplicitEuler, settings(dt)).unwrap();
    let steps = 20_000;
    for _ in 0..steps {
        sim.step().unwrap();
    }
    let plate = &sim.scene().particles[1];
    assert_eq!(plate.velocity, speed);
    assert_eq!(plate.angular_velocity, 0.0);
    let travelled = plate.pose.position.x;
    let expected = speed.x * steps as f64 * dt;
    assert!(
        (travelled - expected).abs() < 1e-9,
        "{travelled} vs {expected}"
    );
    assert_eq!(plate.pose.position.y, -0.05);
    let carried = &sim.scene().particles[block];
    assert!(
        (carried.velocity - speed).norm() < 1e-3,
        "block at {:?}",
        carried.velocity
    );
    let own = carried.kinetic_energy();
    assert!((sim.kinetic_energy() - own).abs() <= 1e-12 * own);
    // Carried at the plate's speed, the block presses on the plate with
    // its weight and no horizontal force.
    let (on_plate, _) = sim.force_on(1).unwrap();
    assert!((on_plate.y + weight).abs() < 1e-3 * weight, "{on_plate:?}");
    assert!(on_plate.x.abs() < 1e-3 * weight, "{on_plate:?}");
    assert!(sim.force_on(2).is_err());
}

/// Discs of a rough base may overlap each other when both are fixed; a
/// disc dropped on them comes to rest, carried by the two it falls between.
#[test]
fn a_disc_comes_to_rest_on_a_rough_base_of_fixed_discs() {
    let frame = Frame::from_walls(vec![(
        "floor".into(),
        Segment::new(Point::new(-10.0, -10.0), Point::new(10.0, -10.0)),
    )])
    .unwrap();
    let mut scene = Scene::new(frame, Vec2::new(0.0, -G)).unwrap();
    let r = 0.05;
    for k in -3..=3 {
        // Centres 1.8 r apart: neighbours overlap by 0.2 r.
        scene.particles.push(Particle::fixed(
            Circle::new(r).unwrap().into(),
            Pose2::new(1.8 * r * k as f64, 0.0, 0.0),
        ));
    }
    let falling = scene
        .add_circle(Point::new(0.9 * r, 2.5 * r), r, 2650.0)
        .unwrap();
    let mut sim = DemSimulation::new(scene, law(0.5), ExplicitEuler, settings(1e-5)).unwrap();
    for _ in 0..60_000 {
        sim.step().unwrap();
    }
    let disc = &sim.scene().particles[falling];
    // Between the fixed discs at 0 and 1.8 r, at the height where it
    // touches both (less the springs' sink).
    let height = ((2.0 * r).powi(2) - (0.9 * r).powi(2)).sqrt();
    assert!(
        (disc.pose.position.x - 0.9 * r).abs() < 1e-6,
        "{:?}",
        disc.pose
    );
    assert!(
        (disc.pose.position.y - height).abs() < 1e-4 * r,
        "{:?}",
        disc.pose
    );
    assert!(disc.velocity.norm() < 1e-6, "{:?}", disc.velocity);
    assert!(sim.unbalanced_force_ratio() < 1e-6);
    for fixed in &sim.scene().particles[..falling] {
        assert_eq!(fixed.velocity, Vec2::zeros());
        assert!(fixed.pose.position.y == 0.0);
    }
}

/// An infinite mass with a finite moment of inertia (or the other way
/// round) is refused, naming the value: a prescribed particle has both.
#[test]
fn half_prescribed_particle_is_refused() {
    let frame = Frame::open_box(1.0, 1.0).unwrap();
    let mut scene = Scene::new(frame, Vec2::new(0.0, -G)).unwrap();
    let disc = scene
        .add_circle(Point::new(0.5, 0.5), 0.05, 2650.0)
        .unwrap();
    scene.particles[disc].mass = f64::INFINITY;
    match DemSimulation::new(scene, law(0.5), ExplicitEuler, settings(1e-5)) {
        Err(DismechError::Explicit(ExplicitError::InvalidParticle { particle, name, .. })) => {
            assert_eq!((particle, name), (disc, "mass"));
        }
        Err(other) => panic!("{other}"),
        Ok(_) => panic!("accepted"),
    }
}

/// A plate driven into a disc supplies the energy the disc gains: a run to
/// rest is not stopped as an energy blow-up, and ends at its time limit
/// with the disc pushed along at the plate's speed.
#[test]
fn a_plate_pushing_a_disc_is_not_taken_for_an_energy_blow_up() {
    let frame = Frame::from_walls(vec![(
        "floor".into(),
        Segment::new(Point::new(-10.0, 0.0), Point::new(10.0, 0.0)),
    )])
    .unwrap();
    let mut scene = Scene::new(frame, Vec2::new(0.0, -G)).unwrap();
    let r = 0.05;
    let disc = scene.add_circle(Point::new(0.0, r), r, 2650.0).unwrap();
    let speed = 0.1;
    scene.particles.push(Particle::prescribed(
        Polygon::rectangle(0.02, 0.3).unwrap().into(),
        Pose2::new(-r - 0.01, 0.2, 0.0),
        Vec2::new(speed, 0.0),
        0.0,
    ));
    let mut sim = DemSimulation::new(scene, law(0.3), ExplicitEuler, settings(1e-5)).unwrap();
    let criterion = RestCriterion {
        max_time: 0.5,
        ..RestCriterion::default()
    };
    let outcome = sim.run_to_rest(&criterion, |_, _| {}).unwrap();
    assert_eq!(outcome.status, RunStatus::TimeLimit, "{outcome:?}");
    let pushed = &sim.scene().particles[disc];
    assert!(
        (pushed.velocity.x - speed).abs() < 0.05 * speed,
        "{:?}",
        pushed.velocity
    );
    assert!(pushed.pose.position.x > 0.02, "{:?}", pushed.pose);
}

/// A packing with a prescribed particle has no limit model (its fixed
/// boundaries are straight supports): refused, naming why.
#[test]
fn a_packing_with_a_prescribed_particle_is_refused_by_the_limit_model() {
    use dismech::law::RigidPlastic;
    use dismech::limit::{model_from_packing, PackingLimitSettings};
    let mut scene = Scene::new(Frame::open_box(1.0, 1.0).unwrap(), Vec2::new(0.0, -G)).unwrap();
    scene
        .add_circle(Point::new(0.5, 0.5), 0.05, 2650.0)
        .unwrap();
    scene.particles.push(Particle::fixed(
        Circle::new(0.05).unwrap().into(),
        Pose2::new(0.2, 0.05, 0.0),
    ));
    let law = RigidPlastic::coulomb(0.0, 0.5, true).unwrap();
    let settings = PackingLimitSettings {
        rolling: true,
        contact_law: law,
        wall_law: law,
        plate_law: law,
        plate_wall: "left".into(),
        self_weight: true,
    };
    match model_from_packing(&scene, &[], &settings) {
        Err(DismechError::InvalidParameter { name, .. }) => {
            assert!(name.contains("prescribed"), "{name}")
        }
        other => panic!("{other:?}"),
    }
}
