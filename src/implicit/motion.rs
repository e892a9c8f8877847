//! How far the bodies' boundaries move over an increment: the too-fast
//! check of a step (no boundary point may move further than the search
//! distance relative to a body it could reach, or a contact could close
//! undetected) and the limit on a Newton update.
//!
//! Every kinematics here moves a body's points by an affine map, so a
//! displacement field is affine in the point: over a polygon's or a wall's
//! boundary its largest norm is at a vertex or an end, and over an ellipse
//! `c + A e`, `|e| = 1`, it is at most `|u(c)| + ‖[u(c + A e₁) − u(c),
//! u(c + A e₂) − u(c)]‖₂`.

use nalgebra::{Matrix2, SVector};

use super::body::{Body, BodyGeometry};
use crate::kinematics::Kinematics;
use crate::math::{Point, Vec2};

/// The displacement over the increment `d` of the material point of
/// `body` now at `p`.
pub(super) fn displacement<const N: usize, K: Kinematics<N>>(
    kinematics: &K,
    body: &Body<N>,
    p: &Point,
    d: &SVector<f64, N>,
) -> Vec2 {
    let c = body.centroid();
    if K::LINEAR {
        kinematics.point_jacobian(d, &(p - c)) * d
    } else {
        kinematics.map(d).apply(&c, p) - p
    }
}

/// The largest norm of the affine field `u` over the boundary of
/// `geometry`, among the polygon vertices and wall ends `p` for which
/// `counts(p, |u(p)|)` holds (an ellipse's bound covers its whole
/// boundary).
pub(super) fn boundary_max(
    geometry: &BodyGeometry,
    u: impl Fn(&Point) -> Vec2,
    counts: impl Fn(&Point, f64) -> bool,
) -> f64 {
    let over = |points: &mut dyn Iterator<Item = Point>| {
        points.fold(0.0f64, |worst, p| {
            let m = u(&p).norm();
            if counts(&p, m) {
                worst.max(m)
            } else {
                worst
            }
        })
    };
    match geometry {
        BodyGeometry::Polygon(p) => over(&mut (0..p.vertex_count()).map(|v| p.vertex(v))),
        BodyGeometry::Wall(s) => over(&mut [s.start, s.end].into_iter()),
        BodyGeometry::Ellipse(e) => {
            let (c, axes) = (e.centre(), e.axes());
            let w = u(&c);
            let g = Matrix2::from_columns(&[
                u(&(c + axes.column(0))) - w,
                u(&(c + axes.column(1))) - w,
            ]);
            w.norm() + spectral_norm(&g)
        }
    }
}

/// The largest motion of a boundary point of `body` over the increment
/// `d`.
pub(super) fn own_motion<const N: usize, K: Kinematics<N>>(
    kinematics: &K,
    body: &Body<N>,
    d: &SVector<f64, N>,
) -> f64 {
    boundary_max(
        body.geometry(),
        |p| displacement(kinematics, body, p, d),
        |_, _| true,
    )
}

/// The largest change of a boundary point of `body` under the Newton
/// update `delta` at the iterate `d` (to first order).
pub(super) fn update_motion<const N: usize, K: Kinematics<N>>(
    kinematics: &K,
    body: &Body<N>,
    d: &SVector<f64, N>,
    delta: &SVector<f64, N>,
) -> f64 {
    let c = body.centroid();
    boundary_max(
        body.geometry(),
        |p| kinematics.point_jacobian(d, &(p - c)) * delta,
        |_, _| true,
    )
}

/// The largest motion over the increments `d_a`, `d_b` of a boundary point
/// of `a` relative to the material of `b`, among the points that could
/// reach `b`: within `margin` plus their own motion plus `reach_b` (the
/// largest motion of `b`'s boundary) of `b`'s box.
pub(super) fn relative_motion<const N: usize, K: Kinematics<N>>(
    kinematics: &K,
    (a, d_a): (&Body<N>, &SVector<f64, N>),
    (b, d_b): (&Body<N>, &SVector<f64, N>),
    margin: f64,
    reach_b: f64,
) -> f64 {
    let near = b.geometry().aabb();
    boundary_max(
        a.geometry(),
        |p| displacement(kinematics, a, p, d_a) - displacement(kinematics, b, p, d_b),
        |p, _| {
            let own = displacement(kinematics, a, p, d_a).norm();
            near.inflated(margin + own + reach_b).contains(p)
        },
    )
}

/// The largest singular value of a 2×2 matrix.
pub(super) fn spectral_norm(m: &Matrix2<f64>) -> f64 {
    let f2 = m.norm_squared();
    let det = m.determinant();
    (0.5 * (f2 + (f2 * f2 - 4.0 * det * det).max(0.0).sqrt())).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spectral_norm_is_the_largest_singular_value() {
        let m = Matrix2::new(3.0, 1.0, -2.0, 0.5);
        let svd = m.svd(false, false);
        let largest = svd.singular_values.max();
        assert!((spectral_norm(&m) - largest).abs() < 1e-14 * largest);
    }
}
