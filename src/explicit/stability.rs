//! The stable time step of the explicit scheme.

use crate::law::{BoundedStiffness, PairProperties};
use crate::scene::Scene;
use crate::shape::{AnyShape2, Shape2};

/// The estimated stable limit and the mode that governs it.
#[derive(Debug, Clone, PartialEq)]
pub struct StabilityLimit {
    /// Largest stable time step (s).
    pub dt: f64,
    /// Which contact mode governs, in words.
    pub governing: String,
}

/// Stable limit of semi-implicit Euler for a damped oscillator of
/// frequency `ω = √(k/m)` and damping ratio `ζ = η / (2√(k m))`:
/// `Δt < (2/ω)(√(1+ζ²) − ζ)` (from the eigenvalues of the one-step map;
/// `2/ω` without damping).
pub fn oscillator_limit(stiffness: f64, mass: f64, damping: f64) -> f64 {
    if stiffness <= 0.0 || mass <= 0.0 {
        return f64::INFINITY;
    }
    let omega = (stiffness / mass).sqrt();
    let zeta = damping / (2.0 * (stiffness * mass).sqrt());
    2.0 / omega * ((1.0 + zeta * zeta).sqrt() - zeta)
}

/// The stable time step of a scene under `law`: the smallest single-contact
/// limit over every particle, for a contact with an identical particle and
/// with a wall, in the normal mode (relative mass) and the shear–rotation
/// mode (effective mass `1/m* = 1/m + r²/I` per body, rotation included).
///
/// The law's largest stiffness is used (for eq. 19 at the widest contact),
/// at overlaps up to [`DEFAULT_STABILITY_OVERLAP`] of each particle's
/// bounding radius ([`critical_time_step_at`] takes another share).
/// A particle with several contacts is stiffer than one contact: the run
/// also watches the energy and stops if it grows.
///
/// A polygon's unit of contact is a face on a face: two vertex points, each
/// with the law's stiffness, at lever arms up to the bounding radius `R`
/// from the centroid, so that a normal force turns the body too. Its modes
/// take twice the stiffness and damping of one point and the effective mass
/// `1/m* = 1/m + R²/I` in both the normal and the shear–rotation mode; the
/// largest eigenvalue of the two points' stiffness over the mass is at most
/// `2 k (1/m + R²/I)`, so this bounds the face's stable step. A law with
/// no finite stiffness at a vertex gives `dt = 0`
/// ([`crate::explicit::ExplicitDynamics::new`] refuses such a law for polygons).
pub fn critical_time_step<L: BoundedStiffness<2>>(scene: &Scene, law: &L) -> StabilityLimit {
    critical_time_step_at(scene, law, DEFAULT_STABILITY_OVERLAP)
}

/// The share of a particle's bounding radius up to which overlaps are
/// assumed when the stable step is estimated (the default of
/// [`crate::explicit::DemSettings::stability_overlap`]): 5 %, above the
/// overlaps of a well-chosen stiffness (about 1 %).
pub const DEFAULT_STABILITY_OVERLAP: f64 = 0.05;

