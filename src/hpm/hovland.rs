//! Hovland's 3D column method (1977) on the same grid data: the simplified
//! method HPM is meant to match (paper 001, §1, its ref. 1).
//!
//! Each column is a rigid prism whose base is the slip surface at the cell
//! centre (the bilinear surface of eq. 23 and its slopes there), with the
//! column's weight W (the sum of the HPM element weights, eqs. 5–10),
//! the seismic force `k_h W` of eqs. (11)–(13) (on the total weight below
//! a water table, W and the buoyancy, as in [`HpmModel::loads`]) and the
//! seepage force below a water table (the sum of the elements',
//! [`super::Element::seepage`]); forces between columns are neglected. A
//! pore pressure `u` on the slip surface
//! ([`HpmModel::set_column_pore_pressure`]) lowers `N` to `N − u A`.
//! With `w` the column's load vector, `n` the base normal pointing into
//! the ground and `d` the unit vector along the base in the
//! sliding direction (the horizontal direction given, lifted onto the base):
//! `N = w · n`, `T = w · d`, `A` the true base area and
//! `Fs = Σ (c A + N tan φ) / Σ T`.
//!
//! The Fs is a ratio of resisting to driving forces: it is given only where
//! the columns' loads drive the slide along the direction asked,
//! `Σ T > `[`MIN_DRIVING_RATIO`](super::analysis::MIN_DRIVING_RATIO)` × Σ W`.
//! On a level slip surface without seismic load or seepage force `Σ T` is
//! zero (the Fs would be infinite, or a huge number
//! of either sign from rounding), and towards a direction up the slope it
//! is negative (a negative Fs means nothing): both are refused with
//! [`HpmError::NothingDrivesSliding`](super::HpmError::NothingDrivesSliding),
//! naming `Σ T` and `Σ W`.
//!
//! A column whose load pulls it off its base (`N < 0`, a seismic force
//! that outweighs the weight's normal part, or a pore pressure `u A` above
//! it: with r_u, where `r_u > cos² θ` on a base of true dip θ) has a
//! strength `c A + N tan φ` that falls below zero beyond
//! `N = −c A / tan φ`: `N` is the equilibrium's, not floored at zero as
//! the slope search's Hovland floors `N − u A` ([`crate::slope`]), so
//! there the two differ. Where the columns'
//! strengths sum to zero or less, the Fs would be zero or negative, which
//! is no factor of safety, and is refused with
//! [`HpmError::SlipSurfaceInTension`](super::HpmError::SlipSurfaceInTension),
//! naming those columns and their share of the base area.

use nalgebra::Vector3;

use super::analysis::{
    resisting_over_driving, DrivingForce, SafetyFactorKind, SafetyFactorTerm, Tension,
};
use super::material::{horizontal_unit, Seismic};
use super::model::{cell_slope, HpmModel};
use crate::error::Result;

/// One column's terms in Hovland's sums.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HovlandColumn {
    /// Base normal force N (N), less the pore pressure's `u A` where the
    /// model has one ([`HpmModel::set_column_pore_pressure`]).
    pub normal: f64,
    /// Driving force T along the sliding direction (N).
    pub driving: f64,
    /// Base area A (m²).
    pub area: f64,
}

/// Hovland's safety factor and the column terms.
#[derive(Debug, Clone, PartialEq)]
pub struct Hovland {
    /// `Σ (c A + N tan φ) / Σ T`.
    pub safety_factor: f64,
    /// Terms, in the order of [`HpmModel::columns`].
    pub columns: Vec<HovlandColumn>,
}

/// Hovland's method for the columns of `model`, sliding horizontally
/// towards `towards`, a horizontal direction `(x, y)` of any non-zero
/// length (e.g. `(0.0, -1.0)` towards −y), as every plan direction of HPM.
///
/// # Errors
/// An invalid seismic load ([`Seismic::validate`]) or a direction that is
/// not finite or has zero length ([`DismechError::InvalidParameter`](crate::error::DismechError::InvalidParameter));
/// [`HpmError::NothingDrivesSliding`](super::HpmError::NothingDrivesSliding)
/// when the driving force `Σ T` is not above
/// [`MIN_DRIVING_RATIO`](super::analysis::MIN_DRIVING_RATIO) of the columns'
/// weight `Σ W`: level ground, or a direction up the slope;
/// [`HpmError::SlipSurfaceInTension`](super::HpmError::SlipSurfaceInTension)
/// when the strength `Σ (c A + N tan φ)` is not positive: columns pulled
/// off their base beyond `c A / tan φ` (a large seismic coefficient).
pub fn hovland(model: &HpmModel, seismic: &Seismic, towards: (f64, f64)) -> Result<Hovland> {
    seismic.validate()?;
    let (dx, dy) = horizontal_unit("sliding direction (length)", towards)?;
    let (sx, sy) = seismic.unit();
    let strengths = model.column_strengths();
    let pressures = model.column_pore_pressures();
    let d = model.grid.2;
    let columns: Vec<HovlandColumn> = model
        .columns
        .iter()
        .zip(&pressures)
        .map(|(column, &pressure)| {
            let z = column.shape.bottom();
            let (zx, zy) = cell_slope(&z, d);
            let elements = &model.elements[column.elements.clone()];
            let weight: f64 = elements.iter().map(|e| e.weight).sum();
            let total: f64 = elements.iter().map(|e| e.weight + e.buoyancy).sum();
            let seepage_x: f64 = elements.iter().map(|e| e.seepage[0]).sum();
            let seepage_y: f64 = elements.iter().map(|e| e.seepage[1]).sum();
            let w = Vector3::new(
                seismic.coefficient * total * sx + seepage_x,
                seismic.coefficient * total * sy + seepage_y,
                -weight,
            );
            let root = (1.0 + zx * zx + zy * zy).sqrt();
            let n = Vector3::new(zx, zy, -1.0) / root;
            let along = Vector3::new(dx, dy, zx * dx + zy * dy).normalize();
            let area = d * d * root;
            HovlandColumn {
                normal: w.dot(&n) - pressure * area,
                driving: w.dot(&along),
                area,
            }
        })
        .collect();
    let resisting: f64 = columns
        .iter()
        .zip(&strengths)
        .map(|(k, s)| s.cohesion * k.area + k.normal * s.friction)
        .sum();
    let driving: f64 = columns.iter().map(|k| k.driving).sum();
    let safety_factor = resisting_over_driving(
        resisting,
        driving,
        model.total_weight(),
        SafetyFactorTerm {
            factor: SafetyFactorKind::Hovland {
                towards_deg: dy.atan2(dx).to_degrees().rem_euclid(360.0),
            },
            force: DrivingForce::ColumnDriving,
        },
        || {
            Tension::of(
                model,
                columns.iter().enumerate().map(|(k, t)| {
                    let s = &strengths[k];
                    (k, t.area, s.cohesion * t.area + t.normal * s.friction)
                }),
            )
        },
    )?;
    Ok(Hovland {
        safety_factor,
        columns,
    })
}
