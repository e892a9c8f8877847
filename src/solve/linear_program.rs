//! Sparse linear programs solved with the Clarabel interior-point method.
//!
//! A [`LinearProgram`] describes
//!
//! ```text
//! minimise    cᵀx
//! subject to  A_eq   x  = b_eq
//!             A_ineq x ≤ b_ineq
//! ```
//!
//! with free variables `x`; variable bounds are ordinary rows of `A_ineq`
//! (see [`LinearProgram::add_bounds`]). The matrices are stored as
//! `(row, col, value)` triplets, duplicates being summed, so assembly code
//! can scatter element contributions without bookkeeping.
//!
//! In rigid-plastic limit analysis of circular elements the two bounding
//! theorems both become LPs of this form:
//!
//! * the **lower bound** (static) problem maximises the load factor over
//!   stress fields that satisfy equilibrium (equality rows) and a linearised
//!   yield condition (inequality rows);
//! * the **upper bound** (kinematic) problem minimises the dissipated power
//!   over mechanisms satisfying a normalisation of the external power
//!   (equality row) and flow-rule / compatibility constraints.
//!
//! Maximisation is done by negating the objective. The dual variables
//! returned in [`LinearProgramSolution`] are the multipliers of the other
//! bound problem (e.g. the velocities of the collapse mechanism are the
//! equilibrium multipliers of the static problem), up to the sign convention
//! documented on [`LinearProgramSolution::equality_duals`]:
//!
//! ```text
//! c + A_eqᵀ y + A_ineqᵀ z = 0,    z ≥ 0,    zᵢ (b_ineq − A_ineq x)ᵢ = 0,
//! dual objective = −b_eqᵀ y − b_ineqᵀ z.
//! ```
//!
//! **Interior-point caveat:** when the optimum is not unique (a whole face of
//! the feasible polytope is optimal, common for symmetric collapse
//! mechanisms), an interior-point method converges towards the analytic
//! centre of that optimal face rather than to a vertex. The optimal value is
//! reliable, but `x` (and the duals) may be a blend of several vertex
//! solutions, and inequality rows may be only approximately active.
//!
//! ```
//! use dismech::solve::GlobalSolver;
//! use dismech::solve::{LinearProgram, LinearProgramSolver, LpStatus};
//!
//! // maximise x + y  s.t.  x + 2y ≤ 4, 3x + y ≤ 6, x, y ≥ 0
//! let mut lp = LinearProgram::new(2);
//! lp.objective = vec![-1.0, -1.0];
//! lp.add_inequality(&[(0, 1.0), (1, 2.0)], 4.0);
//! lp.add_inequality(&[(0, 3.0), (1, 1.0)], 6.0);
//! lp.add_bounds(0, Some(0.0), None);
//! lp.add_bounds(1, Some(0.0), None);
//! let sol = LinearProgramSolver::default().solve(&lp).unwrap();
//! assert_eq!(sol.status, LpStatus::Optimal);
//! assert!((sol.objective + 2.8).abs() < 1e-6);
//! ```

use super::{GlobalSolver, SolveError};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettings, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus, SupportedConeT,
    ZeroConeT,
};

/// A linear program `min cᵀx  s.t.  A_eq x = b_eq,  A_ineq x ≤ b_ineq` with
/// free `x`.
///
/// Matrices are given as `(row, col, value)` triplets; duplicate entries are
/// summed. The number of rows of each block is the length of its right-hand
/// side vector. Nothing is validated on construction; [`LinearProgramSolver`]
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
    fn num_equalities(&self) -> usize {
        self.equality_rhs.len()
    }

    /// Number of inequality rows.
    fn num_inequalities(&self) -> usize {
        self.inequality_rhs.len()
    }

    /// Checks lengths, triplet indices and finiteness of all data.
    fn validate(&self) -> Result<(), SolveError> {
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

/// Termination status of a linear program solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LpStatus {
    /// Solved to the requested tolerance.
    Optimal,
    /// Solved only to Clarabel's reduced tolerances.
    AlmostOptimal,
    /// No feasible point exists (also reported for Clarabel's reduced-accuracy
    /// infeasibility certificate). `equality_duals`/`inequality_duals` hold
    /// the certificate.
    PrimalInfeasible,
    /// The dual is infeasible, i.e. the primal is unbounded below (if
    /// feasible); also reported for the reduced-accuracy certificate. `x`
    /// holds an improving ray.
    DualInfeasible,
    /// The iteration limit was reached.
    MaxIterations,
    /// The solver stopped on a numerical error or for lack of progress.
    NumericalError,
    /// Any other termination (e.g. time limit).
    Other,
}

