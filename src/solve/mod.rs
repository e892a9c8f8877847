//! Global solvers: the step that turns assembled element and contact
//! contributions into the unknowns of one step.
//!
//! | method | system | solver |
//! |---|---|---|
//! | explicit DEM (paper 000) | diagonal (lumped) mass, `M a = f` | [`LumpedMassSolver`] |
//! | implicit DDA (003), HPM (001) | sparse stiffness `K Δd = r` | [`SparseDirectSolver`] (faer, symbolic analysis reused) |
//! | large SPD stiffness (HPM, 001) | `K x = b` through products `K p` | [`ConjugateGradientSolver`] (PCG, [`BlockJacobi`]) |
//!
//! Each solver implements [`GlobalSolver`]: it owns its workspace (a
//! factorization, an LP solver's settings), takes the assembled system by
//! reference and returns a solution or a typed [`SolveError`]. Numerical
//! outcomes that are not misuse (an infeasible LP, a singular matrix) are
//! reported in the solution's status or as a `SolveError` variant that names
//! what happened, never as a panic.

mod conjugate_gradient;
mod lumped_mass;
mod sparse_direct;

pub use conjugate_gradient::{
    conjugate_gradient, BlockJacobi, CgSettings, CgSolution, CgSystem, ConjugateGradientSolver,
    LinearOperator, Preconditioner,
};
pub use lumped_mass::{solve_lumped_into, LumpedMassSolver, LumpedSystem};
pub use sparse_direct::{Factorization, SparseDirectSolver, SparseSystem};

/// Solve one assembled global system.
///
/// `System` is what the assembly produces and `Solution` what the method
/// reads back. The solver may keep state between calls (a symbolic
/// factorization, a workspace) so that repeated solves on the same pattern are
/// cheap.
pub trait GlobalSolver {
    /// The assembled problem.
    type System;
    /// What a solve returns.
    type Solution;
    /// Solve `system`.
    fn solve(&mut self, system: &Self::System) -> Result<Self::Solution, SolveError>;
}

/// Why a global solve failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SolveError {
    /// The system's parts have inconsistent sizes.
    #[error("dimension mismatch in {what}: expected {expected}, found {found}")]
    DimensionMismatch {
        /// Which part of the system.
        what: &'static str,
        /// The size implied by the rest of the system.
        expected: usize,
        /// The size given.
        found: usize,
    },
    /// An entry of the system is NaN or infinite.
    #[error("non-finite value {value} in {what} at index {index}")]
    NonFinite {
        /// Which part of the system.
        what: &'static str,
        /// Position of the entry.
        index: usize,
        /// The value.
        value: f64,
    },
    /// A diagonal mass or pivot is not positive.
    #[error("non-positive {what} {value} at index {index}")]
    NonPositive {
        /// Which part of the system.
        what: &'static str,
        /// Position of the entry.
        index: usize,
        /// The value.
        value: f64,
    },
    /// The matrix could not be factorized (singular or, for Cholesky, not
    /// positive definite).
    #[error("factorization failed: {0}")]
    Factorization(String),
    /// The underlying LP solver refused the problem.
    #[error("linear program solver error: {0}")]
    LinearProgram(String),
}

// The LP solver has its own slot, `crate::lp`; re-exported here for the
// code that names it through `solve`.
pub use crate::lp::{LinearProgram, LinearProgramSolution, LinearProgramSolver, LpStatus};
