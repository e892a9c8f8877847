//! # dismech — discrete mechanics of granular and blocky geomaterials
//!
//! dismech rebuilds published methods of discrete mechanics from a few
//! generic pieces, so that a user can compose a new model by picking one of
//! each:
//!
//! | piece | trait | family |
//! |---|---|---|
//! | geometry of a body | [`shape::Shape`] (+ [`shape::Shape2`] in 2D) | [`shape`] |
//! | pair geometry | [`contact::dispatch::contact_2d`] (one routine per shape pair) | [`contact`] |
//! | candidate pairs | [`broad_phase::CellGrid`] (uniform grid, O(N)) | [`broad_phase`] |
//! | contact force and history | [`contact::ContactLaw`] | [`contact`] |
//! | time stepping | [`integrate::Integrator`] | [`integrate`] |
//! | linear solve (analyse once, factor many, solve many) | [`linsolve::LinearSolver`] | [`linsolve`] |
//! | linear program | [`solve::GlobalSolver`] | [`solve`] |
//!
//! ## The four methods as compositions
//!
//! | method (paper) | Shape | ContactLaw | Integrator | solver | status |
//! |---|---|---|---|---|---|
//! | ellipse DEM (000, Katsuki & Ishikawa 1990) | [`shape::Circle`], [`shape::Ellipse`] | [`contact::SpringDashpotCoulomb`] (spring + dashpot + Coulomb slip, eqs. 14–19) | [`integrate::ExplicitEuler`] | [`linsolve::LumpedSystem`] (diagonal mass) | [`dem`] (circles and ellipses; Examples 2–3 to come) |
//! | implicit DDA (003) | [`shape::Polygon`] (6-DOF block, [`dda::Block`]) | [`dda::PenaltyCoulomb`] (return mapping or conventional; consistent tangent [`contact::ContactResponse::tangent`]) | [`integrate::Newmark`] (β = ½, γ = 1) | [`linsolve::SparseLu`] (supernodal LU on a 6 × 6 block pattern, analysis reused) + open–close + Newton | [`dda`] |
//! | rigid-plastic limit analysis (002) | `Circle` | [`contact::RigidPlastic`] (admissible set [`contact::Strength`], flow rule) | none (limit state) | [`solve::LinearProgramSolver`] (Clarabel) | [`limit`] |
//! | HPM slope stability (001) | [`shape::Column`] (3D, 12-DOF layers) | penalty springs; [`contact::MohrCoulombSpring`] (c, φ, no tension, return mapping) on the slip surface | none (one load step) | any [`linsolve::LinearSolver`] of the [`hpm::BlockMatrix`] stiffness, factored once ([`linsolve::SparseCholesky`] by default, or PCG), initial-stiffness iteration | [`hpm`] |
//!
//! ## Data flow of one step
//! 1. **Scene** ([`scene`]): bodies (shape, pose, velocities, mass), frame
//!    walls, gravity.
//! 2. **Broad phase**: candidate pairs from the cell grid.
//! 3. **Narrow phase**: [`contact::ContactGeometry`] from the dispatcher —
//!    point, unit normal (A → B), overlap, contact width, radii of curvature.
//! 4. **Contact law**: the relative increment
//!    ([`contact::relative_increment`], rotation included) and the history
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
//! ## Reproductions
//! [`reproduce`] runs each paper's examples and compares them with the
//! paper (`dismech reproduce all`).

#![deny(missing_docs)]

pub mod broad_phase;
pub mod contact;
pub mod dda;
pub mod dem;
pub mod error;
pub mod grid;
pub mod hpm;
pub mod integrate;
pub mod limit;
pub mod linsolve;
pub mod math;
pub mod output;
pub mod reproduce;
pub mod scene;
pub mod shape;
pub mod solve;

/// The README's code blocks, compiled as doctests so that they stay true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
