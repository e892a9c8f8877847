//! The static admissibility of a limit analysis' dual: every body in
//! equilibrium under its loads and the contact forces, every contact force
//! within strength.

use super::analysis::LimitResult;
use super::model::{LimitModel, LoadDriver, Partner};
use crate::math::{cross, Vec2};

/// How far the dual contact forces of a result are from a statically
/// admissible field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Admissibility {
    /// Largest out-of-balance force or moment of a body (moments only for
    /// rotating bodies), over the scale of the loads and contact forces.
    pub equilibrium: f64,
    /// Largest excess `|T| − (c + μ max(N, 0))` over the same scale (zero or
    /// negative when every force is within strength).
    pub strength_excess: f64,
    /// The force scale: the largest of the loads (as given, and times the
    /// multiplier where the dead loads drive), the live load at its
    /// multiplier and the contact forces (N per m).
    pub scale: f64,
}

/// Check the dual of `result` (normal and shear forces) against `model`:
/// equilibrium of every body with its dead load (times the found
/// multiplier where the dead loads drive the analysis), the live load at
/// the found multiplier (if the model has one) and the contact forces.
pub fn admissibility(model: &LimitModel, result: &LimitResult) -> Admissibility {
    let n = model.bodies().len();
    let mut force = vec![Vec2::zeros(); n];
    let mut moment = vec![0.0; n];
    let mut scale = 0.0f64;
    let mut excess = f64::NEG_INFINITY;
    for (c, contact) in model.contacts().iter().enumerate() {
        let (normal, shear) = (result.normal_force[c], result.shear_force[c]);
        let on_b = contact.normal * normal - contact.tangent() * shear;
        scale = scale.max(on_b.norm());
        let a = contact.body;
        force[a] -= on_b;
        moment[a] -= cross(&(contact.point - model.bodies()[a].centre), &on_b);
        if let Partner::Body(b) = contact.partner {
            force[b] += on_b;
            moment[b] += cross(&(contact.point - model.bodies()[b].centre), &on_b);
        }
        let law = contact.law;
        excess = excess.max(shear.abs() - (law.cohesion() + law.friction() * normal.max(0.0)));
    }
    // The dead loads, at their multiplier where it is the one sought.
    let factor = match (model.load_driver(), result.load) {
        (Some(LoadDriver::DeadLoads), Some(lambda)) => lambda,
        _ => 1.0,
    };
    // The scale counts the real loads (λ = 1) too: a small multiplier of
    // the dead loads is judged against the weight, as its certificate is.
    for (i, b) in model.bodies().iter().enumerate() {
        force[i] += b.load * factor;
        scale = scale.max((b.load * factor).norm()).max(b.load.norm());
    }
    if let (Some(live), Some(lambda)) = (model.live_load(), result.load) {
        let f = live.force * lambda;
        force[live.body] += f;
        moment[live.body] += cross(&(live.point - model.bodies()[live.body].centre), &f);
        scale = scale.max(f.norm());
    }
    let scale = scale.max(f64::MIN_POSITIVE);
    let mut worst = 0.0f64;
    for (i, b) in model.bodies().iter().enumerate() {
        worst = worst.max(force[i].norm());
        if b.rotates {
            worst = worst.max(moment[i].abs() / b.radius().max(f64::MIN_POSITIVE));
        }
    }
    Admissibility {
        equilibrium: worst / scale,
        strength_excess: excess.max(0.0) / scale,
        scale,
    }
}
