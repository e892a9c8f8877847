//! The simple polygon: the block of DDA (paper 003), convex or concave.

use std::sync::Arc;

use nalgebra::SMatrix;

use super::simple::{first_defect, Defect};
use super::{MassProperties, Shape, Shape2, ShapeKind};
use crate::error::{require_positive, DismechError, Result};
use crate::math::{cross, Aabb2, Point, Pose2, Vec2};

/// A simple polygon (no self-intersection), vertices counter-clockwise in
/// the body frame, whose origin is the centroid.
///
/// Vertex `k` joins edge `k − 1` (ending there) and edge `k` (from vertex `k`
/// to vertex `k + 1`); the outward unit normals of the edges and which
/// vertices are reflex (interior angle above 180°) are kept for the contact
/// routines.
///
/// Serialized with everything it keeps (vertices, normals, reflex
/// vertices, radius, area, moments), so that a polygon read back is the
/// same to the last bit: its area was measured from the world vertices it
/// was made from, which it does not keep. Reading refuses fewer than three
/// vertices, normals or flags that do not match them in number, a value
/// that is not finite and an area that is not positive.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "PolygonRecord", into = "PolygonRecord")]
pub struct Polygon {
    /// Shared: a particle's shape stays small (a polygon's vertices and
    /// normals live apart from the hot data of the particle).
    data: Arc<PolygonData>,
}

/// What a polygon is made of.
#[derive(Debug, PartialEq)]
struct PolygonData {
    vertices: Vec<Point>,
    /// Outward unit normal of edge `k`, body frame.
    normals: Vec<Vec2>,
    /// Whether vertex `k` is reflex.
    reflex: Vec<bool>,
    /// Largest distance from the centroid to a vertex.
    radius: f64,
    area: f64,
    /// `∫x² dA`, `∫y² dA`, `∫xy dA` about the centroid.
    second_moments: [f64; 3],
}

/// A polygon as serialized: what it keeps.
#[derive(serde::Serialize, serde::Deserialize)]
struct PolygonRecord {
    vertices: Vec<Point>,
    normals: Vec<Vec2>,
    reflex: Vec<bool>,
    radius: f64,
    area: f64,
    second_moments: [f64; 3],
}

impl From<Polygon> for PolygonRecord {
    fn from(p: Polygon) -> Self {
        let d = &*p.data;
        Self {
            vertices: d.vertices.clone(),
            normals: d.normals.clone(),
            reflex: d.reflex.clone(),
            radius: d.radius,
            area: d.area,
            second_moments: d.second_moments,
        }
    }
}

impl TryFrom<PolygonRecord> for Polygon {
    type Error = &'static str;
    fn try_from(r: PolygonRecord) -> std::result::Result<Self, Self::Error> {
        let n = r.vertices.len();
        if n < 3 {
            return Err("a polygon has fewer than three vertices");
        }
        if r.normals.len() != n || r.reflex.len() != n {
            return Err("a polygon's normals or reflex flags do not match its vertices");
        }
        let finite = (r.vertices.iter().flat_map(|v| [v.x, v.y]))
            .chain(r.normals.iter().flat_map(|v| [v.x, v.y]))
            .chain([r.radius, r.area])
            .chain(r.second_moments)
            .all(f64::is_finite);
        if !finite || r.area <= 0.0 || r.radius < 0.0 {
            return Err(
                "a polygon has a value that is not finite, or an area that is not positive",
            );
        }
        Ok(Self {
            data: Arc::new(PolygonData {
                vertices: r.vertices,
                normals: r.normals,
                reflex: r.reflex,
                radius: r.radius,
                area: r.area,
                second_moments: r.second_moments,
            }),
        })
    }
}

/// Whether segments pq and rs cross or touch.
pub(crate) fn segments_meet(p: &Point, q: &Point, r: &Point, s: &Point) -> bool {
    let d1 = cross(&(q - p), &(r - p));
    let d2 = cross(&(q - p), &(s - p));
    let d3 = cross(&(s - r), &(p - r));
    let d4 = cross(&(s - r), &(q - r));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    let on = |a: &Point, b: &Point, c: &Point, d: f64| {
        d == 0.0
            && c.x >= a.x.min(b.x)
            && c.x <= a.x.max(b.x)
            && c.y >= a.y.min(b.y)
            && c.y <= a.y.max(b.y)
    };
    on(p, q, r, d1) || on(p, q, s, d2) || on(r, s, p, d3) || on(r, s, q, d4)
}

