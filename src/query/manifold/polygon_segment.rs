//! Contact of a polygon with a fixed one-sided wall.
//!
//! As for a circle ([`super::circle_segment`]), the wall is one-sided
//! (material on its left) and its line counts within its extent while
//! beyond its ends the end points act as corners:
//! * every convex vertex of the polygon that projects onto the wall and lies
//!   behind its line gives a point (`Vertex(k)` on the wall's `Edge(0)`),
//!   however deep, so that a body pushed past the line is pushed back; the
//!   normal is the wall's outward normal (from the polygon into the wall);
//! * each end of the wall (`Vertex(0)` = start, `Vertex(1)` = end) that lies
//!   inside the polygon acts as a corner whose side runs back along the wall,
//!   and gives a point against the polygon's edge it has penetrated, by the
//!   rules of [`super::polygon`] (normal = that edge's outward normal).
//!
//! A face resting on the wall thus gives two points, at its two vertices,
//! or at one vertex and the wall's end where the face overhangs the end. A
//! vertex and a wall end that make the same contact (the polygon's corner on
//! the wall's end) merge into one point, as in [`super::polygon`]. The
//! points are halfway between the penetrating vertex and its projection;
//! contact width 0, radii 0 at a vertex and infinite on an edge or the wall.

use super::polygon::{merge_coincident, penetrated_edges, vertex_on_edge, Corner};
use super::{ContactFeatures, ContactGeometry, Feature};
use crate::math::{perp, Pose2};
use crate::shape::{Polygon, Segment, Shape2};

/// The contact manifold of polygon `a` at `pose_a` with the fixed wall
/// `wall` (world coordinates), appended to `out`; normals from the polygon
/// into the wall.
pub fn contact_polygon_segment(
    a: &Polygon,
    pose_a: &Pose2,
    wall: &Segment,
    out: &mut Vec<ContactGeometry>,
) {
    let length = wall.length();
    if length <= 0.0 {
        return;
    }
    let reach = a.bounding_radius();
    if (wall.closest_point(&pose_a.position) - pose_a.position).norm_squared() > reach * reach {
        return;
    }
    let start = out.len();
    let direction = wall.direction();
    let inner = perp(&direction);
    for (k, v) in a.vertices().iter().enumerate() {
        if a.is_reflex(k) {
            continue;
        }
        let w = pose_a.transform_point(v);
        let along = (w - wall.start).dot(&direction);
        let depth = -(w - wall.start).dot(&inner);
        if (0.0..=length).contains(&along) && depth > 0.0 {
            let features = ContactFeatures {
                a: Feature::Vertex(k),
                b: Feature::Edge(0),
            };
            out.push(vertex_on_edge(w, inner, depth, features));
        }
    }
    for (k, end, side) in [(0, wall.start, direction), (1, wall.end, -direction)] {
        let side = pose_a.inverse_transform_vector(&side);
        let corner = Corner {
            point: pose_a.inverse_transform_point(&end),
            sides: [side, side],
        };
        for (e, depth) in penetrated_edges(a, &corner, 0.0).into_iter().flatten() {
            let m = pose_a.transform_vector(&a.edge_normal(e));
            let features = ContactFeatures {
                a: Feature::Vertex(k),
                b: Feature::Edge(e),
            };
            out.push(vertex_on_edge(end, m, depth, features).flipped());
        }
    }
    merge_coincident(out, start, a.vertices().len(), 2, 0.0);
}
