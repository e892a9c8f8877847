//! The limit-analysis driver: rigid-plastic collapse of rigid bodies by
//! linear programming (paper 002, Yamada & Tamura 2000, generalised to
//! bodies of any shape), generic over the LP solver.
//!
//! | slot | here |
//! |---|---|
//! | shape | any [`crate::shape::AnyShape2`] outline ([`LimitBody`]); straight supports ([`Support`]) |
//! | pair query | the contact points and normals: from circle geometry ([`LimitModel::add_contact`]) or given, e.g. a manifold's points or a DEM packing's contacts ([`LimitModel::add_contact_at`], [`model_from_packing`]) |
//! | body kinematics | rigid, 3 DOF (or 2 without rotation) |
//! | contact law | any [`crate::law::StrengthLaw`]: its strength `|T| ≤ c + N tan φ` and whether it may open ([`PlasticContact`]); [`crate::law::RigidPlastic`] is paper 002's |
//! | integrator | none: the limit state |
//! | LP solver | any [`crate::lp::LpSolver`], e.g. [`crate::lp::LinearProgramSolver`] (Clarabel) |
//!
//! The collapse is driven by one support moving at a given velocity (a
//! loading plate: the limit load is the force on it), by a live load on a
//! body ([`LimitModel::set_live_load`]: the limit is its multiplier λ), or
//! by the dead loads themselves ([`LimitModel::multiply_dead_loads`]: the
//! limit is the factor λ on the self-weight; see [`LoadDriver`]). [`admissibility`] checks the dual contact forces for equilibrium and
//! strength.
//!
//! The kinematic (upper-bound) LP: the unknowns are the element
//! velocities `q` (u, v and, for rolling elements, θ̇), the slip rates
//! `S = S⁺ − S⁻` and, where a contact may open, the opening rates. The
//! compatibility rows are `s = Dᵀ q` (eqs. 5–9, built from the contact
//! geometry, not from a lattice formula): the relative velocity at every
//! contact is split into its normal part (zero for a contact that keeps
//! contact) and its slip. The objective is the dissipation `Σ C|S|` (eq. 15)
//! minus the power of known loads (self-weight); with the plate driven at
//! unit speed its minimum is the limit load `P` (eq. 13); with a live load
//! instead, the live load's power is normalised to one and the minimum is
//! its multiplier. The dual of this
//! LP is the static (lower-bound) problem: its multipliers are the contact
//! forces `N`, `T`, in equilibrium with `P` (eq. 4) and within strength;
//! equal primal and dual optima certify the limit load. The solution is
//! checked against the LP's own optimality conditions (primal and dual
//! feasibility, zero gap) at [`CERTIFICATE_TOLERANCE`], whatever tolerance
//! the solver was given, before a load is reported; a zero load is
//! [`LimitStatus::ZeroLoad`], a model that cannot carry its dead loads
//! [`LimitStatus::Unbounded`] (see `verdict.rs`).

mod analysis;
mod equilibrium;
mod error;
mod from_dem;
pub mod lattice;
mod model;
mod static_lp;
mod verdict;

pub use analysis::{analyse, mechanism_uniqueness, LimitResult, LimitStatus, Uniqueness};
pub use equilibrium::{admissibility, Admissibility};
pub use error::LimitError;
pub use from_dem::{model_from_packing, PackingLimitSettings};
pub use model::{
    LimitBody, LimitContact, LimitModel, LiveLoad, LoadDriver, NamedPartner, Partner,
    PlasticContact, Support,
};
pub use static_lp::analyse_static;
pub use verdict::CERTIFICATE_TOLERANCE;
