//! Why the memory of an explicit run is refused
//! ([`ExplicitError::OutOfMemory`](crate::explicit::ExplicitError::OutOfMemory)): what it was for, and what to change.

use super::MAX_LISTED_PAIRS_PER_PARTICLE;

/// What a refused allocation was for.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MemoryUse {
    /// The driver's memory for a scene.
    #[error("a DEM of {particles} particles")]
    Dem {
        /// Particles of the scene.
        particles: usize,
    },
    /// A neighbour list at a skin that lists too many pairs.
    #[error("a neighbour list at a skin of {skin:e} m over {particles} particles (more than {budget} pairs, up to {pairs})")]
    NeighbourList {
        /// The skin (m).
        skin: f64,
        /// Particles of the scene.
        particles: usize,
        /// The most pairs listed.
        budget: usize,
        /// Every pair of the scene.
        pairs: u128,
    },
}

/// Why the memory is refused, and what to change.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MemoryAdvice {
    /// More bytes than the address space holds.
    #[error("more than the address space; run fewer particles")]
    AddressSpace,
    /// The system's allocator refused them.
    #[error("the system refused the memory; run fewer particles or on a machine with more memory")]
    SystemRefused,
    /// A skin far wider than the particles.
    #[error("more than {MAX_LISTED_PAIRS_PER_PARTICLE} pairs a particle is a skin far wider than the particles; use a skin of about the smallest bounding radius ({smallest_radius:.3e} m) or leave neighbour_skin at None to tune it")]
    SkinTooWide {
        /// The smallest bounding radius of the particles (m).
        smallest_radius: f64,
    },
}
