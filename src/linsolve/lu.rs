//! Sparse LU for square, unsymmetric or indefinite matrices, such as the
//! consistent tangent of frictional slip.
//!
//! [`LuPivoting::Supernode`] (the default) factors on the structure of
//! `A + Aᵀ` ordered by approximate minimum degree, pivoting inside each
//! supernode (`supernodal_lu.rs`): for a structurally symmetric matrix
//! whose unknowns come in blocks (the six of a DDA block), this keeps the
//! fill of a Cholesky factor. When a pivot would leave a multiplier above
//! `1 / pivot_tolerance`, that factorization is redone by
//! [`LuPivoting::Partial`], faer's LU with partial pivoting over whole
//! columns (COLAMD order), and [`SparseLu::fallbacks`] counts it.
//!
//! Both analyses are kept while the pattern is unchanged (the same
//! [`SparsePattern`] handle, or equal arrays); the factors' storage and the
//! workspaces are reused by every factorization.

use super::partial_pivot_lu::PartialPivotLu;
use super::pattern::{check_rhs, check_solution, SparseMatrix, SparsePattern};
use super::supernodal_lu::{Breakdown, SupernodalLu};
use super::{FactorizationFailure, LinearSolver, LinearSolverInfo, SolveError, SolveStats};

/// How [`SparseLu`] pivots.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LuPivoting {
    /// Symmetric fill-reducing order, pivots chosen inside each supernode;
    /// falls back to [`LuPivoting::Partial`] for a factorization whose
    /// pivots are too small.
    #[default]
    Supernode,
    /// faer's LU: COLAMD column order, partial pivoting over whole columns.
    Partial,
}

/// Settings of [`SparseLu`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LuSettings {
    /// Pivoting strategy.
    pub pivoting: LuPivoting,
    /// τ in (0, 1]: a pivot chosen inside a supernode is accepted when no
    /// multiplier below it exceeds `1 / τ` (the pivot is at least τ times
    /// the largest entry of its column), which bounds the growth of the
    /// entries by `1 + 1/τ` per elimination step.
    pub pivot_tolerance: f64,
}

impl Default for LuSettings {
    /// Supernode pivoting with τ = 1e-3.
    fn default() -> Self {
        Self {
            pivoting: LuPivoting::Supernode,
            pivot_tolerance: 1e-3,
        }
    }
}

/// Which factor holds the last factorization.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Active {
    Supernodal,
    Partial,
}

/// Sparse `L U` as a [`LinearSolver`].
#[derive(Debug, Default)]
pub struct SparseLu {
    settings: LuSettings,
    pattern: Option<SparsePattern>,
    supernodal: Option<SupernodalLu>,
    partial: Option<PartialPivotLu>,
    active: Option<Active>,
    analyses: usize,
    fallbacks: usize,
}

impl SparseLu {
    /// A solver with `settings`.
    ///
    /// # Errors
    /// [`SolveError::InvalidSetting`] for a pivot tolerance outside (0, 1].
    pub fn new(settings: LuSettings) -> Result<Self, SolveError> {
        let tau = settings.pivot_tolerance;
        if !(tau > 0.0 && tau <= 1.0) {
            return Err(SolveError::InvalidSetting {
                name: "pivot tolerance",
                value: tau,
                requirement: "must lie in (0, 1]",
            });
        }
        Ok(Self {
            settings,
            ..Self::default()
        })
    }

    /// The settings.
    pub fn settings(&self) -> LuSettings {
        self.settings
    }

    /// Stored entries of the last matrix analysed.
    pub fn matrix_entries(&self) -> usize {
        self.pattern.as_ref().map_or(0, |p| p.entries())
    }

    /// How many factorizations needed pivoting across supernodes (and
    /// were redone by faer's LU).
    pub fn fallbacks(&self) -> usize {
        self.fallbacks
    }

    /// Largest multiplier `|l_ij|` of the last factorization when it was
    /// supernodal (at most `1 / pivot_tolerance`); `None` otherwise.
    pub fn largest_multiplier(&self) -> Option<f64> {
        match (self.active, &self.supernodal) {
            (Some(Active::Supernodal), Some(lu)) => Some(lu.largest_multiplier()),
            _ => None,
        }
    }

