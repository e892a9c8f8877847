//! The linear-solver slot: the sparse layer under the implicit drivers
//! (DDA, HPM). A solver is handed a matrix, analyses its sparsity pattern
//! once while the pattern is unchanged, factors the values as often as
//! they change, and solves as many right-hand sides as needed.
//!
//! | solver | matrix | for |
//! |---|---|---|
//! | [`SparseLu`] | [`SparseMatrix`] (any square) | unsymmetric tangents (DDA friction); supernodal LU on a symmetric fill-reducing ordering, falling back to faer's partial-pivoting LU |
//! | [`SparseCholesky`] | [`SparseMatrix`] (lower triangle read), [`crate::hpm::BlockMatrix`] | symmetric positive definite stiffness (HPM) |
//! | [`ConjugateGradient`] | any [`LinearOperator`] with a [`Preconditioner`] for it ([`BlockJacobi`], [`SmoothedAggregation`] multigrid, whose finest level may be given as lines of strongly coupled blocks, [`LineLevel`]) | large SPD systems where a factor does not fit (HPM) |
//! | [`LumpedMassSolver`] | a diagonal, as `[f64]` | explicit methods (`M a = f`) |
//!
//! # How a driver uses it
//!
//! A driver is generic over `S: LinearSolver<M>` and owns the matrix:
//!
//! ```
//! use dismech::linsolve::{BlockAssembly, LinearSolver, LinearSolverInfo, SparseLu};
//! # fn main() -> Result<(), dismech::error::SolveError> {
//! // Two bodies of two unknowns, coupled: the pattern is built once.
//! let mut assembly = BlockAssembly::new(2, 2, &[(0, 1)])?;
//! let mut solver = SparseLu::default();
//! for k in [1.0, 2.0] {
//!     // A Newton iteration refills the values of the same pattern ...
//!     assembly.clear();
//!     for (a, b) in [(0, 0), (1, 1)] {
//!         assembly.add_block(a, b, |p, q| if p == q { 4.0 * k } else { 1.0 })?;
//!     }
//!     assembly.add_block(0, 1, |_, _| -k)?;
//!     assembly.add_block(1, 0, |_, _| -k)?;
//!     // ... which the solver factors without a new analysis, then solves.
//!     solver.factor(assembly.matrix())?;
//!     let mut x = vec![1.0; 4];
//!     solver.solve_in_place(assembly.matrix(), &mut x)?;
//! }
//! assert_eq!(solver.symbolic_analyses(), 1);
//! # Ok(())
//! # }
//! ```
//!
//! The solve takes the matrix again: an iterative solver needs it for its
//! products, a direct one ignores it; it must be the matrix last factored.
//! Numerical outcomes that are not misuse are results, not panics: a
//! singular matrix is a [`SolveError::Factorization`], a PCG that stops at
//! its iteration limit returns [`SolveStats::converged`]` = false`.
//!
//! # Fill of the DDA tangent
//!
//! The DDA tangent is structurally symmetric (a block for every pair of
//! bodies in contact) but unsymmetric in value. faer's sparse LU orders the
//! columns by COLAMD, bounds the fill by the structure of `AᵀA` and pivots
//! over whole columns; it picks its simplicial kernel when that bound is
//! small (walls of ~100 blocks, where it is 3 times slower than its own
//! supernodal kernel) and its supernodal one above. On a running-bond wall
//! of 1 610 blocks (9 666 unknowns, 393 486 entries) its factor stores
//! 4.24 million entries in L and U and takes about 85 ms on one core;
//! given an approximate-minimum-degree order of `A + Aᵀ` instead of COLAMD
//! it stores 13.7 million, its pivoting bound being that of `AᵀA`.
//! [`SparseLu`] factors on the symmetric structure instead, pivoting
//! inside each supernode (the six unknowns of a block always share one):
//! 2.13 million entries and about 22 ms on the same matrix, with
//! multipliers no larger than 3.5, far inside the `1 / τ = 1000` that
//! would make it fall back to faer's LU
//! ([`LuSettings::pivot_tolerance`]; see `benches/dda_wall.rs`).

mod block_assembly;
mod block_jacobi;
mod cholesky;
mod conjugate_gradient;
mod lu;
mod lumped;
mod partial_pivot_lu;
mod pattern;
mod smoothed_aggregation;
mod supernodal_lu;

