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
//! the real quartic `(1 + u²)² g`. Its roots are isolated between its
//! critical points and refined by a safeguarded Halley iteration
//! ([`crate::math::real_roots::quartic_nonpositive`]), which returns the
//! ends of the arcs where i's boundary lies inside j; a shallow contact,
//! two close roots about a minimum of g, is found as long as the computed
//! minimum is negative. The shift `t₀` puts `u = ∞` at the point of i
//! farthest from j, where `g > 0`, so no root is lost there. The crossing
//! points follow from the rational parametrisation
//! `cos(t − t₀) = (1 − u²)/(1 + u²)`, `sin(t − t₀) = 2u/(1 + u²)`, and the
//! whole geometry is computed in i's body frame from the cosines and sines
//! of the two bodies' angles (two `sin_cos` per pair, or none when the
//! caller keeps each body's rotation:
//! [`contact_ellipse_ellipse_oriented`], which also leaves out the radii
//! of curvature where the caller's law does not read them), with no other
//! trigonometry.
//!
//! **A pair that touched at the last step** ([`contact_ellipse_ellipse_near`])
//! takes t₀ at its last contact point instead, so that the lens lies about
//! `u = 0`: its two crossings are refined from the quadratic model there
//! and shown to be the only ones by dividing the quartic by their factor
//! ([`quartic_nonpositive_about_zero`]). That spares the search for the
//! quartic's critical points; where it cannot show a single lens, the full
//! isolation answers, so the contact is the same either way (to
//! round-off).
//!
//! As in the paper, the contact point is the midpoint M of the chord P1P2,
//! the normal is perpendicular to the chord (from i towards j), the contact
//! width is B = |P1P2| and r1, r2 are the radii of curvature (eqs. 20–21)
//! where the normal through M crosses each boundary. The overlap is the
//! distance between those two crossings. When the boundaries cross four
//! times (two lens-shaped overlaps, possible for elongated ellipses), the
//! deeper lens is taken.

use super::{ContactFeatures, ContactGeometry, ContactShape};
use crate::math::real_roots::{quartic_nonpositive, quartic_nonpositive_about_zero, quartic_value};
use crate::math::{perp, Point, Pose2, Vec2};
use crate::shape::{Ellipse, Segment};
use nalgebra::UnitComplex;

/// A rotation by an angle, as its cosine and sine.
#[derive(Debug, Clone, Copy)]
struct Turn {
    c: f64,
    s: f64,
}

impl From<&UnitComplex<f64>> for Turn {
    fn from(rotation: &UnitComplex<f64>) -> Self {
        Self {
            c: rotation.cos_angle(),
            s: rotation.sin_angle(),
        }
    }
}

impl Turn {
    /// The direction of `(x, y)`; `None` for the zero vector.
    fn towards(x: f64, y: f64) -> Option<Self> {
        let length = (x * x + y * y).sqrt();
        (length > 0.0).then(|| {
            let inverse = 1.0 / length;
            Self {
                c: x * inverse,
                s: y * inverse,
            }
        })
    }

    /// The opposite direction.
    fn opposite(self) -> Self {
        Self {
            c: -self.c,
            s: -self.s,
        }
    }

    fn of(angle: f64) -> Self {
        let (s, c) = angle.sin_cos();
        Self { c, s }
    }

    fn apply(&self, v: &Vec2) -> Vec2 {
        Vec2::new(self.c * v.x - self.s * v.y, self.s * v.x + self.c * v.y)
    }

    fn undo(&self, v: &Vec2) -> Vec2 {
        Vec2::new(self.c * v.x + self.s * v.y, -self.s * v.x + self.c * v.y)
    }

    /// `self` after `other` undone: the rotation by the difference of the
    /// angles.
    fn relative_to(&self, other: &Turn) -> Turn {
        Turn {
            c: self.c * other.c + self.s * other.s,
            s: self.s * other.c - self.c * other.s,
        }
    }
}

/// The boundary of ellipse `i` in its body frame, `(a cos t, b sin t)`,
/// against the implicit function of ellipse `j`, as the quartic
/// `(1 + u²)² g(t)` in `u = tan((t − t₀)/2)`.
#[derive(Debug, Clone, Copy)]
struct BoundaryQuartic {
    /// Coefficients, highest power first.
    p: [f64; 5],
    /// `(cos t₀, sin t₀)`.
    start: Turn,
}

