//! Contact of ellipses (paper 000, §2(1)–(3)) with each other, with circles
//! and with walls.
//!
//! The paper finds the intersection points P1, P2 of two ellipses by
//! Newton's method on its distance function L(θ) (eqs. 2–11). Newton can
//! diverge, converge to the far side or miss a shallow contact, so here the
//! intersection points are found exactly: the boundary of ellipse i,
//! `p(t) = cᵢ + Rᵢ (aᵢ cos t, bᵢ sin t)`, put into the implicit equation of
//! ellipse j gives `g(t) = c₀ + c₁ cos t + s₁ sin t + c₂ cos 2t + s₂ sin 2t`,
//! whose zeros are the intersection points; with `u = tan((t − t₀)/2)` it is
//! a real quartic, solved through the eigenvalues of its companion matrix
//! and polished by Newton on `g`. The shift `t₀` puts `u = ∞` at the point
//! of i farthest from j, where `g > 0`, so no root is lost.
//!
//! As in the paper, the contact point is the midpoint M of the chord P1P2,
//! the normal is perpendicular to the chord (from i towards j), the contact
//! width is B = |P1P2| and r1, r2 are the radii of curvature (eqs. 20–21)
//! where the normal through M crosses each boundary. The overlap is the
//! distance between those two crossings. When the boundaries cross four
//! times (two lens-shaped overlaps, possible for elongated ellipses), the
//! deeper lens is taken.

use super::{ContactFeatures, ContactGeometry};
use crate::math::{perp, Point, Pose2, Vec2};
use crate::shape::{Ellipse, Segment};
use nalgebra::Matrix4;

/// `g(t) = c₀ + c₁ cos t + s₁ sin t + c₂ cos 2t + s₂ sin 2t`.
#[derive(Debug, Clone, Copy)]
struct TrigQuadratic {
    c0: f64,
    c1: f64,
    s1: f64,
    c2: f64,
    s2: f64,
}

impl TrigQuadratic {
    fn value(&self, t: f64) -> f64 {
        self.c0
            + self.c1 * t.cos()
            + self.s1 * t.sin()
            + self.c2 * (2.0 * t).cos()
            + self.s2 * (2.0 * t).sin()
    }

    fn derivative(&self, t: f64) -> f64 {
        -self.c1 * t.sin() + self.s1 * t.cos() - 2.0 * self.c2 * (2.0 * t).sin()
            + 2.0 * self.s2 * (2.0 * t).cos()
    }

    /// The implicit function of `j` along the boundary of `i`.
    fn along(i: &Ellipse, pose_i: &Pose2, j: &Ellipse, pose_j: &Pose2) -> Self {
        let d = pose_j.inverse_transform_point(&pose_i.position).coords;
        let (s, c) = (pose_i.angle - pose_j.angle).sin_cos();
        // q(t) = d + M (cos t, sin t), M = R(φi − φj) diag(ai, bi).
        let m = [[c * i.a(), -s * i.b()], [s * i.a(), c * i.b()]];
        let w = [1.0 / (j.a() * j.a()), 1.0 / (j.b() * j.b())];
        let mut g = Self {
            c0: -1.0,
            c1: 0.0,
            s1: 0.0,
            c2: 0.0,
            s2: 0.0,
        };
        for k in 0..2 {
            let (dk, a, b) = (d[k], m[k][0], m[k][1]);
            g.c0 += w[k] * (dk * dk + 0.5 * (a * a + b * b));
            g.c1 += w[k] * 2.0 * dk * a;
            g.s1 += w[k] * 2.0 * dk * b;
            g.c2 += w[k] * 0.5 * (a * a - b * b);
            g.s2 += w[k] * a * b;
        }
        g
    }

    /// All zeros in [t₀ − π, t₀ + π), sorted, given `g(t₀ + π) > 0`.
    fn zeros(&self, t0: f64) -> Vec<f64> {
        let (s0, c0) = t0.sin_cos();
        let (s20, c20) = (2.0 * t0).sin_cos();
        let c1 = self.c1 * c0 + self.s1 * s0;
        let s1 = -self.c1 * s0 + self.s1 * c0;
        let c2 = self.c2 * c20 + self.s2 * s20;
        let s2 = -self.c2 * s20 + self.s2 * c20;
        // (1 + u²)² g as a quartic in u = tan((t − t₀)/2), highest first.
        let p = [
            self.c0 - c1 + c2,
            2.0 * s1 - 4.0 * s2,
            2.0 * self.c0 - 6.0 * c2,
            2.0 * s1 + 4.0 * s2,
            self.c0 + c1 + c2,
        ];
        let scale = p.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if p[0].abs() <= 1e-14 * scale {
            return Vec::new();
        }
        let companion = Matrix4::new(
            -p[1] / p[0],
            -p[2] / p[0],
            -p[3] / p[0],
            -p[4] / p[0],
            1.0,
            0.0,
            0.0,
            0.0,
            0.0,
            1.0,
            0.0,
            0.0,
            0.0,
            0.0,
            1.0,
            0.0,
        );
        let mut roots: Vec<f64> = companion
            .complex_eigenvalues()
            .iter()
            .filter(|z| z.im.abs() <= 1e-6 * (1.0 + z.re.abs()))
            .map(|z| t0 + 2.0 * z.re.atan())
            .map(|t| self.polish(t))
            .collect();
        roots.sort_by(f64::total_cmp);
        roots.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
        roots
    }

