//! Schemes without carried motion: quasi-static steps, and any implicit
//! scheme restarted from rest after every step.

use super::{ImplicitCoefficients, ImplicitIntegrator};

/// No inertia: each step is an equilibrium of the loads at its end
/// (penalty pushovers, load steps). Velocities and accelerations stay zero.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct QuasiStatic;

impl ImplicitIntegrator for QuasiStatic {
    fn coefficients(&self, _dt: f64) -> ImplicitCoefficients {
        ImplicitCoefficients::zero()
    }

    fn finish(&self, _dt: f64, _increment: f64, velocity: &mut f64, acceleration: &mut f64) {
        *velocity = 0.0;
        *acceleration = 0.0;
    }
}

/// An implicit scheme whose velocities and accelerations are reset to zero
/// after every step: the "static" analysis of classic DDA, which keeps the
/// inertia term in each step's equations (a numerical damping of the
/// step) but lets no motion carry over.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Restarting<I>(pub I);

impl<I: ImplicitIntegrator> ImplicitIntegrator for Restarting<I> {
    fn coefficients(&self, dt: f64) -> ImplicitCoefficients {
        self.0.coefficients(dt)
    }

    fn finish(&self, _dt: f64, _increment: f64, velocity: &mut f64, acceleration: &mut f64) {
        *velocity = 0.0;
        *acceleration = 0.0;
    }
}