/// `[A, ∫x dA, ∫y dA, ∫x² dA, ∫y² dA, ∫xy dA]` of a polygon by the exact
/// vertex formulas (Green's theorem).
fn moments(vertices: &[Point]) -> [f64; 6] {
    let mut m = [0.0; 6];
    for k in 0..vertices.len() {
        let (p, q) = (vertices[k], vertices[(k + 1) % vertices.len()]);
        let c = p.x * q.y - q.x * p.y;
        m[0] += c / 2.0;
        m[1] += c * (p.x + q.x) / 6.0;
        m[2] += c * (p.y + q.y) / 6.0;
        m[3] += c * (p.x * p.x + p.x * q.x + q.x * q.x) / 12.0;
        m[4] += c * (p.y * p.y + p.y * q.y + q.y * q.y) / 12.0;
        m[5] += c * (p.x * q.y + 2.0 * p.x * p.y + 2.0 * q.x * q.y + q.x * p.y) / 24.0;
    }
    m
}

/// Whether segments `pq` and `rs` cross strictly: each one's ends lie on
/// opposite sides of the other's line by more than rounding (touching or
/// collinear segments do not cross).
fn segments_cross(p: &Point, q: &Point, r: &Point, s: &Point) -> bool {
    let side = |a: &Point, b: &Point, c: &Point| {
        let (e, f) = (b - a, c - a);
        let d = cross(&e, &f);
        if d.abs() <= 1e-12 * e.norm() * f.norm() {
            0.0
        } else {
            d.signum()
        }
    };
    side(p, q, r) * side(p, q, s) < 0.0 && side(r, s, p) * side(r, s, q) < 0.0
}

/// How deeply two polygons given by their world vertices (counter-clockwise)
/// overlap when an edge of one crosses an edge of the other strictly: the
/// smallest overlap of their projections on the edge normals of both (the
/// penetration depth for convex polygons; for concave ones that of their
/// convex hulls). `None` when no two edges cross — the polygons are apart,
/// touch along edges or at corners, or one holds a vertex of the other,
/// which the contact manifold finds.
///
/// Two rectangles crossed as a plus sign hold no vertex of each other, so
/// only this test sees their overlap.
pub fn crossing_depth(a: &[Point], b: &[Point]) -> Option<f64> {
    fn edges(v: &[Point]) -> impl Iterator<Item = (Point, Point)> + '_ {
        let n = v.len();
        (0..n).map(move |k| (v[k], v[(k + 1) % n]))
    }
    let cross_any = edges(a).any(|(p, q)| edges(b).any(|(r, s)| segments_cross(&p, &q, &r, &s)));
    if !cross_any {
        return None;
    }
    let span = |v: &[Point], m: &Vec2| {
        v.iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                let x = p.coords.dot(m);
                (lo.min(x), hi.max(x))
            })
    };
    let depth = edges(a)
        .chain(edges(b))
        .filter_map(|(p, q)| {
            let e = q - p;
            Vec2::new(e.y, -e.x).try_normalize(0.0)
        })
        .map(|m| {
            let ((a0, a1), (b0, b1)) = (span(a, &m), span(b, &m));
            a1.min(b1) - a0.max(b0)
        })
        .fold(f64::INFINITY, f64::min);
    Some(depth.max(0.0))
}

