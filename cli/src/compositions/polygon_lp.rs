//! A rigid rectangle on a frictional floor in the limit analysis: a
//! polygon body, contacts at the two points of its face-on-floor manifold,
//! and a live load whose multiplier the LP finds, against the closed form
//! of [`dismech::reference::block_on_floor`].
//!
//! The block is a [`Polygon`] (a body of the limit driver like any other
//! shape), its weight a known load at the centroid; the floor a fixed
//! [`dismech::limit::Support`]; the contacts unilateral Coulomb contacts
//! without cohesion ([`RigidPlastic::coulomb`]`(0, μ, true)`, associated flow)
//! at the two bottom corners; the live load a unit horizontal force at the
//! middle of the top face. The LP's minimum is the multiplier of that load
//! at collapse: `W w/(2h)` when the block rocks about its leading corner
//! (`μ > w/2h`) and `μ W` when it slides (`μ < w/2h`).

use dismech::error::{require_positive, DismechError, Result};
use dismech::law::RigidPlastic;
use dismech::limit::{admissibility, analyse, Admissibility, LimitModel, LimitResult, Partner};
use dismech::lp::LinearProgramSolver;
use dismech::math::{Point, Pose2, Vec2};
use dismech::reference::{BlockMechanism, BlockOnFloor};
use dismech::shape::Polygon;

/// The block of the tipping case: 0.4 m wide, 0.8 m high (`w/2h = 0.25`),
/// weight 1 kN/m, on a floor with φ = 30° (`μ = 0.577 > 0.25`).
pub fn tipping_block() -> BlockOnFloor {
    BlockOnFloor {
        width: 0.4,
        height: 0.8,
        weight: 1e3,
        friction: 30f64.to_radians().tan(),
    }
}

/// The block of the sliding case: [`tipping_block`] on a floor with φ = 10°
/// (`μ = 0.176 < 0.25`).
pub fn sliding_block() -> BlockOnFloor {
    BlockOnFloor {
        friction: 10f64.to_radians().tan(),
        ..tipping_block()
    }
}

/// The limit model of `block`: the rectangle centred at `(0, h/2)` with its
/// weight, the floor `y = 0`, a contact at each bottom corner and the unit
/// horizontal live load (+x) at the middle of the top face.
///
/// # Errors
/// [`DismechError::InvalidParameter`] for a size or weight that is not
/// finite and positive, or a friction coefficient that is negative or not
/// finite; the limit model's own errors.
pub fn block_limit_model(block: &BlockOnFloor) -> Result<LimitModel> {
    let (w, h) = (
        require_positive("block width", block.width)?,
        require_positive("block height", block.height)?,
    );
    require_positive("block weight", block.weight)?;
    if !(block.friction.is_finite() && block.friction >= 0.0) {
        return Err(DismechError::InvalidParameter {
            name: "friction coefficient mu",
            value: block.friction,
            requirement: "must be finite and >= 0",
        });
    }
    let law = RigidPlastic::coulomb(0.0, block.friction, true)?;
    let mut model = LimitModel::new(1e-9 * w.max(h))?;
    let body = model.add_shape(
        Polygon::rectangle(w, h)?.into(),
        Pose2::new(0.0, 0.5 * h, 0.0),
        true,
    )?;
    model.set_load(body, Vec2::new(0.0, -block.weight))?;
    let floor = model.add_support("floor", Point::origin(), Vec2::y(), Vec2::zeros())?;
    for x in [-0.5 * w, 0.5 * w] {
        model.add_contact_at(
            body,
            Partner::Support(floor),
            law,
            Point::new(x, 0.0),
            -Vec2::y(),
        )?;
    }
    model.set_live_load(body, Vec2::x(), Point::new(0.0, h))?;
    Ok(model)
}

/// The limit analysis of a block and the closed form it is checked against.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockLimit {
    /// The block.
    pub block: BlockOnFloor,
    /// The LP's result; `load` is the multiplier of the unit live load, the
    /// horizontal force (N/m) at collapse.
    pub result: LimitResult,
    /// Equilibrium and strength of the dual contact forces.
    pub admissibility: Admissibility,
    /// The closed form `W min(μ, w/2h)` (N/m).
    pub exact: f64,
    /// The mechanism the closed form predicts.
    pub mechanism: BlockMechanism,
    /// The LP's limit load over the closed form (NaN without a collapse).
    pub ratio: f64,
}

/// Solve the limit analysis of `block`.
///
/// # Errors
/// As [`block_limit_model`] and [`analyse`].
pub fn block_limit(block: &BlockOnFloor) -> Result<BlockLimit> {
    let model = block_limit_model(block)?;
    let result = analyse(&model, &mut LinearProgramSolver::default())?;
    let exact = block.limit_load();
    Ok(BlockLimit {
        block: *block,
        admissibility: admissibility(&model, &result),
        ratio: result.load.map_or(f64::NAN, |p| p / exact),
        exact,
        mechanism: block.mechanism(),
        result,
    })
}

/// The LP limit load of [`tipping_block`] over `W w/(2h)` (the check
/// `polygon_lp.tipping_ratio`).
///
/// # Errors
/// As [`block_limit`].
pub fn tipping_ratio() -> Result<f64> {
    let block = tipping_block();
    let limit = block_limit(&block)?;
    Ok(limit
        .result
        .load
        .map_or(f64::NAN, |p| p / block.tipping_load()))
}

/// The LP limit load of [`sliding_block`] over `μ W` (the check
/// `polygon_lp.sliding_ratio`).
///
/// # Errors
/// As [`block_limit`].
pub fn sliding_ratio() -> Result<f64> {
    let block = sliding_block();
    let limit = block_limit(&block)?;
    Ok(limit
        .result
        .load
        .map_or(f64::NAN, |p| p / block.sliding_load()))
}
