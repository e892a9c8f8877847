//! The LP-solver slot: linear programs and the solvers that solve them.
//!
//! A [`LinearProgram`] describes
//!
//! ```text
//! minimise    cᵀx
//! subject to  A_eq   x  = b_eq
//!             A_ineq x ≤ b_ineq
//! ```
//!
//! with free variables `x`; variable bounds are ordinary rows of `A_ineq`
//! (see [`LinearProgram::add_bounds`]). The matrices are stored as
//! `(row, col, value)` triplets, duplicates being summed, so assembly code
//! can scatter element contributions without bookkeeping.
//!
//! In rigid-plastic limit analysis of circular elements the two bounding
//! theorems both become LPs of this form:
//!
//! * the **lower bound** (static) problem maximises the load factor over
//!   stress fields that satisfy equilibrium (equality rows) and a linearised
//!   yield condition (inequality rows);
//! * the **upper bound** (kinematic) problem minimises the dissipated power
//!   over mechanisms satisfying a normalisation of the external power
//!   (equality row) and flow-rule / compatibility constraints.
//!
//! Maximisation is done by negating the objective. The dual variables
//! returned in [`LinearProgramSolution`] are the multipliers of the other
//! bound problem (e.g. the velocities of the collapse mechanism are the
//! equilibrium multipliers of the static problem), up to the sign convention
//! documented on [`LinearProgramSolution::equality_duals`]:
//!
//! ```text
//! c + A_eqᵀ y + A_ineqᵀ z = 0,    z ≥ 0,    zᵢ (b_ineq − A_ineq x)ᵢ = 0,
//! dual objective = −b_eqᵀ y − b_ineqᵀ z.
//! ```
//!
//! **Interior-point caveat:** when the optimum is not unique (a whole face of
//! the feasible polytope is optimal, common for symmetric collapse
//! mechanisms), an interior-point method converges towards the analytic
//! centre of that optimal face rather than to a vertex. The optimal value is
//! reliable, but `x` (and the duals) may be a blend of several vertex
//! solutions, and inequality rows may be only approximately active.
//!
//! ```
//! use dismech::lp::{LinearProgram, LinearProgramSolver, LpSolver, LpStatus};
//!
//! // maximise x + y  s.t.  x + 2y ≤ 4, 3x + y ≤ 6, x, y ≥ 0
//! let mut lp = LinearProgram::new(2);
//! lp.objective = vec![-1.0, -1.0];
//! lp.add_inequality(&[(0, 1.0), (1, 2.0)], 4.0);
//! lp.add_inequality(&[(0, 3.0), (1, 1.0)], 6.0);
//! lp.add_bounds(0, Some(0.0), None);
//! lp.add_bounds(1, Some(0.0), None);
//! let sol = LinearProgramSolver::default().solve(&lp).unwrap();
//! assert_eq!(sol.status, LpStatus::Optimal);
//! assert!((sol.objective + 2.8).abs() < 1e-6);
//! ```

mod certificate;
mod clarabel;
mod program;
mod solution;

pub use certificate::{Optimality, Scales};
pub use clarabel::LinearProgramSolver;
pub use program::LinearProgram;
pub use solution::{LinearProgramSolution, LpStatus};

use crate::error::SolveError;

/// A solver of [`LinearProgram`]s: the slot a limit analysis is generic
/// over. [`LinearProgramSolver`] (Clarabel's interior-point method) is the
/// one this crate provides.
pub trait LpSolver {
    /// Solve `lp`. Misuse (bad sizes, non-finite data) is an error;
    /// infeasibility, unboundedness and iteration limits are reported in
    /// the solution's [`LpStatus`].
    ///
    /// # Errors
    /// Implementations return [`SolveError::DimensionMismatch`] for an
    /// objective whose length is not `lp.num_variables` or a triplet whose
    /// row or column index is out of range, [`SolveError::NonFinite`] for a
    /// coefficient or right-hand side that is not finite, an error of their
    /// own settings (for [`LinearProgramSolver`]: [`SolveError::NonFinite`]
    /// or [`SolveError::NonPositive`] for its tolerance), and
    /// [`SolveError::LinearProgram`] when the underlying solver refuses the
    /// problem or fails internally. An infeasible or unbounded LP, or one
    /// stopped at the iteration limit, is not an error.
    fn solve(&mut self, lp: &LinearProgram) -> Result<LinearProgramSolution, SolveError>;
}
