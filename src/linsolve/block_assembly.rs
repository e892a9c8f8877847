//! Assembly of a sparse matrix made of dense blocks: one block row and one
//! block column per body (6 × 6 blocks for a DDA block, 12 × 12 for an
//! HPM element), a block on the diagonal of every body and a pair of
//! blocks `(a, b)`, `(b, a)` for every coupling of two bodies.
//!
//! The pattern is built once from the couplings; each block then has a
//! fixed slot among the stored values, so that a Newton iteration only
//! zeroes the values and adds its blocks into their slots, with no
//! triplet list to sort. While the couplings are unchanged the pattern
//! is the same handle, and a [`super::LinearSolver`] keeps its analysis.

use super::pattern::{SparseMatrix, SparsePattern};
use crate::error::SolveError;

/// Where block `(a, b)` lives among the stored values: entry `(p, q)` of
/// the block is value `start + q · stride + p`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BlockSlot {
    start: usize,
    stride: usize,
}

impl BlockSlot {
    /// Index among the stored values of entry `(p, q)` of the block.
    pub fn index(&self, p: usize, q: usize) -> usize {
        self.start + q * self.stride + p
    }
}

/// A block-sparse matrix on a pattern fixed by the couplings of bodies.
#[derive(Debug, Clone)]
pub struct BlockAssembly {
    bodies: usize,
    block: usize,
    couplings: Vec<(usize, usize)>,
    /// Bodies `a` holding a block `(a, b)` in block column `b`, sorted, for
    /// all `b` one after the other.
    neighbours: Vec<usize>,
    /// Start of the neighbours of each block column (length `bodies + 1`).
    neighbour_ptr: Vec<usize>,
    matrix: SparseMatrix,
}

impl BlockAssembly {
    /// The zero matrix of `bodies` bodies with `block` unknowns each,
    /// coupled by `couplings` (pairs of bodies, in any order and with
    /// repetitions; a pair of a body with itself is its diagonal block,
    /// always present).
    ///
    /// # Errors
    /// [`SolveError::DimensionMismatch`] for a body index out of range.
    pub fn new(
        bodies: usize,
        block: usize,
        couplings: &[(usize, usize)],
    ) -> Result<Self, SolveError> {
        if let Some(&(a, b)) = couplings.iter().find(|(a, b)| *a >= bodies || *b >= bodies) {
            return Err(SolveError::DimensionMismatch {
                what: "body of a coupling (found is the body, expected the body count)",
                expected: bodies,
                found: a.max(b),
            });
        }
        let couplings = Self::normalised(couplings);
        let mut lists: Vec<Vec<usize>> = (0..bodies).map(|b| vec![b]).collect();
        for &(a, b) in &couplings {
            lists[a].push(b);
            lists[b].push(a);
        }
        let mut neighbours = Vec::with_capacity(bodies + 2 * couplings.len());
        let mut neighbour_ptr = Vec::with_capacity(bodies + 1);
        neighbour_ptr.push(0);
        for list in &mut lists {
            list.sort_unstable();
            neighbours.extend_from_slice(list);
            neighbour_ptr.push(neighbours.len());
        }
        let n = bodies * block;
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::with_capacity(neighbours.len() * block * block);
        col_ptr.push(0);
        for list in &lists {
            for _ in 0..block {
                row_idx.extend(list.iter().flat_map(|&a| block * a..block * (a + 1)));
                col_ptr.push(row_idx.len());
            }
        }
        let pattern = SparsePattern::from_columns(n, col_ptr, row_idx)?;
        Ok(Self {
            bodies,
            block,
            couplings,
            neighbours,
            neighbour_ptr,
            matrix: SparseMatrix::zeros(pattern),
        })
    }

