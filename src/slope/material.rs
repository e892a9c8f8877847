//! Strength and unit weight of the ground, and the loads of a search:
//! pore water and the seismic coefficient.

use crate::error::{require_non_negative, require_positive, DismechError, Result};
use crate::hpm::MAX_SEISMIC_COEFFICIENT;

/// One material for the whole terrain: Mohr–Coulomb strength on the slip
/// surface and the unit weight of the ground above it (a one-layer
/// [`super::Ground`]; layers of several materials are [`super::Layer`]s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlopeMaterial {
    /// Effective cohesion c (Pa).
    pub cohesion: f64,
    /// Friction coefficient `μ = tan φ` (≥ 0; the crate's convention,
    /// [`crate::law::friction_from_degrees`] converts an angle).
    pub friction_coefficient: f64,
    /// Total unit weight γ of the ground, above and below the water table
    /// alike (N/m³); pore water enters through the pore pressure on the
    /// base ([`SlopeLoads::water_unit_weight`]).
    pub unit_weight: f64,
}

impl SlopeMaterial {
    /// Check the values.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming the value for a cohesion or
    /// friction coefficient that is negative or not finite, both zero (no
    /// strength), or a unit weight that is not finite and positive.
    pub fn validate(&self) -> Result<()> {
        require_non_negative("cohesion c", self.cohesion)?;
        require_non_negative(
            "friction coefficient mu = tan(phi)",
            self.friction_coefficient,
        )?;
        if self.cohesion == 0.0 && self.friction_coefficient == 0.0 {
            return Err(DismechError::InvalidParameter {
                name: "cohesion c (with friction coefficient mu = 0)",
                value: self.cohesion,
                requirement: "c or phi must be > 0: a slip surface with neither has no strength",
            });
        }
        require_positive("unit weight gamma", self.unit_weight)?;
        Ok(())
    }
}

/// The unit weight of water, 9810 N/m³ (ρ_w g with g = 9.81 m/s²).
pub const WATER_UNIT_WEIGHT: f64 = 9810.0;

/// Loads on every trial surface: pore water (through the terrain's water
/// table) and the pseudo-static seismic force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlopeLoads {
    /// Horizontal seismic coefficient k_h, in
    /// `[0, `[`MAX_SEISMIC_COEFFICIENT`]`]`: each column carries `k_h W`
    /// horizontally along the surface's sliding direction (Hovland 1977;
    /// eqs. 11–13 of paper 001).
    pub seismic_coefficient: f64,
    /// Unit weight of pore water γ_w (N/m³): the pore pressure on a base is
    /// `u = γ_w h_p`, with `h_p` the height of the water table (lowered to
    /// the ground where it lies above it) over the base.
    pub water_unit_weight: f64,
}

impl Default for SlopeLoads {
    /// No seismic load; γ_w = [`WATER_UNIT_WEIGHT`].
    fn default() -> Self {
        Self {
            seismic_coefficient: 0.0,
            water_unit_weight: WATER_UNIT_WEIGHT,
        }
    }
}

impl SlopeLoads {
    /// Check the values.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming the value for a seismic
    /// coefficient that is negative, not finite or above
    /// [`MAX_SEISMIC_COEFFICIENT`], or a unit weight of water that is not
    /// finite and positive.
    pub fn validate(&self) -> Result<()> {
        require_non_negative("seismic coefficient k_h", self.seismic_coefficient)?;
        if self.seismic_coefficient > MAX_SEISMIC_COEFFICIENT {
            return Err(DismechError::InvalidParameter {
                name: "seismic coefficient k_h",
                value: self.seismic_coefficient,
                requirement: "must be at most 10 (a horizontal acceleration of 10 g; design values lie below 1)",
            });
        }
        require_positive("unit weight of water gamma_w", self.water_unit_weight)?;
        Ok(())
    }
}
