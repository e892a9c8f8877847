//! The explicit Euler scheme of the DEM.

use super::ExplicitIntegrator;

/// Semi-implicit (symplectic) Euler, the DEM convention: first the velocity,
/// then the position with the *new* velocity,
///
/// `v₁ = v₀ + Δt a₀`, `Δd = Δt v₁`.
///
/// Paper 000 solves its eqs. (20)–(22) "by Euler's method"; this variant is
/// the one Cundall's DEM uses. It is first-order accurate, symplectic for
/// conservative forces, and stable for an undamped spring when
/// `Δt < 2/ω`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct ExplicitEuler;

impl ExplicitIntegrator for ExplicitEuler {
    fn step(&self, dt: f64, acceleration: f64, velocity: &mut f64) -> f64 {
        *velocity += dt * acceleration;
        dt * *velocity
    }
}
