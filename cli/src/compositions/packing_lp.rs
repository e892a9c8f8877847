//! A DEM-settled packing of ellipses analysed by the LP: the explicit
//! driver (paper 000's ellipse law) settles the packing, and the limit
//! driver takes its bodies, walls and contact manifolds as they are.
//! Paper 002 analysed regular lattices of circles and named settled
//! packings as future work; this is that analysis for non-circular
//! particles.
//!
//! The packing: ellipses of aspect ratio 2, semi-major axes spread over
//! `[a_min, a_max]` and orientations spread over `[0, π)` by low-discrepancy
//! sequences (deterministic, no seed), placed on a grid and settled under
//! gravity in an open box. The limit model: every ellipse a rigid, rolling
//! element; contacts of strength `C = 1` between elements and `2` on the
//! floor and right wall; the left wall a smooth plate pushed into the
//! packing at unit speed; no weight (a c-material, as in paper 002).

use dismech::dem::DemSimulation;
use dismech::error::Result;
use dismech::explicit::{DemSettings, RestCriterion, RunOutcome};
use dismech::integrate::ExplicitEuler;
use dismech::law::{RigidPlastic, SpringDashpotCoulomb};
use dismech::limit::{
    admissibility, analyse, model_from_packing, Admissibility, LimitModel, LimitResult,
    PackingLimitSettings,
};
use dismech::lp::LinearProgramSolver;
use dismech::math::{Point, Vec2};
use dismech::scene::{Frame, Scene};

/// The packing to settle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EllipsePacking {
    /// Number of ellipses.
    pub count: usize,
    /// Ellipses per grid row.
    pub per_row: usize,
    /// Grid pitch (m).
    pub pitch: f64,
    /// Smallest and largest semi-major axis (m); `b = a / aspect`.
    pub semi_major: (f64, f64),
    /// Aspect ratio a/b.
    pub aspect: f64,
}

impl Default for EllipsePacking {
    /// 120 ellipses of aspect ratio 2, a ∈ [0.06, 0.09] m, 8 per row on a
    /// 0.2 m grid (a box 1.6 m wide).
    fn default() -> Self {
        Self {
            count: 120,
            per_row: 8,
            pitch: 0.2,
            semi_major: (0.06, 0.09),
            aspect: 2.0,
        }
    }
}

/// Paper 000's material: E = 750 kgf/cm², ν = 0.3, k_s/k_n = 0.25,
/// μ = 0.577, ρ = 2.69 gf/cm³ (in SI), Δt = 1e-4 s.
const YOUNGS_MODULUS: f64 = 750.0 * 9.80665 / 1e-4;
const DENSITY: f64 = 2690.0;
const TIME_STEP: f64 = 1e-4;

/// The fractional part of `k φ` for the golden ratio φ, and of `k ψ` for
/// the plastic number ψ: two independent low-discrepancy sequences.
fn spread(k: usize) -> (f64, f64) {
    let golden = 0.618_033_988_749_894_9;
    let plastic = 0.754_877_666_246_692_8;
    ((k as f64 * golden).fract(), (k as f64 * plastic).fract())
}

/// Settle the packing under gravity in an open box `per_row · pitch` wide.
///
/// # Errors
/// Invalid sizes (typed errors naming the value), or a run that does not
/// come to rest (the outcome's status says so, it is not an error).
pub fn settle_ellipses(
    packing: &EllipsePacking,
) -> Result<(DemSimulation<SpringDashpotCoulomb>, RunOutcome)> {
    let width = packing.per_row as f64 * packing.pitch;
    let rows = packing.count.div_ceil(packing.per_row.max(1));
    let height = (rows as f64 + 1.0) * packing.pitch;
    let mut scene = Scene::new(Frame::open_box(width, height)?, Vec2::new(0.0, -9.80665))?;
    let (a_min, a_max) = packing.semi_major;
    for k in 0..packing.count {
        let (size, turn) = spread(k + 1);
        let a = a_min + (a_max - a_min) * size;
        let (row, col) = (k / packing.per_row, k % packing.per_row);
        let centre = Point::new(
            packing.pitch * (col as f64 + 0.5),
            packing.pitch * (row as f64 + 0.5),
        );
        scene.add_ellipse(
            centre,
            a,
            a / packing.aspect,
            std::f64::consts::PI * turn,
            DENSITY,
        )?;
    }
    let law = SpringDashpotCoulomb::katsuki(YOUNGS_MODULUS, 0.3, 0.25, 0.577)?;
    let settings = DemSettings {
        dt: TIME_STEP,
        ..DemSettings::default()
    };
    let mut sim = DemSimulation::new(scene, law, ExplicitEuler, settings)?;
    let criterion = RestCriterion {
        min_time: 0.5,
        max_time: 30.0,
        ..RestCriterion::default()
    };
    let outcome = sim.run_to_rest(&criterion, |_, _| {})?;
    Ok((sim, outcome))
}

/// The limit model of a settled packing: rolling rigid ellipses, C = 1
/// between them, 2 on the floor and right wall, a smooth left plate, no
/// weight.
///
/// # Errors
/// As [`model_from_packing`].
pub fn packing_limit_model(sim: &DemSimulation<SpringDashpotCoulomb>) -> Result<LimitModel> {
    let settings = PackingLimitSettings {
        rolling: true,
        contact_law: RigidPlastic::cohesive(1.0)?,
        wall_law: RigidPlastic::cohesive(2.0)?,
        plate_law: RigidPlastic::cohesive(0.0)?,
        plate_wall: "left".into(),
        self_weight: false,
    };
    model_from_packing(sim.scene(), sim.contacts(), &settings)
}

/// The limit analysis of a packing and how well its dual is certified.
#[derive(Debug, Clone, PartialEq)]
pub struct PackingLimit {
    /// Bodies and contact points of the limit model.
    pub size: (usize, usize),
    /// The limit model (bodies, supports, contacts), e.g. to draw the
    /// mechanism or the dual forces.
    pub model: LimitModel,
    /// The LP's result (limit load `P / C`, mechanism, dual forces).
    pub result: LimitResult,
    /// Equilibrium and strength of the dual contact forces.
    pub admissibility: Admissibility,
    /// `|primal − dual| / max(1, |primal|)`; NaN without a collapse.
    pub primal_dual_gap: f64,
}

/// Settle `packing`, build its limit model and solve it.
///
/// # Errors
/// As [`settle_ellipses`] and [`analyse`].
pub fn ellipse_packing_limit(packing: &EllipsePacking) -> Result<PackingLimit> {
    let (sim, _) = settle_ellipses(packing)?;
    let model = packing_limit_model(&sim)?;
    let result = analyse(&model, &mut LinearProgramSolver::default())?;
    let gap = match (result.kinematic_load, result.static_load) {
        (Some(primal), Some(dual)) => (primal - dual).abs() / primal.abs().max(1.0),
        _ => f64::NAN,
    };
    Ok(PackingLimit {
        size: (model.bodies().len(), model.contacts().len()),
        admissibility: admissibility(&model, &result),
        primal_dual_gap: gap,
        result,
        model,
    })
}
