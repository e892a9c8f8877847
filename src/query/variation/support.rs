//! The support term of smooth bodies: `ρ(n, G) = |Gᵀ n|`, the support
//! function of the ellipse with axes matrix `G` (shape matrix `G Gᵀ`) in
//! the direction `n`, with its derivatives in `(n, G)`, and the chain rules
//! through the two normals the kinds use (an edge's normal `n(b)`, a unit
//! vector `n(θ)`).

use nalgebra::{Matrix2, SMatrix, SVector};

use crate::kinematics::PlacedEllipse;
use crate::math::{Point, Vec2};

/// One side of a smooth pair: an ellipse (or circle) with centre `e` and
/// axes matrix `A` (see [`PlacedEllipse`]), moving with the body whose
/// reference point (centroid) is `reference`. A polygon vertex is the side
/// with `A = 0`, a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SmoothSide {
    /// Centre `e` at the start of the step (world).
    pub centre: Point,
    /// Axes matrix `A` at the start of the step (zero for a point).
    pub axes: Matrix2<f64>,
    /// Reference point of the body's map at the start of the step.
    pub reference: Point,
}

impl SmoothSide {
    /// An ellipse or circle that is a body of its own (its centre is the
    /// reference point).
    pub fn ellipse(e: &PlacedEllipse) -> Self {
        Self {
            centre: e.centre(),
            axes: e.axes(),
            reference: e.centre(),
        }
    }

    /// A polygon vertex `point` of the body with reference point
    /// `reference`.
    pub fn vertex(point: Point, reference: Point) -> Self {
        Self {
            centre: point,
            axes: Matrix2::zeros(),
            reference,
        }
    }

    /// Support function `|Aᵀ m|` (zero for a point).
    pub fn support(&self, m: &Vec2) -> f64 {
        (self.axes.transpose() * m).norm()
    }

    /// The boundary point farthest along `m` (the point itself for a point).
    pub fn support_point(&self, m: &Vec2) -> Point {
        let v = self.axes.transpose() * m;
        let r = v.norm();
        if r == 0.0 {
            self.centre
        } else {
            self.centre + self.axes * (v / r)
        }
    }
}

/// A 2×2 matrix as a vector, row by row (the order of `Δp`'s F entries).
pub(super) fn flatten(m: &Matrix2<f64>) -> SVector<f64, 4> {
    SVector::<f64, 4>::new(m[(0, 0)], m[(0, 1)], m[(1, 0)], m[(1, 1)])
}

/// The 2×2 matrix of a row-by-row vector.
pub(super) fn unflatten(v: &[f64]) -> Matrix2<f64> {
    Matrix2::new(v[0], v[1], v[2], v[3])
}

/// `∂ vec(F A) / ∂Δp` (4×6): the moved axes `G = F A` are linear in `F`,
/// `∂G_ij/∂F_ik = A_kj`, and independent of the translation.
pub(super) fn axes_chain(axes: &Matrix2<f64>) -> SMatrix<f64, 4, 6> {
    let mut l = SMatrix::<f64, 4, 6>::zeros();
    let at = axes.transpose();
    l.fixed_view_mut::<2, 2>(0, 2).copy_from(&at);
    l.fixed_view_mut::<2, 2>(2, 4).copy_from(&at);
    l
}

/// A scalar with its gradient and Hessian in six variables.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Jet6 {
    pub value: f64,
    pub grad: SVector<f64, 6>,
    pub hess: SMatrix<f64, 6, 6>,
}

/// `ρ = |v|`, `v = Gᵀ n`, with derivatives in `(n, vec G)`: `∇ρ = Wᵀ v̂`,
/// `∇²ρ = Wᵀ (I − v̂v̂ᵀ)/ρ W + ∂²v/∂n∂G · v̂`, with `W = ∂v/∂(n, G)`. A
/// point (`G = 0`) has `ρ ≡ 0`.
pub(super) fn support_jet(n: &Vec2, g: &Matrix2<f64>) -> Jet6 {
    let v = g.transpose() * n;
    let rho = v.norm();
    if rho == 0.0 {
        return Jet6 {
            value: 0.0,
            grad: SVector::zeros(),
            hess: SMatrix::zeros(),
        };
    }
    let vh = v / rho;
    let proj = (Matrix2::identity() - vh * vh.transpose()) / rho;
    // v_j = Σ_i G_ij n_i: ∂v/∂n = Gᵀ, ∂v_j/∂G_ik = n_i δ_jk.
    let mut w = SMatrix::<f64, 2, 6>::zeros();
    w.fixed_view_mut::<2, 2>(0, 0).copy_from(&g.transpose());
    w[(0, 2)] = n.x;
    w[(1, 3)] = n.x;
    w[(0, 4)] = n.y;
    w[(1, 5)] = n.y;
    let mut hess = w.transpose() * proj * w;
    for i in 0..2 {
        for k in 0..2 {
            hess[(i, 2 + 2 * i + k)] += vh[k];
            hess[(2 + 2 * i + k, i)] += vh[k];
        }
    }
    Jet6 {
        value: rho,
        grad: w.transpose() * vh,
        hess,
    }
}

