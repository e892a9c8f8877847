//! Example 3 (back storage sand pressure): a settled pattern, its back wall
//! replaced by a uniform horizontal pressure on the back particles and its
//! frame closed by a lid (a rigid rectangular frame), is run to rest again;
//! the front-wall pressure per unit back pressure against height is
//! Fig. 8(c).
//!
//! The back pressure is [`BACK_PRESSURE`] = 100 kPa, about five times the
//! vertical pressure of the filling on the floor, so that the front-wall
//! pressure is mostly the back pressure's; self-weight stays on. Where the
//! front-wall force acts is summarised by the height of its centroid over
//! the filling height: 1/3 for a triangular distribution growing with
//! depth, 1/2 for a uniform one.

use std::path::Path;

use super::patterns::Pattern;
use super::settle_scene;
use super::shape_anisotropy::{picture, PatternRun};
use crate::reproduce::fill_patterns::back_pressure_scene;
use dismech::dem::DemSimulation;
use dismech::error::Result;
use dismech::explicit::{ContactTarget, RunOutcome};
use dismech::integrate::ExplicitEuler;
use dismech::law::SpringDashpotCoulomb;
use dismech::math::Vec2;
use dismech_cli::output::plot::{line_chart, Series};
use dismech_cli::output::{write_csv, Check, Reference, Reported, Rule};

/// The uniform back storage sand pressure (Pa).
pub const BACK_PRESSURE: f64 = 100e3;
/// Gap between the top of the settled filling and the lid (m).
pub const LID_GAP: f64 = 1e-3;

/// A pattern under back pressure, at rest.
#[derive(Debug)]
pub struct BackPressureRun {
    /// The simulation at rest under the back pressure.
    pub sim: DemSimulation<SpringDashpotCoulomb, ExplicitEuler>,
    /// How the run ended.
    pub outcome: RunOutcome,
    /// Filling height H before loading (m).
    pub fill_height: f64,
    /// Total applied back force `p · H` (N/m).
    pub applied: f64,
    /// `(height, P_h / d / p)` at each front-wall contact, by height.
    pub front_profile: Vec<(f64, f64)>,
}

impl BackPressureRun {
    /// Sum of the reactions of all walls on the particles (N/m).
    pub fn wall_reaction(&self) -> Vec2 {
        -(0..self.sim.scene().frame.walls().len())
            .map(|w| self.sim.wall_load(w))
            .sum::<Vec2>()
    }

    /// Reaction of one named wall on the particles (N/m).
    pub fn reaction_of(&self, name: &str) -> Vec2 {
        self.sim
            .scene()
            .frame
            .index_of(name)
            .map(|w| -self.sim.wall_load(w))
            .unwrap_or_default()
    }

    /// |Σ horizontal wall reactions + applied back force| / applied force.
    pub fn horizontal_imbalance(&self) -> f64 {
        (self.wall_reaction().x + self.applied).abs() / self.applied
    }

    /// Σ vertical wall reactions / weight.
    pub fn vertical_ratio(&self) -> f64 {
        self.wall_reaction().y / self.sim.scene().total_weight()
    }

    /// `(height, normal force)` of each contact of the front wall.
    fn front_forces(&self) -> Vec<(f64, f64)> {
        let Some(front) = self.sim.scene().frame.index_of("front") else {
            return Vec::new();
        };
        self.sim
            .contacts()
            .iter()
            .filter(|c| c.target == ContactTarget::Wall(front))
            .map(|c| (c.point.y, c.force_on_target.x))
            .collect()
    }

    /// Height of the centroid of the front-wall normal force over the
    /// filling height (1/3 triangular growing with depth, 1/2 uniform).
    pub fn front_centroid_ratio(&self) -> f64 {
        let forces = self.front_forces();
        let moment: f64 = forces.iter().map(|(y, f)| y * f).sum();
        let total: f64 = forces.iter().map(|(_, f)| f).sum();
        moment / total / self.fill_height
    }

    /// Share of the front-wall normal force carried by its lower half.
    pub fn front_lower_half_share(&self) -> f64 {
        let forces = self.front_forces();
        let lower: f64 = forces
            .iter()
            .filter(|(y, _)| *y < 0.5 * self.fill_height)
            .map(|(_, f)| f)
            .sum();
        let total: f64 = forces.iter().map(|(_, f)| f).sum();
        lower / total
    }
}

/// Load the settled `run` with the back pressure and run it to rest;
/// `on_check(time, ratio)` reports progress.
pub fn run_back_pressure(
    run: &PatternRun,
    on_check: impl FnMut(f64, f64),
) -> Result<BackPressureRun> {
    let fill_height = run.equilibrium.fill_height;
    let scene = back_pressure_scene(&run.sim, BACK_PRESSURE, fill_height, LID_GAP)?;
    let applied: f64 = scene.particles.iter().map(|p| p.external_force.x).sum();
    let (sim, outcome) = settle_scene(scene, 1e-3, on_check)?;
    let front_profile = front_profile(&sim, BACK_PRESSURE);
    Ok(BackPressureRun {
        sim,
        outcome,
        fill_height,
        applied,
        front_profile,
    })
}

/// `(height, P_h / d / p)` at each contact of the `front` wall, d being the
/// mean distance between its contacts.
fn front_profile(
    sim: &DemSimulation<SpringDashpotCoulomb, ExplicitEuler>,
    pressure: f64,
) -> Vec<(f64, f64)> {
    super::wall_pressure_profile(sim, "front", 2.0 * super::patterns::EQUIVALENT_RADIUS)
        .into_iter()
        .map(|(h, p)| (h, p / pressure))
        .collect()
}

