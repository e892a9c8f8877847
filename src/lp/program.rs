//! The data of a linear program.

use crate::error::SolveError;

/// A linear program `min cᵀx  s.t.  A_eq x = b_eq,  A_ineq x ≤ b_ineq` with
/// free `x`.
///
/// Matrices are given as `(row, col, value)` triplets; duplicate entries are
/// summed. The number of rows of each block is the length of its right-hand
/// side vector. Nothing is validated on construction; [`super::LinearProgramSolver`]
/// checks indices, lengths and finiteness before solving.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LinearProgram {
    /// Number of (free) variables `n`.
    pub num_variables: usize,
    /// Objective coefficients `c`, of length `num_variables`.
    pub objective: Vec<f64>,
    /// Triplets `(row, col, value)` of `A_eq`; duplicates are summed.
    pub equalities: Vec<(usize, usize, f64)>,
    /// Right-hand side `b_eq`; its length is the number of equality rows.
    pub equality_rhs: Vec<f64>,
    /// Triplets `(row, col, value)` of `A_ineq`; duplicates are summed.
    pub inequalities: Vec<(usize, usize, f64)>,
    /// Right-hand side `b_ineq`; its length is the number of inequality rows.
    /// Clarabel's presolve treats entries above `1e20` as `+∞` and drops
    /// those rows (their duals are reported as 0), so encode "no bound" by
    /// omitting the row rather than by a huge finite value.
    pub inequality_rhs: Vec<f64>,
}

impl LinearProgram {
    /// Creates an LP with `num_variables` free variables, a zero objective
    /// and no constraints.
    pub fn new(num_variables: usize) -> Self {
        Self {
            num_variables,
            objective: vec![0.0; num_variables],
            ..Self::default()
        }
    }

    /// Appends the equality row `Σ aⱼ xⱼ = rhs` given as `(j, aⱼ)` pairs and
    /// returns its row index in `A_eq`.
    pub fn add_equality(&mut self, coefficients: &[(usize, f64)], rhs: f64) -> usize {
        let row = self.equality_rhs.len();
        self.equalities
            .extend(coefficients.iter().map(|&(col, value)| (row, col, value)));
        self.equality_rhs.push(rhs);
        row
    }

    /// Appends the inequality row `Σ aⱼ xⱼ ≤ rhs` given as `(j, aⱼ)` pairs and
    /// returns its row index in `A_ineq`.
    pub fn add_inequality(&mut self, coefficients: &[(usize, f64)], rhs: f64) -> usize {
        let row = self.inequality_rhs.len();
        self.inequalities
            .extend(coefficients.iter().map(|&(col, value)| (row, col, value)));
        self.inequality_rhs.push(rhs);
        row
    }

    /// Size of the LP: `(variables, equality rows, non-zeros of all rows)`.
    pub fn size(&self) -> (usize, usize, usize) {
        (
            self.num_variables,
            self.equality_rhs.len(),
            self.equalities.len() + self.inequalities.len(),
        )
    }

    /// Adds `lower ≤ x[var] ≤ upper` as inequality rows: `−x[var] ≤ −lower`
    /// (if `lower` is given) followed by `x[var] ≤ upper` (if `upper` is
    /// given). `None` means unbounded on that side.
    pub fn add_bounds(&mut self, var: usize, lower: Option<f64>, upper: Option<f64>) {
        if let Some(lower) = lower {
            self.add_inequality(&[(var, -1.0)], -lower);
        }
        if let Some(upper) = upper {
            self.add_inequality(&[(var, 1.0)], upper);
        }
    }

    /// Number of equality rows.
    pub(super) fn num_equalities(&self) -> usize {
        self.equality_rhs.len()
    }

    /// Number of inequality rows.
    pub(super) fn num_inequalities(&self) -> usize {
        self.inequality_rhs.len()
    }

    /// Checks lengths, triplet indices and finiteness of all data.
    pub(super) fn validate(&self) -> Result<(), SolveError> {
        let n = self.num_variables;
        if self.objective.len() != n {
            return Err(SolveError::DimensionMismatch {
                what: "objective length",
                expected: n,
                found: self.objective.len(),
            });
        }
        check_finite("objective", &self.objective)?;
        check_finite("equality rhs", &self.equality_rhs)?;
        check_finite("inequality rhs", &self.inequality_rhs)?;
        check_triplets(
            &self.equalities,
            self.num_equalities(),
            n,
            "equality row index",
            "equality column index",
            "equality coefficient",
        )?;
        check_triplets(
            &self.inequalities,
            self.num_inequalities(),
            n,
            "inequality row index",
            "inequality column index",
            "inequality coefficient",
        )
    }
}

/// Returns [`SolveError::NonFinite`] for the first non-finite entry.
fn check_finite(what: &'static str, values: &[f64]) -> Result<(), SolveError> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(SolveError::NonFinite {
            what,
            index,
            value: values[index],
        }),
        None => Ok(()),
    }
}

/// Validates triplets. An out-of-range index is reported as
/// [`SolveError::DimensionMismatch`] with `expected` the exclusive upper
/// bound and `found` the offending index; a non-finite value as
/// [`SolveError::NonFinite`] with `index` the position in the triplet list.
fn check_triplets(
    triplets: &[(usize, usize, f64)],
    rows: usize,
    cols: usize,
    row_what: &'static str,
    col_what: &'static str,
    value_what: &'static str,
) -> Result<(), SolveError> {
    for (index, &(row, col, value)) in triplets.iter().enumerate() {
        if row >= rows {
            return Err(SolveError::DimensionMismatch {
                what: row_what,
                expected: rows,
                found: row,
            });
        }
        if col >= cols {
            return Err(SolveError::DimensionMismatch {
                what: col_what,
                expected: cols,
                found: col,
            });
        }
        if !value.is_finite() {
            return Err(SolveError::NonFinite {
                what: value_what,
                index,
                value,
            });
        }
    }
    Ok(())
}
