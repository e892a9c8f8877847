//! A square sparse matrix in compressed columns: a shared [`SparsePattern`]
//! (which entries are stored) and the values of one matrix on it.
//!
//! The pattern is what the direct solvers analyse (ordering, symbolic
//! factorization). It is a cheap clonable handle, so that a driver that
//! refills the values of a matrix keeps the very same pattern and the
//! solver sees at once that its analysis still holds.

use std::sync::Arc;

use faer::prelude::Reborrow;
use faer::sparse::{Pair, SparseColMatRef, SymbolicSparseColMat, SymbolicSparseColMatRef};

use crate::error::{FactorizationFailure, SolveError};

/// The positions of the stored entries of a square sparse matrix, by
/// columns with sorted, distinct rows. Clones share the same data.
#[derive(Debug, Clone)]
pub struct SparsePattern {
    structure: Arc<SymbolicSparseColMat<usize>>,
}

impl PartialEq for SparsePattern {
    fn eq(&self, other: &Self) -> bool {
        self.same_as(other)
    }
}

impl SparsePattern {
    /// The pattern of the distinct positions among `entries` `(row, col)` of
    /// an `n × n` matrix, and for each entry its position in the stored
    /// values (repeated positions share one).
    ///
    /// # Errors
    /// [`SolveError::DimensionMismatch`] for an index out of range (the
    /// index is reported as `found`, the dimension as `expected`).
    pub fn from_entries(
        n: usize,
        entries: &[(usize, usize)],
    ) -> Result<(Self, Vec<usize>), SolveError> {
        for &(row, col) in entries {
            check_index("entry row index", row, n)?;
            check_index("entry column index", col, n)?;
        }
        let pairs: Vec<Pair<usize, usize>> = entries
            .iter()
            .map(|&(row, col)| Pair { row, col })
            .collect();
        let (structure, _) =
            SymbolicSparseColMat::try_new_from_indices(n, n, &pairs).map_err(|e| {
                SolveError::Factorization(FactorizationFailure::Analysis {
                    stage: "building a sparse pattern",
                    message: e.to_string(),
                })
            })?;
        let pattern = Self {
            structure: Arc::new(structure),
        };
        let slots = entries
            .iter()
            .map(|&(row, col)| pattern.position(row, col).unwrap_or(usize::MAX))
            .collect();
        Ok((pattern, slots))
    }

    /// A pattern from its compressed columns: `col_ptr` (length `n + 1`,
    /// non-decreasing from 0) and the rows of each column, sorted and
    /// distinct.
    ///
    /// # Errors
    /// [`SolveError::DimensionMismatch`] when the arrays do not describe
    /// such a pattern.
    pub fn from_columns(
        n: usize,
        col_ptr: Vec<usize>,
        row_idx: Vec<usize>,
    ) -> Result<Self, SolveError> {
        if col_ptr.len() != n + 1 || col_ptr[0] != 0 || col_ptr[n] != row_idx.len() {
            return Err(SolveError::DimensionMismatch {
                what:
                    "column pointers of a sparse pattern (length n + 1, from 0 to the entry count)",
                expected: n + 1,
                found: col_ptr.len(),
            });
        }
        for j in 0..n {
            if col_ptr[j] > col_ptr[j + 1] {
                return Err(SolveError::DimensionMismatch {
                    what: "column pointers of a sparse pattern (non-decreasing)",
                    expected: col_ptr[j],
                    found: col_ptr[j + 1],
                });
            }
            let rows = &row_idx[col_ptr[j]..col_ptr[j + 1]];
            for (k, &row) in rows.iter().enumerate() {
                check_index("row index of a sparse pattern", row, n)?;
                if k > 0 && rows[k - 1] >= row {
                    return Err(SolveError::DimensionMismatch {
                        what: "rows of a sparse pattern column (sorted and distinct)",
                        expected: rows[k - 1] + 1,
                        found: row,
                    });
                }
            }
        }
        let structure = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        Ok(Self {
            structure: Arc::new(structure),
        })
    }

    /// Number of rows and columns.
    pub fn dimension(&self) -> usize {
        self.structure.ncols()
    }

    /// Number of stored entries.
    pub fn entries(&self) -> usize {
        self.structure.row_idx().len()
    }