/// [`critical_time_step`] with the law's stiffness bounded at overlaps up
/// to `overlap_ratio` of each particle's bounding radius (what a law whose
/// stiffness grows with the overlap needs; a linear law gives the same
/// limit at any ratio).
pub fn critical_time_step_at<L: BoundedStiffness<2>>(
    scene: &Scene,
    law: &L,
    overlap_ratio: f64,
) -> StabilityLimit {
    let mut best = StabilityLimit {
        dt: f64::INFINITY,
        governing: "no contact mode".into(),
    };
    for (i, p) in scene.particles.iter().enumerate() {
        // A prescribed particle does not respond: to a free one it is a
        // wall, whose mode that particle's own bound covers.
        if p.is_prescribed() {
            continue;
        }
        if let AnyShape2::Polygon(polygon) = &p.shape {
            polygon_limit(
                i,
                p.mass,
                p.inertia,
                polygon.bounding_radius(),
                law,
                overlap_ratio,
                &mut best,
            );
            continue;
        }
        let r = match &p.shape {
            AnyShape2::Circle(c) => c.radius(),
            other => other.as_shape().bounding_radius(),
        };
        // The largest radius of curvature on the outline (an ellipse's
        // flat side, a²/b), where a law's rolling spring is stiffest.
        let curvature = match &p.shape {
            AnyShape2::Ellipse(e) => e.a() * e.a() / e.b(),
            _ => r,
        };
        let shear_mass_one = 1.0 / (1.0 / p.mass + r * r / p.inertia);
        for (partner, partner_radius, partner_mass, rel_mass, rel_shear_mass) in [
            (
                "an identical particle",
                curvature,
                p.mass,
                0.5 * p.mass,
                0.5 * shear_mass_one,
            ),
            (
                "a wall",
                f64::INFINITY,
                f64::INFINITY,
                p.mass,
                shear_mass_one,
            ),
        ] {
            let pair = PairProperties {
                curvature_radius_a: curvature,
                curvature_radius_b: partner_radius,
                width: 2.0 * r,
                mass_a: p.mass,
                mass_b: partner_mass,
            };
            let bound = law.stiffness_bound(&pair, overlap_ratio * r);
            // A rolling spring turns the particle beside the shear spring:
            // at the lever r it acts as a shear spring k_r / r², whose
            // mode with the shear–rotation mass (≤ I / r²) bounds the
            // rolling mode √(k_r / I) of an identical pair or a wall.
            let shear = if bound.rolling == 0.0 {
                bound.shear
            } else {
                bound.shear + bound.rolling / (r * r)
            };
            for (mode, k, m, eta) in [
                ("normal", bound.normal, rel_mass, bound.normal_damping),
                ("shear-rotation", shear, rel_shear_mass, bound.shear_damping),
            ] {
                let dt = oscillator_limit(k, m, eta);
                if dt < best.dt {
                    best = StabilityLimit {
                        dt,
                        governing: format!(
                            "{mode} mode of particle {i} against {partner}, k = {k:.3e} N/m, m = {m:.3e} kg"
                        ),
                    };
                }
            }
        }
    }
    best
}

/// The face-on-face modes of polygon `i` (mass `m`, inertia `inertia`,
/// bounding radius `r`) against an identical polygon and a wall; lowers
/// `best` where they are stiffer.
fn polygon_limit<L: BoundedStiffness<2>>(
    i: usize,
    m: f64,
    inertia: f64,
    r: f64,
    law: &L,
    overlap_ratio: f64,
    best: &mut StabilityLimit,
) {
    let turning_mass = 1.0 / (1.0 / m + r * r / inertia);
    for (partner, partner_mass, rel_mass) in [
        ("an identical polygon", m, 0.5 * turning_mass),
        ("a wall", f64::INFINITY, turning_mass),
    ] {
        let pair = PairProperties {
            curvature_radius_a: 0.0,
            curvature_radius_b: f64::INFINITY,
            width: 0.0,
            mass_a: m,
            mass_b: partner_mass,
        };
        let bound = law.stiffness_bound(&pair, overlap_ratio * r);
        for (mode, k, eta) in [
            ("normal-rotation", bound.normal, bound.normal_damping),
            ("shear-rotation", bound.shear, bound.shear_damping),
        ] {
            let dt = if k.is_finite() && eta.is_finite() {
                oscillator_limit(2.0 * k, rel_mass, 2.0 * eta)
            } else {
                0.0
            };
            if dt < best.dt {
                *best = StabilityLimit {
                    dt,
                    governing: format!(
                        "{mode} mode of a face of polygon {i} (two points) against {partner}, k = {k:.3e} N/m per point, m* = {rel_mass:.3e} kg"
                    ),
                };
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn undamped_limit_is_two_over_omega() {
        approx::assert_relative_eq!(oscillator_limit(4.0, 1.0, 0.0), 1.0);
    }

    /// Iterate the one-step map of semi-implicit Euler with the dashpot on
    /// the old velocity and check growth just above / decay just below the
    /// limit.
    #[test]
    fn damped_limit_separates_growth_from_decay() {
        let (k, m) = (100.0f64, 1.0f64);
        let eta = 2.0 * (k * m).sqrt();
        let limit = oscillator_limit(k, m, eta);
        let run = |dt: f64| {
            let (mut x, mut v) = (1.0f64, 0.0f64);
            for _ in 0..20_000 {
                v += dt * (-k * x - eta * v) / m;
                x += dt * v;
            }
            x.abs() + v.abs() * dt
        };
        assert!(run(0.99 * limit) < 1.0);
        assert!(run(1.01 * limit) > 1.0);
    }
}
