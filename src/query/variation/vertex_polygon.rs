//! Which edges of a polygon B a vertex of polygon A meets in a step: the
//! choice of classic DDA (Shi 1988, ch. 4: the previous step's edge, else
//! the shortest way out) made safe at the corners that blocks cut from
//! joint sets always share.
//!
//! The rules are given at [`entrance_edges`].

use smallvec::SmallVec;

use super::VertexEdgeContact;
use crate::kinematics::PlacedPolygon;
use crate::math::{Point, Vec2};

/// How far (as the sine of the angle) an edge of A may point to the
/// inner side of B's edge line for that line still to separate A's angle
/// from B: blocks that rest flush on each other turn by far less.
pub const SEPARATION_TOLERANCE: f64 = 1e-3;

/// A polygon's vertex with the two edges that meet there, as the choice
/// of a contact edge at a corner reads it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PolygonCorner {
    /// The vertex (world).
    pub point: Point,
    /// Unit directions from the vertex along its two edges, towards the
    /// previous and the next vertex.
    pub edges: [Vec2; 2],
    /// Whether the interior angle exceeds 180°.
    pub reflex: bool,
}

impl PolygonCorner {
    /// Vertex `k` of `polygon`.
    pub fn of(polygon: &PlacedPolygon, k: usize) -> Self {
        let count = polygon.vertex_count();
        let point = polygon.vertex(k);
        let before = polygon.vertex(k + count - 1) - point;
        let after = polygon.vertex(k + 1) - point;
        Self {
            point,
            edges: [before.normalize(), after.normalize()],
            reflex: polygon.polygon().is_reflex(k % count),
        }
    }

    /// Whether the line through an edge of outward unit normal `normal`
    /// leaves this corner's angle on its outer side.
    fn outside_of(&self, normal: &Vec2) -> bool {
        !self.reflex
            && self
                .edges
                .iter()
                .all(|u| u.dot(normal) >= -SEPARATION_TOLERANCE)
    }
}

