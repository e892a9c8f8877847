//! Checkpoints of the explicit driver: a run stopped at step k, saved,
//! dropped and resumed ends N steps in the same bits as the run that
//! never stopped (positions, angles, velocities, forces, contacts, time,
//! neighbour list), with contacts sliding at the checkpoint; and a
//! checkpoint that does not fit is refused by a typed error; and a run
//! that writes its checkpoints through an observer, killed at a random
//! step, resumes from the last one on disk to the same bits.

use crate::kill_common;

use std::path::PathBuf;

use dismech::checkpoint::{CheckpointProblem, FORMAT_VERSION};
use dismech::dem::DemSimulation;
use dismech::error::DismechError;
use dismech::explicit::DemSettings;
use dismech::integrate::{ExplicitEuler, ExplicitIntegrator};
use dismech::law::{Damping, NormalStiffness, Regime, SpringDashpotCoulomb};
use dismech::math::{Point, Vec2};
use dismech::observe::{every, Event};
use dismech::scene::{Frame, Scene};

const G: f64 = 9.81;
const DENSITY: f64 = 2600.0;

type Dem = DemSimulation<SpringDashpotCoulomb>;

fn law(friction: f64) -> SpringDashpotCoulomb {
    SpringDashpotCoulomb::new(
        NormalStiffness::Constant(1e6),
        0.5,
        friction,
        Damping::Critical,
    )
    .unwrap()
}

/// A frame whose floor is an incline from (0, 1) down to (4, 0) (14°),
/// between a left and a right wall: the line `x + 4 y = 4`.
fn incline_frame() -> Frame {
    let p = |x: f64, y: f64| Point::new(x, y);
    let wall =
        |name: &str, a: Point, b: Point| (name.to_string(), dismech::shape::Segment::new(a, b));
    Frame::from_walls(vec![
        wall("left", p(0.0, 2.0), p(0.0, 1.0)),
        wall("incline", p(0.0, 1.0), p(4.0, 0.0)),
        wall("right", p(4.0, 0.0), p(4.0, 2.0)),
    ])
    .unwrap()
}

/// The point above the incline at `x` whose distance to it is `d`.
fn above_incline(x: f64, d: f64) -> Point {
    Point::new(x, (d * 17f64.sqrt() + 4.0 - x) / 4.0)
}

/// Along the incline, downhill.
fn incline_angle() -> f64 {
    (-1.0f64).atan2(4.0)
}

/// A disc, an ellipse, a square and a triangle 0.1 mm above the incline,
/// which land and slide down it (μ = 0.15 against tan 14° = 0.25), and a
/// pile of four discs in the corner of the incline and the right wall.
fn incline_scene() -> Scene {
    let mut scene = Scene::new(incline_frame(), Vec2::new(0.0, -G)).unwrap();
    let gap = 1e-4;
    let angle = incline_angle();
    scene
        .add_circle(above_incline(0.5, 0.05 + gap), 0.05, DENSITY)
        .unwrap();
    scene
        .add_ellipse(above_incline(0.9, 0.03 + gap), 0.06, 0.03, angle, DENSITY)
        .unwrap();
    scene
        .add_rectangle(above_incline(1.3, 0.04 + gap), 0.08, 0.08, angle, DENSITY)
        .unwrap();
    let (s, c) = angle.sin_cos();
    let local = |u: f64, v: f64| {
        let base = above_incline(1.7, gap);
        Point::new(base.x + c * u - s * v, base.y + s * u + c * v)
    };
    scene
        .add_polygon(
            &[local(-0.05, 0.0), local(0.05, 0.0), local(0.0, 0.07)],
            DENSITY,
        )
        .unwrap();
    // The pile: two discs on the incline, the lower one against the right
    // wall, and one on each.
    let r = 0.05;
    let corner = above_incline(4.0 - r - gap, r + gap);
    let next = above_incline(corner.x - 2.0 * r - 3.0 * gap, r + gap);
    for centre in [corner, next] {
        scene.add_circle(centre, r, DENSITY).unwrap();
        let on_top = Point::new(centre.x, centre.y + 2.0 * r + 2.0 * gap);
        scene.add_circle(on_top, r, DENSITY).unwrap();
    }
    scene
}

