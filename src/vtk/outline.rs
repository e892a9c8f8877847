//! Outlines of 2D shapes as the points of a VTK cell, and the contact
//! lines the 2D frames share.

use std::f64::consts::TAU;

use super::xml::{cell_type, DataArray, PolyData, UnstructuredGrid};
use crate::error::{DismechError, Result};
use crate::math::{perp, Point, Pose2, Vec2};
use crate::shape::AnyShape2;

/// Segments of a circle's or an ellipse's outline unless asked otherwise.
pub const DEFAULT_SEGMENTS: usize = 32;

/// The code of each shape in the `kind` arrays.
pub mod kind {
    /// A circle.
    pub const CIRCLE: u8 = 0;
    /// An ellipse.
    pub const ELLIPSE: u8 = 1;
    /// A polygon.
    pub const POLYGON: u8 = 2;
    /// A segment (a wall).
    pub const SEGMENT: u8 = 3;
}

/// Refuse fewer than three segments for a curved outline.
pub(super) fn check_segments(segments: usize) -> Result<()> {
    if segments < 3 {
        return Err(DismechError::InvalidParameter {
            name: "outline segments",
            value: segments as f64,
            requirement: "must be at least 3 (a circle's or an ellipse's outline is a polygon of that many sides)",
        });
    }
    Ok(())
}

/// A 2D point in VTK's 3D space (z = 0).
pub(super) fn xyz(p: &Point) -> [f64; 3] {
    [p.x, p.y, 0.0]
}

/// A 2D vector in VTK's 3D space (z = 0).
pub(super) fn vec3(v: &Vec2) -> [f64; 3] {
    [v.x, v.y, 0.0]
}

/// The code of a shape ([`kind`]).
pub(super) fn shape_kind(shape: &AnyShape2) -> u8 {
    match shape {
        AnyShape2::Circle(_) => kind::CIRCLE,
        AnyShape2::Ellipse(_) => kind::ELLIPSE,
        AnyShape2::Polygon(_) => kind::POLYGON,
        AnyShape2::Segment(_) => kind::SEGMENT,
    }
}

/// The outline of `shape` at `pose`, counter-clockwise: a circle or an
/// ellipse sampled at `segments` points equally spaced in its parameter,
/// the first on the body's x axis (so that the outline turns with the
/// body); a polygon's vertices; a segment's two ends.
pub(super) fn shape_outline(shape: &AnyShape2, pose: &Pose2, segments: usize) -> Vec<Point> {
    let angles = || (0..segments).map(move |k| TAU * k as f64 / segments as f64);
    match shape {
        AnyShape2::Circle(c) => angles()
            .map(|t| pose.transform_point(&Point::new(c.radius() * t.cos(), c.radius() * t.sin())))
            .collect(),
        AnyShape2::Ellipse(e) => angles()
            .map(|t| pose.transform_point(&e.local_point(t)))
            .collect(),
        AnyShape2::Polygon(p) => p.world_vertices(pose).collect(),
        AnyShape2::Segment(s) => vec![pose.transform_point(&s.start), pose.transform_point(&s.end)],
    }
}

/// Add `outline` to `grid` as one cell: a polygon, or a line for two
/// points.
pub(super) fn push_outline(grid: &mut UnstructuredGrid, outline: &[Point]) {
    let first = grid.points.len();
    grid.points.extend(outline.iter().map(xyz));
    let kind = if outline.len() == 2 {
        cell_type::LINE
    } else {
        cell_type::POLYGON
    };
    grid.push_cell(kind, first..first + outline.len());
}

/// One contact of a 2D frame, in the convention every contact file
/// shares: A touches B at `point`, `normal` is the unit normal from A to
/// B and `force` the force A exerts on B.
pub(super) struct ContactLine {
    /// A's reference point.
    pub a_centre: Point,
    /// B's reference point, or `None` for a wall or a support (the line
    /// ends at the contact point).
    pub b_centre: Option<Point>,
    pub point: Point,
    pub normal: Vec2,
    pub force: Vec2,
}

/// The contacts as poly-lines from A's centre through the contact point
/// to B's centre (to the point alone for a wall or a support), with the
/// cell data every contact file has: `point`, `normal`, `force`,
/// `normal_force` (`force · normal`, compression positive) and
/// `shear_force` (`force · tangent`, the tangent the normal turned by
/// +90°). The caller adds its own arrays.
pub(super) fn contact_lines(contacts: &[ContactLine]) -> PolyData {
    let mut d = PolyData::default();
    for c in contacts {
        let first = d.points.len();
        d.points.push(xyz(&c.a_centre));
        d.points.push(xyz(&c.point));
        if let Some(b) = c.b_centre {
            d.points.push(xyz(&b));
        }
        d.lines.push(first..d.points.len());
    }
    d.cell_data = vec![
        DataArray::vectors(
            "point",
            &contacts.iter().map(|c| xyz(&c.point)).collect::<Vec<_>>(),
        ),
        DataArray::vectors(
            "normal",
            &contacts.iter().map(|c| vec3(&c.normal)).collect::<Vec<_>>(),
        ),
        DataArray::vectors(
            "force",
            &contacts.iter().map(|c| vec3(&c.force)).collect::<Vec<_>>(),
        ),
        DataArray::scalars(
            "normal_force",
            contacts.iter().map(|c| c.force.dot(&c.normal)).collect(),
        ),
        DataArray::scalars(
            "shear_force",
            contacts
                .iter()
                .map(|c| c.force.dot(&perp(&c.normal)))
                .collect(),
        ),
    ];
    d
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::{Circle, Ellipse, Polygon};

    #[test]
    fn outlines_lie_on_the_shape_and_turn_with_it() {
        let pose = Pose2::new(1.0, 2.0, 0.3);
        let circle: AnyShape2 = Circle::new(0.5).unwrap().into();
        let points = shape_outline(&circle, &pose, 8);
        assert_eq!(points.len(), 8);
        for p in &points {
            approx::assert_relative_eq!((p - pose.position).norm(), 0.5, epsilon = 1e-15);
        }
        approx::assert_relative_eq!(
            points[0],
            Point::new(1.0 + 0.5 * 0.3f64.cos(), 2.0 + 0.5 * 0.3f64.sin()),
            epsilon = 1e-15
        );
        let ellipse = Ellipse::new(0.4, 0.2).unwrap();
        for p in shape_outline(&ellipse.into(), &pose, 16) {
            approx::assert_relative_eq!(ellipse.implicit(&pose, &p), 0.0, epsilon = 1e-12);
        }
        let square: AnyShape2 = Polygon::rectangle(1.0, 1.0).unwrap().into();
        assert_eq!(shape_outline(&square, &pose, 8).len(), 4);
        assert!(check_segments(2).is_err());
    }
}
