//! The strength-reduction safety factor (beyond paper 001): the largest
//! factor F by which c and tan φ of the slip surface can be divided while
//! the nonlinear HPM solve still finds equilibrium.
//!
//! F is bracketed by stepping up from 1 (or down, if the material's own
//! strength already fails) and then bisected; "no equilibrium" is a
//! [`Convergence::NotConverged`] of the nonlinear solve within its
//! iteration limit, so F depends (weakly) on that limit, which the result
//! reports. The search steps no further than [`MAX_REDUCTION_FACTOR`] up and
//! [`MIN_REDUCTION_FACTOR`] down: a slide in equilibrium at every factor up to the
//! first, or at none down to the second, has no bracket and gets a typed
//! error rather than a factor that was never bracketed.

use super::analysis::{Convergence, HpmIterate, HpmSolver, NonlinearSettings};
use super::error::HpmError;
use super::material::Seismic;
use super::model::HpmModel;
use super::stiffness::BlockMatrix;
use crate::error::{require_positive, DismechError, Result};
use crate::linsolve::LinearSolver;
use crate::observe::{Event, Observer, Unobserved};

/// The largest factor the search steps up to (past 1000).
pub const MAX_REDUCTION_FACTOR: f64 = 1e3;

/// The smallest factor the search steps down to (below 0.001).
pub const MIN_REDUCTION_FACTOR: f64 = 1e-3;

/// The outcome of a strength-reduction search.
#[derive(Debug, Clone, PartialEq)]
pub struct StrengthReduction {
    /// Largest factor found with equilibrium.
    pub safety_factor: f64,
    /// Smallest factor found without equilibrium.
    pub failed_at: f64,
    /// Every factor tried and whether it converged, in order.
    pub trials: Vec<(f64, Convergence)>,
}

/// Search the strength-reduction factor to a bracket of relative width
/// `resolution`, each trial a nonlinear solve with `solver` (a direct
/// factor, or conjugate gradients).
///
/// # Errors
/// A resolution that is not finite and positive, or settings out of range
/// ([`NonlinearSettings::validate`]), each a
/// [`DismechError::InvalidParameter`] naming it; a failed solve;
/// [`HpmError::StrengthReductionNoFailure`] when every factor up to
/// past [`MAX_REDUCTION_FACTOR`] finds equilibrium, and
/// [`HpmError::StrengthReductionNoEquilibrium`] when none down to
/// below [`MIN_REDUCTION_FACTOR`] does.
pub fn strength_reduction<S: LinearSolver<BlockMatrix>>(
    solver: &mut HpmSolver<S>,
    model: &HpmModel,
    seismic: &Seismic,
    settings: &NonlinearSettings,
    resolution: f64,
) -> Result<StrengthReduction> {
    strength_reduction_observed(
        solver,
        model,
        seismic,
        settings,
        resolution,
        &mut Unobserved,
    )
}

/// [`strength_reduction`], telling `observer` of every iterate of every
/// trial's nonlinear analysis ([`Event::Iteration`], as
/// [`HpmSolver::nonlinear_observed`] does) and of the end of each trial
/// ([`Event::Trial`]: the factor and whether it found equilibrium, with the
/// trial's displacements). The search and its result are those of
/// [`strength_reduction`], bit for bit.
///
/// # Errors
/// Those of [`strength_reduction`], and the first error the observer
/// returns, which stops the search.
pub fn strength_reduction_observed<S, O>(
    solver: &mut HpmSolver<S>,
    model: &HpmModel,
    seismic: &Seismic,
    settings: &NonlinearSettings,
    resolution: f64,
    observer: &mut O,
) -> Result<StrengthReduction>
where
    S: LinearSolver<BlockMatrix>,
    O: for<'a> Observer<HpmIterate<'a>> + ?Sized,
{
    require_positive("strength-reduction resolution", resolution)?;
    settings.validate()?;
    seismic.validate()?;
    let mut trials = Vec::new();
    let mut converges = |f: f64, trials: &mut Vec<(f64, Convergence)>| -> Result<bool> {
        let r = solver.nonlinear_observed(model, seismic, f, settings, observer)?;
        trials.push((f, r.convergence));
        observer.observe(
            &HpmIterate {
                model,
                reduction: f,
                displacements: &r.displacements,
            },
            &Event::Trial {
                factor: f,
                converged: r.convergence.converged(),
            },
        )?;
        Ok(r.convergence.converged())
    };
    let step = 1.25;
    let (mut lo, mut hi) = (1.0, 1.0);
    if converges(1.0, &mut trials)? {
        loop {
            hi = lo * step;
            if !converges(hi, &mut trials)? {
                break;
            }
            lo = hi;
            if lo > MAX_REDUCTION_FACTOR {
                return Err(DismechError::Hpm(HpmError::StrengthReductionNoFailure {
                    factor: lo,
                }));
            }
        }
    } else {
        loop {
            lo = hi / step;
            if converges(lo, &mut trials)? {
                break;
            }
            hi = lo;
            if hi < MIN_REDUCTION_FACTOR {
                return Err(DismechError::Hpm(
                    HpmError::StrengthReductionNoEquilibrium { factor: hi },
                ));
            }
        }
    }
    while hi / lo - 1.0 > resolution {
        let mid = (lo * hi).sqrt();
        if converges(mid, &mut trials)? {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(StrengthReduction {
        safety_factor: lo,
        failed_at: hi,
        trials,
    })
}
