//! faer's sparse LU with partial pivoting over whole columns: COLAMD
//! column order, its simplicial or supernodal kernel as it chooses. The
//! fallback of [`super::SparseLu`], with its storage and workspaces kept
//! between factorizations.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, NumericLu, SymbolicLu};
use faer::{MatMut, Par};

use super::pattern::{SparseMatrix, SparsePattern};
use super::{FactorizationFailure, SolveError};

/// faer's LU of one pattern.
pub(crate) struct PartialPivotLu {
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    factor_scratch: MemBuffer,
    solve_scratch: MemBuffer,
    par: Par,
}

impl std::fmt::Debug for PartialPivotLu {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PartialPivotLu")
            .field("symbolic", &self.symbolic)
            .finish_non_exhaustive()
    }
}

fn workspace(workspace: &'static str, e: &dyn std::fmt::Debug) -> SolveError {
    SolveError::Factorization(FactorizationFailure::Workspace {
        workspace,
        message: format!("{e:?}"),
    })
}

impl PartialPivotLu {
    /// COLAMD ordering and symbolic factorization of `pattern`.
    pub(crate) fn analyse(pattern: &SparsePattern) -> Result<Self, SolveError> {
        let symbolic = factorize_symbolic_lu(pattern.faer(), Default::default()).map_err(|e| {
            SolveError::Factorization(FactorizationFailure::Analysis {
                stage: "symbolic LU analysis",
                message: format!("{e:?}"),
            })
        })?;
        let par = faer::get_global_parallelism();
        let factor_scratch = MemBuffer::try_new(
            symbolic.factorize_numeric_lu_scratch::<f64>(par, Default::default()),
        )
        .map_err(|e| workspace("LU", &e))?;
        let solve_scratch = MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, par))
            .map_err(|e| workspace("solve", &e))?;
        Ok(Self {
            symbolic,
            numeric: NumericLu::new(),
            factor_scratch,
            solve_scratch,
            par,
        })
    }

    /// Numeric factorization of `matrix`, whose pattern is the analysed one.
    pub(crate) fn factor(&mut self, matrix: &SparseMatrix) -> Result<(), SolveError> {
        self.symbolic
            .factorize_numeric_lu(
                &mut self.numeric,
                matrix.faer(),
                self.par,
                MemStack::new(&mut self.factor_scratch),
                Default::default(),
            )
            .map(|_| ())
            .map_err(|e| {
                SolveError::Factorization(FactorizationFailure::StructurallySingular {
                    message: format!("{e:?}"),
                })
            })
    }

    /// Overwrite `x` (holding `b`) with the solution of `A x = b`.
    pub(crate) fn solve_in_place(&mut self, x: &mut [f64]) {
        let n = x.len();
        LuRef::new_unchecked(&self.symbolic, &self.numeric).solve_in_place_with_conj(
            faer::Conj::No,
            MatMut::from_column_major_slice_mut(x, n, 1),
            self.par,
            MemStack::new(&mut self.solve_scratch),
        );
    }
}
