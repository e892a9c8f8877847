//! Cross-compositions: models that combine the slots in ways the four
//! papers do not, each a short constructor over the library's drivers and a
//! function that measures what an exact solution or a second method
//! predicts. The `compositions` study and the tests call the same
//! functions.
//!
//! | composition | drivers and pieces | checked against |
//! |---|---|---|
//! | [`polygon_incline`]: a rigid rectangle on an incline | [`dismech::shape::Polygon`], [`dismech::query::manifold::dispatch::contact_manifold_2d`] (polygon–wall, two points), [`dismech::law::SpringDashpotCoulomb`] with a constant `k_n`, [`dismech::dem::DemSimulation`] | sliding at `g (sin β − μ cos β)`, or at rest for `tan β ≤ μ` |
//! | [`polygon_lp`]: a rigid rectangle on a frictional floor pushed at its top | [`dismech::shape::Polygon`] in the limit driver ([`dismech::limit::LimitModel::add_shape`]), contacts at the two corners of the face-on-floor manifold ([`dismech::limit::LimitModel::add_contact_at`], [`dismech::law::RigidPlastic`] unilateral, c = 0), a live load ([`dismech::limit::LimitModel::set_live_load`]), Clarabel | [`dismech::reference::block_on_floor`]: `W w/(2h)` (tipping) or `μ W` (sliding), to 1e-6 |
//! | [`packing_lp`]: a DEM-settled packing of ellipses | explicit DEM of ellipses → limit analysis ([`dismech::limit::model_from_packing`], Clarabel) | equilibrium of the dual, primal = dual |
//! | [`block_wall`]: a running-bond wall of 39 blocks at rest on a base | the polygon DEM (rigid blocks, [`dismech::law::SpringDashpotCoulomb`], `k_s = k_n`) and the DDA ([`dismech::dda::DdaModel`], deformable blocks, [`dismech::law::PenaltyCoulomb`] with return mapping, static steps), same contact points and stiffness per point | each other: the base carries the weight in both; the bottom course's shares differ in proportion to `k/E` (the DDA blocks' strain) |
//!
//! A composition is a set-up struct with a [`Default`] (the study's size),
//! a function that builds and solves it, and small functions returning the
//! checked quantities (e.g. [`polygon_lp::tipping_ratio`]); the study adds
//! one function that reports them, the tests assert them.

pub mod affine_disc;
pub mod block_wall;
pub mod implicit_ellipses;
pub mod packing_lp;
pub mod penalty_vs_lp;
pub mod polygon_incline;
pub mod polygon_lp;

use dismech::error::{require_positive, DismechError, Result};

/// The checks of a run on an incline: a slope angle in (0, 90°) (rad), a
/// positive settling time and a duration beyond it.
fn require_incline_run(slope: f64, settling_time: f64, duration: f64) -> Result<()> {
    if !(slope.is_finite() && slope > 0.0 && slope < std::f64::consts::FRAC_PI_2) {
        return Err(DismechError::InvalidParameter {
            name: "slope angle",
            value: slope,
            requirement: "must lie in (0, 90°) (radians)",
        });
    }
    require_positive("settling time", settling_time)?;
    require_positive("duration", duration)?;
    if duration <= settling_time {
        return Err(DismechError::InvalidParameter {
            name: "duration",
            value: duration,
            requirement: "must exceed the settling time",
        });
    }
    Ok(())
}
