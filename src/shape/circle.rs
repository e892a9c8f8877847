//! The disc: the particle of the classic DEM and of the rigid-plastic LP.

use super::{MassProperties, Shape, Shape2, ShapeKind};
use crate::error::{require_positive, Result};
use crate::math::{Aabb2, Point, Pose2};

/// A disc of radius `radius` centred on the body's reference point.
/// Serialized as its radius; read back through [`Circle::new`], which
/// refuses a radius that is not finite and positive.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "CircleRecord", into = "CircleRecord")]
pub struct Circle {
    radius: f64,
}

impl Circle {
    /// A circle; the radius must be finite and positive.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`](crate::error::DismechError::InvalidParameter)
    /// naming `radius` when it is not finite and positive.
    pub fn new(radius: f64) -> Result<Self> {
        Ok(Self {
            radius: require_positive("radius", radius)?,
        })
    }

    /// The radius (m).
    pub fn radius(&self) -> f64 {
        self.radius
    }
}

/// A circle as serialized: its radius.
#[derive(serde::Serialize, serde::Deserialize)]
struct CircleRecord {
    radius: f64,
}

impl From<Circle> for CircleRecord {
    fn from(c: Circle) -> Self {
        Self { radius: c.radius }
    }
}

impl TryFrom<CircleRecord> for Circle {
    type Error = crate::error::DismechError;
    fn try_from(record: CircleRecord) -> Result<Self> {
        Self::new(record.radius)
    }
}

impl Shape for Circle {
    fn kind(&self) -> ShapeKind {
        ShapeKind::Circle
    }
    fn dimension(&self) -> usize {
        2
    }
    fn measure(&self) -> f64 {
        std::f64::consts::PI * self.radius * self.radius
    }
    /// `m = ρ π r²`, `I = m r² / 2` (per unit thickness).
    fn mass_properties(&self, density: f64) -> MassProperties {
        let mass = density * self.measure();
        MassProperties {
            mass,
            inertia: 0.5 * mass * self.radius * self.radius,
        }
    }
}

impl Shape2 for Circle {
    fn aabb(&self, pose: &Pose2) -> Aabb2 {
        let c = pose.position;
        let r = self.radius;
        Aabb2 {
            min: Point::new(c.x - r, c.y - r),
            max: Point::new(c.x + r, c.y + r),
        }
    }
    fn bounding_radius(&self) -> f64 {
        self.radius
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circle_rejects_non_positive_or_non_finite_radius() {
        for r in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(Circle::new(r).is_err(), "radius {r} accepted");
        }
    }

    #[test]
    fn circle_mass_properties_are_those_of_a_uniform_disc() {
        let c = Circle::new(0.5).unwrap();
        let mp = c.mass_properties(2.0);
        approx::assert_relative_eq!(mp.mass, 2.0 * std::f64::consts::PI * 0.25);
        approx::assert_relative_eq!(mp.inertia, 0.5 * mp.mass * 0.25);
    }
}
