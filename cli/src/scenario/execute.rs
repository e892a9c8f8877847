//! Run a prepared scenario: a progress bar, ParaView frames through
//! [`dismech::vtk`] with their `.pvd` indices, and `summary.json` of the
//! final state, written into a staged folder that takes the output
//! folder's place only once everything is written.

use std::path::{Path, PathBuf};

use dismech::checkpoint::CheckpointProblem;
use dismech::dem::DemSimulation;
use dismech::error::{DismechError, Result};
use dismech::grid::{write_rasters_with_crs, Raster, RasterFormat};
use dismech::hpm::{ColumnMaps, HpmIterate, HpmSolver};
use dismech::implicit::ImplicitDynamics;
use dismech::integrate::ExplicitEuler;
use dismech::io::write_atomically;
use dismech::kinematics::{Advance, Kinematics};
use dismech::kinematics::{PlacedEllipse, PlacedPolygon};
use dismech::law::{BoundedStiffness, ContactLaw, TangentLaw};
use dismech::limit::{analyse, model_from_packing, LimitModel, LimitResult, LimitStatus};
use dismech::linsolve::SparseLu;
use dismech::observe::Event;
use dismech::scene::Scene;
use dismech::vtk::{hpm_frame, implicit_frame, limit_frame, DemFrames, PvdSeries, VtkFrame};
use indicatif::{ProgressBar, ProgressStyle};
use serde::de::DeserializeOwned;
use serde::Serialize;
use serde_json::{json, Value};

use super::checkpoint::{
    self, decode, encode, file_name, fingerprint, from_file, mismatch, Driver, RunCounters,
};

use super::analysis::PackingAnalysis;
use super::explicit::{ExplicitDem, ExplicitPlan};
use super::hpm::HpmPlan;
use super::implicit::{ImplicitDriver, Scheme};
use super::limit::LimitPlan;
use super::{Model, Prepared, ScenarioError};
use crate::output::{limit_summary, StagedFolder};

/// Steps between two frames when `[output]` does not say.
pub const DEFAULT_FRAMES_EVERY: u64 = 100;
/// Sides of a circle's or an ellipse's outline when `[output]` does not
/// say.
pub const DEFAULT_SEGMENTS: usize = 32;

/// What a finished run wrote and how it ended.
#[derive(Debug, Clone)]
pub struct Finished {
    /// The output folder.
    pub out: PathBuf,
    /// The summary written as `summary.json`.
    pub summary: Value,
    /// The limit analysis' outcome (limit driver).
    pub limit_status: Option<LimitStatus>,
}

/// Run `prepared` (read from `file`) and write its outputs into `out`,
/// whole or not at all; `progress` shows a progress bar on stderr.
///
/// # Errors
/// [`ScenarioError::Invalid`] for `[output]` values out of range;
/// [`ScenarioError::Run`] with the driver's error where the run stops, or
/// the path that could not be written.
pub fn execute(
    prepared: Prepared,
    file: &Path,
    out: &Path,
    progress: bool,
) -> std::result::Result<Finished, ScenarioError> {
    run(prepared, file, out, progress, None)
}

/// [`execute`] from the scenario's checkpoint `checkpoint` (written by a
/// run of the same scenario with `output.checkpoint_every`): the model is
/// built from the file, its state replaced by the checkpoint's, and the
/// run goes on to the end of its `[run]` (and the command line's limits,
/// counted from the start of the run), as if it had never stopped.
///
/// # Errors
/// Those of [`execute`]; [`ScenarioError::Run`] with
/// [`DismechError::Checkpoint`] naming the checkpoint's path when it
/// cannot be read, is damaged, is another driver's or another model's;
/// [`ScenarioError::Option`] when it lies at or past the run's end.
pub fn resume(
    prepared: Prepared,
    file: &Path,
    out: &Path,
    progress: bool,
    checkpoint: &Path,
) -> std::result::Result<Finished, ScenarioError> {
    run(prepared, file, out, progress, Some(checkpoint))
}

/// Where a run writes its checkpoints, and what it writes beside the
/// driver's state.
struct Saver {
    dir: PathBuf,
    every: u64,
    dt_bits: u64,
    settings: u64,
    /// Checkpoints to keep (`output.keep_checkpoints`); all when none.
    keep: Option<usize>,
    /// The step of the last checkpoint written or resumed from.
    last: Option<u64>,
}

