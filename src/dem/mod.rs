//! The explicit distinct element method (Cundall; paper 000), composed from
//! the generic pieces:
//!
//! | step | piece |
//! |---|---|
//! | candidate pairs | [`crate::broad_phase::CellGrid`] |
//! | pair geometry | [`crate::contact::dispatch::contact_2d`] |
//! | relative motion at the contact | [`crate::contact::relative_increment`] |
//! | contact force and history | any [`crate::contact::ContactLaw<2>`], e.g. [`crate::contact::SpringDashpotCoulomb`] |
//! | `M a = f` | [`crate::linsolve::LumpedSystem`] (diagonal mass) |
//! | time step | any explicit [`crate::integrate::Integrator`], e.g. [`crate::integrate::ExplicitEuler`] |
//!
//! Per step: contact forces from the positions and the previous step's
//! increments, accelerations from forces plus gravity (paper 000 eqs.
//! 20–22), then velocities and positions. The contact history (spring
//! forces and the overlap) is kept per pair while the pair overlaps. The
//! shear increment is the relative displacement at the contact point
//! (rotation included); the normal increment of a continuing contact is
//! the change of the overlap itself, which stays exact when a non-circular
//! body rolls and its deepest point moves along its boundary.

mod simulation;
mod stability;

pub use simulation::{
    ContactRecord, ContactTarget, DemSettings, DemSimulation, RestCriterion, RunOutcome, RunStatus,
};
pub use stability::{critical_time_step, StabilityLimit};
