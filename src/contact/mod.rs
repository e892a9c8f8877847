//! Contacts: pair geometry (narrow phase), the dispatcher that picks the
//! routine for a shape pair, and the contact laws that turn relative motion
//! into forces.
//!
//! The data flow of one contact in one step is
//!
//! 1. [`dispatch::contact_manifold_2d`] gives the contact points of a pair
//!    (a manifold: a face on a face gives two), each a [`ContactGeometry`]:
//!    contact point, unit normal from A to B, overlap, contact width, the
//!    radii of curvature of both surfaces at the contact and the
//!    [`ContactFeatures`] (vertex, edge or whole body of each side) that
//!    name the point across steps; [`dispatch::contact_2d`] gives the single
//!    (deepest) point;
//! 2. the method computes the relative displacement increment of B with
//!    respect to A at the contact point, in the local frame (normal, tangent),
//!    with [`relative_increment`], which includes the motion of the contact
//!    point due to each body's rotation (the point paper 000 stresses for
//!    ellipses);
//! 3. a [`ContactLaw`] maps that increment and the contact's history state to
//!    forces, a consistent tangent (for implicit methods) and a regime
//!    (open, stick, slip); a law may also expose the linear strength
//!    `|t_s| ≤ c + μ t_n` that a limit analysis needs.

pub mod circle_circle;
pub mod circle_polygon;
pub mod circle_segment;
pub mod dispatch;
pub mod ellipse;
pub mod ellipse_polygon;
mod geometry;
pub mod polygon;
pub mod polygon_segment;

pub use geometry::{moment_about, relative_increment, ContactFeatures, ContactGeometry, Feature};
// The laws live in their own slot, `crate::law`; re-exported here for the
// code that names them through `contact`.
pub use crate::law::{
    BoundedStiffness, ContactInput, ContactLaw, ContactResponse, Damping, MohrCoulombSpring,
    NormalStiffness, PairProperties, Regime, RigidPlastic, SpringDashpotCoulomb, SpringState,
    StiffnessBound, Strength, StrengthLaw, Tangent, TangentLaw,
};
