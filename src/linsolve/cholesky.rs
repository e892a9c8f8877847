//! Sparse Cholesky `K = L Lᵀ` (faer) for symmetric positive definite
//! matrices, such as the elastic stiffness of a structure held against
//! rigid-body motion.
//!
//! Only the lower triangle (`row ≥ col`) of the matrix is read: give the
//! whole symmetric matrix or its lower triangle. The analysis (faer's
//! approximate minimum degree ordering, the elimination tree, supernodes
//! where they pay) is kept while the pattern is unchanged; the factor's
//! storage and the workspaces are reused by every factorization. The
//! numeric factorization runs on faer's global parallelism, a solve with
//! one right-hand side sequentially.

use std::time::{Duration, Instant};

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::{MatMut, Side};

use super::pattern::{check_rhs, check_solution, SparseMatrix, SparsePattern};
use super::{FactorizationFailure, LinearSolver, LinearSolverInfo, SolveError, SolveStats};

/// Wall-clock times of the stages of the last factorization.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct CholeskyTimings {
    /// Conversion of the caller's matrix to compressed columns (zero for a
    /// [`SparseMatrix`]).
    pub convert: Duration,
    /// Ordering (AMD) and symbolic factorization; zero when the analysis
    /// was reused.
    pub symbolic: Duration,
    /// Numeric factorization.
    pub numeric: Duration,
}

/// The analysis of one pattern.
#[derive(Debug)]
struct Analysis {
    pattern: SparsePattern,
    symbolic: SymbolicCholesky<usize>,
    /// Made by [`SparseCholesky::analyse_pattern`] and not yet used by a
    /// factorization, which then reports its time as its own.
    fresh: bool,
}

/// Sparse `L Lᵀ` as a [`LinearSolver`].
#[derive(Debug, Default)]
pub struct SparseCholesky {
    analysis: Option<Analysis>,
    /// Values of L; empty until a factorization succeeds.
    values: Vec<f64>,
    factored: bool,
    analyses: usize,
    timings: CholeskyTimings,
}

impl SparseCholesky {
    /// A solver with nothing analysed yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Times of the stages of the last factorization.
    pub fn timings(&self) -> CholeskyTimings {
        self.timings
    }

    /// Record how long the caller took to convert its matrix (reported in
    /// [`CholeskyTimings::convert`]).
    pub(crate) fn record_conversion(&mut self, duration: Duration) {
        self.timings.convert = duration;
    }

    /// Stored entries of the last matrix analysed (as given: both
    /// triangles, or the lower one).
    pub fn matrix_entries(&self) -> usize {
        self.analysis.as_ref().map_or(0, |a| a.pattern.entries())
    }

    /// Overwrite `rhs` (holding `b`) with the solution of `K x = b` for
    /// the last matrix factored, whatever its type.
    pub(crate) fn solve_factored(&mut self, rhs: &mut [f64]) -> Result<SolveStats, SolveError> {
        let analysis = match (&self.analysis, self.factored) {
            (Some(a), true) => a,
            _ => return Err(SolveError::Factorization(FactorizationFailure::NotFactored)),
        };
        let n = analysis.symbolic.nrows();
        check_rhs(rhs, n)?;
        // One right-hand side: the triangular solves run sequentially.
        let par = faer::Par::Seq;
        let mut buffer = MemBuffer::try_new(
            analysis.symbolic.solve_in_place_scratch::<f64>(1, par),
        )
        .map_err(|e| {
            SolveError::Factorization(FactorizationFailure::Workspace {
                workspace: "solve",
                message: format!("{e:?}"),
            })
        })?;
        LltRef::new(&analysis.symbolic, &self.values).solve_in_place_with_conj(
            faer::Conj::No,
            MatMut::from_column_major_slice_mut(rhs, n, 1),
            par,
            MemStack::new(&mut buffer),
        );
        check_solution(rhs)?;
        Ok(SolveStats::direct())
    }

    /// Analyse `pattern` (the AMD ordering and the symbolic factorization)
    /// without factoring, so that the memory of the factor
    /// ([`SparseCholesky::factor_bytes`]) can be weighed before it is
    /// taken; the next factorization of a matrix with this pattern reuses
    /// the analysis (and reports its time).
    ///
    /// # Errors
    /// [`SolveError::Factorization`] when faer's symbolic analysis fails.
    pub fn analyse_pattern(&mut self, pattern: &SparsePattern) -> Result<(), SolveError> {
        self.factored = false;
        self.analyse(pattern)?;
        if let Some(analysis) = &mut self.analysis {
            analysis.fresh = true;
        }
        Ok(())
    }

