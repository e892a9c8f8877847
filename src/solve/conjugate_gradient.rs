//! Preconditioned conjugate gradients for symmetric positive definite
//! systems `K x = b`, with a block-Jacobi preconditioner.
//!
//! An alternative to [`super::SparseDirectSolver`] where a sparse Cholesky
//! factor is too large: only `K x` products are needed (the matrix may be
//! kept in any form implementing [`LinearOperator`]), and memory is a few
//! vectors plus the preconditioner.
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
//!
//! # Block-Jacobi preconditioner
//!
//! [`BlockJacobi`] partitions the unknowns into consecutive blocks, takes
//! the dense diagonal block of `K` on each, and applies the inverse of
//! each block (from its dense Cholesky factor), the blocks in parallel. Choosing blocks that hold strongly coupled
//! unknowns (for HPM, all the elements of one grid column) removes those
//! couplings from the condition number that PCG sees.

use std::marker::PhantomData;

use nalgebra::{DMatrix, DVectorView, DVectorViewMut};
use rayon::prelude::*;

use super::{GlobalSolver, SolveError};

/// A symmetric positive definite matrix, known through its products.
pub trait LinearOperator {
    /// Number of rows and columns.
    fn dimension(&self) -> usize;
    /// `y = K x` (`y` is overwritten).
    fn apply(&self, x: &[f64], y: &mut [f64]);
}

/// An approximation `M⁻¹` of the inverse of the matrix.
pub trait Preconditioner {
    /// `z = M⁻¹ r` (`z` is overwritten).
    fn apply(&self, r: &[f64], z: &mut [f64]);
}

/// Stopping rule of [`ConjugateGradientSolver`].
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

/// The system a [`ConjugateGradientSolver`] solves.
#[derive(Debug, Clone)]
pub struct CgSystem<A, M> {
    /// `K`.
    pub operator: A,
    /// `M⁻¹`.
    pub preconditioner: M,
    /// `b`.
    pub rhs: Vec<f64>,
}

/// Preconditioned conjugate gradients as a [`GlobalSolver`].
#[derive(Debug, Clone)]
pub struct ConjugateGradientSolver<A, M> {
    /// Stopping rule.
    pub settings: CgSettings,
    marker: PhantomData<fn() -> (A, M)>,
}

impl<A, M> ConjugateGradientSolver<A, M> {
    /// A solver with the stopping rule `settings`.
    pub fn new(settings: CgSettings) -> Self {
        Self {
            settings,
            marker: PhantomData,
        }
    }
}

impl<A: LinearOperator, M: Preconditioner> GlobalSolver for ConjugateGradientSolver<A, M> {
    type System = CgSystem<A, M>;
    type Solution = CgSolution;

