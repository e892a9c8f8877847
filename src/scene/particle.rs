//! A rigid 2D particle.

use crate::math::{Point, Pose2, Vec2};
use crate::shape::{AnyShape2, MassProperties};

/// A rigid particle: shape, pose, velocities and mass properties (per unit
/// thickness).
///
/// A particle of infinite mass and moment of inertia is **prescribed**
/// ([`Particle::prescribed`], [`Particle::fixed`]): it keeps its velocity
/// and angular velocity whatever the contacts push, as a wall of any
/// shape (a fixed polygon incline, a rough base of fixed discs, a plate
/// driven at constant speed): its acceleration is zero, so an integrator
/// that keeps a velocity at zero acceleration (every one of this crate)
/// keeps its motion; one that damps velocities would slow it too. Gravity
/// and external forces do not act on it, and it is left out of the kinetic
/// and potential energies, the total weight and the unbalanced force,
/// which describe the free particles; the force of its contacts is
/// `ExplicitDynamics::force_on`.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
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
    /// A prescribed particle: `shape` at `pose`, moving at `velocity` and
    /// `angular_velocity` for the whole run (infinite mass and moment of
    /// inertia).
    pub fn prescribed(
        shape: AnyShape2,
        pose: Pose2,
        velocity: Vec2,
        angular_velocity: f64,
    ) -> Self {
        Self {
            shape,
            pose,
            velocity,
            angular_velocity,
            mass: f64::INFINITY,
            inertia: f64::INFINITY,
            external_force: Vec2::zeros(),
        }
    }

    /// A fixed particle: `shape` at `pose`, at rest for the whole run.
    pub fn fixed(shape: AnyShape2, pose: Pose2) -> Self {
        Self::prescribed(shape, pose, Vec2::zeros(), 0.0)
    }

    /// Whether the particle's motion is prescribed (infinite mass).
    pub fn is_prescribed(&self) -> bool {
        self.mass == f64::INFINITY
    }

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

    /// Kinetic energy `½ m v² + ½ I ω²` (J/m); zero for a prescribed
    /// particle.
    pub fn kinetic_energy(&self) -> f64 {
        if self.is_prescribed() {
            return 0.0;
        }
        0.5 * self.mass * self.velocity.norm_squared()
            + 0.5 * self.inertia * self.angular_velocity * self.angular_velocity
    }
}
