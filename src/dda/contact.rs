//! Vertex–edge contacts of DDA: detection, the gap `g_n` (eq. 17) and shear
//! displacement `g_s` (eq. 27) as functions of the step's unknowns, with
//! their first variations (eqs. 20–22, 29–31) and second variations
//! `Δδg_n`, `Δδg_s` (eqs. 23–26, 32–35).
//!
//! Conventions. Vertex P₁ belongs to block j; the edge P₂P₃ to block k,
//! running counter-clockwise, so that its outward normal is
//! `n = (τ_y, −τ_x)` with `τ = (x₃ − x₂)/l` (the paper's eq. 18 writes the
//! same vector for an edge traversed clockwise). With `a = x₁ − x₂`,
//! `b = x₃ − x₂`, `l = |b|`:
//!
//! * `g_n = (a × b)/l = (x₁ − x₀)·n` (eq. 17), negative when P₁ has
//!   penetrated;
//! * `g_s = (x₁ − x₀')·τ = a·b/l − ξ l` (eq. 27), where the shear reference
//!   point `x₀' = x₂ + ξ b` is the material point of the edge under P₁ at
//!   the start of the step, so `g_s` is the step's shear increment `Δg_s`.
//!
//! Within a step the points move linearly with the unknowns, `x = x̄ +
//! T(x̄) d` (eq. 14), so all the nonlinearity is in `n(b)`, `τ(b)`, `l(b)`:
//! the gradients and Hessians are taken in closed form with respect to
//! `(a, b)` ([`crate::query::variation::local_geometry`]) and carried to the
//! twelve unknowns of the pair by the chain rule.
//! This is the content of eqs. (19)–(35) (whose `G`, `H`, `I`, `J`, `E'`
//! matrices are these gradients written out), derived afresh because the
//! printed equations are partly garbled.
//!
//! Detection rule. For each vertex of one block and each edge of the other,
//! the pair is a candidate when the foot of the perpendicular lies on the
//! edge (`0 ≤ ξ ≤ 1`) and `−d₀ ≤ g_n ≤ d₀` (`d₀`: search distance). Among
//! candidates the edge the contact had in the previous step is kept;
//! otherwise the one with the largest `g_n` (for a vertex inside, the
//! shallowest penetration — the edge it entered through; for a vertex near
//! a corner, vertex–vertex, the edge it would cross first). Both blocks'
//! vertices are tested against the other's edges, so where two corners meet
//! each may hold a contact on the other's edge; no rule merges the two.

use nalgebra::{SMatrix, SVector, Vector2};

use super::block::Block;
use crate::math::{cross, Point};
use crate::query::variation::local_geometry;

/// Gradient with respect to the 12 unknowns of a pair `(d_j, d_k)`.
pub type Grad12 = SVector<f64, 12>;
/// Hessian with respect to the 12 unknowns of a pair.
pub type Hess12 = SMatrix<f64, 12, 12>;

/// One vertex–edge contact, fixed for the duration of a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VertexEdge {
    /// Block owning the vertex (j).
    pub vertex_block: usize,
    /// Vertex index in block j.
    pub vertex: usize,
    /// Block owning the edge (k).
    pub edge_block: usize,
    /// Edge index in block k (from vertex `edge` to `edge + 1`).
    pub edge: usize,
    /// Position of the shear reference point `x₀' = x₂ + ξ (x₃ − x₂)`.
    pub xi: f64,
    /// Gap `g_n` at the start of the step.
    pub initial_gap: f64,
}

impl VertexEdge {
    /// Key identifying the contact across steps.
    pub fn key(&self) -> (usize, usize, usize, usize) {
        (self.vertex_block, self.vertex, self.edge_block, self.edge)
    }
}

/// `g_n`, `g_s` and their first and second variations at an iterate.
#[derive(Debug, Clone, PartialEq)]
pub struct Kinematics {
    /// Gap (negative: penetration).
    pub gap: f64,
    /// Shear displacement of the step.
    pub shear: f64,
    /// `δg_n = grad_gap · (δd_j, δd_k)` (eqs. 20–22).
    pub grad_gap: Grad12,
    /// `δg_s = grad_shear · (δd_j, δd_k)` (eqs. 29–31).
    pub grad_shear: Grad12,
    /// `Δδg_n` (eq. 24).
    pub hess_gap: Hess12,
    /// `Δδg_s` (eq. 33).
    pub hess_shear: Hess12,
}

