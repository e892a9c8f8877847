//! How far a solution is from the optimality conditions of its LP.
//!
//! A solver's `Solved` says that *its* stopping test passed at *its*
//! tolerance, measured on its own scaled copy of the data. A caller that
//! claims a certified optimum (the limit analysis) checks the returned
//! point against the LP as written, with the conditions of the module docs
//! of [`crate::lp`]:
//!
//! ```text
//! primal feasibility   A_eq x = b_eq,  A_ineq x ≤ b_ineq
//! dual feasibility     c + A_eqᵀ y + A_ineqᵀ z = 0,  z ≥ 0
//! zero gap             cᵀx = −b_eqᵀ y − b_ineqᵀ z
//! ```
//!
//! Each residual is relative to the size of the terms it is made of, so
//! that it measures what the data can resolve, whatever the units.

use super::{LinearProgram, LinearProgramSolution};
use crate::error::SolveError;

/// The residuals of the optimality conditions of an LP at a solution, each
/// relative to the terms it sums (see [`LinearProgramSolution::optimality`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Optimality {
    /// Largest violation of an equality or inequality row, over the largest
    /// of `|b|` and the row sums `Σ |aᵢⱼ xⱼ|`.
    pub primal_residual: f64,
    /// Largest entry of `c + A_eqᵀ y + A_ineqᵀ z`, or of a negative `z`,
    /// over the largest of `|c|` and the column sums `Σ |aᵢⱼ yᵢ|`.
    pub dual_residual: f64,
    /// `|cᵀx − (−b_eqᵀ y − b_ineqᵀ z)|` over [`Optimality::scale`].
    pub gap: f64,
    /// The scale of the objective: the largest of `|cᵀx|`, the dual
    /// objective, `‖c‖∞ ‖x‖∞` and `‖b‖∞ ‖(y, z)‖∞`. An optimum below
    /// a tolerance times this scale is zero to the resolution of the data.
    pub scale: f64,
}

impl Optimality {
    /// The largest of the three residuals (NaN counts as the largest).
    pub fn worst(&self) -> f64 {
        [self.primal_residual, self.dual_residual, self.gap]
            .into_iter()
            .fold(
                0.0,
                |worst, r| if r.is_nan() { f64::NAN } else { worst.max(r) },
            )
    }

    /// Whether every residual is at most `tolerance`.
    pub fn holds(&self, tolerance: f64) -> bool {
        self.worst() <= tolerance
    }
}

/// `residual / scale`, zero when the residual is (a residual that is not
/// zero implies a term that is not, hence a positive scale).
fn relative(residual: f64, scale: f64) -> f64 {
    if residual == 0.0 {
        0.0
    } else {
        residual / scale
    }
}

/// Largest absolute value of `values` (0 when empty).
fn max_abs(values: &[f64]) -> f64 {
    values.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// Least scales against which [`LinearProgramSolution::optimality_at_scales`]
/// measures the three residuals (zero: the solution's own sizes alone).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Scales {
    /// Least scale of the primal rows' terms.
    pub primal: f64,
    /// Least scale of the dual (stationarity) terms.
    pub dual: f64,
    /// Least scale of the objectives.
    pub gap: f64,
}

impl LinearProgramSolution {
    /// The residuals of `lp`'s optimality conditions at this solution's
    /// `x`, `equality_duals` and `inequality_duals` (see [`Optimality`]).
    /// Meaningful for an optimal status; for an infeasibility certificate
    /// the vectors are a ray and the residuals say nothing.
    ///
    /// # Errors
    /// [`SolveError::DimensionMismatch`] when the vectors do not have the
    /// sizes of `lp` (a solution of another LP); as the solver's
    /// validation for malformed `lp` data.
    pub fn optimality(&self, lp: &LinearProgram) -> Result<Optimality, SolveError> {
        self.optimality_at_scales(lp, Scales::default())
    }