impl From<SolverStatus> for LpStatus {
    fn from(status: SolverStatus) -> Self {
        match status {
            SolverStatus::Solved => Self::Optimal,
            SolverStatus::AlmostSolved => Self::AlmostOptimal,
            SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => {
                Self::PrimalInfeasible
            }
            SolverStatus::DualInfeasible | SolverStatus::AlmostDualInfeasible => {
                Self::DualInfeasible
            }
            SolverStatus::MaxIterations => Self::MaxIterations,
            SolverStatus::NumericalError | SolverStatus::InsufficientProgress => {
                Self::NumericalError
            }
            _ => Self::Other,
        }
    }
}

/// Result of solving a [`LinearProgram`].
///
/// For non-optimal statuses the vectors are Clarabel's final iterate or
/// infeasibility certificate and the objectives may be NaN or meaningless.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearProgramSolution {
    /// Termination status.
    pub status: LpStatus,
    /// Primal solution `x`.
    pub x: Vec<f64>,
    /// Primal objective `cᵀx`.
    pub objective: f64,
    /// Dual objective `−b_eqᵀ y − b_ineqᵀ z`; equals `objective` at optimum.
    pub dual_objective: f64,
    /// Multipliers `y` of the equality rows (free sign), with the convention
    /// that at optimum `c + A_eqᵀ y + A_ineqᵀ z = 0`. Equivalently `−yᵢ` is
    /// the sensitivity `∂(optimal value)/∂b_eq,i`.
    pub equality_duals: Vec<f64>,
    /// Multipliers `z ≥ 0` of the inequality rows, in the same stationarity
    /// relation `c + A_eqᵀ y + A_ineqᵀ z = 0`; `zᵢ > 0` only for active rows.
    pub inequality_duals: Vec<f64>,
    /// Number of interior-point iterations performed.
    pub iterations: u32,
    /// Clarabel's own termination status, verbatim (e.g. `Solved`,
    /// `AlmostSolved`, `MaxIterations`).
    pub solver_status: String,
}

/// Interior-point LP solver backed by Clarabel.
#[derive(Debug, Clone)]
pub struct LinearProgramSolver {
    /// Used as Clarabel's `tol_gap_abs`, `tol_gap_rel` and `tol_feas`; must be
    /// finite and positive. Default `1e-9`.
    pub tolerance: f64,
    /// Maximum number of interior-point iterations. Default `200`.
    pub max_iterations: u32,
    /// Print Clarabel's iteration log to stdout. Default `false`.
    pub verbose: bool,
}

impl Default for LinearProgramSolver {
    fn default() -> Self {
        Self {
            tolerance: 1e-9,
            max_iterations: 200,
            verbose: false,
        }
    }
}

