//! The block-Jacobi preconditioner: the inverse of the dense diagonal
//! blocks of a matrix over consecutive ranges of unknowns.
//!
//! Choosing ranges that hold strongly coupled unknowns (for HPM, all the
//! elements of one grid column) removes those couplings from the condition
//! number that the conjugate gradients see.

use std::ops::Range;

use nalgebra::{DMatrix, DVectorView, DVectorViewMut};
use rayon::prelude::*;

use super::conjugate_gradient::Preconditioner;
use super::pattern::SparseMatrix;
use super::{FactorizationFailure, SolveError};

/// A matrix that can hand out its dense diagonal blocks.
pub trait DiagonalBlocks {
    /// The dense diagonal blocks over `ranges` of unknowns (consecutive,
    /// from 0).
    ///
    /// # Errors
    /// Implementations return [`SolveError::DimensionMismatch`] for ranges
    /// the matrix cannot cut its blocks at (for [`SparseMatrix`], a range
    /// that ends beyond its dimension).
    fn diagonal_blocks(&self, ranges: &[Range<usize>]) -> Result<Vec<DMatrix<f64>>, SolveError>;
}

impl DiagonalBlocks for SparseMatrix {
    fn diagonal_blocks(&self, ranges: &[Range<usize>]) -> Result<Vec<DMatrix<f64>>, SolveError> {
        let n = self.dimension();
        let mut owner = vec![usize::MAX; n];
        for (g, range) in ranges.iter().enumerate() {
            if range.end > n {
                return Err(SolveError::DimensionMismatch {
                    what: "end of a block-Jacobi range (expected at most the dimension)",
                    expected: n,
                    found: range.end,
                });
            }
            owner[range.clone()].fill(g);
        }
        let mut blocks: Vec<DMatrix<f64>> = ranges
            .iter()
            .map(|r| DMatrix::zeros(r.len(), r.len()))
            .collect();
        let (col_ptr, row_idx) = (self.pattern().col_ptr(), self.pattern().row_idx());
        for j in 0..n {
            let g = owner[j];
            if g == usize::MAX {
                continue;
            }
            let column = col_ptr[j]..col_ptr[j + 1];
            for (&i, &value) in row_idx[column.clone()].iter().zip(&self.values()[column]) {
                if owner[i] == g {
                    let start = ranges[g].start;
                    blocks[g][(i - start, j - start)] = value;
                }
            }
        }
        Ok(blocks)
    }
}

/// `M⁻¹ = blockdiag(K_11, K_22, …)⁻¹` over consecutive ranges of unknowns.
#[derive(Debug, Clone, Default)]
pub struct BlockJacobi {
    /// The ranges of unknowns, consecutive from 0.
    ranges: Vec<Range<usize>>,
    /// Inverse of each block (from its Cholesky factor), applied as a
    /// dense product.
    inverses: Vec<DMatrix<f64>>,
}

impl BlockJacobi {
    /// A preconditioner over the consecutive `ranges` of unknowns, built
    /// from the matrix at [`Preconditioner::setup`].
    pub fn new(ranges: Vec<Range<usize>>) -> Self {
        Self {
            ranges,
            inverses: Vec::new(),
        }
    }

    /// Factorise the diagonal blocks `blocks`, which cover the unknowns in
    /// order (the first block starts at unknown 0, each next one where the
    /// previous ends).
    ///
    /// # Errors
    /// [`SolveError::DimensionMismatch`] for a block that is not square;
    /// [`SolveError::Factorization`] naming the index of a block that is
    /// not positive definite (its Cholesky factorization fails).
    pub fn from_blocks(blocks: Vec<DMatrix<f64>>) -> Result<Self, SolveError> {
        let mut ranges = Vec::with_capacity(blocks.len());
        let mut start = 0;
        for block in &blocks {
            ranges.push(start..start + block.nrows());
            start += block.nrows();
        }
        let mut out = Self::new(ranges);
        out.invert(blocks)?;
        Ok(out)
    }

