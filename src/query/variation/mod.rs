//! Gap and shear of a contact with their first and second variations, for
//! implicit drivers (Newton on the step's increments).
//!
//! A contact pairs body A and body B over one step. Its fixed data (which
//! vertex and edge, the shear reference ξ, the start normal, the material
//! points that carry the shear) are chosen once, at the start of the step,
//! by a detection helper; then at every Newton iterate the gap `g_n` and
//! the shear `g_s` are functions of the two bodies' map parameters
//! `p = (Δp_A, Δp_B)` (12; see [`crate::kinematics`]), and through them of
//! the degrees of freedom `(d_A, d_B)`.
//!
//! ## How a query is written
//! Every point of a body moves affinely in its map parameters, so each kind
//! writes `g_n` and `g_s` as functions of a few *local variables* `z`
//! (relative positions, edge vectors, ellipse axes) that are **linear** in
//! `p`: `z = z₀ + L_A Δp_A + L_B Δp_B` with constant `L_A`, `L_B` (M×6). A
//! kind implements [`GapVariation`]: `z₀`, `(L_A, L_B)` and the closed-form
//! values, gradients and Hessians in `z`. The chain rule is written once:
//! * in map parameters ([`GapVariation::map_variation`]): `∇_p = Lᵀ ∇_z`,
//!   `∇²_p = Lᵀ ∇²_z L`;
//! * in degrees of freedom ([`GapVariation::dof_variation`], generic over
//!   each body's [`Kinematics`]): with `C = L P(d)` (M×N),
//!   `∇_d = Cᵀ ∇_z`, `∇²_d = Cᵀ ∇²_z C + Σ_k (Lᵀ∇_z)_k ∂²Δp_k/∂d²`, the last
//!   term only for a nonlinear kinematics ([`Rigid2`](crate::kinematics::Rigid2)).
//!   For a linear one ([`Affine2`](crate::kinematics::Affine2)) `z = z₀ +
//!   C d` directly, so the vertex–edge contact of two DDA blocks reproduces
//!   classic DDA's chain through the displacement matrices of paper 003
//!   eq. (15), to round-off (it measures the vertex from the foot of the
//!   perpendicular; tested in `tests/variations.rs`).
//!
//! The result keeps the two bodies apart as blocks (`aa`, `ab`, `ba`,
//! `bb`), so the bodies may have different numbers of unknowns.
//!
//! ## The kinds
//! | kind | pair | local variables | file |
//! |---|---|---|---|
//! | [`VertexEdgeContact`] | polygon vertex vs polygon or wall edge | `a' = x₁ − x₀'` (from the foot of the perpendicular), `b = x₃ − x₂` (M = 4) | `vertex_edge.rs`; which edges a vertex meets: `vertex_polygon.rs` |
//! | [`SmoothEdgeContact`] | circle or ellipse vs edge | centre − x₀', `b`, axes, support point − x₀' (M = 10) | `smooth_edge.rs` |
//! | [`SmoothSmoothContact`] | circle/ellipse pairs, polygon vertex vs circle/ellipse | centre difference, both axes, relative displacement (M = 12) | `smooth_smooth.rs` |
//!
//! ## Driver's view
//! 1. start of step: detection helpers ([`VertexEdgeContact::detect`],
//!    [`entrance_edges`], [`SmoothEdgeContact::detect`],
//!    [`SmoothSmoothContact::detect`], [`smooth_polygon_contacts`]) on the
//!    start-of-step geometry give the fixed data, or `None` beyond the
//!    search distance;
//! 2. every iterate: `contact.dof_variation(&k_a, &d_a, &k_b, &d_b)` gives
//!    `g_n`, `g_s` and their variations in the bodies' unknowns, ready for
//!    the law's force and tangent;
//! 3. end of step: the kinematics' [`Advance`](crate::kinematics::Advance)
//!    moves each body's geometry.

mod smooth_edge;
mod smooth_smooth;
mod support;
mod vertex_edge;
mod vertex_polygon;

pub use smooth_edge::{smooth_polygon_contacts, SmoothEdgeContact};
pub use smooth_smooth::SmoothSmoothContact;
pub use support::SmoothSide;
pub use vertex_edge::{local_geometry, wall_edge, VertexEdgeContact, EDGE_END_TOLERANCE};
pub use vertex_polygon::{entrance_edges, PolygonCorner, BEHIND_TOLERANCE, SEPARATION_TOLERANCE};