/// Builds the stacked constraint matrix `[A_eq; A_ineq]` in CSC form (sorted
/// by column then row, duplicates summed). Indices must already be validated.
fn stacked_csc(lp: &LinearProgram) -> CscMatrix<f64> {
    let m_eq = lp.num_equalities();
    let m = m_eq + lp.num_inequalities();
    let n = lp.num_variables;

    let mut entries: Vec<(usize, usize, f64)> = lp
        .equalities
        .iter()
        .map(|&(r, c, v)| (c, r, v))
        .chain(lp.inequalities.iter().map(|&(r, c, v)| (c, m_eq + r, v)))
        .collect();
    entries.sort_unstable_by_key(|&(c, r, _)| (c, r));

    let mut colptr = vec![0usize; n + 1];
    let mut rowval: Vec<usize> = Vec::with_capacity(entries.len());
    let mut nzval: Vec<f64> = Vec::with_capacity(entries.len());
    let mut last: Option<(usize, usize)> = None;
    for (c, r, v) in entries {
        if last == Some((c, r)) {
            if let Some(value) = nzval.last_mut() {
                *value += v;
            }
        } else {
            rowval.push(r);
            nzval.push(v);
            colptr[c + 1] += 1;
            last = Some((c, r));
        }
    }
    for j in 0..n {
        colptr[j + 1] += colptr[j];
    }
    CscMatrix {
        m,
        n,
        colptr,
        rowval,
        nzval,
    }
}

impl LinearProgramSolver {
    /// Solves an LP without variables (which Clarabel cannot factor): it is a
    /// pure feasibility check `0 = b_eq`, `0 ≤ b_ineq` up to `tolerance`. If
    /// infeasible the duals are a Farkas certificate (`b_eqᵀy + b_ineqᵀz < 0`).
    fn solve_without_variables(&self, lp: &LinearProgram) -> LinearProgramSolution {
        let tol = self.tolerance;
        let equality_duals: Vec<f64> = lp
            .equality_rhs
            .iter()
            .map(|&b| if b.abs() > tol { -b } else { 0.0 })
            .collect();
        let inequality_duals: Vec<f64> = lp
            .inequality_rhs
            .iter()
            .map(|&b| if b < -tol { 1.0 } else { 0.0 })
            .collect();
        let feasible = equality_duals
            .iter()
            .chain(&inequality_duals)
            .all(|&d| d == 0.0);
        let (status, value) = if feasible {
            (LpStatus::Optimal, 0.0)
        } else {
            (LpStatus::PrimalInfeasible, f64::NAN)
        };
        LinearProgramSolution {
            status,
            x: Vec::new(),
            objective: value,
            dual_objective: value,
            equality_duals,
            inequality_duals,
            iterations: 0,
            solver_status: "not run (no variables)".into(),
        }
    }

    /// Runs Clarabel on validated data.
    fn run(&self, lp: &LinearProgram) -> Result<LinearProgramSolution, SolveError> {
        let n = lp.num_variables;
        let m_eq = lp.num_equalities();
        let m_ineq = lp.num_inequalities();

        let p = CscMatrix::<f64>::zeros((n, n));
        let a = stacked_csc(lp);
        let b: Vec<f64> = lp
            .equality_rhs
            .iter()
            .chain(lp.inequality_rhs.iter())
            .copied()
            .collect();
        let mut cones: Vec<SupportedConeT<f64>> = Vec::with_capacity(2);
        if m_eq > 0 {
            cones.push(ZeroConeT(m_eq));
        }
        if m_ineq > 0 {
            cones.push(NonnegativeConeT(m_ineq));
        }
        let settings = DefaultSettings::<f64> {
            max_iter: self.max_iterations,
            verbose: self.verbose,
            tol_gap_abs: self.tolerance,
            tol_gap_rel: self.tolerance,
            tol_feas: self.tolerance,
            ..DefaultSettings::default()
        };

        let mut solver = DefaultSolver::new(&p, &lp.objective, &a, &b, &cones, settings)
            .map_err(|e| SolveError::LinearProgram(e.to_string()))?;
        solver.solve();
        let sol = &solver.solution;

        let mut z = sol.z.clone();
        z.resize(m_eq + m_ineq, 0.0);
        let inequality_duals = z.split_off(m_eq);
        Ok(LinearProgramSolution {
            status: sol.status.into(),
            x: sol.x.clone(),
            objective: sol.obj_val,
            dual_objective: sol.obj_val_dual,
            equality_duals: z,
            inequality_duals,
            iterations: sol.iterations,
            solver_status: format!("{:?}", sol.status),
        })
    }
}

