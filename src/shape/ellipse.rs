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
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipse {
    a: f64,
    b: f64,
}

impl Ellipse {
    /// An ellipse with semi-major axis `a` and semi-minor axis `b`.
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
        Ok(Self { a, b })
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
        let (ia2, ib2) = (1.0 / (self.a * self.a), 1.0 / (self.b * self.b));
        let qa = d.x * d.x * ia2 + d.y * d.y * ib2;
        let qb = 2.0 * (o.x * d.x * ia2 + o.y * d.y * ib2);
        let qc = o.x * o.x * ia2 + o.y * o.y * ib2 - 1.0;
        let disc = qb * qb - 4.0 * qa * qc;
        if disc < 0.0 || qa <= 0.0 {
            return None;
        }
        let root = disc.sqrt();
        // Numerically stable pair of roots.
        let q = -0.5 * (qb + qb.signum() * root);
        let (r1, r2) = if q != 0.0 {
            (q / qa, qc / q)
        } else {
            (0.0, 0.0)
        };
        Some((r1.min(r2), r1.max(r2)))
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
    fn degrees_of_freedom(&self) -> usize {
        3
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
