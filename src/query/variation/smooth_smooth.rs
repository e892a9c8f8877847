//! Smooth–smooth contact: two circles or ellipses, or a polygon vertex (a
//! point side) against a circle or ellipse.
//!
//! With current centres `e_A`, `e_B` and axes matrices `G_A`, `G_B` (shape
//! matrices `G Gᵀ = F M₀ Fᵀ`), the gap is the signed distance
//!
//! ```text
//! g = max over θ of φ(θ),   φ = (e_B − e_A)·n − h_A(n) − h_B(−n),   n = (cos θ, sin θ),
//! ```
//!
//! with `h(m) = |Gᵀ m|`: the separation of disjoint bodies, and minus the
//! minimum translation distance of overlapping ones (`D = A ⊕ (−B)` is
//! convex and `φ = Δe·n − h_D(n)`). At the maximiser θ* the support points
//! differ along `n` only, by `g`.
//!
//! * The maximiser is found by a safeguarded Newton on θ started from the
//!   contact's start-of-step normal θ₀ (ascent is enforced by halving; a
//!   non-concave point takes a bounded gradient step), so `g` is the
//!   smooth branch of local maxima through θ₀.
//! * Gradient by the envelope theorem, `∇g = φ_z`; Hessian
//!   `∇²g = φ_zz − φ_zθ φ_θz / φ_θθ` at θ*, with `φ_θθ < 0` required.
//! * Shear: `g_s = [(x_B − X_B) − (x_A − X_A)]·τ₀`, the relative
//!   displacement of the two material points that were the support points
//!   at the start of the step, along the start tangent `τ₀ = (−sin θ₀, cos
//!   θ₀)`. The tangent is **frozen** at the start of the step, so `g_s` is
//!   linear in the map parameters (zero Hessian there) and its derivatives
//!   are exact; it is not objective within a step: a rotation α of the
//!   whole pair adds `g₀ sin α` (g₀ the start gap, at most the search
//!   distance).
//!
//! Local variables (M = 12): `Δe = e_B − e_A`, `vec G_A`, `vec G_B` (row by
//! row) and the relative displacement `u` of the material points.

use nalgebra::{SMatrix, SVector};

use super::support::{axes_chain, flatten, support_jet, support_profile, unflatten, Jet6};
use super::{GapVariation, LocalVariation, SmoothSide, VariationError};
use crate::kinematics::{point_map_jacobian, MapVector};
use crate::math::{Point, Vec2};

/// Newton iterations allowed for the contact normal.
const MAX_ITERATIONS: usize = 100;
/// Largest change of θ in one iteration (rad).
const MAX_STEP: f64 = 0.5;
/// Angles sampled to start the normal search when no start is given.
const SCAN: usize = 128;

/// One smooth–smooth contact, fixed for the duration of a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SmoothSmoothContact {
    /// Body A at the start of the step.
    pub side_a: SmoothSide,
    /// Body B at the start of the step.
    pub side_b: SmoothSide,
    /// Angle θ₀ of the start normal `n₀` (from A to B).
    pub angle: f64,
    /// A's material point carrying the shear: its support point along `n₀`.
    pub material_a: Point,
    /// B's material point carrying the shear: its support point along `−n₀`.
    pub material_b: Point,
    /// `g` at the start of the step.
    pub initial_gap: f64,
}

/// `φ(θ)`, `φ'`, `φ''` for the local variables `z`.
fn profile(z: &SVector<f64, 12>, theta: f64) -> (f64, f64, f64) {
    let (s, c) = theta.sin_cos();
    let (n, tau) = (Vec2::new(c, s), Vec2::new(-s, c));
    let de = Vec2::new(z[0], z[1]);
    let (ra, ra1, ra2) = support_profile(&n, &tau, &unflatten(&z.as_slice()[2..6]));
    let (rb, rb1, rb2) = support_profile(&n, &tau, &unflatten(&z.as_slice()[6..10]));
    let dn = de.dot(&n);
    (dn - ra - rb, de.dot(&tau) - ra1 - rb1, -dn - ra2 - rb2)
}