    /// A few Newton steps on g, kept only while they reduce |g|.
    fn polish(&self, mut t: f64) -> f64 {
        for _ in 0..8 {
            let (g, dg) = (self.value(t), self.derivative(t));
            if dg == 0.0 {
                break;
            }
            let next = t - g / dg;
            if self.value(next).abs() < g.abs() {
                t = next;
            } else {
                break;
            }
        }
        t
    }
}

/// The parametric angle of a body-frame point of `e`.
pub(crate) fn parametric_angle_of(e: &Ellipse, local: &Point) -> f64 {
    (local.y / e.b()).atan2(local.x / e.a())
}

/// How far ellipse `e` at `pose` reaches from its centre along the unit
/// direction `u`: `√((a u₁)² + (b u₂)²)`, with `(u₁, u₂)` the direction in
/// the ellipse's axes.
fn support(e: &Ellipse, pose: &Pose2, u: &Vec2) -> f64 {
    let local = pose.inverse_transform_vector(u);
    (e.a() * local.x).hypot(e.b() * local.y)
}

/// Contact of ellipse `i` at `pose_i` with ellipse `j` at `pose_j` (a circle
/// is passed as an ellipse with a = b); `None` when they do not overlap.
pub fn contact_ellipse_ellipse(
    i: &Ellipse,
    pose_i: &Pose2,
    j: &Ellipse,
    pose_j: &Pose2,
) -> Option<ContactGeometry> {
    let between = pose_j.position - pose_i.position;
    let distance = between.norm();
    if distance >= i.a() + j.a() {
        return None;
    }
    // Apart along the line of centres: the two supports along it fall
    // short of the distance, by a margin (1e-6 of it) that keeps the
    // decision clear of the root finder's tolerances below, so no pair it
    // would find touching is refused here. This spares the root finding
    // for most neighbours of a packing that do not touch.
    if distance > 0.0 {
        let direction = between / distance;
        let reach = support(i, pose_i, &direction) + support(j, pose_j, &direction);
        if reach < distance * (1.0 - 1e-6) {
            return None;
        }
    }
    let g = TrigQuadratic::along(i, pose_i, j, pose_j);
    // t₀ + π: the point of i farthest from j's centre, where g > 0 unless i
    // lies inside j.
    let away = pose_i.inverse_transform_vector(&(-between));
    let t_far = (i.b() * away.y).atan2(i.a() * away.x);
    let t0 = t_far - std::f64::consts::PI;
    if g.value(t_far) <= 0.0 {
        return Some(containment(i, pose_i, j, pose_j));
    }
    let roots = g.zeros(t0);
    if roots.len() < 2 {
        // No crossing: apart, or j entirely inside i.
        return if i.implicit(pose_i, &pose_j.position) < 0.0 {
            Some(containment(i, pose_i, j, pose_j))
        } else {
            None
        };
    }
    // Arcs between consecutive zeros where i's boundary is inside j: each
    // bounds one lens of overlap. With four crossings there are two; the
    // deeper one (by overlap, which does not depend on the order of the
    // pair) is the contact.
    let mut best: Option<ContactGeometry> = None;
    for k in 0..roots.len() {
        let start = roots[k];
        let end = if k + 1 < roots.len() {
            roots[k + 1]
        } else {
            roots[0] + std::f64::consts::TAU
        };
        if g.value(0.5 * (start + end)) >= 0.0 {
            continue;
        }
        if let Some(lens) = lens_geometry(i, pose_i, j, pose_j, start, end) {
            if best.is_none_or(|b| lens.overlap > b.overlap) {
                best = Some(lens);
            }
        }
    }
    best
}

