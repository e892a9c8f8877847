//! # dismech — discrete mechanics of granular and blocky geomaterials
//!
//! dismech rebuilds published methods of discrete mechanics from a few
//! generic pieces, so that a user can compose a new model by picking one of
//! each:
//!
//! | piece | trait | family |
//! |---|---|---|
//! | geometry of a body | [`shape::Shape`] (+ [`shape::Shape2`] in 2D) | [`shape`] |
//! | pair geometry | [`query::contact_manifold_2d`] (one routine per shape pair; several points, named by [`query::ContactFeatures`], where a face meets a face) | [`query`] |
//! | gap and shear with first and second variations (implicit drivers) | [`query::variation::GapVariation`] (vertex–edge, smooth–edge, smooth–smooth) | [`query`] |
//! | how a body's unknowns move its points, its mass and stiffness | [`kinematics::Kinematics`] ([`kinematics::Rigid2`], [`kinematics::Affine2`], [`kinematics::Fixed`]) | [`kinematics`] |
//! | candidate pairs | [`broad_phase::CellGrid`] (uniform grid, O(N)) | [`broad_phase`] |
//! | contact force and history | [`law::ContactLaw`] | [`law`] |
//! | time stepping | [`integrate::ExplicitIntegrator`], [`integrate::ImplicitIntegrator`] | [`integrate`] |
//! | linear solve (analyse once, factor many, solve many) | [`linsolve::LinearSolver`] | [`linsolve`] |
//! | linear program | [`lp::LpSolver`] | [`lp`] |
//!
//! ## The four methods as compositions
//!
//! | method (paper) | Shape | ContactLaw | Integrator | solver | status |
//! |---|---|---|---|---|---|
//! | ellipse DEM (000, Katsuki & Ishikawa 1990) | [`shape::Circle`], [`shape::Ellipse`] | [`law::SpringDashpotCoulomb`] (spring + dashpot + Coulomb slip, eqs. 14–19) | [`integrate::ExplicitEuler`] | [`linsolve::LumpedSystem`] (diagonal mass) | [`dem`] ([`explicit`]) (circles and ellipses; Examples 2–3 to come) |
//! | polygon DEM | [`shape::Polygon`] (rigid, 3 DOF), with circles, ellipses and walls | [`law::SpringDashpotCoulomb`] with [`law::NormalStiffness::Constant`] (eq. 19 has no value at a vertex) | [`integrate::ExplicitEuler`] | [`linsolve::LumpedSystem`] | [`dem`] ([`explicit`]); checked by [`compositions::polygon_incline`], and against the DDA by [`compositions::block_wall`] |
//! | implicit DDA (003) | [`shape::Polygon`] (6-DOF block, [`dda::Block`]) | [`dda::PenaltyCoulomb`] (return mapping or conventional; consistent tangent [`law::TangentLaw`]) | [`integrate::Newmark`] (β = ½, γ = 1) | [`linsolve::SparseLu`] (supernodal LU on a 6 × 6 block pattern, analysis reused) + open–close + Newton | [`dda`] |
//! | rigid-plastic limit analysis (002) | `Circle` (the paper), any [`shape::AnyShape2`] ([`compositions::polygon_lp`], [`compositions::packing_lp`]) | [`law::RigidPlastic`] (admissible set [`law::Strength`], flow rule) | none (limit state) | [`lp::LinearProgramSolver`] (Clarabel) | [`limit`] |
//! | HPM slope stability (001) | [`shape::Column`] (3D, 12-DOF layers) | penalty springs; [`law::MohrCoulombSpring`] (c, φ, no tension, return mapping) on the slip surface | none (one load step) | any [`linsolve::LinearSolver`] of the [`hpm::BlockMatrix`] stiffness, factored once ([`linsolve::SparseCholesky`] by default, or PCG), initial-stiffness iteration | [`hpm`] |
//!
//! ## Data flow of one step
//! 1. **Scene** ([`scene`]): bodies (shape, pose, velocities, mass), frame
//!    walls, gravity.
//! 2. **Broad phase**: candidate pairs from the cell grid.
//! 3. **Narrow phase**: the [`query::ContactGeometry`] points of a pair
//!    from the dispatcher — point, unit normal (A → B), overlap, contact
//!    width, radii of curvature, features.
//! 4. **Contact law**: the relative increment
//!    ([`query::relative_increment`], rotation included) and the history
//!    state give forces, tangent and regime.
//! 5. **Assembly / solve**: force sums into `M a = f`, or a sparse system, or
//!    an LP.
//! 6. **Integrator**: advance the state.
//! 7. **Outputs** ([`output`]): CSV, SVG plots, `summary.json`, all written
//!    whole or not at all.
//!
//! ## Conventions
//! SI units (m, kg, s, N, Pa); 2D quantities are per metre of thickness.
//! 2D methods work in the x–y plane, y up, angles counter-clockwise from +x.
//! Misuse is an `Err` of [`error::DismechError`] naming the offending value;
//! a run that goes unstable stops with an error saying what to change.
//!
//! ## Exact references and reproductions
//! [`reference`](mod@reference) holds exact reference solutions (the rigid and compliant
//! sliding block, the planar slab's Fs, paper 002's two-element example and
//! closed forms, an independent ellipse contact, a block tipping or sliding
//! on a floor) that tests, examples and
//! the reproductions check the methods against. The reproductions of the
//! papers are clients of this library, in the `dismech` binary
//! (`dismech reproduce all`): they build their scenes from these pieces,
//! run them and compare with each paper. The [`compositions`] combine the
//! pieces in ways the papers do not and check them against exact solutions
//! or a second method (`dismech reproduce compositions`).

#![deny(missing_docs)]

pub mod broad_phase;
pub mod compositions;
pub mod dda;
pub mod dem;
pub mod error;
pub mod explicit;
pub mod grid;
pub mod hpm;
pub mod implicit;
pub mod integrate;
pub mod kinematics;
pub mod law;
pub mod limit;
pub mod linsolve;
pub mod lp;
pub mod math;
pub mod output;
pub mod query;
pub mod reference;
pub mod scene;
pub mod shape;

/// The README's code blocks, compiled as doctests so that they stay true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
