//! Preconditioned conjugate gradients (PCG) for symmetric positive
//! definite systems `K x = b`.
//!
//! An alternative to [`super::SparseCholesky`] where a factor is too
//! large: only products `K p` are needed (the matrix may be kept in any
//! form implementing [`LinearOperator`]), and memory is a few vectors plus
//! the preconditioner ([`super::BlockJacobi`]).
//!
//! # Algorithm
//!
//! Standard PCG from `x₀ = 0`: `r = b`, `z = M⁻¹ r`, `p = z`; each
//! iteration `α = rᵀz / pᵀKp`, `x += α p`, `r −= α K p`, `z = M⁻¹ r`,
//! `β = rᵀz_new / rᵀz_old`, `p = z + β p`. It stops when the relative
//! residual `‖b − K x‖ / ‖b‖` (Euclidean norms, with the recursively
//! updated residual) is at most [`CgSettings::relative_tolerance`], or
//! reports [`CgSolution::converged`]` = false` with its last residual after
//! [`CgSettings::max_iterations`].

use super::{LinearSolver, LinearSolverInfo, SolveError, SolveStats};

/// A symmetric positive definite matrix, known through its products.
pub trait LinearOperator {
    /// Number of rows and columns.
    fn dimension(&self) -> usize;
    /// `y = K x` (`y` is overwritten).
    fn apply(&self, x: &[f64], y: &mut [f64]);
}

/// An approximation `M⁻¹` of the inverse of a matrix of type `A`.
pub trait Preconditioner<A: ?Sized> {
    /// Build the approximation for `matrix`.
    ///
    /// # Errors
    /// Implementations return a [`SolveError`] when the approximation
    /// cannot be built; [`BlockJacobi`](super::BlockJacobi) returns
    /// [`SolveError::DimensionMismatch`] for ranges that are not
    /// consecutive from 0 or that the matrix cannot cut its blocks at, and
    /// [`SolveError::Factorization`] naming a block that is not positive
    /// definite.
    fn setup(&mut self, matrix: &A) -> Result<(), SolveError>;
    /// `z = M⁻¹ r` (`z` is overwritten).
    fn apply(&self, r: &[f64], z: &mut [f64]);
    /// Stored entries.
    fn entries(&self) -> usize;
}

/// Stopping rule of the conjugate gradients.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CgSettings {
    /// Accepted relative residual `‖b − K x‖ / ‖b‖`.
    pub relative_tolerance: f64,
    /// Iteration limit.
    pub max_iterations: usize,
}

impl Default for CgSettings {
    /// `‖b − K x‖ ≤ 1e-10 ‖b‖`, 20 000 iterations.
    fn default() -> Self {
        Self {
            relative_tolerance: 1e-10,
            max_iterations: 20_000,
        }
    }
}

impl CgSettings {
    /// Check the values; errors name the field.
    ///
    /// # Errors
    /// [`SolveError::InvalidSetting`] for a relative tolerance that is not
    /// a finite number in (0, 1), or an iteration limit of 0.
    pub fn validate(&self) -> Result<(), SolveError> {
        let tol = self.relative_tolerance;
        if !(tol.is_finite() && tol > 0.0 && tol < 1.0) {
            return Err(SolveError::InvalidSetting {
                name: "CgSettings::relative_tolerance",
                value: tol,
                requirement: "must be a finite number in (0, 1), e.g. 1e-10",
            });
        }
        if self.max_iterations == 0 {
            return Err(SolveError::InvalidSetting {
                name: "CgSettings::max_iterations",
                value: 0.0,
                requirement: "must be at least 1, e.g. 20000",
            });
        }
        Ok(())
    }
}

/// What a PCG solve returns.
#[derive(Debug, Clone, PartialEq)]
pub struct CgSolution {
    /// The solution (the last iterate when not converged).
    pub x: Vec<f64>,
    /// Iterations made.
    pub iterations: usize,
    /// The last relative residual `‖r‖ / ‖b‖`.
    pub relative_residual: f64,
    /// Whether the tolerance was met.
    pub converged: bool,
}

/// The vectors of one PCG run, kept between solves.
#[derive(Debug, Clone, Default)]
struct Workspace {
    r: Vec<f64>,
    z: Vec<f64>,
    p: Vec<f64>,
    kp: Vec<f64>,
}

/// PCG with preconditioner `P` as a [`LinearSolver`]: factoring builds
/// the preconditioner, each solve runs PCG from zero.
#[derive(Debug, Clone)]
pub struct ConjugateGradient<P> {
    /// Stopping rule.
    pub settings: CgSettings,
    preconditioner: P,
    work: Workspace,
    dimension: Option<usize>,
    entries: Option<usize>,
}