/// Everything a run shows, as bits: time, steps, each particle's pose,
/// velocities and force, each contact's point, normal, force, regime and
/// features, and the neighbour list's builds and skin.
fn fingerprint(sim: &Dem) -> Vec<u64> {
    let mut bits = vec![
        sim.time().to_bits(),
        sim.steps(),
        sim.neighbour_list_builds(),
        sim.neighbour_skin().to_bits(),
        sim.kinetic_energy().to_bits(),
        sim.unbalanced_force_ratio().to_bits(),
    ];
    for (i, p) in sim.scene().particles.iter().enumerate() {
        let (force, moment) = sim.force_on(i).unwrap();
        bits.extend(
            [
                p.pose.position.x,
                p.pose.position.y,
                p.pose.angle,
                p.velocity.x,
                p.velocity.y,
                p.angular_velocity,
                force.x,
                force.y,
                moment,
            ]
            .map(f64::to_bits),
        );
    }
    for c in sim.contacts() {
        bits.push(c.particle as u64);
        bits.push(format!("{:?} {:?} {:?}", c.target, c.regime, c.features).len() as u64);
        bits.extend(
            [
                c.point.x,
                c.point.y,
                c.normal.x,
                c.normal.y,
                c.force_on_target.x,
                c.force_on_target.y,
            ]
            .map(f64::to_bits),
        );
    }
    bits
}

/// The contacts of the last step, described (target, regime, features),
/// to compare beside the bits.
fn described_contacts(sim: &Dem) -> Vec<String> {
    sim.contacts()
        .iter()
        .map(|c| {
            format!(
                "{} {:?} {:?} {:?}",
                c.particle, c.target, c.regime, c.features
            )
        })
        .collect()
}

fn steps(sim: &mut Dem, count: usize) {
    for _ in 0..count {
        sim.step().unwrap();
    }
}

fn temp_path(name: &str) -> PathBuf {
    std::env::temp_dir()
        .join(format!(
            "dismech-checkpoint-explicit-{}-{name}",
            std::process::id()
        ))
        .join(format!("{name}.ckpt"))
}

const SETTINGS: DemSettings = DemSettings {
    dt: 1e-4,
    initial_overlap_tolerance: 1e-6,
    stability_overlap: dismech::explicit::DEFAULT_STABILITY_OVERLAP,
    check_stability: true,
    neighbour_skin: None,
    relative_travel: false,
};

/// The incline: 2 000 steps straight, or 1 000, a checkpoint to bytes
/// (and, at 1 500, one through a file), the driver dropped, restored and
/// run to 2 000. At the checkpoint the four bodies slide (their contacts
/// with the incline slip) and the pile rests; the neighbour list is built
/// again after it. Every bit is the same, and the checkpoint of the
/// restored run is the checkpoint it was restored from.
#[test]
fn a_resumed_incline_run_ends_in_the_same_bits() {
    let (n, k) = (2000, 1000);
    let mut straight = Dem::new(incline_scene(), law(0.15), ExplicitEuler, SETTINGS).unwrap();
    steps(&mut straight, n);

    let mut first = Dem::new(incline_scene(), law(0.15), ExplicitEuler, SETTINGS).unwrap();
    steps(&mut first, k);
    let slipping = first
        .contacts()
        .iter()
        .filter(|c| c.regime == Regime::Slip)
        .count();
    assert!(slipping >= 4, "{slipping} contacts slip at the checkpoint");
    for p in &first.scene().particles[..4] {
        assert!(p.velocity.norm() > 0.05, "{:?}", p.velocity);
    }
    let builds_at_k = first.neighbour_list_builds();
    let bytes = first.checkpoint().unwrap();
    let at_k = fingerprint(&first);
    drop(first);

    let mut resumed = Dem::restore(law(0.15), ExplicitEuler, &bytes).unwrap();
    assert_eq!(fingerprint(&resumed), at_k);
    assert_eq!(resumed.checkpoint().unwrap(), bytes);
    steps(&mut resumed, (n - k) / 2);
    // Once more, through a file.
    let path = temp_path("incline");
    resumed.save_checkpoint(&path).unwrap();
    drop(resumed);
    let mut resumed = Dem::load_checkpoint(law(0.15), ExplicitEuler, &path).unwrap();
    steps(&mut resumed, (n - k) / 2);
    std::fs::remove_dir_all(path.parent().unwrap()).unwrap();

    assert!(resumed.neighbour_list_builds() > builds_at_k);
    assert_eq!(described_contacts(&resumed), described_contacts(&straight));
    assert_eq!(fingerprint(&resumed), fingerprint(&straight));
    assert_eq!(
        resumed.checkpoint().unwrap(),
        straight.checkpoint().unwrap()
    );
}