impl Polygon {
    /// A polygon from world vertices listed counter-clockwise; returns the
    /// polygon (in its centroid frame) and the centroid. Refuses fewer than
    /// three vertices, non-finite coordinates, a zero or negative
    /// (clockwise) area (judged against the polygon's own size), moments
    /// of area that overflow, and self-intersection (every pair of edges,
    /// found by a quadtree in about `n log n`: `simple.rs`); `block` names the
    /// block in the error.
    ///
    /// # Errors
    /// [`DismechError::InvalidPolygon`] naming `block` and the reason for
    /// fewer than three vertices, a vertex that is not finite, two
    /// consecutive vertices that coincide, edges that intersect, moments of
    /// area that overflow, or vertices that run clockwise or enclose no
    /// area.
    pub fn from_world(vertices: &[Point], block: usize) -> Result<(Self, Point)> {
        let bad = |reason: &'static str| DismechError::InvalidPolygon { block, reason };
        if vertices.len() < 3 {
            return Err(bad("it has fewer than three vertices"));
        }
        if vertices
            .iter()
            .any(|v| !(v.x.is_finite() && v.y.is_finite()))
        {
            return Err(bad("a vertex is not finite"));
        }
        let n = vertices.len();
        // Every pair of edges as if tested in order, by a quadtree.
        match first_defect(vertices) {
            Some(Defect::CoincidentVertices) => {
                return Err(bad("two consecutive vertices coincide"))
            }
            Some(Defect::Intersection) => {
                return Err(bad("its edges intersect (not a simple polygon)"))
            }
            None => {}
        }
        // Area and moments measured from the first vertex (not the world
        // origin, against which a small block far away loses its area to
        // cancellation), orientation against the polygon's own size.
        let origin = vertices[0];
        let relative: Vec<Point> = vertices.iter().map(|v| Point::from(v - origin)).collect();
        let m = moments(&relative);
        let area = m[0];
        let scale = relative
            .iter()
            .map(|v| v.coords.norm_squared())
            .fold(0.0, f64::max);
        if !(m.iter().all(|x| x.is_finite()) && scale.is_finite()) {
            return Err(bad(
                "its moments of area overflow (coordinates too large; choose a smaller unit of length)",
            ));
        }
        if area <= 1e-14 * scale {
            return Err(bad(if area < 0.0 {
                "its vertices run clockwise (list them counter-clockwise)"
            } else {
                "its area is zero"
            }));
        }
        let centroid = origin + Vec2::new(m[1] / area, m[2] / area);
        let local: Vec<Point> = vertices.iter().map(|v| Point::from(v - centroid)).collect();
        let c = moments(&local);
        let normals = (0..n)
            .map(|k| {
                let edge = local[(k + 1) % n] - local[k];
                Vec2::new(edge.y, -edge.x) / edge.norm()
            })
            .collect();
        let reflex = (0..n)
            .map(|k| {
                let (prev, here, next) = (local[(k + n - 1) % n], local[k], local[(k + 1) % n]);
                cross(&(here - prev), &(next - here)) < 0.0
            })
            .collect();
        let radius = local.iter().map(|v| v.coords.norm()).fold(0.0, f64::max);
        Ok((
            Self {
                data: Arc::new(PolygonData {
                    vertices: local,
                    normals,
                    reflex,
                    radius,
                    area,
                    second_moments: [c[3], c[4], c[5]],
                }),
            },
            centroid,
        ))
    }

    /// A `width × height` rectangle centred on its centroid, sides along the
    /// body axes; vertex 0 is the lower-left corner, edge 0 the bottom.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for a width or height that is not
    /// finite and positive; [`DismechError::InvalidPolygon`] (block 0) for
    /// sizes so far apart that the area vanishes against the rectangle's
    /// size, or so large that its moments of area overflow.
    pub fn rectangle(width: f64, height: f64) -> Result<Self> {
        let (hw, hh) = (
            0.5 * require_positive("rectangle width", width)?,
            0.5 * require_positive("rectangle height", height)?,
        );
        let corners = [(-hw, -hh), (hw, -hh), (hw, hh), (-hw, hh)].map(|(x, y)| Point::new(x, y));
        Ok(Self::from_world(&corners, 0)?.0)
    }

    /// Vertices in the centroid frame, counter-clockwise.
    pub fn vertices(&self) -> &[Point] {
        &self.data.vertices
    }