/// The local maximiser of `φ` reached from `start` by safeguarded Newton.
fn maximise(z: &SVector<f64, 12>, start: f64) -> Result<f64, VariationError> {
    let scale = z.fixed_rows::<10>(0).norm() + f64::MIN_POSITIVE;
    let tolerance = 4.0 * f64::EPSILON * scale;
    // Below this curvature the maximiser is not resolved in floating point
    // (e.g. concentric circles, whose separation is the same along every n).
    let flat = 1e3 * f64::EPSILON * scale;
    let mut theta = start;
    let (mut f, mut f1, mut f2) = profile(z, theta);
    let mut converged = f1.abs() <= tolerance;
    let mut iterations = 0;
    while !converged && iterations < MAX_ITERATIONS {
        iterations += 1;
        let newton = if f2 < -flat { -f1 / f2 } else { f64::INFINITY };
        let mut step = if newton.abs() <= MAX_STEP {
            newton
        } else {
            MAX_STEP.copysign(f1)
        };
        let mut trial = profile(z, theta + step);
        for _ in 0..60 {
            if trial.0 >= f - tolerance {
                break;
            }
            step *= 0.5;
            trial = profile(z, theta + step);
        }
        theta += step;
        (f, f1, f2) = trial;
        converged = f1.abs() <= tolerance || step.abs() <= 1e-14;
    }
    if !converged {
        return Err(VariationError::NormalNotFound {
            start,
            slope: f1,
            iterations,
        });
    }
    if f2 >= -flat {
        return Err(VariationError::NotAMaximum {
            angle: theta,
            curvature: f2,
        });
    }
    Ok(theta)
}

/// A support jet in `(n, G)` carried to `(θ, G)` by `n = (cos θ, sin θ)`:
/// returns `(ρ_θ, ρ_θθ, ρ_θG)`.
fn along_angle(jet: &Jet6, n: &Vec2, tau: &Vec2) -> (f64, f64, SVector<f64, 4>) {
    let gn = jet.grad.fixed_rows::<2>(0);
    let hnn = jet.hess.fixed_view::<2, 2>(0, 0);
    let hng = jet.hess.fixed_view::<2, 4>(0, 2);
    (
        gn.dot(tau),
        (tau.transpose() * hnn * tau)[0] - gn.dot(n),
        hng.transpose() * tau,
    )
}

impl SmoothSmoothContact {
    /// The local variables at the start of the step.
    fn start_of(a: &SmoothSide, b: &SmoothSide) -> SVector<f64, 12> {
        let mut z = SVector::<f64, 12>::zeros();
        z.fixed_rows_mut::<2>(0).copy_from(&(b.centre - a.centre));
        z.fixed_rows_mut::<4>(2).copy_from(&flatten(&a.axes));
        z.fixed_rows_mut::<4>(6).copy_from(&flatten(&b.axes));
        z
    }

    /// The contact of `a` and `b` when their signed distance is at most
    /// `search`, `None` otherwise. The normal search starts from `start`
    /// (rad; e.g. the contact's normal in the previous step), or, without
    /// one, from the best of a scan of 128 directions.
    ///
    /// # Errors
    /// [`VariationError::NormalNotFound`] when the normal search does not
    /// settle; [`VariationError::NotAMaximum`] when the normal found is not
    /// a strict maximiser of the separation (e.g. concentric circles, whose
    /// normal is undefined).
    pub fn detect(
        a: &SmoothSide,
        b: &SmoothSide,
        search: f64,
        start: Option<f64>,
    ) -> Result<Option<Self>, VariationError> {
        let z = Self::start_of(a, b);
        let start = start.unwrap_or_else(|| {
            (0..SCAN)
                .map(|k| k as f64 * std::f64::consts::TAU / SCAN as f64)
                .map(|t| (t, profile(&z, t).0))
                .fold((0.0, f64::NEG_INFINITY), |best, x| {
                    if x.1 > best.1 {
                        x
                    } else {
                        best
                    }
                })
                .0
        });
        let angle = maximise(&z, start)?;
        let gap = profile(&z, angle).0;
        if gap > search {
            return Ok(None);
        }
        let n = Vec2::new(angle.cos(), angle.sin());
        Ok(Some(Self {
            side_a: *a,
            side_b: *b,
            angle,
            material_a: a.support_point(&n),
            material_b: b.support_point(&(-n)),
            initial_gap: gap,
        }))
    }

    /// The start normal `n₀` (from A to B).
    pub fn normal(&self) -> Vec2 {
        Vec2::new(self.angle.cos(), self.angle.sin())
    }

    /// The start tangent `τ₀ = (−sin θ₀, cos θ₀)` along which the shear is
    /// measured.
    pub fn tangent(&self) -> Vec2 {
        Vec2::new(-self.angle.sin(), self.angle.cos())
    }

