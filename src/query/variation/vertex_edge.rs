//! Vertex–edge contact (paper 003 eqs. 17–35): a polygon vertex P₁ of body
//! A against an edge P₂P₃ of body B (a polygon edge or a wall).
//!
//! The edge runs with B's material on its left, so its outward normal is
//! `n = (τ_y, −τ_x)`, `τ = (x₃ − x₂)/l`: for a polygon listed
//! counter-clockwise, edge k runs from vertex k to k + 1; a wall segment,
//! whose material (the allowed side) is on its left, is passed reversed
//! ([`wall_edge`]). With `a = x₁ − x₂`, `b = x₃ − x₂`, `l = |b|`:
//!
//! * `g_n = (a × b)/l = (x₁ − x₂)·n`, negative when P₁ has penetrated;
//! * `g_s = (x₁ − x₀')·τ = a·b/l − ξ l`, where `x₀' = x₂ + ξ b` is the
//!   material point of the edge under P₁ at the start of the step, so that
//!   `g_s` is the step's shear increment measured along the current edge.
//!
//! The contact evaluates both from `a' = x₁ − x₀' = a − ξ b` (so `g_n = (a'
//! × b)/l`, `g_s = a'·b/l`, [`local_geometry`] with ξ = 0): `a'` is of the
//! size of the gap and the step's motion, whereas `a` is of the edge's
//! length, and the round-off of `a × b / l` grows with it (on a 60 m
//! incline it left Newton a relative residual of 3e-10). `a'` and `b` are
//! the local variables (M = 4): every point moves affinely in its body's
//! map parameters, so `(a', b)` is linear in them and all the nonlinearity
//! is in `n(b)`, `τ(b)`, `l(b)`, differentiated in closed form.

use nalgebra::{Matrix2, SMatrix, SVector, Vector2};

use super::{GapVariation, LocalVariation, VariationError};
use crate::kinematics::point_map_jacobian;
use crate::math::{cross, Point};
use crate::shape::Segment;

/// `(g_n, g_s)` of a vertex against an edge, with their gradients and
/// Hessians in `(a, b) = (x₁ − x₂, x₃ − x₂)`; `xi` places the shear
/// reference point `x₀' = x₂ + ξ b`. These are eqs. (19)–(35) of paper 003
/// (its `G`, `H`, `I`, `J`, `E'` matrices), derived afresh because the
/// printed equations are partly garbled.
pub fn local_geometry(a: &Vector2<f64>, b: &Vector2<f64>, xi: f64) -> LocalVariation<4> {
    let l2 = b.norm_squared();
    let l = l2.sqrt();
    let tau = b / l;
    let n = Vector2::new(tau.y, -tau.x);
    let ra = Vector2::new(-a.y, a.x);
    let gap = cross(a, b) / l;
    let ab = a.dot(b);
    let shear = ab / l - xi * l;
    let id = Matrix2::identity();
    let rt = Matrix2::new(0.0, 1.0, -1.0, 0.0);
    let bbt = b * b.transpose();

    let dgap_b = ra / l - b * (gap / l2);
    let hgap_ab = rt / l - n * b.transpose() / l2;
    let hgap_bb = -(ra * b.transpose() + b * ra.transpose()) / (l2 * l) - id * (gap / l2)
        + bbt * (3.0 * gap / (l2 * l2));

    let dshear_b = a / l - b * (ab / (l2 * l)) - tau * xi;
    let hshear_ab = id / l - bbt / (l2 * l);
    let hshear_bb = -(a * b.transpose() + b * a.transpose()) / (l2 * l) - id * (ab / (l2 * l))
        + bbt * (3.0 * ab / (l2 * l2 * l))
        - (id / l - bbt / (l2 * l)) * xi;

    let pack = |ga: Vector2<f64>, gb: Vector2<f64>| SVector::<f64, 4>::new(ga.x, ga.y, gb.x, gb.y);
    let hess = |hab: Matrix2<f64>, hbb: Matrix2<f64>| {
        let mut h = SMatrix::<f64, 4, 4>::zeros();
        h.fixed_view_mut::<2, 2>(0, 2).copy_from(&hab);
        h.fixed_view_mut::<2, 2>(2, 0).copy_from(&hab.transpose());
        h.fixed_view_mut::<2, 2>(2, 2).copy_from(&hbb);
        h
    };
    LocalVariation {
        gap,
        shear,
        grad_gap: pack(n, dgap_b),
        grad_shear: pack(tau, dshear_b),
        hess_gap: hess(hgap_ab, hgap_bb),
        hess_shear: hess(hshear_ab, hshear_bb),
    }
}

/// The edge of a wall segment in the orientation of this module: the wall's
/// inner side (left of start → end) is the side a vertex may occupy, so the
/// edge runs from `end` to `start`.
pub fn wall_edge(wall: &Segment) -> [Point; 2] {
    [wall.end, wall.start]
}

