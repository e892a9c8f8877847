//! The pair dispatcher: picks the contact routine for a pair of shapes.
//!
//! One routine per shape pair, written once in a fixed order (circle before
//! ellipse before polygon before segment); the dispatcher swaps the pair
//! where needed and flips the result, so the normal always points from the
//! first argument into the second and swapping the arguments flips the
//! normals, swaps the features and keeps the points. A pair without a
//! routine is `Err(UnsupportedPair)` naming both shapes, never a panic.
//!
//! [`contact_manifold_2d`] gives every contact point of a pair, each named
//! by its [`ContactFeatures`](super::ContactFeatures):
//!
//! | pair | points | features |
//! |---|---|---|
//! | circle, ellipse with circle, ellipse or segment | at most one (paper 000's chord midpoint; beyond a wall's end, the end as a corner) | `Whole`, `Whole` |
//! | circle–polygon | one per touched edge or convex corner: one on a convex polygon, two for a disc in a notch ([`super::circle_polygon`]) | `Whole`, `Edge(k)` / `Vertex(k)` |
//! | ellipse–polygon | the ellipse–wall contact per edge it rests on, plus convex corners inside the ellipse ([`super::ellipse_polygon`]) | `Whole`, `Edge(k)` / `Vertex(k)` |
//! | polygon–polygon | each convex vertex inside the other against the edge it penetrated, both ways: a face on a face gives two ([`super::polygon`]) | `Vertex(i)`, `Edge(k)`; `Vertex(i)`, `Vertex(k)` for a coincident pair |
//! | polygon–segment | vertices behind the wall within its extent, the wall's ends inside the polygon as corners ([`super::polygon_segment`]) | `Vertex(k)`, `Edge(0)`; `Edge(k)`, `Vertex(0 or 1)` |
//! | segment–segment | `Err(UnsupportedPair("segment", "segment"))` | |
//!
//! A wall against a smooth body keeps `Whole`: that pair has one point,
//! which moves continuously from the wall's line onto its end, and the
//! contact history follows it. Two segments are refused: segments are the
//! fixed walls of a frame, a wall has no interior for another wall to
//! penetrate (two crossing segments have no overlap depth nor a side to push
//! towards), and no driver ever asks for the pair.
//!
//! Every routine assumes small overlaps: the penetration is smaller than
//! the smallest feature of either body (a polygon's shortest edge or notch,
//! an ellipse's radius of curvature). Segments are taken in world
//! coordinates (their pose is ignored): walls are fixed.

use super::circle_circle::contact_circle_circle;
use super::circle_polygon::contact_circle_polygon;
use super::circle_segment::contact_circle_segment;
use super::ellipse::{contact_ellipse_ellipse_near, contact_ellipse_segment};
use super::ellipse_polygon::contact_ellipse_polygon;
use super::polygon::contact_polygon_polygon;
use super::polygon_segment::contact_polygon_segment;
use super::ContactGeometry;
use crate::error::{DismechError, Result};
use crate::math::{Point, Pose2};
use crate::shape::{AnyShape2, Circle, Ellipse};

/// A circle as the a = b ellipse, for circle–ellipse pairs.
fn as_ellipse(c: &Circle) -> Result<Ellipse> {
    Ellipse::new(c.radius(), c.radius())
}

/// The unsupported-pair error naming both shapes, in the caller's order.
fn unsupported(a: &AnyShape2, b: &AnyShape2) -> DismechError {
    DismechError::UnsupportedPair(a.as_shape().kind().name(), b.as_shape().kind().name())
}

/// The single contact of `a` at `pose_a` with `b` at `pose_b`: `Ok(None)`
/// when they do not touch. For a pair with a polygon, which may touch at
/// several points, it is the deepest point of [`contact_manifold_2d`]
/// (computed into a temporary buffer; loops should call the manifold query
/// with a reused one).
///
/// # Errors
/// [`DismechError::UnsupportedPair`] for two segments.
pub fn contact_2d(
    a: &AnyShape2,
    pose_a: &Pose2,
    b: &AnyShape2,
    pose_b: &Pose2,
) -> Result<Option<ContactGeometry>> {
    contact_2d_near(a, pose_a, b, pose_b, None)
}