/// A jet in `(n, G)` carried to `(b, G)` through the outward normal of an
/// edge vector, `n(b) = (b_y, −b_x)/|b|`: `∂n/∂b = −τ nᵀ/l` and
/// `Σ_i w_i ∂²n_i/∂b² = [−(w·n) n nᵀ + (w·τ)(n τᵀ + τ nᵀ)]/l²`.
pub(super) fn through_edge_normal(jet: &Jet6, b: &Vec2) -> Jet6 {
    let l = b.norm();
    let tau = b / l;
    let n = Vec2::new(tau.y, -tau.x);
    let dn = -(tau * n.transpose()) / l;
    let dnt = dn.transpose();
    let wn = jet.grad.fixed_rows::<2>(0).into_owned();
    let curvature = (-(n * n.transpose()) * wn.dot(&n)
        + (n * tau.transpose() + tau * n.transpose()) * wn.dot(&tau))
        / (l * l);
    let mut out = jet.clone();
    out.grad.fixed_rows_mut::<2>(0).copy_from(&(dnt * wn));
    let hnn = jet.hess.fixed_view::<2, 2>(0, 0).into_owned();
    let hng = jet.hess.fixed_view::<2, 4>(0, 2).into_owned();
    let hbg = dnt * hng;
    out.hess
        .fixed_view_mut::<2, 2>(0, 0)
        .copy_from(&(dnt * hnn * dn + curvature));
    out.hess.fixed_view_mut::<2, 4>(0, 2).copy_from(&hbg);
    out.hess
        .fixed_view_mut::<4, 2>(2, 0)
        .copy_from(&hbg.transpose());
    out
}

/// `ρ(n(θ))` and its first two θ-derivatives for `n = (cos θ, sin θ)`,
/// `τ = n'`: `ρ' = v·w/ρ`, `ρ'' = (|w|² − ρ² − ρ'²)/ρ` with `v = Gᵀn`,
/// `w = Gᵀτ`. Zero for a point.
pub(super) fn support_profile(n: &Vec2, tau: &Vec2, g: &Matrix2<f64>) -> (f64, f64, f64) {
    let v = g.transpose() * n;
    let rho = v.norm();
    if rho == 0.0 {
        return (0.0, 0.0, 0.0);
    }
    let w = g.transpose() * tau;
    let d1 = v.dot(&w) / rho;
    (rho, d1, (w.norm_squared() - rho * rho - d1 * d1) / rho)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fd_check(f: impl Fn(&SVector<f64, 6>) -> Jet6, x: SVector<f64, 6>) {
        let jet = f(&x);
        let h = 1e-6;
        for i in 0..6 {
            let mut e = SVector::<f64, 6>::zeros();
            e[i] = h;
            let (p, m) = (f(&(x + e)), f(&(x - e)));
            let fd = (p.value - m.value) / (2.0 * h);
            assert!(
                (fd - jet.grad[i]).abs() < 1e-8,
                "grad {i}: {fd} vs {}",
                jet.grad[i]
            );
            for j in 0..6 {
                let fd = (p.grad[j] - m.grad[j]) / (2.0 * h);
                assert!(
                    (fd - jet.hess[(j, i)]).abs() < 1e-7,
                    "hess {j},{i}: {fd} vs {}",
                    jet.hess[(j, i)]
                );
            }
        }
    }

    #[test]
    fn support_jet_matches_finite_differences() {
        let x = SVector::<f64, 6>::from_row_slice(&[0.6, -0.8, 1.3, 0.4, -0.2, 0.7]);
        fd_check(
            |x| support_jet(&Vec2::new(x[0], x[1]), &unflatten(&x.as_slice()[2..6])),
            x,
        );
    }

    #[test]
    fn support_through_edge_normal_matches_finite_differences() {
        let x = SVector::<f64, 6>::from_row_slice(&[1.7, 0.4, 1.3, 0.4, -0.2, 0.7]);
        fd_check(
            |x| {
                let b = Vec2::new(x[0], x[1]);
                let l = b.norm();
                let n = Vec2::new(b.y / l, -b.x / l);
                through_edge_normal(&support_jet(&n, &unflatten(&x.as_slice()[2..6])), &b)
            },
            x,
        );
    }

    #[test]
    fn support_profile_matches_finite_differences() {
        let g = Matrix2::new(1.3, 0.4, -0.2, 0.7);
        let at = |t: f64| {
            support_profile(
                &Vec2::new(t.cos(), t.sin()),
                &Vec2::new(-t.sin(), t.cos()),
                &g,
            )
        };
        let (t, h) = (0.9, 1e-5);
        let (r, d1, d2) = at(t);
        let ((rp, d1p, _), (rm, d1m, _)) = (at(t + h), at(t - h));
        approx::assert_relative_eq!((rp - rm) / (2.0 * h), d1, epsilon = 1e-8);
        approx::assert_relative_eq!((d1p - d1m) / (2.0 * h), d2, epsilon = 1e-8);
        approx::assert_relative_eq!(r, (g.transpose() * Vec2::new(t.cos(), t.sin())).norm());
    }

    #[test]
    fn axes_chain_is_the_derivative_of_the_moved_axes() {
        let a = Matrix2::new(1.3, 0.4, -0.2, 0.7);
        let dp = SVector::<f64, 6>::from_row_slice(&[0.3, -0.1, 0.05, 0.2, -0.3, 0.1]);
        let f = Matrix2::new(1.0 + dp[2], dp[3], dp[4], 1.0 + dp[5]);
        approx::assert_relative_eq!(
            flatten(&(f * a)),
            flatten(&a) + axes_chain(&a) * dp,
            epsilon = 1e-15
        );
    }
}
