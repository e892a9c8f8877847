//! Contact of a circle with a polygon (convex or concave).
//!
//! Rules (small overlaps, as for [`super::polygon`]): with the circle's
//! centre outside the polygon, every edge whose foot of the perpendicular
//! from the centre lies on the edge, with the centre in front of it closer
//! than the radius, gives a point (`Edge(k)`); every convex vertex whose
//! region holds the centre (beyond the ends of both its edges) and lies
//! within the radius gives a point (`Vertex(k)`) with the normal along the
//! line from the centre to the vertex. For a convex polygon these regions
//! do not overlap, so there is one point, on the nearest feature; a disc in
//! a notch of a concave polygon touches both edges of the notch and gets
//! two. On an edge the point, overlap, width and normal are those of
//! [`super::circle_segment::contact_circle_segment`] against that edge as a
//! wall; at a vertex the width is the chord the tangent at the nearest
//! point cuts, as at a wall's end. A centre inside the polygon (beyond the
//! small-overlap range) is pushed out through the nearest edge.

use super::{ContactFeatures, ContactGeometry, Feature};
use crate::math::{Point, Pose2, Vec2};
use crate::shape::{Circle, Polygon, Shape2};

/// The geometry of the circle (centre `c`, radius `r`, world) at `distance`
/// from the polygon's surface along `normal` (from the circle into the
/// polygon), mirroring the wall routine.
fn circle_point(
    c: Point,
    r: f64,
    normal: Vec2,
    distance: f64,
    radius_b: f64,
    b: Feature,
) -> ContactGeometry {
    let overlap = r - distance;
    let half_width = (r * r - distance * distance).max(0.0).sqrt();
    ContactGeometry {
        point: c + normal * (distance.max(0.0) + 0.5 * overlap.min(r)),
        normal,
        overlap,
        width: 2.0 * half_width,
        curvature_radius_a: r,
        curvature_radius_b: radius_b,
        features: ContactFeatures {
            a: Feature::Whole,
            b,
        },
    }
}

/// The contact manifold of circle `a` at `pose_a` with polygon `b` at
/// `pose_b`, appended to `out`; normals from the circle into the polygon.
pub fn contact_circle_polygon(
    a: &Circle,
    pose_a: &Pose2,
    b: &Polygon,
    pose_b: &Pose2,
    out: &mut Vec<ContactGeometry>,
) {
    let r = a.radius();
    let c = pose_a.position;
    let local = pose_b.inverse_transform_point(&c);
    let reach = r + b.bounding_radius();
    if local.coords.norm_squared() > reach * reach {
        return;
    }
    let v = b.vertices();
    let n = v.len();
    if b.contains(&local) {
        push_out_through_nearest_edge(b, pose_b, c, r, &local, out);
        return;
    }
    for e in 0..n {
        let (p, q) = (v[e], v[(e + 1) % n]);
        let pq = q - p;
        let t = (local - p).dot(&pq) / pq.norm_squared();
        let m = b.edge_normal(e);
        let distance = (local - p).dot(&m);
        if (0.0..=1.0).contains(&t) && distance >= 0.0 && distance < r {
            let normal = -pose_b.transform_vector(&m);
            out.push(circle_point(
                c,
                r,
                normal,
                distance,
                f64::INFINITY,
                Feature::Edge(e),
            ));
        }
    }
    for k in 0..n {
        if b.is_reflex(k) {
            continue;
        }
        let (prev, here, next) = (v[(k + n - 1) % n], v[k], v[(k + 1) % n]);
        let to_centre = local - here;
        let beyond_both =
            to_centre.dot(&(here - prev)) > 0.0 && to_centre.dot(&(next - here)) < 0.0;
        let distance = to_centre.norm();
        if beyond_both && distance < r && distance > 0.0 {
            let normal = pose_b.transform_vector(&(-to_centre / distance));
            out.push(circle_point(
                c,
                r,
                normal,
                distance,
                0.0,
                Feature::Vertex(k),
            ));
        }
    }
}

/// A centre inside the polygon: one point on the nearest edge, overlap
/// `r − d` with `d < 0` the centre's signed distance to that edge's line.
fn push_out_through_nearest_edge(
    b: &Polygon,
    pose_b: &Pose2,
    c: Point,
    r: f64,
    local: &Point,
    out: &mut Vec<ContactGeometry>,
) {
    let v = b.vertices();
    let n = v.len();
    let nearest = (0..n)
        .map(|e| {
            let (p, q) = (v[e], v[(e + 1) % n]);
            let pq = q - p;
            let t = ((local - p).dot(&pq) / pq.norm_squared()).clamp(0.0, 1.0);
            (e, (local - (p + pq * t)).norm_squared())
        })
        .min_by(|x, y| x.1.total_cmp(&y.1));
    if let Some((e, _)) = nearest {
        let m = b.edge_normal(e);
        let distance = (local - v[e]).dot(&m);
        let normal = -pose_b.transform_vector(&m);
        out.push(circle_point(
            c,
            r,
            normal,
            distance,
            f64::INFINITY,
            Feature::Edge(e),
        ));
    }
}
