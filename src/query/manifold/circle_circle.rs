//! Contact between two circles.

use super::{ContactFeatures, ContactGeometry, ContactShape};
use crate::math::{Point, Pose2, Vec2};
use crate::shape::Circle;

/// The contact of circle `a` at `pose_a` with circle `b` at `pose_b`, or
/// `None` when they do not overlap.
///
/// The contact point is the midpoint of the chord P1P2 through the two
/// intersection points, the normal is the line of centres (perpendicular to
/// the chord) and the width is the chord length, as paper 000 defines them
/// for ellipses (for circles the construction is exact and closed-form).
/// Coincident centres have no defined normal; +x is used.
#[inline]
pub fn contact_circle_circle(
    a: &Circle,
    pose_a: &Pose2,
    b: &Circle,
    pose_b: &Pose2,
) -> Option<ContactGeometry> {
    contact_circle_circle_shaped(a, pose_a, b, pose_b, ContactShape::Computed)
}

/// [`contact_circle_circle`] with the width (a square root of its own)
/// only if `shape` asks for it; NaN otherwise.
#[inline]
pub fn contact_circle_circle_shaped(
    a: &Circle,
    pose_a: &Pose2,
    b: &Circle,
    pose_b: &Pose2,
    shape: ContactShape,
) -> Option<ContactGeometry> {
    contact_circles(
        a.radius(),
        &pose_a.position,
        b.radius(),
        &pose_b.position,
        shape,
    )
}

/// [`contact_circle_circle_shaped`] for circles of radii `ra` and `rb`
/// centred at `centre_a` and `centre_b` (a circle's contact does not
/// depend on its angle).
#[inline]
pub(crate) fn contact_circles(
    ra: f64,
    centre_a: &Point,
    rb: f64,
    centre_b: &Point,
    shape: ContactShape,
) -> Option<ContactGeometry> {
    let delta = centre_b - centre_a;
    // Clearly apart, without the square root: the margin 1e-12 covers the
    // rounding of both sides, so this refuses only pairs the test below
    // refuses too.
    let reach = ra + rb;
    if delta.norm_squared() > reach * reach * (1.0 + 1e-12) {
        return None;
    }
    let distance = delta.norm();
    let overlap = ra + rb - distance;
    if overlap <= 0.0 {
        return None;
    }
    let normal = if distance > 0.0 {
        delta / distance
    } else {
        Vec2::x()
    };
    // Distance from A's centre to the chord, and the chord's half length.
    let (along, half_width) = if distance > (ra - rb).abs() {
        let along = (distance * distance + ra * ra - rb * rb) / (2.0 * distance);
        let half_width = match shape {
            ContactShape::Computed => (ra * ra - along * along).max(0.0).sqrt(),
            ContactShape::Skipped => f64::NAN,
        };
        (along, half_width)
    } else {
        // One circle inside the other: no chord; use the deepest point.
        (ra - 0.5 * overlap, 0.0)
    };
    Some(ContactGeometry {
        point: centre_a + normal * along,
        normal,
        overlap,
        width: 2.0 * half_width,
        curvature_radius_a: ra,
        curvature_radius_b: rb,
        features: ContactFeatures::WHOLE,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// Without the width, the rest of the contact is the very same.
    #[test]
    fn a_contact_without_its_width_is_otherwise_the_same() {
        let (a, b) = (Circle::new(1.0).unwrap(), Circle::new(0.6).unwrap());
        for k in 0..200 {
            let angle = 0.1 * k as f64;
            let d = 1.0 + 0.55 * (k as f64 / 200.0);
            let (pa, pb) = (
                Pose2::new(0.3, -0.2, 0.0),
                Pose2::new(0.3 + d * angle.cos(), -0.2 + d * angle.sin(), 0.0),
            );
            let full = contact_circle_circle(&a, &pa, &b, &pb).unwrap();
            let without =
                contact_circle_circle_shaped(&a, &pa, &b, &pb, ContactShape::Skipped).unwrap();
            assert!(full.width > 0.0 && without.width.is_nan());
            assert_eq!(
                ContactGeometry {
                    width: full.width,
                    ..without
                },
                full
            );
        }
    }

    /// A circle's contact does not depend on its angle (the explicit
    /// driver's pairs of circles take it from the centres alone): the
    /// same bits at any angles of the two circles.
    #[test]
    fn a_circle_pair_does_not_read_the_angles() {
        let (a, b) = (Circle::new(0.7).unwrap(), Circle::new(0.45).unwrap());
        for k in 0..100 {
            let t = 0.37 * k as f64;
            let d = 0.3 + 0.85 * (k as f64 / 100.0);
            let (pa, pb) = (
                Pose2::new(-0.1, 0.4, 0.0),
                Pose2::new(-0.1 + d * t.cos(), 0.4 + d * t.sin(), 0.0),
            );
            for shape in [ContactShape::Computed, ContactShape::Skipped] {
                let turned = contact_circle_circle_shaped(
                    &a,
                    &Pose2 {
                        angle: 1.3 * t,
                        ..pa
                    },
                    &b,
                    &Pose2 {
                        angle: -2.9 + t,
                        ..pb
                    },
                    shape,
                );
                let plain = contact_circle_circle_shaped(&a, &pa, &b, &pb, shape);
                assert!(plain.is_some(), "case {k}: the circles overlap");
                // (NaN widths compare by their bits.)
                assert_eq!(format!("{turned:?}"), format!("{plain:?}"), "case {k}");
            }
        }
    }

    #[test]
    fn equal_circles_touch_at_the_midpoint_with_the_chord_width() {
        let c = Circle::new(1.0).unwrap();
        let g = contact_circle_circle(
            &c,
            &Pose2::new(0.0, 0.0, 0.0),
            &c,
            &Pose2::new(1.8, 0.0, 0.0),
        )
        .unwrap();
        assert_relative_eq!(g.overlap, 0.2, epsilon = 1e-12);
        assert_relative_eq!(g.point.x, 0.9, epsilon = 1e-12);
        assert_relative_eq!(g.width, 2.0 * (1.0f64 - 0.81).sqrt(), epsilon = 1e-12);
        assert_relative_eq!(g.normal.x, 1.0);
    }

    #[test]
    fn separated_circles_have_no_contact() {
        let c = Circle::new(1.0).unwrap();
        assert!(
            contact_circle_circle(&c, &Pose2::default(), &c, &Pose2::new(2.0, 0.0, 0.0)).is_none()
        );
    }
}
