//! The global HPM stiffness of eq. (4) as 12 × 12 blocks, and its sparse
//! Cholesky factor (faer).
//!
//! Elements couple only through faces, so the matrix is kept as one
//! diagonal block per element and one off-diagonal block per pair of
//! elements sharing a face. The compressed lower triangle is built
//! directly from the blocks (no triplet list), analysed and factorised
//! once; the factor is kept for the repeated solves of the nonlinear
//! iteration.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::prelude::Reborrow;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LltRef, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use faer::{Col, Side};
use std::time::{Duration, Instant};

use std::ops::Range;

use nalgebra::DMatrix;
use rayon::prelude::*;

use super::element::{Block, ElementDofs, ELEMENT_DOF};
use crate::solve::{LinearOperator, SolveError};

/// A symmetric block-sparse matrix: `diagonal[e]` and `coupling` blocks
/// `K_ab` (a ≠ b; `K_ba = K_abᵀ` is implied).
#[derive(Debug, Clone, PartialEq)]
pub struct BlockMatrix {
    /// Diagonal blocks, one per element.
    pub diagonal: Vec<Block>,
    /// Off-diagonal blocks `(a, b, K_ab)`, one per pair of elements.
    pub coupling: Vec<(usize, usize, Block)>,
}

impl BlockMatrix {
    /// A zero matrix for `elements` elements.
    pub fn zeros(elements: usize) -> Self {
        Self {
            diagonal: vec![Block::zeros(); elements],
            coupling: Vec::new(),
        }
    }

    /// Dimension (12 × elements).
    pub fn dimension(&self) -> usize {
        ELEMENT_DOF * self.diagonal.len()
    }

    /// `y = K x`.
    pub fn multiply(&self, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; x.len()];
        self.apply(x, &mut y);
        y
    }

    /// The dense diagonal blocks of K over consecutive groups of elements
    /// (`groups` in order, covering all elements): the blocks of a
    /// [`crate::solve::BlockJacobi`] preconditioner. For HPM the group of a grid column
    /// holds its layers, which the stiff penalty springs between layers
    /// (eqs. 20–22) couple.
    pub fn group_blocks(&self, groups: &[Range<usize>]) -> Vec<DMatrix<f64>> {
        let mut group_of = vec![0; self.diagonal.len()];
        let mut blocks: Vec<DMatrix<f64>> = groups
            .iter()
            .enumerate()
            .map(|(g, range)| {
                group_of[range.clone()].fill(g);
                let m = ELEMENT_DOF * range.len();
                let mut block = DMatrix::zeros(m, m);
                for e in range.clone() {
                    let i = ELEMENT_DOF * (e - range.start);
                    block
                        .view_mut((i, i), (ELEMENT_DOF, ELEMENT_DOF))
                        .copy_from(&self.diagonal[e]);
                }
                block
            })
            .collect();
        for (a, b, k) in &self.coupling {
            let g = group_of[*a];
            if group_of[*b] != g {
                continue;
            }
            let start = groups[g].start;
            let (i, j) = (ELEMENT_DOF * (a - start), ELEMENT_DOF * (b - start));
            let block = &mut blocks[g];
            block
                .view_mut((i, j), (ELEMENT_DOF, ELEMENT_DOF))
                .copy_from(k);
            block
                .view_mut((j, i), (ELEMENT_DOF, ELEMENT_DOF))
                .copy_from(&k.transpose());
        }
        blocks
    }
}

/// A [`BlockMatrix`] by block rows: `rows[a]` lists `(b, k, transposed)`,
/// the coupling block `k` of row a with column b (`K_ab`, stored as
/// `K_baᵀ` when `transposed`). Its product runs over the rows in parallel
/// (rayon).
#[derive(Debug, Clone)]
pub struct BlockRows<'a> {
    matrix: &'a BlockMatrix,
    rows: Vec<Vec<(usize, usize, bool)>>,
}

