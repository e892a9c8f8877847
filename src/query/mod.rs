//! The pair-query slot: what two placed shapes know of each other.
//!
//! | query | for | module |
//! |---|---|---|
//! | contact manifold: points, normals, overlaps, widths, radii of curvature, features | explicit dynamics (DEM), limit analysis | [`manifold`] |
//! | gap and shear with their first and second variations in the bodies' unknowns | implicit dynamics (DDA and its generalisations) | [`variation`] |
//!
//! Both cover every pair of 2D shapes the crate has (circle, ellipse,
//! polygon — convex or concave — and wall segment); a pair without a
//! routine is a typed error naming both shapes.

pub mod manifold;
pub mod variation;

pub use manifold::{
    contact_2d, contact_manifold_2d, moment_about, relative_increment, ContactFeatures,
    ContactGeometry, ContactShape, Feature,
};
