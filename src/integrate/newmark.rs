//! The Newmark-β family of implicit schemes.

use super::{ImplicitCoefficients, ImplicitIntegrator};
use crate::error::{DismechError, Result};

/// Newmark's scheme:
///
/// `Δd = Δt v₀ + Δt² [(½ − β) a₀ + β a₁]`, `v₁ = v₀ + Δt [(1 − γ) a₀ + γ a₁]`.
///
/// β = ¼, γ = ½ is the energy-conserving trapezoidal rule; β = ½, γ = 1 is
/// the dissipative choice of classic DDA (paper 003).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Newmark {
    beta: f64,
    gamma: f64,
}

impl Newmark {
    /// A Newmark scheme; requires `β > 0` and `γ ≥ ½` (unconditional
    /// stability needs `2β ≥ γ ≥ ½`).
    pub fn new(beta: f64, gamma: f64) -> Result<Self> {
        if !(beta.is_finite() && beta > 0.0) {
            return Err(DismechError::InvalidParameter {
                name: "Newmark beta",
                value: beta,
                requirement: "must be finite and > 0",
            });
        }
        if !(gamma.is_finite() && gamma >= 0.5) {
            return Err(DismechError::InvalidParameter {
                name: "Newmark gamma",
                value: gamma,
                requirement: "must be finite and >= 0.5",
            });
        }
        Ok(Self { beta, gamma })
    }

    /// The classic DDA choice β = ½, γ = 1.
    pub fn dda() -> Self {
        Self {
            beta: 0.5,
            gamma: 1.0,
        }
    }

    /// The trapezoidal rule β = ¼, γ = ½.
    pub fn trapezoidal() -> Self {
        Self {
            beta: 0.25,
            gamma: 0.5,
        }
    }
}

impl Newmark {
    /// β.
    pub fn beta(&self) -> f64 {
        self.beta
    }

    /// γ.
    pub fn gamma(&self) -> f64 {
        self.gamma
    }
}

impl ImplicitIntegrator for Newmark {
    fn coefficients(&self, dt: f64) -> ImplicitCoefficients {
        let (b, g) = (self.beta, self.gamma);
        let ca = 1.0 / (b * dt * dt);
        let av = 1.0 / (b * dt);
        let aa = 0.5 / b - 1.0;
        // v₁ = v₀ + Δt(1−γ)a₀ + Δt γ a₁, with a₁ substituted.
        ImplicitCoefficients {
            acceleration_per_increment: ca,
            acceleration_from_velocity: av,
            acceleration_from_acceleration: aa,
            velocity_per_increment: g * dt * ca,
            velocity_from_velocity: g * dt * av - 1.0,
            velocity_from_acceleration: g * dt * aa - dt * (1.0 - g),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Integrate `m a + k d = 0` implicitly: each step solves
    /// `(k + c_a m) Δd = −k d₀ + m (a_v v₀ + a_a a₀)`.
    fn oscillate(scheme: &Newmark, steps: usize, dt: f64) -> (f64, f64) {
        let (m, k) = (1.0, 4.0 * std::f64::consts::PI * std::f64::consts::PI);
        let (mut d, mut v, mut a) = (1.0, 0.0, -k);
        let c = scheme.coefficients(dt);
        for _ in 0..steps {
            let rhs = -k * d
                + m * (c.acceleration_from_velocity * v + c.acceleration_from_acceleration * a);
            let dd = rhs / (k + c.acceleration_per_increment * m);
            scheme.finish(dt, dd, &mut v, &mut a);
            d += dd;
        }
        (d, 0.5 * m * v * v + 0.5 * k * d * d)
    }

    #[test]
    fn trapezoidal_newmark_conserves_the_energy_of_an_oscillator() {
        let e0 = 0.5 * 4.0 * std::f64::consts::PI * std::f64::consts::PI;
        let (_, e) = oscillate(&Newmark::trapezoidal(), 1000, 0.01);
        approx::assert_relative_eq!(e, e0, max_relative = 1e-10);
    }

    #[test]
    fn dda_newmark_dissipates_but_stays_stable_at_large_steps() {
        let e0 = 0.5 * 4.0 * std::f64::consts::PI * std::f64::consts::PI;
        let (d, e) = oscillate(&Newmark::dda(), 100, 0.5);
        assert!(d.is_finite());
        assert!(e < e0);
    }

    #[test]
    fn newmark_rejects_gamma_below_one_half() {
        assert!(Newmark::new(0.25, 0.4).is_err());
    }
}
