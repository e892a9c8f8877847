//! What an LP solve returns.

use clarabel::solver::SolverStatus;

/// Termination status of a linear program solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LpStatus {
    /// Solved to the requested tolerance.
    Optimal,
    /// Solved only to Clarabel's reduced tolerances.
    AlmostOptimal,
    /// No feasible point exists (also reported for Clarabel's reduced-accuracy
    /// infeasibility certificate). `equality_duals`/`inequality_duals` hold
    /// the certificate.
    PrimalInfeasible,
    /// The dual is infeasible, i.e. the primal is unbounded below (if
    /// feasible); also reported for the reduced-accuracy certificate. `x`
    /// holds an improving ray.
    DualInfeasible,
    /// The iteration limit was reached.
    MaxIterations,
    /// The solver stopped on a numerical error or for lack of progress.
    NumericalError,
    /// Any other termination (e.g. time limit).
    Other,
}

impl From<SolverStatus> for LpStatus {
    fn from(status: SolverStatus) -> Self {
        match status {
            SolverStatus::Solved => Self::Optimal,
            SolverStatus::AlmostSolved => Self::AlmostOptimal,
            SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => {
                Self::PrimalInfeasible
            }
            SolverStatus::DualInfeasible | SolverStatus::AlmostDualInfeasible => {
                Self::DualInfeasible
            }
            SolverStatus::MaxIterations => Self::MaxIterations,
            SolverStatus::NumericalError | SolverStatus::InsufficientProgress => {
                Self::NumericalError
            }
            _ => Self::Other,
        }
    }
}

/// Result of solving a [`super::LinearProgram`].
///
/// For non-optimal statuses the vectors are Clarabel's final iterate or
/// infeasibility certificate and the objectives may be NaN or meaningless.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearProgramSolution {
    /// Termination status.
    pub status: LpStatus,
    /// Primal solution `x`.
    pub x: Vec<f64>,
    /// Primal objective `cᵀx`.
    pub objective: f64,
    /// Dual objective `−b_eqᵀ y − b_ineqᵀ z`; equals `objective` at optimum.
    pub dual_objective: f64,
    /// Multipliers `y` of the equality rows (free sign), with the convention
    /// that at optimum `c + A_eqᵀ y + A_ineqᵀ z = 0`. Equivalently `−yᵢ` is
    /// the sensitivity `∂(optimal value)/∂b_eq,i`.
    pub equality_duals: Vec<f64>,
    /// Multipliers `z ≥ 0` of the inequality rows, in the same stationarity
    /// relation `c + A_eqᵀ y + A_ineqᵀ z = 0`; `zᵢ > 0` only for active rows.
    pub inequality_duals: Vec<f64>,
    /// Number of interior-point iterations performed.
    pub iterations: u32,
    /// Clarabel's own termination status, verbatim (e.g. `Solved`,
    /// `AlmostSolved`, `MaxIterations`).
    pub solver_status: String,
}
