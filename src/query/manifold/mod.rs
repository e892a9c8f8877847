//! The pair queries of the explicit and limit drivers: for two placed
//! shapes, the points where they touch (a manifold: a face on a face gives
//! two), each a [`ContactGeometry`] with its point, unit normal from A to
//! B, overlap, contact width, radii of curvature and the
//! [`ContactFeatures`] (vertex, edge or whole body of each side) that name
//! the point across steps.
//!
//! One routine per shape pair behind one dispatcher
//! ([`dispatch::contact_manifold_2d`]; [`dispatch::contact_2d`] for the
//! single deepest point). Each routine is written once for a pair in a
//! fixed order; the dispatcher swaps the pair where needed and flips the
//! result, so the normal always points from the first argument into the
//! second. A pair without a routine is `Err(UnsupportedPair)` naming both
//! shapes, never a panic.
//!
//! [`relative_increment`] gives the relative displacement of the two
//! bodies at a contact point in the local frame, rotation included (the
//! point paper 000 stresses for ellipses), which a contact law turns into
//! forces.

pub mod circle_circle;
pub mod circle_polygon;
pub mod circle_segment;
pub mod dispatch;
pub mod ellipse;
pub mod ellipse_polygon;
mod geometry;
pub mod polygon;
pub mod polygon_segment;

pub use dispatch::{contact_2d, contact_manifold_2d};
pub use geometry::{
    moment_about, relative_increment, ContactFeatures, ContactGeometry, ContactShape, Feature,
};
