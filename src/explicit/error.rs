//! Errors of the explicit driver: [`ExplicitError`], joined into
//! [`DismechError::Explicit`](crate::error::DismechError::Explicit): a
//! run refused before it starts (a particle's state or mass, particles
//! overlapping each other or a wall, a contact law undefined for a
//! particle's shape, a time step above the stable limit, a scene whose
//! memory the system does not give) and a run stopped on the way (a
//! non-finite value, a particle leaving the frame, an energy blow-up).
//! The DEM of paper 000 ([`crate::dem`]) is one instantiation of the
//! driver and returns these. Each variant names the offending particle,
//! value or step.

use crate::error::{Bytes, Number};

/// Why an explicit run ([`crate::explicit::ExplicitDynamics`]) cannot
/// start or go on; joined into
/// [`DismechError::Explicit`](crate::error::DismechError::Explicit).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExplicitError {
    /// A particle starts inside a wall.
    #[error("particle {body} starts inside wall {wall}: penetration {penetration:.3e} m exceeds the tolerance {tolerance:.3e} m{}", if *clockwise_frame { "; the frame's walls run clockwise, which puts the material outside them: list the walls counter-clockwise around what the frame holds" } else { "" })]
    StartsInsideWall {
        /// Index of the particle.
        body: usize,
        /// Index of the wall.
        wall: usize,
        /// Depth of the penetration.
        penetration: f64,
        /// Largest penetration accepted at the start.
        tolerance: f64,
        /// Whether the frame's walls run clockwise (material outside them).
        clockwise_frame: bool,
    },
    /// A particle's state or mass properties cannot start a run.
    #[error("particle {particle}: invalid {name} = {}: {requirement}", Number(*value))]
    InvalidParticle {
        /// Index of the particle.
        particle: usize,
        /// The quantity (position, velocity, mass…).
        name: &'static str,
        /// The value found.
        value: f64,
        /// What it must satisfy, and what to change.
        requirement: &'static str,
    },
    /// A model would take more memory than its budget or than the system
    /// gives; refused before the memory is taken.
    #[error("{what} needs about {bytes} bytes ({}): {advice}", Bytes(*bytes))]
    OutOfMemory {
        /// What would be allocated, with its sizes.
        what: crate::explicit::MemoryUse,
        /// Bytes it needs (an estimate where it is a budget).
        bytes: u128,
        /// Why it is refused and what to change.
        advice: crate::explicit::MemoryAdvice,
    },
    /// Two particles overlap at the start by more than the tolerance.
    #[error("particles {a} and {b} overlap by {overlap:.3e} m at the start, more than the tolerance {tolerance:.3e} m")]
    InitialOverlap {
        /// First particle.
        a: usize,
        /// Second particle.
        b: usize,
        /// Their overlap.
        overlap: f64,
        /// Largest overlap accepted at the start.
        tolerance: f64,
    },
    /// The time step is above the stable limit of the explicit scheme.
    #[error("time step {dt:.3e} s exceeds the stable limit {limit:.3e} s ({governing}{}); use dt <= {limit:.3e} s, or lower the contact stiffness", overlap_note(overlap))]
    UnstableTimeStep {
        /// The time step requested.
        dt: f64,
        /// The estimated stable limit.
        limit: f64,
        /// Which mode governs the limit.
        governing: crate::explicit::GoverningMode,
        /// Where a run's overlap outgrew the one the step was checked at
        /// and the limit was estimated again there; `None` for the check
        /// before a run.
        overlap: Option<crate::explicit::OverlapReached>,
    },
    /// The run produced a NaN or an infinite value.
    #[error("non-finite {quantity} of particle {body} at step {step} (t = {time:.6} s); reduce the time step or check the contact stiffness")]
    NonFinite {
        /// Step number at which it appeared.
        step: u64,
        /// Simulated time.
        time: f64,
        /// The particle.
        body: usize,
        /// Which quantity (position, velocity, force…).
        quantity: &'static str,
    },
    /// A particle fell or was pushed out of the frame.
    #[error("particle {body} left the frame at step {step} (t = {time:.6} s): its centre ({x:.3}, {y:.3}) m is farther than the frame's size from the walls; close the frame on the side it left, or check the loads on the particles there")]
    ParticleLeftFrame {
        /// Step number.
        step: u64,
        /// Simulated time.
        time: f64,
        /// The particle.
        body: usize,
        /// Centre x (m).
        x: f64,
        /// Centre y (m).
        y: f64,
    },
    /// The kinetic energy grew beyond what the loads can supply.
    #[error("energy blow-up at step {step}: kinetic energy {kinetic:.3e} J exceeds twice the energy supplied {available:.3e} J; the time step is above the stable limit of the packed assembly: reduce dt (the largest overlap at the start was {initial_overlap:.3e} m; the elastic energy of overlaps at the start is not counted as supplied, so if that is large, separate the particles at the start instead)")]
    EnergyBlowUp {
        /// Step number.
        step: u64,
        /// Kinetic energy at that step.
        kinetic: f64,
        /// Released potential energy plus initial kinetic energy.
        available: f64,
        /// Largest overlap between two particles, or a particle and a
        /// wall, at the start (m).
        initial_overlap: f64,
    },
    /// The contact law has no finite response for the contacts a particle
    /// of this shape makes.
    #[error("particle {body} is a {shape}: the contact law gives no finite force or stiffness for {contact}; {advice}")]
    LawUndefinedForShape {
        /// The particle.
        body: usize,
        /// Its shape.
        shape: &'static str,
        /// The contact the law was probed with.
        contact: &'static str,
        /// What to change.
        advice: &'static str,
    },
}

/// ` at the overlap reached …` where a run's overlap outgrew the checked
/// one, or nothing.
fn overlap_note(overlap: &Option<crate::explicit::OverlapReached>) -> String {
    overlap.map(|o| format!(" at {o}")).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::DismechError;

    #[test]
    fn joined_into_dismech_error_with_the_same_message() {
        let e = ExplicitError::EnergyBlowUp {
            step: 12,
            kinetic: 3.0,
            available: 1.0,
            initial_overlap: 0.0,
        };
        let joined = DismechError::from(e.clone());
        assert_eq!(joined.to_string(), e.to_string());
        assert!(joined.to_string().starts_with(
            "energy blow-up at step 12: kinetic energy 3.000e0 J exceeds twice the energy supplied 1.000e0 J;"
        ));
        assert!(matches!(
            joined,
            DismechError::Explicit(ExplicitError::EnergyBlowUp { step: 12, .. })
        ));
    }
}