    /// Bytes a numeric factorization of the analysed pattern takes beyond
    /// the matrix and its pattern: the factor's values (8 bytes an entry),
    /// its symbolic structure (row indices, supernodes, the row-major copy
    /// of a supernodal structure, the ordering) and faer's workspace (a
    /// permuted copy of the matrix and the supernodes' updates). `None`
    /// before an analysis.
    pub fn factor_bytes(&self) -> Option<u128> {
        let symbolic = &self.analysis.as_ref()?.symbolic;
        let word = std::mem::size_of::<usize>() as u128;
        let n = symbolic.nrows() as u128;
        let structure = match symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(s) => s.row_idx().len() as u128 + n + 1,
            SymbolicCholeskyRaw::Supernodal(s) => {
                2 * s.row_idx().len() as u128 + 4 * (s.n_supernodes() as u128 + 1) + n + 1
            }
        };
        let workspace = symbolic
            .factorize_numeric_llt_scratch::<f64>(
                faer::get_global_parallelism(),
                Default::default(),
            )
            .size_bytes();
        Some(
            symbolic.len_val() as u128 * std::mem::size_of::<f64>() as u128
                + (structure + 2 * n) * word
                + workspace as u128,
        )
    }

    /// Entries of the factor of the analysed pattern (0 before an
    /// analysis), whether or not it has been factored.
    pub fn factor_entries_analysed(&self) -> usize {
        self.analysis.as_ref().map_or(0, |a| a.symbolic.len_val())
    }

    fn analyse(&mut self, pattern: &SparsePattern) -> Result<(), SolveError> {
        if let Some(a) = &mut self.analysis {
            if a.pattern.same_as(pattern) {
                if !std::mem::take(&mut a.fresh) {
                    self.timings.symbolic = Duration::ZERO;
                }
                return Ok(());
            }
        }
        self.analysis = None;
        let start = Instant::now();
        let symbolic = factorize_symbolic_cholesky(
            pattern.faer(),
            Side::Lower,
            SymmetricOrdering::Amd,
            Default::default(),
        )
        .map_err(|e| {
            SolveError::Factorization(FactorizationFailure::Analysis {
                stage: "symbolic Cholesky analysis",
                message: format!("{e:?}"),
            })
        })?;
        self.timings.symbolic = start.elapsed();
        self.analyses += 1;
        self.analysis = Some(Analysis {
            pattern: pattern.clone(),
            symbolic,
            fresh: false,
        });
        Ok(())
    }
}

impl LinearSolver<SparseMatrix> for SparseCholesky {
    /// Analyse (if the pattern is new) and factor `K = L Lᵀ` from the lower
    /// triangle of `matrix`.
    fn factor(&mut self, matrix: &SparseMatrix) -> Result<(), SolveError> {
        self.factored = false;
        self.timings.convert = Duration::ZERO;
        matrix.check_finite()?;
        self.analyse(matrix.pattern())?;
        let Some(analysis) = &self.analysis else {
            unreachable!("analysed above")
        };
        let start = Instant::now();
        let symbolic = &analysis.symbolic;
        let par = faer::get_global_parallelism();

        if self.values.len() == symbolic.len_val() {
            self.values.fill(0.0);
        } else {
            // A fresh zeroed allocation: the pages are zeroed lazily, which
            // a memset of a large factor would not be.
            self.values = vec![0.0; symbolic.len_val()];
        }
        let mut buffer = MemBuffer::try_new(
            symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()),
        )
        .map_err(|e| {
            SolveError::Factorization(FactorizationFailure::Workspace {
                workspace: "Cholesky",
                message: format!("{e:?}"),
            })
        })?;
        symbolic
            .factorize_numeric_llt::<f64>(
                &mut self.values,
                matrix.faer(),
                Side::Lower,
                Default::default(),
                par,
                MemStack::new(&mut buffer),
                Default::default(),
            )
            .map_err(|e| {
                SolveError::Factorization(FactorizationFailure::NotPositiveDefinite {
                    message: format!("{e:?}"),
                })
            })?;
        self.timings.numeric = start.elapsed();
        self.factored = true;
        Ok(())
    }

    fn solve_in_place(
        &mut self,
        _: &SparseMatrix,
        rhs: &mut [f64],
    ) -> Result<SolveStats, SolveError> {
        self.solve_factored(rhs)
    }
}

impl LinearSolverInfo for SparseCholesky {
    fn symbolic_analyses(&self) -> usize {
        self.analyses
    }