impl BoundaryQuartic {
    /// `g(t) = c₀ + c₁ cos t + s₁ sin t + c₂ cos 2t + s₂ sin 2t`, the
    /// implicit function of `j` at `i`'s boundary point `t`, for `i`'s
    /// centre at `d` in `j`'s frame and `i`'s frame turned by `relative`
    /// from `j`'s, then as a quartic in `u` from `t₀ = ` the angle of
    /// `start`.
    fn new(i: &Ellipse, j: &Ellipse, d: &Vec2, relative: &Turn, start: Turn) -> Self {
        let (c, s) = (relative.c, relative.s);
        // q(t) = d + M (cos t, sin t), M = R(φi − φj) diag(ai, bi).
        let m = [[c * i.a(), -s * i.b()], [s * i.a(), c * i.b()]];
        let w = j.inverse_squares();
        let (mut c0, mut c1, mut s1, mut c2, mut s2) = (-1.0, 0.0, 0.0, 0.0, 0.0);
        for k in 0..2 {
            let (dk, a, b) = (d[k], m[k][0], m[k][1]);
            c0 += w[k] * (dk * dk + 0.5 * (a * a + b * b));
            c1 += w[k] * 2.0 * dk * a;
            s1 += w[k] * 2.0 * dk * b;
            c2 += w[k] * 0.5 * (a * a - b * b);
            s2 += w[k] * a * b;
        }
        // The same terms about t₀: cos(t₀ + θ) etc.
        let (ct, st) = (start.c, start.s);
        let (c2t, s2t) = (ct * ct - st * st, 2.0 * st * ct);
        let (c1, s1) = (c1 * ct + s1 * st, -c1 * st + s1 * ct);
        let (c2, s2) = (c2 * c2t + s2 * s2t, -c2 * s2t + s2 * c2t);
        // cos θ = (1 − u²)/(1 + u²), sin θ = 2u/(1 + u²).
        Self {
            p: [
                c0 - c1 + c2,
                2.0 * s1 - 4.0 * s2,
                2.0 * c0 - 6.0 * c2,
                2.0 * s1 + 4.0 * s2,
                c0 + c1 + c2,
            ],
            start,
        }
    }

    /// `g` at `t₀ + π` (`u = ∞`).
    fn at_infinity(&self) -> f64 {
        self.p[0]
    }

    /// `(1 + u²)² g` at `u`: the sign of `g` there.
    fn value(&self, u: f64) -> f64 {
        quartic_value(&self.p, u)
    }

    /// `(cos t, sin t)` at `u`, by the rational parametrisation about t₀.
    fn direction(&self, u: f64) -> Vec2 {
        let (cos, sin) = if u.abs() <= 1.0 {
            let w = 1.0 / (1.0 + u * u);
            ((1.0 - u * u) * w, 2.0 * u * w)
        } else {
            // Far out, in v = 1/u.
            let v = 1.0 / u;
            let w = 1.0 / (v * v + 1.0);
            ((v * v - 1.0) * w, 2.0 * v * w)
        };
        self.start.apply(&Vec2::new(cos, sin))
    }
}

/// How far ellipse `e` turned by `turn` reaches from its centre along the
/// unit direction `u`: `√((a u₁)² + (b u₂)²)`, with `(u₁, u₂)` the
/// direction in the ellipse's axes.
fn support(e: &Ellipse, turn: &Turn, u: &Vec2) -> f64 {
    let local = turn.undo(u);
    let (x, y) = (e.a() * local.x, e.b() * local.y);
    (x * x + y * y).sqrt()
}

/// Contact of ellipse `i` at `pose_i` with ellipse `j` at `pose_j` (a circle
/// is passed as an ellipse with a = b); `None` when they do not overlap.
pub fn contact_ellipse_ellipse(
    i: &Ellipse,
    pose_i: &Pose2,
    j: &Ellipse,
    pose_j: &Pose2,
) -> Option<ContactGeometry> {
    contact_ellipse_ellipse_near(i, pose_i, j, pose_j, None)
}

