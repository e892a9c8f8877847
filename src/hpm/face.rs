//! Faces of the column elements and their Gauss points (paper 001, §4):
//! vertical side faces between neighbouring columns (eqs. 14–19), bilinear
//! faces between layers of a column (eqs. 20–22) and the bilinear slip
//! surface under the bottom element (eqs. 23–28).
//!
//! Each face is integrated with 2 × 2 Gauss points; a point carries its
//! position, unit normal and the area it represents.

use nalgebra::{Matrix3, Point3, Vector3};

/// Two-point Gauss rule on [0, 1].
const GAUSS: [(f64, f64); 2] = [
    (0.211_324_865_405_187_1, 0.5),
    (0.788_675_134_594_812_9, 0.5),
];

/// A Gauss point of a face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FacePoint {
    /// Position (m).
    pub position: Point3<f64>,
    /// Unit normal.
    pub normal: Vector3<f64>,
    /// Area this point represents (m²).
    pub area: f64,
}

/// A Gauss point of the slip surface with its local frame (eqs. 24–28).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlipPoint {
    /// Position, normal (eq. 24, pointing down into the fixed ground) and area.
    pub point: FacePoint,
    /// First tangent s (eq. 25), in the y–z plane.
    pub s: Vector3<f64>,
    /// Second tangent t: eq. (26) made orthogonal to s (Gram–Schmidt), so
    /// that (s, t, n) is orthonormal and `|τ|` does not depend on the frame.
    pub t: Vector3<f64>,
}

/// Height of a bilinear face with corners in the order of
/// [`crate::shape::Column::new`] at (ξ, η) ∈ [0, 1]², and its slopes
/// (∂z/∂ξ, ∂z/∂η).
fn bilinear(z: &[f64; 4], xi: f64, eta: f64) -> (f64, f64, f64) {
    let height = z[0] * (1.0 - xi) * (1.0 - eta)
        + z[1] * xi * (1.0 - eta)
        + z[2] * xi * eta
        + z[3] * (1.0 - xi) * eta;
    let d_xi = (z[1] - z[0]) * (1.0 - eta) + (z[2] - z[3]) * eta;
    let d_eta = (z[3] - z[0]) * (1.0 - xi) + (z[2] - z[1]) * xi;
    (height, d_xi, d_eta)
}

/// Gauss points of the bilinear surface `z` (eq. 23) over the cell with
/// lower-left corner `origin` and side `size`; the normal points down
/// (eq. 24), `(∂z/∂x, ∂z/∂y, −1) / √(1 + ∂z/∂x² + ∂z/∂y²)`.
pub fn bilinear_face(origin: (f64, f64), size: f64, z: &[f64; 4]) -> Vec<SlipPoint> {
    let mut points = Vec::with_capacity(4);
    for &(xi, wx) in &GAUSS {
        for &(eta, wy) in &GAUSS {
            let (height, d_xi, d_eta) = bilinear(z, xi, eta);
            let (zx, zy) = (d_xi / size, d_eta / size);
            let root = (1.0 + zx * zx + zy * zy).sqrt();
            let normal = Vector3::new(zx, zy, -1.0) / root;
            let s = Vector3::new(0.0, 1.0, zy) / (1.0 + zy * zy).sqrt();
            let t_raw = Vector3::new(1.0, 0.0, zx);
            let t = (t_raw - s * s.dot(&t_raw)).normalize();
            points.push(SlipPoint {
                point: FacePoint {
                    position: Point3::new(origin.0 + xi * size, origin.1 + eta * size, height),
                    normal,
                    area: wx * wy * size * size * root,
                },
                s,
                t,
            });
        }
    }
    points
}

/// Which vertical side of a cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The face at x = x0 + size (towards +x).
    East,
    /// The face at y = y0 + size (towards +y).
    North,
}

/// Gauss points of a vertical side face of the layer between the bilinear
/// faces `bottom` and `top`; the normal is +x (east) or +y (north).
pub fn side_face(
    origin: (f64, f64),
    size: f64,
    bottom: &[f64; 4],
    top: &[f64; 4],
    side: Side,
) -> Vec<FacePoint> {
    // The edge runs from corner a to corner b.
    let (a, b, normal) = match side {
        Side::East => (1, 2, Vector3::x()),
        Side::North => (3, 2, Vector3::y()),
    };
    let mut points = Vec::with_capacity(4);
    for &(along, wa) in &GAUSS {
        let zb = bottom[a] + along * (bottom[b] - bottom[a]);
        let zt = top[a] + along * (top[b] - top[a]);
        let (x, y) = match side {
            Side::East => (origin.0 + size, origin.1 + along * size),
            Side::North => (origin.0 + along * size, origin.1 + size),
        };
        for &(up, wz) in &GAUSS {
            points.push(FacePoint {
                position: Point3::new(x, y, zb + up * (zt - zb)),
                normal,
                area: wa * wz * size * (zt - zb),
            });
        }
    }
    points
}

/// The penalty matrix of eq. (16) in global axes for a face with unit
/// normal `n`: `k_s (I − n nᵀ) + k_n n nᵀ` (k_s = k_t, so the tangents'
/// orientation does not matter).
pub fn spring_matrix(normal: &Vector3<f64>, k_n: f64, k_s: f64) -> Matrix3<f64> {
    Matrix3::identity() * k_s + normal * normal.transpose() * (k_n - k_s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn face_areas_are_exact_for_planar_faces_and_frames_are_orthonormal() {
        // Plane z = 0.3 x − 0.4 y over a 10 m cell.
        let z = [0.0, 3.0, -1.0, -4.0];
        let pts = bilinear_face((0.0, 0.0), 10.0, &z);
        let area: f64 = pts.iter().map(|p| p.point.area).sum();
        assert!((area - 100.0 * (1.0f64 + 0.09 + 0.16).sqrt()).abs() < 1e-9);
        for p in &pts {
            let n = p.point.normal;
            assert!((n - Vector3::new(0.3, -0.4, -1.0).normalize()).norm() < 1e-12);
            assert!(n.dot(&p.s).abs() < 1e-12 && n.dot(&p.t).abs() < 1e-12);
            assert!(p.s.dot(&p.t).abs() < 1e-12 && (p.t.norm() - 1.0).abs() < 1e-12);
        }
        let side = side_face(
            (0.0, 0.0),
            10.0,
            &[0.0; 4],
            &[1.0, 2.0, 4.0, 1.0],
            Side::East,
        );
        let side_area: f64 = side.iter().map(|p| p.area).sum();
        assert!((side_area - 30.0).abs() < 1e-12);
    }
}
