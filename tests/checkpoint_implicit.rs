//! Checkpoints of the implicit driver (DDA): a run stopped after k steps,
//! saved, dropped and restored into the model built again ends N steps in
//! the same bits as the run that never stopped (vertices, stresses,
//! velocities, accelerations, contacts, reports, time), with a block
//! sliding under return mapping at the checkpoint and steps halved around
//! it; and a checkpoint that does not fit is refused by a typed error;
//! and a run that writes its checkpoints through an observer, killed at a
//! random step, resumes from the last one on disk to the same bits.

use crate::kill_common;

use std::path::PathBuf;

use dismech::checkpoint::CheckpointProblem;
use dismech::dda::{Block, BlockMaterial, DdaModel, DdaSettings, PlaneState, Prescribed};
use dismech::error::DismechError;
use dismech::implicit::{BodyGeometry, ContactLaws, StepReport};
use dismech::integrate::Newmark;
use dismech::kinematics::Affine2;
use dismech::law::{FrictionIntegration, PenaltyCoulomb, Regime};
use dismech::linsolve::SparseLu;
use dismech::math::{Point, Vec2};
use dismech::observe::Event;

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

const BETA_DEGREES: f64 = 30.0;

/// Points given along a slope rising at 30° (u along it, v normal to it),
/// in the world.
fn on_slope(points: &[Point]) -> Vec<Point> {
    let (s, c) = BETA_DEGREES.to_radians().sin_cos();
    points
        .iter()
        .map(|p| Point::new(c * p.x - s * p.y, s * p.x + c * p.y))
        .collect()
}

fn law(friction_degrees: f64) -> PenaltyCoulomb {
    PenaltyCoulomb::new(
        1e9,
        friction_degrees.to_radians().tan(),
        FrictionIntegration::ReturnMapping,
    )
    .unwrap()
}

fn settings() -> DdaSettings {
    DdaSettings {
        gravity: Vec2::new(0.0, -9.8),
        overlap_tolerance: 1e-4,
        // The search distance follows the motion from 0.01 m up to this;
        // a step that moves a point further is halved.
        max_search_distance: Some(0.012),
        ..DdaSettings::default()
    }
}

/// A fixed slab at 30° with a block sliding down it (φ = 20°) carrying a
/// smaller block, and a disc rolling ahead of them; a fixed flat base with
/// a stack of two blocks and a disc rolling off another disc.
fn blocks() -> Vec<Block> {
    let m = material();
    let fixed = |mut b: Block| {
        b.prescribed = Some(Prescribed::fixed());
        b
    };
    let slope_centre = |u: f64, v: f64| on_slope(&[Point::new(u, v)])[0];
    vec![
        fixed(Block::new(&on_slope(&rect(-3.0, -0.5, 3.0, 0.0)), m, 0).unwrap()),
        Block::new(&on_slope(&rect(0.5, 0.0, 1.5, 0.4)), m, 1).unwrap(),
        Block::new(&on_slope(&rect(0.7, 0.4, 1.2, 0.7)), m, 2).unwrap(),
        Block::circle(slope_centre(-1.0, 0.2), 0.2, m, 3).unwrap(),
        fixed(Block::new(&rect(5.0, -0.5, 9.0, 0.0), m, 4).unwrap()),
        Block::new(&rect(5.5, 0.0, 6.1, 0.3), m, 5).unwrap(),
        Block::new(&rect(5.6, 0.3, 6.0, 0.5), m, 6).unwrap(),
        Block::circle(Point::new(7.5, 0.15), 0.15, m, 7).unwrap(),
        Block::circle(
            Point::new(7.55, 0.15 + (0.25f64 * 0.25 - 0.05 * 0.05).sqrt()),
            0.1,
            m,
            8,
        )
        .unwrap(),
    ]
}

/// The law of every contact, φ = 20°, but between the two blocks on the
/// slope (group 1), φ = 40°: the small one stays on the sliding one.
fn laws(friction_degrees: f64) -> ContactLaws<PenaltyCoulomb> {
    ContactLaws::uniform(law(friction_degrees)).with_pair(1, 1, law(40.0))
}

fn model_of(
    blocks: Vec<Block>,
    laws: ContactLaws<PenaltyCoulomb>,
    settings: DdaSettings,
) -> DdaModel {
    let mut blocks = blocks;
    blocks[1].group = 1;
    blocks[2].group = 1;
    DdaModel::compose(
        blocks,
        Affine2,
        laws,
        Newmark::dda(),
        SparseLu::default(),
        settings,
    )
    .unwrap()
}

