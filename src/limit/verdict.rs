//! What a solved LP says about a limit analysis: whether its optimum is
//! certified, and what a zero or negative limit load means.
//!
//! **Certificate.** An LP solver's `Solved` means that its own stopping
//! test passed at the tolerance it was given, on its scaled copy of the
//! data; at a loose tolerance (`LinearProgramSolver.tolerance = 1e-3`) a
//! mechanism that is not quite compatible can show a load below the exact
//! one while primal and dual agree. Before a load is called certified the
//! returned point is checked against the LP's own optimality conditions,
//! primal feasibility, dual feasibility and a zero gap, each at most
//! [`CERTIFICATE_TOLERANCE`] relative to the terms it sums
//! ([`crate::lp::Optimality`]); a solution that fails is refused
//! ([`LimitError::UncertifiedOptimum`]).
//!
//! **Zero and negative loads.** The optimum is a dissipation less the
//! power of the dead loads. Where it is zero to the resolution of the data
//! (below [`CERTIFICATE_TOLERANCE`] times the objective's scale) the driver
//! moves the assembly with nothing to overcome: an element that rolls
//! away, a contact without strength. That is reported as
//! [`LimitStatus::ZeroLoad`], not as a collapse. A live load's multiplier
//! λ is the largest for which a statically admissible field exists, and
//! the admissible multipliers form an interval: a negative λ means that
//! λ = 0 is not admissible, so the dead loads alone cannot be carried, and
//! the status is [`LimitStatus::Unbounded`]. A negative plate load is kept
//! as a collapse: a plate may have to hold the assembly back while it
//! moves (a bilateral plate contact, dead loads driving towards it).

use super::analysis::{Driver, LimitResult, LimitStatus};
use super::model::LimitModel;
use super::LimitError;
use crate::error::Result;
use crate::lp::{LinearProgram, LinearProgramSolution, Optimality, Scales};

/// The largest relative residual of the LP's optimality conditions (primal
/// feasibility, dual feasibility, duality gap) that a certified limit load
/// may have; the library's own, whatever tolerance the LP solver was given.
///
/// On the rolling U-model (8, 8, 2) of paper 002 (exact load 14.5902…)
/// Clarabel at its default tolerance 1e-9 leaves residuals of 2e-10 at
/// most (the lattices of the studies, up to k = 40, 3e-11); at a solver
/// tolerance of 1e-6 the primal residual is 2e-8 and the upper bound
/// falls 7e-7 below the exact load, which this tolerance refuses; at 1e-3
/// the residual is 1e-4 and the "bound" 14.53.
pub const CERTIFICATE_TOLERANCE: f64 = 1e-8;

/// Record in `result`, whose status is set, the two bounds of its
/// certified optimum and the limit load the status gives: `load` for a
/// collapse, zero for [`LimitStatus::ZeroLoad`], none otherwise (the
/// bounds too).
pub(super) fn record_bounds(
    result: &mut LimitResult,
    kinematic: f64,
    statical: Option<f64>,
    load: f64,
) {
    let load = match result.status {
        LimitStatus::Collapse => load,
        LimitStatus::ZeroLoad => 0.0,
        _ => return,
    };
    result.kinematic_load = Some(kinematic);
    result.static_load = statical;
    result.load = Some(load);
}

/// The least scales of a limit LP's residuals where the dead loads are
/// the driver: the optimum λ and the forces scale with λ, so a small
/// multiplier (a little cohesion) would leave the solver's rounding large
/// against them. The residuals are then measured against the problem at
/// λ = 1, its real weight: forces of the largest dead load (in the
/// kinematic LP's dual, the static LP's primal) and the dead loads' unit
/// power (the objectives). Other drivers keep the solution's own scales.
pub(super) fn dead_load_scales(
    model: &LimitModel,
    driver: &Driver,
    forces_are_primal: bool,
) -> Scales {
    if *driver != Driver::DeadLoads {
        return Scales::default();
    }
    let weight = model
        .bodies()
        .iter()
        .map(|b| b.load.x.abs().max(b.load.y.abs()))
        .fold(0.0, f64::max);
    Scales {
        primal: if forces_are_primal { weight } else { 0.0 },
        dual: if forces_are_primal { 0.0 } else { weight },
        gap: 1.0,
    }
}

/// Check an optimal `solution` of `lp` against the LP's optimality
/// conditions at [`CERTIFICATE_TOLERANCE`], each residual against at least
/// `floors` (see [`dead_load_scales`]).
///
/// # Errors
/// [`LimitError::UncertifiedOptimum`] when a residual is above the
/// tolerance; a [`crate::error::SolveError`] when the solution does not
/// have the sizes of `lp`.
pub(super) fn certify(
    lp: &LinearProgram,
    solution: &LinearProgramSolution,
    floors: Scales,
) -> Result<Optimality> {
    let optimality = solution.optimality_at_scales(lp, floors)?;
    if optimality.holds(CERTIFICATE_TOLERANCE) {
        Ok(optimality)
    } else {
        Err(LimitError::UncertifiedOptimum {
            solver_status: solution.solver_status.clone(),
            primal_residual: optimality.primal_residual,
            dual_residual: optimality.dual_residual,
            gap: optimality.gap,
            tolerance: CERTIFICATE_TOLERANCE,
        }
        .into())
    }
}

/// The status of a certified optimum: `optimum` is the LP's objective
/// (`±` the load times the driver's speed), `load` the limit load read
/// from it (see the module documentation).
pub(super) fn status_of_load(
    driver: &Driver,
    optimum: f64,
    load: f64,
    optimality: &Optimality,
) -> LimitStatus {
    if optimum.abs() <= CERTIFICATE_TOLERANCE * optimality.scale {
        LimitStatus::ZeroLoad
    } else if matches!(driver, Driver::Live(_)) && load < 0.0 {
        LimitStatus::Unbounded
    } else {
        LimitStatus::Collapse
    }
}
