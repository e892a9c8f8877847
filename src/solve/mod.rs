//! Linear programs (Clarabel) for the rigid-plastic limit analysis (paper
//! 002). The linear solvers of the implicit methods live in
//! [`crate::linsolve`].
//!
//! [`LinearProgramSolver`] implements [`GlobalSolver`]: it owns its
//! settings, takes the assembled problem by reference and returns a
//! solution or a typed [`SolveError`]. Numerical outcomes that are not
//! misuse (an infeasible LP) are reported in the solution's status, never
//! as a panic.

mod linear_program;

pub use crate::error::SolveError;
pub use linear_program::{LinearProgram, LinearProgramSolution, LinearProgramSolver, LpStatus};

/// Solve one assembled global system.
///
/// `System` is what the assembly produces and `Solution` what the method
/// reads back. The solver may keep state between calls (a workspace) so
/// that repeated solves are cheap.
pub trait GlobalSolver {
    /// The assembled problem.
    type System;
    /// What a solve returns.
    type Solution;
    /// Solve `system`.
    fn solve(&mut self, system: &Self::System) -> Result<Self::Solution, SolveError>;
}
