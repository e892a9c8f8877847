//! The ellipse: the particle of paper 000 (Katsuki & Ishikawa 1990).

use super::{MassProperties, Shape, Shape2, ShapeKind};
use crate::error::{require_positive, DismechError, Result};
use crate::math::{rotate, Aabb2, Point, Pose2, Vec2};

/// Largest aspect ratio a/b the contact routines are verified for.
pub const MAX_ASPECT_RATIO: f64 = 10.0;

/// An ellipse with semi-axes `a ≥ b > 0`; the major axis lies along the
/// body's x-axis, so the body angle φ is the angle of the major axis.
///
/// `a < b` is refused rather than swapped: write the same ellipse as
/// (b, a) with the orientation turned by 90°.
///
/// Serialized as its semi-axes; read back through [`Ellipse::new`], which
/// checks them and computes the same weights.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "EllipseRecord", into = "EllipseRecord")]
pub struct Ellipse {
    a: f64,
    b: f64,
    /// `1 / a²` and `1 / b²`, the weights of the implicit function, kept
    /// for the contact routines.
    inverse_squares: [f64; 2],
}

/// An ellipse as serialized: its semi-axes.
#[derive(serde::Serialize, serde::Deserialize)]
struct EllipseRecord {
    a: f64,
    b: f64,
}

impl From<Ellipse> for EllipseRecord {
    fn from(e: Ellipse) -> Self {
        Self { a: e.a, b: e.b }
    }
}

impl TryFrom<EllipseRecord> for Ellipse {
    type Error = DismechError;
    fn try_from(record: EllipseRecord) -> Result<Self> {
        Self::new(record.a, record.b)
    }
}

impl Ellipse {
    /// An ellipse with semi-major axis `a` and semi-minor axis `b`.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming the value for a semi-axis
    /// that is not finite and positive, `a < b`, or an aspect ratio `a/b`
    /// above [`MAX_ASPECT_RATIO`].
    pub fn new(a: f64, b: f64) -> Result<Self> {
        require_positive("semi-axis a", a)?;
        require_positive("semi-axis b", b)?;
        if a < b {
            return Err(DismechError::InvalidParameter {
                name: "semi-axis a (must not be smaller than b; turn the ellipse by 90° instead)",
                value: a,
                requirement: "must be >= b",
            });
        }
        if a / b > MAX_ASPECT_RATIO {
            return Err(DismechError::InvalidParameter {
                name: "aspect ratio a/b",
                value: a / b,
                requirement: "must be <= 10 (the verified range of the contact routine)",
            });
        }
        Ok(Self {
            a,
            b,
            inverse_squares: [1.0 / (a * a), 1.0 / (b * b)],
        })
    }

    /// Semi-major axis a.
    pub fn a(&self) -> f64 {
        self.a
    }

    /// Semi-minor axis b.
    pub fn b(&self) -> f64 {
        self.b
    }

    /// Boundary point at parametric angle `t` in the body frame:
    /// `(a cos t, b sin t)` (Appendix I, eq. A-1).
    pub fn local_point(&self, t: f64) -> Point {
        Point::new(self.a * t.cos(), self.b * t.sin())
    }

    /// Parametric angle of the boundary point seen at polar angle `beta`
    /// from the centre, in the body frame: `atan2(a sin β, b cos β)`
    /// (eq. A-5, written with atan2 so that every quadrant is right).
    pub fn parametric_angle(&self, beta: f64) -> f64 {
        (self.a * beta.sin()).atan2(self.b * beta.cos())
    }

    /// Radius of curvature at parametric angle `t`:
    /// `(a² sin² t + b² cos² t)^{3/2} / (a b)` (eqs. 20–21).
    pub fn curvature_radius(&self, t: f64) -> f64 {
        let (s, c) = t.sin_cos();
        (self.a * self.a * s * s + self.b * self.b * c * c).powf(1.5) / (self.a * self.b)
    }

    /// The implicit function `(x/a)² + (y/b)² − 1` of a world point for the
    /// ellipse at `pose`: negative inside, zero on the boundary.
    pub fn implicit(&self, pose: &Pose2, p: &Point) -> f64 {
        let q = pose.inverse_transform_point(p);
        (q.x / self.a).powi(2) + (q.y / self.b).powi(2) - 1.0
    }

    /// World boundary point at parametric angle `t` for the ellipse at `pose`.
    pub fn world_point(&self, pose: &Pose2, t: f64) -> Point {
        pose.transform_point(&self.local_point(t))
    }