/// The contact geometry of the lens bounded by i's boundary arc
/// `[start, end]` (inside j).
fn lens_geometry(
    i: &Ellipse,
    pose_i: &Pose2,
    j: &Ellipse,
    pose_j: &Pose2,
    start: f64,
    end: f64,
) -> Option<ContactGeometry> {
    let p1 = i.world_point(pose_i, start);
    let p2 = i.world_point(pose_i, end);
    let midpoint = Point::from(0.5 * (p1.coords + p2.coords));
    let chord = p2 - p1;
    let width = chord.norm();
    let arc_point = i.world_point(pose_i, 0.5 * (start + end));
    let mut normal = if width > 0.0 {
        perp(&(chord / width))
    } else {
        (arc_point - midpoint)
            .try_normalize(0.0)
            .unwrap_or_else(Vec2::x)
    };
    if normal.dot(&(arc_point - midpoint)) < 0.0 {
        normal = -normal;
    }
    // Crossings of the normal line through M with both boundaries.
    let (_, s_i) = i.line_crossings(pose_i, &midpoint, &normal)?;
    let (s_j, _) = j.line_crossings(pose_j, &midpoint, &normal)?;
    let on_i = midpoint + normal * s_i;
    let on_j = midpoint + normal * s_j;
    Some(ContactGeometry {
        point: midpoint,
        normal,
        overlap: (s_i - s_j).max(0.0),
        width,
        curvature_radius_a: i.curvature_radius(parametric_angle_of(
            i,
            &pose_i.inverse_transform_point(&on_i),
        )),
        curvature_radius_b: j.curvature_radius(parametric_angle_of(
            j,
            &pose_j.inverse_transform_point(&on_j),
        )),
        features: ContactFeatures::WHOLE,
    })
}

/// One ellipse inside the other: no chord exists; push along the line of
/// centres with an overlap of the smaller full width.
fn containment(i: &Ellipse, pose_i: &Pose2, j: &Ellipse, pose_j: &Pose2) -> ContactGeometry {
    let between = pose_j.position - pose_i.position;
    let normal = if between.norm() > 0.0 {
        between.normalize()
    } else {
        Vec2::x()
    };
    ContactGeometry {
        point: Point::from(0.5 * (pose_i.position.coords + pose_j.position.coords)),
        normal,
        overlap: 2.0 * i.b().min(j.b()),
        width: 2.0 * i.b().min(j.b()),
        curvature_radius_a: i.b(),
        curvature_radius_b: j.b(),
        features: ContactFeatures::WHOLE,
    }
}

/// An ellipse against a line with material on the ellipse's side, before
/// any test of where along the line the contact lies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct EllipseLine {
    /// The unit normal of the line towards the ellipse's side.
    pub inner: Vec2,
    /// Signed distance of the ellipse's centre from the line, along `inner`.
    pub distance: f64,
    /// Depth of the ellipse's deepest point beyond the line.
    pub overlap: f64,
    /// Where the line cuts the ellipse, along the line from its origin.
    pub crossings: (f64, f64),
    /// The deepest point, body frame.
    pub deepest_local: Point,
}

/// The ellipse `e` at `pose` against the line through `origin` along the
/// unit `direction`, material on its left (inner normal `perp(direction)`);
/// `None` when the ellipse does not reach beyond the line.
pub(crate) fn ellipse_line(
    e: &Ellipse,
    pose: &Pose2,
    origin: &Point,
    direction: &Vec2,
) -> Option<EllipseLine> {
    let inner = perp(direction);
    let outward = pose.inverse_transform_vector(&(-inner));
    // Support point of the ellipse in the direction out of the wall.
    let reach = ((e.a() * outward.x).powi(2) + (e.b() * outward.y).powi(2)).sqrt();
    let distance = (pose.position - origin).dot(&inner);
    let overlap = reach - distance;
    if overlap <= 0.0 {
        return None;
    }
    let crossings = e.line_crossings(pose, origin, direction)?;
    Some(EllipseLine {
        inner,
        distance,
        overlap,
        crossings,
        deepest_local: Point::new(
            e.a() * e.a() * outward.x / reach,
            e.b() * e.b() * outward.y / reach,
        ),
    })
}

impl EllipseLine {
    /// The contact geometry with the point at `along` on the line and the
    /// contact width `width`; normal from the ellipse into the line.
    pub(crate) fn geometry(
        &self,
        e: &Ellipse,
        origin: &Point,
        direction: &Vec2,
        along: f64,
        width: f64,
    ) -> ContactGeometry {
        ContactGeometry {
            point: origin + direction * along,
            normal: -self.inner,
            overlap: self.overlap,
            width,
            curvature_radius_a: e.curvature_radius(parametric_angle_of(e, &self.deepest_local)),
            curvature_radius_b: f64::INFINITY,
            features: ContactFeatures::WHOLE,
        }
    }
}

/// Contact of ellipse `e` at `pose` with the fixed one-sided wall `wall`
/// (material on its left): the overlap is the depth of the ellipse's
/// deepest point beyond the wall line, P1 and P2 are where the wall line
/// cuts the ellipse, M their midpoint and the normal points from the
/// ellipse into the wall. The contact must lie within the segment.
pub fn contact_ellipse_segment(
    e: &Ellipse,
    pose: &Pose2,
    wall: &Segment,
) -> Option<ContactGeometry> {
    let length = wall.length();
    if length <= 0.0 {
        return None;
    }
    let direction = wall.direction();
    let line = ellipse_line(e, pose, &wall.start, &direction)?;
    let (s1, s2) = line.crossings;
    let midpoint_s = 0.5 * (s1 + s2);
    if !(0.0..=length).contains(&midpoint_s) {
        return None;
    }
    Some(line.geometry(e, &wall.start, &direction, midpoint_s, s2 - s1))
}