impl Saver {
    /// Write `driver` (a driver's checkpoint) as the checkpoint of
    /// `counters.step`, unless one of that step is written already; then,
    /// with `keep`, remove the older ones beyond it.
    fn save(&mut self, driver: Checkpoint, step: u64, substeps: u64, halvings: u64) -> Result<()> {
        if self.last == Some(step) {
            return Ok(());
        }
        let counters = RunCounters {
            driver: driver.0,
            step,
            substeps,
            halvings,
            dt_bits: self.dt_bits,
            settings: self.settings,
        };
        let bytes = encode(&counters, &driver.1?);
        write_atomically(&file_name(&self.dir, step), &bytes)?;
        self.last = Some(step);
        // Older checkpoints go only once the new one is whole on disk.
        if let Some(keep) = self.keep {
            checkpoint::prune(&self.dir, step, keep)?;
        }
        Ok(())
    }
}

/// A driver's checkpoint, or why it could not be made.
struct Checkpoint(Driver, Result<Vec<u8>>);

/// The bytes of the checkpoint at `path`.
fn read_checkpoint(path: &Path) -> Result<Vec<u8>> {
    std::fs::read(path).map_err(|e| DismechError::Checkpoint {
        origin: path.display().to_string(),
        problem: CheckpointProblem::Unreadable(e.to_string()),
    })
}

/// Refuse a resumed scene whose bodies, walls or gravity are not those
/// `fresh` was built with from the file.
fn same_scene(restored: &Scene, fresh: &Scene, origin: &str) -> Result<()> {
    if restored.particles.len() != fresh.particles.len() {
        return Err(mismatch(
            origin,
            "number of bodies",
            restored.particles.len(),
            fresh.particles.len(),
        ));
    }
    for (k, (a, b)) in restored.particles.iter().zip(&fresh.particles).enumerate() {
        if a.shape != b.shape {
            return Err(mismatch(
                origin,
                format!("body {k}'s shape"),
                format!("{:?}", a.shape),
                format!("{:?}", b.shape),
            ));
        }
        let bits = |p: &dismech::scene::Particle| {
            [
                p.mass.to_bits(),
                p.inertia.to_bits(),
                p.external_force.x.to_bits(),
                p.external_force.y.to_bits(),
            ]
        };
        if bits(a) != bits(b) {
            return Err(mismatch(
                origin,
                format!("body {k}'s mass, inertia or external force"),
                format!("{}, {}, {:?}", a.mass, a.inertia, a.external_force),
                format!("{}, {}, {:?}", b.mass, b.inertia, b.external_force),
            ));
        }
    }
    // A prescribed body keeps its motion: the file's velocity (and a fixed
    // body's position) is the model's, not the run's state.
    for (k, (a, b)) in restored.particles.iter().zip(&fresh.particles).enumerate() {
        if !b.is_prescribed() {
            continue;
        }
        if a.velocity != b.velocity || a.angular_velocity != b.angular_velocity {
            return Err(mismatch(
                origin,
                format!("body {k}'s prescribed velocity and angular velocity"),
                format!("{:?}, {}", a.velocity, a.angular_velocity),
                format!("{:?}, {}", b.velocity, b.angular_velocity),
            ));
        }
        let fixed = b.velocity == dismech::math::Vec2::zeros() && b.angular_velocity == 0.0;
        if fixed && a.pose != b.pose {
            return Err(mismatch(
                origin,
                format!("body {k}'s fixed pose"),
                format!("{:?}", a.pose),
                format!("{:?}", b.pose),
            ));
        }
    }
    if restored.frame != fresh.frame {
        return Err(mismatch(origin, "walls", "other walls", "the file's walls"));
    }
    if restored.gravity.x.to_bits() != fresh.gravity.x.to_bits()
        || restored.gravity.y.to_bits() != fresh.gravity.y.to_bits()
    {
        return Err(mismatch(
            origin,
            "gravity",
            format!("{:?}", restored.gravity),
            format!("{:?}", fresh.gravity),
        ));
    }
    Ok(())
}

/// The explicit driver of `fresh`'s law resumed from `payload` (a
/// driver's checkpoint read from `origin`), its scene checked against
/// `fresh`'s.
fn resume_dem<L>(
    fresh: &DemSimulation<L>,
    payload: &[u8],
    origin: &str,
) -> Result<Box<DemSimulation<L>>>
where
    L: ContactLaw<2> + BoundedStiffness<2> + Serialize + Copy,
    L::State: Serialize + DeserializeOwned,
{
    let restored = DemSimulation::restore(*fresh.law(), ExplicitEuler, payload)
        .map_err(|e| from_file(e, origin))?;
    same_scene(restored.scene(), fresh.scene(), origin)?;
    Ok(Box::new(restored))
}

