//! A rigid 2D particle.

use crate::math::{Point, Pose2, Vec2};
use crate::shape::{AnyShape2, MassProperties};

/// A rigid particle: shape, pose, velocities and mass properties (per unit
/// thickness).
#[derive(Debug, Clone, PartialEq)]
pub struct Particle {
    /// Geometry.
    pub shape: AnyShape2,
    /// Centre and orientation.
    pub pose: Pose2,
    /// Velocity of the centre (m/s).
    pub velocity: Vec2,
    /// Angular velocity (rad/s, counter-clockwise).
    pub angular_velocity: f64,
    /// Mass (kg/m).
    pub mass: f64,
    /// Moment of inertia about the centre (kg·m²/m).
    pub inertia: f64,
    /// A constant external force on the centre (N/m), besides gravity;
    /// e.g. a pressure applied to the particles on a free boundary.
    pub external_force: Vec2,
}

impl Particle {
    /// A particle at rest at `centre`.
    pub fn at_rest(shape: AnyShape2, centre: Point, mass: MassProperties) -> Self {
        Self {
            shape,
            pose: Pose2 {
                position: centre,
                angle: 0.0,
            },
            velocity: Vec2::zeros(),
            angular_velocity: 0.0,
            mass: mass.mass,
            inertia: mass.inertia,
            external_force: Vec2::zeros(),
        }
    }

    /// Kinetic energy `½ m v² + ½ I ω²` (J/m).
    pub fn kinetic_energy(&self) -> f64 {
        0.5 * self.mass * self.velocity.norm_squared()
            + 0.5 * self.inertia * self.angular_velocity * self.angular_velocity
    }
}