impl VertexEdge {
    /// The linear map `(d_j, d_k) ↦ (Δa, Δb)` of the step (4×12), from
    /// `Δx = T(x̄) d` at P₁ (block j) and P₂, P₃ (block k).
    fn chain(&self, blocks: &[Block]) -> SMatrix<f64, 4, 12> {
        let (bj, bk) = (&blocks[self.vertex_block], &blocks[self.edge_block]);
        let t1 = bj.displacement_matrix(&bj.vertex(self.vertex));
        let t2 = bk.displacement_matrix(&bk.vertex(self.edge));
        let t3 = bk.displacement_matrix(&bk.vertex(self.edge + 1));
        let mut c = SMatrix::<f64, 4, 12>::zeros();
        c.fixed_view_mut::<2, 6>(0, 0).copy_from(&t1);
        c.fixed_view_mut::<2, 6>(0, 6).copy_from(&(-t2));
        c.fixed_view_mut::<2, 6>(2, 6).copy_from(&(t3 - t2));
        c
    }

    /// Start-of-step `(a, b)`.
    fn start(&self, blocks: &[Block]) -> (Vector2<f64>, Vector2<f64>) {
        let (bj, bk) = (&blocks[self.vertex_block], &blocks[self.edge_block]);
        let x2 = bk.vertex(self.edge);
        (bj.vertex(self.vertex) - x2, bk.vertex(self.edge + 1) - x2)
    }

    /// `g_n`, `g_s` and their variations at the step increments `d_j`, `d_k`
    /// of the two blocks (the blocks hold the start-of-step geometry).
    pub fn kinematics(
        &self,
        blocks: &[Block],
        d_j: &SVector<f64, 6>,
        d_k: &SVector<f64, 6>,
    ) -> Kinematics {
        let c = self.chain(blocks);
        let mut d = Grad12::zeros();
        d.fixed_rows_mut::<6>(0).copy_from(d_j);
        d.fixed_rows_mut::<6>(6).copy_from(d_k);
        let delta = c * d;
        let (a0, b0) = self.start(blocks);
        let a = a0 + delta.fixed_rows::<2>(0);
        let b = b0 + delta.fixed_rows::<2>(2);
        let g = local_geometry(&a, &b, self.xi);
        let ct = c.transpose();
        Kinematics {
            gap: g.gap,
            shear: g.shear,
            grad_gap: ct * g.grad_gap,
            grad_shear: ct * g.grad_shear,
            hess_gap: ct * g.hess_gap * c,
            hess_shear: ct * g.hess_shear * c,
        }
    }
}

/// The candidate edge of block `k` for vertex `p`: `(edge, ξ, g_n)` by the
/// rule of the module docs, preferring `previous` when it qualifies.
pub fn closest_edge(
    p: &Point,
    k: &Block,
    search: f64,
    previous: Option<usize>,
) -> Option<(usize, f64, f64)> {
    let mut best: Option<(usize, f64, f64)> = None;
    for e in 0..k.vertex_count() {
        let (x2, x3) = (k.vertex(e), k.vertex(e + 1));
        let (a, b) = (p - x2, x3 - x2);
        let l2 = b.norm_squared();
        let xi = a.dot(&b) / l2;
        let gap = cross(&a, &b) / l2.sqrt();
        if !(0.0..=1.0).contains(&xi) || gap.abs() > search {
            continue;
        }
        if previous == Some(e) {
            return Some((e, xi, gap));
        }
        if best.is_none_or(|(_, _, g)| gap > g) {
            best = Some((e, xi, gap));
        }
    }
    best
}

/// Depth of `p` inside block `k` (distance to the nearest edge), or `None`
/// when `p` is outside.
pub fn penetration_depth(p: &Point, k: &Block) -> Option<f64> {
    let n = k.vertex_count();
    let mut inside = false;
    let mut depth = f64::INFINITY;
    for e in 0..n {
        let (q, r) = (k.vertex(e), k.vertex(e + 1));
        if (q.y > p.y) != (r.y > p.y) && p.x < q.x + (p.y - q.y) * (r.x - q.x) / (r.y - q.y) {
            inside = !inside;
        }
        let b = r - q;
        let s = ((p - q).dot(&b) / b.norm_squared()).clamp(0.0, 1.0);
        depth = depth.min((p - (q + b * s)).norm());
    }
    inside.then_some(depth)
}
