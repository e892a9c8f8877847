//! The solve of an explicit method: a diagonal (lumped) mass matrix.

use super::{LinearSolver, LinearSolverInfo, SolveError, SolveStats};

/// A diagonal system `M a = f`, one entry per degree of freedom.
///
/// The explicit DEM fills `mass` once (masses and moments of inertia) and
/// `force` every step; the solver writes the accelerations.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LumpedSystem {
    /// Diagonal of the mass matrix (mass for translations, moment of inertia
    /// for rotations); each entry must be positive. An infinite entry is a
    /// prescribed degree of freedom: it does not accelerate, whatever its
    /// (finite) force.
    pub mass: Vec<f64>,
    /// Right-hand side (force or moment).
    pub force: Vec<f64>,
}

/// A diagonal matrix, given as its diagonal, as a [`LinearSolver`]; hot
/// loops call [`solve_lumped_into`] with a buffer they keep instead.
#[derive(Debug, Clone, Default)]
pub struct LumpedMassSolver {
    diagonal: Vec<f64>,
}

impl LumpedMassSolver {
    /// The solver.
    pub fn new() -> Self {
        Self::default()
    }
}

impl LinearSolver<[f64]> for LumpedMassSolver {
    /// Check that every diagonal entry is positive (or `+∞`, a prescribed
    /// degree of freedom), and keep the diagonal.
    fn factor(&mut self, diagonal: &[f64]) -> Result<(), SolveError> {
        if let Some((index, &value)) = diagonal
            .iter()
            .enumerate()
            .find(|(_, m)| m.is_nan() || **m <= 0.0)
        {
            return Err(SolveError::NonPositive {
                what: "lumped mass",
                index,
                value,
            });
        }
        self.diagonal.clear();
        self.diagonal.extend_from_slice(diagonal);
        Ok(())
    }

    /// `x_i = b_i / m_i`.
    fn solve_in_place(&mut self, _: &[f64], rhs: &mut [f64]) -> Result<SolveStats, SolveError> {
        super::pattern::check_rhs(rhs, self.diagonal.len())?;
        for (x, m) in rhs.iter_mut().zip(&self.diagonal) {
            *x /= m;
        }
        Ok(SolveStats::direct())
    }
}

impl LinearSolverInfo for LumpedMassSolver {
    /// Always 0: a diagonal has no pattern to analyse.
    fn symbolic_analyses(&self) -> usize {
        0
    }

    fn factor_entries(&self) -> Option<usize> {
        Some(self.diagonal.len())
    }
}

/// Solve `M a = f` into `out` without allocating when `out` already has the
/// right length; used in explicit hot loops.
///
/// # Errors
/// [`SolveError::DimensionMismatch`] when `force` and `mass` differ in
/// length; [`SolveError::NonPositive`] naming the index of a mass that is
/// zero, negative or NaN (`+∞`, a prescribed degree of freedom, is
/// accepted); [`SolveError::NonFinite`] naming the index of a force that
/// is not finite. `out` may be partly written on an error.
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
        if m.is_nan() || m <= 0.0 {
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
        let mut a = Vec::new();
        solve_lumped_into(&system, &mut a).unwrap();
        assert_eq!(a, vec![0.5, -2.0]);
        let mut solver = LumpedMassSolver::new();
        solver.factor(&system.mass).unwrap();
        let mut b = system.force.clone();
        solver.solve_in_place(&system.mass, &mut b).unwrap();
        assert_eq!(b, a);
    }

    #[test]
    fn lumped_solve_rejects_zero_mass() {
        let system = LumpedSystem {
            mass: vec![1.0, 0.0],
            force: vec![1.0, 1.0],
        };
        let err = solve_lumped_into(&system, &mut Vec::new()).unwrap_err();
        assert!(matches!(err, SolveError::NonPositive { index: 1, .. }));
        let err = LumpedMassSolver::new().factor(&system.mass).unwrap_err();
        assert!(matches!(err, SolveError::NonPositive { index: 1, .. }));
    }
}
