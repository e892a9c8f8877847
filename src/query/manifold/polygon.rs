//! Contact of two polygons (convex or concave) as a manifold of
//! vertex-in-polygon points, and the pieces the other polygon pairs share.
//!
//! # Rules
//! * **Which points.** Every convex vertex of A that lies inside B gives a
//!   point against the edge of B it has penetrated, and every convex vertex
//!   of B inside A one against the edge of A. A face pressed on a face thus
//!   gives two points, one at each end of the overlap (each end is a vertex
//!   of one body or the other). Reflex vertices (interior angle above 180°)
//!   give no point of their own: they cannot enter a face, and the faces
//!   that meet there are reached by the other body's vertices.
//! * **Which edge.** A vertex enters a face from outside, so both of its
//!   sides leave the face outward: the candidate edges of the other polygon
//!   are those whose outward normal `m` makes `d·m ≥ −`[`WEDGE_TOLERANCE`]
//!   with the unit directions `d` of both sides of the vertex. Among them the
//!   edge nearest to the vertex (distance to the segment) is the penetrated
//!   one. This keeps the face of a block stacked on an aligned block even
//!   when a corner lies within the overlap of the side face. When the
//!   nearest point is a reflex vertex of the other polygon (a corner pressed
//!   into a notch), the vertex touches both edges that meet there and gives
//!   one point on each.
//! * **Normal, overlap, point.** The normal is the penetrated edge's outward
//!   normal, oriented from A into B; the overlap is the vertex's depth
//!   behind the edge's line; the point is halfway between the vertex and its
//!   projection on that line. Contact width 0; the vertex's radius of
//!   curvature is 0 and the edge's infinite.
//! * **Coincident vertex pairs.** When a vertex `i` of A inside B and a
//!   vertex `k` of B inside A each lie on an edge ending at the other and
//!   their points are closer than the larger overlap (aligned faces whose
//!   ends coincide, or two corners meeting), they are one contact: one point
//!   with features `(Vertex(i), Vertex(k))`, at the mean point, with the
//!   mean overlap and the mean of the two normals.
//! * **Small overlaps.** The rules assume that the penetration is smaller
//!   than the smallest feature of either body (edge length, notch size): a
//!   vertex deeper than that may be referred to the wrong edge. The explicit
//!   DEM's stiff contacts keep overlaps well below that.
//! * **Symmetry.** Each half (A's vertices in B, B's in A) is computed by the
//!   same function with the roles exchanged, so swapping A and B gives the
//!   same points with flipped normals and swapped features.

use super::{ContactFeatures, ContactGeometry, Feature};
use crate::math::{rotate, Point, Pose2, Vec2};
use crate::shape::{Polygon, Shape2};

/// How far (as `d·m`, the cosine of the angle to the face plus 90°) a side
/// of a vertex may turn back into a face it has entered: sides of two faces
/// pressed together are nearly parallel, and either may lean slightly into
/// the other. `0.1` allows a tilt of about 5.7°.
pub const WEDGE_TOLERANCE: f64 = 0.1;

/// How far outside a polygon (relative to its bounding radius) a vertex may
/// lie and still count as inside: a vertex exactly on a side edge (the
/// corners of aligned faces) must not fall out by rounding.
pub const CONTAINMENT_TOLERANCE: f64 = 1e-9;

/// Whether the body-frame point `p` lies in `q` or within
/// [`CONTAINMENT_TOLERANCE`] of its boundary, or within `margin` of it.
fn inside_or_on(q: &Polygon, p: &Point, margin: f64) -> bool {
    let reach = q.bounding_radius();
    let tolerance = (CONTAINMENT_TOLERANCE * reach).max(margin);
    let outer = (reach * (1.0 + CONTAINMENT_TOLERANCE)).max(reach + margin);
    if p.coords.norm_squared() > outer.powi(2) {
        return false;
    }
    if q.contains(p) {
        return true;
    }
    let v = q.vertices();
    let n = v.len();
    (0..n).any(|e| {
        let ab = v[(e + 1) % n] - v[e];
        let t = ((p - v[e]).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
        (p - (v[e] + ab * t)).norm_squared() <= tolerance * tolerance
    })
}

/// A corner of one body seen in the frame of a polygon: its position and
/// the unit directions along its two sides, away from the corner.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Corner {
    pub point: Point,
    pub sides: [Vec2; 2],
}