/// Refuse counters whose `dt` or settings (`what`) are not the file's.
fn same_step(counters: &RunCounters, dt: f64, settings: (&str, u64), origin: &str) -> Result<()> {
    let (what, settings) = settings;
    if counters.dt_bits != dt.to_bits() {
        return Err(mismatch(
            origin,
            "driver.dt",
            f64::from_bits(counters.dt_bits),
            dt,
        ));
    }
    if counters.settings != settings {
        return Err(mismatch(
            origin,
            what,
            "those it was written with",
            "others",
        ));
    }
    Ok(())
}

/// Replace the state of `model` (built from the scenario `file`) by the
/// checkpoint at `path`, checked against the model: its driver, step,
/// settings, scene, and a step before the run's end.
///
/// # Errors
/// [`ScenarioError::Run`] with [`DismechError::Checkpoint`] naming `path`
/// when it cannot be read, is damaged, is another driver's or another
/// model's; [`ScenarioError::Option`] when it lies at or past the run's
/// end, or the model is a limit or HPM analysis.
fn restore(
    model: &mut Model,
    file: &Path,
    path: &Path,
) -> std::result::Result<RunCounters, ScenarioError> {
    let run_error = |error: DismechError| ScenarioError::Run {
        file: file.display().to_string(),
        error: Box::new(error),
    };
    let origin = path.display().to_string();
    let no_steps = || {
        ScenarioError::Option(format!(
            "--resume {origin}: a limit or HPM analysis takes no steps and has no checkpoints"
        ))
    };
    // Refused before the file is read: no file would do.
    if matches!(model, Model::Limit(_) | Model::Hpm(_)) {
        return Err(no_steps());
    }
    let bytes = read_checkpoint(path).map_err(run_error)?;
    let past_end = |step: u64, end: u64| {
        ScenarioError::Option(format!(
            "--resume {origin}: the checkpoint of step {step} lies at or past the run's end at step {end}; nothing is left to run"
        ))
    };
    match model {
        Model::Explicit(m) => {
            let (counters, payload) =
                decode(&bytes, &origin, Driver::Explicit).map_err(run_error)?;
            same_step(
                &counters,
                m.dt,
                ("driver settings", fingerprint(&m.settings)),
                &origin,
            )
            .map_err(run_error)?;
            m.dem = match &m.dem {
                ExplicitDem::Spring(d) => {
                    ExplicitDem::Spring(resume_dem(d, payload, &origin).map_err(run_error)?)
                }
                ExplicitDem::Penalty(d) => {
                    ExplicitDem::Penalty(resume_dem(d, payload, &origin).map_err(run_error)?)
                }
            };
            let k = counters.step;
            match &mut m.plan {
                ExplicitPlan::Steps(n) => {
                    if k >= *n {
                        return Err(past_end(k, *n));
                    }
                }
                ExplicitPlan::ToRest(c) => {
                    if k >= c.max_steps {
                        return Err(past_end(k, c.max_steps));
                    }
                    if k % c.check_every.max(1) != 0 {
                        return Err(run_error(mismatch(
                            &origin,
                            "step, a multiple of run.check_every",
                            k,
                            c.check_every,
                        )));
                    }
                    // The criterion counts the steps of the call.
                    c.max_steps -= k;
                }
            }
            Ok(counters)
        }
        Model::Implicit(m) => {
            let (counters, payload) =
                decode(&bytes, &origin, Driver::Implicit).map_err(run_error)?;
            same_step(
                &counters,
                m.dt,
                (
                    "bodies' sine motions and moving walls' velocities",
                    m.motions,
                ),
                &origin,
            )
            .map_err(run_error)?;
            let restored = match &mut m.driver {
                ImplicitDriver::RigidSpring(d) => d.restore(payload),
                ImplicitDriver::RigidPenalty(d) => d.restore(payload),
                ImplicitDriver::AffineSpring(d) => d.restore(payload),
                ImplicitDriver::AffinePenalty(d) => d.restore(payload),
            };
            restored.map_err(|e| run_error(from_file(e, &origin)))?;
            if counters.step >= m.steps {
                return Err(past_end(counters.step, m.steps));
            }
            Ok(counters)
        }
        Model::Limit(_) | Model::Hpm(_) => Err(no_steps()),
    }
}