/// The incline run for 10 000 steps by a child process that writes a
/// checkpoint every 500 steps through an observer ([`every`],
/// [`Dem::save_checkpoint`], a file per checkpoint, each written
/// atomically) and is killed by SIGKILL at a random step (see
/// `kill_common`); resumed from the last checkpoint on disk and run to
/// step 10 000, it ends in the same bits as the run never interrupted.
#[test]
fn a_run_killed_at_a_random_step_resumes_from_its_last_checkpoint_in_the_same_bits() {
    const STEPS: u64 = 10_000;
    const EVERY: u64 = 500;
    const LEAD: u64 = 1_000;
    let new = || Dem::new(incline_scene(), law(0.15), ExplicitEuler, SETTINGS).unwrap();
    if let Some((folder, limit)) = kill_common::child() {
        let mut sim = new();
        let mut observer = (
            |_: &Dem, event: &Event<'_>| {
                if let Event::Step { step, .. } = event {
                    kill_common::report_progress(*step);
                }
                Ok(())
            },
            every(EVERY, |sim: &Dem, event: &Event<'_>| {
                if let Event::Step { step, .. } = event {
                    sim.save_checkpoint(&kill_common::checkpoint_path(&folder, *step))?;
                }
                Ok(())
            }),
        );
        sim.run_steps_observed(limit, &mut observer).unwrap();
        kill_common::wait_for_the_kill();
    }

    let mut straight = new();
    steps(&mut straight, STEPS as usize);
    let folder = temp_path("killed").parent().unwrap().to_path_buf();
    let killed = kill_common::run_and_kill(
        concat!(
            module_path!(),
            "::a_run_killed_at_a_random_step_resumes_from_its_last_checkpoint_in_the_same_bits"
        ),
        &folder,
        2 * EVERY..=STEPS - LEAD - 1,
        LEAD,
    );
    let (at, path) = &killed.checkpoint;
    // The last checkpoint is the one before the kill, or the one before
    // that where the kill fell inside its write.
    assert_eq!(at % EVERY, 0, "{killed:?}");
    assert!(*at <= killed.last_reported, "{killed:?}");
    assert!(at + 2 * EVERY > killed.last_reported, "{killed:?}");
    assert!(killed.last_reported >= killed.drawn, "{killed:?}");

    let mut resumed = Dem::load_checkpoint(law(0.15), ExplicitEuler, path).unwrap();
    assert_eq!(resumed.steps(), *at);
    steps(&mut resumed, (STEPS - at) as usize);
    std::fs::remove_dir_all(&folder).unwrap();
    assert_eq!(resumed.steps(), STEPS);
    assert_eq!(described_contacts(&resumed), described_contacts(&straight));
    assert_eq!(fingerprint(&resumed), fingerprint(&straight));
    assert_eq!(
        resumed.checkpoint().unwrap(),
        straight.checkpoint().unwrap()
    );
}

/// 2 100 discs falling in columns onto the incline, on four threads (the
/// parallel path, from 2 000 particles on), with a fixed skin of 0.2 mm
/// that builds the list again and again: 40 steps, a checkpoint, 40 more,
/// the same bits as 80 straight, and as 80 on one thread.
#[test]
fn the_parallel_path_resumes_in_the_same_bits() {
    let scene = || {
        let mut scene = Scene::new(incline_frame(), Vec2::new(0.0, -G)).unwrap();
        let (r, gap) = (0.01, 1e-5);
        for column in 0..100 {
            let x = 0.5 + column as f64 * (2.0 * r + 3.0 * gap);
            let bottom = above_incline(x, r + gap);
            for row in 0..21 {
                let centre = Point::new(x, bottom.y + row as f64 * (2.0 * r + gap));
                scene.add_circle(centre, r, DENSITY).unwrap();
            }
        }
        scene
    };
    let settings = DemSettings {
        neighbour_skin: Some(2e-4),
        ..SETTINGS
    };
    let law = law(0.15);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(4)
        .build()
        .unwrap();
    let (straight, resumed, builds_at_k) = pool.install(|| {
        let mut straight = Dem::new(scene(), law, ExplicitEuler, settings).unwrap();
        steps(&mut straight, 80);
        let mut first = Dem::new(scene(), law, ExplicitEuler, settings).unwrap();
        steps(&mut first, 40);
        assert!(first.contacts().iter().any(|c| c.regime == Regime::Slip));
        let builds_at_k = first.neighbour_list_builds();
        let bytes = first.checkpoint().unwrap();
        drop(first);
        let mut resumed = Dem::restore(law, ExplicitEuler, &bytes).unwrap();
        steps(&mut resumed, 40);
        (straight, resumed, builds_at_k)
    });
    assert!(resumed.neighbour_list_builds() > builds_at_k);
    assert_eq!(fingerprint(&resumed), fingerprint(&straight));
    let mut serial = Dem::new(scene(), law, ExplicitEuler, settings).unwrap();
    steps(&mut serial, 80);
    assert_eq!(fingerprint(&serial), fingerprint(&straight));
}

