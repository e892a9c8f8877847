//! The stable time step of the explicit scheme.

use super::driver::ContactTarget;
use crate::law::{BoundedStiffness, PairProperties};
use crate::scene::Scene;
use crate::shape::{AnyShape2, Shape2};

/// The estimated stable limit and the mode that governs it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StabilityLimit {
    /// Largest stable time step (s).
    pub dt: f64,
    /// Which contact mode governs (its [`Display`](std::fmt::Display)
    /// says it in words).
    pub governing: GoverningMode,
}

/// The contact mode whose oscillation limits the stable time step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GoverningMode {
    /// No free particle has a contact mode: the limit is infinite.
    NoContactMode,
    /// A single-contact mode of a particle that is not a polygon (a
    /// circle, an ellipse…) against an identical particle or a wall.
    Particle {
        /// The particle.
        particle: usize,
        /// The mode.
        mode: OscillationMode,
        /// What the particle is in contact with.
        partner: ModePartner,
        /// The mode's stiffness (N/m).
        stiffness: f64,
        /// The mode's relative (or effective) mass (kg).
        mass: f64,
    },
    /// A face-on-face mode of a polygon (two vertex points) against an
    /// identical polygon or a wall.
    PolygonFace {
        /// The polygon.
        polygon: usize,
        /// The mode.
        mode: OscillationMode,
        /// What the face is in contact with.
        partner: ModePartner,
        /// The law's stiffness at one of the two points (N/m).
        stiffness_per_point: f64,
        /// The effective mass `m*` of the face's mode (kg).
        mass: f64,
    },
}

/// The overlap a run reached beyond the one its time step was checked at
/// ([`crate::explicit::DemSettings::stability_overlap`]), at which the
/// stable step was estimated again
/// ([`crate::explicit::ExplicitDynamics::check_overlap_stability`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OverlapReached {
    /// The step at which it was found.
    pub step: u64,
    /// The particle with the largest overlap.
    pub particle: usize,
    /// What it overlaps.
    pub target: ContactTarget,
    /// The overlap as a share of the particle's bounding radius (of the
    /// smaller one for two particles).
    pub ratio: f64,
    /// The share the time step was checked at
    /// ([`crate::explicit::DemSettings::stability_overlap`]).
    pub stability_overlap: f64,
}

impl std::fmt::Display for OverlapReached {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the overlap reached at step {} by particle {} against {:?}, {:.3e} of its bounding radius, above stability_overlap = {:e} (the law stiffens with the overlap: lower dt, or raise stability_overlap so that the step is checked there from the start)",
            self.step, self.particle, self.target, self.ratio, self.stability_overlap
        )
    }
}

/// A mode of oscillation of one contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum OscillationMode {
    /// Along the normal, relative masses only (a particle that is not a
    /// polygon).
    Normal,
    /// Along the normal, with the turn a normal force gives a polygon's
    /// face at its lever arm.
    NormalRotation,
    /// Along the tangent, with the turn the tangential force gives.
    ShearRotation,
}

/// What the particle of a [`GoverningMode`] is in contact with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ModePartner {
    /// An identical particle (or polygon).
    Identical,
    /// A wall (an infinite mass).
    Wall,
}

impl std::fmt::Display for OscillationMode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::Normal => "normal",
            Self::NormalRotation => "normal-rotation",
            Self::ShearRotation => "shear-rotation",
        })
    }
}

impl std::fmt::Display for GoverningMode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Self::NoContactMode => f.write_str("no contact mode"),
            Self::Particle {
                particle,
                mode,
                partner,
                stiffness,
                mass,
            } => {
                let partner = match partner {
                    ModePartner::Identical => "an identical particle",
                    ModePartner::Wall => "a wall",
                };
                write!(
                    f,
                    "{mode} mode of particle {particle} against {partner}, k = {stiffness:.3e} N/m, m = {mass:.3e} kg"
                )
            }
            Self::PolygonFace {
                polygon,
                mode,
                partner,
                stiffness_per_point,
                mass,
            } => {
                let partner = match partner {
                    ModePartner::Identical => "an identical polygon",
                    ModePartner::Wall => "a wall",
                };
                write!(
                    f,
                    "{mode} mode of a face of polygon {polygon} (two points) against {partner}, k = {stiffness_per_point:.3e} N/m per point, m* = {mass:.3e} kg"
                )
            }
        }
    }
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
        governing: GoverningMode::NoContactMode,
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
                ModePartner::Identical,
                curvature,
                p.mass,
                0.5 * p.mass,
                0.5 * shear_mass_one,
            ),
            (
                ModePartner::Wall,
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
                (
                    OscillationMode::Normal,
                    bound.normal,
                    rel_mass,
                    bound.normal_damping,
                ),
                (
                    OscillationMode::ShearRotation,
                    shear,
                    rel_shear_mass,
                    bound.shear_damping,
                ),
            ] {
                let dt = oscillator_limit(k, m, eta);
                if dt < best.dt {
                    best = StabilityLimit {
                        dt,
                        governing: GoverningMode::Particle {
                            particle: i,
                            mode,
                            partner,
                            stiffness: k,
                            mass: m,
                        },
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
        (ModePartner::Identical, m, 0.5 * turning_mass),
        (ModePartner::Wall, f64::INFINITY, turning_mass),
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
            (
                OscillationMode::NormalRotation,
                bound.normal,
                bound.normal_damping,
            ),
            (
                OscillationMode::ShearRotation,
                bound.shear,
                bound.shear_damping,
            ),
        ] {
            let dt = if k.is_finite() && eta.is_finite() {
                oscillator_limit(2.0 * k, rel_mass, 2.0 * eta)
            } else {
                0.0
            };
            if dt < best.dt {
                *best = StabilityLimit {
                    dt,
                    governing: GoverningMode::PolygonFace {
                        polygon: i,
                        mode,
                        partner,
                        stiffness_per_point: k,
                        mass: rel_mass,
                    },
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
