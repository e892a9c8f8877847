//! Smooth–edge contact: a circle or ellipse (body A) against an edge P₂P₃
//! of body B, oriented as in [`super::vertex_edge`] (outward normal `n =
//! (τ_y, −τ_x)` towards A).
//!
//! With `G` the current axes matrix of A (`G = F_A A₀`, shape matrix `M =
//! G Gᵀ = F M₀ Fᵀ`) and `e` its current centre:
//!
//! * `g_n = (e − x₂)·n(b) − h_A(−n)`, `h_A(m) = |Gᵀ m|`: the distance from
//!   the edge's line to A's nearest point, negative when A has penetrated;
//! * `g_s = (x_s − x₀')·τ(b)`: the tangential displacement of A's material
//!   point `x_s` that was the support point (nearest to the edge) at the
//!   start of the step, relative to the edge's material point `x₀' = x₂ +
//!   ξ b` under it then, measured along the current edge, as DDA measures
//!   a vertex's shear.
//!
//! Local variables (M = 10): `a_c = e − x₀'`, `b = x₃ − x₂`, `vec G` (row
//! by row), `a_s = x_s − x₀'`, measured from the foot `x₀'` rather than from
//! the edge's start so that their round-off is that of the contact's size,
//! not of the edge's length (a 60 m incline left Newton a floor of 3e-10
//! otherwise). The first term of `g_n` and the whole of `g_s`
//! are the vertex–edge expressions in `(a_c, b)` and `(a_s, b)`
//! ([`local_geometry`]); the support term adds `−|Gᵀ n(b)|`.
//!
//! For a circle of radius r under any rigid motion, `g_n` is the
//! vertex–edge gap of its centre minus r.

use nalgebra::{SMatrix, SVector, Vector2};

use super::support::{axes_chain, flatten, support_jet, through_edge_normal, unflatten};
use super::{
    local_geometry, GapVariation, LocalVariation, PairContact, SmoothSide, SmoothSmoothContact,
    VariationError,
};
use crate::kinematics::{point_map_jacobian, PlacedPolygon};
use crate::math::{cross, Point, Vec2};

/// One smooth–edge contact, fixed for the duration of a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SmoothEdgeContact {
    /// The smooth body A at the start of the step.
    pub side: SmoothSide,
    /// The edge `[P₂, P₃]` of body B at the start of the step (world).
    pub edge: [Point; 2],
    /// Reference point (centroid) of body B at the start of the step.
    pub reference_b: Point,
    /// A's material point that carries the shear: its support point
    /// towards the edge at the start of the step.
    pub material: Point,
    /// Foot of `material` on the edge, `x₀' = x₂ + ξ (x₃ − x₂)`.
    pub xi: f64,
    /// `g_n` at the start of the step.
    pub initial_gap: f64,
}

impl SmoothEdgeContact {
    /// The contact of the smooth `side` (body A) with `edge` (body B,
    /// reference `reference_b`) when the foot of A's support point towards
    /// the edge lies on the edge, `0 ≤ ξ ≤ 1`, and `|g_n| ≤ search`.
    pub fn detect(
        side: &SmoothSide,
        edge: [Point; 2],
        reference_b: Point,
        search: f64,
    ) -> Option<Self> {
        let (material, xi, n) = support_foot(side, &edge);
        let b = edge[1] - edge[0];
        let gap = cross(&(side.centre - edge[0]), &b) / b.norm() - side.support(&n);
        if !(0.0..=1.0).contains(&xi) || gap.abs() > search {
            return None;
        }
        Some(Self {
            side: *side,
            edge,
            reference_b,
            material,
            xi,
            initial_gap: gap,
        })
    }
}

/// A's support point towards `edge` (along `−n`), the position ξ of its
/// foot on the edge, and the edge's outward normal `n`.
fn support_foot(side: &SmoothSide, edge: &[Point; 2]) -> (Point, f64, Vec2) {
    let b = edge[1] - edge[0];
    let l2 = b.norm_squared();
    let l = l2.sqrt();
    let n = Vec2::new(b.y / l, -b.x / l);
    let material = side.support_point(&(-n));
    (material, (material - edge[0]).dot(&b) / l2, n)
}

impl SmoothEdgeContact {
    /// The edge's material point under A's support point at the start of
    /// the step, `x₀' = x₂ + ξ (x₃ − x₂)`: the origin of the local
    /// variables (as [`super::VertexEdgeContact::foot`]).
    pub fn foot(&self) -> Point {
        self.edge[0] + (self.edge[1] - self.edge[0]) * self.xi
    }
}

impl GapVariation<10> for SmoothEdgeContact {
    fn start(&self) -> SVector<f64, 10> {
        let foot = self.foot();
        let mut z = SVector::<f64, 10>::zeros();
        z.fixed_rows_mut::<2>(0)
            .copy_from(&(self.side.centre - foot));
        z.fixed_rows_mut::<2>(2)
            .copy_from(&(self.edge[1] - self.edge[0]));
        z.fixed_rows_mut::<4>(4)
            .copy_from(&flatten(&self.side.axes));
        z.fixed_rows_mut::<2>(8).copy_from(&(self.material - foot));
        z
    }