    /// Where the line `origin + s·direction` crosses the boundary (the two
    /// roots `s₁ ≤ s₂`), or `None` if it misses.
    pub fn line_crossings(
        &self,
        pose: &Pose2,
        origin: &Point,
        direction: &Vec2,
    ) -> Option<(f64, f64)> {
        let o = pose.inverse_transform_point(origin);
        let d = rotate(direction, -pose.angle);
        self.line_crossings_local(&o, &d)
    }

    /// `1 / a²` and `1 / b²`: the weights of the implicit function
    /// `x²/a² + y²/b² − 1`.
    pub fn inverse_squares(&self) -> [f64; 2] {
        self.inverse_squares
    }

    /// [`Self::line_crossings`] for a line given in the body frame.
    pub fn line_crossings_local(&self, o: &Point, d: &Vec2) -> Option<(f64, f64)> {
        let line = self.line_quadratic(o, d)?;
        let (r1, r2) = line.roots();
        Some((r1.min(r2), r1.max(r2)))
    }

    /// Where the body-frame line `o + s d` leaves the ellipse: the larger
    /// of [`Self::line_crossings_local`] (for a line all but tangent, the
    /// two may differ by round-off), with one division.
    pub fn line_exit_local(&self, o: &Point, d: &Vec2) -> Option<f64> {
        Some(self.line_quadratic(o, d)?.root(true))
    }

    /// Where the body-frame line `o + s d` enters the ellipse: the smaller
    /// of [`Self::line_crossings_local`] (to round-off, as for
    /// [`Self::line_exit_local`]), with one division.
    pub fn line_entry_local(&self, o: &Point, d: &Vec2) -> Option<f64> {
        Some(self.line_quadratic(o, d)?.root(false))
    }

    /// The implicit function along the body-frame line `o + s d`, a
    /// quadratic in `s`; `None` when the line misses the ellipse.
    fn line_quadratic(&self, o: &Point, d: &Vec2) -> Option<LineQuadratic> {
        let [ia2, ib2] = self.inverse_squares;
        let qa = d.x * d.x * ia2 + d.y * d.y * ib2;
        let qb = 2.0 * (o.x * d.x * ia2 + o.y * d.y * ib2);
        let qc = o.x * o.x * ia2 + o.y * o.y * ib2 - 1.0;
        let disc = qb * qb - 4.0 * qa * qc;
        if disc < 0.0 || qa <= 0.0 {
            return None;
        }
        // Numerically stable pair of roots: q / qa and qc / q.
        let q = -0.5 * (qb + qb.signum() * disc.sqrt());
        Some(LineQuadratic { qa, qc, q })
    }

    /// Radius of curvature at the boundary point seen from the centre
    /// through the body-frame point `local`: [`Self::curvature_radius`] at
    /// the parametric angle `t` of `(x/a, y/b) = r (cos t, sin t)`, without
    /// the angle: `ρ = q^{3/2} / (a b)` with
    /// `q = a² sin² t + b² cos² t = (a⁴ y² + b⁴ x²) / (b² x² + a² y²)`.
    pub fn curvature_radius_at(&self, local: &Point) -> f64 {
        let (a2, b2) = (self.a * self.a, self.b * self.b);
        let (x2, y2) = (local.x * local.x, local.y * local.y);
        let r2 = b2 * x2 + a2 * y2;
        let q = if r2 > 0.0 {
            (a2 * a2 * y2 + b2 * b2 * x2) / r2
        } else {
            b2
        };
        q * q.sqrt() / (self.a * self.b)
    }
}

/// `qa s² + qb s + qc` with real roots, and `q = −(qb + sign(qb) √disc)/2`
/// for the cancellation-free pair `q / qa`, `qc / q`.
struct LineQuadratic {
    qa: f64,
    qc: f64,
    q: f64,
}

impl LineQuadratic {
    /// Both roots, unordered.
    fn roots(&self) -> (f64, f64) {
        if self.q != 0.0 {
            (self.q / self.qa, self.qc / self.q)
        } else {
            (0.0, 0.0)
        }
    }

    /// The larger root (`larger`) or the smaller one. `q / qa` (`qa > 0`)
    /// has the sign of `q` and is the root of larger magnitude, so it is
    /// the larger root when `q > 0` and the smaller one otherwise.
    fn root(&self, larger: bool) -> f64 {
        if self.q == 0.0 {
            0.0
        } else if (self.q > 0.0) == larger {
            self.q / self.qa
        } else {
            self.qc / self.q
        }
    }
}