use nalgebra::{SMatrix, SVector};

use crate::kinematics::{Kinematics, MapVector};

/// `g_n`, `g_s` and their gradients and Hessians, in whatever variables `G`
/// and `H` are written (local variables, map parameters or unknowns).
#[derive(Debug, Clone, PartialEq)]
pub struct Variation<G, H> {
    /// Gap (negative: penetration).
    pub gap: f64,
    /// Shear displacement of the step.
    pub shear: f64,
    /// First variation of the gap.
    pub grad_gap: G,
    /// First variation of the shear.
    pub grad_shear: G,
    /// Second variation of the gap.
    pub hess_gap: H,
    /// Second variation of the shear.
    pub hess_shear: H,
}

/// Variations in a kind's `M` local variables `z`.
pub type LocalVariation<const M: usize> = Variation<SVector<f64, M>, SMatrix<f64, M, M>>;

/// Variations in the 12 map parameters `(Δp_A, Δp_B)` of the pair.
pub type MapVariation = Variation<SVector<f64, 12>, SMatrix<f64, 12, 12>>;

/// Variations in the unknowns `(d_A, d_B)` of the pair, split by body.
pub type DofVariation<const NA: usize, const NB: usize> =
    Variation<PairVector<NA, NB>, PairMatrix<NA, NB>>;

/// A gradient over `(d_A, d_B)`, kept as one block per body.
#[derive(Debug, Clone, PartialEq)]
pub struct PairVector<const NA: usize, const NB: usize> {
    /// Part in `d_A`.
    pub a: SVector<f64, NA>,
    /// Part in `d_B`.
    pub b: SVector<f64, NB>,
}

/// A Hessian over `(d_A, d_B)`, kept as four blocks.
#[derive(Debug, Clone, PartialEq)]
pub struct PairMatrix<const NA: usize, const NB: usize> {
    /// `∂²/∂d_A∂d_A`.
    pub aa: SMatrix<f64, NA, NA>,
    /// `∂²/∂d_A∂d_B`.
    pub ab: SMatrix<f64, NA, NB>,
    /// `∂²/∂d_B∂d_A`.
    pub ba: SMatrix<f64, NB, NA>,
    /// `∂²/∂d_B∂d_B`.
    pub bb: SMatrix<f64, NB, NB>,
}

/// Why a variation could not be evaluated at an iterate: a numerical
/// outcome for the driver to act on (e.g. by cutting the step), not misuse.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum VariationError {
    /// The search for the contact normal of a smooth pair did not settle.
    #[error("contact normal search from {start:.6} rad did not converge: slope {slope:.3e} after {iterations} iterations")]
    NormalNotFound {
        /// Angle the search started from (rad).
        start: f64,
        /// `∂φ/∂θ` where it stopped.
        slope: f64,
        /// Iterations made.
        iterations: usize,
    },
    /// The normal found is not a strict local maximiser of the separation
    /// (e.g. concentric circles), so the gap has no second variation.
    #[error("contact normal at {angle:.6} rad is not a strict maximiser of the separation: curvature {curvature:.3e} is not negative beyond round-off")]
    NotAMaximum {
        /// Angle of the normal (rad).
        angle: f64,
        /// `∂²φ/∂θ²` there.
        curvature: f64,
    },
}

/// A contact's gap and shear as functions of `M` local variables that are
/// linear in the pair's map parameters, `z = z₀ + L_A Δp_A + L_B Δp_B`.
pub trait GapVariation<const M: usize> {
    /// `z₀`: the local variables at the start of the step.
    fn start(&self) -> SVector<f64, M>;

    /// `(L_A, L_B) = (∂z/∂Δp_A, ∂z/∂Δp_B)`, constant over the step.
    fn chain(&self) -> (SMatrix<f64, M, 6>, SMatrix<f64, M, 6>);

    /// `g_n`, `g_s` and their closed-form variations at `z`.
    ///
    /// # Errors
    /// Implementations return a [`VariationError`] when the kind has no
    /// smooth gap at `z`: only smooth–smooth pairs, whose normal is found
    /// iteratively, fail, with [`VariationError::NormalNotFound`] when the
    /// search does not settle and [`VariationError::NotAMaximum`] when the
    /// normal found is not a strict maximiser of the separation (e.g.
    /// concentric circles); vertex–edge and smooth–edge contacts never
    /// fail.
    fn local(&self, z: &SVector<f64, M>) -> Result<LocalVariation<M>, VariationError>;