/// One vertex–edge contact, fixed for the duration of a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VertexEdgeContact {
    /// The vertex P₁ of body A at the start of the step (world).
    pub vertex: Point,
    /// Reference point (centroid) of body A at the start of the step.
    pub reference_a: Point,
    /// The edge `[P₂, P₃]` of body B at the start of the step (world).
    pub edge: [Point; 2],
    /// Reference point (centroid) of body B at the start of the step.
    pub reference_b: Point,
    /// Position of the shear reference point `x₀' = x₂ + ξ (x₃ − x₂)`.
    pub xi: f64,
    /// `g_n` at the start of the step.
    pub initial_gap: f64,
}

/// How far past an end of an edge (as a fraction of its length) a vertex
/// still meets it: the round-off of corners that coincide, and their
/// drift while blocks that share them rest under load. Relative to the
/// edge, so a long edge reaches further (60 µm on a 60 m wall).
pub const EDGE_END_TOLERANCE: f64 = 1e-6;

impl VertexEdgeContact {
    /// The contact of `vertex` (body A, reference `reference_a`) with
    /// `edge` (body B), whatever its position: `ξ` is the position of the
    /// foot of the perpendicular on the edge, `g_n` the signed distance
    /// from the edge's line.
    pub fn new(vertex: Point, reference_a: Point, edge: [Point; 2], reference_b: Point) -> Self {
        let (a, b) = (vertex - edge[0], edge[1] - edge[0]);
        let l2 = b.norm_squared();
        Self {
            vertex,
            reference_a,
            edge,
            reference_b,
            xi: a.dot(&b) / l2,
            initial_gap: cross(&a, &b) / l2.sqrt(),
        }
    }

    /// Whether the foot of the perpendicular lies on the edge, up to
    /// [`EDGE_END_TOLERANCE`] past either end.
    pub fn foot_on_edge(&self) -> bool {
        (-EDGE_END_TOLERANCE..=1.0 + EDGE_END_TOLERANCE).contains(&self.xi)
    }

    /// The contact of `vertex` (body A, reference `reference_a`) with
    /// `edge` (body B) when the foot of the perpendicular lies on the edge
    /// ([`Self::foot_on_edge`]) and `|g_n| ≤ search`; `None` otherwise.
    pub fn detect(
        vertex: Point,
        reference_a: Point,
        edge: [Point; 2],
        reference_b: Point,
        search: f64,
    ) -> Option<Self> {
        let c = Self::new(vertex, reference_a, edge, reference_b);
        (c.foot_on_edge() && c.initial_gap.abs() <= search).then_some(c)
    }

    /// The material point of the edge under the vertex at the start of
    /// the step, `x₀' = x₂ + ξ (x₃ − x₂)`: the origin of the contact's local
    /// variables.
    pub fn foot(&self) -> Point {
        self.edge[0] + (self.edge[1] - self.edge[0]) * self.xi
    }
}

impl GapVariation<4> for VertexEdgeContact {
    /// `(a', b)` with `a' = x₁ − x₀'`: measured from the foot rather than
    /// from the edge's start, so that `g_n` and `g_s` are computed from a
    /// vector of the size of the gap and the step's motion, whatever the
    /// length of the edge (from `x₂` the round-off of `a × b / l` grows with
    /// the edge's length times the distance to its start).
    fn start(&self) -> SVector<f64, 4> {
        let (a, b) = (self.vertex - self.foot(), self.edge[1] - self.edge[0]);
        SVector::<f64, 4>::new(a.x, a.y, b.x, b.y)
    }

    /// `Δa' = ∂x₁/∂Δp_A Δp_A − ∂x₀'/∂Δp_B Δp_B`, `Δb = (∂x₃ − ∂x₂)/∂Δp_B
    /// Δp_B`, with `x₀' = (1 − ξ) x₂ + ξ x₃` a material point of B.
    fn chain(&self) -> (SMatrix<f64, 4, 6>, SMatrix<f64, 4, 6>) {
        let j1 = point_map_jacobian(&(self.vertex - self.reference_a));
        let j0 = point_map_jacobian(&(self.foot() - self.reference_b));
        let j2 = point_map_jacobian(&(self.edge[0] - self.reference_b));
        let j3 = point_map_jacobian(&(self.edge[1] - self.reference_b));
        let mut la = SMatrix::<f64, 4, 6>::zeros();
        la.fixed_view_mut::<2, 6>(0, 0).copy_from(&j1);
        let mut lb = SMatrix::<f64, 4, 6>::zeros();
        lb.fixed_view_mut::<2, 6>(0, 0).copy_from(&(-j0));
        lb.fixed_view_mut::<2, 6>(2, 0).copy_from(&(j3 - j2));
        (la, lb)
    }

    fn local(&self, z: &SVector<f64, 4>) -> Result<LocalVariation<4>, VariationError> {
        Ok(local_geometry(
            &Vector2::new(z[0], z[1]),
            &Vector2::new(z[2], z[3]),
            0.0,
        ))
    }

    const VALUES_ALONE: bool = true;

    /// The values of [`local_geometry`] (with ξ = 0), by the same
    /// operations.
    fn values(&self, z: &SVector<f64, 4>) -> Result<(f64, f64), VariationError> {
        let (a, b) = (Vector2::new(z[0], z[1]), Vector2::new(z[2], z[3]));
        let l = b.norm_squared().sqrt();
        Ok((cross(&a, &b) / l, a.dot(&b) / l - 0.0 * l))
    }
}