/// The root `s̄` of `(r₀ z₀ / (s + r₀))² + (z₁ / (s + 1))² = 1` by
/// bisection, for [`Ellipse::closest_boundary_point`] (Eberly, "Distance
/// from a point to an ellipse"); `g` is the implicit function at the point.
fn closest_point_root(r0: f64, z0: f64, z1: f64, g: f64) -> f64 {
    let n0 = r0 * z0;
    let mut s0 = z1 - 1.0;
    let mut s1 = if g < 0.0 { 0.0 } else { n0.hypot(z1) - 1.0 };
    let mut s = 0.0;
    // Bisection of doubles ends in at most ~1100 halvings.
    for _ in 0..1100 {
        s = 0.5 * (s0 + s1);
        if s == s0 || s == s1 {
            break;
        }
        let (ratio0, ratio1) = (n0 / (s + r0), z1 / (s + 1.0));
        let value = ratio0 * ratio0 + ratio1 * ratio1 - 1.0;
        if value > 0.0 {
            s0 = s;
        } else if value < 0.0 {
            s1 = s;
        } else {
            break;
        }
    }
    s
}

impl Ellipse {
    /// The boundary point nearest to the body-frame point `p`, inside or
    /// outside (Eberly's robust bisection; exact to rounding).
    pub fn closest_boundary_point(&self, p: &Point) -> Point {
        let (e0, e1) = (self.a, self.b);
        let (y0, y1) = (p.x.abs(), p.y.abs());
        let (x0, x1) = if y1 > 0.0 {
            if y0 > 0.0 {
                let (z0, z1) = (y0 / e0, y1 / e1);
                let g = z0 * z0 + z1 * z1 - 1.0;
                if g != 0.0 {
                    let r0 = (e0 / e1) * (e0 / e1);
                    let s = closest_point_root(r0, z0, z1, g);
                    (r0 * y0 / (s + r0), y1 / (s + 1.0))
                } else {
                    (y0, y1)
                }
            } else {
                (0.0, e1)
            }
        } else {
            let (numer, denom) = (e0 * y0, e0 * e0 - e1 * e1);
            if numer < denom {
                let xde0 = numer / denom;
                (e0 * xde0, e1 * (1.0 - xde0 * xde0).max(0.0).sqrt())
            } else {
                (e0, 0.0)
            }
        };
        Point::new(x0.copysign(p.x), x1.copysign(p.y))
    }

    /// The outward unit normal at the body-frame boundary point `x`.
    pub fn outward_normal(&self, x: &Point) -> Vec2 {
        Vec2::new(x.x / (self.a * self.a), x.y / (self.b * self.b)).normalize()
    }
}

impl Shape for Ellipse {
    fn kind(&self) -> ShapeKind {
        ShapeKind::Ellipse
    }
    fn dimension(&self) -> usize {
        2
    }
    fn measure(&self) -> f64 {
        std::f64::consts::PI * self.a * self.b
    }
    /// `m = ρ π a b`, `I = m (a² + b²) / 4`.
    fn mass_properties(&self, density: f64) -> MassProperties {
        let mass = density * self.measure();
        MassProperties {
            mass,
            inertia: 0.25 * mass * (self.a * self.a + self.b * self.b),
        }
    }
}

