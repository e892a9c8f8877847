//! Implicit discontinuous deformation analysis (DDA) after Hashimoto,
//! Koyama & Kikumoto (paper 003): deformable polygon blocks with six
//! unknowns each, penalty vertex–edge contacts with Coulomb friction
//! integrated by return mapping (or by the conventional DDA treatment, for
//! comparison), Newton–Raphson with the consistent tangent, and Newmark
//! time integration with β = ½, γ = 1.
//!
//! | concept | file | paper 003 |
//! |---|---|---|
//! | block: displacement field, stiffness, inertia, loads | [`block`] | eqs. (1)–(2), (14)–(16) |
//! | vertex–edge contact: gap, shear, variations | [`contact`] | eqs. (17)–(35) |
//! | friction: conventional and return mapping | [`crate::law::PenaltyCoulomb`] | eqs. (7)–(10), Fig. 1 |
//! | assembly, open–close, Newton, Newmark, Δt control | [`model`] | eqs. (11)–(13), §2.(5), Fig. 5 |
//!
//! The pieces are the crate's generic ones: [`crate::shape::Polygon`] for
//! the geometry, the [`crate::contact::ContactLaw`] trait for the friction
//! law, [`crate::integrate::Newmark`] for time and
//! [`crate::linsolve::SparseLu`] (a [`crate::linsolve::LinearSolver`]) for the global system; the
//! broad phase is [`crate::broad_phase::CellGrid`].
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
//!   so a rotation `r₀` stretches a block slightly, as in classic DDA;
//! * the density is kept as a block deforms, so its mass follows its area
//!   (as in classic DDA);
//! * the static analysis of classic DDA keeps the inertia term in the
//!   equations and resets velocities after every step;
//! * the shear reference point `x₀'` is the material point of the edge
//!   under the vertex at the start of each step, and the shear force is
//!   carried from step to step as contact history.

pub mod block;
pub mod contact;
pub mod model;

pub use crate::law::{FrictionIntegration, PenaltyCoulomb, PenaltyState};
pub use block::{Block, BlockMaterial, Motion, PlaneState, Prescribed};
pub use contact::{Kinematics, VertexEdge};
pub use model::{
    ContactReport, DdaModel, DdaSettings, FixedPoint, StepFailure, StepReport, StepStatus,
};
