//! Material, loads and discretisation settings of an HPM slope analysis
//! (paper 001, §3–§5), validated once when built.

use crate::error::{require_non_negative, require_positive, DismechError, Result};

/// One averaged material for the whole slope (§3: "平均的な値"), and the
/// slip-surface springs and strength.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HpmMaterial {
    /// Young's modulus E of the soil (Pa).
    pub youngs_modulus: f64,
    /// Poisson's ratio ν, in [0, 0.5).
    pub poisson_ratio: f64,
    /// Cohesion c on the slip surface (Pa); c and μ may not both be 0.
    pub cohesion: f64,
    /// Friction coefficient `μ = tan φ` on the slip surface (≥ 0; the
    /// crate's convention for friction: [`crate::law::friction_from_degrees`]
    /// or [`Self::with_friction_angle_deg`] convert an angle).
    pub friction_coefficient: f64,
    /// Unit weight γ_t above the water table (N/m³); below it the soil is
    /// taken as saturated at this unit weight.
    pub unit_weight: f64,
    /// Submerged unit weight γ_sub below the water table (N/m³), at most
    /// γ_t: `γ_t − γ_sub` is the unit weight of the pore water, whose
    /// buoyancy and seepage force the elements below the table take
    /// ([`super::Element::seepage`]).
    pub submerged_unit_weight: f64,
    /// Modulus E_slip of the slip-surface springs (eq. 30), giving
    /// `k_n = (1 − ν) E_slip / ((1 + ν)(1 − 2ν) h_I)` (Pa/m).
    pub slip_modulus: f64,
    /// Shear stiffness `k_s = k_t` of the slip-surface springs (Pa/m); `None`
    /// takes `E_slip / ((1 + ν) h_I)` of eq. (30).
    pub slip_shear_stiffness: Option<f64>,
}

impl HpmMaterial {
    /// The material of the paper's §5: E = 1 GPa, ν = 0.2, c = 4.22 kN/m²,
    /// φ = 22°, γ_t = 18 kN/m³ (γ_sub = 8 kN/m³, not used by the paper's
    /// example, which has no water table), E_slip = E and k_s = 100 MPa/m.
    pub fn paper() -> Self {
        Self {
            youngs_modulus: 1.0e9,
            poisson_ratio: 0.2,
            cohesion: 4.22e3,
            friction_coefficient: 22f64.to_radians().tan(),
            unit_weight: 18.0e3,
            submerged_unit_weight: 8.0e3,
            slip_modulus: 1.0e9,
            slip_shear_stiffness: Some(100.0e6),
        }
    }

    /// Check every value; errors name the offending one. c = μ = 0 is
    /// refused: the slip surface would have no strength.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming the value for a Young's
    /// modulus, unit weight, submerged unit weight or slip-surface modulus
    /// that is not finite and positive, a submerged unit weight above the
    /// unit weight, a Poisson's ratio outside
    /// `[0, 0.5)`, a cohesion or friction coefficient that is negative or
    /// not finite, cohesion and friction both zero, or a slip shear stiffness given that is not finite and
    /// positive.
    pub fn validate(&self) -> Result<()> {
        require_positive("Young's modulus E", self.youngs_modulus)?;
        let nu = self.poisson_ratio;
        if !(nu.is_finite() && (0.0..0.5).contains(&nu)) {
            return Err(DismechError::InvalidParameter {
                name: "Poisson's ratio nu",
                value: nu,
                requirement: "must lie in [0, 0.5)",
            });
        }
        require_non_negative("cohesion c", self.cohesion)?;
        let mu = self.friction_coefficient;
        require_non_negative("friction coefficient mu = tan(phi)", mu)?;
        if self.cohesion == 0.0 && mu == 0.0 {
            return Err(DismechError::InvalidParameter {
                name: "cohesion c (with friction coefficient mu = 0)",
                value: self.cohesion,
                requirement: "c or phi must be > 0: a slip surface with neither has no strength, and its safety factor is 0 or undefined",
            });
        }
        require_positive("unit weight gamma_t", self.unit_weight)?;
        require_positive(
            "submerged unit weight gamma_sub",
            self.submerged_unit_weight,
        )?;
        require_submerged_below_total(
            "submerged unit weight gamma_sub",
            self.submerged_unit_weight,
            self.unit_weight,
        )?;
        require_positive("slip-surface modulus E_slip", self.slip_modulus)?;
        if let Some(k) = self.slip_shear_stiffness {
            require_positive("slip-surface shear stiffness k_s", k)?;
        }
        Ok(())
    }

    /// The friction coefficient μ = tan φ.
    pub fn friction(&self) -> f64 {
        self.friction_coefficient
    }

    /// This material with the friction angle φ given in degrees, in
    /// `[0, 90)` (`μ = tan φ`).
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming the angle when it is not
    /// finite or outside `[0, 90)` degrees.
    pub fn with_friction_angle_deg(self, friction_angle_deg: f64) -> Result<Self> {
        Ok(Self {
            friction_coefficient: crate::law::friction_from_degrees(friction_angle_deg)?,
            ..self
        })
    }