/// The edges of `q` that the corner `c` (in `q`'s frame) has penetrated,
/// with the corner's depth behind each edge's line: none when the corner is
/// outside (a corner on the boundary, within [`CONTAINMENT_TOLERANCE`],
/// counts as inside), one as a rule, two when the corner presses into a reflex vertex
/// of `q` (see the module docs). With a `margin` above zero, a corner
/// outside `q` by at most `margin` counts too, with its (negative) depth.
pub(crate) fn penetrated_edges(q: &Polygon, c: &Corner, margin: f64) -> [Option<(usize, f64)>; 2] {
    let mut found = [None, None];
    let p = c.point;
    if !inside_or_on(q, &p, margin) {
        return found;
    }
    let vertices = q.vertices();
    let n = vertices.len();
    let faces = |e: usize| {
        let m = q.edge_normal(e);
        c.sides[0].dot(&m) >= -WEDGE_TOLERANCE && c.sides[1].dot(&m) >= -WEDGE_TOLERANCE
    };
    let depth = |e: usize| -(p - vertices[e]).dot(&q.edge_normal(e));
    // Nearest candidate edge, and which end (if any) its nearest point is.
    let mut best: Option<(usize, f64, Option<usize>)> = None;
    for e in 0..n {
        if !faces(e) {
            continue;
        }
        let (a, b) = (vertices[e], vertices[(e + 1) % n]);
        let ab = b - a;
        let t = (p - a).dot(&ab) / ab.norm_squared();
        let (foot, end) = if t <= 0.0 {
            (a, Some(e))
        } else if t >= 1.0 {
            (b, Some((e + 1) % n))
        } else {
            (a + ab * t, None)
        };
        let distance2 = (p - foot).norm_squared();
        if best.is_none_or(|(_, d2, _)| distance2 < d2) {
            best = Some((e, distance2, end));
        }
    }
    let Some((e, _, end)) = best else {
        return found;
    };
    let d = depth(e);
    if d > -margin {
        found[0] = Some((e, d));
    }
    if let Some(w) = end.filter(|&w| q.is_reflex(w)) {
        // The other edge meeting at the reflex vertex w.
        let other = if w == e { (e + n - 1) % n } else { w };
        let d = depth(other);
        if faces(other) && d > -margin {
            found[1] = Some((other, d));
        }
    }
    found
}

/// The unit directions from vertex `k` of `p` along its two sides (body
/// frame).
pub(crate) fn vertex_sides(p: &Polygon, k: usize) -> [Vec2; 2] {
    let v = p.vertices();
    let n = v.len();
    let here = v[k];
    [
        (v[(k + 1) % n] - here).normalize(),
        (v[(k + n - 1) % n] - here).normalize(),
    ]
}

/// A vertex-on-edge point: `vertex` (world) at `depth` behind the edge
/// whose outward normal is `m` (world); normal from the vertex's body into
/// the edge's body.
pub(crate) fn vertex_on_edge(
    vertex: Point,
    m: Vec2,
    depth: f64,
    features: ContactFeatures,
) -> ContactGeometry {
    ContactGeometry {
        point: vertex + m * (0.5 * depth),
        normal: -m,
        overlap: depth,
        width: 0.0,
        curvature_radius_a: 0.0,
        curvature_radius_b: f64::INFINITY,
        features,
    }
}

/// Appends the points of the convex vertices of `p` inside `q`, with the
/// normal from `p` into `q` (flipped to `q` into `p` if `flip`).
fn vertices_in_polygon(
    p: &Polygon,
    pose_p: &Pose2,
    q: &Polygon,
    pose_q: &Pose2,
    flip: bool,
    margin: f64,
    out: &mut Vec<ContactGeometry>,
) {
    let turn = pose_p.angle - pose_q.angle;
    for (i, v) in p.vertices().iter().enumerate() {
        if p.is_reflex(i) {
            continue;
        }
        let world = pose_p.transform_point(v);
        let sides = vertex_sides(p, i);
        let corner = Corner {
            point: pose_q.inverse_transform_point(&world),
            sides: [rotate(&sides[0], turn), rotate(&sides[1], turn)],
        };
        for (e, depth) in penetrated_edges(q, &corner, margin).into_iter().flatten() {
            let m = pose_q.transform_vector(&q.edge_normal(e));
            let features = ContactFeatures {
                a: Feature::Vertex(i),
                b: Feature::Edge(e),
            };
            let g = vertex_on_edge(world, m, depth, features);
            out.push(if flip { g.flipped() } else { g });
        }
    }
}

