//! Geometry placed in the world at the start of a step: what a pair query
//! reads and what a kinematics moves when an increment is committed.

use nalgebra::Matrix2;

use super::AreaMoments;
use crate::error::{require_positive, DismechError, Result};
use crate::math::{Point, Pose2, Vec2};
use crate::shape::{Ellipse, Polygon, Shape};

/// A simple polygon in the world: its shape about the centroid and the
/// centroid (the reference point of its kinematics), as a DDA block holds
/// them.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PlacedPolygon {
    polygon: Polygon,
    centroid: Point,
}

impl PlacedPolygon {
    /// A polygon from world vertices listed counter-clockwise.
    ///
    /// # Errors
    /// [`DismechError::InvalidPolygon`] naming `body` for fewer than three
    /// vertices, non-finite coordinates, two consecutive vertices that
    /// coincide, a clockwise or zero area, self-intersection or moments of
    /// area that overflow (as [`Polygon::from_world`]).
    pub fn from_world(vertices: &[Point], body: usize) -> Result<Self> {
        let (polygon, centroid) = Polygon::from_world(vertices, body)?;
        Ok(Self { polygon, centroid })
    }

    /// A polygon given about its centroid, placed at `centroid` (e.g. a
    /// DDA block's `polygon()` and `centroid()`).
    pub fn new(polygon: Polygon, centroid: Point) -> Self {
        Self { polygon, centroid }
    }

    /// The shape about its centroid.
    pub fn polygon(&self) -> &Polygon {
        &self.polygon
    }

    /// The centroid (world).
    pub fn centroid(&self) -> Point {
        self.centroid
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.polygon.vertices().len()
    }

    /// Vertex `k` (modulo the count) in the world frame.
    pub fn vertex(&self, k: usize) -> Point {
        let v = self.polygon.vertices();
        self.centroid + v[k % v.len()].coords
    }

    /// Area and second moments about the centroid.
    pub fn moments(&self) -> AreaMoments {
        AreaMoments::new(self.polygon.measure(), self.polygon.second_moments())
    }
}

/// An ellipse in the world, `{x : (x − e)ᵀ M⁻¹ (x − e) ≤ 1}` with `M = A
/// Aᵀ`, held by its centre `e` and an *axes matrix* `A` whose columns are a
/// pair of conjugate semi-diameters (for an ellipse with semi-axes a, b at
/// angle φ, `A = R(φ) diag(a, b)`; for a circle, `A = r I`). An affine map
/// with gradient `F` takes it to the ellipse with axes `F A`, matrix `F M
/// Fᵀ`; its support function is `h(m) = √(mᵀ M m) = |Aᵀ m|`.
///
/// Serialized as its centre and axes matrix; read back through
/// [`PlacedEllipse::new`], which checks them.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "PlacedEllipseRecord", into = "PlacedEllipseRecord")]
pub struct PlacedEllipse {
    centre: Point,
    axes: Matrix2<f64>,
}

/// A placed ellipse as serialized.
#[derive(serde::Serialize, serde::Deserialize)]
struct PlacedEllipseRecord {
    centre: Point,
    axes: Matrix2<f64>,
}

impl From<PlacedEllipse> for PlacedEllipseRecord {
    fn from(e: PlacedEllipse) -> Self {
        Self {
            centre: e.centre,
            axes: e.axes,
        }
    }
}

impl TryFrom<PlacedEllipseRecord> for PlacedEllipse {
    type Error = DismechError;
    fn try_from(record: PlacedEllipseRecord) -> Result<Self> {
        Self::new(record.centre, record.axes)
    }
}

impl PlacedEllipse {
    /// An ellipse from its centre and axes matrix.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] when an entry is not finite or the
    /// axes are (nearly) parallel, `|det A| ≤ 10⁻¹⁴ |A|²`.
    pub fn new(centre: Point, axes: Matrix2<f64>) -> Result<Self> {
        let det = axes.determinant();
        let finite = centre.iter().chain(axes.iter()).all(|v| v.is_finite());
        if !finite || det.abs() <= 1e-14 * axes.norm_squared() {
            return Err(DismechError::InvalidParameter {
                name: "determinant of the ellipse axes matrix",
                value: det,
                requirement: "must be finite and non-zero (the ellipse degenerated)",
            });
        }
        Ok(Self { centre, axes })
    }