    /// `g_n`, `g_s` and their variations in the 12 map parameters.
    ///
    /// # Errors
    /// As [`Self::local`].
    fn map_variation(
        &self,
        dp_a: &MapVector,
        dp_b: &MapVector,
    ) -> Result<MapVariation, VariationError> {
        let (la, lb) = self.chain();
        let z = self.start() + la * dp_a + lb * dp_b;
        let local = self.local(&z)?;
        let mut l = SMatrix::<f64, M, 12>::zeros();
        l.fixed_view_mut::<M, 6>(0, 0).copy_from(&la);
        l.fixed_view_mut::<M, 6>(0, 6).copy_from(&lb);
        let lt = l.transpose();
        Ok(Variation {
            gap: local.gap,
            shear: local.shear,
            grad_gap: lt * local.grad_gap,
            grad_shear: lt * local.grad_shear,
            hess_gap: lt * local.hess_gap * l,
            hess_shear: lt * local.hess_shear * l,
        })
    }

    /// Whether [`Self::values`] costs less than [`Self::local`] (a kind
    /// that overrides it says so): a caller that may need the variations
    /// after the values then takes both from one [`Self::local`].
    const VALUES_ALONE: bool = false;

    /// `g_n` and `g_s` alone at `z`: the values [`Self::local`] gives, to
    /// the bit (a kind may compute them without the variations).
    ///
    /// # Errors
    /// As [`Self::local`].
    fn values(&self, z: &SVector<f64, M>) -> Result<(f64, f64), VariationError> {
        self.local(z).map(|l| (l.gap, l.shear))
    }

    /// The local variables `z` at the step increments `d_a`, `d_b` of two
    /// bodies with kinematics `k_a`, `k_b`, with `C_A = L_A P_A(d_a)` and
    /// `C_B = L_B P_B(d_b)`: the first stage of
    /// [`Self::dof_variation`], shared with [`Self::dof_values`].
    #[allow(clippy::type_complexity)]
    fn dof_local_variables<KA, KB, const NA: usize, const NB: usize>(
        &self,
        k_a: &KA,
        d_a: &SVector<f64, NA>,
        k_b: &KB,
        d_b: &SVector<f64, NB>,
    ) -> (SVector<f64, M>, SMatrix<f64, M, NA>, SMatrix<f64, M, NB>)
    where
        KA: Kinematics<NA>,
        KB: Kinematics<NB>,
    {
        let (la, lb) = self.chain();
        let ca = la * k_a.map_jacobian(d_a);
        let cb = lb * k_b.map_jacobian(d_b);
        // One accumulation over the pair's unknowns in order, as a single
        // (M × (NA + NB)) product would do it.
        let mut delta = if KA::LINEAR {
            ca * d_a
        } else {
            la * k_a.map_parameters(d_a)
        };
        if KB::LINEAR {
            delta.gemv(1.0, &cb, d_b, 1.0);
        } else {
            delta.gemv(1.0, &lb, &k_b.map_parameters(d_b), 1.0);
        }
        (self.start() + delta, ca, cb)
    }

    /// `g_n` and `g_s` alone at the step increments: the values of
    /// [`Self::dof_variation`], to the bit, without the variations (what a
    /// driver needs to tell an open contact, which carries no force).
    ///
    /// # Errors
    /// As [`Self::local`].
    fn dof_values<KA, KB, const NA: usize, const NB: usize>(
        &self,
        k_a: &KA,
        d_a: &SVector<f64, NA>,
        k_b: &KB,
        d_b: &SVector<f64, NB>,
    ) -> Result<(f64, f64), VariationError>
    where
        KA: Kinematics<NA>,
        KB: Kinematics<NB>,
    {
        let (z, _, _) = self.dof_local_variables(k_a, d_a, k_b, d_b);
        self.values(&z)
    }

