//! The affine 2D body of DDA (paper 003 eqs. 14–16): six degrees of freedom
//! `d = (u₀, v₀, r₀, εx, εy, γxy)` about the centroid, with the linear
//! displacement field `u = T(X − c) d` within a step, and the geometry
//! moved at the end of the step with the rotation made exact.

use nalgebra::{Matrix2, Matrix3, SMatrix, SVector, Vector3};

use super::{Advance, AreaMoments, BodyMap, Kinematics, MapVector, PlacedEllipse, PlacedPolygon};
use crate::error::Result;
use crate::math::Point;
use crate::shape::Polygon;

/// DDA's block kinematics: `x = X + T(X − c) d`, that is `t = (u₀, v₀)` and
/// `F = I + [[εx, γxy/2 − r₀], [γxy/2 + r₀, εy]]`, linear in `d`, within a
/// step (the equations of the step are classic DDA's).
///
/// `I + [[0, −r₀], [r₀, 0]]` is a rotation only to first order: it
/// stretches the body by `√(1 + r₀²)` along every direction, so its area
/// grows by `r₀²` a step, whatever it carries; a disc rolling on a 40°
/// incline grew by 45 % over 990°. At the end of a step the geometry
/// is therefore moved by `F = R(r₀) (I + E)`, `E = [[εx, γxy/2], [γxy/2,
/// εy]]` ([`Kinematics::committed_map`]): the same map to first order, with
/// the rotation exact, so that a body turning without strain keeps its
/// shape and area. This is the post-correction of finite rotation used in
/// DDA practice (Ke 1995, *Proc. ICADD-1*; MacLaughlin & Doolin 2006, *Int.
/// J. Numer. Anal. Methods Geomech.* 30, "Review of validation of the
/// discontinuous deformation analysis (DDA) method").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Affine2;

impl Affine2 {
    /// The constant `P = ∂Δp/∂d`.
    fn jacobian() -> SMatrix<f64, 6, 6> {
        SMatrix::<f64, 6, 6>::from_row_slice(&[
            1.0, 0.0, 0.0, 0.0, 0.0, 0.0, //
            0.0, 1.0, 0.0, 0.0, 0.0, 0.0, //
            0.0, 0.0, 0.0, 1.0, 0.0, 0.0, //
            0.0, 0.0, -1.0, 0.0, 0.0, 0.5, //
            0.0, 0.0, 1.0, 0.0, 0.0, 0.5, //
            0.0, 0.0, 0.0, 0.0, 1.0, 0.0,
        ])
    }
}

impl Kinematics<6> for Affine2 {
    const LINEAR: bool = true;

    fn map_parameters(&self, d: &SVector<f64, 6>) -> MapVector {
        MapVector::new(d[0], d[1], d[3], 0.5 * d[5] - d[2], 0.5 * d[5] + d[2], d[4])
    }

    fn map_jacobian(&self, _d: &SVector<f64, 6>) -> SMatrix<f64, 6, 6> {
        Self::jacobian()
    }

    fn map_curvature(&self, _d: &SVector<f64, 6>, _w: &MapVector) -> SMatrix<f64, 6, 6> {
        SMatrix::zeros()
    }

    /// `ρ ∫ TᵀT dA` exactly from the area and second moments: with
    /// `T = T₀ + x Tx + y Ty` about the centroid,
    /// `∫TᵀT = A T₀ᵀT₀ + Ixx TxᵀTx + Iyy TyᵀTy + Ixy (TxᵀTy + TyᵀTx)`
    /// (the arithmetic of classic DDA, paper 003 eq. 2).
    fn mass(&self, moments: &AreaMoments, density: f64) -> SMatrix<f64, 6, 6> {
        let t0 = Polygon::dda_displacement_matrix(0.0, 0.0);
        let tx = Polygon::dda_displacement_matrix(1.0, 0.0) - t0;
        let ty = Polygon::dda_displacement_matrix(0.0, 1.0) - t0;
        let s = &moments.second;
        let (ixx, iyy, ixy) = (s[(0, 0)], s[(1, 1)], s[(0, 1)]);
        let m = t0.transpose() * t0 * moments.area
            + tx.transpose() * tx * ixx
            + ty.transpose() * ty * iyy
            + (tx.transpose() * ty + ty.transpose() * tx) * ixy;
        m * density
    }