    /// The vertices placed at `pose` (world frame).
    pub fn world_vertices<'a>(&'a self, pose: &'a Pose2) -> impl Iterator<Item = Point> + 'a {
        self.data.vertices.iter().map(|v| pose.transform_point(v))
    }

    /// Outward unit normal of edge `k` (from vertex `k` to `k + 1`), body
    /// frame.
    pub fn edge_normal(&self, k: usize) -> Vec2 {
        self.data.normals[k]
    }

    /// Whether vertex `k` is reflex (interior angle above 180°).
    pub fn is_reflex(&self, k: usize) -> bool {
        self.data.reflex[k]
    }

    /// Whether the body-frame point `p` lies inside the polygon (crossing
    /// number; a point on the boundary may count either way).
    pub fn contains(&self, p: &Point) -> bool {
        let n = self.data.vertices.len();
        let mut inside = false;
        for k in 0..n {
            let (a, b) = (self.data.vertices[k], self.data.vertices[(k + 1) % n]);
            if (a.y > p.y) != (b.y > p.y) {
                let x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
                if p.x < x {
                    inside = !inside;
                }
            }
        }
        inside
    }

    /// Second moments of area about the centroid: `[∫x², ∫y², ∫xy] dA`.
    pub fn second_moments(&self) -> [f64; 3] {
        self.data.second_moments
    }

    /// The DDA displacement matrix `[T(x, y)]` of paper 003 eq. (15) at a
    /// point `(x, y)` given relative to the centroid: `u = T d` with
    /// `d = (u₀, v₀, r₀, εx, εy, γxy)` (eq. 16).
    pub fn dda_displacement_matrix(x: f64, y: f64) -> SMatrix<f64, 2, 6> {
        SMatrix::<f64, 2, 6>::from_row_slice(&[
            1.0,
            0.0,
            -y,
            x,
            0.0,
            0.5 * y, //
            0.0,
            1.0,
            x,
            0.0,
            y,
            0.5 * x,
        ])
    }
}

impl Shape for Polygon {
    fn kind(&self) -> ShapeKind {
        ShapeKind::Polygon
    }
    fn dimension(&self) -> usize {
        2
    }
    fn measure(&self) -> f64 {
        self.data.area
    }
    /// `m = ρ A`, `I = ρ (∫x² + ∫y²) dA` about the centroid.
    fn mass_properties(&self, density: f64) -> MassProperties {
        MassProperties {
            mass: density * self.data.area,
            inertia: density * (self.data.second_moments[0] + self.data.second_moments[1]),
        }
    }
}