    fn chain(&self) -> (SMatrix<f64, 10, 6>, SMatrix<f64, 10, 6>) {
        let s = &self.side;
        let mut la = SMatrix::<f64, 10, 6>::zeros();
        la.fixed_view_mut::<2, 6>(0, 0)
            .copy_from(&point_map_jacobian(&(s.centre - s.reference)));
        la.fixed_view_mut::<4, 6>(4, 0)
            .copy_from(&axes_chain(&s.axes));
        la.fixed_view_mut::<2, 6>(8, 0)
            .copy_from(&point_map_jacobian(&(self.material - s.reference)));
        let j0 = point_map_jacobian(&(self.foot() - self.reference_b));
        let j2 = point_map_jacobian(&(self.edge[0] - self.reference_b));
        let j3 = point_map_jacobian(&(self.edge[1] - self.reference_b));
        let mut lb = SMatrix::<f64, 10, 6>::zeros();
        lb.fixed_view_mut::<2, 6>(0, 0).copy_from(&(-j0));
        lb.fixed_view_mut::<2, 6>(2, 0).copy_from(&(j3 - j2));
        lb.fixed_view_mut::<2, 6>(8, 0).copy_from(&(-j0));
        (la, lb)
    }

    fn local(&self, z: &SVector<f64, 10>) -> Result<LocalVariation<10>, VariationError> {
        let a_c = Vector2::new(z[0], z[1]);
        let b = Vector2::new(z[2], z[3]);
        let a_s = Vector2::new(z[8], z[9]);
        let centre = local_geometry(&a_c, &b, 0.0);
        let shear = local_geometry(&a_s, &b, 0.0);
        let l = b.norm();
        let n = Vec2::new(b.y / l, -b.x / l);
        // Support term in (b, vec G): indices 2..8 of z.
        let support = through_edge_normal(&support_jet(&n, &unflatten(&z.as_slice()[4..8])), &b);

        let mut grad_gap = SVector::<f64, 10>::zeros();
        grad_gap.fixed_rows_mut::<4>(0).copy_from(&centre.grad_gap);
        let mut hess_gap = SMatrix::<f64, 10, 10>::zeros();
        hess_gap
            .fixed_view_mut::<4, 4>(0, 0)
            .copy_from(&centre.hess_gap);
        let mut g = grad_gap.fixed_rows_mut::<6>(2);
        g -= support.grad;
        let mut h = hess_gap.fixed_view_mut::<6, 6>(2, 2);
        h -= support.hess;

        // Shear: (a_s, b) of the vertex–edge form sit at indices (8, 9, 2, 3).
        let idx = [8, 9, 2, 3];
        let mut grad_shear = SVector::<f64, 10>::zeros();
        let mut hess_shear = SMatrix::<f64, 10, 10>::zeros();
        for (i, &zi) in idx.iter().enumerate() {
            grad_shear[zi] = shear.grad_shear[i];
            for (j, &zj) in idx.iter().enumerate() {
                hess_shear[(zi, zj)] = shear.hess_shear[(i, j)];
            }
        }
        Ok(LocalVariation {
            gap: centre.gap - support.value,
            shear: shear.shear,
            grad_gap,
            grad_shear,
            hess_gap,
            hess_shear,
        })
    }
}

/// The contacts of a smooth body A (`side`) with a polygon B within
/// `search`, each with the index of the polygon feature it involves:
/// smooth–edge contacts on every edge k (from vertex k to k + 1) that
/// [`SmoothEdgeContact::detect`] accepts, and vertex contacts
/// ([`SmoothSmoothContact`] with B's vertex k as a point side) on convex
/// vertices past both of whose adjacent edges A's support point falls (ξ >
/// 1 on the edge before, ξ < 0 on the edge after). The vertex rule is the
/// strict complement of the edges' `0 ≤ ξ ≤ 1`, computed from the same
/// numbers, so a corner is counted once; where the feet leave both edges
/// the nearest point of the polygon is the vertex, so nothing within
/// `search` is missed.
///
/// # Errors
/// [`VariationError::NormalNotFound`] or [`VariationError::NotAMaximum`]
/// when the normal search of a vertex contact fails
/// ([`SmoothSmoothContact::detect`]); edge contacts do not fail.
pub fn smooth_polygon_contacts(
    side: &SmoothSide,
    polygon: &PlacedPolygon,
    search: f64,
) -> Result<Vec<(usize, PairContact)>, VariationError> {
    let count = polygon.vertex_count();
    let centroid = polygon.centroid();
    let mut out = Vec::new();
    for k in 0..count {
        let edge = [polygon.vertex(k), polygon.vertex(k + 1)];
        if let Some(c) = SmoothEdgeContact::detect(side, edge, centroid, search) {
            out.push((k, PairContact::SmoothEdge(c)));
        }
    }
    for k in 0..count {
        let (prev, v, next) = (
            polygon.vertex(k + count - 1),
            polygon.vertex(k),
            polygon.vertex(k + 1),
        );
        if cross(&(v - prev), &(next - v)) <= 0.0 {
            continue;
        }
        let (_, xi_before, _) = support_foot(side, &[prev, v]);
        let (_, xi_after, _) = support_foot(side, &[v, next]);
        if !(xi_before > 1.0 && xi_after < 0.0) {
            continue;
        }
        let vertex = SmoothSide::vertex(v, centroid);
        if let Some(c) = SmoothSmoothContact::detect(side, &vertex, search, None)? {
            out.push((k, PairContact::SmoothSmooth(c)));
        }
    }
    Ok(out)
}
