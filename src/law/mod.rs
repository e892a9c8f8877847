//! The contact-law slot: relative motion and history at one contact →
//! force, consistent tangent, regime; and a law's strength for limit
//! analysis.
//!
//! A law states what it provides through the traits it implements
//! ([`ContactLaw`] force, [`TangentLaw`] consistent tangent,
//! [`StrengthLaw`] linear strength, [`BoundedStiffness`] stable-step
//! bound); a driver states what it needs in its bounds, so a law missing a
//! capability is a compile error.
//!
//! | law | paper | force | tangent | strength | stiffness bound |
//! |---|---|---|---|---|---|
//! | [`SpringDashpotCoulomb`] | 000 eqs. 14–19 | ✓ | ✓ | ✓ | ✓ |
//! | [`PenaltyCoulomb`] (return mapping or conventional) | 003 eqs. 7–10 | ✓ | ✓ | ✓ | ✓ |
//! | [`MohrCoulombSpring`] (3D, cohesive, no tension) | 001 §4(4) | ✓ | ✓ | ✓ | ✓ |
//! | [`RigidPlastic`] | 002 eqs. 13–15 | – | – | ✓ | – |
//! | [`RollingResistance`]`<L>` (adds a rolling moment to a 2D law `L`) | Iwashita & Oda 1998 | ✓ + moment | – | – | ✓ (if `L`'s) |
//!
//! Friction is the coefficient `μ = tan φ` in every law (and in HPM's
//! material); [`friction_from_degrees`] converts a friction angle, and
//! [`RigidPlastic::from_friction_angle_deg`] takes one.
//!
//! The three frictional laws share one Coulomb core ([`coulomb`]): the
//! elastic predictor of the shear force and its radial return onto
//! `|t_s| ≤ c + μ t_n`, with the consistent tangent; they differ only in
//! their normal part and in what they add (dashpots).
//!
//! [`conformance`] holds the checks every law of this crate passes
//! (no tension, the Coulomb cap, the tangent against finite differences,
//! purity), written once and generic over the law, so that a user's own law
//! can be checked the same way.

pub mod conformance;
pub mod coulomb;
mod mohr_coulomb;
mod penalty_coulomb;
mod rigid_plastic;
mod rolling;
mod spring_dashpot;
mod traits;

pub use coulomb::friction_from_degrees;
pub use mohr_coulomb::MohrCoulombSpring;
pub use penalty_coulomb::{FrictionIntegration, PenaltyCoulomb, PenaltyState};
pub use rigid_plastic::RigidPlastic;
pub use rolling::{RollingResistance, RollingState};
pub use spring_dashpot::{
    effective_mass, Damping, NormalStiffness, SpringDashpotCoulomb, SpringState, SpringVector,
};
pub use traits::{
    BoundedStiffness, ContactInput, ContactLaw, ContactResponse, PairProperties, Regime,
    StiffnessBound, Strength, StrengthLaw, Tangent, TangentLaw,
};
