//! Contact of an ellipse with a polygon (convex or concave).
//!
//! Rules (small overlaps, as for [`super::polygon`]):
//! * **Edges.** An edge whose line has the ellipse's centre in front of it
//!   and whose deepest point of the ellipse beyond the line projects onto
//!   the edge gives a point (`Edge(k)`): the ellipse–wall contact of
//!   [`super::ellipse::contact_ellipse_segment`] against the edge (overlap =
//!   depth of the deepest point, normal = the edge's normal, radius of the
//!   ellipse at the deepest point), with the chord P1P2 clipped to the edge
//!   (so that its midpoint, the contact point, stays on the edge). On an
//!   edge longer than the chord this is exactly the ellipse–wall contact.
//! * **Corners.** A convex vertex inside the ellipse gives a point
//!   (`Vertex(k)`) when the normal of the ellipse at its nearest boundary
//!   point lies strictly between the normals of the vertex's two edges: the
//!   overlap is the distance to that nearest point, the normal is the
//!   ellipse's normal there, the point is halfway. Where that normal reaches
//!   an edge's normal, the deepest point of the ellipse beyond that edge
//!   reaches the edge's end and the edge rule takes over with the same depth.
//! * A centre inside the polygon (beyond the small-overlap range) is pushed
//!   out through the nearest edge.

use super::ellipse::ellipse_line;
use super::{ContactFeatures, ContactGeometry, Feature};
use crate::math::{cross, Point, Pose2};
use crate::shape::{Ellipse, Polygon, Shape2};

/// The edge `k` of `b` (world end points `p → q`) as a wall for the
/// ellipse, or `None`; `front`: require the ellipse's centre in front of it
/// and its deepest point over the edge.
fn edge_point(
    a: &Ellipse,
    pose_a: &Pose2,
    p: Point,
    q: Point,
    k: usize,
    front: bool,
) -> Option<ContactGeometry> {
    // The outer side of a counter-clockwise edge p → q is the left of q → p.
    let length = (p - q).norm();
    let direction = (p - q) / length;
    let line = ellipse_line(a, pose_a, &q, &direction)?;
    if front {
        let deepest = pose_a.transform_point(&line.deepest_local);
        let along = (deepest - q).dot(&direction);
        if line.distance <= 0.0 || !(0.0..=length).contains(&along) {
            return None;
        }
    }
    let (s1, s2) = (line.crossings.0.max(0.0), line.crossings.1.min(length));
    let mut g = line.geometry(a, &q, &direction, 0.5 * (s1 + s2), (s2 - s1).max(0.0));
    g.features = ContactFeatures {
        a: Feature::Whole,
        b: Feature::Edge(k),
    };
    Some(g)
}

/// The contact manifold of ellipse `a` at `pose_a` with polygon `b` at
/// `pose_b`, appended to `out`; normals from the ellipse into the polygon.
pub fn contact_ellipse_polygon(
    a: &Ellipse,
    pose_a: &Pose2,
    b: &Polygon,
    pose_b: &Pose2,
    out: &mut Vec<ContactGeometry>,
) {
    let reach = a.a() + b.bounding_radius();
    if (pose_b.position - pose_a.position).norm_squared() > reach * reach {
        return;
    }
    let v = b.vertices();
    let n = v.len();
    let world = |k: usize| pose_b.transform_point(&v[k % n]);
    let centre = pose_b.inverse_transform_point(&pose_a.position);
    if b.contains(&centre) {
        let nearest = (0..n)
            .map(|e| {
                let pq = v[(e + 1) % n] - v[e];
                let t = ((centre - v[e]).dot(&pq) / pq.norm_squared()).clamp(0.0, 1.0);
                (e, (centre - (v[e] + pq * t)).norm_squared())
            })
            .min_by(|x, y| x.1.total_cmp(&y.1));
        if let Some((e, _)) = nearest {
            out.extend(edge_point(a, pose_a, world(e), world(e + 1), e, false));
        }
        return;
    }
    for e in 0..n {
        out.extend(edge_point(a, pose_a, world(e), world(e + 1), e, true));
    }
    for k in 0..n {
        if b.is_reflex(k) {
            continue;
        }
        let corner = world(k);
        let local = pose_a.inverse_transform_point(&corner);
        if (local.x / a.a()).powi(2) + (local.y / a.b()).powi(2) >= 1.0 {
            continue;
        }
        let nearest = a.closest_boundary_point(&local);
        let normal = pose_a.transform_vector(&a.outward_normal(&nearest));
        let m_prev = pose_b.transform_vector(&b.edge_normal((k + n - 1) % n));
        let m_next = pose_b.transform_vector(&b.edge_normal(k));
        if !(cross(&m_prev, &(-normal)) > 0.0 && cross(&(-normal), &m_next) > 0.0) {
            continue;
        }
        let on_ellipse = pose_a.transform_point(&nearest);
        out.push(ContactGeometry {
            point: Point::from(0.5 * (corner.coords + on_ellipse.coords)),
            normal,
            overlap: (on_ellipse - corner).norm(),
            width: 0.0,
            curvature_radius_a: a.curvature_radius_at(&nearest),
            curvature_radius_b: 0.0,
            features: ContactFeatures {
                a: Feature::Whole,
                b: Feature::Vertex(k),
            },
        });
    }
}
