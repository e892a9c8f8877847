//! Errors of the implicit driver: [`ImplicitError`], joined into
//! [`DismechError::Implicit`](crate::error::DismechError::Implicit): a
//! body whose material or load cannot be used, an edge traction on an edge
//! the body lacks, bodies that overlap or cross at the start, a time step
//! too small for the clock, and a step that fails even at the smallest
//! time step ([`ImplicitDynamics::advance`](crate::implicit::ImplicitDynamics::advance)).
//! DDA ([`crate::dda`]) is one instantiation of the driver and returns
//! these. Each variant names the offending body, value or step.

/// Why an implicit model ([`crate::implicit::ImplicitDynamics`], DDA's
/// [`crate::dda::DdaModel`]) cannot be built or a step of it taken;
/// joined into [`DismechError::Implicit`](crate::error::DismechError::Implicit).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ImplicitError {
    /// A DDA block has an invalid material value.
    #[error("block {block}: invalid {name} = {value}: {requirement}")]
    InvalidBlock {
        /// Index of the block.
        block: usize,
        /// The parameter.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What it must satisfy.
        requirement: &'static str,
    },
    /// An edge traction that names no edge of its body, or is not finite.
    #[error("body {body}: edge traction on edge {edge}: {reason}")]
    InvalidEdgeTraction {
        /// Index of the body.
        body: usize,
        /// The edge index given.
        edge: usize,
        /// What is wrong, with the body's edge count where that is it.
        reason: crate::implicit::EdgeTractionProblem,
    },
    /// A time step too small for the clock: added to the time reached it
    /// changes nothing, or its smallest sub-step underflows.
    #[error("time step dt = {dt:e} s at t = {time} s: {reason}")]
    TimeStepTooSmall {
        /// The step asked for (s).
        dt: f64,
        /// The time reached (s).
        time: f64,
        /// Why it cannot be taken (its Display says what to change).
        reason: crate::implicit::StepTooSmall,
    },
    /// Two DDA blocks overlap at the start by more than the tolerance.
    #[error("vertex {vertex} of block {vertex_block} lies {depth:.3e} m inside block {edge_block} at the start, more than the tolerance {tolerance:.3e} m")]
    BlocksOverlap {
        /// Block owning the vertex.
        vertex_block: usize,
        /// The vertex.
        vertex: usize,
        /// Block it penetrates.
        edge_block: usize,
        /// Depth of the penetration.
        depth: f64,
        /// Largest penetration accepted at the start.
        tolerance: f64,
    },
    /// Two polygon bodies cross at the start (edges crossing, no vertex of
    /// either inside the other) by more than the tolerance.
    #[error("blocks {a} and {b} cross at the start (their edges intersect), overlapping by {depth:.3e} m, more than the tolerance {tolerance:.3e} m")]
    BlocksCross {
        /// One block.
        a: usize,
        /// The other block.
        b: usize,
        /// Smallest overlap of their projections on their edge normals.
        depth: f64,
        /// Largest overlap accepted at the start.
        tolerance: f64,
    },
    /// A step of the implicit driver could not be completed even at the
    /// smallest time step; the model is left at the last accepted state.
    #[error("implicit step failed at t = {time:.6} s with dt = {dt:.3e} s: {reason}; reduce the time step or the contact penalty")]
    StepFailed {
        /// Time reached (s).
        time: f64,
        /// The smallest step tried (s).
        dt: f64,
        /// What failed.
        reason: crate::implicit::StepFailure,
        /// The record of the call up to the failure (its sub-steps,
        /// halvings and iterations).
        report: Box<crate::implicit::StepReport>,
    },
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::DismechError;

    #[test]
    fn joined_into_dismech_error_with_the_same_message() {
        let e = ImplicitError::BlocksCross {
            a: 0,
            b: 1,
            depth: 0.25,
            tolerance: 1e-9,
        };
        let joined = DismechError::from(e.clone());
        assert_eq!(joined.to_string(), e.to_string());
        assert_eq!(
            joined.to_string(),
            "blocks 0 and 1 cross at the start (their edges intersect), overlapping by 2.500e-1 m, more than the tolerance 1.000e-9 m"
        );
        assert!(matches!(
            joined,
            DismechError::Implicit(ImplicitError::BlocksCross { a: 0, b: 1, depth, .. }) if depth == 0.25
        ));
    }
}
