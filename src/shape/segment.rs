//! A straight segment: the geometry of a rigid wall, loading plate or frame
//! member.

use super::{MassProperties, Shape, Shape2, ShapeKind};
use crate::math::{Aabb2, Point, Pose2, Vec2};

/// A segment from `start` to `end`, in world coordinates (walls do not move
/// in the DEM; a moving plate carries its own pose).
///
/// The *inner side* of a wall is the left of the direction `start → end`:
/// a frame is drawn counter-clockwise around the material it holds.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Segment {
    /// First end point.
    pub start: Point,
    /// Second end point.
    pub end: Point,
}

impl Segment {
    /// A segment between two points.
    pub fn new(start: Point, end: Point) -> Self {
        Self { start, end }
    }

    /// Length (m).
    pub fn length(&self) -> f64 {
        (self.end - self.start).norm()
    }

    /// Unit vector from `start` to `end`.
    pub fn direction(&self) -> Vec2 {
        (self.end - self.start) / self.length()
    }

    /// Unit normal pointing to the inner (left) side.
    pub fn inner_normal(&self) -> Vec2 {
        crate::math::perp(&self.direction())
    }

    /// The point of the segment closest to `p`.
    pub fn closest_point(&self, p: &Point) -> Point {
        let d = self.end - self.start;
        let len2 = d.norm_squared();
        let t = if len2 > 0.0 {
            ((p - self.start).dot(&d) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        self.start + d * t
    }
}

impl Shape for Segment {
    fn kind(&self) -> ShapeKind {
        ShapeKind::Segment
    }
    fn dimension(&self) -> usize {
        2
    }
    fn measure(&self) -> f64 {
        0.0
    }
    /// A wall has no mass of its own: it is fixed or driven.
    fn mass_properties(&self, _density: f64) -> MassProperties {
        MassProperties {
            mass: 0.0,
            inertia: 0.0,
        }
    }
}

impl Shape2 for Segment {
    /// The bounding box of the segment moved by `pose` (a fixed wall uses
    /// the identity pose).
    fn aabb(&self, pose: &Pose2) -> Aabb2 {
        Aabb2::from_corners(
            pose.transform_point(&self.start),
            pose.transform_point(&self.end),
        )
    }
    fn bounding_radius(&self) -> f64 {
        self.start.coords.norm().max(self.end.coords.norm())
    }
}