/// The explicit Euler step under another name: an integrator of another
/// type.
#[derive(Debug, Clone, Copy, serde::Serialize)]
struct OtherEuler;

impl ExplicitIntegrator for OtherEuler {
    fn step(&self, dt: f64, acceleration: f64, velocity: &mut f64) -> f64 {
        ExplicitEuler.step(dt, acceleration, velocity)
    }
}

fn refusal<T: std::fmt::Debug>(result: dismech::error::Result<T>) -> (String, CheckpointProblem) {
    match result {
        Err(DismechError::Checkpoint { origin, problem }) => (origin, problem),
        other => panic!("not a checkpoint refusal: {other:?}"),
    }
}

/// A checkpoint restored with a law of another friction coefficient, or
/// another integrator, is refused naming what differs; one of the other
/// driver's format version, one cut short, or one with a flipped bit, by
/// what is wrong.
#[test]
fn a_checkpoint_that_does_not_fit_is_refused() {
    let mut sim = Dem::new(incline_scene(), law(0.15), ExplicitEuler, SETTINGS).unwrap();
    steps(&mut sim, 50);
    let bytes = sim.checkpoint().unwrap();

    let (origin, problem) = refusal(Dem::restore(law(0.2), ExplicitEuler, &bytes));
    assert_eq!(origin, "bytes");
    match &problem {
        CheckpointProblem::ModelMismatch { what, .. } => assert_eq!(what, "contact law parameters"),
        other => panic!("{other:?}"),
    }
    assert!(
        problem.to_string().contains("contact law parameters"),
        "{problem}"
    );

    let (_, problem) = refusal(DemSimulation::restore(law(0.15), OtherEuler, &bytes));
    match problem {
        CheckpointProblem::ModelMismatch {
            what,
            checkpoint,
            model,
        } => {
            assert_eq!(what, "integrator type");
            assert!(checkpoint.ends_with("ExplicitEuler"), "{checkpoint}");
            assert!(model.ends_with("OtherEuler"), "{model}");
        }
        other => panic!("{other:?}"),
    }

    let mut newer = bytes.clone();
    newer[8..12].copy_from_slice(&(FORMAT_VERSION + 1).to_le_bytes());
    assert_eq!(
        refusal(Dem::restore(law(0.15), ExplicitEuler, &newer)).1,
        CheckpointProblem::UnsupportedVersion {
            found: FORMAT_VERSION + 1,
            supported: FORMAT_VERSION
        }
    );

    let mut flipped = bytes.clone();
    let last = flipped.len() - 1;
    flipped[last] ^= 1;
    assert!(matches!(
        refusal(Dem::restore(law(0.15), ExplicitEuler, &flipped)).1,
        CheckpointProblem::Corrupt(_)
    ));

    assert_eq!(
        refusal(Dem::restore(law(0.15), ExplicitEuler, b"not a checkpoint")).1,
        CheckpointProblem::NotACheckpoint
    );
}

/// A checkpoint file cut short (as by a copy interrupted) is refused as
/// truncated, naming the file and both lengths; so is every shorter
/// prefix of the bytes, and none panics.
#[test]
fn a_truncated_checkpoint_file_is_refused() {
    let mut sim = Dem::new(incline_scene(), law(0.15), ExplicitEuler, SETTINGS).unwrap();
    steps(&mut sim, 50);
    let path = temp_path("truncated");
    sim.save_checkpoint(&path).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    std::fs::write(&path, &bytes[..bytes.len() / 2]).unwrap();
    let error = Dem::load_checkpoint(law(0.15), ExplicitEuler, &path).unwrap_err();
    assert!(
        error.to_string().contains(&path.display().to_string()),
        "{error}"
    );
    let (origin, problem) = refusal::<Dem>(Err(error));
    assert_eq!(origin, path.display().to_string());
    assert_eq!(
        problem,
        CheckpointProblem::Truncated {
            expected: bytes.len() as u64,
            found: (bytes.len() / 2) as u64
        }
    );
    let missing = Dem::load_checkpoint(law(0.15), ExplicitEuler, &path.with_extension("none"));
    assert!(matches!(
        refusal(missing).1,
        CheckpointProblem::Unreadable(_)
    ));
    std::fs::remove_dir_all(path.parent().unwrap()).unwrap();
    for cut in (0..bytes.len()).step_by(7) {
        assert!(matches!(
            refusal(Dem::restore(law(0.15), ExplicitEuler, &bytes[..cut])).1,
            CheckpointProblem::Truncated { .. }
        ));
    }
}