    fn solve(&mut self, system: &Self::System) -> Result<CgSolution, SolveError> {
        conjugate_gradient(
            &system.operator,
            &system.preconditioner,
            &system.rhs,
            &self.settings,
        )
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Solve `K x = b` by PCG (see the module documentation).
pub fn conjugate_gradient<A: LinearOperator + ?Sized, M: Preconditioner + ?Sized>(
    operator: &A,
    preconditioner: &M,
    b: &[f64],
    settings: &CgSettings,
) -> Result<CgSolution, SolveError> {
    let n = operator.dimension();
    if b.len() != n {
        return Err(SolveError::DimensionMismatch {
            what: "right-hand side length",
            expected: n,
            found: b.len(),
        });
    }
    if let Some((index, &value)) = b.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(SolveError::NonFinite {
            what: "right-hand side",
            index,
            value,
        });
    }
    let b_norm = dot(b, b).sqrt();
    let mut x = vec![0.0; n];
    if b_norm == 0.0 {
        return Ok(CgSolution {
            x,
            iterations: 0,
            relative_residual: 0.0,
            converged: true,
        });
    }
    let mut r = b.to_vec();
    let mut z = vec![0.0; n];
    preconditioner.apply(&r, &mut z);
    let mut p = z.clone();
    let mut kp = vec![0.0; n];
    let mut rz = dot(&r, &z);
    let mut relative = 1.0;
    for iteration in 0..settings.max_iterations {
        operator.apply(&p, &mut kp);
        let curvature = dot(&p, &kp);
        if curvature.is_nan() || curvature <= 0.0 {
            return Err(SolveError::NonPositive {
                what: "curvature pᵀKp (matrix not positive definite)",
                index: iteration,
                value: curvature,
            });
        }
        let alpha = rz / curvature;
        for i in 0..n {
            x[i] += alpha * p[i];
            r[i] -= alpha * kp[i];
        }
        relative = dot(&r, &r).sqrt() / b_norm;
        if relative <= settings.relative_tolerance {
            return Ok(CgSolution {
                x,
                iterations: iteration + 1,
                relative_residual: relative,
                converged: true,
            });
        }
        preconditioner.apply(&r, &mut z);
        let rz_new = dot(&r, &z);
        let beta = rz_new / rz;
        rz = rz_new;
        for (pi, zi) in p.iter_mut().zip(&z) {
            *pi = zi + beta * *pi;
        }
    }
    Ok(CgSolution {
        x,
        iterations: settings.max_iterations,
        relative_residual: relative,
        converged: false,
    })
}

/// `M⁻¹ = blockdiag(K_11, K_22, …)⁻¹` over consecutive blocks of unknowns.
#[derive(Debug, Clone)]
pub struct BlockJacobi {
    /// First unknown of each block.
    offsets: Vec<usize>,
    /// Inverse of each block (from its Cholesky factor), applied as a
    /// dense product.
    inverses: Vec<DMatrix<f64>>,
}

impl BlockJacobi {
    /// Factorise the diagonal blocks `blocks`, which cover the unknowns in
    /// order (the first block starts at unknown 0, each next one where the
    /// previous ends). A block that is not positive definite is an error
    /// naming its index.
    pub fn new(blocks: Vec<DMatrix<f64>>) -> Result<Self, SolveError> {
        let mut offsets = Vec::with_capacity(blocks.len());
        let mut inverses = Vec::with_capacity(blocks.len());
        let mut start = 0;
        for (index, block) in blocks.into_iter().enumerate() {
            if !block.is_square() {
                return Err(SolveError::DimensionMismatch {
                    what: "block-Jacobi block columns",
                    expected: block.nrows(),
                    found: block.ncols(),
                });
            }
            let size = block.nrows();
            let factor = block.cholesky().ok_or_else(|| {
                SolveError::Factorization(format!(
                    "block-Jacobi block {index} is not positive definite"
                ))
            })?;
            offsets.push(start);
            inverses.push(factor.inverse());
            start += size;
        }
        offsets.push(start);
        Ok(Self { offsets, inverses })
    }

    /// Number of unknowns covered.
    pub fn dimension(&self) -> usize {
        *self.offsets.last().unwrap_or(&0)
    }
}

impl Preconditioner for BlockJacobi {
    /// `z_k = K_kk⁻¹ r_k`, the blocks in parallel (rayon).
    fn apply(&self, r: &[f64], z: &mut [f64]) {
        let mut parts = Vec::with_capacity(self.inverses.len());
        let mut rest = z;
        for k in 0..self.inverses.len() {
            let (part, tail) = rest.split_at_mut(self.offsets[k + 1] - self.offsets[k]);
            parts.push(part);
            rest = tail;
        }
        parts
            .into_par_iter()
            .zip(&self.inverses)
            .zip(&self.offsets)
            .for_each(|((part, inverse), &a)| {
                let v = DVectorView::from_slice(&r[a..a + part.len()], part.len());
                let mut out = DVectorViewMut::from_slice(part, v.len());
                out.gemv(1.0, inverse, &v, 0.0);
            });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DVector;

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
        let preconditioner = BlockJacobi::new(blocks).unwrap();
        assert_eq!(preconditioner.dimension(), n);
        let settings = CgSettings {
            relative_tolerance: 1e-12,
            max_iterations: 1000,
        };
        let identity = BlockJacobi::new(vec![DMatrix::identity(n, n)]).unwrap();
        let plain = conjugate_gradient(&Dense(k.clone()), &identity, &b, &settings).unwrap();
        let mut solver = ConjugateGradientSolver::new(settings);
        let solution = solver
            .solve(&CgSystem {
                operator: Dense(k),
                preconditioner,
                rhs: b,
            })
            .unwrap();
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
    }

    #[test]
    fn an_iteration_limit_is_reported_with_the_last_residual() {
        let k = chain(40);
        let b = vec![1.0; 40];
        let identity = BlockJacobi::new(vec![DMatrix::identity(40, 40)]).unwrap();
        let settings = CgSettings {
            relative_tolerance: 1e-14,
            max_iterations: 3,
        };
        let s = conjugate_gradient(&Dense(k), &identity, &b, &settings).unwrap();
        assert!(!s.converged);
        assert_eq!(s.iterations, 3);
        assert!(s.relative_residual > 1e-14);
    }
}
