//! The implicit-dynamics driver: penalty contact of 2D bodies stepped by an
//! implicit integrator, with an open–close iteration and Newton–Raphson on
//! the consistent tangent, a line search and automatic reduction of the
//! step — written once, generic over the slots:
//!
//! | slot | here |
//! |---|---|
//! | shape | [`BodyGeometry`]: polygons (convex or concave), ellipses and circles, walls |
//! | pair query | [`crate::query::variation`]: gap and shear of vertex–edge, smooth–edge and smooth–smooth contacts with their first and second variations |
//! | body kinematics | `K:` [`crate::kinematics::Kinematics`]`<N>`: [`crate::kinematics::Rigid2`] (3 unknowns), [`crate::kinematics::Affine2`] (DDA's 6) |
//! | contact law | `L:` [`crate::law::TangentLaw`]`<2>` (a law without a consistent tangent does not compile here), per pair of body groups ([`ContactLaws`]) |
//! | integrator | `I:` [`crate::integrate::ImplicitIntegrator`]: Newmark with the user's β, γ; quasi-static; restarted from rest |
//! | linear solver | `S:` [`crate::linsolve::LinearSolver`] on a [`crate::linsolve::BlockAssembly`] pattern kept while the pairs in contact are unchanged |
//!
//! Paper 003's DDA is one instantiation ([`crate::dda::DdaModel`]:
//! `ImplicitDynamics<6, Affine2, PenaltyCoulomb, Newmark, SparseLu>`).
//!
//! | concept | file |
//! |---|---|
//! | body: geometry, material, state, prescribed unknowns | `body.rs` |
//! | contact detection at the start of a step | `detect.rs` |
//! | laws per pair of body groups | `laws.rs` |
//! | assembly, open–close, Newton, line search | `step.rs` |
//! | the driver: time loop, Δt control, commit | `driver.rs` |
//! | settings, reports | `settings.rs`, `report.rs` |
//! | errors ([`ImplicitError`], joined into [`DismechError::Implicit`](crate::error::DismechError::Implicit)) | `error.rs` |
//!
//! * **Contacts**: detected at the start of each step; a polygon vertex
//!   meets the edges [`crate::query::variation::entrance_edges`] gives it:
//!   classic DDA's rule (Shi 1988, *Discontinuous Deformation Analysis*,
//!   ch. 4: the previous step's edge, else the shortest way out) with the
//!   entrance line at shared corners (the edge whose line separates the
//!   vertex's angle from the other block; blocks cut from joint sets share
//!   corners, and "the shortest way out" there picks a side edge that
//!   carries no load, through which a block sank under `Converged` steps),
//!   no edge met from behind, and both edges of a notch. Gaps are measured
//!   from the foot of the perpendicular, so their round-off does not grow
//!   with an edge's length.
//! * **Open–close**: while the set of open contacts changes from one
//!   iterate to the next, the iteration is an open–close iteration (at
//!   most `max_open_close`).
//! * **Newton**: once the set is stable, a consistent law iterates to
//!   `‖R‖ ≤ tol · scale`, or to 100 times the residual's own round-off
//!   where that is larger (a stiff penalty turns the rounding of the bodies'
//!   motion in a contact's gap into forces; see [`StepFailure::RoundOff`]
//!   for where that round-off alone is too large), with the consistent
//!   tangent (at most `max_newton` iterations), with the stick/slip states and slip directions unchanged
//!   between the last two iterates. An update that would take a slipping
//!   contact, whose slip has already reversed once in the step, to slip
//!   the other way again stops where that contact sticks (its stick band
//!   is too narrow for a full update to land in, and Newton would cycle
//!   between the two slip directions); with several such contacts it stops
//!   at a quantile of where they stick, by default where a fifth of them
//!   have stuck ([`ImplicitSettings::slip_reversal_quantile`], 0.2; 0 stops
//!   it where the first sticks); a backtracking line
//!   search on `‖R‖` then halves a step that does not lower the residual
//!   (at most 8 times).
//!   A law that is not consistent ([`crate::law::TangentLaw::is_consistent`],
//!   DDA's conventional friction) has no Newton phase: as in classic DDA
//!   the step is accepted when the open/closed states no longer change
//!   (and refused as [`StepFailure::Imprecise`] if the equations then hold
//!   only above a relative residual of 5e-6, the sign of a penalty too
//!   stiff for double precision), and its tangent has no Hessian terms.
//! * **Predictor**: the iteration starts from the constant-acceleration
//!   motion for bodies in free flight and from the start-of-step
//!   configuration for bodies that ended the last step in contact
//!   ([`Predictor::FreeFlight`]).
//! * **Search distance**: a step whose boundary point moves further than
//!   the search distance relative to a body it could reach may have missed
//!   a contact. With [`ImplicitSettings::max_search_distance`] above the
//!   search distance, such a step is detected again at a search distance
//!   covering its motion (up to that bound) and repeated at its size
//!   ([`StepReport::redetections`]), and the next step starts from the
//!   search distance the last motion needed; otherwise it is halved.
//! * **Damping**: [`ImplicitSettings::mass_damping`] adds `α M v` to the
//!   residual (zero by default), for runs that must come to rest.
//! * **Δt reduction**: a step whose iteration fails, whose solve is
//!   singular, or which moves a point further than the largest search
//!   distance relative to a neighbouring body is retried with half the step, down to
//!   `min_dt_ratio` times the requested step; after a successful sub-step
//!   the step doubles again up to the requested one
//!   ([`StepReport::halvings`] counts the causes). Past that bound
//!   [`ImplicitDynamics::advance`] returns
//!   [`ImplicitError::StepFailed`] saying what failed and what
//!   to change (the explicit driver's answer to an unstable step is an
//!   error too). The halving is bounded: `min_dt_ratio`
//!   is at least [`MIN_DT_RATIO_FLOOR`] (52 halvings), a step is halved
//!   only while its half moves the clock on, and a step whose smallest
//!   sub-step underflows, or which itself does not move the clock, is
//!   refused ([`ImplicitError::TimeStepTooSmall`]).
//!
//! * **Checkpoints**: [`ImplicitDynamics::checkpoint`] (or
//!   [`ImplicitDynamics::save_checkpoint`]) saves the bodies' geometry and
//!   motion, the step control and the contact history;
//!   [`ImplicitDynamics::restore`] puts them into the model built again,
//!   refusing a model that is not the run's, and the run goes on to the
//!   same bits ([`crate::checkpoint`]).
//!
//! Conventions: the first two unknowns of every kinematics translate the
//! body's reference point (its centroid); within a step every point moves
//! by the kinematics' map `x = c + t(d) + F(d)(X − c)`.

mod body;
mod detect;
mod driver;
mod error;
mod laws;
mod motion;
mod report;
mod settings;
mod step;

pub use body::{
    Body, BodyGeometry, BodyMaterial, EdgeTractionProblem, Motion, PlaneState, Prescribed,
};
pub use detect::{ContactKey, StepContact};
pub use driver::{FixedPoint, ImplicitDynamics};
pub use error::ImplicitError;
pub use laws::ContactLaws;
pub use report::{ContactReport, Halvings, StepFailure, StepReport, StepTooSmall};
pub use settings::{ImplicitSettings, Predictor, MIN_DT_RATIO_FLOOR};

#[cfg(test)]
mod tests;
