//! Direct sparse linear solver for the global systems `K x = b` of discrete mechanics.
//!
//! Assembling a discrete-mechanics model (springs, rods, shells, contact) produces a
//! large, very sparse square matrix `K` (a stiffness or tangent matrix) and a right-hand
//! side `b`. This module turns such a system, given as a list of `(row, col, value)`
//! triplets, into a solution vector using a sparse direct factorization from `faer`.
//!
//! # Choosing a factorization
//!
//! * [`Factorization::Cholesky`] (the default) computes a sparse `L Lᵀ` factorization.
//!   Use it for **symmetric positive definite** matrices, such as the elastic stiffness
//!   matrix of a structure that is sufficiently supported (no rigid-body modes). It is
//!   about twice as cheap as LU and needs no pivoting. Give the *full* symmetric matrix
//!   (both triangles) in the triplets; only the lower triangle (`row >= col`) is read,
//!   so an unsymmetric matrix is silently treated as its lower triangle mirrored.
//! * [`Factorization::Lu`] computes a sparse `L U` factorization with partial
//!   pivoting. Use it for **unsymmetric** or **indefinite** matrices, such as the
//!   consistent tangent of frictional slip or any non-associative model.
//!
//! # Reuse of the symbolic analysis
//!
//! A Newton iteration or a time-stepping loop solves many systems with the same
//! sparsity pattern and different values. [`SparseDirectSolver`] keeps the symbolic
//! analysis (fill-reducing ordering, elimination tree, column structure) and the
//! triplet-to-storage mapping from the previous call and reuses them as long as the
//! sequence of `(row, col)` positions — in the order given — is unchanged. Only the
//! numeric factorization is redone then. [`SparseDirectSolver::symbolic_analyses`]
//! reports how many symbolic analyses have been performed.
//!
//! # Errors
//!
//! Invalid input (indices out of range, wrong right-hand-side length, non-finite
//! values) is reported as [`SolveError`] before anything is factorized. A failed
//! factorization (singular matrix, or not positive definite for Cholesky) yields
//! [`SolveError::Factorization`] carrying faer's message.

use faer::prelude::{Reborrow, Solve};
use faer::sparse::linalg::solvers::{Llt, Lu, SymbolicLlt, SymbolicLu};
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat};
use faer::{Col, Side};

use super::{GlobalSolver, SolveError};

/// Which sparse factorization [`SparseDirectSolver`] uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Factorization {
    /// Sparse Cholesky `L Lᵀ` for symmetric positive definite matrices (e.g. elastic
    /// stiffness). Only the lower triangle of the given matrix is read.
    #[default]
    Cholesky,
    /// Sparse `L U` with partial pivoting for general unsymmetric matrices (e.g. the
    /// tangent of frictional slip).
    Lu,
}

/// A sparse square linear system `K x = b` given as triplets.
///
/// Triplets at the same `(row, col)` position are summed, which is exactly what
/// finite-element style assembly needs.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SparseSystem {
    /// Number of rows and columns of `K`, and length of `b`.
    pub dimension: usize,
    /// Entries `(row, col, value)` of `K`; duplicates are summed.
    pub triplets: Vec<(usize, usize, f64)>,
    /// Right-hand side `b`, of length `dimension`.
    pub rhs: Vec<f64>,
}

impl SparseSystem {
    /// Creates an empty system of the given dimension with a zero right-hand side.
    pub fn new(dimension: usize) -> Self {
        Self {
            dimension,
            triplets: Vec::new(),
            rhs: vec![0.0; dimension],
        }
    }

    /// Appends the entry `K[row, col] += value`.
    ///
    /// Indices are not checked here; out-of-range indices are reported by
    /// [`GlobalSolver::solve`].
    pub fn add(&mut self, row: usize, col: usize, value: f64) {
        self.triplets.push((row, col, value));
    }

    /// Removes all triplets and zeroes the right-hand side, keeping the dimension
    /// (the right-hand side is resized to `dimension` if needed).
    pub fn clear_values(&mut self) {
        self.triplets.clear();
        self.rhs.clear();
        self.rhs.resize(self.dimension, 0.0);
    }
}

