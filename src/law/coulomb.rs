//! The Coulomb core shared by every frictional law: an elastic predictor of
//! the shear force and a radial return onto the strength `|t_s| ≤ c + μ t_n`,
//! with the consistent tangent of the return.
//!
//! With the previous shear force `t_s,old`, the shear stiffness `k_s` and the
//! shear increment `Δu_s` (one component in 2D, two in 3D):
//!
//! * trial (elastic predictor): `t* = t_s,old + k_s Δu_s`;
//! * stick when `‖t*‖ ≤ ℓ`, `ℓ = c + μ t_n`: `t_s = t*`, `∂t_s/∂Δu_s = k_s I`;
//! * slip otherwise (radial return, backward Euler, paper 003 eqs. 9–10):
//!   `t_s = ℓ t*/‖t*‖`, with the tangent
//!   `∂t_s/∂Δu_s = k_s (ℓ/‖t*‖)(I − d dᵀ)` and `∂t_s/∂Δu_n = μ k_n d`,
//!   `d = t*/‖t*‖` (`k_n = ∂t_n/∂Δu_n`); in 2D the first is zero.
//!
//! The spring–dashpot law of paper 000 ([`super::SpringDashpotCoulomb`]),
//! the penalty law of DDA (paper 003, [`super::PenaltyCoulomb`]) and the
//! slip springs of HPM (paper 001, [`super::MohrCoulombSpring`]) differ only
//! in their normal part and in what they add to the shear (dashpots); the
//! shear step is this one.

use nalgebra::{SMatrix, SVector};

use super::traits::{Regime, Strength};
use crate::error::{DismechError, Result};

/// The friction coefficient `μ = tan φ` of a friction angle φ given in
/// degrees, in `[0, 90)`: every law and material of the crate takes
/// friction as μ, and this is the one conversion from an angle.
///
/// # Errors
/// [`DismechError::InvalidParameter`] naming the angle when it is not
/// finite or lies outside `[0, 90)` degrees.
pub fn friction_from_degrees(friction_angle_deg: f64) -> Result<f64> {
    if !(friction_angle_deg.is_finite() && (0.0..90.0).contains(&friction_angle_deg)) {
        return Err(DismechError::InvalidParameter {
            name: "friction angle phi (degrees)",
            value: friction_angle_deg,
            requirement: "must lie in [0, 90)",
        });
    }
    Ok(friction_angle_deg.to_radians().tan())
}

/// The outcome of one shear step: components `1..D` of `force` hold the
/// shear force (component 0 is left at zero), `tangent` the shear rows of
/// the consistent tangent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShearStep<const D: usize> {
    /// Shear force in components `1..D` (after the return, if any).
    pub force: SVector<f64, D>,
    /// The elastic trial `t*` in components `1..D`.
    pub trial: SVector<f64, D>,
    /// Stick or slip.
    pub regime: Regime,
    /// Rows `1..D` of `∂force/∂increment`: `∂t_s/∂Δu_n` in column 0 (in
    /// slip), `∂t_s/∂Δu_s` in columns `1..D`.
    pub tangent: SMatrix<f64, D, D>,
}