impl Shape2 for Ellipse {
    fn aabb(&self, pose: &Pose2) -> Aabb2 {
        let (s, c) = pose.angle.sin_cos();
        let hx = ((self.a * c).powi(2) + (self.b * s).powi(2)).sqrt();
        let hy = ((self.a * s).powi(2) + (self.b * c).powi(2)).sqrt();
        let p = pose.position;
        Aabb2 {
            min: Point::new(p.x - hx, p.y - hy),
            max: Point::new(p.x + hx, p.y + hy),
        }
    }
    fn bounding_radius(&self) -> f64 {
        self.a
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ellipse_refuses_a_below_b_and_extreme_aspect() {
        assert!(Ellipse::new(1.0, 2.0).is_err());
        assert!(Ellipse::new(11.0, 1.0).is_err());
        assert!(Ellipse::new(0.0, 0.0).is_err());
        assert!(Ellipse::new(2.0, 1.0).is_ok());
    }

    #[test]
    fn curvature_radius_is_b2_over_a_at_the_ends_and_a2_over_b_on_the_flat_side() {
        let e = Ellipse::new(2.0, 1.0).unwrap();
        approx::assert_relative_eq!(e.curvature_radius(0.0), 0.5);
        approx::assert_relative_eq!(e.curvature_radius(std::f64::consts::FRAC_PI_2), 4.0);
    }

    #[test]
    fn curvature_radius_at_a_point_equals_the_radius_at_its_parametric_angle() {
        let e = Ellipse::new(2.5, 0.7).unwrap();
        for k in 0..1000 {
            let t = -3.2 + k as f64 * 0.0064;
            let at = e.curvature_radius(t);
            // On the boundary and off it along the same ray from the centre.
            for scale in [1.0, 0.3, 1.7] {
                let p = Point::from(e.local_point(t).coords * scale);
                approx::assert_relative_eq!(e.curvature_radius_at(&p), at, max_relative = 1e-14);
            }
        }
        approx::assert_relative_eq!(
            e.curvature_radius_at(&Point::origin()),
            e.curvature_radius(0.0)
        );
    }

    #[test]
    fn closest_boundary_point_is_the_nearest_of_a_dense_sampling() {
        let e = Ellipse::new(2.0, 1.0).unwrap();
        for p in [
            Point::new(0.3, 0.2),
            Point::new(-1.7, 0.1),
            Point::new(0.5, -0.0),
            Point::new(0.0, 0.4),
            Point::new(2.5, -1.5),
            Point::new(-0.1, -0.95),
        ] {
            let x = e.closest_boundary_point(&p);
            approx::assert_relative_eq!(e.implicit(&Pose2::default(), &x), 0.0, epsilon = 1e-12);
            let sampled = (0..200_000)
                .map(|k| (e.local_point(k as f64 * std::f64::consts::TAU / 200_000.0) - p).norm())
                .fold(f64::INFINITY, f64::min);
            approx::assert_relative_eq!((x - p).norm(), sampled, epsilon = 1e-9);
            // The nearest point lies on the normal through it.
            let n = e.outward_normal(&x);
            assert!(crate::math::cross(&n, &(p - x)).abs() < 1e-9);
        }
    }

    #[test]
    fn a_line_enters_and_leaves_where_its_crossings_lie() {
        let e = Ellipse::new(2.0, 0.5).unwrap();
        for k in 0..2000 {
            let angle = k as f64 * 0.0131;
            let d = Vec2::new(angle.cos(), angle.sin());
            // Through the centre, off it, through the boundary, and with
            // a signed zero in the linear coefficient.
            for o in [
                Point::new(0.0, 0.0),
                Point::new(-0.0, 0.0),
                Point::new(0.7 * angle.sin(), -0.3),
                Point::new(2.0, 0.0),
                Point::new(1.9, 0.1 * angle.cos()),
            ] {
                let crossings = e.line_crossings_local(&o, &d);
                assert_eq!(crossings.map(|c| c.0), e.line_entry_local(&o, &d));
                assert_eq!(crossings.map(|c| c.1), e.line_exit_local(&o, &d));
                if let Some((entry, exit)) = crossings {
                    assert!(entry <= exit);
                    for s in [entry, exit] {
                        let p = o + d * s;
                        assert!(e.implicit(&Pose2::default(), &p).abs() < 1e-12);
                    }
                }
            }
        }
        // A line given in the world, with the ellipse at a pose: its
        // crossings are those of the same line in the body frame.
        let pose = Pose2::new(1.5, -0.7, 0.9);
        let (origin, direction) = (Point::new(0.2, -1.1), Vec2::new(0.8, 0.6));
        let local = (
            pose.inverse_transform_point(&origin),
            crate::math::rotate(&direction, -pose.angle),
        );
        let crossings = e.line_crossings(&pose, &origin, &direction);
        assert!(crossings.is_some());
        assert_eq!(crossings, e.line_crossings_local(&local.0, &local.1));
        // A line that misses.
        let (o, d) = (Point::new(0.0, 1.0), Vec2::x());
        assert_eq!(e.line_crossings_local(&o, &d), None);
        assert_eq!(e.line_exit_local(&o, &d), None);
    }

    #[test]
    fn aabb_of_a_turned_ellipse_touches_its_boundary() {
        let e = Ellipse::new(2.0, 1.0).unwrap();
        let pose = Pose2::new(1.0, -1.0, 0.7);
        let bb = e.aabb(&pose);
        let max_x = (0..100_000)
            .map(|k| {
                e.world_point(&pose, k as f64 * std::f64::consts::TAU / 100_000.0)
                    .x
            })
            .fold(f64::MIN, f64::max);
        approx::assert_relative_eq!(bb.max.x, max_x, max_relative = 1e-8);
    }
}