    /// The angle of the contact normal (from A to B) after the bodies moved
    /// by the map parameters `dp_a`, `dp_b`: the maximiser reached from θ₀,
    /// e.g. to start the next step's search from the committed state.
    ///
    /// # Errors
    /// [`VariationError::NormalNotFound`] or
    /// [`VariationError::NotAMaximum`] when the normal search from θ₀ at
    /// the moved state fails, as in [`Self::detect`].
    pub fn normal_angle(&self, dp_a: &MapVector, dp_b: &MapVector) -> Result<f64, VariationError> {
        let (la, lb) = self.chain();
        maximise(&(self.start() + la * dp_a + lb * dp_b), self.angle)
    }
}

impl GapVariation<12> for SmoothSmoothContact {
    fn start(&self) -> SVector<f64, 12> {
        Self::start_of(&self.side_a, &self.side_b)
    }

    fn chain(&self) -> (SMatrix<f64, 12, 6>, SMatrix<f64, 12, 6>) {
        let (a, b) = (&self.side_a, &self.side_b);
        let mut la = SMatrix::<f64, 12, 6>::zeros();
        la.fixed_view_mut::<2, 6>(0, 0)
            .copy_from(&(-point_map_jacobian(&(a.centre - a.reference))));
        la.fixed_view_mut::<4, 6>(2, 0)
            .copy_from(&axes_chain(&a.axes));
        la.fixed_view_mut::<2, 6>(10, 0)
            .copy_from(&(-point_map_jacobian(&(self.material_a - a.reference))));
        let mut lb = SMatrix::<f64, 12, 6>::zeros();
        lb.fixed_view_mut::<2, 6>(0, 0)
            .copy_from(&point_map_jacobian(&(b.centre - b.reference)));
        lb.fixed_view_mut::<4, 6>(6, 0)
            .copy_from(&axes_chain(&b.axes));
        lb.fixed_view_mut::<2, 6>(10, 0)
            .copy_from(&point_map_jacobian(&(self.material_b - b.reference)));
        (la, lb)
    }

    fn local(&self, z: &SVector<f64, 12>) -> Result<LocalVariation<12>, VariationError> {
        let theta = maximise(z, self.angle)?;
        let (s, c) = theta.sin_cos();
        let (n, tau) = (Vec2::new(c, s), Vec2::new(-s, c));
        let de = Vec2::new(z[0], z[1]);
        let ja = support_jet(&n, &unflatten(&z.as_slice()[2..6]));
        let jb = support_jet(&n, &unflatten(&z.as_slice()[6..10]));
        let (_, a2, a_g) = along_angle(&ja, &n, &tau);
        let (_, b2, b_g) = along_angle(&jb, &n, &tau);
        let f_tt = -de.dot(&n) - a2 - b2;

        // φ_z, φ_θz and φ_zz over z[0..10].
        let mut f_z = SVector::<f64, 12>::zeros();
        f_z.fixed_rows_mut::<2>(0).copy_from(&n);
        f_z.fixed_rows_mut::<4>(2)
            .copy_from(&(-ja.grad.fixed_rows::<4>(2)));
        f_z.fixed_rows_mut::<4>(6)
            .copy_from(&(-jb.grad.fixed_rows::<4>(2)));
        let mut f_tz = SVector::<f64, 12>::zeros();
        f_tz.fixed_rows_mut::<2>(0).copy_from(&tau);
        f_tz.fixed_rows_mut::<4>(2).copy_from(&(-a_g));
        f_tz.fixed_rows_mut::<4>(6).copy_from(&(-b_g));
        let mut hess_gap = -(f_tz * f_tz.transpose()) / f_tt;
        let mut h = hess_gap.fixed_view_mut::<4, 4>(2, 2);
        h -= ja.hess.fixed_view::<4, 4>(2, 2);
        let mut h = hess_gap.fixed_view_mut::<4, 4>(6, 6);
        h -= jb.hess.fixed_view::<4, 4>(2, 2);

        let t0 = self.tangent();
        let u = Vec2::new(z[10], z[11]);
        let mut grad_shear = SVector::<f64, 12>::zeros();
        grad_shear.fixed_rows_mut::<2>(10).copy_from(&t0);
        Ok(LocalVariation {
            gap: de.dot(&n) - ja.value - jb.value,
            shear: u.dot(&t0),
            grad_gap: f_z,
            grad_shear,
            hess_gap,
            hess_shear: SMatrix::zeros(),
        })
    }
}