/// [`contact_2d`] given the pair's contact point at the last step (world),
/// where it touched then: pairs of ellipses and circle–ellipse pairs seek
/// their crossings about it first ([`contact_ellipse_ellipse_near`]); the
/// others do not use it.
///
/// # Errors
/// [`DismechError::UnsupportedPair`] for two segments.
pub fn contact_2d_near(
    a: &AnyShape2,
    pose_a: &Pose2,
    b: &AnyShape2,
    pose_b: &Pose2,
    near: Option<&Point>,
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
            Ok(contact_ellipse_ellipse_near(ea, pose_a, eb, pose_b, near))
        }
        (AnyShape2::Ellipse(e), AnyShape2::Circle(c)) => Ok(contact_ellipse_ellipse_near(
            e,
            pose_a,
            &as_ellipse(c)?,
            pose_b,
            near,
        )),
        (AnyShape2::Circle(c), AnyShape2::Ellipse(e)) => Ok(contact_ellipse_ellipse_near(
            &as_ellipse(c)?,
            pose_a,
            e,
            pose_b,
            near,
        )),
        (AnyShape2::Ellipse(e), AnyShape2::Segment(s)) => Ok(contact_ellipse_segment(e, pose_a, s)),
        (AnyShape2::Segment(s), AnyShape2::Ellipse(e)) => {
            Ok(contact_ellipse_segment(e, pose_b, s).map(|g| g.flipped()))
        }
        (AnyShape2::Segment(_), AnyShape2::Segment(_)) => Err(unsupported(a, b)),
        (AnyShape2::Polygon(_), _) | (_, AnyShape2::Polygon(_)) => {
            let mut points = Vec::new();
            contact_manifold_2d(a, pose_a, b, pose_b, &mut points)?;
            Ok(points
                .into_iter()
                .max_by(|x, y| x.overlap.total_cmp(&y.overlap)))
        }
    }
}

/// Flips the points appended from `start` on: a routine written for (B, A)
/// answers for (A, B).
fn flip_from(out: &mut [ContactGeometry], start: usize) {
    for g in &mut out[start..] {
        *g = g.flipped();
    }
}

/// Every contact point of `a` at `pose_a` with `b` at `pose_b`, appended to
/// `out` (nothing when they do not touch); normals from A into B. The rules
/// for each pair are in the module docs. Allocates nothing once `out` has
/// grown to the largest manifold met.
///
/// # Errors
/// [`DismechError::UnsupportedPair`] for two segments (`out` unchanged).
pub fn contact_manifold_2d(
    a: &AnyShape2,
    pose_a: &Pose2,
    b: &AnyShape2,
    pose_b: &Pose2,
    out: &mut Vec<ContactGeometry>,
) -> Result<()> {
    let start = out.len();
    match (a, b) {
        (AnyShape2::Polygon(pa), AnyShape2::Polygon(pb)) => {
            contact_polygon_polygon(pa, pose_a, pb, pose_b, out)
        }
        (AnyShape2::Polygon(p), AnyShape2::Segment(s)) => {
            contact_polygon_segment(p, pose_a, s, out)
        }
        (AnyShape2::Segment(s), AnyShape2::Polygon(p)) => {
            contact_polygon_segment(p, pose_b, s, out);
            flip_from(out, start);
        }
        (AnyShape2::Circle(c), AnyShape2::Polygon(p)) => {
            contact_circle_polygon(c, pose_a, p, pose_b, out)
        }
        (AnyShape2::Polygon(p), AnyShape2::Circle(c)) => {
            contact_circle_polygon(c, pose_b, p, pose_a, out);
            flip_from(out, start);
        }
        (AnyShape2::Ellipse(e), AnyShape2::Polygon(p)) => {
            contact_ellipse_polygon(e, pose_a, p, pose_b, out)
        }
        (AnyShape2::Polygon(p), AnyShape2::Ellipse(e)) => {
            contact_ellipse_polygon(e, pose_b, p, pose_a, out);
            flip_from(out, start);
        }
        _ => out.extend(contact_2d(a, pose_a, b, pose_b)?),
    }
    Ok(())
}