    /// `(1 − ν) / ((1 + ν)(1 − 2ν))` and `1 / (1 + ν)`: the factors of E'/h in
    /// `k_n` and `k_s = k_t` (eq. 16, with the errata's form of `k_n`).
    pub fn spring_factors(&self) -> (f64, f64) {
        let nu = self.poisson_ratio;
        (
            (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            1.0 / (1.0 + nu),
        )
    }
}

/// The largest seismic coefficient k_h accepted: 10 g of horizontal
/// acceleration, ten times the largest design value (1e300 made the loads
/// overflow).
pub const MAX_SEISMIC_COEFFICIENT: f64 = 10.0;

/// The static seismic load of eqs. (11)–(13): `H = k_h W` in the horizontal
/// direction `direction` (x, y), W the total weight (below a water table
/// the submerged weight and the buoyancy: [`HpmModel::loads`](super::HpmModel::loads)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Seismic {
    /// Design horizontal seismic coefficient k_h, in `[0, MAX_SEISMIC_COEFFICIENT]`.
    pub coefficient: f64,
    /// Horizontal direction of the force `(x, y)`: any finite vector of
    /// non-zero length (it is normalised), e.g. `(0.0, -1.0)` towards −y,
    /// as every plan direction of HPM.
    pub direction: (f64, f64),
}

impl Seismic {
    /// No seismic load.
    pub fn none() -> Self {
        Self {
            coefficient: 0.0,
            direction: (1.0, 0.0),
        }
    }

    /// Check the values.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for a coefficient that is negative,
    /// not finite or above [`MAX_SEISMIC_COEFFICIENT`], or a direction that
    /// is not finite or has zero length.
    pub fn validate(&self) -> Result<()> {
        require_non_negative("seismic coefficient k_h", self.coefficient)?;
        if self.coefficient > MAX_SEISMIC_COEFFICIENT {
            return Err(DismechError::InvalidParameter {
                name: "seismic coefficient k_h",
                value: self.coefficient,
                requirement: "must be at most 10 (a horizontal acceleration of 10 g; design values lie below 1)",
            });
        }
        horizontal_unit("seismic direction (length)", self.direction)?;
        Ok(())
    }

    /// Unit horizontal vector of the force (the direction normalised; a
    /// direction that [`Self::validate`] refuses gives NaN).
    pub fn unit(&self) -> (f64, f64) {
        let (x, y) = self.direction;
        let n = x.hypot(y);
        (x / n, y / n)
    }
}

/// `direction` normalised: the unit horizontal vector `(x, y)`.
///
/// # Errors
/// [`DismechError::InvalidParameter`] named `name`, with the length as its
/// value, for a direction that is not finite or has zero length.
pub(super) fn horizontal_unit(name: &'static str, direction: (f64, f64)) -> Result<(f64, f64)> {
    let (x, y) = direction;
    let n = x.hypot(y);
    if !(n.is_finite() && n > 0.0) {
        return Err(DismechError::InvalidParameter {
            name,
            value: n,
            requirement: "must be a finite horizontal direction (x, y) of non-zero length",
        });
    }
    Ok((x / n, y / n))
}

/// How the columns are discretised, and the memory the model may take.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HpmSettings {
    /// Layers per column of equal thickness: bottom, middle and top, so at
    /// least 3 (§3, Fig. 7).
    pub layers: usize,
    /// Penalty factor p of eq. (17), `E' = p E` for the springs between
    /// elements.
    pub penalty: f64,
    /// The most memory (bytes) the model and its linear solver may take,
    /// as [`HpmModel::memory_estimate`](super::HpmModel::memory_estimate)
    /// and the solver's part count it (for the sparse Cholesky of
    /// [`HpmSolver::new`](super::HpmSolver::new) the factor's fill, from
    /// the symbolic analysis; for the conjugate gradients of
    /// [`HpmSolver::iterative`](super::HpmSolver::iterative) the column
    /// blocks). Checked before each part is allocated; a model over it is
    /// refused with
    /// [`HpmError::HpmModelTooLarge`](crate::hpm::HpmError::HpmModelTooLarge).
    ///
    /// `None` (the default) asks the system: the bytes are requested from
    /// the allocator and given back at once, so that a model larger than
    /// the machine can hold is refused rather than aborted. Linux, with its
    /// default overcommit heuristic, refuses a request larger than its
    /// memory and swap together, whatever is in use; a system that
    /// overcommits without limit refuses only what the address space
    /// cannot hold, so set a budget there (or wherever other work shares
    /// the machine). A budget is compared with the estimate and nothing is
    /// asked of the system.
    pub memory_budget: Option<u64>,
}

impl Default for HpmSettings {
    /// Three layers, p = 100 and no memory budget (the system is asked).
    fn default() -> Self {
        Self {
            layers: 3,
            penalty: 100.0,
            memory_budget: None,
        }
    }
}

impl HpmSettings {
    /// Check the values (any memory budget is valid: one too small for the
    /// model refuses it when it is built).
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for fewer than 3 layers or a
    /// penalty factor that is not finite and positive.
    pub fn validate(&self) -> Result<()> {
        if self.layers < 3 {
            return Err(DismechError::InvalidParameter {
                name: "layers per column",
                value: self.layers as f64,
                requirement: "must be >= 3 (bottom, at least one middle, top)",
            });
        }
        require_positive("penalty factor p", self.penalty)?;
        Ok(())
    }
}

/// Refuse a submerged unit weight above the total one: `γ_t − γ_sub` is
/// the pore water's unit weight, and a negative one would make the
/// buoyancy a downward force and the seepage force point up the water
/// table's slope.
pub(super) fn require_submerged_below_total(
    name: &'static str,
    submerged: f64,
    total: f64,
) -> Result<()> {
    if submerged > total {
        return Err(DismechError::InvalidParameter {
            name,
            value: submerged,
            requirement: "must not exceed the unit weight gamma_t (gamma_t - gamma_sub is the pore water's unit weight)",
        });
    }
    Ok(())
}
