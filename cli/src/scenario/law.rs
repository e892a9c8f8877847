//! `[law]`: the contact law and its parameters.

use serde::Deserialize;

/// The contact law (`kind` = `katsuki`, `spring-dashpot-coulomb`,
/// `penalty-coulomb`, `rigid-plastic` or `hpm`).
#[derive(Debug, Clone, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LawSpec {
    /// Paper 000's spring–dashpot–Coulomb law ([`dismech::law::SpringDashpotCoulomb::katsuki`]).
    Katsuki(KatsukiSpec),
    /// A spring–dashpot–Coulomb law with a constant normal stiffness.
    SpringDashpotCoulomb(SpringDashpotSpec),
    /// The penalty Coulomb law of DDA ([`dismech::law::PenaltyCoulomb`]).
    PenaltyCoulomb(PenaltySpec),
    /// A rigid-plastic strength for limit analysis ([`dismech::law::RigidPlastic`]).
    RigidPlastic(RigidPlasticSpec),
    /// The soil and slip surface of the HPM ([`dismech::hpm::HpmMaterial`]).
    Hpm(HpmLawSpec),
}

impl LawSpec {
    /// The `kind` as written.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Katsuki(_) => "katsuki",
            Self::SpringDashpotCoulomb(_) => "spring-dashpot-coulomb",
            Self::PenaltyCoulomb(_) => "penalty-coulomb",
            Self::RigidPlastic(_) => "rigid-plastic",
            Self::Hpm(_) => "hpm",
        }
    }
}

/// One entry of `[[pair_laws]]` (implicit driver): the law of the
/// contacts between bodies of two groups (the bodies' `group` keys), in
/// place of `[law]`'s ([`dismech::implicit::ContactLaws::with_pair`]).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PairLawSpec {
    /// The two groups, in either order (twice the same group: the
    /// contacts inside it).
    #[serde(deserialize_with = "super::exact::array")]
    pub groups: [usize; 2],
    /// The law, its keys as `[law]`'s and of the same kind.
    pub law: LawSpec,
}

/// Paper 000's law: `k_n` from the contact width (eq. 19), critical
/// dashpots.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KatsukiSpec {
    /// Young's modulus E (Pa).
    pub youngs_modulus: f64,
    /// Poisson's ratio ν, in [−1, 0.5).
    pub poisson_ratio: f64,
    /// s = k_s / k_n.
    pub stiffness_ratio: f64,
    /// Friction coefficient μ = tan φ (or `friction_angle`).
    pub friction: Option<f64>,
    /// Friction angle φ (degrees), in [0, 90) (or `friction`).
    pub friction_angle: Option<f64>,
}

/// A spring–dashpot–Coulomb law with a constant `k_n`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringDashpotSpec {
    /// Normal stiffness k_n (N/m per m of thickness).
    pub normal_stiffness: f64,
    /// s = k_s / k_n.
    pub stiffness_ratio: f64,
    /// Friction coefficient μ (or `friction_angle`).
    pub friction: Option<f64>,
    /// Friction angle φ (degrees) (or `friction`).
    pub friction_angle: Option<f64>,
    /// `critical` (the default) or `none`.
    pub damping: Option<DampingSpec>,
}

/// Dashpots of a spring–dashpot law.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DampingSpec {
    /// η_n = 2√(m k_n), η_s = η_n √s.
    Critical,
    /// No dashpots.
    None,
}

/// The penalty Coulomb law.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PenaltySpec {
    /// Penalty (normal and shear) stiffness (N/m per m).
    pub penalty: f64,
    /// Friction coefficient μ (or `friction_angle`).
    pub friction: Option<f64>,
    /// Friction angle φ (degrees) (or `friction`).
    pub friction_angle: Option<f64>,
    /// `return-mapping` (the default) or `conventional`.
    pub integration: Option<IntegrationSpec>,
    /// Cohesion of a bonded contact (N/m); none by default.
    pub cohesion: Option<f64>,
}

/// [`dismech::law::FrictionIntegration`].
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum IntegrationSpec {
    /// Elastic predictor, return mapping.
    ReturnMapping,
    /// Classic DDA's treatment.
    Conventional,
}

/// A rigid-plastic strength.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RigidPlasticSpec {
    /// Cohesion c (N/m).
    pub cohesion: f64,
    /// Friction coefficient μ (or `friction_angle`); 0 by default.
    pub friction: Option<f64>,
    /// Friction angle φ (degrees) (or `friction`).
    pub friction_angle: Option<f64>,
    /// No tension: the contact may open (false by default).
    pub unilateral: Option<bool>,
}

/// The soil and the slip surface of the HPM.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HpmLawSpec {
    /// Young's modulus E of the soil (Pa).
    pub youngs_modulus: f64,
    /// Poisson's ratio ν, in [0, 0.5).
    pub poisson_ratio: f64,
    /// Cohesion c on the slip surface (Pa).
    pub cohesion: f64,
    /// Friction coefficient μ = tan φ on the slip surface (or
    /// `friction_angle`).
    pub friction: Option<f64>,
    /// Friction angle φ (degrees) (or `friction`).
    pub friction_angle: Option<f64>,
    /// Unit weight γ_t above the water table (N/m³).
    pub unit_weight: f64,
    /// Submerged unit weight γ_sub below the water table (N/m³); γ_t by
    /// default.
    pub submerged_unit_weight: Option<f64>,
    /// Modulus E_slip of the slip-surface springs (Pa); E by default.
    pub slip_modulus: Option<f64>,
    /// Shear stiffness of the slip-surface springs (Pa/m); eq. (30) by
    /// default.
    pub slip_shear_stiffness: Option<f64>,
}