    /// Supernodal factorization of `matrix`; `Ok(false)` when its pivots
    /// are too small.
    fn factor_supernodal(&mut self, matrix: &SparseMatrix) -> Result<bool, SolveError> {
        if self.supernodal.is_none() {
            self.supernodal = Some(SupernodalLu::analyse(matrix.pattern())?);
            self.analyses += 1;
        }
        let Some(lu) = self.supernodal.as_mut() else {
            unreachable!("analysed above")
        };
        match lu.factor(matrix.values(), self.settings.pivot_tolerance) {
            Ok(()) => Ok(true),
            Err(Breakdown::WeakPivot { .. }) => Ok(false),
        }
    }
}

impl LinearSolver<SparseMatrix> for SparseLu {
    fn factor(&mut self, matrix: &SparseMatrix) -> Result<(), SolveError> {
        self.active = None;
        matrix.check_finite()?;
        let reuse = matches!(&self.pattern, Some(p) if p.same_as(matrix.pattern()));
        if !reuse {
            self.pattern = Some(matrix.pattern().clone());
            self.supernodal = None;
            self.partial = None;
        }
        if matrix.dimension() == 0 {
            self.active = Some(Active::Partial);
            return Ok(());
        }
        if self.settings.pivoting == LuPivoting::Supernode {
            if self.factor_supernodal(matrix)? {
                self.active = Some(Active::Supernodal);
                return Ok(());
            }
            self.fallbacks += 1;
        }
        if self.partial.is_none() {
            self.partial = Some(PartialPivotLu::analyse(matrix.pattern())?);
            self.analyses += 1;
        }
        let Some(lu) = self.partial.as_mut() else {
            unreachable!("analysed above")
        };
        lu.factor(matrix)?;
        self.active = Some(Active::Partial);
        Ok(())
    }

    fn solve_in_place(
        &mut self,
        matrix: &SparseMatrix,
        rhs: &mut [f64],
    ) -> Result<SolveStats, SolveError> {
        check_rhs(rhs, matrix.dimension())?;
        match (self.active, &mut self.supernodal, &mut self.partial) {
            (Some(_), _, _) if rhs.is_empty() => {}
            (Some(Active::Supernodal), Some(lu), _) => lu.solve_in_place(rhs),
            (Some(Active::Partial), _, Some(lu)) => lu.solve_in_place(rhs),
            _ => return Err(SolveError::Factorization(FactorizationFailure::NotFactored)),
        }
        check_solution(rhs)?;
        Ok(SolveStats::direct())
    }
}

impl LinearSolverInfo for SparseLu {
    fn symbolic_analyses(&self) -> usize {
        self.analyses
    }