    /// Stored entries of L.
    fn factor_entries(&self) -> Option<usize> {
        Some(self.values.len())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn solve(
        solver: &mut SparseCholesky,
        m: &SparseMatrix,
        b: &[f64],
    ) -> Result<Vec<f64>, SolveError> {
        solver.factor(m)?;
        let mut x = b.to_vec();
        solver.solve_in_place(m, &mut x)?;
        Ok(x)
    }

    #[test]
    fn cholesky_spring_chain_matches_exact_solution() {
        let (n, k) = (50, 3.0);
        let mut t = Vec::new();
        for i in 0..n {
            t.push((i, i, 2.0 * k));
            if i + 1 < n {
                t.push((i, i + 1, -k));
                t.push((i + 1, i, -k));
            }
        }
        let m = SparseMatrix::from_triplets(n, &t).unwrap();
        let mut solver = SparseCholesky::new();
        let x = solve(&mut solver, &m, &vec![1.0; n]).unwrap();
        // Exact: k (−u'') = 1 discretised, u_i = i' (n + 1 − i') / (2k), i' = i + 1.
        for (i, &xi) in x.iter().enumerate() {
            let j = (i + 1) as f64;
            let exact = j * ((n + 1) as f64 - j) / (2.0 * k);
            assert_relative_eq!(xi, exact, max_relative = 1e-10);
        }
        assert_eq!(solver.symbolic_analyses(), 1);
        assert_eq!(solver.matrix_entries(), 3 * n - 2);
        assert!(solver.factor_entries().unwrap() >= 2 * n - 1);
        // New values on the same pattern: no new analysis.
        let mut stiffer = m.clone();
        stiffer.values_mut().iter_mut().for_each(|v| *v *= 2.0);
        let y = solve(&mut solver, &stiffer, &vec![1.0; n]).unwrap();
        assert_relative_eq!(y[0], 0.5 * x[0], max_relative = 1e-12);
        assert_eq!(solver.symbolic_analyses(), 1);
    }

    #[test]
    fn cholesky_reads_only_the_lower_triangle_and_sums_duplicates() {
        // Upper triangle deliberately wrong; K = [[4, 1], [1, 3]] from pieces.
        let m = SparseMatrix::from_triplets(
            2,
            &[
                (0, 0, 1.0),
                (1, 0, 0.5),
                (0, 1, 100.0),
                (1, 1, 3.0),
                (0, 0, 3.0),
                (1, 0, 0.5),
            ],
        )
        .unwrap();
        let x = solve(&mut SparseCholesky::new(), &m, &[1.0, 2.0]).unwrap();
        // Exact: det = 11, x = [(3 − 2) / 11, (8 − 1) / 11].
        assert_relative_eq!(x[0], 1.0 / 11.0, max_relative = 1e-12);
        assert_relative_eq!(x[1], 7.0 / 11.0, max_relative = 1e-12);
    }

    #[test]
    fn factor_bytes_are_known_after_the_analysis_before_the_factor() {
        let n = 40;
        let mut t = Vec::new();
        for i in 0..n {
            t.push((i, i, 4.0));
            for j in [i + 1, i + 7] {
                if j < n {
                    t.push((j, i, -1.0));
                }
            }
        }
        let m = SparseMatrix::from_triplets(n, &t).unwrap();
        let mut solver = SparseCholesky::new();
        assert_eq!(solver.factor_bytes(), None);
        solver.analyse_pattern(m.pattern()).unwrap();
        let entries = solver.factor_entries_analysed();
        let bytes = solver.factor_bytes().unwrap();
        assert!(entries >= m.values().len(), "{entries}");
        assert!(bytes >= 8 * entries as u128, "{bytes}");
        // Nothing factored yet: the factor's values are not allocated.
        assert_eq!(solver.factor_entries(), Some(0));
        assert!(solver.solve_factored(&mut vec![1.0; n]).is_err());
        // The factorization reuses the analysis and keeps its time.
        let x = solve(&mut solver, &m, &vec![1.0; n]).unwrap();
        assert!(x.iter().all(|v| v.is_finite() && *v > 0.0));
        assert_eq!(solver.symbolic_analyses(), 1);
        assert_eq!(solver.factor_entries(), Some(entries));
        assert!(solver.timings().symbolic > Duration::ZERO);
        assert_eq!(solver.factor_bytes(), Some(bytes));
    }

    #[test]
    fn failed_factorization_does_not_poison_the_solver() {
        let good =
            SparseMatrix::from_triplets(2, &[(0, 0, 2.0), (1, 0, -1.0), (0, 1, -1.0), (1, 1, 2.0)])
                .unwrap();
        let mut bad = good.clone();
        bad.values_mut()[0] = -10.0;
        let mut solver = SparseCholesky::new();
        assert!(matches!(
            solve(&mut solver, &bad, &[1.0, 1.0]),
            Err(SolveError::Factorization(_))
        ));
        assert!(matches!(
            solver.solve_in_place(&bad, &mut [1.0, 1.0]),
            Err(SolveError::Factorization(_))
        ));
        let x = solve(&mut solver, &good, &[1.0, 1.0]).unwrap();
        assert_relative_eq!(x[0], 1.0, max_relative = 1e-12);
        assert_eq!(solver.symbolic_analyses(), 1);
    }
}
