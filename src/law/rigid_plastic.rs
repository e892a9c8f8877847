//! The rigid-plastic contact of limit analysis (paper 002, eqs. 13–15):
//! rigid bodies, a contact that keeps contact (or, unilaterally, may open),
//! and a shear force bounded by a strength, `|T| ≤ C + N tan φ`.

use super::traits::{Strength, StrengthLaw};
use crate::error::{require_non_negative, Result};

/// A rigid-plastic contact: cohesion `C`, friction coefficient `μ = tan φ`,
/// and whether it may open.
///
/// In a limit analysis the law gives the LP its admissible set
/// ([`StrengthLaw::strength`]) and its flow rule: slip `Ṡ` dissipates
/// `C |Ṡ|` (eq. 15); with friction the flow is associated, so slip comes
/// with dilation `|Ṡ| tan φ` and the dissipation stays `C |Ṡ|`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidPlastic {
    cohesion: f64,
    friction: f64,
    unilateral: bool,
}

impl RigidPlastic {
    /// A bilateral (never opening) cohesive contact of strength `C ≥ 0`,
    /// the contact of paper 002.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`](crate::error::DismechError::InvalidParameter) naming `contact cohesion C` for a
    /// cohesion that is negative or not finite.
    pub fn cohesive(cohesion: f64) -> Result<Self> {
        Self::coulomb(cohesion, 0.0, false)
    }

    /// A contact with cohesion `C ≥ 0`, friction coefficient `μ = tan φ ≥ 0`
    /// (the crate's convention for friction; [`Self::from_friction_angle_deg`]
    /// takes φ in degrees) and, if `unilateral`, no tension: the contact may
    /// open.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`](crate::error::DismechError::InvalidParameter) naming the value for a cohesion
    /// or a friction coefficient that is negative or not finite.
    pub fn coulomb(cohesion: f64, friction: f64, unilateral: bool) -> Result<Self> {
        require_non_negative("contact cohesion C", cohesion)?;
        require_non_negative("contact friction coefficient mu = tan(phi)", friction)?;
        Ok(Self {
            cohesion,
            friction,
            unilateral,
        })
    }

    /// [`Self::coulomb`] with the friction angle φ in degrees, in `[0, 90)`:
    /// `μ = tan φ`.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`](crate::error::DismechError::InvalidParameter) naming the value for a cohesion
    /// that is negative or not finite, or a friction angle that is not
    /// finite or outside `[0, 90)` degrees.
    pub fn from_friction_angle_deg(
        cohesion: f64,
        friction_angle_deg: f64,
        unilateral: bool,
    ) -> Result<Self> {
        Self::coulomb(
            cohesion,
            super::friction_from_degrees(friction_angle_deg)?,
            unilateral,
        )
    }

    /// Cohesion C.
    pub fn cohesion(&self) -> f64 {
        self.cohesion
    }

    /// Friction coefficient μ = tan φ.
    pub fn friction(&self) -> f64 {
        self.friction
    }

    /// Whether the contact may open.
    pub fn is_unilateral(&self) -> bool {
        self.unilateral
    }

    /// Whether the contact resists shear at all.
    pub fn resists_shear(&self) -> bool {
        self.cohesion > 0.0 || self.friction > 0.0
    }
}

/// The admissible set of eq. (13): `|T| ≤ C + N tan φ`; a unilateral
/// contact may open. A rigid-plastic contact has no force–displacement
/// relation (its forces are reactions found by the LP), so it is a
/// [`StrengthLaw`] and not a [`super::ContactLaw`]: the dynamic drivers
/// refuse it at compile time.
impl StrengthLaw for RigidPlastic {
    fn strength(&self) -> Strength {
        Strength {
            cohesion: self.cohesion,
            friction: self.friction(),
        }
    }

    fn may_open(&self) -> bool {
        self.unilateral
    }
}
