//! `[loads]`: gravity, forces on bodies, tractions on polygon edges, a
//! seismic coefficient, a live load.

use serde::Deserialize;

/// The loads.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadsSpec {
    /// Gravitational acceleration (m/s²); [0, -9.81] by default.
    #[serde(default, deserialize_with = "super::exact::optional")]
    pub gravity: Option<[f64; 2]>,
    /// Constant forces at bodies' centres (explicit driver).
    #[serde(default)]
    pub forces: Vec<ForceSpec>,
    /// Uniform tractions on polygon edges (implicit driver).
    #[serde(default)]
    pub tractions: Vec<TractionSpec>,
    /// A horizontal seismic coefficient (HPM driver).
    pub seismic: Option<SeismicSpec>,
    /// The live load whose multiplier at collapse the limit driver finds.
    pub live: Option<LiveLoadSpec>,
}

/// A reference force on a body whose multiplier λ at collapse the limit
/// driver finds ([`dismech::limit::LimitModel::set_live_load`]).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LiveLoadSpec {
    /// Index of the body, counted over the `[[bodies]]` that are not walls.
    pub body: usize,
    /// Reference force (N per m of thickness).
    #[serde(deserialize_with = "super::exact::array")]
    pub force: [f64; 2],
    /// Point of application (m); the body's centre by default.
    #[serde(default, deserialize_with = "super::exact::optional")]
    pub point: Option<[f64; 2]>,
}

/// A horizontal seismic load `k_h W` ([`dismech::hpm::Seismic`]).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SeismicSpec {
    /// The seismic coefficient k_h.
    pub coefficient: f64,
    /// The horizontal direction of the force (x, y), normalised.
    #[serde(deserialize_with = "super::exact::array")]
    pub direction: [f64; 2],
}

/// A constant force at a body's centre.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForceSpec {
    /// Index of the body, counted over the bodies as built.
    pub body: usize,
    /// Force (N per m of thickness).
    #[serde(deserialize_with = "super::exact::array")]
    pub force: [f64; 2],
}

/// A uniform traction on one edge of a polygon body.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TractionSpec {
    /// Index of the body, counted over the bodies as built.
    pub body: usize,
    /// Edge k runs from vertex k to vertex k + 1.
    pub edge: usize,
    /// Traction (Pa), in world axes.
    #[serde(deserialize_with = "super::exact::array")]
    pub traction: [f64; 2],
}