/// [`contact_ellipse_ellipse`] given where the pair touched at the last
/// step (`near`, the contact point, world): the crossings are then sought
/// about the point of i's boundary in that direction, by
/// [`quartic_nonpositive_about_zero`], which needs a few Halley steps
/// where the search for every root needs its critical points first. The
/// result is the same, to round-off, whenever the fast path shows that
/// the overlap is a single lens; otherwise, or without `near`, the roots
/// are isolated in full.
pub fn contact_ellipse_ellipse_near(
    i: &Ellipse,
    pose_i: &Pose2,
    j: &Ellipse,
    pose_j: &Pose2,
    near: Option<&Point>,
) -> Option<ContactGeometry> {
    contact_with_turns(i, pose_i, j, pose_j, near, ContactShape::Computed, || {
        (Turn::of(pose_i.angle), Turn::of(pose_j.angle))
    })
}

/// An ellipse at a pose, with the rotation of the pose's angle
/// (`UnitComplex::new(pose.angle)`) kept beside it.
#[derive(Debug, Clone, Copy)]
pub struct OrientedEllipse<'a> {
    /// The shape.
    pub shape: &'a Ellipse,
    /// Where it is.
    pub pose: &'a Pose2,
    /// The rotation of `pose.angle`.
    pub rotation: &'a UnitComplex<f64>,
}

/// [`contact_ellipse_ellipse_near`] given the rotations of the two poses'
/// angles, for a caller that keeps them per body rather than per pair,
/// and with the radii of curvature only if `shape` asks for them (the
/// width comes with the normal, so it is always computed).
pub fn contact_ellipse_ellipse_oriented(
    i: OrientedEllipse<'_>,
    j: OrientedEllipse<'_>,
    near: Option<&Point>,
    shape: ContactShape,
) -> Option<ContactGeometry> {
    debug_assert!(
        [&i, &j]
            .iter()
            .all(|e| (e.rotation.angle_to(&UnitComplex::new(e.pose.angle))).abs() < 1e-9),
        "a rotation is not that of its pose's angle"
    );
    contact_with_turns(i.shape, i.pose, j.shape, j.pose, near, shape, || {
        (Turn::from(i.rotation), Turn::from(j.rotation))
    })
}

