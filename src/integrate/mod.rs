//! Time integrators: advance the state of the degrees of freedom over a step.
//!
//! | scheme | kind | used by |
//! |---|---|---|
//! | [`ExplicitEuler`] (semi-implicit / symplectic Euler) | explicit | ellipse and circle DEM (paper 000) |
//! | [`Newmark`] (β, γ) | implicit | DDA (paper 003: β = 0.5, γ = 1) |
//!
//! Quasi-static methods (HPM load steps, the LP limit state) use no
//! integrator.
//!
//! An explicit scheme advances each DOF from the acceleration at the start
//! of the step. An implicit scheme gives instead the linear map from the
//! step's displacement increment `Δd` to the end-of-step acceleration and
//! velocity, `a₁ = c_a Δd − (a_v v₀ + a_a a₀)`, `v₁ = c_v Δd − (…)`, which the
//! global assembly turns into an effective mass term `c_a M` and an inertia
//! load; after the solve, [`Integrator::finish_implicit`] updates `v` and
//! `a`.

mod explicit_euler;
mod newmark;

pub use explicit_euler::ExplicitEuler;
pub use newmark::Newmark;

/// Coefficients of an implicit scheme for one step of size `dt`:
/// `a₁ = acceleration_per_increment · Δd − acceleration_history(v₀, a₀)` and
/// `v₁ = velocity_per_increment · Δd − velocity_history(v₀, a₀)`.
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

/// A time-stepping scheme for second-order equations `M a = f`.
pub trait Integrator {
    /// Whether the scheme is explicit (needs only `M⁻¹ f`).
    fn is_explicit(&self) -> bool;

    /// Explicit step of one DOF: given the acceleration at the start of the
    /// step, update the velocity in place and return the displacement
    /// increment. Implicit schemes return `None`.
    fn explicit_step(&self, dt: f64, acceleration: f64, velocity: &mut f64) -> Option<f64>;

    /// The implicit scheme's coefficients for a step `dt`; `None` for an
    /// explicit scheme.
    fn implicit_coefficients(&self, dt: f64) -> Option<ImplicitCoefficients>;

    /// After an implicit solve: end-of-step velocity and acceleration of one
    /// DOF from its increment `Δd`. Explicit schemes leave them unchanged.
    fn finish_implicit(&self, dt: f64, increment: f64, velocity: &mut f64, acceleration: &mut f64) {
        if let Some(c) = self.implicit_coefficients(dt) {
            let (v0, a0) = (*velocity, *acceleration);
            *acceleration = c.acceleration_per_increment * increment
                - c.acceleration_from_velocity * v0
                - c.acceleration_from_acceleration * a0;
            *velocity = c.velocity_per_increment * increment
                - c.velocity_from_velocity * v0
                - c.velocity_from_acceleration * a0;
        }
    }
}
