//! What the pairs of a step read of each body, one record per particle
//! beside the scene's particles: the centre, the last step's increment,
//! the mass and, for a circle, the shape. A pair of two circles (the
//! commonest) reads only its two records, one cache line each, where a
//! particle itself (shape, pose, velocities, inertia, loads) spans two;
//! in a scene larger than the caches that is most of what a pair's B
//! costs.

use crate::math::{Point, Vec2};
use crate::scene::Particle;
use crate::shape::{AnyShape2, Circle};

/// A body as its pairs read it. The motion keeps `centre` equal to the
/// particle's `pose.position` (the same value, written from it) and sets
/// `increment`; `mass` and `circle` do not change during a run.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
pub(super) struct PairBody {
    /// The particle's centre (m).
    pub centre: Point,
    /// The particle's increment of the last step (translation, rotation).
    pub increment: (Vec2, f64),
    /// The particle's mass (kg/m).
    pub mass: f64,
    /// The shape, when the particle is a circle.
    pub circle: Option<Circle>,
}

impl PairBody {
    /// The record of a particle at rest (no increment yet).
    pub fn of(particle: &Particle) -> Self {
        Self {
            centre: particle.pose.position,
            increment: (Vec2::zeros(), 0.0),
            mass: particle.mass,
            circle: match particle.shape {
                AnyShape2::Circle(circle) => Some(circle),
                _ => None,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One record is one cache line (on the machines whose lines are 64
    /// bytes, the record's alignment puts each in a line of its own).
    #[test]
    fn a_record_fills_one_cache_line() {
        assert_eq!(std::mem::size_of::<PairBody>(), 64);
        assert_eq!(std::mem::align_of::<PairBody>(), 64);
    }
}