    fn invert(&mut self, blocks: Vec<DMatrix<f64>>) -> Result<(), SolveError> {
        self.inverses.clear();
        // In parallel; the first failing block in order is reported.
        let inverses: Vec<Result<DMatrix<f64>, SolveError>> = blocks
            .into_par_iter()
            .enumerate()
            .map(|(index, block)| {
                if !block.is_square() {
                    return Err(SolveError::DimensionMismatch {
                        what: "block-Jacobi block columns",
                        expected: block.nrows(),
                        found: block.ncols(),
                    });
                }
                let factor = block.cholesky().ok_or(SolveError::Factorization(
                    FactorizationFailure::BlockNotPositiveDefinite { block: index },
                ))?;
                Ok(factor.inverse())
            })
            .collect();
        self.inverses = inverses.into_iter().collect::<Result<_, _>>()?;
        Ok(())
    }

    /// Number of unknowns covered.
    pub fn dimension(&self) -> usize {
        self.ranges.last().map_or(0, |r| r.end)
    }
}

impl<A: DiagonalBlocks + ?Sized> Preconditioner<A> for BlockJacobi {
    /// Take the diagonal blocks of `matrix` over the ranges and invert them.
    fn setup(&mut self, matrix: &A) -> Result<(), SolveError> {
        let mut start = 0;
        for range in &self.ranges {
            if range.start != start || range.end < range.start {
                return Err(SolveError::DimensionMismatch {
                    what: "start of a block-Jacobi range (ranges are consecutive from 0)",
                    expected: start,
                    found: range.start,
                });
            }
            start = range.end;
        }
        let blocks = matrix.diagonal_blocks(&self.ranges)?;
        self.invert(blocks)
    }

    /// `z_k = K_kk⁻¹ r_k`, the blocks in parallel (rayon).
    fn apply(&self, r: &[f64], z: &mut [f64]) {
        let mut parts = Vec::with_capacity(self.inverses.len());
        let mut rest = z;
        for range in &self.ranges {
            let (part, tail) = rest.split_at_mut(range.len());
            parts.push(part);
            rest = tail;
        }
        parts
            .into_par_iter()
            .zip(&self.inverses)
            .zip(&self.ranges)
            .for_each(|((part, inverse), range)| {
                let v = DVectorView::from_slice(&r[range.clone()], part.len());
                let mut out = DVectorViewMut::from_slice(part, v.len());
                out.gemv(1.0, inverse, &v, 0.0);
            });
    }

    fn entries(&self) -> usize {
        self.inverses.iter().map(|m| m.len()).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_of_a_sparse_matrix_and_a_block_that_is_not_positive_definite() {
        let m = SparseMatrix::from_triplets(
            3,
            &[
                (0, 0, 2.0),
                (1, 0, 1.0),
                (0, 1, 1.0),
                (1, 1, 2.0),
                (2, 2, -1.0),
                (2, 0, 5.0),
            ],
        )
        .unwrap();
        let blocks = m.diagonal_blocks(&[0..2, 2..3]).unwrap();
        assert_eq!(
            blocks[0],
            DMatrix::from_row_slice(2, 2, &[2.0, 1.0, 1.0, 2.0])
        );
        assert_eq!(blocks[1], DMatrix::from_element(1, 1, -1.0));
        let mut p = BlockJacobi::new(vec![0..2, 2..3]);
        assert!(matches!(
            Preconditioner::<SparseMatrix>::setup(&mut p, &m),
            Err(SolveError::Factorization(failure)) if failure.to_string().contains("block 1")
                && failure == FactorizationFailure::BlockNotPositiveDefinite { block: 1 }
        ));
        let mut gap = BlockJacobi::new(vec![0..1, 2..3]);
        assert!(matches!(
            Preconditioner::<SparseMatrix>::setup(&mut gap, &m),
            Err(SolveError::DimensionMismatch {
                expected: 1,
                found: 2,
                ..
            })
        ));
    }
}
