//! The pair dispatcher: picks the contact routine for a pair of shapes.
//!
//! One function per shape pair, written once in a fixed order (circle before
//! segment); the dispatcher swaps the pair where needed and flips the
//! result, so the normal always points from the first argument into the
//! second. A pair without a routine is `Err(UnsupportedPair)`, never a panic.

use super::circle_circle::contact_circle_circle;
use super::circle_segment::contact_circle_segment;
use super::ellipse::{contact_ellipse_ellipse, contact_ellipse_segment};
use super::ContactGeometry;
use crate::error::{DismechError, Result};
use crate::math::Pose2;
use crate::shape::{AnyShape2, Circle, Ellipse};

/// A circle as the a = b ellipse, for circle–ellipse pairs.
fn as_ellipse(c: &Circle) -> Result<Ellipse> {
    Ellipse::new(c.radius(), c.radius())
}

/// The contact of `a` at `pose_a` with `b` at `pose_b`: `Ok(None)` when
/// they do not touch. Segments are taken in world coordinates (their pose is
/// ignored): walls are fixed.
pub fn contact_2d(
    a: &AnyShape2,
    pose_a: &Pose2,
    b: &AnyShape2,
    pose_b: &Pose2,
) -> Result<Option<ContactGeometry>> {
    match (a, b) {
        (AnyShape2::Circle(ca), AnyShape2::Circle(cb)) => {
            Ok(contact_circle_circle(ca, pose_a, cb, pose_b))
        }
        (AnyShape2::Circle(c), AnyShape2::Segment(s)) => Ok(contact_circle_segment(c, pose_a, s)),
        (AnyShape2::Segment(s), AnyShape2::Circle(c)) => {
            Ok(contact_circle_segment(c, pose_b, s).map(|g| g.flipped()))
        }
        (AnyShape2::Ellipse(ea), AnyShape2::Ellipse(eb)) => {
            Ok(contact_ellipse_ellipse(ea, pose_a, eb, pose_b))
        }
        (AnyShape2::Ellipse(e), AnyShape2::Circle(c)) => {
            Ok(contact_ellipse_ellipse(e, pose_a, &as_ellipse(c)?, pose_b))
        }
        (AnyShape2::Circle(c), AnyShape2::Ellipse(e)) => {
            Ok(contact_ellipse_ellipse(&as_ellipse(c)?, pose_a, e, pose_b))
        }
        (AnyShape2::Ellipse(e), AnyShape2::Segment(s)) => Ok(contact_ellipse_segment(e, pose_a, s)),
        (AnyShape2::Segment(s), AnyShape2::Ellipse(e)) => {
            Ok(contact_ellipse_segment(e, pose_b, s).map(|g| g.flipped()))
        }
        (AnyShape2::Segment(_), AnyShape2::Segment(_)) => Err(DismechError::UnsupportedPair(
            a.as_shape().kind().name(),
            b.as_shape().kind().name(),
        )),
    }
}