/// Check that `prepared` (read from `file`) resumes from the checkpoint
/// `checkpoint` as [`resume`] would, without running it or writing
/// anything (`dismech run --check --resume`): the step it resumes from.
///
/// # Errors
/// Those of [`resume`] before it runs: the checkpoint unreadable,
/// damaged, another driver's or another model's, or at or past the run's
/// end.
pub fn check_resume(
    prepared: Prepared,
    file: &Path,
    checkpoint: &Path,
) -> std::result::Result<u64, ScenarioError> {
    let Prepared { mut model, .. } = prepared;
    restore(&mut model, file, checkpoint).map(|c| c.step)
}

fn run(
    prepared: Prepared,
    file: &Path,
    out: &Path,
    progress: bool,
    resume: Option<&Path>,
) -> std::result::Result<Finished, ScenarioError> {
    let run_error = |error: DismechError| ScenarioError::Run {
        file: file.display().to_string(),
        error: Box::new(error),
    };
    let Prepared {
        spec,
        mut model,
        checkpoints,
    } = prepared;
    let segments = spec.output.segments.unwrap_or(DEFAULT_SEGMENTS);
    let every = spec.output.frames_every.unwrap_or(DEFAULT_FRAMES_EVERY);
    let resumed = match resume {
        Some(path) => Some(restore(&mut model, file, path)?),
        None => None,
    };
    let mut saver = checkpoints.map(|plan| Saver {
        dir: checkpoint::folder(file, out, plan.dir.as_deref()),
        every: plan.every,
        keep: plan.keep,
        dt_bits: match &model {
            Model::Explicit(m) => m.dt.to_bits(),
            Model::Implicit(m) => m.dt.to_bits(),
            Model::Limit(_) | Model::Hpm(_) => 0,
        },
        settings: match &model {
            Model::Explicit(m) => fingerprint(&m.settings),
            Model::Implicit(m) => m.motions,
            _ => 0,
        },
        last: resumed.map(|c| c.step),
    });
    let folder = StagedFolder::new_replacing_runs(out, "summary.json").map_err(run_error)?;
    let dir = folder.path().to_path_buf();
    let bar = |len: u64, unit: &str| -> ProgressBar {
        if !progress {
            return ProgressBar::hidden();
        }
        let bar = ProgressBar::new(len);
        if let Ok(style) = ProgressStyle::with_template(&format!(
            "{{prefix}} [{{elapsed_precise}}] {{bar:30}} {{pos}}/{{len}} {unit}  {{msg}}"
        )) {
            bar.set_style(style);
        }
        bar.set_prefix(
            spec.title
                .clone()
                .unwrap_or_else(|| file.display().to_string()),
        );
        bar
    };
    let (mut result, limit_status) = match model {
        Model::Explicit(m) => {
            let steps = match m.plan {
                ExplicitPlan::ToRest(c) => c.max_steps.min(steps_to(c.max_time, m.dt)),
                ExplicitPlan::Steps(n) => n,
            };
            let bar = bar(steps, "steps");
            let analysis = m.analysis;
            let (value, analysed) = match m.dem {
                ExplicitDem::Spring(mut d) => {
                    run_explicit(&mut d, m.plan, &dir, every, segments, &bar, saver.as_mut())
                        .and_then(|v| {
                            let analysed = analyse_packing(&d, analysis, &v, &dir, segments)?;
                            Ok((v, analysed))
                        })
                }
                ExplicitDem::Penalty(mut d) => {
                    run_explicit(&mut d, m.plan, &dir, every, segments, &bar, saver.as_mut())
                        .and_then(|v| {
                            let analysed = analyse_packing(&d, analysis, &v, &dir, segments)?;
                            Ok((v, analysed))
                        })
                }
            }
            .map_err(run_error)?;
            bar.finish_and_clear();
            let mut value = value;
            let status = analysed.and_then(|(limit, status)| {
                if let Value::Object(map) = &mut value {
                    map.insert("limit".into(), limit);
                }
                status
            });
            (value, status)
        }
        Model::Implicit(m) => {
            let bar = bar(m.steps, "steps");
            let plan = ImplicitRun {
                dt: m.dt,
                steps: m.steps,
                every,
                segments,
                resumed,
            };
            let value = match m.driver {
                ImplicitDriver::RigidSpring(mut d) => {
                    run_implicit(&mut d, &plan, &dir, &bar, saver.as_mut())
                }
                ImplicitDriver::RigidPenalty(mut d) => {
                    run_implicit(&mut d, &plan, &dir, &bar, saver.as_mut())
                }
                ImplicitDriver::AffineSpring(mut d) => {
                    run_implicit(&mut d, &plan, &dir, &bar, saver.as_mut())
                }
                ImplicitDriver::AffinePenalty(mut d) => {
                    run_implicit(&mut d, &plan, &dir, &bar, saver.as_mut())
                }
            }
            .map_err(run_error)?;
            bar.finish_and_clear();
            (value, None)
        }
        Model::Hpm(plan) => {
            let bar = bar(1, "solve");
            bar.set_message(if plan.nonlinear.is_some() {
                "solving the HPM's elastic and nonlinear equations"
            } else {
                "solving the HPM's elastic equations"
            });
            let value = run_hpm(*plan, &dir, &bar).map_err(run_error)?;
            bar.finish_and_clear();
            (value, None)
        }
        Model::Limit(plan) => {
            let bar = bar(1, "LP");
            bar.set_message("solving the limit analysis");
            let (value, status) = run_limit(*plan, &dir, segments).map_err(run_error)?;
            bar.finish_and_clear();
            (value, Some(status))
        }
    };
    if let Value::Object(map) = &mut result {
        map.insert("scenario".into(), json!(file.display().to_string()));
        map.insert("title".into(), json!(spec.title));
        map.insert("driver".into(), json!(spec.driver.kind()));
        map.insert("law".into(), json!(spec.law.kind()));
        if let (Some(path), Some(counters)) = (resume, resumed) {
            map.insert(
                "resumed_from".into(),
                json!({ "checkpoint": path.display().to_string(), "step": counters.step }),
            );
        }
    }
    let text = serde_json::to_string_pretty(&result).map_err(|e| {
        run_error(DismechError::Output {
            path: dir.join("summary.json").display().to_string(),
            message: e.to_string(),
        })
    })?;
    write_atomically(&dir.join("summary.json"), text.as_bytes()).map_err(run_error)?;
    folder.commit().map_err(run_error)?;
    Ok(Finished {
        out: out.to_path_buf(),
        summary: result,
        limit_status,
    })
}