/// Symbolic factorization of the cached pattern.
#[derive(Debug, Clone)]
enum SymbolicFactor {
    Llt(SymbolicLlt<usize>),
    Lu(SymbolicLu<usize>),
}

/// Everything that depends only on the sparsity pattern.
#[derive(Debug, Clone)]
struct SymbolicCache {
    /// Dimension of the analysed matrix.
    dimension: usize,
    /// The `(row, col)` positions of all triplets, in the order given.
    pattern: Vec<(usize, usize)>,
    /// Indices into the triplet list of the entries passed to faer (all of them for
    /// LU, the lower triangle for Cholesky).
    selected: Vec<usize>,
    /// Compressed-column structure of the matrix passed to faer.
    structure: SymbolicSparseColMat<usize>,
    /// Mapping from the selected triplets to the compressed-column values.
    argsort: Argsort<usize>,
    /// Symbolic factorization.
    factor: SymbolicFactor,
}

impl SymbolicCache {
    fn matches(&self, system: &SparseSystem) -> bool {
        self.dimension == system.dimension
            && self.pattern.len() == system.triplets.len()
            && self
                .pattern
                .iter()
                .zip(&system.triplets)
                .all(|(&(r, c), &(row, col, _))| r == row && c == col)
    }
}

/// Direct sparse solver for [`SparseSystem`]s, backed by faer.
///
/// The symbolic analysis is reused while the sparsity pattern (the sequence of
/// `(row, col)` positions of the triplets, in the order given, and the dimension)
/// is unchanged; otherwise it is redone.
#[derive(Debug, Clone)]
pub struct SparseDirectSolver {
    kind: Factorization,
    cache: Option<SymbolicCache>,
    symbolic_analyses: usize,
}

impl Default for SparseDirectSolver {
    fn default() -> Self {
        Self::new(Factorization::default())
    }
}

impl SparseDirectSolver {
    /// Creates a solver using the given factorization.
    pub fn new(kind: Factorization) -> Self {
        Self {
            kind,
            cache: None,
            symbolic_analyses: 0,
        }
    }

    /// The factorization this solver uses.
    pub fn factorization(&self) -> Factorization {
        self.kind
    }

    /// How many symbolic analyses have been performed so far.
    ///
    /// This stays constant across solves whose sparsity pattern does not change,
    /// which lets callers (and tests) verify that the analysis is reused.
    pub fn symbolic_analyses(&self) -> usize {
        self.symbolic_analyses
    }

    /// Builds the symbolic analysis for the pattern of `system`.
    fn analyse(&self, system: &SparseSystem) -> Result<SymbolicCache, SolveError> {
        let n = system.dimension;
        let selected: Vec<usize> = system
            .triplets
            .iter()
            .enumerate()
            .filter(|(_, &(row, col, _))| match self.kind {
                Factorization::Cholesky => row >= col,
                Factorization::Lu => true,
            })
            .map(|(k, _)| k)
            .collect();
        let indices: Vec<Pair<usize, usize>> = selected
            .iter()
            .map(|&k| {
                let (row, col, _) = system.triplets[k];
                Pair { row, col }
            })
            .collect();
        let (structure, argsort) = SymbolicSparseColMat::try_new_from_indices(n, n, &indices)
            .map_err(|e| {
                SolveError::Factorization(format!("building sparse structure failed: {e}"))
            })?;
        let factor = match self.kind {
            Factorization::Cholesky => SymbolicLlt::try_new(structure.rb(), Side::Lower)
                .map(SymbolicFactor::Llt)
                .map_err(|e| {
                    SolveError::Factorization(format!("symbolic Cholesky analysis failed: {e}"))
                })?,
            Factorization::Lu => SymbolicLu::try_new(structure.rb())
                .map(SymbolicFactor::Lu)
                .map_err(|e| {
                    SolveError::Factorization(format!("symbolic LU analysis failed: {e}"))
                })?,
        };
        Ok(SymbolicCache {
            dimension: n,
            pattern: system.triplets.iter().map(|&(r, c, _)| (r, c)).collect(),
            selected,
            structure,
            argsort,
            factor,
        })
    }
}

