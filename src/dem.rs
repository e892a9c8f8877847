//! The ellipse DEM of Katsuki & Ishikawa (paper 000) as one composition of
//! the explicit driver:
//!
//! `DemSimulation<SpringDashpotCoulomb, ExplicitEuler> = ExplicitDynamics<SpringDashpotCoulomb, ExplicitEuler>`
//!
//! | slot | piece | paper 000 |
//! |---|---|---|
//! | shape | [`crate::shape::Ellipse`], [`crate::shape::Circle`] (and the frame's [`crate::shape::Segment`] walls) | §2(1) |
//! | pair query | [`crate::query::manifold::ellipse`]: exact intersection of the boundaries, contact at the chord's midpoint | eqs. (2)–(11), (20)–(21) |
//! | body kinematics | rigid, 3 DOF | eqs. (20)–(22) |
//! | contact law | [`crate::law::SpringDashpotCoulomb::katsuki`]: spring, dashpot, Coulomb slip, eq. (19) stiffness | eqs. (14)–(19) |
//! | integrator | [`crate::integrate::ExplicitEuler`] | "Euler's method" |
//! | global solve | diagonal mass ([`crate::linsolve::LumpedSystem`]) | |
//!
//! The driver is generic: the same type runs polygons, a user's own law
//! (with a stiffness bound) or a user's own explicit integrator. Its
//! settings, rest criterion, outcomes and contact records are in
//! [`crate::explicit`] ([`crate::explicit::DemSettings`],
//! [`crate::explicit::RestCriterion`], [`crate::explicit::RunOutcome`], …).

use crate::integrate::ExplicitEuler;

/// The DEM: the explicit driver, with paper 000's explicit Euler by
/// default and any contact law.
pub type DemSimulation<L, I = ExplicitEuler> = crate::explicit::ExplicitDynamics<L, I>;