/// Steps of `dt` to reach `time` (for a progress bar's length).
fn steps_to(time: f64, dt: f64) -> u64 {
    (time / dt).ceil().clamp(1.0, 1e15) as u64
}

/// Run the explicit driver to its plan, writing a frame every `every`
/// steps (and at the start and the end).
///
/// With `saver`, a checkpoint is written every `saver.every` steps of the
/// driver's count and at the end. A run to rest is saved only at its rest
/// checks whose test failed (the count of passed checks in a row, which
/// the driver keeps inside the call, is then zero, as a resumed run
/// starts it): at the first such check at or after each due step, and at
/// the end where the last check failed.
#[allow(clippy::too_many_arguments)]
fn run_explicit<L>(
    dem: &mut DemSimulation<L>,
    plan: ExplicitPlan,
    dir: &Path,
    every: u64,
    segments: usize,
    bar: &ProgressBar,
    mut saver: Option<&mut Saver>,
) -> Result<Value>
where
    L: ContactLaw<2> + BoundedStiffness<2> + Serialize,
    L::State: Serialize + DeserializeOwned,
{
    let mut frames = DemFrames::new(dir, segments)?;
    frames.write(dem)?;
    let start = dem.steps();
    let rest = match plan {
        ExplicitPlan::ToRest(c) => Some(c),
        ExplicitPlan::Steps(_) => None,
    };
    // A run to rest: whether the last check passed; the next due step.
    let mut calm = false;
    let mut due = saver
        .as_ref()
        .map_or(u64::MAX, |s| (start / s.every + 1).saturating_mul(s.every));
    let mut observer = |dem: &DemSimulation<L>, event: &Event<'_>| -> Result<()> {
        let snapshot = |dem: &DemSimulation<L>| Checkpoint(Driver::Explicit, dem.checkpoint());
        match *event {
            Event::Step { step, .. } => {
                let taken = step - start;
                if taken % 100 == 0 {
                    bar.set_position(taken);
                }
                if every > 0 && step % every == 0 {
                    frames.write(dem)?;
                }
                if let Some(saver) = saver.as_deref_mut() {
                    if rest.is_none() && step % saver.every == 0 {
                        saver.save(snapshot(dem), step, 0, 0)?;
                    }
                }
            }
            Event::Check { rest_ratio, .. } => {
                bar.set_message(format!("KE/released = {rest_ratio:.2e}"));
                if let (Some(c), Some(saver)) = (rest, saver.as_deref_mut()) {
                    calm = rest_ratio < c.kinetic_to_released_ratio
                        && dem.unbalanced_force_ratio() < c.unbalanced_force_ratio;
                    let step = dem.steps();
                    if !calm && step >= due && step % c.check_every.max(1) == 0 {
                        saver.save(snapshot(dem), step, 0, 0)?;
                        due = (step / saver.every + 1).saturating_mul(saver.every);
                    }
                }
            }
            Event::Finished { time, step } => {
                if frames.series().last_time() != Some(time) {
                    frames.write(dem)?;
                }
                if let Some(saver) = saver.as_deref_mut() {
                    let resumable = match rest {
                        None => true,
                        Some(c) => !calm && step % c.check_every.max(1) == 0,
                    };
                    if resumable {
                        saver.save(snapshot(dem), step, 0, 0)?;
                    }
                }
            }
            // The implicit driver's and HPM's events.
            _ => {}
        }
        Ok(())
    };
    let status = match plan {
        ExplicitPlan::ToRest(criterion) => {
            let outcome = dem.run_to_rest_observed(&criterion, &mut observer)?;
            json!({
                "status": format!("{:?}", outcome.status),
                "kinetic_energy": outcome.kinetic_energy,
                "released_potential_energy": outcome.released_potential_energy,
                "unbalanced_force_ratio": outcome.unbalanced_force_ratio,
                "rest_ratio": outcome.rest_ratio,
            })
        }
        ExplicitPlan::Steps(n) => {
            dem.run_steps_observed(n - start, &mut observer)?;
            json!({ "status": "Steps", "kinetic_energy": dem.kinetic_energy() })
        }
    };
    let frames_written = frames.series().frames();
    let scene = dem.scene();
    let walls: Vec<Value> = (0..scene.frame.walls().len())
        .map(|w| {
            let load = dem.wall_load(w);
            json!({ "name": scene.frame.name(w), "load": [load.x, load.y] })
        })
        .collect();
    let bodies: Vec<Value> = scene
        .particles
        .iter()
        .map(|p| {
            json!({
                "centre": [p.pose.position.x, p.pose.position.y],
                "angle": p.pose.angle,
                "velocity": [p.velocity.x, p.velocity.y],
                "angular_velocity": p.angular_velocity,
            })
        })
        .collect();
    Ok(json!({
        "outcome": status,
        "steps": dem.steps(),
        "time": dem.time(),
        "weight": scene.total_weight(),
        "contacts": dem.contacts().len(),
        "walls": walls,
        "bodies": bodies,
        "frames": frames_written,
    }))
}