    /// `g_n`, `g_s` and their variations in the unknowns `(d_A, d_B)` of
    /// two bodies with kinematics `k_a`, `k_b`, at the step increments
    /// `d_a`, `d_b`.
    ///
    /// # Errors
    /// As [`Self::local`].
    fn dof_variation<KA, KB, const NA: usize, const NB: usize>(
        &self,
        k_a: &KA,
        d_a: &SVector<f64, NA>,
        k_b: &KB,
        d_b: &SVector<f64, NB>,
    ) -> Result<DofVariation<NA, NB>, VariationError>
    where
        KA: Kinematics<NA>,
        KB: Kinematics<NB>,
    {
        let (la, lb) = self.chain();
        let (z, ca, cb) = self.dof_local_variables(k_a, d_a, k_b, d_b);
        let local = self.local(&z)?;
        let (ta, tb) = (ca.transpose(), cb.transpose());
        let chain = |grad: &SVector<f64, M>, hess: &SMatrix<f64, M, M>| {
            let (wa, wb) = (ta * hess, tb * hess);
            let mut h = PairMatrix {
                aa: wa * ca,
                ab: wa * cb,
                ba: wb * ca,
                bb: wb * cb,
            };
            if !KA::LINEAR {
                h.aa += k_a.map_curvature(d_a, &(la.transpose() * grad));
            }
            if !KB::LINEAR {
                h.bb += k_b.map_curvature(d_b, &(lb.transpose() * grad));
            }
            (
                PairVector {
                    a: ta * grad,
                    b: tb * grad,
                },
                h,
            )
        };
        let (grad_gap, hess_gap) = chain(&local.grad_gap, &local.hess_gap);
        let (grad_shear, hess_shear) = chain(&local.grad_shear, &local.hess_shear);
        Ok(Variation {
            gap: local.gap,
            shear: local.shear,
            grad_gap,
            grad_shear,
            hess_gap,
            hess_shear,
        })
    }
}

/// A contact of any kind, as a driver stores it for a step.
#[derive(Debug, Clone, PartialEq)]
pub enum PairContact {
    /// A polygon vertex against an edge.
    VertexEdge(VertexEdgeContact),
    /// A circle or ellipse against an edge.
    SmoothEdge(SmoothEdgeContact),
    /// Two circles or ellipses, or a vertex against one.
    SmoothSmooth(SmoothSmoothContact),
}

impl PairContact {
    /// The gap at the start of the step.
    pub fn initial_gap(&self) -> f64 {
        match self {
            PairContact::VertexEdge(c) => c.initial_gap,
            PairContact::SmoothEdge(c) => c.initial_gap,
            PairContact::SmoothSmooth(c) => c.initial_gap,
        }
    }

    /// [`GapVariation::map_variation`] of the contact.
    ///
    /// # Errors
    /// As [`GapVariation::local`].
    pub fn map_variation(
        &self,
        dp_a: &MapVector,
        dp_b: &MapVector,
    ) -> Result<MapVariation, VariationError> {
        match self {
            PairContact::VertexEdge(c) => c.map_variation(dp_a, dp_b),
            PairContact::SmoothEdge(c) => c.map_variation(dp_a, dp_b),
            PairContact::SmoothSmooth(c) => c.map_variation(dp_a, dp_b),
        }
    }

    /// [`GapVariation::dof_values`] of the contact.
    ///
    /// # Errors
    /// As [`GapVariation::local`].
    pub fn dof_values<KA, KB, const NA: usize, const NB: usize>(
        &self,
        k_a: &KA,
        d_a: &SVector<f64, NA>,
        k_b: &KB,
        d_b: &SVector<f64, NB>,
    ) -> Result<(f64, f64), VariationError>
    where
        KA: Kinematics<NA>,
        KB: Kinematics<NB>,
    {
        match self {
            PairContact::VertexEdge(c) => c.dof_values(k_a, d_a, k_b, d_b),
            PairContact::SmoothEdge(c) => c.dof_values(k_a, d_a, k_b, d_b),
            PairContact::SmoothSmooth(c) => c.dof_values(k_a, d_a, k_b, d_b),
        }
    }

    /// [`GapVariation::dof_variation`] of the contact.
    ///
    /// # Errors
    /// As [`GapVariation::local`].
    pub fn dof_variation<KA, KB, const NA: usize, const NB: usize>(
        &self,
        k_a: &KA,
        d_a: &SVector<f64, NA>,
        k_b: &KB,
        d_b: &SVector<f64, NB>,
    ) -> Result<DofVariation<NA, NB>, VariationError>
    where
        KA: Kinematics<NA>,
        KB: Kinematics<NB>,
    {
        match self {
            PairContact::VertexEdge(c) => c.dof_variation(k_a, d_a, k_b, d_b),
            PairContact::SmoothEdge(c) => c.dof_variation(k_a, d_a, k_b, d_b),
            PairContact::SmoothSmooth(c) => c.dof_variation(k_a, d_a, k_b, d_b),
        }
    }
}