    /// Stored entries of L and U when the last factorization was
    /// supernodal; `None` for faer's LU, which does not tell.
    fn factor_entries(&self) -> Option<usize> {
        match (self.active, &self.supernodal) {
            (Some(Active::Supernodal), Some(lu)) => Some(lu.entries()),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::SparseCholesky;
    use super::*;
    use approx::assert_relative_eq;

    /// Dense Gaussian elimination with partial pivoting, used as a reference.
    #[allow(clippy::needless_range_loop)] // index form mirrors the textbook algorithm
    pub(crate) fn dense_solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
        let n = b.len();
        for k in 0..n {
            let p = (k..n)
                .max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))
                .unwrap();
            a.swap(k, p);
            b.swap(k, p);
            for i in k + 1..n {
                let f = a[i][k] / a[k][k];
                for j in k..n {
                    a[i][j] -= f * a[k][j];
                }
                b[i] -= f * b[k];
            }
        }
        let mut x = vec![0.0; n];
        for i in (0..n).rev() {
            let s: f64 = (i + 1..n).map(|j| a[i][j] * x[j]).sum();
            x[i] = (b[i] - s) / a[i][i];
        }
        x
    }

    /// Chain of `n` free nodes between two walls, linked by springs of
    /// stiffness `k` (tridiagonal SPD).
    pub(crate) fn spring_chain(n: usize, k: f64) -> SparseMatrix {
        let mut t = Vec::new();
        for i in 0..n {
            t.push((i, i, 2.0 * k));
            if i + 1 < n {
                t.push((i, i + 1, -k));
                t.push((i + 1, i, -k));
            }
        }
        SparseMatrix::from_triplets(n, &t).unwrap()
    }

    fn solve<S: LinearSolver<SparseMatrix>>(
        solver: &mut S,
        m: &SparseMatrix,
        b: &[f64],
    ) -> Result<Vec<f64>, SolveError> {
        solver.factor(m)?;
        let mut x = b.to_vec();
        solver.solve_in_place(m, &mut x)?;
        Ok(x)
    }

    fn partial() -> SparseLu {
        SparseLu::new(LuSettings {
            pivoting: LuPivoting::Partial,
            ..LuSettings::default()
        })
        .unwrap()
    }

    #[test]
    fn lu_spring_chain_matches_cholesky() {
        let m = spring_chain(50, 2.0);
        let b = vec![1.0; 50];
        let a = solve(&mut SparseCholesky::new(), &m, &b).unwrap();
        for mut lu in [SparseLu::default(), partial()] {
            let x = solve(&mut lu, &m, &b).unwrap();
            for (x, y) in a.iter().zip(&x) {
                assert_relative_eq!(x, y, max_relative = 1e-10);
            }
        }
    }

    /// A matrix that needs pivoting across its whole columns: small
    /// diagonal, larger unsymmetric off-diagonals.
    fn needs_pivoting(n: usize) -> (Vec<Vec<f64>>, SparseMatrix, Vec<f64>) {
        let mut dense = vec![vec![0.0; n]; n];
        let mut t = Vec::new();
        for i in 0..n {
            let entries = [
                (i, i, 0.1 + 0.01 * i as f64),
                (i, (i + 1) % n, 2.0 + i as f64),
                ((i + 3) % n, i, -1.5 + 0.3 * i as f64),
            ];
            for (r, c, v) in entries {
                t.push((r, c, v));
                dense[r][c] += v;
            }
        }
        let b = (0..n).map(|i| (i as f64).sin() + 0.5).collect();
        (dense, SparseMatrix::from_triplets(n, &t).unwrap(), b)
    }

    #[test]
    fn lu_unsymmetric_system_matches_dense_gaussian_elimination() {
        let n = 12;
        let (dense, m, b) = needs_pivoting(n);
        let expected = dense_solve(dense.clone(), b.clone());
        for mut lu in [SparseLu::default(), partial()] {
            let x = solve(&mut lu, &m, &b).unwrap();
            for (xi, ei) in x.iter().zip(&expected) {
                assert_relative_eq!(xi, ei, max_relative = 1e-9, epsilon = 1e-12);
            }
            // Residual against the assembled dense matrix.
            for (i, (row, bi)) in dense.iter().zip(&b).enumerate() {
                let r: f64 = row.iter().zip(&x).map(|(a, xj)| a * xj).sum::<f64>() - bi;
                assert!(r.abs() < 1e-10, "residual {r} at row {i}");
            }
        }
    }

    /// A block-structured, structurally symmetric, unsymmetric matrix whose
    /// diagonal blocks need row exchanges inside themselves: solved by the
    /// supernodal factor without falling back.
    #[test]
    fn supernode_pivoting_solves_block_matrices_without_falling_back() {
        let (bodies, block) = (30, 6);
        let n = bodies * block;
        let mut dense = vec![vec![0.0; n]; n];
        let mut t = Vec::new();
        let mut push = |r: usize, c: usize, v: f64| {
            t.push((r, c, v));
            dense[r][c] += v;
        };
        for a in 0..bodies {
            for p in 0..block {
                for q in 0..block {
                    // The diagonal block is a permuted, dominant matrix:
                    // its large entries sit off the diagonal.
                    let big = if (p + 1) % block == q { 50.0 } else { 0.0 };
                    push(
                        6 * a + p,
                        6 * a + q,
                        big + 0.1 * ((p * 7 + q * 3 + a) % 5) as f64,
                    );
                }
            }
            for b in [(a + 1) % bodies, (a + 7) % bodies] {
                for p in 0..block {
                    for q in 0..block {
                        let v = 0.3 * (((a + b + p * q) % 7) as f64 - 3.0);
                        push(6 * a + p, 6 * b + q, v);
                        push(6 * b + q, 6 * a + p, 0.5 * v);
                    }
                }
            }
        }
        let m = SparseMatrix::from_triplets(n, &t).unwrap();
        let b: Vec<f64> = (0..n).map(|i| (0.3 * i as f64).cos()).collect();
        let mut lu = SparseLu::default();
        let x = solve(&mut lu, &m, &b).unwrap();
        assert_eq!(lu.fallbacks(), 0);
        assert!(lu.largest_multiplier().unwrap() < 1e3);
        assert!(lu.factor_entries().unwrap() >= m.pattern().entries());
        let expected = dense_solve(dense, b);
        for (xi, ei) in x.iter().zip(&expected) {
            assert_relative_eq!(xi, ei, max_relative = 1e-9, epsilon = 1e-12);
        }
    }

    /// An arrow matrix whose leaves have tiny diagonal entries needs its
    /// pivots from the centre's row, in another supernode: the
    /// factorization falls back to partial pivoting over whole columns, and
    /// still solves exactly.
    #[test]
    fn weak_pivots_fall_back_to_partial_pivoting() {
        let n = 60;
        let centre = n - 1;
        let mut dense = vec![vec![0.0; n]; n];
        let mut t = Vec::new();
        let mut push = |r: usize, c: usize, v: f64| {
            t.push((r, c, v));
            dense[r][c] = v;
        };
        push(centre, centre, 1.0);
        for leaf in 0..centre {
            push(leaf, leaf, 1e-12 * (1.0 + leaf as f64));
            push(centre, leaf, 1.0 + 0.01 * leaf as f64);
            push(leaf, centre, -1.0 - 0.02 * leaf as f64);
        }
        let m = SparseMatrix::from_triplets(n, &t).unwrap();
        let b: Vec<f64> = (0..n).map(|i| 1.0 + (i % 3) as f64).collect();
        let mut lu = SparseLu::default();
        let x = solve(&mut lu, &m, &b).unwrap();
        assert_eq!(lu.fallbacks(), 1);
        assert_eq!(lu.symbolic_analyses(), 2);
        assert_eq!((lu.largest_multiplier(), lu.factor_entries()), (None, None));
        let expected = dense_solve(dense, b);
        for (xi, ei) in x.iter().zip(&expected) {
            assert_relative_eq!(xi, ei, max_relative = 1e-9, epsilon = 1e-12);
        }
    }

    #[test]
    fn symbolic_analysis_is_reused_when_only_values_change() {
        for mut lu in [SparseLu::default(), partial()] {
            let pattern = spring_chain(20, 1.0).pattern().clone();
            for (step, k) in [1.0, 2.5, 7.0].into_iter().enumerate() {
                // Same pattern handle, new values.
                let values = spring_chain(20, k).values().to_vec();
                let m = SparseMatrix::new(pattern.clone(), values).unwrap();
                let x = solve(&mut lu, &m, &[1.0; 20]).unwrap();
                assert_relative_eq!(x[0], 20.0 / (2.0 * k), max_relative = 1e-10);
                assert_eq!(lu.symbolic_analyses(), 1, "step {step}");
            }
        }
    }

    #[test]
    fn symbolic_analysis_is_redone_when_the_pattern_changes() {
        let mut lu = SparseLu::default();
        let chain = spring_chain(10, 1.0);
        solve(&mut lu, &chain, &[1.0; 10]).unwrap();
        assert_eq!(lu.symbolic_analyses(), 1);
        // An equal pattern built anew is recognised.
        solve(&mut lu, &spring_chain(10, 3.0), &[1.0; 10]).unwrap();
        assert_eq!(lu.symbolic_analyses(), 1);
        // New positions (0, 9), (9, 0): analysed again.
        let mut t: Vec<_> = (0..10)
            .flat_map(|j| {
                let col = chain.pattern().col_ptr()[j]..chain.pattern().col_ptr()[j + 1];
                col.map(move |k| (k, j))
            })
            .map(|(k, j)| (chain.pattern().row_idx()[k], j, chain.values()[k]))
            .collect();
        t.extend([(0, 9, -0.1), (9, 0, -0.1)]);
        let coupled = SparseMatrix::from_triplets(10, &t).unwrap();
        solve(&mut lu, &coupled, &[1.0; 10]).unwrap();
        assert_eq!(lu.symbolic_analyses(), 2);
        solve(&mut lu, &coupled, &[1.0; 10]).unwrap();
        assert_eq!(lu.symbolic_analyses(), 2);
        // A different dimension: analysed again.
        solve(&mut lu, &spring_chain(11, 1.0), &[1.0; 11]).unwrap();
        assert_eq!(lu.symbolic_analyses(), 3);
    }

    #[test]
    fn singular_matrices_give_factorization_errors() {
        // Free-free spring: rigid-body mode, singular.
        let free =
            SparseMatrix::from_triplets(2, &[(0, 0, 1.0), (0, 1, -1.0), (1, 0, -1.0), (1, 1, 1.0)])
                .unwrap();
        // Column 1 entirely empty.
        let empty_column =
            SparseMatrix::from_triplets(3, &[(0, 0, 1.0), (2, 2, 1.0), (1, 0, 1.0)]).unwrap();
        // No entries at all.
        let nothing = SparseMatrix::from_triplets(4, &[]).unwrap();
        for m in [&free, &empty_column, &nothing] {
            let b = vec![1.0; m.dimension()];
            for mut lu in [SparseLu::default(), partial()] {
                let err = solve(&mut lu, m, &b).unwrap_err();
                assert!(matches!(err, SolveError::Factorization(_)), "{err:?}");
            }
            let err = solve(&mut SparseCholesky::new(), m, &b).unwrap_err();
            assert!(matches!(err, SolveError::Factorization(_)), "{err:?}");
        }
    }

    #[test]
    fn indefinite_matrix_fails_cholesky_but_lu_solves_it() {
        let m =
            SparseMatrix::from_triplets(2, &[(0, 0, 1.0), (0, 1, 2.0), (1, 0, 2.0), (1, 1, 1.0)])
                .unwrap();
        let err = solve(&mut SparseCholesky::new(), &m, &[3.0, 3.0]).unwrap_err();
        assert!(matches!(err, SolveError::Factorization(_)), "{err:?}");
        let x = solve(&mut SparseLu::default(), &m, &[3.0, 3.0]).unwrap();
        assert_relative_eq!(x[0], 1.0, max_relative = 1e-12);
        assert_relative_eq!(x[1], 1.0, max_relative = 1e-12);
    }

    #[test]
    fn bad_input_is_an_error_not_a_panic() {
        let mut lu = SparseLu::default();
        let m = spring_chain(4, 1.0);
        let mut short = vec![1.0; 3];
        assert!(matches!(
            lu.solve_in_place(&m, &mut [1.0; 4]),
            Err(SolveError::Factorization(_))
        ));
        lu.factor(&m).unwrap();
        assert_eq!(
            lu.solve_in_place(&m, &mut short),
            Err(SolveError::DimensionMismatch {
                what: "right-hand side length",
                expected: 4,
                found: 3,
            })
        );
        let mut rhs = [0.0, 0.0, 0.0, f64::INFINITY];
        assert_eq!(
            lu.solve_in_place(&m, &mut rhs),
            Err(SolveError::NonFinite {
                what: "right-hand side",
                index: 3,
                value: f64::INFINITY,
            })
        );
        let mut nan = m.clone();
        nan.values_mut()[2] = f64::NAN;
        assert!(matches!(
            lu.factor(&nan),
            Err(SolveError::NonFinite { what: "sparse matrix value", index: 2, value }) if value.is_nan()
        ));
        assert!(matches!(
            SparseLu::new(LuSettings {
                pivot_tolerance: 0.0,
                ..LuSettings::default()
            }),
            Err(SolveError::InvalidSetting { .. })
        ));
    }

    #[test]
    fn empty_system_has_empty_solution() {
        let m = SparseMatrix::from_triplets(0, &[]).unwrap();
        assert_eq!(solve(&mut SparseLu::default(), &m, &[]), Ok(Vec::new()));
    }

    #[test]
    fn failed_factorization_does_not_poison_the_solver() {
        let mut lu = SparseLu::default();
        let good = spring_chain(5, 1.0);
        let mut bad = good.clone();
        bad.values_mut().fill(0.0);
        assert!(solve(&mut lu, &bad, &[1.0; 5]).is_err());
        let x = solve(&mut lu, &good, &[1.0; 5]).unwrap();
        assert_relative_eq!(x[0], 5.0 / 2.0, max_relative = 1e-10);
    }
}