/// How an implicit run goes: `steps` calls of `advance(dt)`, a frame
/// every `every` calls (and at the start and the end), from the start or
/// from the counters of a checkpoint.
struct ImplicitRun {
    dt: f64,
    steps: u64,
    every: u64,
    segments: usize,
    resumed: Option<RunCounters>,
}

/// Run the implicit driver to the end of `run`, writing its frames and,
/// with `saver`, a checkpoint every `saver.every` calls and at the end.
fn run_implicit<const N: usize, K, L>(
    model: &mut ImplicitDynamics<N, K, L, Scheme, SparseLu>,
    run: &ImplicitRun,
    dir: &Path,
    bar: &ProgressBar,
    mut saver: Option<&mut Saver>,
) -> Result<Value>
where
    K: Kinematics<N> + Advance<PlacedPolygon, N> + Advance<PlacedEllipse, N>,
    L: TangentLaw<2> + Serialize,
    L::State: Serialize + DeserializeOwned,
{
    let ImplicitRun {
        dt,
        steps,
        every,
        segments,
        resumed,
    } = *run;
    let mut series = PvdSeries::new(dir)?;
    let write = |series: &mut PvdSeries,
                 model: &ImplicitDynamics<N, K, L, Scheme, SparseLu>|
     -> Result<()> {
        let frame: VtkFrame = implicit_frame(model, segments)?;
        series.write_frame(model.time(), &frame)
    };
    write(&mut series, model)?;
    let (start, mut substeps, mut halvings) =
        resumed.map_or((0, 0, 0), |c| (c.step, c.substeps, c.halvings));
    for step in start + 1..=steps {
        let report = model.advance(dt)?;
        substeps += report.substeps as u64;
        halvings += report.reductions as u64;
        bar.set_position(step);
        if (every > 0 && step % every == 0) || step == steps {
            write(&mut series, model)?;
        }
        if let Some(saver) = saver.as_deref_mut() {
            if step % saver.every == 0 || step == steps {
                let driver = Checkpoint(Driver::Implicit, model.checkpoint());
                saver.save(driver, step, substeps, halvings)?;
            }
        }
    }
    let bodies: Vec<Value> = model
        .bodies()
        .iter()
        .enumerate()
        .map(|(k, b)| {
            let c = b.centroid();
            let force = model.contact_force_on(k);
            json!({
                "centroid": [c.x, c.y],
                "displacement": b.displacement.as_slice(),
                "velocity": b.velocity.as_slice(),
                "stress": b.stress.as_slice(),
                "contact_force": [force.x, force.y],
            })
        })
        .collect();
    Ok(json!({
        "outcome": { "status": "Steps", "substeps": substeps, "halvings": halvings },
        "steps": steps,
        "time": model.time(),
        "contacts": model.contacts().len(),
        "bodies": bodies,
        "frames": series.frames(),
    }))
}

