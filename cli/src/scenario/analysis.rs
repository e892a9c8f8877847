//! `[limit_analysis]`: the limit analysis of the explicit driver's final
//! packing ([`dismech::limit::model_from_packing`]), solved by the LP
//! after the run: the packing-LP composition from a file.

use dismech::law::RigidPlastic;
use dismech::limit::PackingLimitSettings;
use dismech::lp::LinearProgramSolver;
use dismech::scene::Scene;
use serde::Deserialize;

use super::check::{self, combination, non_negative, Refusal};
use super::law::RigidPlasticSpec;
use super::source::{KeyPath, Source};
use super::ScenarioSpec;

/// The limit analysis of the run's final packing.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LimitAnalysisSpec {
    /// The frame wall that becomes the loading plate, pushed along its
    /// inner normal at unit speed (`left`, `right`, `bottom` of an open
    /// box, or a name of `boundary.names`).
    pub plate_wall: String,
    /// Whether the elements may rotate (true by default).
    pub rolling: Option<bool>,
    /// Include the particles' weights under `loads.gravity` as dead loads
    /// (false by default).
    pub self_weight: Option<bool>,
    /// Strength of the contacts between particles.
    pub contacts: RigidPlasticSpec,
    /// Strength of the contacts with the walls but the plate; that of
    /// `contacts` by default.
    pub walls: Option<RigidPlasticSpec>,
    /// Strength of the contacts with the plate; that of `walls` by
    /// default.
    pub plate: Option<RigidPlasticSpec>,
}

/// A limit analysis ready to run on the final packing.
#[derive(Debug, Clone)]
pub struct PackingAnalysis {
    /// The settings of [`dismech::limit::model_from_packing`].
    pub settings: PackingLimitSettings,
    /// The LP solver.
    pub solver: LinearProgramSolver,
}

/// The strength of the table at `table`.
fn strength(
    source: &Source<'_>,
    table: &KeyPath,
    spec: &RigidPlasticSpec,
) -> Result<RigidPlastic, Refusal> {
    let cohesion = non_negative(source, &table.key("cohesion"), spec.cohesion)?;
    let mu = check::friction(source, table, spec.friction, spec.friction_angle, Some(0.0))?;
    RigidPlastic::coulomb(cohesion, mu, spec.unilateral.unwrap_or(false))
        .map_err(|e| Box::new(source.at_key(table, e.to_string())))
}

/// The analysis of `spec.limit_analysis` (none where absent), checked
/// against `scene` (the explicit driver's scene, built from the file):
/// the plate names one of its walls, and no body is fixed or driven.
///
/// # Errors
/// A refusal naming `limit_analysis.plate_wall` (no such wall), a
/// strength's key, or a prescribed body's `motion.kind` beside
/// `limit_analysis`.
pub fn build(
    source: &Source<'_>,
    spec: &ScenarioSpec,
    scene: &Scene,
    entry_of: &[usize],
) -> Result<Option<Box<PackingAnalysis>>, Refusal> {
    let Some(analysis) = &spec.limit_analysis else {
        return Ok(None);
    };
    let table = KeyPath::root("limit_analysis");
    if scene.frame.index_of(&analysis.plate_wall).is_none() {
        let names: Vec<String> = (0..scene.frame.walls().len())
            .map(|w| format!("\"{}\"", scene.frame.name(w).unwrap_or_default()))
            .collect();
        return Err(Box::new(source.at_key(
            &table.key("plate_wall"),
            format!(
                "no wall of the boundary has this name: give one of {}",
                names.join(", ")
            ),
        )));
    }
    if let Some(k) = scene.particles.iter().position(|p| p.is_prescribed()) {
        let entry = KeyPath::root("bodies").index(entry_of.get(k).copied().unwrap_or(0));
        return Err(combination(
            source,
            &[&entry.key("motion").key("kind"), &table],
            &format!(
                "body {k} is fixed or driven: it has no counterpart in the limit analysis of the packing, whose fixed boundaries are the frame's walls"
            ),
        ));
    }
    let contacts = strength(source, &table.key("contacts"), &analysis.contacts)?;
    let walls = match &analysis.walls {
        Some(w) => strength(source, &table.key("walls"), w)?,
        None => contacts,
    };
    let plate = match &analysis.plate {
        Some(p) => strength(source, &table.key("plate"), p)?,
        None => walls,
    };
    Ok(Some(Box::new(PackingAnalysis {
        settings: PackingLimitSettings {
            rolling: analysis.rolling.unwrap_or(true),
            contact_law: contacts,
            wall_law: walls,
            plate_law: plate,
            plate_wall: analysis.plate_wall.clone(),
            self_weight: analysis.self_weight.unwrap_or(false),
        },
        solver: super::limit::lp_solver(source, spec)?,
    })))
}
