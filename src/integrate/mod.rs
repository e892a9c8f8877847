//! The integrator slot: how a step advances the degrees of freedom.
//!
//! | scheme | trait | used by |
//! |---|---|---|
//! | [`ExplicitEuler`] (semi-implicit / symplectic Euler) | [`ExplicitIntegrator`] | explicit dynamics: ellipse and circle DEM (paper 000), polygon DEM |
//! | [`Newmark`] (β, γ of the user's choice) | [`ImplicitIntegrator`] | implicit dynamics: DDA (paper 003: β = ½, γ = 1), the trapezoidal rule (β = ¼, γ = ½) |
//! | [`QuasiStatic`] | [`ImplicitIntegrator`] | quasi-static penalty analyses (no inertia) |
//! | [`Restarting`] | [`ImplicitIntegrator`] | "static" DDA: a scheme whose velocities are reset after every step |
//!
//! The limit state of a rigid-plastic LP uses no integrator.
//!
//! An explicit scheme advances each DOF from the acceleration at the start
//! of the step. An implicit scheme gives instead the linear map from the
//! step's displacement increment `Δd` to the end-of-step acceleration and
//! velocity, `a₁ = c_a Δd − (a_v v₀ + a_a a₀)`, `v₁ = c_v Δd − (…)`, which the
//! global assembly turns into an effective mass term `c_a M` and an inertia
//! load; after the solve, [`ImplicitIntegrator::finish`] updates `v` and
//! `a`. A driver names the kind it needs in its bounds, so an implicit
//! scheme handed to an explicit driver (or the reverse) does not compile.

mod explicit_euler;
mod newmark;
mod quasi_static;

pub use explicit_euler::ExplicitEuler;
pub use newmark::Newmark;
pub use quasi_static::{QuasiStatic, Restarting};

/// Coefficients of an implicit scheme for one step of size `dt`:
/// `a₁ = acceleration_per_increment · Δd − acceleration_from_velocity · v₀
/// − acceleration_from_acceleration · a₀` and likewise for `v₁`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImplicitCoefficients {
    /// `∂a₁/∂Δd`: the factor of the effective mass term.
    pub acceleration_per_increment: f64,
    /// Factor of `v₀` in `a₁ = … − (·) v₀ − …`.
    pub acceleration_from_velocity: f64,
    /// Factor of `a₀` in `a₁ = … − (·) a₀`.
    pub acceleration_from_acceleration: f64,
    /// `∂v₁/∂Δd`.
    pub velocity_per_increment: f64,
    /// Factor of `v₀` in `v₁ = … − (·) v₀ − …`.
    pub velocity_from_velocity: f64,
    /// Factor of `a₀` in `v₁ = … − (·) a₀`.
    pub velocity_from_acceleration: f64,
}

impl ImplicitCoefficients {
    /// All zero: no inertia and no rate (quasi-static).
    pub fn zero() -> Self {
        Self {
            acceleration_per_increment: 0.0,
            acceleration_from_velocity: 0.0,
            acceleration_from_acceleration: 0.0,
            velocity_per_increment: 0.0,
            velocity_from_velocity: 0.0,
            velocity_from_acceleration: 0.0,
        }
    }
}

/// An explicit scheme for `M a = f`: each DOF advances from the
/// acceleration at the start of the step. Shared by the threads that
/// advance the bodies, hence `Sync`.
pub trait ExplicitIntegrator: Sync {
    /// Advance one DOF: update the velocity in place and return the
    /// displacement increment of the step.
    fn step(&self, dt: f64, acceleration: f64, velocity: &mut f64) -> f64;
}

/// An implicit scheme for `M a = f`: the step's equations are solved for
/// the displacement increment, with the inertia expressed through it.
pub trait ImplicitIntegrator {
    /// The scheme's coefficients for a step `dt`.
    fn coefficients(&self, dt: f64) -> ImplicitCoefficients;

    /// After the solve: end-of-step velocity and acceleration of one DOF
    /// from its increment `Δd`.
    fn finish(&self, dt: f64, increment: f64, velocity: &mut f64, acceleration: &mut f64) {
        let c = self.coefficients(dt);
        let (v0, a0) = (*velocity, *acceleration);
        *acceleration = c.acceleration_per_increment * increment
            - c.acceleration_from_velocity * v0
            - c.acceleration_from_acceleration * a0;
        *velocity = c.velocity_per_increment * increment
            - c.velocity_from_velocity * v0
            - c.velocity_from_acceleration * a0;
    }
}