/// Checks indices, lengths and finiteness of `system`.
fn validate(system: &SparseSystem) -> Result<(), SolveError> {
    let n = system.dimension;
    if system.rhs.len() != n {
        return Err(SolveError::DimensionMismatch {
            what: "right-hand side length",
            expected: n,
            found: system.rhs.len(),
        });
    }
    for (k, &(row, col, value)) in system.triplets.iter().enumerate() {
        if row >= n {
            return Err(SolveError::DimensionMismatch {
                what: "triplet row index (found is the index, expected the dimension)",
                expected: n,
                found: row,
            });
        }
        if col >= n {
            return Err(SolveError::DimensionMismatch {
                what: "triplet column index (found is the index, expected the dimension)",
                expected: n,
                found: col,
            });
        }
        if !value.is_finite() {
            return Err(SolveError::NonFinite {
                what: "sparse matrix triplet",
                index: k,
                value,
            });
        }
    }
    if let Some((index, &value)) = system.rhs.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(SolveError::NonFinite {
            what: "right-hand side",
            index,
            value,
        });
    }
    Ok(())
}

impl GlobalSolver for SparseDirectSolver {
    type System = SparseSystem;
    type Solution = Vec<f64>;

    /// Solves `K x = b`, reusing the symbolic analysis when the pattern is unchanged.
    fn solve(&mut self, system: &Self::System) -> Result<Self::Solution, SolveError> {
        validate(system)?;
        let n = system.dimension;
        if n == 0 {
            return Ok(Vec::new());
        }

        let cache = match self.cache.take() {
            Some(cache) if cache.matches(system) => cache,
            _ => {
                let cache = self.analyse(system)?;
                self.symbolic_analyses += 1;
                cache
            }
        };
        let cache = self.cache.insert(cache);

        let values: Vec<f64> = cache
            .selected
            .iter()
            .map(|&k| system.triplets[k].2)
            .collect();
        let matrix =
            SparseColMat::new_from_argsort(cache.structure.clone(), &cache.argsort, &values)
                .map_err(|e| {
                    SolveError::Factorization(format!("filling sparse matrix failed: {e}"))
                })?;

        let mut x = Col::<f64>::from_fn(n, |i| system.rhs[i]);
        match &cache.factor {
            SymbolicFactor::Llt(symbolic) => {
                let llt = Llt::try_new_with_symbolic(symbolic.clone(), matrix.rb(), Side::Lower)
                    .map_err(|e| {
                        SolveError::Factorization(format!(
                            "sparse Cholesky failed (matrix not symmetric positive definite): {e}"
                        ))
                    })?;
                llt.solve_in_place(x.as_mut());
            }
            SymbolicFactor::Lu(symbolic) => {
                let lu = Lu::try_new_with_symbolic(symbolic.clone(), matrix.rb()).map_err(|e| {
                    SolveError::Factorization(format!("sparse LU failed (matrix singular): {e}"))
                })?;
                lu.solve_in_place(x.as_mut());
            }
        }

        let solution: Vec<f64> = x.iter().copied().collect();
        // faer's numeric LU does not report exactly-zero pivots; they show up as
        // non-finite entries in the solution.
        if let Some((index, value)) = solution.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(SolveError::Factorization(format!(
                "matrix is numerically singular: solution entry {index} is {value}"
            )));
        }
        Ok(solution)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// Dense Gaussian elimination with partial pivoting, used as a reference.
    #[allow(clippy::needless_range_loop)] // index form mirrors the textbook algorithm
    fn dense_solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
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

    /// Chain of `n` free nodes between two walls, linked by springs of stiffness
    /// `k`, with unit load on every node (tridiagonal SPD).
    fn spring_chain(n: usize, k: f64) -> SparseSystem {
        let mut sys = SparseSystem::new(n);
        for i in 0..n {
            sys.add(i, i, 2.0 * k);
            if i + 1 < n {
                sys.add(i, i + 1, -k);
                sys.add(i + 1, i, -k);
            }
            sys.rhs[i] = 1.0;
        }
        sys
    }