/// The contact, with the bodies' rotations taken from `turns` once the
/// pair is close enough to need them.
#[inline]
fn contact_with_turns(
    i: &Ellipse,
    pose_i: &Pose2,
    j: &Ellipse,
    pose_j: &Pose2,
    near: Option<&Point>,
    shape: ContactShape,
    turns: impl FnOnce() -> (Turn, Turn),
) -> Option<ContactGeometry> {
    let between = pose_j.position - pose_i.position;
    let bound = i.a() + j.a();
    if between.norm_squared() >= bound * bound {
        return None;
    }
    let (turn_i, turn_j) = turns();
    let relative = turn_i.relative_to(&turn_j);
    let d = turn_j.undo(&(-between));
    let pair = |quartic: BoundaryQuartic| Pair {
        i,
        j,
        d,
        relative,
        quartic,
        shape,
    };
    let world = |lens: Lens| ContactGeometry {
        point: pose_i.position + turn_i.apply(&lens.point.coords),
        normal: turn_i.apply(&lens.normal),
        overlap: lens.overlap,
        width: lens.width,
        curvature_radius_a: lens.curvature_radius_i,
        curvature_radius_b: lens.curvature_radius_j,
        features: ContactFeatures::WHOLE,
    };
    // t₀: the direction of the last contact point from i's centre, in i's
    // parametric angle.
    if let Some(start) = near.and_then(|near| {
        let local = turn_i.undo(&(near - pose_i.position));
        Turn::towards(local.x / i.a(), local.y / i.b())
    }) {
        let quartic = BoundaryQuartic::new(i, j, &d, &relative, start);
        if let Some((r1, r2)) = quartic_nonpositive_about_zero(quartic.p) {
            if let Some(lens) = pair(quartic).lens(r1, r2) {
                return Some(world(lens));
            }
        }
    }
    // Apart along the line of centres: the two supports along it fall
    // short of the distance, by a margin (1e-6 of it) that keeps the
    // decision clear of the root finder's tolerances below, so no pair it
    // would find touching is refused here. This spares the root finding
    // for most neighbours of a packing that do not touch. (A pair that
    // touched at the last step and still does was usually found above.)
    let distance = between.norm();
    if distance > 0.0 {
        let direction = between * (1.0 / distance);
        let reach = support(i, &turn_i, &direction) + support(j, &turn_j, &direction);
        if reach < distance * (1.0 - 1e-6) {
            return None;
        }
    }
    // t₀ + π: the point of i farthest from j's centre, where g > 0 unless i
    // lies inside j or, elongated, deep in j.
    let away = turn_i.undo(&(-between));
    let start = Turn::towards(i.a() * away.x, i.b() * away.y)
        .map_or(Turn { c: -1.0, s: 0.0 }, Turn::opposite);
    let quartic = BoundaryQuartic::new(i, j, &d, &relative, start);
    if quartic.at_infinity() <= 0.0 {
        return deep_in_j(quartic, pair(quartic))
            .map(world)
            .or_else(|| Some(containment(i, pose_i, j, pose_j)));
    }
    let scale = quartic.p.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let roots = if quartic.p[0] > 1e-14 * scale {
        quartic_nonpositive(quartic.p)
    } else {
        Default::default()
    };
    if roots.is_empty() {
        // No crossing: apart, or j entirely inside i.
        return if i.implicit(pose_i, &pose_j.position) < 0.0 {
            Some(containment(i, pose_i, j, pose_j))
        } else {
            None
        };
    }
    // The arcs of i's boundary inside j lie between pairs of roots in
    // increasing u (counter-clockwise); each bounds one lens of overlap.
    // With four crossings there are two; the deeper one (by overlap, which
    // does not depend on the order of the pair) is the contact.
    let pair = pair(quartic);
    let mut best: Option<Lens> = None;
    for ends in roots.as_slice().chunks_exact(2) {
        let (start, end) = (ends[0], ends[1]);
        let inside = quartic.value(0.5 * (start + end)) < 0.0;
        if !inside {
            continue;
        }
        if let Some(lens) = pair.lens(start, end) {
            if best.is_none_or(|b| lens.overlap > b.overlap) {
                best = Some(lens);
            }
        }
    }
    best.map(world)
}

/// The contact when the point of i farthest from j's centre (`u = ∞`)
/// lies inside j: either i lies inside j (`None`), or i, elongated and
/// deep in j, leaves j elsewhere. The arcs of i outside j are where the
/// negated quartic is not positive; the arcs inside run between them, the
/// last one through `u = ∞`. The deepest lens is the contact, as in the
/// ordinary case.
fn deep_in_j(quartic: BoundaryQuartic, pair: Pair<'_>) -> Option<Lens> {
    let negated = quartic.p.map(|v| -v);
    if negated[0] <= 0.0 {
        return None;
    }
    let outside = quartic_nonpositive(negated);
    let ends = outside.as_slice();
    (0..ends.len() / 2)
        .filter_map(|k| pair.lens(ends[2 * k + 1], ends[(2 * k + 2) % ends.len()]))
        .max_by(|a, b| a.overlap.total_cmp(&b.overlap))
}

/// A pair of ellipses seen from `i`'s body frame.
struct Pair<'a> {
    i: &'a Ellipse,
    j: &'a Ellipse,
    /// `i`'s centre in `j`'s frame.
    d: Vec2,
    /// `i`'s frame turned from `j`'s.
    relative: Turn,
    quartic: BoundaryQuartic,
    /// Whether the radii of curvature are wanted.
    shape: ContactShape,
}

/// A lens's contact geometry in `i`'s body frame.
#[derive(Debug, Clone, Copy)]
struct Lens {
    point: Point,
    normal: Vec2,
    overlap: f64,
    width: f64,
    curvature_radius_i: f64,
    curvature_radius_j: f64,
}

