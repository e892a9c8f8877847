//! The explicit-dynamics driver: rigid 2D bodies of any shape stepped by an
//! explicit integrator, contact forces from a contact law — the distinct
//! element method of Cundall, written once over the slots. Paper 000's
//! ellipse DEM is one instantiation of it ([`crate::dem`]).
//!
//! | slot or step | piece |
//! |---|---|
//! | candidate pairs | [`crate::broad_phase::CellGrid`] |
//! | pair geometry | [`crate::query::manifold::dispatch::contact_manifold_2d`] (several points for polygons) |
//! | relative motion at the contact | [`crate::query::relative_increment`] |
//! | contact force and history | any [`crate::law::ContactLaw<2>`] with a [`crate::law::BoundedStiffness`], e.g. [`crate::law::SpringDashpotCoulomb`] |
//! | `M a = f` | [`crate::linsolve::LumpedSystem`] (diagonal mass) |
//! | time step | any [`crate::integrate::ExplicitIntegrator`], e.g. [`crate::integrate::ExplicitEuler`] (an implicit scheme does not compile here) |
//! | body kinematics | rigid, 3 DOF (translation and rotation of the centroid) |
//!
//! Per step: contact forces from the positions and the previous step's
//! increments, accelerations from forces plus gravity (paper 000 eqs.
//! 20–22), then velocities and positions. The contact history (spring
//! forces and the overlap) is kept per contact point, keyed by the particle,
//! what it touches and the point's [`crate::query::ContactFeatures`],
//! while the point exists: a pair of smooth bodies has one point (features
//! `Whole`), a polygon one per vertex-on-edge contact, and a point whose
//! features change (a vertex sliding off an edge onto the next) starts a
//! new history. The shear increment is the relative displacement at the
//! contact point (rotation included); the normal increment of a continuing
//! contact is the change of the overlap itself, which stays exact when a
//! non-circular body rolls and its deepest point moves along its boundary.
//!
//! Polygons are rigid bodies (3 DOF) here. Their contact points are vertices
//! on edges, where paper 000's eq. (19) has no value (radius of curvature 0
//! at the vertex, contact width 0): [`ExplicitDynamics::new`] refuses a law
//! whose force or stiffness is not finite there, so polygons take a constant
//! normal stiffness per point (a face on a face: two points, `2 k_n`).

mod checks;
mod driver;
mod neighbours;
mod pair_forces;
mod stability;

pub use driver::{
    ContactRecord, ContactTarget, DemSettings, ExplicitDynamics, RestCriterion, RunOutcome,
    RunStatus,
};
pub use stability::{critical_time_step, StabilityLimit};
