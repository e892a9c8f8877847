//! `[driver]`: which driver runs the model, and its settings.

use serde::Deserialize;

/// The driver and its settings (`kind` = `explicit`, `implicit` or
/// `limit`, `hpm`).
#[derive(Debug, Clone, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DriverSpec {
    /// Explicit dynamics (DEM): [`dismech::explicit::ExplicitDynamics`].
    Explicit(ExplicitSpec),
    /// Implicit dynamics (DDA and its kin): [`dismech::implicit::ImplicitDynamics`].
    Implicit(ImplicitSpec),
    /// Rigid-plastic limit analysis by LP: [`dismech::limit::analyse`].
    Limit(LimitSpec),
    /// The hybrid penalty method on grid columns (paper 001):
    /// [`dismech::hpm::HpmSolver::elastic`] (and
    /// [`dismech::hpm::HpmSolver::nonlinear`]).
    Hpm(HpmSpec),
}

impl DriverSpec {
    /// The `kind` as written.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Explicit(_) => "explicit",
            Self::Implicit(_) => "implicit",
            Self::Limit(_) => "limit",
            Self::Hpm(_) => "hpm",
        }
    }
}

/// Settings of the explicit driver ([`dismech::explicit::DemSettings`]).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExplicitSpec {
    /// Time step Δt (s).
    pub dt: f64,
    /// Largest overlap accepted at the start (m); 1e-6 by default.
    pub initial_overlap_tolerance: Option<f64>,
    /// Overlap share up to which the stable step is estimated, in (0, 1].
    pub stability_overlap: Option<f64>,
    /// Refuse a time step above the stable limit (true by default).
    pub check_stability: Option<bool>,
    /// Skin of the neighbour list (m); tuned by the driver when absent.
    pub neighbour_skin: Option<f64>,
    /// Keep the neighbour list while the particles move together.
    pub relative_travel: Option<bool>,
}

/// Settings of the implicit driver ([`dismech::implicit::ImplicitSettings`]).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImplicitSpec {
    /// The step requested of each call of `advance` (s).
    pub dt: f64,
    /// Search distance d₀ of contact detection (m).
    pub search_distance: Option<f64>,
    /// Largest search distance a step may use (m).
    pub max_search_distance: Option<f64>,
    /// Largest penetration accepted at the start (m).
    pub overlap_tolerance: Option<f64>,
    /// Most open–close iterations per step.
    pub max_open_close: Option<usize>,
    /// Most Newton iterations per step.
    pub max_newton: Option<usize>,
    /// Relative residual tolerance of Newton.
    pub residual_tolerance: Option<f64>,
    /// Smallest step as a fraction of the requested one.
    pub min_dt_ratio: Option<f64>,
    /// Where each step's iteration starts.
    pub predictor: Option<PredictorSpec>,
    /// Share of a slipping contact's normal stiffness added to its shear
    /// stiffness in Newton's matrix.
    pub slip_regularization: Option<f64>,
    /// The quantile of the stick points at which an update stops.
    pub slip_reversal_quantile: Option<f64>,
    /// Mass-proportional damping α (1/s).
    pub mass_damping: Option<f64>,
}

/// [`dismech::implicit::Predictor`].
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PredictorSpec {
    /// Constant acceleration for free bodies, start of step for the others.
    FreeFlight,
    /// Constant acceleration for every body.
    ConstantAcceleration,
    /// The start-of-step configuration.
    StartOfStep,
}

/// Settings of the limit analysis.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LimitSpec {
    /// Distance within which outlines touch (m), bodies of shapes only;
    /// 1e-9 by default.
    pub contact_tolerance: Option<f64>,
    /// Seek the factor on the dead loads (self-weight and `loads.forces`)
    /// at collapse instead of a live load's multiplier (false by default).
    pub multiply_dead_loads: Option<bool>,
}

/// Settings of the HPM ([`dismech::hpm::HpmSettings`]).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HpmSpec {
    /// Layers per column (≥ 3); 3 by default.
    pub layers: Option<usize>,
    /// Penalty factor p between elements; 100 by default.
    pub penalty: Option<f64>,
    /// Run the nonlinear analysis too
    /// ([`dismech::hpm::HpmSolver::nonlinear`]); false by default.
    pub nonlinear: Option<bool>,
    /// The nonlinear analysis' relative out-of-balance force accepted as
    /// equilibrium ([`dismech::hpm::NonlinearSettings::tolerance`]).
    pub tolerance: Option<f64>,
    /// The nonlinear analysis' iteration limit
    /// ([`dismech::hpm::NonlinearSettings::max_iterations`]).
    pub max_iterations: Option<usize>,
}