pub use block_assembly::{BlockAssembly, BlockSlot};
pub use block_jacobi::{BlockJacobi, DiagonalBlocks};
pub use cholesky::{CholeskyTimings, SparseCholesky};
pub use conjugate_gradient::{
    conjugate_gradient, CgSettings, CgSolution, ConjugateGradient, LinearOperator, Preconditioner,
};
pub use lu::{LuPivoting, LuSettings, SparseLu};
pub use lumped::{solve_lumped_into, LumpedMassSolver, LumpedSystem};
pub use pattern::{SparseMatrix, SparsePattern};
pub use smoothed_aggregation::{AggregationSettings, BlockSparse, LineLevel, SmoothedAggregation};

pub use crate::error::{FactorizationFailure, LpFailure, SolveError};

/// What a solve reports besides its solution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolveStats {
    /// Iterations made (0 for a direct solve).
    pub iterations: usize,
    /// Relative residual `‖b − A x‖ / ‖b‖` where the solver computes it
    /// (iterative solvers), `None` otherwise.
    pub relative_residual: Option<f64>,
    /// Whether the solution met the solver's tolerance (always `true` for
    /// a direct solve that succeeded).
    pub converged: bool,
}

impl SolveStats {
    /// The statistics of a direct solve.
    pub fn direct() -> Self {
        Self {
            iterations: 0,
            relative_residual: None,
            converged: true,
        }
    }
}

/// What a linear solver has done and keeps, whatever the matrix type.
pub trait LinearSolverInfo {
    /// How many symbolic analyses were made so far: constant while the
    /// pattern is unchanged.
    fn symbolic_analyses(&self) -> usize;

    /// Stored entries of the last factor (L + U for an LU, L for a
    /// Cholesky factor, the dense blocks of a preconditioner, the diagonal
    /// of a lumped matrix): the fill and the memory kept between solves;
    /// `None` where the backend does not tell.
    fn factor_entries(&self) -> Option<usize>;
}

/// A solver of `A x = b` for matrices of type `M`: analyse the pattern
/// once, factor many times, solve many times.
pub trait LinearSolver<M: ?Sized>: LinearSolverInfo {
    /// Prepare to solve with `matrix`: analyse its sparsity pattern if it
    /// is not the one analysed last (ordering, symbolic factorization),
    /// then factor its values (direct solvers) or build the preconditioner
    /// (iterative ones).
    ///
    /// # Errors
    /// Implementations return [`SolveError::NonFinite`] for a matrix entry
    /// that is not finite, [`SolveError::NonPositive`] for a diagonal that
    /// must be positive and is not ([`LumpedMassSolver`]), and
    /// [`SolveError::Factorization`] when the factorization or its analysis
    /// fails (a singular matrix, one not positive definite for
    /// [`SparseCholesky`], a workspace that cannot be allocated); an
    /// iterative solver returns its preconditioner's error
    /// ([`Preconditioner::setup`]).
    fn factor(&mut self, matrix: &M) -> Result<(), SolveError>;

    /// Overwrite `rhs`, holding `b`, with the solution `x` of
    /// `matrix · x = b`; `matrix` is the one last factored.
    ///
    /// # Errors
    /// Implementations return [`SolveError::DimensionMismatch`] for a
    /// right-hand side whose length is not the matrix's dimension (for an
    /// iterative solver, also a matrix of another size than the one last
    /// factored, or none factored), [`SolveError::NonFinite`] for a
    /// right-hand side entry that is not finite, and
    /// [`SolveError::Factorization`] for a direct solve before any
    /// factorization or a solution that is not finite (a numerically
    /// singular matrix); [`ConjugateGradient`] returns
    /// [`SolveError::NonPositive`] for a curvature `pᵀKp` that is not
    /// positive (the matrix is not positive definite).
    fn solve_in_place(&mut self, matrix: &M, rhs: &mut [f64]) -> Result<SolveStats, SolveError>;
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Solvers can move to another thread with the driver that owns them.
    #[test]
    fn solvers_are_send_and_sync() {
        fn check<T: Send + Sync>() {}
        check::<SparseLu>();
        check::<SparseCholesky>();
        check::<ConjugateGradient<BlockJacobi>>();
        check::<LumpedMassSolver>();
        check::<crate::dda::DdaModel>();
        check::<crate::hpm::HpmSolver>();
    }
}