/// Solve the limit analysis and write its mechanism (one frame at time
/// 0) where it has one.
fn run_limit(mut plan: LimitPlan, dir: &Path, segments: usize) -> Result<(Value, LimitStatus)> {
    let result = analyse(&plan.model, &mut plan.solver)?;
    let mechanism = matches!(result.status, LimitStatus::Collapse | LimitStatus::ZeroLoad);
    let mut frames = 0;
    if mechanism {
        let mut series = PvdSeries::new(dir)?;
        series.write_frame(0.0, &limit_frame(&plan.model, &result, segments)?)?;
        frames = series.frames();
    }
    let mut value = json!({
        "outcome": { "status": format!("{:?}", result.status) },
        "elements": plan.model.bodies().len(),
        "contacts": plan.model.contacts().len(),
        "frames": frames,
    });
    if let Some(object) = value.as_object_mut() {
        match &plan.lattice {
            Some(lattice) => object.extend(limit_summary(&result, lattice.plate_length())),
            None => object.extend(shapes_summary(&result, &plan.model)),
        }
    }
    Ok((value, result.status))
}

/// The summary of the limit analysis of bodies of shapes: the load (a
/// multiplier, not in units of a plate's C_p), its bounds, the status,
/// the LP's solver and the number of supports.
fn shapes_summary(result: &LimitResult, model: &LimitModel) -> serde_json::Map<String, Value> {
    let mut map = limit_summary(result, f64::NAN);
    map.remove("plate_length");
    for (from, to) in [
        ("p_over_cp", "load"),
        ("kinematic_p_over_cp", "kinematic_load"),
        ("static_p_over_cp", "static_load"),
    ] {
        if let Some(v) = map.remove(from) {
            map.insert(to.into(), v);
        }
    }
    map.insert("supports".into(), json!(model.supports().len()));
    map
}

/// With `analysis`, the limit analysis of `dem`'s packing as it ends
/// ([`model_from_packing`]): its mechanism written as one frame at time 0
/// into `dir/limit/` where it has one, and its summary (as the limit
/// driver's of bodies of shapes) with its status. A run to rest that
/// ended by a limit (`run`'s summary says how it ended), before the
/// packing came to rest, is not analysed: the summary says so, without a
/// status.
fn analyse_packing<L>(
    dem: &DemSimulation<L>,
    analysis: Option<Box<PackingAnalysis>>,
    run: &Value,
    dir: &Path,
    segments: usize,
) -> Result<Option<(Value, Option<LimitStatus>)>>
where
    L: ContactLaw<2>,
{
    let Some(mut analysis) = analysis else {
        return Ok(None);
    };
    let ended = &run["outcome"]["status"];
    if ended != "AtRest" && ended != "Steps" {
        let reason = format!(
            "the run to rest ended by a limit ({}) before the packing came to rest",
            ended.as_str().unwrap_or("?")
        );
        return Ok(Some((
            json!({ "status": "NotAnalysed", "reason": reason }),
            None,
        )));
    }
    let model = model_from_packing(dem.scene(), dem.contacts(), &analysis.settings)?;
    let result = analyse(&model, &mut analysis.solver)?;
    let mechanism = matches!(result.status, LimitStatus::Collapse | LimitStatus::ZeroLoad);
    let mut frames = 0;
    if mechanism {
        let mut series = PvdSeries::new(dir.join("limit"))?;
        series.write_frame(0.0, &limit_frame(&model, &result, segments)?)?;
        frames = series.frames();
    }
    let mut value = json!({
        "elements": model.bodies().len(),
        "contacts": model.contacts().len(),
        "frames": frames,
    });
    if let Some(object) = value.as_object_mut() {
        object.extend(shapes_summary(&result, &model));
    }
    Ok(Some((value, Some(result.status))))
}