impl Shape2 for Polygon {
    fn aabb(&self, pose: &Pose2) -> Aabb2 {
        let mut bb = Aabb2 {
            min: Point::new(f64::INFINITY, f64::INFINITY),
            max: Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
        };
        for v in &self.data.vertices {
            let w = pose.transform_point(v);
            bb.min = Point::new(bb.min.x.min(w.x), bb.min.y.min(w.y));
            bb.max = Point::new(bb.max.x.max(w.x), bb.max.y.max(w.y));
        }
        bb
    }
    fn bounding_radius(&self) -> f64 {
        self.data.radius
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    fn rectangle(w: f64, h: f64, x: f64, y: f64) -> Vec<Point> {
        vec![
            Point::new(x, y),
            Point::new(x + w, y),
            Point::new(x + w, y + h),
            Point::new(x, y + h),
        ]
    }

    #[test]
    fn rectangle_has_the_textbook_area_centroid_and_moments() {
        let (p, c) = Polygon::from_world(&rectangle(4.0, 2.0, 1.0, -1.0), 0).unwrap();
        assert_relative_eq!(p.measure(), 8.0);
        assert_relative_eq!(c.x, 3.0);
        assert_relative_eq!(c.y, 0.0, epsilon = 1e-15);
        let [ixx, iyy, ixy] = p.second_moments();
        assert_relative_eq!(ixx, 2.0 * 4f64.powi(3) / 12.0);
        assert_relative_eq!(iyy, 4.0 * 2f64.powi(3) / 12.0);
        assert_relative_eq!(ixy, 0.0, epsilon = 1e-12);
    }

    #[test]
    fn concave_l_shape_moments_equal_the_sum_of_its_rectangles() {
        // L = [0,2]×[0,1] ∪ [0,1]×[1,2].
        let l = [
            (0.0, 0.0),
            (2.0, 0.0),
            (2.0, 1.0),
            (1.0, 1.0),
            (1.0, 2.0),
            (0.0, 2.0),
        ]
        .map(|(x, y)| Point::new(x, y));
        let (p, c) = Polygon::from_world(&l, 3).unwrap();
        assert_relative_eq!(p.measure(), 3.0);
        assert_relative_eq!(c.x, (2.0 * 1.0 + 1.0 * 0.5) / 3.0);
        // ∫x² about the origin: [0,2]×[0,1] gives 8/3, [0,1]×[1,2] gives 1/3.
        let ixx_origin = 8.0 / 3.0 + 1.0 / 3.0;
        assert_relative_eq!(
            p.second_moments()[0],
            ixx_origin - 3.0 * c.x * c.x,
            max_relative = 1e-12
        );
    }

    #[test]
    fn bad_polygons_are_refused_naming_the_block() {
        let bow_tie =
            [(0.0, 0.0), (1.0, 1.0), (1.0, 0.0), (0.0, 1.0)].map(|(x, y)| Point::new(x, y));
        let mut clockwise = rectangle(1.0, 1.0, 0.0, 0.0);
        clockwise.reverse();
        let flat = [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0)].map(|(x, y)| Point::new(x, y));
        for (vertices, word) in [
            (&bow_tie[..], "intersect"),
            (&clockwise[..], "clockwise"),
            (&flat[..], ""),
        ] {
            match Polygon::from_world(vertices, 7).unwrap_err() {
                DismechError::InvalidPolygon { block: 7, reason } => {
                    assert!(reason.contains(word), "{reason}")
                }
                other => panic!("{other}"),
            }
        }
    }

    proptest! {
        /// A regular n-gon's area and polar moment match the closed forms,
        /// wherever it is placed.
        #[test]
        fn regular_polygon_matches_closed_forms(n in 3usize..40, r in 0.1f64..10.0, x in -50.0f64..50.0, y in -50.0f64..50.0, turn in 0.0f64..6.3) {
            let vertices: Vec<Point> = (0..n)
                .map(|k| { let t = turn + k as f64 * std::f64::consts::TAU / n as f64; Point::new(x + r * t.cos(), y + r * t.sin()) })
                .collect();
            let (p, c) = Polygon::from_world(&vertices, 0).unwrap();
            let nf = n as f64;
            let area = 0.5 * nf * r * r * (std::f64::consts::TAU / nf).sin();
            let polar = area * r * r / 6.0 * (2.0 + (std::f64::consts::TAU / nf).cos());
            prop_assert!((p.measure() - area).abs() <= 1e-9 * area);
            prop_assert!((c.x - x).abs() < 1e-9 * (1.0 + x.abs()) && (c.y - y).abs() < 1e-9 * (1.0 + y.abs()));
            let [ixx, iyy, _] = p.second_moments();
            prop_assert!((ixx + iyy - polar).abs() <= 1e-8 * polar);
        }
    }

    #[test]
    fn dda_matrix_gives_rigid_rotation_and_uniform_strain() {
        // r₀ = 1: u = (−y, x); εx = 1: u = (x, 0); γxy = 2: u = (y, x).
        let t = Polygon::dda_displacement_matrix(2.0, 3.0);
        let apply = |d: [f64; 6]| t * nalgebra::SVector::<f64, 6>::from_row_slice(&d);
        assert_eq!(
            apply([0.0, 0.0, 1.0, 0.0, 0.0, 0.0]),
            nalgebra::Vector2::new(-3.0, 2.0)
        );
        assert_eq!(
            apply([0.0, 0.0, 0.0, 1.0, 0.0, 0.0]),
            nalgebra::Vector2::new(2.0, 0.0)
        );
        assert_eq!(
            apply([0.0, 0.0, 0.0, 0.0, 0.0, 2.0]),
            nalgebra::Vector2::new(3.0, 2.0)
        );
    }
}
