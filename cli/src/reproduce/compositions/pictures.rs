//! Pictures of the compositions: the dual contact forces of a limit
//! analysis, and the wall's contact forces by two methods side by side.

use std::path::Path;

use dismech::error::Result;
use dismech::limit::{LimitBody, LimitModel, LimitResult, Support};
use dismech::math::{perp, Point, Vec2};
use dismech::shape::{AnyShape2, Segment};
use dismech_cli::compositions::block_wall::{RunningBondWall, WallSolution};
use dismech_cli::output::plot::{outline_picture, ForceMark};

/// Points on the outline of a shape drawn as a closed polyline.
const OUTLINE_POINTS: usize = 48;

/// The outline of a limit body (closed polyline, world).
fn outline(body: &LimitBody) -> Vec<Point> {
    let pose = body.pose();
    let mut points: Vec<Point> = match &body.shape {
        AnyShape2::Polygon(p) => p.world_vertices(&pose).collect(),
        AnyShape2::Segment(s) => vec![s.start, s.end],
        AnyShape2::Circle(c) => (0..OUTLINE_POINTS)
            .map(|k| {
                let t = k as f64 / OUTLINE_POINTS as f64 * std::f64::consts::TAU;
                body.centre + Vec2::new(t.cos(), t.sin()) * c.radius()
            })
            .collect(),
        AnyShape2::Ellipse(e) => (0..OUTLINE_POINTS)
            .map(|k| {
                e.world_point(
                    &pose,
                    k as f64 / OUTLINE_POINTS as f64 * std::f64::consts::TAU,
                )
            })
            .collect(),
    };
    if let Some(&first) = points.first() {
        points.push(first);
    }
    points
}

/// The supports (infinite lines) clipped to the box `lo`–`hi`.
fn support_segments(supports: &[Support], lo: Point, hi: Point) -> Vec<Segment> {
    supports
        .iter()
        .map(|s| {
            let d = perp(&s.normal);
            let (t0, t1) = [lo, hi, Point::new(lo.x, hi.y), Point::new(hi.x, lo.y)]
                .iter()
                .map(|q| (q - s.point).dot(&d))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), t| {
                    (a.min(t), b.max(t))
                });
            Segment::new(s.point + d * t0, s.point + d * t1)
        })
        .collect()
}

/// The dual contact forces of a solved limit model (the statically
/// admissible field at collapse): each drawn through its contact point,
/// the largest as long as a body's size.
pub fn dual_forces(
    path: &Path,
    title: &str,
    model: &LimitModel,
    result: &LimitResult,
) -> Result<()> {
    let outlines: Vec<Vec<Point>> = model.bodies().iter().map(outline).collect();
    let (mut lo, mut hi) = (
        Point::new(f64::INFINITY, f64::INFINITY),
        Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
    );
    for p in outlines.iter().flatten() {
        lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
    }
    let forces: Vec<ForceMark> = model
        .contacts()
        .iter()
        .enumerate()
        .map(|(c, contact)| ForceMark {
            point: contact.point,
            force: contact.normal * result.normal_force[c]
                - contact.tangent() * result.shear_force[c],
        })
        .collect();
    let size = model
        .bodies()
        .iter()
        .map(LimitBody::radius)
        .fold(0.0, f64::max);
    outline_picture(
        path,
        title,
        &outlines,
        &support_segments(model.supports(), lo, hi),
        &forces,
        2.0 * size,
    )
}

/// The wall at rest by the DEM (left) and the DDA (right, shifted by the
/// wall's length and a gap), each with its base and contact forces, on one
/// force scale.
pub fn wall_forces(
    path: &Path,
    title: &str,
    wall: &RunningBondWall,
    dem: &WallSolution,
    dda: &WallSolution,
) -> Result<()> {
    let shift = Vec2::new(wall.length() + 1.0, 0.0);
    let mut outlines = Vec::new();
    let mut forces = Vec::new();
    let mut bases = Vec::new();
    for (offset, solution) in [(Vec2::zeros(), dem), (shift, dda)] {
        for b in wall.blocks()? {
            let mut corners: Vec<Point> = b.corners.iter().map(|c| c + offset).collect();
            corners.push(corners[0]);
            outlines.push(corners);
        }
        forces.extend(solution.contacts.iter().map(|c| ForceMark {
            point: c.point + offset,
            force: c.force,
        }));
        bases.push(Segment::new(
            Point::new(-0.2, 0.0) + offset,
            Point::new(wall.length() + 0.2, 0.0) + offset,
        ));
    }
    outline_picture(path, title, &outlines, &bases, &forces, wall.block_height)
}