impl Pair<'_> {
    /// `i`'s boundary point at `u`, body frame.
    fn boundary_point(&self, u: f64) -> Point {
        let direction = self.quartic.direction(u);
        Point::new(self.i.a() * direction.x, self.i.b() * direction.y)
    }

    /// The contact geometry of the lens bounded by i's boundary arc from
    /// `start` to `end` (inside j).
    fn lens(&self, start: f64, end: f64) -> Option<Lens> {
        let (i, j) = (self.i, self.j);
        let p1 = self.boundary_point(start);
        let p2 = self.boundary_point(end);
        let midpoint = Point::from(0.5 * (p1.coords + p2.coords));
        let chord = p2 - p1;
        let width = chord.norm();
        // The arc runs counter-clockwise from P1 to P2, so it lies to the
        // right of the chord: the normal from i into j is the chord's
        // right perpendicular. A chord too short to have a direction
        // takes i's outward normal there.
        let normal = if width > 0.0 {
            -perp(&(chord * (1.0 / width)))
        } else {
            i.outward_normal(&midpoint)
        };
        // Crossings of the normal line through M with both boundaries.
        let s_i = i.line_exit_local(&midpoint, &normal)?;
        let midpoint_j = Point::from(self.d + self.relative.apply(&midpoint.coords));
        let normal_j = self.relative.apply(&normal);
        let s_j = j.line_entry_local(&midpoint_j, &normal_j)?;
        let (curvature_radius_i, curvature_radius_j) = match self.shape {
            ContactShape::Computed => (
                i.curvature_radius_at(&(midpoint + normal * s_i)),
                j.curvature_radius_at(&(midpoint_j + normal_j * s_j)),
            ),
            ContactShape::Skipped => (f64::NAN, f64::NAN),
        };
        Some(Lens {
            point: midpoint,
            normal,
            overlap: (s_i - s_j).max(0.0),
            width,
            curvature_radius_i,
            curvature_radius_j,
        })
    }
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
    let turn = Turn::of(pose.angle);
    let outward = turn.undo(&(-inner));
    // Support point of the ellipse in the direction out of the wall.
    let reach = support(e, &turn, &(-inner));
    let distance = (pose.position - origin).dot(&inner);
    let overlap = reach - distance;
    if overlap <= 0.0 {
        return None;
    }
    // The line in the body frame.
    let start = Point::from(turn.undo(&(origin - pose.position)));
    let crossings = e.line_crossings_local(&start, &turn.undo(direction))?;
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
            curvature_radius_a: e.curvature_radius_at(&self.deepest_local),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::ellipse_contact::touching_distance;

    /// A pair that touched at the last step, where it touches now, takes
    /// the fast path: the search about its contact point answers, for
    /// aspect ratios 1–4 and overlaps of 0.1–20 % of the smaller b in
    /// every direction and orientation.
    #[test]
    fn the_fast_path_answers_about_the_contact_point() {
        let mut cases = 0;
        for (k, aspect) in [1.0, 1.5, 2.0, 4.0].into_iter().enumerate() {
            let i = Ellipse::new(aspect * 0.5, 0.5).unwrap();
            let j = Ellipse::new(0.4 * (1.0 + k as f64), 0.4).unwrap();
            for m in 0..24 {
                let (phi_i, phi_j, dir) = (0.37 * m as f64, 1.1 - 0.29 * m as f64, 0.26 * m as f64);
                let pose_i = Pose2::new(0.0, 0.0, phi_i);
                let direction = Vec2::new(dir.cos(), dir.sin());
                for overlap in [0.001, 0.02, 0.1, 0.2] {
                    let d = touching_distance(&i, &pose_i, &j, phi_j, &direction) - overlap * 0.4;
                    let pose_j = Pose2::new(d * direction.x, d * direction.y, phi_j);
                    let contact = contact_ellipse_ellipse(&i, &pose_i, &j, &pose_j).unwrap();
                    let (turn_i, turn_j) = (Turn::of(phi_i), Turn::of(phi_j));
                    let local = turn_i.undo(&(contact.point - pose_i.position));
                    let start = Turn::towards(local.x / i.a(), local.y / i.b()).unwrap();
                    let d = turn_j.undo(&(pose_i.position - pose_j.position));
                    let quartic =
                        BoundaryQuartic::new(&i, &j, &d, &turn_i.relative_to(&turn_j), start);
                    assert!(
                        quartic_nonpositive_about_zero(quartic.p).is_some(),
                        "aspect {aspect}, case {m}, overlap {overlap}: {:?}",
                        quartic.p
                    );
                    cases += 1;
                }
            }
        }
        assert_eq!(cases, 384);
    }
}
