//! The rigid 2D body: three degrees of freedom `(u₀, v₀, θ)`, the
//! translation of the centroid and an exact rotation about it.

use nalgebra::{Matrix2, Matrix3, SMatrix, SVector};

use super::{Advance, AreaMoments, Kinematics, MapVector, PlacedEllipse, PlacedPolygon};
use crate::error::Result;
use crate::math::{Point, Pose2};

/// Rigid motion `x = c + (u₀, v₀) + R(θ)(X − c)` with the exact rotation
/// `R(θ)`: the map parameters are nonlinear in θ, so the chain rule carries
/// a curvature term.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Rigid2;

impl Rigid2 {
    /// `R(θ)`.
    pub fn rotation(theta: f64) -> Matrix2<f64> {
        let (s, c) = theta.sin_cos();
        Matrix2::new(c, -s, s, c)
    }
}

impl Kinematics<3> for Rigid2 {
    const LINEAR: bool = false;

    /// `(u₀, v₀, cos θ − 1, −sin θ, sin θ, cos θ − 1)`, with `cos θ − 1`
    /// written `−2 sin²(θ/2)` to keep its digits for small θ.
    fn map_parameters(&self, d: &SVector<f64, 3>) -> MapVector {
        let s = d[2].sin();
        let h = (0.5 * d[2]).sin();
        let c1 = -2.0 * h * h;
        MapVector::new(d[0], d[1], c1, -s, s, c1)
    }

    fn map_jacobian(&self, d: &SVector<f64, 3>) -> SMatrix<f64, 6, 3> {
        let (s, c) = d[2].sin_cos();
        let mut p = SMatrix::<f64, 6, 3>::zeros();
        p[(0, 0)] = 1.0;
        p[(1, 1)] = 1.0;
        p[(2, 2)] = -s;
        p[(3, 2)] = -c;
        p[(4, 2)] = c;
        p[(5, 2)] = -s;
        p
    }

    fn map_curvature(&self, d: &SVector<f64, 3>, w: &MapVector) -> Matrix3<f64> {
        let (s, c) = d[2].sin_cos();
        let mut k = Matrix3::zeros();
        k[(2, 2)] = -c * w[2] + s * w[3] - s * w[4] - c * w[5];
        k
    }

    /// `diag(ρA, ρA, ρ∫|X − c|² dA)`: exact at every θ, since the centroid
    /// is the reference point.
    fn mass(&self, moments: &AreaMoments, density: f64) -> Matrix3<f64> {
        let m = density * moments.area;
        Matrix3::from_diagonal(&nalgebra::Vector3::new(m, m, density * moments.polar()))
    }

    /// A rigid body stores no strain energy.
    fn stiffness(&self, _moments: &AreaMoments, _elastic: &Matrix3<f64>) -> Matrix3<f64> {
        Matrix3::zeros()
    }
}

/// A rigid body's pose: its centroid moves by `(u₀, v₀)`, its angle by θ.
impl Advance<Pose2, 3> for Rigid2 {
    fn advance(&self, pose: &Pose2, d: &SVector<f64, 3>, _body: usize) -> Result<Pose2> {
        Ok(Pose2 {
            position: pose.position + nalgebra::Vector2::new(d[0], d[1]),
            angle: pose.angle + d[2],
        })
    }
}

/// An ellipse given in the world: centre moved, axes rotated.
impl Advance<PlacedEllipse, 3> for Rigid2 {
    fn advance(
        &self,
        e: &PlacedEllipse,
        d: &SVector<f64, 3>,
        _body: usize,
    ) -> Result<PlacedEllipse> {
        let map = self.map(d);
        PlacedEllipse::new(e.centre() + map.translation, map.gradient * e.axes())
    }
}

/// A polygon given in the world: vertices moved rigidly, polygon rebuilt
/// about its centroid.
impl Advance<PlacedPolygon, 3> for Rigid2 {
    fn advance(
        &self,
        p: &PlacedPolygon,
        d: &SVector<f64, 3>,
        body: usize,
    ) -> Result<PlacedPolygon> {
        let map = self.map(d);
        let c = p.centroid();
        let moved: Vec<Point> = (0..p.vertex_count())
            .map(|k| map.apply(&c, &p.vertex(k)))
            .collect();
        PlacedPolygon::from_world(&moved, body)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rigid_map_rotates_exactly_about_the_centroid() {
        let d = SVector::<f64, 3>::new(0.5, -0.25, 1.2);
        let map = Rigid2.map(&d);
        let (c, x) = (Point::new(1.0, 2.0), Point::new(3.0, 2.0));
        let moved = map.apply(&c, &x);
        let expected = Point::new(1.5 + 2.0 * 1.2f64.cos(), 1.75 + 2.0 * 1.2f64.sin());
        approx::assert_relative_eq!(moved, expected, epsilon = 1e-14);
        approx::assert_relative_eq!(map.gradient, Rigid2::rotation(1.2), epsilon = 1e-15);
    }

    #[test]
    fn rigid_pose_advances_by_the_increment() {
        let pose = Rigid2
            .advance(
                &Pose2::new(1.0, 2.0, 0.5),
                &SVector::<f64, 3>::new(0.1, -0.2, 0.3),
                0,
            )
            .unwrap();
        approx::assert_relative_eq!(pose.position, Point::new(1.1, 1.8), epsilon = 1e-15);
        approx::assert_relative_eq!(pose.angle, 0.8, epsilon = 1e-15);
    }
}
