//! Helpers shared by the pair-variation test files.
#![allow(dead_code)]

use dismech::kinematics::PlacedEllipse;
use dismech::math::{Point, Vec2};
use dismech::query::variation::{SmoothEdgeContact, SmoothSide, VertexEdgeContact};
use nalgebra::Matrix2;

/// A point from two numbers.
pub fn point(v: &[f64]) -> Point {
    Point::new(v[0], v[1])
}

/// An ellipse side with semi-axes `a`, `b` at angle `phi`, its own body.
pub fn ellipse(centre: Point, a: f64, b: f64, phi: f64) -> SmoothSide {
    let (s, c) = phi.sin_cos();
    let axes = Matrix2::new(c, -s, s, c) * Matrix2::new(a, 0.0, 0.0, b);
    SmoothSide::ellipse(&PlacedEllipse::new(centre, axes).unwrap())
}

/// A vertex–edge contact from eleven numbers (points, references, ξ).
pub fn vertex_edge(v: &[f64]) -> VertexEdgeContact {
    VertexEdgeContact {
        vertex: point(&v[0..2]),
        reference_a: point(&v[2..4]),
        edge: [point(&v[4..6]), point(&v[6..8]) + Vec2::new(2.0, 0.5)],
        reference_b: point(&v[8..10]),
        xi: v[10],
        initial_gap: 0.0,
    }
}

/// A smooth–edge contact of `side` from the same eleven numbers.
pub fn smooth_edge(v: &[f64], side: SmoothSide) -> SmoothEdgeContact {
    SmoothEdgeContact {
        side,
        edge: [point(&v[4..6]), point(&v[6..8]) + Vec2::new(2.0, 0.5)],
        reference_b: point(&v[8..10]),
        material: point(&v[0..2]),
        xi: v[10],
        initial_gap: 0.0,
    }
}

/// `count` boundary points of an ellipse side.
pub fn boundary(side: &SmoothSide, count: usize) -> Vec<Point> {
    (0..count)
        .map(|k| k as f64 * std::f64::consts::TAU / count as f64)
        .map(|t| side.centre + side.axes * Vec2::new(t.cos(), t.sin()))
        .collect()
}