    /// `A D` on the strain unknowns `(εx, εy, γxy)` (from `∫σ·δε dΩ`,
    /// eq. 2, with uniform strain).
    fn stiffness(&self, moments: &AreaMoments, elastic: &Matrix3<f64>) -> SMatrix<f64, 6, 6> {
        let mut k = SMatrix::<f64, 6, 6>::zeros();
        k.fixed_view_mut::<3, 3>(3, 3)
            .copy_from(&(elastic * moments.area));
        k
    }

    /// `(εx, εy, γxy)`: the last three unknowns.
    fn strain(&self, d: &SVector<f64, 6>) -> Vector3<f64> {
        d.fixed_rows::<3>(3).into_owned()
    }

    /// `A (0, 0, 0, σx, σy, τxy)`.
    fn stress_force(&self, moments: &AreaMoments, stress: &Vector3<f64>) -> SVector<f64, 6> {
        let mut f = SVector::<f64, 6>::zeros();
        f.fixed_rows_mut::<3>(3).copy_from(&(stress * moments.area));
        f
    }

    /// `t = (u₀, v₀)`, `F = R(r₀) (I + E)` with `E = [[εx, γxy/2], [γxy/2,
    /// εy]]`: the step's map with its rotation made exact (see [`Affine2`]).
    fn committed_map(&self, d: &SVector<f64, 6>) -> BodyMap {
        let (s, c) = d[2].sin_cos();
        let rotation = Matrix2::new(c, -s, s, c);
        let stretch = Matrix2::new(1.0 + d[3], 0.5 * d[5], 0.5 * d[5], 1.0 + d[4]);
        BodyMap {
            translation: crate::math::Vec2::new(d[0], d[1]),
            gradient: rotation * stretch,
        }
    }
}

/// A polygon's vertices move by the committed map `c + t + R(r₀)(I +
/// E)(X − c)` (eq. 14 with the rotation made exact) and the polygon is
/// rebuilt about its new centroid.
impl Advance<PlacedPolygon, 6> for Affine2 {
    fn advance(
        &self,
        p: &PlacedPolygon,
        d: &SVector<f64, 6>,
        body: usize,
    ) -> Result<PlacedPolygon> {
        let (c, map) = (p.centroid(), self.committed_map(d));
        let moved: Vec<Point> = (0..p.vertex_count())
            .map(|k| map.apply(&c, &p.vertex(k)))
            .collect();
        PlacedPolygon::from_world(&moved, body)
    }
}

/// An ellipse (or circle) `{x : (x − e)ᵀ M⁻¹ (x − e) ≤ 1}` becomes the
/// ellipse with centre `e + t` and matrix `F M Fᵀ`, `F` the committed map's
/// gradient: its conjugate semi-diameters (the columns of its axes matrix)
/// are multiplied by `F`.
impl Advance<PlacedEllipse, 6> for Affine2 {
    fn advance(
        &self,
        e: &PlacedEllipse,
        d: &SVector<f64, 6>,
        _body: usize,
    ) -> Result<PlacedEllipse> {
        let map = self.committed_map(d);
        PlacedEllipse::new(e.centre() + map.translation, map.gradient * e.axes())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn affine_jacobian_is_the_derivative_of_the_parameters() {
        let d = SVector::<f64, 6>::new(0.1, -0.2, 0.03, 0.004, -0.005, 0.006);
        assert_eq!(Affine2.map_parameters(&d), Affine2::jacobian() * d);
    }
}