    /// A circle of radius `radius` about `centre`.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for a radius that is not finite
    /// and positive.
    pub fn circle(centre: Point, radius: f64) -> Result<Self> {
        let r = require_positive("radius", radius)?;
        Self::new(centre, Matrix2::new(r, 0.0, 0.0, r))
    }

    /// The ellipse `shape` placed at `pose`: axes `R(φ) diag(a, b)`.
    pub fn from_ellipse(shape: &Ellipse, pose: &Pose2) -> Self {
        let (s, c) = pose.angle.sin_cos();
        let rot = Matrix2::new(c, -s, s, c);
        Self {
            centre: pose.position,
            axes: rot * Matrix2::new(shape.a(), 0.0, 0.0, shape.b()),
        }
    }

    /// The centre (world).
    pub fn centre(&self) -> Point {
        self.centre
    }

    /// The axes matrix `A` (columns: conjugate semi-diameters).
    pub fn axes(&self) -> Matrix2<f64> {
        self.axes
    }

    /// The shape matrix `M = A Aᵀ`.
    pub fn matrix(&self) -> Matrix2<f64> {
        self.axes * self.axes.transpose()
    }

    /// Support function `h(m) = |Aᵀ m|`: the largest `(x − e)·m` over the
    /// ellipse.
    pub fn support(&self, m: &Vec2) -> f64 {
        (self.axes.transpose() * m).norm()
    }

    /// The boundary point farthest along `m`: `e + A Aᵀm / |Aᵀm|`.
    pub fn support_point(&self, m: &Vec2) -> Point {
        let v = self.axes.transpose() * m;
        self.centre + self.axes * (v / v.norm())
    }

    /// Area `π |det A|` and second moments `(A/4) M` about the centre.
    pub fn moments(&self) -> AreaMoments {
        let area = std::f64::consts::PI * self.axes.determinant().abs();
        AreaMoments {
            area,
            second: self.matrix() * (0.25 * area),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::Circle;

    #[test]
    fn circle_moments_are_those_of_the_disc() {
        let e = PlacedEllipse::circle(Point::new(1.0, 2.0), 0.5).unwrap();
        let m = e.moments();
        let disc = Circle::new(0.5).unwrap().mass_properties(1.0);
        approx::assert_relative_eq!(m.area, disc.mass, max_relative = 1e-15);
        approx::assert_relative_eq!(m.polar(), disc.inertia, max_relative = 1e-15);
    }

    #[test]
    fn ellipse_moments_and_support_match_the_shape() {
        let shape = Ellipse::new(2.0, 0.5).unwrap();
        let pose = Pose2::new(0.3, -0.1, 0.7);
        let e = PlacedEllipse::from_ellipse(&shape, &pose);
        let m = e.moments();
        let mp = shape.mass_properties(1.0);
        approx::assert_relative_eq!(m.area, mp.mass, max_relative = 1e-15);
        approx::assert_relative_eq!(m.polar(), mp.inertia, max_relative = 1e-14);
        // The support along the major axis is a, along the minor b.
        let major = Vec2::new(0.7f64.cos(), 0.7f64.sin());
        approx::assert_relative_eq!(e.support(&major), 2.0, max_relative = 1e-15);
        let tip = e.support_point(&major);
        approx::assert_relative_eq!(tip, pose.position + major * 2.0, epsilon = 1e-15);
        approx::assert_relative_eq!(shape.implicit(&pose, &tip), 0.0, epsilon = 1e-15);
    }

    #[test]
    fn degenerate_ellipses_are_refused() {
        assert!(PlacedEllipse::new(Point::origin(), Matrix2::new(1.0, 2.0, 1.0, 2.0)).is_err());
        assert!(PlacedEllipse::circle(Point::origin(), 0.0).is_err());
        assert!(PlacedEllipse::new(Point::new(f64::NAN, 0.0), Matrix2::identity()).is_err());
    }
}
