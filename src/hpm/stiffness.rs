//! The global HPM stiffness of eq. (4) as 12 × 12 blocks, and how the
//! linear solvers read it.
//!
//! Elements couple only through faces, so the matrix is kept as one
//! diagonal block per element and one off-diagonal block per pair of
//! elements sharing a face. It is a [`LinearOperator`] (the product by
//! block rows, in parallel) for the conjugate gradients, hands its dense
//! diagonal blocks to [`crate::linsolve::BlockJacobi`], and is converted
//! to its compressed lower triangle (no triplet list) for
//! [`SparseCholesky`].

use std::ops::Range;
use std::sync::OnceLock;
use std::time::Instant;

use nalgebra::DMatrix;
use rayon::prelude::*;

use crate::kinematics::affine3::{Block, ElementDofs, ELEMENT_DOF};
use crate::linsolve::{
    BlockSparse, DiagonalBlocks, LinearOperator, LinearSolver, SolveError, SolveStats,
    SparseCholesky, SparseMatrix, SparsePattern,
};

/// A symmetric block-sparse matrix: a diagonal block per element and
/// coupling blocks `K_ab` (a ≠ b; `K_ba = K_abᵀ` is implied).
#[derive(Debug, Clone)]
pub struct BlockMatrix {
    diagonal: Vec<Block>,
    coupling: Vec<(usize, usize, Block)>,
    /// The coupling blocks by block rows, for the parallel product; built
    /// at the first product after the last coupling was added.
    rows: OnceLock<BlockRows>,
}

impl PartialEq for BlockMatrix {
    fn eq(&self, other: &Self) -> bool {
        self.diagonal == other.diagonal && self.coupling == other.coupling
    }
}

/// Block row `a` holds `entries[start[a]..start[a + 1]]`, each
/// `(b, k, transposed)`: coupling block `k` in column `b` (stored as
/// `K_baᵀ` when `transposed`).
#[derive(Debug, Clone)]
struct BlockRows {
    start: Vec<usize>,
    entries: Vec<(usize, usize, bool)>,
}

impl BlockRows {
    fn new(elements: usize, coupling: &[(usize, usize, Block)]) -> Self {
        let mut start = vec![0; elements + 1];
        for (a, b, _) in coupling {
            start[a + 1] += 1;
            start[b + 1] += 1;
        }
        for e in 0..elements {
            start[e + 1] += start[e];
        }
        let mut next = start.clone();
        let mut entries = vec![(0, 0, false); start[elements]];
        for (k, (a, b, _)) in coupling.iter().enumerate() {
            entries[next[*a]] = (*b, k, false);
            next[*a] += 1;
            entries[next[*b]] = (*a, k, true);
            next[*b] += 1;
        }
        Self { start, entries }
    }
}

impl BlockMatrix {
    /// A zero matrix for `elements` elements.
    pub fn zeros(elements: usize) -> Self {
        Self {
            diagonal: vec![Block::zeros(); elements],
            coupling: Vec::new(),
            rows: OnceLock::new(),
        }
    }

    /// A zero matrix for `elements` elements with room for `couplings`
    /// coupling blocks, so that adding them never reallocates.
    pub(super) fn with_capacity(elements: usize, couplings: usize) -> Self {
        Self {
            diagonal: vec![Block::zeros(); elements],
            coupling: Vec::with_capacity(couplings),
            rows: OnceLock::new(),
        }
    }

    /// Dimension (12 × elements).
    pub fn dimension(&self) -> usize {
        ELEMENT_DOF * self.diagonal.len()
    }

    /// The diagonal blocks, one per element.
    pub fn diagonal(&self) -> &[Block] {
        &self.diagonal
    }

    /// The diagonal blocks, to add to.
    pub fn diagonal_mut(&mut self) -> &mut [Block] {
        &mut self.diagonal
    }

    /// The coupling blocks `(a, b, K_ab)`, in the order added.
    pub fn couplings(&self) -> &[(usize, usize, Block)] {
        &self.coupling
    }

    /// Add the coupling block `K_ab` of elements `a ≠ b` (`K_ba = K_abᵀ`).
    ///
    /// # Panics
    /// If `a` or `b` is not an element of the matrix, or `a = b` (as
    /// indexing [`BlockMatrix::diagonal_mut`] out of range would).
    pub fn add_coupling(&mut self, a: usize, b: usize, block: Block) {
        let n = self.diagonal.len();
        assert!(
            a < n && b < n && a != b,
            "coupling block ({a}, {b}) of a matrix of {n} elements"
        );
        self.coupling.push((a, b, block));
        self.rows = OnceLock::new();
    }