fn model() -> DdaModel {
    model_of(blocks(), laws(20.0), settings())
}

const DT: f64 = 0.01;

/// `count` steps of `DT`, each converged: their reports.
fn advance(model: &mut DdaModel, count: usize) -> Vec<StepReport> {
    (0..count)
        // A step that fails is an error: every step converges.
        .map(|_| model.advance(DT).unwrap())
        .collect()
}

/// Everything a run shows, as bits: time, search distance, each body's
/// geometry, stress, velocity, acceleration and displacement, each
/// contact's bodies, features, state, forces, normal, point, gap and
/// shear.
fn fingerprint(model: &DdaModel) -> Vec<u64> {
    let mut bits = vec![model.time().to_bits(), model.search_distance().to_bits()];
    for b in model.blocks() {
        match b.geometry() {
            BodyGeometry::Polygon(p) => {
                bits.extend([p.centroid().x, p.centroid().y].map(f64::to_bits));
                for v in p.polygon().vertices() {
                    bits.extend([v.x, v.y].map(f64::to_bits));
                }
            }
            BodyGeometry::Ellipse(e) => {
                bits.extend([e.centre().x, e.centre().y].map(f64::to_bits));
                bits.extend(e.axes().iter().map(|v| v.to_bits()));
            }
            BodyGeometry::Wall(s) => {
                bits.extend([s.start.x, s.start.y, s.end.x, s.end.y].map(f64::to_bits))
            }
        }
        bits.extend(b.stress.iter().map(|v| v.to_bits()));
        bits.extend(b.velocity.iter().map(|v| v.to_bits()));
        bits.extend(b.acceleration.iter().map(|v| v.to_bits()));
        bits.extend(b.displacement.iter().map(|v| v.to_bits()));
    }
    for c in model.contacts() {
        bits.extend([c.bodies.0 as u64, c.bodies.1 as u64]);
        bits.push(format!("{:?} {:?}", c.features, c.state.regime).len() as u64);
        bits.extend(
            [
                c.state.normal,
                c.state.shear,
                c.force.0,
                c.force.1,
                c.force_on_a.x,
                c.force_on_a.y,
                c.normal.x,
                c.normal.y,
                c.point.x,
                c.point.y,
                c.gap,
                c.shear,
            ]
            .map(f64::to_bits),
        );
    }
    bits
}

/// The contacts described (bodies, features, regime), beside the bits.
fn described_contacts(model: &DdaModel) -> Vec<String> {
    model
        .contacts()
        .iter()
        .map(|c| format!("{:?} {:?} {:?}", c.bodies, c.features, c.state.regime))
        .collect()
}

/// The reports as text: Rust writes each float so that it reads back to
/// the same bits.
fn described_reports(reports: &[StepReport]) -> Vec<String> {
    reports.iter().map(|r| format!("{r:?}")).collect()
}

fn temp_path(name: &str) -> PathBuf {
    std::env::temp_dir()
        .join(format!(
            "dismech-checkpoint-implicit-{}-{name}",
            std::process::id()
        ))
        .join(format!("{name}.ckpt"))
}

/// 60 steps of 0.01 s straight, or 30, a checkpoint to bytes (and after
/// 15 more, one through a file), the model dropped, built again, restored
/// and advanced to 60. At the checkpoint the block slides on the slope
/// (its contacts slip under return mapping) with the small block stuck on
/// it, the search distance follows the motion, and steps are being halved
/// (a body moves more than the largest search distance in 0.01 s) before
/// and after it. Every bit is the same, the reports of the steps too, and
/// the checkpoints at the end.
#[test]
fn a_resumed_dda_run_ends_in_the_same_bits() {
    let (n, k) = (60, 30);
    let mut straight = model();
    let straight_reports = advance(&mut straight, n);

    let mut first = model();
    advance(&mut first, k);
    let slipping: Vec<_> = (first.contacts().iter())
        .filter(|c| c.state.regime == Some(Regime::Slip))
        .map(|c| c.bodies)
        .collect();
    assert!(slipping.contains(&(1, 0)), "slipping: {slipping:?}");
    let stuck = (first.contacts().iter())
        .any(|c| c.bodies == (2, 1) && c.state.regime == Some(Regime::Stick));
    assert!(stuck, "{:?}", described_contacts(&first));
    let halved = |reports: &[StepReport]| reports.iter().filter(|r| r.reductions > 0).count();
    assert!(halved(&straight_reports[k - 5..k]) > 0);
    assert!(halved(&straight_reports[k..k + 5]) > 0);
    let bytes = first.checkpoint().unwrap();
    let at_k = fingerprint(&first);
    drop(first);

    let mut resumed = model();
    resumed.restore(&bytes).unwrap();
    assert_eq!(fingerprint(&resumed), at_k);
    assert_eq!(resumed.checkpoint().unwrap(), bytes);
    let mut resumed_reports = advance(&mut resumed, (n - k) / 2);
    let path = temp_path("slope");
    resumed.save_checkpoint(&path).unwrap();
    drop(resumed);
    let mut resumed = model();
    resumed.load_checkpoint(&path).unwrap();
    resumed_reports.extend(advance(&mut resumed, (n - k) / 2));
    std::fs::remove_dir_all(path.parent().unwrap()).unwrap();

    assert_eq!(
        described_reports(&resumed_reports),
        described_reports(&straight_reports[k..])
    );
    assert_eq!(described_contacts(&resumed), described_contacts(&straight));
    assert_eq!(fingerprint(&resumed), fingerprint(&straight));
    assert_eq!(
        resumed.checkpoint().unwrap(),
        straight.checkpoint().unwrap()
    );
}