/// The contact manifold of polygon `a` at `pose_a` with polygon `b` at
/// `pose_b`, appended to `out` (see the module docs for the rules); normals
/// from A into B. Allocates nothing once `out` has room.
pub fn contact_polygon_polygon(
    a: &Polygon,
    pose_a: &Pose2,
    b: &Polygon,
    pose_b: &Pose2,
    out: &mut Vec<ContactGeometry>,
) {
    contact_polygon_polygon_within(a, pose_a, b, pose_b, 0.0, out);
}

/// [`contact_polygon_polygon`] with the polygons counted as touching where
/// they are apart by at most `margin` (m): a vertex outside the other
/// polygon by up to `margin` gives a point with a negative overlap (its
/// gap), and points of a coincident vertex pair closer than `margin` are
/// merged. With `margin` = 0 it is [`contact_polygon_polygon`]. A limit
/// analysis takes the faces of blocks cut to fit (an arch's voussoirs,
/// whose corners coincide to rounding) as touching this way.
pub fn contact_polygon_polygon_within(
    a: &Polygon,
    pose_a: &Pose2,
    b: &Polygon,
    pose_b: &Pose2,
    margin: f64,
    out: &mut Vec<ContactGeometry>,
) {
    let reach = a.bounding_radius() + b.bounding_radius() + margin;
    if (pose_b.position - pose_a.position).norm_squared() > reach * reach {
        return;
    }
    let start = out.len();
    vertices_in_polygon(a, pose_a, b, pose_b, false, margin, out);
    vertices_in_polygon(b, pose_b, a, pose_a, true, margin, out);
    merge_coincident(out, start, a.vertices().len(), b.vertices().len(), margin);
}

/// Merges, among the points from `out[start..]`, each vertex of A on an
/// edge of B with a vertex of B on an edge of A when each vertex ends the
/// other's edge and the points are closer than the larger overlap (see the
/// module docs), or than `margin`. `na`, `nb`: vertex counts of A and B (2
/// for a wall).
pub(crate) fn merge_coincident(
    out: &mut Vec<ContactGeometry>,
    start: usize,
    na: usize,
    nb: usize,
    margin: f64,
) {
    let ends = |edge: usize, n: usize, vertex: usize| vertex == edge || vertex == (edge + 1) % n;
    let mut x = start;
    while x < out.len() {
        let (Feature::Vertex(i), Feature::Edge(e)) = (out[x].features.a, out[x].features.b) else {
            x += 1;
            continue;
        };
        let partner = (start..out.len()).find(|&y| {
            let (Feature::Edge(f), Feature::Vertex(k)) = (out[y].features.a, out[y].features.b)
            else {
                return false;
            };
            ends(e, nb, k)
                && ends(f, na, i)
                && (out[x].point - out[y].point).norm()
                    <= out[x].overlap.max(out[y].overlap).max(margin)
        });
        if let Some(y) = partner {
            let (gx, gy) = (out[x], out[y]);
            let Feature::Vertex(k) = gy.features.b else {
                unreachable!("the partner was matched on a vertex of B")
            };
            let sum = gx.normal + gy.normal;
            out[x] = ContactGeometry {
                point: Point::from(0.5 * (gx.point.coords + gy.point.coords)),
                normal: sum.try_normalize(0.0).unwrap_or(gx.normal),
                overlap: 0.5 * (gx.overlap + gy.overlap),
                width: 0.0,
                curvature_radius_a: 0.0,
                curvature_radius_b: 0.0,
                features: ContactFeatures {
                    a: Feature::Vertex(i),
                    b: Feature::Vertex(k),
                },
            };
            out.remove(y);
            if y < x {
                x -= 1;
            }
        }
        x += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn square(side: f64) -> Polygon {
        Polygon::rectangle(side, side).unwrap()
    }

    #[test]
    fn corner_in_a_square_is_referred_to_the_face_it_entered() {
        let q = square(1.0);
        // A corner pointing down, just inside the top face near the left
        // side: the side face is nearer but faces away.
        let c = Corner {
            point: Point::new(-0.499, 0.49),
            sides: [Vec2::new(1.0, 0.0), Vec2::new(0.0, 1.0)],
        };
        let [first, second] = penetrated_edges(&q, &c, 0.0);
        let (e, depth) = first.unwrap();
        assert_eq!(e, 2, "top edge");
        assert_relative_eq!(depth, 0.01, epsilon = 1e-12);
        assert!(second.is_none());
    }

    #[test]
    fn corner_outside_penetrates_nothing() {
        let c = Corner {
            point: Point::new(0.6, 0.0),
            sides: [Vec2::new(1.0, 0.0), Vec2::new(0.0, 1.0)],
        };
        assert_eq!(penetrated_edges(&square(1.0), &c, 0.0), [None, None]);
    }
}