    /// Column pointers (length `dimension + 1`).
    pub fn col_ptr(&self) -> &[usize] {
        self.structure.col_ptr()
    }

    /// Rows of the stored entries, column after column.
    pub fn row_idx(&self) -> &[usize] {
        self.structure.row_idx()
    }

    /// Position of entry `(row, col)` among the stored values, if stored.
    pub fn position(&self, row: usize, col: usize) -> Option<usize> {
        if col >= self.dimension() {
            return None;
        }
        let start = self.col_ptr()[col];
        let rows = &self.row_idx()[start..self.col_ptr()[col + 1]];
        rows.binary_search(&row).ok().map(|k| start + k)
    }

    /// Whether `other` is the same pattern: the same handle (checked
    /// first, in constant time) or equal arrays.
    pub fn same_as(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.structure, &other.structure)
            || (self.col_ptr() == other.col_ptr() && self.row_idx() == other.row_idx())
    }

    /// The pattern as faer sees it.
    pub(crate) fn faer(&self) -> SymbolicSparseColMatRef<'_, usize> {
        self.structure.rb()
    }
}

fn check_index(what: &'static str, index: usize, n: usize) -> Result<(), SolveError> {
    if index < n {
        Ok(())
    } else {
        Err(SolveError::DimensionMismatch {
            what,
            expected: n,
            found: index,
        })
    }
}

/// A square sparse matrix: a [`SparsePattern`] and one value per stored
/// entry.
#[derive(Debug, Clone, PartialEq)]
pub struct SparseMatrix {
    pattern: SparsePattern,
    values: Vec<f64>,
}

impl SparseMatrix {
    /// The zero matrix on `pattern`.
    pub fn zeros(pattern: SparsePattern) -> Self {
        let values = vec![0.0; pattern.entries()];
        Self { pattern, values }
    }

    /// A matrix from its pattern and values (one per stored entry).
    ///
    /// # Errors
    /// [`SolveError::DimensionMismatch`] if the lengths differ.
    pub fn new(pattern: SparsePattern, values: Vec<f64>) -> Result<Self, SolveError> {
        if values.len() != pattern.entries() {
            return Err(SolveError::DimensionMismatch {
                what: "values of a sparse matrix",
                expected: pattern.entries(),
                found: values.len(),
            });
        }
        Ok(Self { pattern, values })
    }

    /// An `n × n` matrix from `(row, col, value)` triplets; values at the
    /// same position are summed (finite-element style assembly).
    ///
    /// # Errors
    /// [`SolveError::DimensionMismatch`] for an index out of range,
    /// [`SolveError::NonFinite`] for a NaN or infinite value (naming its
    /// triplet).
    pub fn from_triplets(n: usize, triplets: &[(usize, usize, f64)]) -> Result<Self, SolveError> {
        if let Some((index, &(_, _, value))) =
            triplets.iter().enumerate().find(|(_, t)| !t.2.is_finite())
        {
            return Err(SolveError::NonFinite {
                what: "sparse matrix triplet",
                index,
                value,
            });
        }
        let entries: Vec<(usize, usize)> = triplets.iter().map(|&(r, c, _)| (r, c)).collect();
        let (pattern, slots) = SparsePattern::from_entries(n, &entries)?;
        let mut matrix = Self::zeros(pattern);
        for (&slot, &(_, _, value)) in slots.iter().zip(triplets) {
            matrix.values[slot] += value;
        }
        Ok(matrix)
    }

    /// The pattern.
    pub fn pattern(&self) -> &SparsePattern {
        &self.pattern
    }

    /// Number of rows and columns.
    pub fn dimension(&self) -> usize {
        self.pattern.dimension()
    }

    /// The stored values, in the order of the pattern.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The stored values, to refill in place.
    pub fn values_mut(&mut self) -> &mut [f64] {
        &mut self.values
    }

    /// `K[row, col] += value`.
    ///
    /// # Errors
    /// [`SolveError::OutsidePattern`] if the pattern does not hold
    /// `(row, col)`.
    pub fn add(&mut self, row: usize, col: usize, value: f64) -> Result<(), SolveError> {
        let k = self
            .pattern
            .position(row, col)
            .ok_or(SolveError::OutsidePattern { row, col })?;
        self.values[k] += value;
        Ok(())
    }