impl<P> ConjugateGradient<P> {
    /// A solver with the stopping rule `settings` and the preconditioner
    /// `preconditioner` (built at each [`LinearSolver::factor`]).
    pub fn new(settings: CgSettings, preconditioner: P) -> Self {
        Self {
            settings,
            preconditioner,
            work: Workspace::default(),
            dimension: None,
            entries: None,
        }
    }

    /// The preconditioner.
    pub fn preconditioner(&self) -> &P {
        &self.preconditioner
    }
}

impl<A: LinearOperator + ?Sized, P: Preconditioner<A>> LinearSolver<A> for ConjugateGradient<P> {
    fn factor(&mut self, matrix: &A) -> Result<(), SolveError> {
        self.dimension = None;
        self.preconditioner.setup(matrix)?;
        self.dimension = Some(matrix.dimension());
        self.entries = Some(self.preconditioner.entries());
        Ok(())
    }

    fn solve_in_place(&mut self, matrix: &A, rhs: &mut [f64]) -> Result<SolveStats, SolveError> {
        let n = matrix.dimension();
        if self.dimension != Some(n) {
            return Err(SolveError::DimensionMismatch {
                what: "matrix solved with, against the one factored (none: 0)",
                expected: self.dimension.unwrap_or(0),
                found: n,
            });
        }
        let outcome = pcg(
            matrix,
            &self.preconditioner,
            rhs,
            &self.settings,
            &mut self.work,
        )?;
        Ok(SolveStats {
            iterations: outcome.iterations,
            relative_residual: Some(outcome.relative_residual),
            converged: outcome.converged,
        })
    }
}

impl<P> LinearSolverInfo for ConjugateGradient<P> {
    /// Always 0: PCG analyses no pattern.
    fn symbolic_analyses(&self) -> usize {
        0
    }