/// The paper's description of the front-wall distribution of a pattern
/// (Fig. 8(b)–(c) and the text of Example 3).
fn paper_shape(name: &str) -> &'static str {
    match name {
        "A" | "B" | "D" => "triangular, larger at the bottom",
        "C" => "larger at the upper part",
        "E" => "uniform",
        _ => "not described",
    }
}

/// The centroid height ratio of the paper's description: 1/3 for the
/// triangular distributions, 1/2 for the uniform one, none for C (only
/// "larger at the upper part").
fn paper_centroid(name: &str) -> Option<f64> {
    match name {
        "A" | "B" | "D" => Some(1.0 / 3.0),
        "E" => Some(0.5),
        _ => None,
    }
}

/// How a front-wall distribution reads from its centroid height ratio:
/// below 0.42 (nearer the triangle's 1/3 than the uniform 1/2) triangular,
/// up to 0.58 close to uniform, above that larger at the upper part.
pub fn shape_of(centroid_ratio: f64) -> &'static str {
    if centroid_ratio < 0.42 {
        "triangular, larger at the bottom"
    } else if centroid_ratio <= 0.58 {
        "close to uniform"
    } else {
        "larger at the upper part"
    }
}

/// Checks, reported values, CSV files and plots of Example 3; also returns
/// the rows of the report table. File names are pushed to `files`.
pub(super) fn example3_outputs(
    dir: &Path,
    runs: &[(Pattern, BackPressureRun)],
    files: &mut Vec<String>,
) -> Result<(Vec<Check>, Vec<Reported>, Vec<String>)> {
    let mut checks = Vec::new();
    let mut values = Vec::new();
    let mut table = Vec::new();
    let mut rows = Vec::new();
    let mut contact_rows = Vec::new();
    let mut series = Vec::new();
    for (index, (pattern, run)) in runs.iter().enumerate() {
        let name = pattern.name;
        let horizontal = run.horizontal_imbalance();
        let vertical = run.vertical_ratio();
        checks.push(Check::new(
            format!("ex3.horizontal_equilibrium.{name}"),
            format!(
                "pattern {name} under {} kPa back pressure: |sum of horizontal wall reactions + applied back force| / applied force at rest",
                BACK_PRESSURE / 1e3
            ),
            "-",
            horizontal,
            &Rule::near(Reference::number(0.0), 0.005),
        ));
        checks.push(Check::new(
            format!("ex3.vertical_reaction_ratio.{name}"),
            format!(
                "pattern {name} under back pressure: sum of vertical wall reactions / total weight at rest"
            ),
            "-",
            vertical,
            &Rule::near(Reference::number(1.0), 0.005),
        ));
        let centroid = run.front_centroid_ratio();
        values.push(Reported {
            id: format!("ex3.front_centroid.{name}"),
            description: format!(
                "pattern {name}: height of the resultant front-wall force / H under back pressure (1/3 triangular, 1/2 uniform); reads as {}; paper: {}",
                shape_of(centroid),
                paper_shape(name)
            ),
            paper: paper_centroid(name),
            computed: centroid,
            unit: "-".into(),
        });
        let lower = run.front_lower_half_share();
        let front = run.reaction_of("front").x.abs() / run.applied;
        table.push(format!(
            "| {name} | {} | {:.3} | {:.3} | {:.3} | {} | {} |",
            pattern.description,
            front,
            centroid,
            lower,
            shape_of(centroid),
            paper_shape(name)
        ));
        rows.push(vec![
            index as f64,
            run.sim.scene().particles.len() as f64,
            run.outcome.time,
            run.fill_height,
            run.applied,
            run.reaction_of("front").x,
            run.reaction_of("bottom").x,
            run.reaction_of("lid").x,
            vertical,
            horizontal,
            centroid,
            lower,
        ]);
        contact_rows.extend(
            run.front_profile
                .iter()
                .map(|&(h, ratio)| vec![index as f64, h, ratio]),
        );
        series.push(Series {
            name: format!("{name}: {}", pattern.description),
            points: run.front_profile.iter().map(|&(h, r)| (r, h)).collect(),
            markers: true,
        });
        picture(
            &dir.join(format!("ex3_pattern_{name}.svg")),
            &format!(
                "Example 3, pattern {name}: contact forces under back pressure (cf. Fig. 8(b))"
            ),
            &run.sim,
        )?;
        files.push(format!("ex3_pattern_{name}.svg"));
    }
    write_csv(
        &dir.join("ex3_patterns.csv"),
        &[
            "pattern_index_a0_to_e4",
            "particles",
            "time_to_rest_s",
            "fill_height_m",
            "applied_back_force_n_per_m",
            "front_reaction_x_n_per_m",
            "bottom_reaction_x_n_per_m",
            "lid_reaction_x_n_per_m",
            "vertical_reaction_ratio",
            "horizontal_imbalance",
            "front_centroid_over_h",
            "front_lower_half_share",
        ],
        &rows,
    )?;
    files.push("ex3_patterns.csv".into());
    write_csv(
        &dir.join("ex3_front_pressure.csv"),
        &[
            "pattern_index_a0_to_e4",
            "height_m",
            "pressure_over_back_pressure",
        ],
        &contact_rows,
    )?;
    files.push("ex3_front_pressure.csv".into());
    line_chart(
        &dir.join("ex3_front_pressure.svg"),
        "Example 3: front-wall pressure / back pressure vs height (cf. Fig. 8(c))",
        "front-wall pressure P_h / d per unit back pressure",
        "height above the floor (m)",
        &series,
    )?;
    files.push("ex3_front_pressure.svg".into());
    Ok((checks, values, table))
}