/// The edges of `polygon` (body B) that the corner `vertex` of body A
/// (reference point `reference_a`) meets in a step of search distance
/// `search`; `previous` is the edge it met in the previous step. Each
/// comes with the edge index (edge k runs from vertex k to k + 1). At most
/// two: two only at a reflex corner of B.
///
/// A vertex P₁ of A meets edge k of B when the foot of its perpendicular
/// lies on the edge ([`VertexEdgeContact::foot_on_edge`]) and `|g_n|` is
/// within the search distance. Three rules then settle the cases that
/// "largest `g_n`" alone gets wrong:
///
/// 1. **Outside, no negative gap.** A vertex that lies outside B, further
///    than ε = [`BEHIND_TOLERANCE`] × the search distance from it, meets
///    no edge from behind (`g_n < 0`): the perpendicular of such a pair
///    crosses B's material, so the pair is not a contact. (A vertex level
///    with the top of a narrow block beside it lies in the strip of the
///    block's far side, `g_n` = minus the distance to it: with a search
///    distance as large as the block, "largest `g_n`" made that a contact
///    and flung the block.)
/// 2. **Corners: the entrance line.** Where P₁ lies within the search
///    distance of a convex corner C of B and meets both edges at C, it
///    meets only the edges whose line separates A's angle at P₁ from B
///    (A's two edges at P₁ point to the outer side of the line, to within
///    [`SEPARATION_TOLERANCE`]): the edge A would have to cross to enter
///    B. A block resting flush on another with their corners coinciding
///    has its corner on the other's top edge *and* on the line of its side
///    edge (`g_n` = 0 there while the top edge's `g_n` < 0 under load),
///    and "largest `g_n`" takes the side edge, which carries no load, so
///    the block sinks through. Where neither edge at C separates (A's
///    angle is reflex, or it straddles C), one of A's edges at P₁ does
///    (two convex angles that do not overlap always have a separating
///    line among their four edges): the contact is B's corner against
///    that edge, found from B's side, and P₁ meets neither edge at C.
/// 3. **Reflex corners: both edges.** A vertex in a reflex corner of B (a
///    notch) meets both of its edges (those of the reflex corner nearest
///    it, in a slot narrower than the search distance).
///
/// Among what remains, the edge of the previous step is kept if it is
/// still met (the contact keeps its shear history), else the one with
/// the largest `g_n` (Shi's shortest path: the shallowest penetration).
pub fn entrance_edges(
    vertex: &PolygonCorner,
    reference_a: Point,
    polygon: &PlacedPolygon,
    search: f64,
    previous: Option<usize>,
) -> SmallVec<[(usize, VertexEdgeContact); 2]> {
    let count = polygon.vertex_count();
    let centroid = polygon.centroid();
    let p = vertex.point;
    // Whether P₁ lies in B or within the tolerance of its boundary.
    let near = BEHIND_TOLERANCE * search;
    let touches = polygon.polygon().contains(&Point::from(p - centroid))
        || (0..count).any(|e| {
            let (x2, x3) = (polygon.vertex(e), polygon.vertex(e + 1));
            let (a, b) = (p - x2, x3 - x2);
            let t = (a.dot(&b) / b.norm_squared()).clamp(0.0, 1.0);
            (a - b * t).norm() <= near
        });
    let mut met: SmallVec<[Option<VertexEdgeContact>; 8]> = (0..count)
        .map(|e| {
            let edge = [polygon.vertex(e), polygon.vertex(e + 1)];
            let c = VertexEdgeContact::new(p, reference_a, edge, centroid);
            let gap = c.initial_gap;
            let from_behind = !touches && gap < 0.0;
            (c.foot_on_edge() && gap.abs() <= search && !from_behind).then_some(c)
        })
        .collect();
    // Corners met from both of their edges, each judged on the edges as
    // met before any corner dropped one (a short edge between two corners
    // must be tested at both), and the reflex one nearest P₁.
    let original = met.clone();
    let mut nearest_reflex: Option<(usize, f64)> = None;
    for k in 0..count {
        let (before, after) = ((k + count - 1) % count, k);
        let (Some(cb), Some(ca)) = (&original[before], &original[after]) else {
            continue;
        };
        let distance = (p - polygon.vertex(k)).norm();
        if distance > search {
            continue;
        }
        if polygon.polygon().is_reflex(k) {
            if nearest_reflex.is_none_or(|(_, d)| distance < d) {
                nearest_reflex = Some((k, distance));
            }
            continue;
        }
        let normal = |c: &VertexEdgeContact| {
            let b = c.edge[1] - c.edge[0];
            Vec2::new(b.y, -b.x).normalize()
        };
        if !vertex.outside_of(&normal(cb)) {
            met[before] = None;
        }
        if !vertex.outside_of(&normal(ca)) {
            met[after] = None;
        }
    }
    let mut out = SmallVec::new();
    if let Some((k, _)) = nearest_reflex {
        let (before, after) = ((k + count - 1) % count, k);
        if let (Some(cb), Some(ca)) = (met[before], met[after]) {
            out.push((before, cb));
            out.push((after, ca));
            return out;
        }
    }
    let chosen = previous
        .filter(|&e| e < count && met[e].is_some())
        .or_else(|| {
            (0..count).filter(|&e| met[e].is_some()).max_by(|&x, &y| {
                let gap = |e: usize| met[e].map_or(f64::NEG_INFINITY, |c| c.initial_gap);
                // The first of equal gaps, as a scan keeping the
                // strictly larger would.
                gap(x).total_cmp(&gap(y)).then(y.cmp(&x))
            })
        });
    if let Some(e) = chosen {
        if let Some(c) = met[e] {
            out.push((e, c));
        }
    }
    out
}

