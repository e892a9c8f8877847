//! Contact between a circle and a wall segment.

use super::{ContactFeatures, ContactGeometry};
use crate::math::Pose2;
use crate::shape::{Circle, Segment};

/// The contact of circle `a` at `pose_a` with the fixed wall `wall` (in
/// world coordinates), or `None`.
///
/// A wall is one-sided: material lies on its inner (left) side. Where the
/// circle's centre projects inside the segment, the overlap is measured
/// along the wall's inner normal, so that a particle pushed past the wall
/// line is still pushed back in; beyond the ends, the nearest end point acts
/// as a corner. The normal points from the circle into the wall. The width
/// is the chord the wall line cuts from the circle; the wall's radius of
/// curvature is infinite.
pub fn contact_circle_segment(
    a: &Circle,
    pose_a: &Pose2,
    wall: &Segment,
) -> Option<ContactGeometry> {
    let r = a.radius();
    let c = pose_a.position;
    let length = wall.length();
    if length <= 0.0 {
        return None;
    }
    let direction = wall.direction();
    let t = (c - wall.start).dot(&direction);
    let (normal, distance) = if (0.0..=length).contains(&t) {
        let inner = wall.inner_normal();
        (-inner, (c - wall.start).dot(&inner))
    } else {
        let corner = if t < 0.0 { wall.start } else { wall.end };
        let d = corner - c;
        let distance = d.norm();
        if distance == 0.0 {
            return None;
        }
        (d / distance, distance)
    };
    let overlap = r - distance;
    if overlap <= 0.0 {
        return None;
    }
    let half_width = (r * r - distance * distance).max(0.0).sqrt();
    Some(ContactGeometry {
        point: c + normal * (distance.max(0.0) + 0.5 * overlap.min(r)),
        normal,
        overlap,
        width: 2.0 * half_width,
        curvature_radius_a: r,
        curvature_radius_b: f64::INFINITY,
        features: ContactFeatures::WHOLE,
    })
}