/// The slope run for 60 calls of `advance(0.01)` by a child process whose
/// observer writes a checkpoint at the end of every third call (at
/// [`Event::Finished`], between calls: a checkpoint at a sub-step inside a
/// call would not resume to the same bits), a file per checkpoint, each
/// written atomically, and which is killed by SIGKILL at a random call
/// (see `kill_common`), most often inside the next one; resumed from the
/// last checkpoint on disk into the model built again and advanced to the
/// 60th call, it ends in the same bits as the run never interrupted.
#[test]
fn a_run_killed_at_a_random_step_resumes_from_its_last_checkpoint_in_the_same_bits() {
    const CALLS: u64 = 60;
    const EVERY: u64 = 3;
    const LEAD: u64 = 10;
    if let Some((folder, limit)) = kill_common::child() {
        let mut run = model();
        for call in 1..=limit {
            let mut observer = |model: &DdaModel, event: &Event<'_>| {
                if let Event::Finished { .. } = event {
                    kill_common::report_progress(call);
                    if call % EVERY == 0 {
                        model.save_checkpoint(&kill_common::checkpoint_path(&folder, call))?;
                    }
                }
                Ok(())
            };
            run.advance_observed(DT, &mut observer).unwrap();
        }
        kill_common::wait_for_the_kill();
    }

    let mut straight = model();
    let straight_reports = advance(&mut straight, CALLS as usize);
    let folder = temp_path("killed").parent().unwrap().to_path_buf();
    let killed = kill_common::run_and_kill(
        concat!(
            module_path!(),
            "::a_run_killed_at_a_random_step_resumes_from_its_last_checkpoint_in_the_same_bits"
        ),
        &folder,
        2 * EVERY..=CALLS - LEAD - 1,
        LEAD,
    );
    let (at, path) = &killed.checkpoint;
    // The last checkpoint is the one before the kill, or the one before
    // that where the kill fell inside its write.
    assert_eq!(at % EVERY, 0, "{killed:?}");
    assert!(*at <= killed.last_reported, "{killed:?}");
    assert!(at + 2 * EVERY > killed.last_reported, "{killed:?}");
    assert!(killed.last_reported >= killed.drawn, "{killed:?}");

    let mut resumed = model();
    resumed.load_checkpoint(path).unwrap();
    let resumed_reports = advance(&mut resumed, (CALLS - at) as usize);
    std::fs::remove_dir_all(&folder).unwrap();
    assert_eq!(
        described_reports(&resumed_reports),
        described_reports(&straight_reports[*at as usize..])
    );
    assert_eq!(described_contacts(&resumed), described_contacts(&straight));
    assert_eq!(fingerprint(&resumed), fingerprint(&straight));
    assert_eq!(
        resumed.checkpoint().unwrap(),
        straight.checkpoint().unwrap()
    );
}

fn refusal(result: dismech::error::Result<()>) -> (String, CheckpointProblem) {
    match result {
        Err(DismechError::Checkpoint { origin, problem }) => (origin, problem),
        other => panic!("not a checkpoint refusal: {other:?}"),
    }
}

fn mismatch(result: dismech::error::Result<()>) -> (String, String, String) {
    match refusal(result).1 {
        CheckpointProblem::ModelMismatch {
            what,
            checkpoint,
            model,
        } => (what, checkpoint, model),
        other => panic!("not a mismatch: {other:?}"),
    }
}

