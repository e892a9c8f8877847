//! The scene: bodies, boundaries and loads, as data apart from the
//! algorithms that advance them.

mod frame;
pub mod layout;
mod numbering;
mod particle;

pub use frame::{Frame, JOINT_TOLERANCE};
pub use layout::{CircleRows, Layout};
pub use particle::Particle;

use crate::error::{require_finite, require_positive, DismechError, Result};
use crate::math::{Point, Pose2, Vec2};
use crate::shape::{AnyShape2, Circle, Ellipse, Polygon};

/// Particles in a rigid frame under gravity (2D, per unit thickness).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Scene {
    /// The moving bodies.
    pub particles: Vec<Particle>,
    /// The rigid walls.
    pub frame: Frame,
    /// Gravitational acceleration (m/s²), e.g. `(0, −9.81)`.
    pub gravity: Vec2,
}

impl Scene {
    /// An empty scene in `frame` under `gravity`.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming `gravity x` or `gravity y`
    /// when a component of `gravity` is not finite.
    pub fn new(frame: Frame, gravity: Vec2) -> Result<Self> {
        require_finite("gravity x", gravity.x)?;
        require_finite("gravity y", gravity.y)?;
        Ok(Self {
            particles: Vec::new(),
            frame,
            gravity,
        })
    }

    /// Add a circle of `radius` (m) and `density` (kg/m³) at rest at
    /// `centre`; returns its index.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming the value for a radius or
    /// density that is not finite and positive, or a centre that is not
    /// finite.
    pub fn add_circle(&mut self, centre: Point, radius: f64, density: f64) -> Result<usize> {
        self.add_shape(
            Circle::new(radius)?,
            Pose2::new(centre.x, centre.y, 0.0),
            density,
        )
    }

    /// Add an ellipse with semi-axes `a ≥ b` (m), major axis at `angle`
    /// (rad), `density` (kg/m³), at rest at `centre`; returns its index.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming the value for semi-axes
    /// that are not finite and positive, `a < b`, an aspect ratio `a/b`
    /// above [`MAX_ASPECT_RATIO`](crate::shape::MAX_ASPECT_RATIO), a centre
    /// or angle that is not finite, or a density that is not finite and
    /// positive (see [`Ellipse::new`]).
    pub fn add_ellipse(
        &mut self,
        centre: Point,
        a: f64,
        b: f64,
        angle: f64,
        density: f64,
    ) -> Result<usize> {
        self.add_shape(
            Ellipse::new(a, b)?,
            Pose2::new(centre.x, centre.y, angle),
            density,
        )
    }

    /// Add a rigid polygon of `density` (kg/m³) at rest, from its vertices
    /// in world coordinates listed counter-clockwise (convex or concave, no
    /// self-intersection); its pose is its centroid with angle 0. Returns
    /// its index.
    ///
    /// # Errors
    /// [`DismechError::InvalidPolygon`] (naming the particle's index as the
    /// block) for fewer than three vertices, a non-finite vertex, two
    /// consecutive vertices that coincide, clockwise order, zero area,
    /// crossing edges or moments of area that overflow
    /// ([`Polygon::from_world`]); [`DismechError::InvalidParameter`] for a
    /// density that is not finite and positive.
    pub fn add_polygon(&mut self, vertices: &[Point], density: f64) -> Result<usize> {
        let (polygon, centroid) = Polygon::from_world(vertices, self.particles.len())?;
        self.add_shape(polygon, Pose2::new(centroid.x, centroid.y, 0.0), density)
    }

    /// Add a `width × height` rectangle of `density` (kg/m³) at rest, centred
    /// at `centre` and turned by `angle` (rad); returns its index. Its
    /// vertices are numbered from the lower-left corner of the unturned
    /// rectangle, edge 0 being its bottom ([`Polygon::rectangle`]).
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for a non-finite centre or angle,
    /// or a size or density that is not finite and positive.
    pub fn add_rectangle(
        &mut self,
        centre: Point,
        width: f64,
        height: f64,
        angle: f64,
        density: f64,
    ) -> Result<usize> {
        let rectangle = Polygon::rectangle(width, height)?;
        self.add_shape(rectangle, Pose2::new(centre.x, centre.y, angle), density)
    }

    /// Add a body of any shape, at rest at `pose` (the shape's reference
    /// point, its centroid, at the pose's position), with `density`
    /// (kg/m³); returns its index.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for a non-finite pose or a
    /// density that is not finite and positive.
    pub fn add_shape(
        &mut self,
        shape: impl Into<AnyShape2>,
        pose: Pose2,
        density: f64,
    ) -> Result<usize> {
        require_finite("centre x", pose.position.x)?;
        require_finite("centre y", pose.position.y)?;
        require_finite("angle", pose.angle)?;
        require_positive("density", density)?;
        let shape = shape.into();
        let mp = shape.as_shape().mass_properties(density);
        let mut particle = Particle::at_rest(shape, pose.position, mp);
        particle.pose.angle = pose.angle;
        self.particles.push(particle);
        Ok(self.particles.len() - 1)
    }

    /// The particle with index `index`.
    ///
    /// # Errors
    /// [`DismechError::NoSuchBody`] with the index and the particle count
    /// when the scene has no particle `index`.
    pub fn particle(&self, index: usize) -> Result<&Particle> {
        self.particles.get(index).ok_or(DismechError::NoSuchBody {
            index,
            count: self.particles.len(),
        })
    }

    /// Apply the constant external force `force` (N/m) to the centre of
    /// particle `index`, replacing any force set before.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming `external force x` or
    /// `external force y` for a component that is not finite;
    /// [`DismechError::NoSuchBody`] when the scene has no particle `index`.
    pub fn set_external_force(&mut self, index: usize, force: Vec2) -> Result<()> {
        require_finite("external force x", force.x)?;
        require_finite("external force y", force.y)?;
        let count = self.particles.len();
        let particle = self
            .particles
            .get_mut(index)
            .ok_or(DismechError::NoSuchBody { index, count })?;
        particle.external_force = force;
        Ok(())
    }

    /// Total weight `Σ m |g|` of the free (not prescribed) particles (N per
    /// m of thickness).
    pub fn total_weight(&self) -> f64 {
        self.particles
            .iter()
            .filter(|p| !p.is_prescribed())
            .map(|p| p.mass)
            .sum::<f64>()
            * self.gravity.norm()
    }
}
