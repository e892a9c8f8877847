//! Implicit discontinuous deformation analysis (DDA) after Hashimoto,
//! Koyama & Kikumoto (paper 003), as one composition of the implicit
//! driver:
//!
//! `DdaModel = ImplicitDynamics<6, Affine2, PenaltyCoulomb, Newmark, SparseLu>`
//!
//! | slot | piece | paper 003 |
//! |---|---|---|
//! | shape | [`crate::shape::Polygon`] blocks ([`Block`]) | eqs. (14)–(16) |
//! | body kinematics | [`crate::kinematics::Affine2`]: six unknowns `(u₀, v₀, r₀, εx, εy, γxy)`, mass `ρ∫TᵀT`, stiffness `A D` | eqs. (1)–(2), (14)–(16) |
//! | pair query | vertex–edge gap and shear with exact first and second variations ([`crate::query::variation::VertexEdgeContact`]) | eqs. (17)–(35) |
//! | contact law | [`crate::law::PenaltyCoulomb`]: return mapping (consistent, unsymmetric CLOSE tangent) or the conventional treatment | eqs. (7)–(10), Fig. 1 |
//! | integrator | [`crate::integrate::Newmark`] β = ½, γ = 1 ([`crate::integrate::Restarting`] for the static analysis of classic DDA) | §2.(5) |
//! | linear solver | [`crate::linsolve::SparseLu`] | |
//! | driver | open–close, Newton with line search, Δt control ([`crate::implicit`]) | eqs. (11)–(13), Fig. 5 |
//!
//! Choices where the paper is silent or garbled:
//! * the linearisation of eqs. (12)–(13) is derived from the penalty
//!   regularisation with return mapping (Wriggers 2006): the law's tangent
//!   `∂(t_n, t_s)/∂(g_n, g_s)` (unsymmetric in CLOSE) sandwiched between the
//!   first variations, plus `t_n Δδg_n` and `t_s Δδg_s` from the exact
//!   second variations of `g_n` and `g_s`;
//! * shear and normal penalties are equal (eq. 8 uses `p_c` for both);
//! * blocks are in plane stress by default (classic DDA);
//! * within a step the displacement field is the linear one of eq. (14),
//!   so a rotation `r₀` stretches a block by `√(1 + r₀²)` within the step,
//!   as in classic DDA; at the end of the step the vertices are moved with
//!   the rotation made exact (the post-correction of DDA practice,
//!   [`crate::kinematics::Affine2`]), so that a block turning without
//!   strain keeps its area (classic DDA grows it by `r₀²` a step: a disc
//!   rolling 990° on a 40° incline grew by 45 %);
//! * the density is kept as a block deforms, so its mass follows its area
//!   (as in classic DDA);
//! * the static analysis of classic DDA keeps the inertia term in the
//!   equations and resets velocities after every step
//!   ([`crate::integrate::Restarting`]);
//! * the shear reference point `x₀'` is the material point of the edge
//!   under the vertex at the start of each step, and the shear force is
//!   carried from step to step as contact history;
//! * where two corners meet, the edge a vertex meets is the entrance line
//!   of the two angles ([`crate::query::variation::entrance_edges`]): an
//!   edge whose line separates the vertex's angle from the other block,
//!   never a side edge through the corner that carries no load; where each
//!   block's corner meets the other's edge both contacts are kept (no rule
//!   merges them), and a vertex in a reflex corner meets both its edges.

use crate::error::Result;
use crate::implicit::{ImplicitDynamics, ImplicitSettings};
use crate::integrate::{ImplicitIntegrator, Newmark};
use crate::kinematics::Affine2;
use crate::linsolve::SparseLu;

pub use crate::implicit::{FixedPoint, Halvings, PlaneState, StepFailure, StepReport};
pub use crate::law::{FrictionIntegration, PenaltyCoulomb, PenaltyState};

/// A DDA block: a polygon body with the six DDA unknowns.
pub type Block = crate::implicit::Body<6>;
/// Elastic and inertial properties of a block.
pub type BlockMaterial = crate::implicit::BodyMaterial;
/// Imposed unknowns of a block.
pub type Prescribed = crate::implicit::Prescribed<6>;
/// A contact of the last accepted step, with the DDA law's history.
pub type ContactReport = crate::implicit::ContactReport<PenaltyState>;
/// Settings of a DDA run.
pub type DdaSettings = ImplicitSettings;

/// Paper 003's DDA: polygon blocks with affine kinematics, the penalty
/// Coulomb law, Newmark (β = ½, γ = 1 by default) and sparse LU.
pub type DdaModel<I = Newmark> = ImplicitDynamics<6, Affine2, PenaltyCoulomb, I, SparseLu>;

impl DdaModel {
    /// A dynamic DDA model of `blocks` with contact law `law`: Newmark
    /// β = ½, γ = 1 (classic DDA). Refuses invalid settings and blocks that
    /// overlap at the start by more than `settings.overlap_tolerance` (the
    /// error names both blocks).
    ///
    /// # Errors
    /// As [`ImplicitDynamics::compose`]:
    /// [`DismechError::InvalidParameter`](crate::error::DismechError::InvalidParameter)
    /// for a setting out of its range ([`ImplicitSettings::validate`]) or an
    /// elliptical block near another at the start whose aspect ratio is
    /// above [`MAX_ASPECT_RATIO`](crate::shape::MAX_ASPECT_RATIO);
    /// [`ImplicitError::InvalidEdgeTraction`](crate::implicit::ImplicitError::InvalidEdgeTraction)
    /// for an edge traction on an edge the block does not have or that is
    /// not finite;
    /// [`ImplicitError::InvalidBlock`](crate::implicit::ImplicitError::InvalidBlock)
    /// for a block whose load (weight and edge tractions) is not finite;
    /// [`ImplicitError::BlocksOverlap`](crate::implicit::ImplicitError::BlocksOverlap)
    /// naming the vertex and both blocks when a vertex lies inside another
    /// block by more than `settings.overlap_tolerance`, and
    /// [`ImplicitError::BlocksCross`](crate::implicit::ImplicitError::BlocksCross)
    /// when two blocks' edges cross by more than it.
    pub fn new(blocks: Vec<Block>, law: PenaltyCoulomb, settings: DdaSettings) -> Result<Self> {
        Self::with_integrator(blocks, law, Newmark::dda(), settings)
    }
}

impl<I: ImplicitIntegrator> DdaModel<I> {
    /// A DDA model with the time integration of one's choice: Newmark with
    /// other β, γ ([`Newmark::new`]), the static analysis of classic DDA
    /// (`Restarting(Newmark::dda())`), or quasi-static steps.
    ///
    /// # Errors
    /// The errors of [`DdaModel::new`] (those of
    /// [`ImplicitDynamics::compose`]); the integrator is not checked here
    /// ([`Newmark::new`] checks β and γ).
    pub fn with_integrator(
        blocks: Vec<Block>,
        law: PenaltyCoulomb,
        integrator: I,
        settings: DdaSettings,
    ) -> Result<Self> {
        Self::compose(
            blocks,
            Affine2,
            law,
            integrator,
            SparseLu::default(),
            settings,
        )
    }
}
