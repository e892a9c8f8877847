//! The limit driver's model: paper 002's lattice of rigid circles with
//! cohesive rigid-plastic contacts, driven by its plate, solved by
//! Clarabel.

use dismech::error::DismechError;
use dismech::limit::lattice::{Lattice, LatticeKind};
use dismech::limit::LimitModel;
use dismech::lp::LinearProgramSolver;

use super::bodies::{BodySpec, LatticeModel};
use super::check::{combination, count, positive, Refusal};
use super::law::LawSpec;
use super::solvers::LpSolverSpec;
use super::source::{KeyPath, Source};
use super::ScenarioSpec;

/// A limit analysis ready to solve.
pub struct LimitPlan {
    /// The lattice as given.
    pub lattice: Lattice,
    /// Its model.
    pub model: LimitModel,
    /// The LP solver.
    pub solver: LinearProgramSolver,
}

/// Build the limit analysis of `spec`.
pub fn build(source: &Source<'_>, spec: &ScenarioSpec) -> Result<LimitPlan, Refusal> {
    let kind = KeyPath::root("driver").key("kind");
    for (present, table) in [
        (spec.kinematics.is_some(), "kinematics"),
        (spec.boundary.is_some(), "boundary"),
        (spec.integrator.is_some(), "integrator"),
        (spec.linear_solver.is_some(), "linear_solver"),
        (spec.run.is_some(), "run"),
        (spec.loads.gravity.is_some(), "loads"),
        (!spec.loads.forces.is_empty(), "loads"),
        (!spec.loads.tractions.is_empty(), "loads"),
        (spec.loads.seismic.is_some(), "loads"),
    ] {
        if present {
            return Err(combination(
                source,
                &[&kind, &KeyPath::root(table)],
                "the limit driver analyses paper 002's lattice, driven by its plate, as one LP: it takes `[[bodies]]` (one lattice), `[law]` (rigid-plastic) and `[lp_solver]`; remove this table",
            ));
        }
    }
    let bodies = KeyPath::root("bodies");
    count(source, &bodies, spec.bodies.len(), 1, 1).map_err(|_| {
        Box::new(source.at_key(
            &bodies,
            "the limit driver takes exactly one `[[bodies]]` table, of kind = \"lattice\"",
        ))
    })?;
    let path = bodies.index(0);
    let BodySpec::Lattice(spec_lattice) = &spec.bodies[0] else {
        return Err(combination(
            source,
            &[&kind, &path.key("kind")],
            "the limit driver takes one `[[bodies]]` table of kind = \"lattice\" (paper 002's lattice)",
        ));
    };
    let law = KeyPath::root("law");
    let LawSpec::RigidPlastic(strength) = &spec.law else {
        return Err(combination(
            source,
            &[&kind, &law.key("kind")],
            "the limit driver needs a strength: `[law] kind = \"rigid-plastic\"`",
        ));
    };
    let frictional = strength.friction.is_some_and(|f| f != 0.0)
        || strength.friction_angle.is_some_and(|f| f != 0.0)
        || strength.unilateral == Some(true);
    if frictional {
        return Err(combination(
            source,
            &[&path.key("kind"), &law.key("friction")],
            "paper 002's lattice has cohesive, bilateral contacts: `law.cohesion` only (no friction, unilateral = false)",
        ));
    }
    let cohesion = dismech::error::require_non_negative("contact cohesion C", strength.cohesion)
        .map_err(|e| Box::new(source.at_key(&law.key("cohesion"), e.to_string())))?;
    let lattice_kind = match spec_lattice.model {
        LatticeModel::U => LatticeKind::U {
            loaded: spec_lattice.loaded.unwrap_or(1),
        },
        LatticeModel::L => {
            if spec_lattice.loaded.is_some() {
                return Err(combination(
                    source,
                    &[&path.key("model"), &path.key("loaded")],
                    "the L-model's plate loads the whole first column: `loaded` is the U-model's",
                ));
            }
            LatticeKind::L
        }
    };
    let lattice = Lattice {
        kind: lattice_kind,
        m: spec_lattice.m,
        n: spec_lattice.n,
        rolling: spec_lattice.rolling.unwrap_or(true),
        cohesion,
        wall_cohesion: spec_lattice.wall_cohesion.unwrap_or(2.0 * cohesion),
        radius: match spec_lattice.radius {
            Some(r) => positive(source, &path.key("radius"), r)?,
            None => 1.0,
        },
    };
    let model = lattice
        .build()
        .map_err(|e| lattice_error(source, &path, e))?;
    let solver = match &spec.lp_solver {
        None => LinearProgramSolver::default(),
        Some(LpSolverSpec::Clarabel(c)) => {
            let d = LinearProgramSolver::default();
            let table = KeyPath::root("lp_solver");
            LinearProgramSolver {
                tolerance: match c.tolerance {
                    Some(t) => positive(source, &table.key("tolerance"), t)?,
                    None => d.tolerance,
                },
                max_iterations: match c.max_iterations {
                    Some(n) => {
                        count(source, &table.key("max_iterations"), n as usize, 1, 100_000)? as u32
                    }
                    None => d.max_iterations,
                },
                verbose: false,
            }
        }
    };
    Ok(LimitPlan {
        lattice,
        model,
        solver,
    })
}

/// The refusal of an error of [`Lattice::build`].
fn lattice_error(source: &Source<'_>, path: &KeyPath, error: DismechError) -> Refusal {
    let message = error.to_string();
    let key = match &error {
        DismechError::InvalidParameter { name, .. } if name.starts_with("m ") => path.key("m"),
        DismechError::InvalidParameter { name, .. } if name.starts_with("n'") => path.key("loaded"),
        DismechError::InvalidParameter { name, .. } if name.starts_with("n ") => path.key("n"),
        DismechError::InvalidParameter { name, .. } if name.contains("radius") => {
            path.key("radius")
        }
        DismechError::InvalidParameter { name, .. } if name.contains("cohesion") => {
            path.key("wall_cohesion")
        }
        DismechError::LatticeTooLarge { .. } => {
            return Box::new(source.at_keys(&[&path.key("m"), &path.key("n")], message))
        }
        _ => path.clone(),
    };
    Box::new(source.at_key(&key, message))
}
