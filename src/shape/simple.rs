//! Whether a closed chain of vertices is a simple polygon, in about
//! `O(n log n)`.
//!
//! The answer is that of the test of every pair of edges (kept as the
//! oracle of the tests): going through the pairs `(i, j)`, `i < j`, in
//! order, the first pair of adjacent edges of which one has coinciding ends
//! refuses the chain for that, the first pair of other edges that meet
//! ([`segments_meet`]: they cross, touch, or overlap collinear) for
//! that, whichever comes first.
//!
//! The pairs of adjacent edges are `n`, read in order. The edges that may
//! meet are found by a quadtree: a region of more than a few edges is split
//! into its four quarters, each holding the edges that pass through it
//! (within a hair, `1e-12` of the polygon's size, far above the rounding
//! of the tests), down to regions of at most [`LEAF`] edges whose pairs are
//! tested. Two edges that meet pass through a common point, so they share
//! the leaves around it; an edge is held by the leaves along it, so long and
//! short edges mix at no extra cost, and the work is about `n log n` for
//! any simple polygon (and for the refused ones, but for many edges through
//! one point, whose leaf is searched pair by pair).
//!
//! Only pairs whose boxes, grown by the hair, overlap are tested: two
//! edges whose boxes lie apart cannot meet, though the all-pairs test's
//! rounding could once in millions of times report two nearly collinear
//! edges far apart along their common line as crossing (their cross
//! products are all rounding, and of any sign); those are not refused.

use super::polygon::segments_meet;
use crate::math::{cross, Aabb2, Point};

/// Why a chain of vertices is not a simple polygon.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Defect {
    /// Two consecutive vertices coincide (an edge of zero length).
    CoincidentVertices,
    /// Two edges that are not neighbours meet.
    Intersection,
}

/// The most edges of a region whose pairs are tested rather than split.
const LEAF: usize = 16;

/// The deepest split of the quadtree (a region `2^-48` of the polygon's
/// size is below the hair's scale).
const MAX_DEPTH: usize = 48;

/// The first defect of the closed chain `vertices` (at least three, all
/// finite), in the order of the pairs of edges; `None` for a simple
/// polygon.
pub(super) fn first_defect(vertices: &[Point]) -> Option<Defect> {
    let n = vertices.len();
    let degenerate = |k: usize| vertices[k] == vertices[(k + 1) % n];
    // The adjacent pairs in order: (0, 1), (0, n − 1), (1, 2), …, (n − 2, n − 1).
    let coincident = std::iter::once((0, 1))
        .chain(std::iter::once((0, n - 1)))
        .chain((1..n - 1).map(|k| (k, k + 1)))
        .find(|&(i, j)| degenerate(i) || degenerate(j));
    if coincident == Some((0, 1)) {
        return Some(Defect::CoincidentVertices);
    }
    match (coincident, first_meeting_pair(vertices, coincident)) {
        (_, Some(_)) => Some(Defect::Intersection),
        (Some(_), None) => Some(Defect::CoincidentVertices),
        (None, None) => None,
    }
}

/// The first pair `(i, j)`, `i < j`, of edges that are not neighbours and
/// meet, if it comes before `before`.
fn first_meeting_pair(
    vertices: &[Point],
    before: Option<(usize, usize)>,
) -> Option<(usize, usize)> {
    let n = vertices.len();
    let edge = |k: usize| (vertices[k], vertices[(k + 1) % n]);
    let mut bounds = Aabb2 {
        min: vertices[0],
        max: vertices[0],
    };
    for v in vertices {
        bounds = bounds.merged(&Aabb2 { min: *v, max: *v });
    }
    let hair = 1e-12 * (bounds.max.x - bounds.min.x).max(bounds.max.y - bounds.min.y);
    let boxes: Vec<Aabb2> = (0..n)
        .map(|k| {
            let (p, q) = edge(k);
            Aabb2::from_corners(p, q).inflated(hair)
        })
        .collect();
    let mut search = Search {
        vertices,
        boxes: &boxes,
        hair,
        best: before,
    };
    search.region(&bounds.inflated(hair), (0..n).collect(), 0);
    search.best.filter(|&pair| Some(pair) != before)
}

/// The quadtree's search, and the first meeting pair found so far (or the
/// pair it must come before).
struct Search<'a> {
    vertices: &'a [Point],
    /// The edges' boxes grown by the hair.
    boxes: &'a [Aabb2],
    hair: f64,
    best: Option<(usize, usize)>,
}