    /// `y = K x`.
    ///
    /// # Panics
    /// If `x` or `y` is not of length [`SparseMatrix::dimension`].
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        let n = self.dimension();
        assert!(x.len() == n && y.len() == n, "vector length");
        y.fill(0.0);
        let (col_ptr, row_idx) = (self.pattern.col_ptr(), self.pattern.row_idx());
        for j in 0..n {
            let xj = x[j];
            for k in col_ptr[j]..col_ptr[j + 1] {
                y[row_idx[k]] += self.values[k] * xj;
            }
        }
    }

    /// The first non-finite value, as an error naming its position.
    pub(crate) fn check_finite(&self) -> Result<(), SolveError> {
        match self.values.iter().position(|v| !v.is_finite()) {
            None => Ok(()),
            Some(index) => Err(SolveError::NonFinite {
                what: "sparse matrix value",
                index,
                value: self.values[index],
            }),
        }
    }

    /// The matrix as faer sees it.
    pub(crate) fn faer(&self) -> SparseColMatRef<'_, usize, f64> {
        SparseColMatRef::new(self.pattern.faer(), &self.values)
    }
}

/// Checks the length and finiteness of a right-hand side.
pub(crate) fn check_rhs(rhs: &[f64], n: usize) -> Result<(), SolveError> {
    if rhs.len() != n {
        return Err(SolveError::DimensionMismatch {
            what: "right-hand side length",
            expected: n,
            found: rhs.len(),
        });
    }
    match rhs.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(index) => Err(SolveError::NonFinite {
            what: "right-hand side",
            index,
            value: rhs[index],
        }),
    }
}

/// A solution with a NaN or an infinite entry: the matrix was
/// numerically singular (faer's LU does not report a zero pivot; it shows
/// in the solution).
pub(crate) fn check_solution(x: &[f64]) -> Result<(), SolveError> {
    match x.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(index) => Err(SolveError::Factorization(
            FactorizationFailure::NumericallySingular {
                index,
                value: x[index],
            },
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triplets_at_one_position_are_summed() {
        let m = SparseMatrix::from_triplets(2, &[(0, 0, 1.0), (1, 0, 2.0), (0, 0, 3.0)]).unwrap();
        assert_eq!(m.pattern().entries(), 2);
        assert_eq!(m.values(), &[4.0, 2.0]);
        let mut y = [0.0; 2];
        m.mul_vec(&[1.0, 5.0], &mut y);
        assert_eq!(y, [4.0, 2.0]);
    }

    #[test]
    fn patterns_compare_by_handle_then_by_content() {
        let (a, _) = SparsePattern::from_entries(3, &[(0, 0), (2, 1)]).unwrap();
        let (b, _) = SparsePattern::from_entries(3, &[(2, 1), (0, 0)]).unwrap();
        let (c, _) = SparsePattern::from_entries(3, &[(0, 0), (1, 1)]).unwrap();
        assert!(a.same_as(&a.clone()) && a.same_as(&b) && !a.same_as(&c));
        assert_eq!(a.position(2, 1), Some(1));
        assert_eq!(a.position(1, 1), None);
    }

    #[test]
    fn bad_columns_and_entries_outside_the_pattern_are_errors() {
        assert!(SparsePattern::from_columns(2, vec![0, 1, 2], vec![0, 0]).is_ok());
        assert!(matches!(
            SparsePattern::from_columns(2, vec![0, 2, 2], vec![1, 0]),
            Err(SolveError::DimensionMismatch { .. })
        ));
        assert!(matches!(
            SparsePattern::from_columns(2, vec![0, 1, 2], vec![0, 2]),
            Err(SolveError::DimensionMismatch { found: 2, .. })
        ));
        let mut m = SparseMatrix::from_triplets(2, &[(0, 0, 1.0)]).unwrap();
        assert_eq!(
            m.add(1, 0, 1.0),
            Err(SolveError::OutsidePattern { row: 1, col: 0 })
        );
        assert!(matches!(
            SparseMatrix::from_triplets(2, &[(0, 5, 1.0)]),
            Err(SolveError::DimensionMismatch { found: 5, .. })
        ));
    }
}