impl GlobalSolver for LinearProgramSolver {
    type System = LinearProgram;
    type Solution = LinearProgramSolution;

    /// Validates `system` and solves it.
    ///
    /// Errors: [`SolveError::DimensionMismatch`] for a wrong objective length
    /// or an out-of-range triplet index (`expected` is the exclusive bound,
    /// `found` the index); [`SolveError::NonFinite`] for a non-finite
    /// coefficient, right-hand side or tolerance; [`SolveError::NonPositive`]
    /// for a non-positive tolerance; [`SolveError::LinearProgram`] if Clarabel
    /// rejects the problem or fails internally. Infeasibility and
    /// unboundedness are reported through [`LinearProgramSolution::status`].
    fn solve(&mut self, system: &LinearProgram) -> Result<LinearProgramSolution, SolveError> {
        if !self.tolerance.is_finite() {
            return Err(SolveError::NonFinite {
                what: "tolerance",
                index: 0,
                value: self.tolerance,
            });
        }
        if self.tolerance <= 0.0 {
            return Err(SolveError::NonPositive {
                what: "tolerance",
                index: 0,
                value: self.tolerance,
            });
        }
        system.validate()?;
        if system.num_variables == 0 {
            return Ok(self.solve_without_variables(system));
        }
        // Clarabel may assert internally on degenerate input; never let that
        // escape as a panic.
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| self.run(system))).unwrap_or_else(
            |payload| {
                let msg = payload
                    .downcast_ref::<&str>()
                    .map(|s| (*s).to_owned())
                    .or_else(|| payload.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "internal solver panic".to_owned());
                Err(SolveError::LinearProgram(msg))
            },
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    const TOL: f64 = 1e-6;

    fn solve(lp: &LinearProgram) -> LinearProgramSolution {
        LinearProgramSolver::default().solve(lp).expect("solve")
    }

    /// max x + y s.t. x + 2y ≤ 4, 3x + y ≤ 6, x, y ≥ 0.
    fn textbook_lp() -> LinearProgram {
        let mut lp = LinearProgram::new(2);
        lp.objective = vec![-1.0, -1.0];
        lp.add_inequality(&[(0, 1.0), (1, 2.0)], 4.0);
        lp.add_inequality(&[(0, 3.0), (1, 1.0)], 6.0);
        lp.add_bounds(0, Some(0.0), None);
        lp.add_bounds(1, Some(0.0), None);
        lp
    }

    /// min x0 + 2 x1 + 3 x2 s.t. x0 + x1 + x2 = 1, x0 − x1 = 0.2, 0 ≤ x ≤ 1.
    /// Optimum x = (0.6, 0.4, 0), objective 1.4.
    fn equality_lp() -> LinearProgram {
        let mut lp = LinearProgram::new(3);
        lp.objective = vec![1.0, 2.0, 3.0];
        lp.add_equality(&[(0, 1.0), (1, 1.0), (2, 1.0)], 1.0);
        // duplicate entries on x0 (0.5 + 0.5) must be summed
        lp.add_equality(&[(0, 0.5), (1, -1.0), (0, 0.5)], 0.2);
        for j in 0..3 {
            lp.add_bounds(j, Some(0.0), Some(1.0));
        }
        lp
    }

    fn stationarity_residual(lp: &LinearProgram, sol: &LinearProgramSolution) -> Vec<f64> {
        let mut r = lp.objective.clone();
        for &(i, j, a) in &lp.equalities {
            r[j] += a * sol.equality_duals[i];
        }
        for &(i, j, a) in &lp.inequalities {
            r[j] += a * sol.inequality_duals[i];
        }
        r
    }

    #[test]
    fn textbook_lp_reaches_known_vertex_optimum() {
        let sol = solve(&textbook_lp());
        assert_eq!(sol.status, LpStatus::Optimal);
        assert_relative_eq!(sol.x[0], 1.6, epsilon = TOL);
        assert_relative_eq!(sol.x[1], 1.2, epsilon = TOL);
        assert_relative_eq!(sol.objective, -2.8, epsilon = TOL);
        assert!(sol.iterations > 0);
    }

    #[test]
    fn equality_constrained_lp_with_duplicate_triplets_is_solved() {
        let sol = solve(&equality_lp());
        assert_eq!(sol.status, LpStatus::Optimal);
        assert_relative_eq!(sol.x[0], 0.6, epsilon = TOL);
        assert_relative_eq!(sol.x[1], 0.4, epsilon = TOL);
        assert_relative_eq!(sol.x[2], 0.0, epsilon = TOL);
        assert_relative_eq!(sol.objective, 1.4, epsilon = TOL);
        assert_eq!(sol.equality_duals.len(), 2);
        assert_eq!(sol.inequality_duals.len(), 6);
    }

    #[test]
    fn primal_objective_equals_dual_objective_at_optimum() {
        for lp in [textbook_lp(), equality_lp()] {
            let sol = solve(&lp);
            assert_eq!(sol.status, LpStatus::Optimal);
            assert_relative_eq!(sol.objective, sol.dual_objective, epsilon = TOL);
            let dual: f64 = -lp
                .equality_rhs
                .iter()
                .zip(&sol.equality_duals)
                .chain(lp.inequality_rhs.iter().zip(&sol.inequality_duals))
                .map(|(b, y)| b * y)
                .sum::<f64>();
            assert_relative_eq!(dual, sol.dual_objective, epsilon = TOL);
        }
    }

    #[test]
    fn dual_sign_convention_satisfies_stationarity_and_complementarity() {
        for lp in [textbook_lp(), equality_lp()] {
            let sol = solve(&lp);
            for r in stationarity_residual(&lp, &sol) {
                assert!(r.abs() < TOL, "stationarity residual {r}");
            }
            for (i, &z) in sol.inequality_duals.iter().enumerate() {
                assert!(z >= -TOL, "negative inequality dual {z}");
                let ax: f64 = lp
                    .inequalities
                    .iter()
                    .filter(|t| t.0 == i)
                    .map(|&(_, j, a)| a * sol.x[j])
                    .sum();
                let slack = lp.inequality_rhs[i] - ax;
                assert!((z * slack).abs() < TOL, "complementarity {z} * {slack}");
            }
        }
        // textbook duals: both resource rows active with z = (0.4, 0.2)
        let sol = solve(&textbook_lp());
        assert_relative_eq!(sol.inequality_duals[0], 0.4, epsilon = TOL);
        assert_relative_eq!(sol.inequality_duals[1], 0.2, epsilon = TOL);
    }

    #[test]
    fn equality_dual_is_minus_rhs_sensitivity() {
        let base = solve(&equality_lp());
        let mut perturbed = equality_lp();
        let h = 1e-3;
        perturbed.equality_rhs[0] += h;
        let p = solve(&perturbed);
        let slope = (p.objective - base.objective) / h;
        assert_relative_eq!(slope, -base.equality_duals[0], epsilon = 1e-4);
    }

    #[test]
    fn infeasible_lp_reports_primal_infeasible_status() {
        let mut lp = LinearProgram::new(1);
        lp.objective = vec![1.0];
        lp.add_bounds(0, Some(2.0), Some(1.0));
        assert_eq!(solve(&lp).status, LpStatus::PrimalInfeasible);

        let mut lp = LinearProgram::new(2);
        lp.add_equality(&[(0, 1.0), (1, 1.0)], 1.0);
        lp.add_equality(&[(0, 1.0), (1, 1.0)], 2.0);
        assert_eq!(solve(&lp).status, LpStatus::PrimalInfeasible);
    }

    #[test]
    fn unbounded_lp_reports_dual_infeasible_status() {
        let mut lp = LinearProgram::new(2);
        lp.objective = vec![-1.0, 0.0];
        lp.add_bounds(0, Some(0.0), None);
        lp.add_inequality(&[(1, 1.0)], 3.0);
        assert_eq!(solve(&lp).status, LpStatus::DualInfeasible);
    }

    #[test]
    fn out_of_range_indices_are_errors_not_panics() {
        let mut lp = textbook_lp();
        lp.add_inequality(&[(5, 1.0)], 1.0);
        assert_eq!(
            LinearProgramSolver::default().solve(&lp),
            Err(SolveError::DimensionMismatch {
                what: "inequality column index",
                expected: 2,
                found: 5
            })
        );

        let mut lp = equality_lp();
        lp.equalities.push((7, 0, 1.0));
        assert_eq!(
            LinearProgramSolver::default().solve(&lp),
            Err(SolveError::DimensionMismatch {
                what: "equality row index",
                expected: 2,
                found: 7
            })
        );
    }

    #[test]
    fn malformed_data_and_settings_are_errors_not_panics() {
        let mut lp = textbook_lp();
        lp.objective.pop();
        assert!(matches!(
            LinearProgramSolver::default().solve(&lp),
            Err(SolveError::DimensionMismatch {
                what: "objective length",
                expected: 2,
                found: 1
            })
        ));

        let mut lp = textbook_lp();
        lp.inequalities[2].2 = f64::NAN;
        assert!(matches!(
            LinearProgramSolver::default().solve(&lp),
            Err(SolveError::NonFinite {
                what: "inequality coefficient",
                index: 2,
                ..
            })
        ));

        let mut lp = textbook_lp();
        lp.equality_rhs.push(f64::INFINITY);
        assert!(matches!(
            LinearProgramSolver::default().solve(&lp),
            Err(SolveError::NonFinite {
                what: "equality rhs",
                index: 0,
                ..
            })
        ));

        let mut solver = LinearProgramSolver {
            tolerance: 0.0,
            ..Default::default()
        };
        assert!(matches!(
            solver.solve(&textbook_lp()),
            Err(SolveError::NonPositive { .. })
        ));
    }

    #[test]
    fn degenerate_sizes_do_not_panic() {
        // no variables: a pure feasibility check
        let sol = solve(&LinearProgram::new(0));
        assert_eq!(sol.status, LpStatus::Optimal);
        let mut lp = LinearProgram::new(0);
        lp.add_equality(&[], 0.0);
        lp.add_inequality(&[], 1.0);
        assert_eq!(solve(&lp).status, LpStatus::Optimal);
        lp.add_inequality(&[], -1.0);
        assert_eq!(solve(&lp).status, LpStatus::PrimalInfeasible);
        // variables but no constraints, zero objective: any x is optimal
        let sol = solve(&LinearProgram::new(3));
        assert_eq!(sol.status, LpStatus::Optimal);
        assert_relative_eq!(sol.objective, 0.0, epsilon = TOL);
        // free variable with nonzero cost and no constraints is unbounded
        let mut lp = LinearProgram::new(1);
        lp.objective = vec![1.0];
        assert_eq!(solve(&lp).status, LpStatus::DualInfeasible);
        // explicit zero coefficients and empty rows are accepted
        let mut lp = LinearProgram::new(1);
        lp.add_inequality(&[(0, 0.0)], 1.0);
        lp.add_equality(&[], 0.0);
        assert!(LinearProgramSolver::default().solve(&lp).is_ok());
    }

    #[test]
    fn iteration_limit_is_reported_as_status() {
        let mut solver = LinearProgramSolver {
            max_iterations: 1,
            ..Default::default()
        };
        let sol = solver.solve(&textbook_lp()).expect("solve");
        assert_eq!(sol.status, LpStatus::MaxIterations);
    }
}
