//! The Newmark-β family of implicit schemes.

use super::{ImplicitCoefficients, ImplicitIntegrator};
use crate::error::{DismechError, Result};

/// Newmark's scheme:
///
/// `Δd = Δt v₀ + Δt² [(½ − β) a₀ + β a₁]`, `v₁ = v₀ + Δt [(1 − γ) a₀ + γ a₁]`.
///
/// β = ¼, γ = ½ is the energy-conserving trapezoidal rule; β = ½, γ = 1 is
/// the dissipative choice of classic DDA (paper 003).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Newmark {
    beta: f64,
    gamma: f64,
}

impl Newmark {
    /// A Newmark scheme; requires `β > 0` and `γ ≥ ½` (unconditional
    /// stability needs `2β ≥ γ ≥ ½`).
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming `Newmark beta` for a β
    /// that is not finite and positive, or `Newmark gamma` for a γ that is
    /// not finite or below ½.
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
    /// The spectral radius of the scheme's amplification matrix for an
    /// undamped oscillator at `ω Δt = omega_dt`: how much of a mode of that
    /// frequency survives one step (1 for no numerical damping). With
    /// `Δt = 1`, `m = 1`, `k = Ω²`, one step takes `(d, v, a)` to
    /// `d₁ = (d + v + (½ − β) a)/(1 + β Ω²)`, `a₁ = −Ω² d₁`,
    /// `v₁ = v + (1 − γ) a + γ a₁`.
    pub fn spectral_radius(&self, omega_dt: f64) -> f64 {
        let (b, g) = (self.beta, self.gamma);
        let w2 = omega_dt * omega_dt;
        let mut amplification = nalgebra::Matrix3::<f64>::zeros();
        for j in 0..3 {
            let mut x = [0.0; 3];
            x[j] = 1.0;
            let [d0, v0, a0] = x;
            let d1 = (d0 + v0 + (0.5 - b) * a0) / (1.0 + b * w2);
            let a1 = -w2 * d1;
            let v1 = v0 + (1.0 - g) * a0 + g * a1;
            amplification.set_column(j, &nalgebra::Vector3::new(d1, v1, a1));
        }
        amplification
            .complex_eigenvalues()
            .iter()
            .map(|z| z.norm())
            .fold(0.0, f64::max)
    }

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

    /// The trapezoidal rule keeps every mode; DDA's β = ½, γ = 1 damps
    /// little at high frequency (ρ → 1) and most near ω Δt = 4; β =
    /// (γ + ½)²/4 with γ = 1 damps the high frequencies to ρ → 1/3.
    #[test]
    fn spectral_radius_shows_where_each_scheme_damps() {
        for w in [0.1, 1.0, 10.0, 1e3] {
            approx::assert_relative_eq!(
                Newmark::trapezoidal().spectral_radius(w),
                1.0,
                epsilon = 1e-9
            );
        }
        let dda = Newmark::dda();
        assert!(dda.spectral_radius(4.0) < 0.34);
        assert!(dda.spectral_radius(40.0) > 0.99);
        let damped = Newmark::new(0.5625, 1.0).unwrap();
        approx::assert_relative_eq!(damped.spectral_radius(1e4), 1.0 / 3.0, epsilon = 1e-4);
        assert!(damped.spectral_radius(40.0) < 0.34);
    }

    #[test]
    fn newmark_rejects_gamma_below_one_half() {
        assert!(Newmark::new(0.25, 0.4).is_err());
    }
}
