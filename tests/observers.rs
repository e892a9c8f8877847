//! Observers of a run: what they are told, that watching changes nothing,
//! that an observer's error stops the run, and ParaView frames written by
//! one.

use dismech::dem::DemSimulation;
use dismech::error::DismechError;
use dismech::explicit::{DemSettings, RestCriterion, RunStatus};
use dismech::integrate::ExplicitEuler;
use dismech::law::SpringDashpotCoulomb;
use dismech::math::{Point, Vec2};
use dismech::observe::{every, Event};
use dismech::scene::{Frame, Scene};
use dismech::vtk::DemFrames;

type Dem = DemSimulation<SpringDashpotCoulomb>;

/// A few discs and an ellipse dropped into a box.
fn dem() -> Dem {
    let mut scene = Scene::new(Frame::open_box(1.0, 1.0).unwrap(), Vec2::new(0.0, -9.81)).unwrap();
    for k in 0..4 {
        scene
            .add_circle(
                Point::new(0.2 + 0.2 * k as f64, 0.1 + 0.05 * k as f64),
                0.05,
                2600.0,
            )
            .unwrap();
    }
    scene
        .add_ellipse(Point::new(0.5, 0.4), 0.08, 0.04, 0.3, 2600.0)
        .unwrap();
    let law = SpringDashpotCoulomb::katsuki(73.55e6, 0.3, 0.25, 0.577).unwrap();
    DemSimulation::new(scene, law, ExplicitEuler, DemSettings::default()).unwrap()
}

fn criterion() -> RestCriterion {
    RestCriterion {
        max_time: 0.5,
        check_every: 50,
        ..RestCriterion::default()
    }
}

/// Every step is told once, in order, then each check, then the end; the
/// run observed ends in the same bits as the run not observed, and the
/// old callback sees the checks' ratios.
#[test]
fn an_observer_sees_every_step_and_check_and_changes_nothing() {
    let mut plain = dem();
    let mut ratios = Vec::new();
    let outcome = plain
        .run_to_rest(&criterion(), |_, ratio| ratios.push(ratio))
        .unwrap();

    let mut observed = dem();
    let mut events = Vec::new();
    let seen = observed
        .run_to_rest_observed(&criterion(), &mut |d: &Dem, e: &Event| {
            if let Event::Step { step, time } = *e {
                assert_eq!((step, time), (d.steps(), d.time()));
            }
            events.push(*e);
            Ok(())
        })
        .unwrap();
    assert_eq!(seen, outcome);
    let steps: Vec<u64> = events
        .iter()
        .filter_map(|e| match e {
            Event::Step { step, .. } => Some(*step),
            _ => None,
        })
        .collect();
    assert_eq!(steps, (1..=outcome.steps).collect::<Vec<_>>());
    let checks: Vec<f64> = events
        .iter()
        .filter_map(|e| match e {
            Event::Check { rest_ratio, .. } => Some(*rest_ratio),
            _ => None,
        })
        .collect();
    assert_eq!(checks, ratios);
    assert_eq!(
        events.last(),
        Some(&Event::Finished {
            step: outcome.steps,
            time: observed.time()
        })
    );
    assert_eq!(
        events
            .iter()
            .filter(|e| matches!(e, Event::Finished { .. }))
            .count(),
        1
    );
    for (a, b) in plain
        .scene()
        .particles
        .iter()
        .zip(&observed.scene().particles)
    {
        assert_eq!(a.pose.position.x.to_bits(), b.pose.position.x.to_bits());
        assert_eq!(a.pose.position.y.to_bits(), b.pose.position.y.to_bits());
        assert_eq!(a.velocity.x.to_bits(), b.velocity.x.to_bits());
        assert_eq!(a.angular_velocity.to_bits(), b.angular_velocity.to_bits());
    }
}

/// An observer that fails stops the run at that step with its error.
#[test]
fn an_observer_error_stops_the_run() {
    let mut sim = dem();
    let result = sim.run_to_rest_observed(&criterion(), &mut |d: &Dem, _: &Event| {
        if d.steps() == 10 {
            return Err(DismechError::InvalidParameter {
                name: "observer",
                value: 10.0,
                requirement: "stops at step 10",
            });
        }
        Ok(())
    });
    assert!(matches!(
        result,
        Err(DismechError::InvalidParameter {
            name: "observer",
            ..
        })
    ));
    assert_eq!(sim.steps(), 10);
}

/// ParaView frames every 200 steps and at the end, by an observer: the
/// series lists their times, each a step of the run, and the last is the
/// run's end.
#[test]
fn frames_are_written_by_an_observer_every_n_steps_and_at_the_end() {
    let folder =
        std::env::temp_dir().join(format!("dismech-observed-frames-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&folder);
    let mut sim = dem();
    let dt = DemSettings::default().dt;
    let mut frames = every(200, DemFrames::new(&folder, 24).unwrap());
    let outcome = sim.run_to_rest_observed(&criterion(), &mut frames).unwrap();
    assert_ne!(outcome.status, RunStatus::StepLimit);
    let frames = frames.into_inner();
    let times: Vec<f64> = frames
        .series()
        .entries("particles")
        .iter()
        .map(|e| e.time)
        .collect();
    let expected: Vec<u64> = (1..=outcome.steps / 200)
        .map(|k| 200 * k)
        .chain((outcome.steps % 200 != 0).then_some(outcome.steps))
        .collect();
    assert_eq!(times.len(), expected.len());
    assert_eq!(*times.last().unwrap(), sim.time());
    for (t, step) in times.iter().zip(&expected) {
        assert!((t - *step as f64 * dt).abs() < 1e-9, "{t} for step {step}");
    }
    for name in ["particles", "contacts", "walls"] {
        let pvd = std::fs::read_to_string(frames.series().pvd_path(name)).unwrap();
        assert_eq!(pvd.matches("<DataSet").count(), expected.len(), "{name}");
    }
    std::fs::remove_dir_all(&folder).unwrap();
}