    #[test]
    fn cholesky_spring_chain_matches_exact_solution() {
        let n = 50;
        let k = 3.0;
        let sys = spring_chain(n, k);
        let mut solver = SparseDirectSolver::new(Factorization::Cholesky);
        let x = solver.solve(&sys).unwrap();
        // Exact: k * (-u'' ) = 1 discretised, u_i = i' (n + 1 - i') / (2k), i' = i + 1.
        for (i, &xi) in x.iter().enumerate() {
            let j = (i + 1) as f64;
            let exact = j * ((n + 1) as f64 - j) / (2.0 * k);
            assert_relative_eq!(xi, exact, max_relative = 1e-10);
        }
    }

    #[test]
    fn lu_spring_chain_matches_cholesky() {
        let sys = spring_chain(50, 2.0);
        let a = SparseDirectSolver::new(Factorization::Cholesky)
            .solve(&sys)
            .unwrap();
        let b = SparseDirectSolver::new(Factorization::Lu)
            .solve(&sys)
            .unwrap();
        for (x, y) in a.iter().zip(&b) {
            assert_relative_eq!(x, y, max_relative = 1e-10);
        }
    }

    #[test]
    fn lu_unsymmetric_system_matches_dense_gaussian_elimination() {
        let n = 12;
        let mut dense = vec![vec![0.0; n]; n];
        let mut sys = SparseSystem::new(n);
        for i in 0..n {
            // Needs pivoting: small diagonal, larger unsymmetric off-diagonals.
            let entries = [
                (i, i, 0.1 + 0.01 * i as f64),
                (i, (i + 1) % n, 2.0 + i as f64),
                ((i + 3) % n, i, -1.5 + 0.3 * i as f64),
            ];
            for (r, c, v) in entries {
                sys.add(r, c, v);
                dense[r][c] += v;
            }
            sys.rhs[i] = (i as f64).sin() + 0.5;
        }
        let expected = dense_solve(dense.clone(), sys.rhs.clone());
        let x = SparseDirectSolver::new(Factorization::Lu)
            .solve(&sys)
            .unwrap();
        for (xi, ei) in x.iter().zip(&expected) {
            assert_relative_eq!(xi, ei, max_relative = 1e-9, epsilon = 1e-12);
        }
        // Residual check against the assembled dense matrix.
        for (i, (row, bi)) in dense.iter().zip(&sys.rhs).enumerate() {
            let r: f64 = row.iter().zip(&x).map(|(a, xj)| a * xj).sum::<f64>() - bi;
            assert!(r.abs() < 1e-10, "residual {r} at row {i}");
        }
    }

    #[test]
    fn symbolic_analysis_is_reused_when_only_values_change() {
        for kind in [Factorization::Cholesky, Factorization::Lu] {
            let mut solver = SparseDirectSolver::new(kind);
            for (step, k) in [1.0, 2.5, 7.0].into_iter().enumerate() {
                let sys = spring_chain(20, k);
                let x = solver.solve(&sys).unwrap();
                assert_relative_eq!(x[0], 20.0 / (2.0 * k), max_relative = 1e-10);
                assert_eq!(solver.symbolic_analyses(), 1, "{kind:?} step {step}");
            }
        }
    }

    #[test]
    fn symbolic_analysis_is_redone_when_pattern_changes() {
        let mut solver = SparseDirectSolver::new(Factorization::Cholesky);
        let mut sys = spring_chain(10, 1.0);
        solver.solve(&sys).unwrap();
        assert_eq!(solver.symbolic_analyses(), 1);

        // New position (0, 9)/(9, 0): pattern changes.
        sys.add(0, 9, -0.1);
        sys.add(9, 0, -0.1);
        solver.solve(&sys).unwrap();
        assert_eq!(solver.symbolic_analyses(), 2);

        // Same pattern again: reused.
        solver.solve(&sys).unwrap();
        assert_eq!(solver.symbolic_analyses(), 2);

        // Different dimension: redone.
        solver.solve(&spring_chain(11, 1.0)).unwrap();
        assert_eq!(solver.symbolic_analyses(), 3);
    }