/// How far outside a polygon (as a fraction of the search distance) a
/// vertex may lie and still meet its edges from behind: a corner pressed
/// into the other block's edge by the penalty's compliance while it
/// drifted off that block's side by as little, or sinking along the line
/// of its side.
pub const BEHIND_TOLERANCE: f64 = 1e-3;

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> PlacedPolygon {
        PlacedPolygon::from_world(
            &[
                Point::new(x0, y0),
                Point::new(x1, y0),
                Point::new(x1, y1),
                Point::new(x0, y1),
            ],
            0,
        )
        .unwrap()
    }

    /// A block resting flush on another, corners coinciding: its lower
    /// corners meet the top edge of the lower block (edge 2), not the
    /// side edges through the same points, at rest and pressed in.
    #[test]
    fn a_flush_corner_meets_the_top_edge_not_the_side() {
        let lower = rect(0.0, 0.0, 0.4, 0.2);
        for sink in [0.0, 1e-7, 1e-4] {
            let upper = rect(0.0, 0.2 - sink, 0.4, 0.4 - sink);
            for k in [0, 1] {
                let corner = PolygonCorner::of(&upper, k);
                let met = entrance_edges(&corner, upper.centroid(), &lower, 0.01, None);
                assert_eq!(met.len(), 1, "sink {sink}, corner {k}");
                assert_eq!(met[0].0, 2, "sink {sink}, corner {k}");
                assert!((met[0].1.initial_gap + sink).abs() < 1e-12);
            }
            // And the lower block's top corners meet the upper's bottom
            // edge (edge 0).
            for k in [2, 3] {
                let corner = PolygonCorner::of(&lower, k);
                let met = entrance_edges(&corner, lower.centroid(), &upper, 0.01, None);
                assert_eq!(met.len(), 1);
                assert_eq!(met[0].0, 0, "sink {sink}, corner {k}");
            }
        }
    }

    /// Even with the previous step's edge the side edge, a corner that the
    /// side's line does not separate from the block no longer meets it.
    #[test]
    fn a_wrong_previous_edge_at_a_corner_is_not_kept() {
        let lower = rect(0.0, 0.0, 0.4, 0.2);
        let upper = rect(0.0, 0.2 - 1e-6, 0.4, 0.4 - 1e-6);
        let corner = PolygonCorner::of(&upper, 0);
        let met = entrance_edges(&corner, upper.centroid(), &lower, 0.01, Some(3));
        assert_eq!(met.iter().map(|m| m.0).collect::<Vec<_>>(), vec![2]);
    }

    /// A corner a round-off past the end of the edge it rests on still
    /// meets it.
    #[test]
    fn a_corner_a_round_off_past_the_end_still_meets_the_edge() {
        let lower = rect(0.0, 0.0, 0.4, 0.2);
        let upper = rect(-1e-12, 0.2 - 1e-7, 0.4 - 1e-12, 0.4 - 1e-7);
        let corner = PolygonCorner::of(&upper, 0);
        let local = Point::from(corner.point - lower.centroid());
        assert!(!lower.polygon().contains(&local));
        let met = entrance_edges(&corner, upper.centroid(), &lower, 0.01, None);
        assert_eq!(met.iter().map(|m| m.0).collect::<Vec<_>>(), vec![2]);
    }

    /// A vertex outside a block does not meet an edge from behind, however
    /// large the search distance: here the only edge whose strip holds the
    /// vertex is the far side of a narrow block, 0.2 m behind.
    #[test]
    fn a_vertex_outside_meets_no_edge_from_behind() {
        let block = PlacedPolygon::from_world(
            &[
                Point::new(0.7, 0.0),
                Point::new(0.8, 0.0),
                Point::new(0.8, 0.25),
                Point::new(0.7, 0.15),
            ],
            0,
        )
        .unwrap();
        let other = rect(0.4, 0.2, 0.6, 0.4);
        let corner = PolygonCorner::of(&other, 1);
        assert_eq!(corner.point, Point::new(0.6, 0.2));
        let far = VertexEdgeContact::detect(
            corner.point,
            other.centroid(),
            [block.vertex(1), block.vertex(2)],
            block.centroid(),
            0.5,
        )
        .expect("the far edge's strip holds the vertex");
        assert!((far.initial_gap + 0.2).abs() < 1e-12);
        let met = entrance_edges(&corner, other.centroid(), &block, 0.5, None);
        assert!(met.is_empty(), "{met:?}");
    }

    /// Where the upper block's corner sits on the meeting point of two
    /// lower blocks, it meets the top of the block beneath it, and the
    /// other block only by the line between them (no load as it sinks).
    #[test]
    fn a_corner_over_a_head_joint_bears_on_the_block_beneath() {
        let left = rect(0.0, 0.0, 0.4, 0.2);
        let right = rect(0.4, 0.0, 0.8, 0.2);
        let upper = rect(0.4, 0.2 - 1e-7, 0.8, 0.4 - 1e-7);
        let corner = PolygonCorner::of(&upper, 0);
        let on_right = entrance_edges(&corner, upper.centroid(), &right, 0.01, None);
        assert_eq!(on_right.iter().map(|m| m.0).collect::<Vec<_>>(), vec![2]);
        let on_left = entrance_edges(&corner, upper.centroid(), &left, 0.01, None);
        assert_eq!(on_left.len(), 1);
        assert_eq!(on_left[0].0, 1);
        assert!(on_left[0].1.initial_gap.abs() < 1e-15);
    }

    /// A vertex in a notch (a reflex corner of B) meets both edges.
    #[test]
    fn a_vertex_in_a_notch_meets_both_edges() {
        // An L: the notch corner is at (0.2, 0.2).
        let l = PlacedPolygon::from_world(
            &[
                Point::new(0.0, 0.0),
                Point::new(0.6, 0.0),
                Point::new(0.6, 0.2),
                Point::new(0.2, 0.2),
                Point::new(0.2, 0.6),
                Point::new(0.0, 0.6),
            ],
            0,
        )
        .unwrap();
        let block = rect(0.2, 0.2, 0.4, 0.4);
        let corner = PolygonCorner::of(&block, 0);
        let met = entrance_edges(&corner, block.centroid(), &l, 0.01, None);
        let mut edges: Vec<usize> = met.iter().map(|m| m.0).collect();
        edges.sort_unstable();
        assert_eq!(edges, vec![2, 3]);
    }

    /// A corner that neither edge at B's corner separates (A's angle
    /// straddles the corner) meets neither; B's corner then meets A's
    /// edge.
    #[test]
    fn a_straddling_corner_leaves_the_contact_to_the_other_side() {
        let lower = rect(0.0, 0.0, 0.4, 0.2);
        // A triangle with its vertex on the lower block's top-left corner,
        // its angle reaching over the top (+x) and down the left side.
        let a = PlacedPolygon::from_world(
            &[
                Point::new(0.0, 0.2),
                Point::new(0.3, 0.5),
                Point::new(-0.3, 0.1),
            ],
            1,
        )
        .unwrap();
        let corner = PolygonCorner::of(&a, 0);
        assert!(entrance_edges(&corner, a.centroid(), &lower, 0.01, None).is_empty());
        let from_b = PolygonCorner::of(&lower, 3);
        let met = entrance_edges(&from_b, lower.centroid(), &a, 0.01, None);
        assert_eq!(met.len(), 1, "{met:?}");
        // Both of A's edges at the vertex separate the angles; the first of
        // their equal (zero) gaps is taken: edge 0, from (0, 0.2).
        assert_eq!(met[0].0, 0);
        assert!(met[0].1.initial_gap.abs() < 1e-15);
    }

    /// A short (chamfer) edge between two corners: the corner rule is
    /// applied at both, so a block's corner pressed into the top near the
    /// chamfer meets the top, not the side beyond the chamfer.
    #[test]
    fn a_chamfer_does_not_let_a_side_edge_through() {
        let chamfered = PlacedPolygon::from_world(
            &[
                Point::new(0.0, 0.0),
                Point::new(0.4, 0.0),
                Point::new(0.4, 0.2),
                Point::new(0.001, 0.2),
                Point::new(0.0, 0.199),
            ],
            0,
        )
        .unwrap();
        let upper = rect(0.00101, 0.1985, 0.4, 0.4);
        let corner = PolygonCorner::of(&upper, 0);
        let met = entrance_edges(&corner, upper.centroid(), &chamfered, 0.01, None);
        assert_eq!(
            met.iter().map(|m| m.0).collect::<Vec<_>>(),
            vec![2],
            "{met:?}"
        );
    }

    /// In a slot narrower than the search distance a block's corner meets
    /// the bottom and the wall it presses on, not the far wall.
    #[test]
    fn in_a_narrow_slot_the_nearest_notch_is_met() {
        // A U: the slot is 0.02 m wide, x from 0.14 to 0.16, bottom at 0.1.
        let u = PlacedPolygon::from_world(
            &[
                Point::new(0.0, 0.0),
                Point::new(0.3, 0.0),
                Point::new(0.3, 0.3),
                Point::new(0.16, 0.3),
                Point::new(0.16, 0.1),
                Point::new(0.14, 0.1),
                Point::new(0.14, 0.3),
                Point::new(0.0, 0.3),
            ],
            0,
        )
        .unwrap();
        // A pin with its lower-right corner 1 mm off the right wall and 1
        // mm above the bottom (the left wall is 19 mm away).
        let pin = rect(0.1420, 0.101, 0.159, 0.25);
        let corner = PolygonCorner::of(&pin, 1);
        let met = entrance_edges(&corner, pin.centroid(), &u, 0.05, None);
        let mut edges: Vec<usize> = met.iter().map(|m| m.0).collect();
        edges.sort_unstable();
        assert_eq!(edges, vec![3, 4], "{met:?}");
    }
}
