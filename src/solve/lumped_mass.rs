//! The "global solve" of an explicit method: a diagonal mass matrix.

use super::{GlobalSolver, SolveError};

/// A diagonal system `M a = f`, one entry per degree of freedom.
///
/// The explicit DEM fills `mass` once (masses and moments of inertia) and
/// `force` every step; the solver writes the accelerations.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LumpedSystem {
    /// Diagonal of the mass matrix (mass for translations, moment of inertia
    /// for rotations); each entry must be positive.
    pub mass: Vec<f64>,
    /// Right-hand side (force or moment).
    pub force: Vec<f64>,
}

/// Solves a [`LumpedSystem`]; hot loops call [`solve_lumped_into`] with a
/// buffer they keep instead.
#[derive(Debug, Clone, Copy, Default)]
pub struct LumpedMassSolver;

impl LumpedMassSolver {
    /// The solver.
    pub fn new() -> Self {
        Self
    }
}

impl GlobalSolver for LumpedMassSolver {
    type System = LumpedSystem;
    type Solution = Vec<f64>;

    fn solve(&mut self, system: &LumpedSystem) -> Result<Vec<f64>, SolveError> {
        let mut out = Vec::with_capacity(system.mass.len());
        solve_lumped_into(system, &mut out)?;
        Ok(out)
    }
}

/// Solve `M a = f` into `out` without allocating when `out` already has the
/// right length; used in explicit hot loops.
pub fn solve_lumped_into(system: &LumpedSystem, out: &mut Vec<f64>) -> Result<(), SolveError> {
    if system.force.len() != system.mass.len() {
        return Err(SolveError::DimensionMismatch {
            what: "lumped force vector",
            expected: system.mass.len(),
            found: system.force.len(),
        });
    }
    out.resize(system.mass.len(), 0.0);
    for (i, (&m, &f)) in system.mass.iter().zip(&system.force).enumerate() {
        if m.is_nan() || m <= 0.0 || !m.is_finite() {
            return Err(SolveError::NonPositive {
                what: "lumped mass",
                index: i,
                value: m,
            });
        }
        if !f.is_finite() {
            return Err(SolveError::NonFinite {
                what: "lumped force",
                index: i,
                value: f,
            });
        }
        out[i] = f / m;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lumped_solve_divides_force_by_mass() {
        let system = LumpedSystem {
            mass: vec![2.0, 4.0],
            force: vec![1.0, -8.0],
        };
        let a = LumpedMassSolver::new().solve(&system).unwrap();
        assert_eq!(a, vec![0.5, -2.0]);
    }

    #[test]
    fn lumped_solve_rejects_zero_mass() {
        let system = LumpedSystem {
            mass: vec![1.0, 0.0],
            force: vec![1.0, 1.0],
        };
        let err = LumpedMassSolver::new().solve(&system).unwrap_err();
        assert!(matches!(err, SolveError::NonPositive { index: 1, .. }));
    }
}