    #[test]
    fn clear_values_keeps_dimension_and_allows_reuse() {
        let mut solver = SparseDirectSolver::new(Factorization::Cholesky);
        let mut sys = spring_chain(8, 1.0);
        solver.solve(&sys).unwrap();
        sys.clear_values();
        assert_eq!(sys.dimension, 8);
        assert!(sys.triplets.is_empty());
        assert_eq!(sys.rhs, vec![0.0; 8]);
        let refilled = spring_chain(8, 4.0);
        for &(r, c, v) in &refilled.triplets {
            sys.add(r, c, v);
        }
        sys.rhs.copy_from_slice(&refilled.rhs);
        solver.solve(&sys).unwrap();
        assert_eq!(solver.symbolic_analyses(), 1);
    }

    #[test]
    fn singular_matrix_gives_factorization_error() {
        // Free-free spring: rigid-body mode, singular (and only semi-definite).
        let mut sys = SparseSystem::new(2);
        for (r, c, v) in [(0, 0, 1.0), (0, 1, -1.0), (1, 0, -1.0), (1, 1, 1.0)] {
            sys.add(r, c, v);
        }
        sys.rhs = vec![1.0, -1.0];
        for kind in [Factorization::Cholesky, Factorization::Lu] {
            let err = SparseDirectSolver::new(kind).solve(&sys).unwrap_err();
            assert!(
                matches!(err, SolveError::Factorization(_)),
                "{kind:?}: {err:?}"
            );
        }
    }

    #[test]
    fn structurally_singular_matrix_gives_factorization_error() {
        // Column 1 is entirely empty.
        let mut sys = SparseSystem::new(3);
        sys.add(0, 0, 1.0);
        sys.add(2, 2, 1.0);
        sys.add(1, 0, 1.0);
        for kind in [Factorization::Cholesky, Factorization::Lu] {
            let err = SparseDirectSolver::new(kind).solve(&sys).unwrap_err();
            assert!(
                matches!(err, SolveError::Factorization(_)),
                "{kind:?}: {err:?}"
            );
        }
        // No triplets at all.
        let empty = SparseSystem::new(4);
        for kind in [Factorization::Cholesky, Factorization::Lu] {
            let err = SparseDirectSolver::new(kind).solve(&empty).unwrap_err();
            assert!(
                matches!(err, SolveError::Factorization(_)),
                "{kind:?}: {err:?}"
            );
        }
    }

    #[test]
    fn indefinite_matrix_fails_cholesky_but_lu_solves_it() {
        let mut sys = SparseSystem::new(2);
        for (r, c, v) in [(0, 0, 1.0), (0, 1, 2.0), (1, 0, 2.0), (1, 1, 1.0)] {
            sys.add(r, c, v);
        }
        sys.rhs = vec![3.0, 3.0];
        let err = SparseDirectSolver::new(Factorization::Cholesky)
            .solve(&sys)
            .unwrap_err();
        assert!(matches!(err, SolveError::Factorization(_)), "{err:?}");
        let x = SparseDirectSolver::new(Factorization::Lu)
            .solve(&sys)
            .unwrap();
        assert_relative_eq!(x[0], 1.0, max_relative = 1e-12);
        assert_relative_eq!(x[1], 1.0, max_relative = 1e-12);
    }

    #[test]
    fn out_of_range_index_is_an_error_not_a_panic() {
        for kind in [Factorization::Cholesky, Factorization::Lu] {
            let mut solver = SparseDirectSolver::new(kind);
            let mut sys = spring_chain(3, 1.0);
            sys.add(3, 0, 1.0);
            assert_eq!(
                solver.solve(&sys),
                Err(SolveError::DimensionMismatch {
                    what: "triplet row index (found is the index, expected the dimension)",
                    expected: 3,
                    found: 3,
                })
            );
            let mut sys = spring_chain(3, 1.0);
            sys.add(0, usize::MAX, 1.0);
            assert!(matches!(
                solver.solve(&sys),
                Err(SolveError::DimensionMismatch {
                    found: usize::MAX,
                    ..
                })
            ));
            assert_eq!(solver.symbolic_analyses(), 0);
        }
    }