    /// `couplings` as this type keeps them: each pair `(a, b)` with
    /// `a < b`, sorted, without repetitions or pairs of a body with itself.
    /// Two assemblies have the same pattern exactly when their normalised
    /// couplings (and sizes) are equal.
    pub fn normalised(couplings: &[(usize, usize)]) -> Vec<(usize, usize)> {
        let mut out: Vec<(usize, usize)> = couplings
            .iter()
            .filter(|(a, b)| a != b)
            .map(|&(a, b)| (a.min(b), a.max(b)))
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Whether this assembly has `bodies` bodies of `block` unknowns and the
    /// normalised couplings `couplings` (see [`BlockAssembly::normalised`]).
    pub fn has_layout(&self, bodies: usize, block: usize, couplings: &[(usize, usize)]) -> bool {
        self.bodies == bodies && self.block == block && self.couplings == couplings
    }

    /// The normalised couplings of the pattern.
    pub fn couplings(&self) -> &[(usize, usize)] {
        &self.couplings
    }

    /// Unknowns per body.
    pub fn block_size(&self) -> usize {
        self.block
    }

    /// The slot of block `(a, b)`: rows of body `a`, columns of body `b`.
    pub fn slot(&self, a: usize, b: usize) -> Option<BlockSlot> {
        if b >= self.bodies {
            return None;
        }
        let (lo, hi) = (self.neighbour_ptr[b], self.neighbour_ptr[b + 1]);
        let rank = self.neighbours[lo..hi].binary_search(&a).ok()?;
        let base = self.matrix.pattern().col_ptr()[self.block * b];
        Some(BlockSlot {
            start: base + rank * self.block,
            stride: (hi - lo) * self.block,
        })
    }

    /// Zero all values, keeping the pattern.
    pub fn clear(&mut self) {
        self.matrix.values_mut().fill(0.0);
    }

    /// Add `value(p, q)` to entry `(p, q)` of block `(a, b)`, for all
    /// `p, q < block`.
    ///
    /// # Errors
    /// [`SolveError::OutsidePattern`] (naming the block's first entry) if
    /// the pattern holds no block `(a, b)`.
    pub fn add_block(
        &mut self,
        a: usize,
        b: usize,
        value: impl Fn(usize, usize) -> f64,
    ) -> Result<(), SolveError> {
        let slot = self.slot(a, b).ok_or(SolveError::OutsidePattern {
            row: self.block * a,
            col: self.block * b,
        })?;
        let values = self.matrix.values_mut();
        for q in 0..self.block {
            for p in 0..self.block {
                values[slot.index(p, q)] += value(p, q);
            }
        }
        Ok(())
    }

    /// `values[slot.index(p, q)] += value`: the fast path once a driver
    /// holds the slots of its blocks.
    pub fn add(&mut self, slot: BlockSlot, p: usize, q: usize, value: f64) {
        self.matrix.values_mut()[slot.index(p, q)] += value;
    }

    /// The assembled matrix.
    pub fn matrix(&self) -> &SparseMatrix {
        &self.matrix
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_land_where_triplets_would() {
        let mut assembly = BlockAssembly::new(3, 2, &[(2, 0), (0, 2), (1, 1)]).unwrap();
        assert_eq!(assembly.couplings(), &[(0, 2)]);
        let mut triplets = Vec::new();
        for (a, b) in [(0, 0), (1, 1), (2, 2), (0, 2), (2, 0)] {
            let value = |p: usize, q: usize| (10 * a + b) as f64 + 0.1 * p as f64 + 0.01 * q as f64;
            assembly.add_block(a, b, value).unwrap();
            for p in 0..2 {
                for q in 0..2 {
                    triplets.push((2 * a + p, 2 * b + q, value(p, q)));
                }
            }
        }
        let reference = SparseMatrix::from_triplets(6, &triplets).unwrap();
        assert!(assembly.matrix().pattern().same_as(reference.pattern()));
        assert_eq!(assembly.matrix().values(), reference.values());
        assert_eq!(
            assembly.add_block(0, 1, |_, _| 1.0),
            Err(SolveError::OutsidePattern { row: 0, col: 2 })
        );
        assembly.clear();
        assert!(assembly.matrix().values().iter().all(|v| *v == 0.0));
        assert!(assembly.has_layout(3, 2, &BlockAssembly::normalised(&[(0, 2)])));
    }
}