/// A checkpoint restored into a model of one body less, a law of another
/// friction angle, other settings, a body of another material or an
/// extra fixed point is refused naming the difference, and the model is
/// left as it was; an explicit driver's checkpoint is refused as another
/// driver's.
#[test]
fn a_checkpoint_restored_into_another_model_is_refused() {
    let mut run = model();
    advance(&mut run, 3);
    let bytes = run.checkpoint().unwrap();

    let mut fewer = blocks();
    fewer.pop();
    let mut smaller = DdaModel::compose(
        fewer,
        Affine2,
        laws(20.0),
        Newmark::dda(),
        SparseLu::default(),
        settings(),
    )
    .unwrap();
    assert_eq!(
        mismatch(smaller.restore(&bytes)),
        ("number of bodies".into(), "9".into(), "8".into())
    );
    assert_eq!(smaller.time(), 0.0);
    let message = smaller.restore(&bytes).unwrap_err().to_string();
    assert!(message.contains("number of bodies"), "{message}");

    let mut other_law = model_of(blocks(), laws(25.0), settings());
    assert_eq!(
        mismatch(other_law.restore(&bytes)).0,
        "contact laws parameters"
    );

    let damped = DdaSettings {
        mass_damping: 0.1,
        ..settings()
    };
    let mut other_settings = model_of(blocks(), laws(20.0), damped);
    assert_eq!(mismatch(other_settings.restore(&bytes)).0, "settings");

    let mut softer = blocks();
    let stiff = BlockMaterial {
        youngs_modulus: 2e9,
        ..material()
    };
    softer[5] = Block::new(&rect(5.5, 0.0, 6.1, 0.3), stiff, 5).unwrap();
    let mut other_material = model_of(softer, laws(20.0), settings());
    let (what, saved, supplied) = mismatch(other_material.restore(&bytes));
    assert_eq!(what, "body 5's material");
    assert!(saved.contains("1000000000.0") && supplied.contains("2000000000.0"));

    let mut pinned = model();
    pinned
        .add_fixed_point(1, Point::new(1.0, 0.5), 1e8)
        .unwrap();
    assert_eq!(mismatch(pinned.restore(&bytes)).0, "number of fixed points");

    // The explicit driver's checkpoint.
    use dismech::dem::DemSimulation;
    use dismech::explicit::DemSettings;
    use dismech::integrate::ExplicitEuler;
    use dismech::law::SpringDashpotCoulomb;
    use dismech::scene::{Frame, Scene};
    let mut scene = Scene::new(Frame::open_box(1.0, 1.0).unwrap(), Vec2::new(0.0, -9.8)).unwrap();
    scene.add_circle(Point::new(0.5, 0.5), 0.1, 2600.0).unwrap();
    let law = SpringDashpotCoulomb::katsuki(1e8, 0.3, 0.25, 0.5).unwrap();
    let dem: DemSimulation<SpringDashpotCoulomb> =
        DemSimulation::new(scene, law, ExplicitEuler, DemSettings::default()).unwrap();
    let mut target = model();
    assert_eq!(
        refusal(target.restore(&dem.checkpoint().unwrap())).1,
        CheckpointProblem::WrongDriver {
            found: "explicit".into(),
            expected: "implicit"
        }
    );
    assert!(matches!(
        refusal(
            DemSimulation::<SpringDashpotCoulomb>::restore(law, ExplicitEuler, &bytes).map(|_| ())
        )
        .1,
        CheckpointProblem::WrongDriver { .. }
    ));
}

/// A checkpoint file cut short is refused as truncated, naming the file
/// and both lengths, and leaves the model as it was; so is every shorter
/// prefix of the bytes.
#[test]
fn a_truncated_checkpoint_file_is_refused() {
    let mut run = model();
    advance(&mut run, 3);
    let path = temp_path("truncated");
    run.save_checkpoint(&path).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let cut = bytes.len() - 10;
    std::fs::write(&path, &bytes[..cut]).unwrap();
    let mut target = model();
    let before = fingerprint(&target);
    let (origin, problem) = refusal(target.load_checkpoint(&path));
    assert_eq!(origin, path.display().to_string());
    assert_eq!(
        problem,
        CheckpointProblem::Truncated {
            expected: bytes.len() as u64,
            found: cut as u64
        }
    );
    assert_eq!(fingerprint(&target), before);
    std::fs::remove_dir_all(path.parent().unwrap()).unwrap();
    for cut in (0..bytes.len()).step_by(5) {
        assert!(matches!(
            refusal(target.restore(&bytes[..cut])).1,
            CheckpointProblem::Truncated { .. }
        ));
    }
}
