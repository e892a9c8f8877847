//! Clarabel's interior-point method as an [`LpSolver`].

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettings, DefaultSolver, IPSolver, NonnegativeConeT, SupportedConeT, ZeroConeT,
};

use super::{LinearProgram, LinearProgramSolution, LpSolver, LpStatus};
use crate::error::{LpFailure, SolveError};

/// Interior-point LP solver backed by Clarabel.
#[derive(Debug, Clone)]
pub struct LinearProgramSolver {
    /// Used as Clarabel's `tol_gap_abs`, `tol_gap_rel` and `tol_feas`; must be
    /// finite and positive. Default `1e-9`. A loose tolerance gives a
    /// loose solution: check it with
    /// [`super::LinearProgramSolution::optimality`] (the limit analysis
    /// does, at its own [`crate::limit::CERTIFICATE_TOLERANCE`]).
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

        let mut solver =
            DefaultSolver::new(&p, &lp.objective, &a, &b, &cones, settings).map_err(|e| {
                SolveError::LinearProgram(LpFailure::Setup {
                    message: e.to_string(),
                })
            })?;
        solver.solve();
        let sol = &solver.solution;

        let mut z = sol.z.clone();
        z.resize(m_eq + m_ineq, 0.0);
        let inequality_duals = z.split_off(m_eq);
        let mut solution = LinearProgramSolution {
            status: sol.status.into(),
            x: sol.x.clone(),
            objective: sol.obj_val,
            dual_objective: sol.obj_val_dual,
            equality_duals: z,
            inequality_duals,
            iterations: sol.iterations,
            solver_status: format!("{:?}", sol.status),
        };
        if matches!(solution.status, LpStatus::Optimal | LpStatus::AlmostOptimal) {
            exact_degenerate_optimum(lp, &mut solution);
        }
        Ok(solution)
    }
}

/// Replace the interior-point answer of two degenerate kinds of LP by
/// their exact optimum, which the interior point only approaches (its
/// iterates shrink towards zero, and their residuals relative to their own
/// size do not):
/// * a zero objective (a feasibility problem, e.g. whether any mechanism
///   lets the dead loads do work): every feasible point is optimal and
///   `y = 0`, `z = 0` is an exact dual optimum;
/// * a homogeneous LP (every right-hand side zero, e.g. the static LP of
///   multiplied dead loads): a bounded optimum is zero, attained at
///   `x = 0`.
fn exact_degenerate_optimum(lp: &LinearProgram, solution: &mut LinearProgramSolution) {
    if lp.objective.iter().all(|&c| c == 0.0) {
        solution.equality_duals.iter_mut().for_each(|y| *y = 0.0);
        solution.inequality_duals.iter_mut().for_each(|z| *z = 0.0);
        solution.objective = 0.0;
        solution.dual_objective = 0.0;
    } else if lp
        .equality_rhs
        .iter()
        .chain(&lp.inequality_rhs)
        .all(|&b| b == 0.0)
    {
        solution.x.iter_mut().for_each(|x| *x = 0.0);
        solution.objective = 0.0;
        solution.dual_objective = 0.0;
    }
}

impl LpSolver for LinearProgramSolver {
    /// Validates `system` and solves it.
    ///
    /// Errors: [`SolveError::DimensionMismatch`] for a wrong objective length
    /// or an out-of-range triplet index (`expected` is the exclusive bound,
    /// `found` the index); [`SolveError::NonFinite`] for a non-finite
    /// coefficient, right-hand side or tolerance; [`SolveError::NonPositive`]
    /// for a non-positive tolerance; [`SolveError::LinearProgram`] if Clarabel
    /// rejects the problem ([`LpFailure::Setup`], with its message) or
    /// fails internally ([`LpFailure::Panicked`]). Infeasibility and
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
                Err(SolveError::LinearProgram(LpFailure::Panicked {
                    message: msg,
                }))
            },
        )
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use approx::assert_relative_eq;

    const TOL: f64 = 1e-6;

    fn solve(lp: &LinearProgram) -> LinearProgramSolution {
        LinearProgramSolver::default().solve(lp).expect("solve")
    }

    /// max x + y s.t. x + 2y ≤ 4, 3x + y ≤ 6, x, y ≥ 0.
    pub(in crate::lp) fn textbook_lp() -> LinearProgram {
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