/// The prefix of the elastic analysis' maps (`elastic_local_fs.asc`...).
const HPM_ELASTIC_PREFIX: &str = "elastic";
/// The prefix of the nonlinear analysis' maps.
const HPM_NONLINEAR_PREFIX: &str = "nonlinear";

/// Solve the HPM's elastic equations (and, where asked, the nonlinear
/// ones) and write the columns (one frame at time 0, of the elastic
/// analysis) and the maps of each analysis on the ground grid; `bar` tells
/// the nonlinear iterates.
fn run_hpm(plan: HpmPlan, dir: &Path, bar: &ProgressBar) -> Result<Value> {
    let HpmPlan {
        model,
        seismic,
        grids,
        crs,
        nonlinear,
    } = plan;
    let mut solver = HpmSolver::new(&model)?;
    let result = solver.elastic(&model, &seismic)?;
    let safety_factor = result.safety_factor(&model)?;
    let sliding = result.sliding_safety_factor(&model)?;
    let mut series = PvdSeries::new(dir)?;
    series.write_frame(0.0, &hpm_frame(&model, &result)?)?;
    let mut maps = vec![write_maps(
        dir,
        HPM_ELASTIC_PREFIX,
        &result.maps(&model, &grids)?,
        crs.as_deref(),
    )?];
    let nonlinear = match nonlinear {
        None => None,
        Some(settings) => {
            // The bar tells each iterate's out-of-balance force.
            let mut show = |_: &HpmIterate<'_>, event: &Event<'_>| {
                if let Event::Iteration {
                    iteration,
                    residual,
                    ..
                } = *event
                {
                    bar.set_message(format!(
                        "nonlinear HPM: iteration {iteration}, residual {residual:.2e} (to {:.0e})",
                        settings.tolerance
                    ));
                }
                Ok(())
            };
            let result = solver.nonlinear_observed(&model, &seismic, 1.0, &settings, &mut show)?;
            let convergence = &result.convergence;
            let status = if convergence.converged() {
                "Converged"
            } else {
                "NotConverged"
            };
            let (iterations, residual) = (convergence.iterations(), convergence.residual());
            let value = json!({
                "status": status,
                "safety_factor": result.safety_factor(&model)?,
                "sliding_safety_factor": result.sliding_safety_factor(&model)?,
                "iterations": iterations,
                "residual": residual,
                "tolerance": settings.tolerance,
                "max_iterations": settings.max_iterations,
            });
            maps.push(write_maps(
                dir,
                HPM_NONLINEAR_PREFIX,
                &result.maps(&model, &grids)?,
                crs.as_deref(),
            )?);
            Some(value)
        }
    };
    let mut value = json!({
        "outcome": { "status": "Elastic" },
        "safety_factor": safety_factor,
        "sliding_safety_factor": sliding,
        "seismic_coefficient": seismic.coefficient,
        "columns": model.columns.len(),
        "elements": model.elements.len(),
        "layers": model.settings.layers,
        "frames": series.frames(),
        "maps": maps.concat(),
    });
    if let (Some(nonlinear), Value::Object(map)) = (nonlinear, &mut value) {
        map.insert("nonlinear".into(), nonlinear);
    }
    Ok(value)
}

/// Write `maps` into `dir` as `{prefix}_{name}.asc` and `.tif`, each
/// atomically, the GeoTIFFs with the coordinate system `crs` inside and a
/// `.prj` holding it beside each ESRI ASCII grid; returns the names of
/// the files written.
fn write_maps(
    dir: &Path,
    prefix: &str,
    maps: &ColumnMaps,
    crs: Option<&str>,
) -> Result<Vec<String>> {
    let list: Vec<(&str, &Raster)> = maps.maps.iter().map(|(n, r)| (*n, r)).collect();
    let mut names = Vec::new();
    let name = |p: &Path| p.file_name().map(|n| n.to_string_lossy().into_owned());
    for path in write_rasters_with_crs(dir, prefix, &list, &RasterFormat::ALL, crs)? {
        names.extend(name(&path));
        if let (Some(text), RasterFormat::EsriAscii) = (crs, RasterFormat::of_path(&path)) {
            let prj = path.with_extension("prj");
            write_atomically(&prj, text.as_bytes())?;
            names.extend(name(&prj));
        }
    }
    Ok(names)
}