/// Elastic predictor and radial return of the shear force (see the module
/// documentation).
///
/// `previous` holds the previous shear force in components `1..D`;
/// `increment` the shear increment in components `1..D`; `normal_force` is
/// the `t_n` the strength is taken at and `normal_stiffness` its derivative
/// with respect to `Δu_n` (for the coupling term of the tangent).
#[inline]
pub fn shear_step<const D: usize>(
    strength: &Strength,
    shear_stiffness: f64,
    previous: &SVector<f64, D>,
    increment: &SVector<f64, D>,
    normal_force: f64,
    normal_stiffness: f64,
) -> ShearStep<D> {
    let k_s = shear_stiffness;
    let mut trial = SVector::<f64, D>::zeros();
    let mut norm2 = 0.0;
    for i in 1..D {
        trial[i] = previous[i] + k_s * increment[i];
        norm2 += trial[i] * trial[i];
    }
    let norm = norm2.sqrt();
    let limit = strength.limit(normal_force);
    let mut force = trial;
    let mut tangent = SMatrix::<f64, D, D>::zeros();
    let regime = if norm > limit {
        // Radial return onto the limit.
        let scale = if norm > 0.0 { limit / norm } else { 0.0 };
        let direction: SVector<f64, D> = if norm > 0.0 {
            trial / norm
        } else {
            SVector::zeros()
        };
        for i in 1..D {
            force[i] *= scale;
            tangent[(i, 0)] = strength.friction * normal_stiffness * direction[i];
            for j in 1..D {
                let identity = if i == j { 1.0 } else { 0.0 };
                tangent[(i, j)] = k_s * scale * (identity - direction[i] * direction[j]);
            }
        }
        Regime::Slip
    } else {
        for i in 1..D {
            tangent[(i, i)] = k_s;
        }
        Regime::Stick
    };
    ShearStep {
        force,
        trial,
        regime,
        tangent,
    }
}

/// The shear force `t` returned onto the limit `ℓ` if it exceeds it (the
/// projection of [`shear_step`] without its tangent): the pull-back of a
/// stored force.
pub fn project_shear<const D: usize>(force: &SVector<f64, D>, limit: f64) -> SVector<f64, D> {
    let mut norm2 = 0.0;
    for i in 1..D {
        norm2 += force[i] * force[i];
    }
    let norm = norm2.sqrt();
    let mut out = *force;
    if norm > limit {
        let scale = if norm > 0.0 { limit / norm } else { 0.0 };
        for i in 1..D {
            out[i] *= scale;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Vector2, Vector3};

    const MC: Strength = Strength {
        cohesion: 2.0,
        friction: 0.5,
    };

    #[test]
    fn inside_the_cone_the_trial_is_kept_with_the_elastic_tangent() {
        let s = shear_step(
            &MC,
            5.0,
            &Vector3::zeros(),
            &Vector3::new(1.0, 0.6, 0.8),
            10.0,
            10.0,
        );
        assert_eq!(s.regime, Regime::Stick);
        assert_eq!(s.force, Vector3::new(0.0, 3.0, 4.0));
        assert_eq!(s.tangent[(1, 1)], 5.0);
        assert_eq!(s.tangent[(1, 0)], 0.0);
    }

    #[test]
    fn outside_the_cone_the_force_returns_radially_to_the_limit() {
        // Limit 2 + 0.5 · 10 = 7; trial (9, 12) has norm 15.
        let s = shear_step(
            &MC,
            5.0,
            &Vector3::zeros(),
            &Vector3::new(0.0, 1.8, 2.4),
            10.0,
            10.0,
        );
        assert_eq!(s.regime, Regime::Slip);
        assert!((s.force[1].hypot(s.force[2]) - 7.0).abs() < 1e-12);
        assert!((s.force[1] / s.force[2] - 0.75).abs() < 1e-12);
    }

    #[test]
    fn in_2d_slip_gives_the_limit_with_the_sign_of_the_trial_and_no_shear_stiffness() {
        let s = shear_step(
            &Strength {
                cohesion: 0.0,
                friction: 0.4,
            },
            3.0,
            &Vector2::new(0.0, -1.0),
            &Vector2::new(0.0, -2.0),
            5.0,
            100.0,
        );
        assert_eq!(s.regime, Regime::Slip);
        assert_eq!(s.force[1], -2.0);
        assert_eq!(s.tangent[(1, 1)], 0.0);
        assert!((s.tangent[(1, 0)] + 0.4 * 100.0).abs() < 1e-12);
    }

    #[test]
    fn projection_equals_the_return_of_the_step() {
        let trial = Vector3::new(0.0, 9.0, -12.0);
        let s = shear_step(&MC, 1.0, &trial, &Vector3::zeros(), 10.0, 1.0);
        assert_eq!(project_shear(&trial, 7.0), s.force);
    }
}