impl Search<'_> {
    /// Search `region` and the edges that pass through it (ascending).
    fn region(&mut self, region: &Aabb2, edges: Vec<usize>, depth: usize) {
        if edges.len() <= LEAF || depth >= MAX_DEPTH {
            self.leaf(&edges);
            return;
        }
        let mid = Point::new(
            0.5 * (region.min.x + region.max.x),
            0.5 * (region.min.y + region.max.y),
        );
        let quarters = [
            Aabb2::from_corners(region.min, mid),
            Aabb2::from_corners(
                Point::new(mid.x, region.min.y),
                Point::new(region.max.x, mid.y),
            ),
            Aabb2::from_corners(
                Point::new(region.min.x, mid.y),
                Point::new(mid.x, region.max.y),
            ),
            Aabb2::from_corners(mid, region.max),
        ];
        let held: [Vec<usize>; 4] = quarters.map(|quarter| {
            edges
                .iter()
                .copied()
                .filter(|&k| self.passes_through(k, &quarter))
                .collect()
        });
        // Many edges through one point are in every quarter at every
        // depth: their region is searched pair by pair.
        if held.iter().all(|h| h.len() == edges.len()) {
            self.leaf(&edges);
            return;
        }
        drop(edges);
        for (quarter, held) in quarters.iter().zip(held) {
            self.region(quarter, held, depth + 1);
        }
    }

    /// Whether edge `k` passes within the hair of `region`: its grown box
    /// meets the region, and the region's corners are not all beyond the
    /// hair on one side of its line.
    fn passes_through(&self, k: usize, region: &Aabb2) -> bool {
        if !self.boxes[k].intersects(region) {
            return false;
        }
        let n = self.vertices.len();
        let (p, q) = (self.vertices[k], self.vertices[(k + 1) % n]);
        let along = q - p;
        let reach = self.hair * along.norm();
        let side = |x: f64, y: f64| cross(&along, &(Point::new(x, y) - p));
        let corners = [
            side(region.min.x, region.min.y),
            side(region.max.x, region.min.y),
            side(region.min.x, region.max.y),
            side(region.max.x, region.max.y),
        ];
        !(corners.iter().all(|&s| s > reach) || corners.iter().all(|&s| s < -reach))
    }

    /// Test the pairs of `edges` (ascending) that are not neighbours, come
    /// before the best so far and whose grown boxes overlap.
    fn leaf(&mut self, edges: &[usize]) {
        let n = self.vertices.len();
        let edge = |k: usize| (self.vertices[k], self.vertices[(k + 1) % n]);
        for (a, &i) in edges.iter().enumerate() {
            for &j in &edges[a + 1..] {
                if self.best.is_some_and(|best| (i, j) >= best) {
                    break;
                }
                let adjacent = j == i + 1 || (i == 0 && j == n - 1);
                if adjacent || !self.boxes[i].intersects(&self.boxes[j]) {
                    continue;
                }
                let ((p, q), (r, s)) = (edge(i), edge(j));
                if segments_meet(&p, &q, &r, &s) {
                    self.best = Some((i, j));
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The test of every pair of edges in order (the check before the
    /// quadtree, and its oracle).
    fn first_defect_of_all_pairs(vertices: &[Point]) -> Option<Defect> {
        let n = vertices.len();
        for i in 0..n {
            for j in i + 1..n {
                let adjacent = j == i + 1 || (i == 0 && j == n - 1);
                let (p, q) = (vertices[i], vertices[(i + 1) % n]);
                let (r, s) = (vertices[j], vertices[(j + 1) % n]);
                if adjacent {
                    if p == q || r == s {
                        return Some(Defect::CoincidentVertices);
                    }
                    continue;
                }
                if segments_meet(&p, &q, &r, &s) {
                    return Some(Defect::Intersection);
                }
            }
        }
        None
    }

    fn points(xy: &[(f64, f64)]) -> Vec<Point> {
        xy.iter().map(|&(x, y)| Point::new(x, y)).collect()
    }

    /// A star-shaped polygon: angles in order, radii drawn; with some
    /// vertices repeated, moved onto a neighbour, or onto a lattice of
    /// a few points (collinear edges, touching vertices, coincidences),
    /// coordinates on a dyadic lattice so that the tests are exact.
    fn chain() -> impl Strategy<Value = Vec<Point>> {
        (
            prop::collection::vec((1u32..16, 0u32..8), 3..60),
            prop::collection::vec((0usize..64, 0u8..5, -8i32..8, -8i32..8), 0..6),
            prop::bool::ANY,
        )
            .prop_map(|(spokes, edits, coarse)| {
                let n = spokes.len();
                let mut v: Vec<Point> = spokes
                    .iter()
                    .enumerate()
                    .map(|(k, &(r, jitter))| {
                        let t =
                            std::f64::consts::TAU * (k as f64 + jitter as f64 / 16.0) / n as f64;
                        let r = r as f64;
                        let round = |x: f64| {
                            if coarse {
                                x.round()
                            } else {
                                (x * 64.0).round() / 64.0
                            }
                        };
                        Point::new(round(r * t.cos()), round(r * t.sin()))
                    })
                    .collect();
                for (k, kind, x, y) in edits {
                    let k = k % v.len();
                    match kind {
                        0 => {
                            let copy = v[k];
                            v.insert(k, copy);
                        }
                        1 => v[k] = v[(k + 3) % v.len()],
                        2 => v[k] = Point::new(x as f64, y as f64),
                        3 => {
                            // a vertex halfway along its edge (collinear edges)
                            let next = v[(k + 1) % v.len()];
                            v.insert(k + 1, Point::from((v[k].coords + next.coords) * 0.5));
                        }
                        _ => v[k] = Point::new(x as f64 * 0.5, 0.0),
                    }
                }
                v
            })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]
        /// On chains with repeated vertices, collinear edges and touching
        /// vertices, the quadtree's check gives the all-pairs answer.
        #[test]
        fn the_quadtree_check_agrees_with_the_all_pairs_check(v in chain()) {
            prop_assert_eq!(first_defect(&v), first_defect_of_all_pairs(&v));
        }

        /// A polygon of many small edges with two long ones (a fine arc
        /// closed by a chord), moved and scaled anywhere, with one vertex
        /// moved anywhere: the same answer as the all-pairs check.
        #[test]
        fn the_quadtree_check_agrees_on_long_and_short_edges(
            n in 20usize..300,
            x in -1e6f64..1e6,
            scale in 1e-3f64..1e3,
            moved in 0usize..300,
            to in (-1.2f64..1.2, -0.2f64..1.2),
        ) {
            let mut v: Vec<Point> = (0..n)
                .map(|k| {
                    let t = std::f64::consts::PI * k as f64 / (n - 1) as f64;
                    Point::new(x + scale * t.cos(), scale * t.sin())
                })
                .collect();
            v.push(Point::new(x, -0.1 * scale));
            let k = moved % v.len();
            v[k] = Point::new(x + scale * to.0, scale * to.1);
            prop_assert_eq!(first_defect(&v), first_defect_of_all_pairs(&v));
        }
    }

    /// The cases of each answer: a square; a bow tie; a vertex on a far
    /// edge; a collinear overlap; a repeated vertex, alone and after an
    /// earlier crossing (the first pair in order decides the reason).
    #[test]
    fn each_defect_is_named_as_the_all_pairs_check_names_it() {
        let cases = [
            (
                points(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]),
                None,
            ),
            (
                points(&[(0.0, 0.0), (1.0, 1.0), (1.0, 0.0), (0.0, 1.0)]),
                Some(Defect::Intersection),
            ),
            (
                points(&[(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (1.0, 0.0), (0.0, 2.0)]),
                Some(Defect::Intersection),
            ),
            (
                points(&[(0.0, 0.0), (2.0, 0.0), (1.0, 0.0), (1.0, 1.0)]),
                Some(Defect::Intersection),
            ),
            (
                points(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (1.0, 1.0), (0.0, 1.0)]),
                Some(Defect::CoincidentVertices),
            ),
            (
                points(&[(0.0, 0.0), (1.0, 1.0), (1.0, 0.0), (0.0, 1.0), (0.0, 1.0)]),
                Some(Defect::Intersection),
            ),
            (
                points(&[(0.0, 0.0), (0.0, 0.0), (1.0, 1.0), (1.0, 0.0), (0.0, 1.0)]),
                Some(Defect::CoincidentVertices),
            ),
        ];
        for (v, defect) in cases {
            assert_eq!(first_defect_of_all_pairs(&v), defect, "{v:?}");
            assert_eq!(first_defect(&v), defect, "{v:?}");
        }
    }

    /// A 100 000-vertex polygon (a circle with a notch) is judged simple,
    /// and with one vertex pulled across the circle, not.
    #[test]
    fn a_hundred_thousand_vertices_are_judged() {
        let n = 100_000;
        let mut v: Vec<Point> = (0..n)
            .map(|k| {
                let t = std::f64::consts::TAU * k as f64 / n as f64;
                let r = if k % 1000 == 0 { 0.5 } else { 1.0 };
                Point::new(r * t.cos(), r * t.sin())
            })
            .collect();
        assert_eq!(first_defect(&v), None);
        v[n / 2] = Point::new(1.5, 0.01);
        assert_eq!(first_defect(&v), Some(Defect::Intersection));
    }
}