    /// `y = K x`, block by block in the order of the blocks (sequential; the
    /// residuals of the analyses use it).
    pub fn multiply(&self, x: &[f64]) -> Vec<f64> {
        let block = |v: &[f64], e: usize| {
            ElementDofs::from_column_slice(&v[ELEMENT_DOF * e..ELEMENT_DOF * (e + 1)])
        };
        let add = |y: &mut [f64], e: usize, v: ElementDofs| {
            for (k, value) in v.iter().enumerate() {
                y[ELEMENT_DOF * e + k] += value;
            }
        };
        let mut y = vec![0.0; x.len()];
        for (e, d) in self.diagonal.iter().enumerate() {
            add(&mut y, e, d * block(x, e));
        }
        for (a, b, k) in &self.coupling {
            add(&mut y, *a, k * block(x, *b));
            add(&mut y, *b, k.transpose() * block(x, *a));
        }
        y
    }

    /// The dense diagonal blocks of K over consecutive groups of elements
    /// (`groups` in order, covering all elements): the blocks of a
    /// [`crate::linsolve::BlockJacobi`] preconditioner. For HPM the group
    /// of a grid column holds its layers, which the stiff penalty springs
    /// between layers (eqs. 20–22) couple.
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

    /// The lower triangle in compressed columns, built from the blocks.
    ///
    /// # Errors
    /// Only if the blocks are inconsistent (not expected from
    /// [`BlockMatrix::add_coupling`]).
    pub fn lower_triangle(&self) -> Result<SparseMatrix, SolveError> {
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
        SparseMatrix::new(SparsePattern::from_columns(n, col_ptr, row_idx)?, values)
    }
}

impl LinearOperator for BlockMatrix {
    fn dimension(&self) -> usize {
        BlockMatrix::dimension(self)
    }

    /// `y = K x` by block rows, the rows in parallel (rayon).
    fn apply(&self, x: &[f64], y: &mut [f64]) {
        let block =
            |e: usize| ElementDofs::from_column_slice(&x[ELEMENT_DOF * e..ELEMENT_DOF * (e + 1)]);
        let rows = self
            .rows
            .get_or_init(|| BlockRows::new(self.diagonal.len(), &self.coupling));
        y.par_chunks_mut(ELEMENT_DOF)
            .enumerate()
            .for_each(|(a, out)| {
                let mut sum = self.diagonal[a] * block(a);
                for &(b, k, transposed) in &rows.entries[rows.start[a]..rows.start[a + 1]] {
                    let coupling = &self.coupling[k].2;
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

impl BlockSparse for BlockMatrix {
    fn block_size(&self) -> usize {
        ELEMENT_DOF
    }

    fn block_count(&self) -> usize {
        self.diagonal.len()
    }

    /// The diagonal blocks and each coupling block twice (`K_ab`, `K_ba`).
    fn visit_blocks(&self, visit: &mut dyn FnMut(usize, usize, &[f64])) {
        // nalgebra stores by columns: the entries of `Kᵀ` by rows.
        for (e, d) in self.diagonal.iter().enumerate() {
            visit(e, e, d.transpose().as_slice());
        }
        for (a, b, k) in &self.coupling {
            visit(*b, *a, k.as_slice());
            visit(*a, *b, k.transpose().as_slice());
        }
    }
}

impl DiagonalBlocks for BlockMatrix {
    /// The blocks over ranges of unknowns that hold whole elements.
    fn diagonal_blocks(&self, ranges: &[Range<usize>]) -> Result<Vec<DMatrix<f64>>, SolveError> {
        let mut groups = Vec::with_capacity(ranges.len());
        for range in ranges {
            for bound in [range.start, range.end] {
                if bound % ELEMENT_DOF != 0 || bound > self.dimension() {
                    return Err(SolveError::DimensionMismatch {
                        what:
                            "bound of a block-Jacobi range (a multiple of 12 up to the dimension)",
                        expected: ELEMENT_DOF * (bound / ELEMENT_DOF),
                        found: bound,
                    });
                }
            }
            groups.push(range.start / ELEMENT_DOF..range.end / ELEMENT_DOF);
        }
        Ok(self.group_blocks(&groups))
    }
}

/// The sparse Cholesky factor of the stiffness: its lower triangle in
/// compressed columns (the conversion timed in
/// [`crate::linsolve::CholeskyTimings::convert`]), factored once and kept
/// for the repeated solves of the nonlinear iteration.
fn check_rhs_length(matrix: &BlockMatrix, rhs: &[f64]) -> Result<(), SolveError> {
    if rhs.len() == matrix.dimension() {
        Ok(())
    } else {
        Err(SolveError::DimensionMismatch {
            what: "right-hand side length",
            expected: matrix.dimension(),
            found: rhs.len(),
        })
    }
}

impl LinearSolver<BlockMatrix> for SparseCholesky {
    fn factor(&mut self, matrix: &BlockMatrix) -> Result<(), SolveError> {
        let start = Instant::now();
        let lower = matrix.lower_triangle()?;
        let convert = start.elapsed();
        LinearSolver::<SparseMatrix>::factor(self, &lower)?;
        self.record_conversion(convert);
        Ok(())
    }

    fn solve_in_place(
        &mut self,
        matrix: &BlockMatrix,
        rhs: &mut [f64],
    ) -> Result<SolveStats, SolveError> {
        check_rhs_length(matrix, rhs)?;
        self.solve_factored(rhs)
    }
}
