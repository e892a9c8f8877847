//! Run a prepared scenario: a progress bar, ParaView frames through
//! [`dismech::vtk`] with their `.pvd` indices, and `summary.json` of the
//! final state, written into a staged folder that takes the output
//! folder's place only once everything is written.

use std::path::{Path, PathBuf};

use dismech::dem::DemSimulation;
use dismech::error::{DismechError, Result};
use dismech::implicit::ImplicitDynamics;
use dismech::io::write_atomically;
use dismech::kinematics::{Advance, Kinematics};
use dismech::kinematics::{PlacedEllipse, PlacedPolygon};
use dismech::law::{BoundedStiffness, ContactLaw, TangentLaw};
use dismech::limit::{analyse, LimitStatus};
use dismech::linsolve::SparseLu;
use dismech::observe::Event;
use dismech::vtk::{implicit_frame, limit_frame, DemFrames, PvdSeries, VtkFrame};
use indicatif::{ProgressBar, ProgressStyle};
use serde_json::{json, Value};

use super::explicit::{ExplicitDem, ExplicitPlan};
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
    let run_error = |error: DismechError| ScenarioError::Run {
        file: file.display().to_string(),
        error: Box::new(error),
    };
    let Prepared { spec, model } = prepared;
    let segments = spec.output.segments.unwrap_or(DEFAULT_SEGMENTS);
    let every = spec.output.frames_every.unwrap_or(DEFAULT_FRAMES_EVERY);
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
            let value = match m.dem {
                ExplicitDem::Spring(mut d) => {
                    run_explicit(&mut d, m.plan, &dir, every, segments, &bar)
                }
                ExplicitDem::Penalty(mut d) => {
                    run_explicit(&mut d, m.plan, &dir, every, segments, &bar)
                }
            }
            .map_err(run_error)?;
            bar.finish_and_clear();
            (value, None)
        }
        Model::Implicit(m) => {
            let bar = bar(m.steps, "steps");
            let value = match m.driver {
                ImplicitDriver::RigidSpring(mut d) => {
                    run_implicit(&mut d, m.dt, m.steps, &dir, every, segments, &bar)
                }
                ImplicitDriver::RigidPenalty(mut d) => {
                    run_implicit(&mut d, m.dt, m.steps, &dir, every, segments, &bar)
                }
                ImplicitDriver::AffineSpring(mut d) => {
                    run_implicit(&mut d, m.dt, m.steps, &dir, every, segments, &bar)
                }
                ImplicitDriver::AffinePenalty(mut d) => {
                    run_implicit(&mut d, m.dt, m.steps, &dir, every, segments, &bar)
                }
            }
            .map_err(run_error)?;
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
fn run_explicit<L>(
    dem: &mut DemSimulation<L>,
    plan: ExplicitPlan,
    dir: &Path,
    every: u64,
    segments: usize,
    bar: &ProgressBar,
) -> Result<Value>
where
    L: ContactLaw<2> + BoundedStiffness<2>,
{
    let mut frames = DemFrames::new(dir, segments)?;
    frames.write(dem)?;
    let start = dem.steps();
    let mut observer = |dem: &DemSimulation<L>, event: &Event<'_>| -> Result<()> {
        match *event {
            Event::Step { step, .. } => {
                let taken = step - start;
                if taken % 100 == 0 {
                    bar.set_position(taken);
                }
                if every > 0 && taken % every == 0 {
                    frames.write(dem)?;
                }
            }
            Event::Check { rest_ratio, .. } => {
                bar.set_message(format!("KE/released = {rest_ratio:.2e}"))
            }
            Event::Finished { time, .. } => {
                if frames.series().last_time() != Some(time) {
                    frames.write(dem)?;
                }
            }
            Event::SubStep { .. } | Event::Halved { .. } => {}
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
            dem.run_steps_observed(n, &mut observer)?;
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
        "steps": dem.steps() - start,
        "time": dem.time(),
        "weight": scene.total_weight(),
        "contacts": dem.contacts().len(),
        "walls": walls,
        "bodies": bodies,
        "frames": frames_written,
    }))
}

/// Run the implicit driver for `steps` calls of `advance(dt)`, writing a
/// frame every `every` calls (and at the start and the end).
fn run_implicit<const N: usize, K, L>(
    model: &mut ImplicitDynamics<N, K, L, Scheme, SparseLu>,
    dt: f64,
    steps: u64,
    dir: &Path,
    every: u64,
    segments: usize,
    bar: &ProgressBar,
) -> Result<Value>
where
    K: Kinematics<N> + Advance<PlacedPolygon, N> + Advance<PlacedEllipse, N>,
    L: TangentLaw<2>,
{
    let mut series = PvdSeries::new(dir)?;
    let write = |series: &mut PvdSeries,
                 model: &ImplicitDynamics<N, K, L, Scheme, SparseLu>|
     -> Result<()> {
        let frame: VtkFrame = implicit_frame(model, segments)?;
        series.write_frame(model.time(), &frame)
    };
    write(&mut series, model)?;
    let (mut substeps, mut halvings) = (0usize, 0usize);
    for step in 1..=steps {
        let report = model.advance(dt)?;
        substeps += report.substeps;
        halvings += report.reductions;
        bar.set_position(step);
        if (every > 0 && step % every == 0) || step == steps {
            write(&mut series, model)?;
        }
    }
    let bodies: Vec<Value> = model
        .bodies()
        .iter()
        .map(|b| {
            let c = b.centroid();
            json!({
                "centroid": [c.x, c.y],
                "displacement": b.displacement.as_slice(),
                "velocity": b.velocity.as_slice(),
                "stress": b.stress.as_slice(),
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
        object.extend(limit_summary(&result, plan.lattice.plate_length()));
    }
    Ok((value, result.status))
}