    /// Entries of the preconditioner built last.
    fn factor_entries(&self) -> Option<usize> {
        self.entries
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Iterations, last residual and convergence of a PCG run.
struct Outcome {
    iterations: usize,
    relative_residual: f64,
    converged: bool,
}

/// Solve `K x = b` by PCG (see the module documentation).
///
/// # Errors
/// [`SolveError::DimensionMismatch`] for a right-hand side whose length is
/// not the operator's dimension; [`SolveError::NonFinite`] for a
/// right-hand side entry that is not finite; [`SolveError::NonPositive`]
/// (with the iteration as its index) for a curvature `pᵀKp` that is not
/// positive (the matrix is not positive definite). A run that stops at
/// `settings.max_iterations` is not an error: see
/// [`CgSolution::converged`].
pub fn conjugate_gradient<A: LinearOperator + ?Sized, M: Preconditioner<A> + ?Sized>(
    operator: &A,
    preconditioner: &M,
    b: &[f64],
    settings: &CgSettings,
) -> Result<CgSolution, SolveError> {
    let mut x = b.to_vec();
    let outcome = pcg(
        operator,
        preconditioner,
        &mut x,
        settings,
        &mut Workspace::default(),
    )?;
    Ok(CgSolution {
        x,
        iterations: outcome.iterations,
        relative_residual: outcome.relative_residual,
        converged: outcome.converged,
    })
}

/// PCG on `x`, which holds `b` on entry and the solution on exit.
fn pcg<A: LinearOperator + ?Sized, M: Preconditioner<A> + ?Sized>(
    operator: &A,
    preconditioner: &M,
    x: &mut [f64],
    settings: &CgSettings,
    work: &mut Workspace,
) -> Result<Outcome, SolveError> {
    let n = operator.dimension();
    super::pattern::check_rhs(x, n)?;
    let b_norm = dot(x, x).sqrt();
    let Workspace { r, z, p, kp } = work;
    r.clear();
    r.extend_from_slice(x);
    x.fill(0.0);
    if b_norm == 0.0 {
        return Ok(Outcome {
            iterations: 0,
            relative_residual: 0.0,
            converged: true,
        });
    }
    z.resize(n, 0.0);
    kp.resize(n, 0.0);
    preconditioner.apply(r, z);
    p.clear();
    p.extend_from_slice(z);
    let mut rz = dot(r, z);
    let mut relative = 1.0;
    for iteration in 0..settings.max_iterations {
        operator.apply(p, kp);
        let curvature = dot(p, kp);
        if curvature.is_nan() || curvature <= 0.0 {
            return Err(SolveError::NonPositive {
                what: "curvature pᵀKp (matrix not positive definite)",
                index: iteration,
                value: curvature,
            });
        }
        let alpha = rz / curvature;
        for (((xi, ri), pi), kpi) in x.iter_mut().zip(r.iter_mut()).zip(p.iter()).zip(kp.iter()) {
            *xi += alpha * pi;
            *ri -= alpha * kpi;
        }
        relative = dot(r, r).sqrt() / b_norm;
        if relative <= settings.relative_tolerance {
            return Ok(Outcome {
                iterations: iteration + 1,
                relative_residual: relative,
                converged: true,
            });
        }
        preconditioner.apply(r, z);
        let rz_new = dot(r, z);
        let beta = rz_new / rz;
        rz = rz_new;
        for (pi, zi) in p.iter_mut().zip(z.iter()) {
            *pi = zi + beta * *pi;
        }
    }
    Ok(Outcome {
        iterations: settings.max_iterations,
        relative_residual: relative,
        converged: false,
    })
}

#[cfg(test)]
mod tests {
    use super::super::BlockJacobi;
    use super::*;
    use nalgebra::{DMatrix, DVector};

    struct Dense(DMatrix<f64>);

    impl LinearOperator for Dense {
        fn dimension(&self) -> usize {
            self.0.nrows()
        }
        fn apply(&self, x: &[f64], y: &mut [f64]) {
            let v = &self.0 * DVector::from_column_slice(x);
            y.copy_from_slice(v.as_slice());
        }
    }

    /// A 1D chain of springs, fixed at one end: spring i joins unknowns
    /// i − 1 and i; those inside each group of three unknowns are stiff.
    fn chain(n: usize) -> DMatrix<f64> {
        let k = |i: usize| if i % 3 == 0 { 1.0 + i as f64 } else { 1e4 };
        let mut m = DMatrix::zeros(n, n);
        for i in 0..n {
            m[(i, i)] += k(i);
            if i + 1 < n {
                m[(i, i)] += k(i + 1);
                m[(i, i + 1)] -= k(i + 1);
                m[(i + 1, i)] -= k(i + 1);
            }
        }
        m
    }

    #[test]
    fn pcg_with_block_jacobi_reproduces_the_dense_solution() {
        let n = 30;
        let k = chain(n);
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).sin()).collect();
        let exact = k
            .clone()
            .cholesky()
            .unwrap()
            .solve(&DVector::from_column_slice(&b));
        let blocks = (0..n / 3)
            .map(|q| k.view((3 * q, 3 * q), (3, 3)).into_owned())
            .collect();
        let preconditioner = BlockJacobi::from_blocks(blocks).unwrap();
        assert_eq!(preconditioner.dimension(), n);
        let settings = CgSettings {
            relative_tolerance: 1e-12,
            max_iterations: 1000,
        };
        let identity = BlockJacobi::from_blocks(vec![DMatrix::identity(n, n)]).unwrap();
        let plain = conjugate_gradient(&Dense(k.clone()), &identity, &b, &settings).unwrap();
        let solution =
            conjugate_gradient(&Dense(k.clone()), &preconditioner, &b, &settings).unwrap();
        assert!(solution.converged && solution.relative_residual <= 1e-12);
        let error = (DVector::from_column_slice(&solution.x) - &exact).norm() / exact.norm();
        assert!(error < 1e-8, "relative error {error}");
        // The blocks hold the stiff springs: fewer iterations than plain CG.
        assert!(
            solution.iterations < plain.iterations,
            "{} vs {}",
            solution.iterations,
            plain.iterations
        );
        // The same through the solver slot, the blocks built from the matrix.
        let groups = (0..n / 3).map(|q| 3 * q..3 * q + 3).collect();
        let mut solver = ConjugateGradient::new(settings, BlockJacobi::new(groups));
        let matrix = Dense(k);
        solver.factor(&matrix).unwrap();
        let mut x = b.clone();
        let stats = solver.solve_in_place(&matrix, &mut x).unwrap();
        assert_eq!(x, solution.x);
        assert_eq!(stats.iterations, solution.iterations);
        assert_eq!(solver.factor_entries(), Some(9 * (n / 3)));
    }

    #[test]
    fn an_iteration_limit_is_reported_with_the_last_residual() {
        let k = chain(40);
        let b = vec![1.0; 40];
        let identity = BlockJacobi::from_blocks(vec![DMatrix::identity(40, 40)]).unwrap();
        let settings = CgSettings {
            relative_tolerance: 1e-14,
            max_iterations: 3,
        };
        let s = conjugate_gradient(&Dense(k), &identity, &b, &settings).unwrap();
        assert!(!s.converged);
        assert_eq!(s.iterations, 3);
        assert!(s.relative_residual > 1e-14);
    }

    impl super::super::DiagonalBlocks for Dense {
        fn diagonal_blocks(
            &self,
            ranges: &[std::ops::Range<usize>],
        ) -> Result<Vec<DMatrix<f64>>, SolveError> {
            Ok(ranges
                .iter()
                .map(|r| {
                    self.0
                        .view((r.start, r.start), (r.len(), r.len()))
                        .into_owned()
                })
                .collect())
        }
    }
}
