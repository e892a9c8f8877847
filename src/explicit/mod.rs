//! The explicit-dynamics driver: rigid 2D bodies of any shape stepped by an
//! explicit integrator, contact forces from a contact law — the distinct
//! element method of Cundall, written once over the slots. Paper 000's
//! ellipse DEM is one instantiation of it ([`crate::dem`]).
//!
//! | slot or step | piece |
//! |---|---|
//! | candidate pairs | a neighbour list with a skin ([`DemSettings::neighbour_skin`]; by default tuned at each build towards a build every 20 steps: wider while the particles move fast, the least again once they settle), built by [`crate::broad_phase::CellGrid`] when a particle has moved half the skin (or, with [`DemSettings::relative_travel`], when two particles may have come closer by the skin or a particle reached a wall not listed with it: a packing moving as a whole keeps its list) |
//! | pair geometry | [`crate::query::manifold::dispatch::contact_manifold_2d`] (several points for polygons; circles against circles and walls call [`crate::query::manifold::circle_circle`] and [`crate::query::manifold::circle_segment`] directly, two ellipses [`crate::query::manifold::ellipse::contact_ellipse_ellipse_oriented`] with each ellipse's rotation kept beside its pose; the radii of curvature (and a circle pair's width) are computed only for a law that reads them ([`crate::law::ContactLaw::uses_contact_shape`]); pairs of ellipses, or of an ellipse and a circle, seek their contact about the last step's contact point first) |
//! | relative motion at the contact | [`crate::query::relative_increment`] |
//! | contact force and history | any [`crate::law::ContactLaw<2>`] with a [`crate::law::BoundedStiffness`], e.g. [`crate::law::SpringDashpotCoulomb`] |
//! | `M a = f` | [`crate::linsolve::LumpedSystem`] (diagonal mass) |
//! | time step | any [`crate::integrate::ExplicitIntegrator`], e.g. [`crate::integrate::ExplicitEuler`] (an implicit scheme does not compile here) |
//! | body kinematics | rigid, 3 DOF (translation and rotation of the centroid) |
//!
//! Per step: contact forces from the positions and the previous step's
//! increments, accelerations from forces plus gravity (paper 000 eqs.
//! 20–22), then velocities and positions. The contact history (spring
//! forces and the overlap) is kept per contact point in the neighbour
//! list's pair (the particle and what it touches), named by the point's
//! [`crate::query::ContactFeatures`], while the point exists: a pair of smooth bodies has one point (features
//! `Whole`), a polygon one per vertex-on-edge contact, and a point whose
//! features change (a vertex sliding off an edge onto the next) starts a
//! new history. The shear increment is the relative displacement at the
//! contact point (rotation included); the normal increment of a continuing
//! contact is the change of the overlap itself, which stays exact when a
//! non-circular body rolls and its deepest point moves along its boundary.
//!
//! The list holds every pair that can touch until it is built again (see
//! the skin's docs), and a wall's geometry is asked only when the
//! particle's box meets the wall's (the wall queries are one-sided), so the
//! forces are those of a broad phase run at every step, to the last bit:
//! the skin sets the speed only. From 2000
//! particles on, the list's build, the pairs' contact points and the
//! particles' updates are computed on rayon's threads (run the stepping
//! loop inside a `ThreadPool::install` so that its thread is one of the
//! pool's). The particles are taken in blocks of 1024 consecutive indices:
//! a block's pairs (A in the block) are evaluated in the list's order and
//! added at once to their particles in the block, and a pair whose B lies
//! in a later block is added to B once every block is done. Each
//! particle's force is thus summed in a fixed order (its weight, its pairs
//! in the list's order but for those whose A is in an earlier block, then
//! those, each pair's points in order), so a run gives the same bits on
//! one thread or many; a scene of at most 1024 particles sums in the
//! list's order. A pair reads of each body a record of one cache line
//! kept beside the particles (its centre, last increment, mass and, for a
//! circle, its shape), so a pair of two circles reads no particle.
//! Neighbours with near indices keep the step fast (few
//! pairs across blocks, and each pair's B read from nearby memory):
//! [`crate::scene::Scene::renumber_for_locality`] numbers a scene so,
//! column by column in bands 32 mean particle widths high (10⁵ disks in
//! 32 rows ran about 1.13 times as fast so numbered as numbered row by
//! row: medians of a few runs on one machine). Contact records
//! ([`ExplicitDynamics::contacts`]) are made from the list only when asked
//! for. `examples/dem_throughput.rs` measures particle-steps per second on
//! the setup of the LAMMPS anchor (2D disks settling in a box).
//!
//! What a run is refused for before it starts: a time step that is not a
//! normal number, a particle whose pose, velocity or load is not finite or
//! whose mass is not positive, overlaps beyond the tolerance (with a word
//! where the frame runs clockwise), a fixed neighbour skin that would list
//! more than [`MAX_LISTED_PAIRS_PER_PARTICLE`] pairs a particle, and a
//! scene whose memory the system does not give
//! ([`ExplicitError::OutOfMemory`], asked of the allocator
//! before it is taken). [`ExplicitDynamics::run_to_rest`] ends at rest, at
//! [`RestCriterion::max_time`], after [`RestCriterion::max_steps`] steps or
//! after [`RestCriterion::max_wall_time`].
//! These refusals, and a run stopped on the way (a value that is not
//! finite, a particle out of the frame, an energy blow-up), are the
//! driver's own errors, [`ExplicitError`] (`error.rs`), joined into
//! [`DismechError::Explicit`](crate::error::DismechError::Explicit).
//!
//! A particle of infinite mass and moment of inertia is prescribed
//! ([`crate::scene::Particle::prescribed`], [`crate::scene::Particle::fixed`]):
//! a wall of any shape (a fixed polygon incline, a rough base of fixed
//! discs) or a body driven at a constant velocity (a plate). Its
//! acceleration is `f / ∞ = 0`, so it keeps its velocity; gravity and
//! external forces do not act on it; its pairs with free particles take
//! the free particle's mass as the pair's (as a wall's do); two prescribed
//! particles, or one and a wall, make no pair (they may overlap); and the
//! energies, the total weight and the unbalanced force count the free
//! particles only.
//!
//! A run is saved with [`ExplicitDynamics::checkpoint`] (or
//! [`ExplicitDynamics::save_checkpoint`]) and resumed to the same bits by
//! [`ExplicitDynamics::restore`] with the law and the integrator supplied
//! again: the scene, the settings, the neighbour list and every contact's
//! history come from the checkpoint ([`crate::checkpoint`]).
//!
//! Polygons are rigid bodies (3 DOF) here. Their contact points are vertices
//! on edges, where paper 000's eq. (19) has no value (radius of curvature 0
//! at the vertex, contact width 0): [`ExplicitDynamics::new`] refuses a law
//! whose force or stiffness is not finite there, so polygons take a constant
//! normal stiffness per point (a face on a face: two points, `2 k_n`).

mod checks;
mod driver;
mod error;
mod keys;
mod list_travel;
mod memory;
mod motion;
mod neighbours;
mod pair_bodies;
mod pair_forces;
mod phases;
mod skin;
mod stability;

pub use checks::MAX_LISTED_PAIRS_PER_PARTICLE;
pub use driver::{
    ContactRecord, ContactTarget, DemSettings, ExplicitDynamics, RestCriterion, RunOutcome,
    RunStatus,
};
pub use error::ExplicitError;
pub use memory::{MemoryAdvice, MemoryUse};
pub use phases::PhaseTimes;
pub use stability::{
    critical_time_step, critical_time_step_at, GoverningMode, ModePartner, OscillationMode,
    OverlapReached, StabilityLimit, DEFAULT_STABILITY_OVERLAP,
};
