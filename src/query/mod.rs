//! Pair queries: what two placed shapes know of each other.
//!
//! [`variation`] gives, for the contacts of an implicit driver, the gap and
//! shear of a pair with their first and second variations with respect to
//! the bodies' degrees of freedom. The manifold queries of the explicit
//! drivers are in [`crate::contact`].

pub mod variation;