impl LinearOperator for BlockRows<'_> {
    fn dimension(&self) -> usize {
        self.matrix.dimension()
    }

    fn apply(&self, x: &[f64], y: &mut [f64]) {
        let block =
            |e: usize| ElementDofs::from_column_slice(&x[ELEMENT_DOF * e..ELEMENT_DOF * (e + 1)]);
        y.par_chunks_mut(ELEMENT_DOF)
            .zip(&self.rows)
            .enumerate()
            .for_each(|(a, (out, row))| {
                let mut sum = self.matrix.diagonal[a] * block(a);
                for &(b, k, transposed) in row {
                    let coupling = &self.matrix.coupling[k].2;
                    if transposed {
                        sum += coupling.tr_mul(&block(b));
                    } else {
                        sum += coupling * block(b);
                    }
                }
                out.copy_from_slice(sum.as_slice());
            });
    }
}

impl LinearOperator for BlockMatrix {
    fn dimension(&self) -> usize {
        BlockMatrix::dimension(self)
    }

    /// `y = K x`, block by block.
    fn apply(&self, x: &[f64], y: &mut [f64]) {
        let block = |v: &[f64], e: usize| {
            ElementDofs::from_column_slice(&v[ELEMENT_DOF * e..ELEMENT_DOF * (e + 1)])
        };
        let add = |y: &mut [f64], e: usize, v: ElementDofs| {
            for (k, value) in v.iter().enumerate() {
                y[ELEMENT_DOF * e + k] += value;
            }
        };
        y.fill(0.0);
        for (e, d) in self.diagonal.iter().enumerate() {
            add(y, e, d * block(x, e));
        }
        for (a, b, k) in &self.coupling {
            add(y, *a, k * block(x, *b));
            add(y, *b, k.transpose() * block(x, *a));
        }
    }
}

impl BlockMatrix {
    /// The blocks of K arranged by block row, for parallel products
    /// ([`BlockRows`]).
    pub fn rows(&self) -> BlockRows<'_> {
        let mut rows: Vec<Vec<(usize, usize, bool)>> = vec![Vec::new(); self.diagonal.len()];
        for (k, (a, b, _)) in self.coupling.iter().enumerate() {
            rows[*a].push((*b, k, false));
            rows[*b].push((*a, k, true));
        }
        BlockRows { matrix: self, rows }
    }

    /// The lower triangle in compressed-column form.
    fn lower_csc(&self) -> Result<SparseColMat<usize, f64>, SolveError> {
        let elements = self.diagonal.len();
        let n = self.dimension();
        // Blocks of block-column b below the diagonal: (row element, block, transposed?).
        let mut below: Vec<Vec<(usize, usize, bool)>> = vec![Vec::new(); elements];
        for (k, (a, b, _)) in self.coupling.iter().enumerate() {
            if a > b {
                below[*b].push((*a, k, false));
            } else {
                below[*a].push((*b, k, true));
            }
        }
        for list in &mut below {
            list.sort_unstable();
        }
        let nnz: usize = below
            .iter()
            .map(|l| l.len() * ELEMENT_DOF * ELEMENT_DOF)
            .sum::<usize>()
            + elements * ELEMENT_DOF * (ELEMENT_DOF + 1) / 2;
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::with_capacity(nnz);
        let mut values = Vec::with_capacity(nnz);
        col_ptr.push(0usize);
        for (b, list) in below.iter().enumerate() {
            for q in 0..ELEMENT_DOF {
                for p in q..ELEMENT_DOF {
                    row_idx.push(ELEMENT_DOF * b + p);
                    values.push(self.diagonal[b][(p, q)]);
                }
                for &(a, k, transposed) in list {
                    let block = &self.coupling[k].2;
                    for p in 0..ELEMENT_DOF {
                        row_idx.push(ELEMENT_DOF * a + p);
                        values.push(if transposed {
                            block[(q, p)]
                        } else {
                            block[(p, q)]
                        });
                    }
                }
                col_ptr.push(row_idx.len());
            }
        }
        let symbolic = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        Ok(SparseColMat::new(symbolic, values))
    }

    /// Factorise `K = L Lᵀ`: faer's sparse Cholesky with its
    /// approximate-minimum-degree ordering, supernodal where it pays, on
    /// faer's global parallelism.
    pub fn factorize(&self) -> Result<CholeskyFactor, SolveError> {
        let start = Instant::now();
        let matrix = self.lower_csc()?;
        let compressed = Instant::now();
        let failed = |what: &str, e: &dyn std::fmt::Debug| {
            SolveError::Factorization(format!("{what} failed: {e:?}"))
        };
        let symbolic = factorize_symbolic_cholesky(
            matrix.symbolic(),
            Side::Lower,
            SymmetricOrdering::Amd,
            Default::default(),
        )
        .map_err(|e| failed("symbolic Cholesky analysis", &e))?;
        let analysed = Instant::now();
        let par = faer::get_global_parallelism();
        let mut values = vec![0.0; symbolic.len_val()];
        let mut buffer = MemBuffer::try_new(
            symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()),
        )
        .map_err(|e| failed("allocating the Cholesky workspace", &e))?;
        symbolic
            .factorize_numeric_llt::<f64>(
                &mut values,
                matrix.rb(),
                Side::Lower,
                Default::default(),
                par,
                MemStack::new(&mut buffer),
                Default::default(),
            )
            .map_err(|e| failed("sparse Cholesky (stiffness not positive definite)", &e))?;
        let timings = FactorTimings {
            compress: compressed - start,
            symbolic: analysed - compressed,
            numeric: analysed.elapsed(),
        };
        Ok(CholeskyFactor {
            symbolic,
            values,
            stored: matrix.compute_nnz(),
            timings,
        })
    }
}