    /// [`Self::optimality`] with each residual measured against at least
    /// the given `floors`: the sizes its terms would have at the
    /// problem's natural scale where the solution's own are smaller (an
    /// optimum that is a small multiple of its data, whose terms shrink
    /// with it while the solver's rounding does not).
    ///
    /// # Errors
    /// As [`Self::optimality`].
    pub fn optimality_at_scales(
        &self,
        lp: &LinearProgram,
        floors: Scales,
    ) -> Result<Optimality, SolveError> {
        lp.validate()?;
        for (what, expected, found) in [
            ("solution x", lp.num_variables, self.x.len()),
            (
                "solution equality duals",
                lp.num_equalities(),
                self.equality_duals.len(),
            ),
            (
                "solution inequality duals",
                lp.num_inequalities(),
                self.inequality_duals.len(),
            ),
        ] {
            if expected != found {
                return Err(SolveError::DimensionMismatch {
                    what,
                    expected,
                    found,
                });
            }
        }
        let (x, y, z) = (&self.x, &self.equality_duals, &self.inequality_duals);

        // Primal: A x − b per row, and the sizes of its terms.
        let mut eq_sum = vec![0.0; lp.num_equalities()];
        let mut eq_size = vec![0.0; lp.num_equalities()];
        for &(i, j, a) in &lp.equalities {
            eq_sum[i] += a * x[j];
            eq_size[i] += (a * x[j]).abs();
        }
        let mut in_sum = vec![0.0; lp.num_inequalities()];
        let mut in_size = vec![0.0; lp.num_inequalities()];
        for &(i, j, a) in &lp.inequalities {
            in_sum[i] += a * x[j];
            in_size[i] += (a * x[j]).abs();
        }
        let violation = eq_sum
            .iter()
            .zip(&lp.equality_rhs)
            .map(|(ax, b)| (ax - b).abs())
            .chain(
                in_sum
                    .iter()
                    .zip(&lp.inequality_rhs)
                    .map(|(ax, b)| (ax - b).max(0.0)),
            )
            .fold(0.0, f64::max);
        let primal_scale = max_abs(&lp.equality_rhs)
            .max(max_abs(&lp.inequality_rhs))
            .max(max_abs(&eq_size))
            .max(max_abs(&in_size))
            .max(floors.primal);

        // Dual: c + A_eqᵀ y + A_ineqᵀ z per column, and z ≥ 0.
        let mut stationarity = lp.objective.clone();
        let mut column_size: Vec<f64> = lp.objective.iter().map(|c| c.abs()).collect();
        for &(i, j, a) in &lp.equalities {
            stationarity[j] += a * y[i];
            column_size[j] += (a * y[i]).abs();
        }
        for &(i, j, a) in &lp.inequalities {
            stationarity[j] += a * z[i];
            column_size[j] += (a * z[i]).abs();
        }
        let negative_z = z.iter().fold(0.0f64, |m, &zi| m.max(-zi));
        let dual_violation = max_abs(&stationarity).max(negative_z);
        let dual_scale = max_abs(&column_size).max(max_abs(z)).max(floors.dual);

        // Gap between cᵀx and the dual objective recomputed from y, z.
        let primal_objective: f64 = lp.objective.iter().zip(x).map(|(c, x)| c * x).sum();
        let dual_objective: f64 = -lp
            .equality_rhs
            .iter()
            .zip(y)
            .chain(lp.inequality_rhs.iter().zip(z))
            .map(|(b, m)| b * m)
            .sum::<f64>();
        let b_norm = max_abs(&lp.equality_rhs).max(max_abs(&lp.inequality_rhs));
        let scale = primal_objective
            .abs()
            .max(dual_objective.abs())
            .max(max_abs(&lp.objective) * max_abs(x))
            .max(b_norm * max_abs(y).max(max_abs(z)))
            .max(floors.gap);
        Ok(Optimality {
            primal_residual: relative(violation, primal_scale),
            dual_residual: relative(dual_violation, dual_scale),
            gap: relative((primal_objective - dual_objective).abs(), scale),
            scale,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lp::{LinearProgramSolver, LpSolver, LpStatus};

    use crate::lp::clarabel::tests::textbook_lp;

    /// The exact optimum x = (1.6, 1.2), z = (0.4, 0.2, 0, 0).
    fn exact_solution() -> LinearProgramSolution {
        LinearProgramSolution {
            status: LpStatus::Optimal,
            x: vec![1.6, 1.2],
            objective: -2.8,
            dual_objective: -2.8,
            equality_duals: Vec::new(),
            inequality_duals: vec![0.4, 0.2, 0.0, 0.0],
            iterations: 0,
            solver_status: "exact".into(),
        }
    }

    #[test]
    fn the_exact_optimum_has_zero_residuals() {
        let o = exact_solution().optimality(&textbook_lp()).unwrap();
        assert!(o.holds(1e-15), "{o:?}");
        // |cᵀx| = 2.8 is the largest of the objective's sizes
        assert!((o.scale - 2.8).abs() < 1e-12, "{o:?}");
    }

    #[test]
    fn each_condition_is_measured_on_its_own() {
        let lp = textbook_lp();
        // infeasible x: 3·2 + 1.2 = 7.2 > 6
        let mut s = exact_solution();
        s.x[0] = 2.0;
        let o = s.optimality(&lp).unwrap();
        assert!((o.primal_residual - 1.2 / 7.2).abs() < 1e-12, "{o:?}");
        // a negative multiplier of an inequality
        let mut s = exact_solution();
        s.inequality_duals[2] = -0.1;
        let o = s.optimality(&lp).unwrap();
        // (1.6 + 2·1.2 rounds to 4 + 4e-16: residuals of round-off only)
        assert!(o.dual_residual > 0.01 && o.primal_residual < 1e-15, "{o:?}");
        // feasible both ways, but not optimal: x = 0, z = the exact duals
        let mut s = exact_solution();
        s.x = vec![0.0, 0.0];
        let o = s.optimality(&lp).unwrap();
        assert!(o.primal_residual == 0.0 && o.dual_residual < 1e-15, "{o:?}");
        assert!(o.gap > 0.5, "{o:?}");
    }

    #[test]
    fn a_solution_of_another_lp_is_an_error() {
        let mut s = exact_solution();
        s.x.push(0.0);
        assert_eq!(
            s.optimality(&textbook_lp()),
            Err(SolveError::DimensionMismatch {
                what: "solution x",
                expected: 2,
                found: 3
            })
        );
    }

    #[test]
    fn clarabel_at_its_default_tolerance_meets_the_conditions_tightly() {
        let lp = textbook_lp();
        let s = LinearProgramSolver::default().solve(&lp).unwrap();
        let o = s.optimality(&lp).unwrap();
        assert!(o.holds(1e-8), "{o:?}");
    }
}