    #[test]
    fn wrong_rhs_length_is_a_dimension_mismatch() {
        let mut sys = spring_chain(4, 1.0);
        sys.rhs.push(0.0);
        assert_eq!(
            SparseDirectSolver::new(Factorization::Cholesky).solve(&sys),
            Err(SolveError::DimensionMismatch {
                what: "right-hand side length",
                expected: 4,
                found: 5,
            })
        );
    }

    #[test]
    fn non_finite_values_are_reported_with_their_index() {
        let mut sys = spring_chain(4, 1.0);
        sys.triplets[2].2 = f64::NAN;
        let err = SparseDirectSolver::default().solve(&sys).unwrap_err();
        assert!(
            matches!(err, SolveError::NonFinite { what: "sparse matrix triplet", index: 2, value } if value.is_nan()),
            "{err:?}"
        );

        let mut sys = spring_chain(4, 1.0);
        sys.rhs[3] = f64::INFINITY;
        assert_eq!(
            SparseDirectSolver::default().solve(&sys),
            Err(SolveError::NonFinite {
                what: "right-hand side",
                index: 3,
                value: f64::INFINITY,
            })
        );
    }

    #[test]
    fn duplicate_triplets_are_summed() {
        // K = [[4, 1], [1, 3]] assembled from pieces; b = [1, 2].
        let mut split = SparseSystem::new(2);
        for (r, c, v) in [
            (0, 0, 1.0),
            (1, 1, 1.0),
            (0, 0, 3.0),
            (0, 1, 0.25),
            (1, 0, 0.5),
            (0, 1, 0.75),
            (1, 0, 0.5),
            (1, 1, 2.0),
        ] {
            split.add(r, c, v);
        }
        split.rhs = vec![1.0, 2.0];
        // Exact: det = 11, x = [(3 - 2) / 11, (8 - 1) / 11].
        for kind in [Factorization::Cholesky, Factorization::Lu] {
            let x = SparseDirectSolver::new(kind).solve(&split).unwrap();
            assert_relative_eq!(x[0], 1.0 / 11.0, max_relative = 1e-12);
            assert_relative_eq!(x[1], 7.0 / 11.0, max_relative = 1e-12);
        }
    }

    #[test]
    fn cholesky_reads_only_the_lower_triangle() {
        // Upper triangle deliberately wrong; Cholesky must ignore it.
        let mut sys = SparseSystem::new(2);
        for (r, c, v) in [(0, 0, 4.0), (1, 0, 1.0), (0, 1, 100.0), (1, 1, 3.0)] {
            sys.add(r, c, v);
        }
        sys.rhs = vec![1.0, 2.0];
        let x = SparseDirectSolver::new(Factorization::Cholesky)
            .solve(&sys)
            .unwrap();
        assert_relative_eq!(x[0], 1.0 / 11.0, max_relative = 1e-12);
        assert_relative_eq!(x[1], 7.0 / 11.0, max_relative = 1e-12);
    }

    #[test]
    fn empty_system_has_empty_solution() {
        let sys = SparseSystem::new(0);
        assert_eq!(SparseDirectSolver::default().solve(&sys), Ok(Vec::new()));
        assert_eq!(SparseSystem::default(), sys);
    }

    #[test]
    fn failed_factorization_does_not_poison_the_solver() {
        let mut solver = SparseDirectSolver::new(Factorization::Cholesky);
        let mut bad = spring_chain(5, 1.0);
        bad.triplets[0].2 = -10.0;
        assert!(matches!(
            solver.solve(&bad),
            Err(SolveError::Factorization(_))
        ));
        let good = spring_chain(5, 1.0);
        let x = solver.solve(&good).unwrap();
        assert_relative_eq!(x[0], 5.0 / 2.0, max_relative = 1e-10);
        assert_eq!(solver.symbolic_analyses(), 1);
    }
}