/// Wall-clock times of the stages of [`BlockMatrix::factorize`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FactorTimings {
    /// Blocks to the compressed lower triangle.
    pub compress: Duration,
    /// Ordering (AMD) and symbolic factorisation.
    pub symbolic: Duration,
    /// Numeric factorisation.
    pub numeric: Duration,
}

/// A sparse Cholesky factor of the stiffness, reused for many solves.
#[derive(Debug)]
pub struct CholeskyFactor {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    stored: usize,
    timings: FactorTimings,
}

impl CholeskyFactor {
    /// Solve `K x = b`.
    pub fn solve(&self, b: &[f64]) -> Result<Vec<f64>, SolveError> {
        let n = self.symbolic.nrows();
        if b.len() != n {
            return Err(SolveError::DimensionMismatch {
                what: "right-hand side length",
                expected: n,
                found: b.len(),
            });
        }
        // One right-hand side: the triangular solves run sequentially (the
        // factorisation uses faer's global parallelism).
        let par = faer::Par::Seq;
        let mut buffer = MemBuffer::try_new(self.symbolic.solve_in_place_scratch::<f64>(1, par))
            .map_err(|e| {
                SolveError::Factorization(format!("allocating the solve workspace failed: {e:?}"))
            })?;
        let mut x = Col::<f64>::from_fn(n, |i| b[i]);
        LltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
            faer::Conj::No,
            x.as_mat_mut(),
            par,
            MemStack::new(&mut buffer),
        );
        let x: Vec<f64> = x.iter().copied().collect();
        if let Some((index, &value)) = x.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(SolveError::NonFinite {
                what: "stiffness solve",
                index,
                value,
            });
        }
        Ok(x)
    }

    /// Number of stored entries of the lower triangle of K.
    pub fn matrix_entries(&self) -> usize {
        self.stored
    }

    /// How long the stages of the factorisation took.
    pub fn timings(&self) -> FactorTimings {
        self.timings
    }

    /// Number of stored entries of the Cholesky factor L.
    pub fn factor_entries(&self) -> usize {
        self.values.len()
    }
}
