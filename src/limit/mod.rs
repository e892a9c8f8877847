//! Rigid-plastic limit analysis of circular elements by linear programming
//! (paper 002, Yamada & Tamura 2000), as a composition of generic pieces:
//!
//! | piece | here |
//! |---|---|
//! | Shape | circles ([`LimitBody`]) and straight supports ([`Support`]) |
//! | ContactLaw | [`crate::contact::RigidPlastic`]: admissible forces `|T| ≤ C + N tan φ`, flow rule |
//! | Integrator | none: the limit state |
//! | GlobalSolver | [`crate::solve::LinearProgramSolver`] (Clarabel) |
//!
//! The kinematic (upper-bound) LP: the unknowns are the element
//! velocities `q` (u, v and, for rolling elements, θ̇), the slip rates
//! `S = S⁺ − S⁻` and, where a contact may open, the opening rates. The
//! compatibility rows are `s = Dᵀ q` (eqs. 5–9, built from the contact
//! geometry, not from a lattice formula): the relative velocity at every
//! contact is split into its normal part (zero for a contact that keeps
//! contact) and its slip. The objective is the dissipation `Σ C|S|` (eq. 15)
//! minus the power of known loads (self-weight); with the plate driven at
//! unit speed its minimum is the limit load `P` (eq. 13). The dual of this
//! LP is the static (lower-bound) problem: its multipliers are the contact
//! forces `N`, `T`, in equilibrium with `P` (eq. 4) and within strength;
//! equal primal and dual optima certify the limit load.

mod analysis;
mod from_dem;
pub mod lattice;
mod model;
mod static_lp;

pub use analysis::{analyse, mechanism_uniqueness, LimitResult, LimitStatus, Uniqueness};
pub use from_dem::{model_from_packing, PackingLimitSettings};
pub use model::{LimitBody, LimitContact, LimitModel, Partner, Support};
pub use static_lp::analyse_static;
