//! HPM slope stability on grid columns (paper 001: Yamaguchi, Takeuchi &
//! Hamasaki, *Simplified 3D slope stability analysis by HPM*).
//!
//! The Hybrid-type Penalty Method discretises the slide into elements with
//! independent linear displacement fields (eq. 2) tied together by penalty
//! springs on their faces (eqs. 3–4). Here the elements come from the same
//! data as a simplified column method: ground surface, slip surface and
//! water table on a regular grid ([`SlopeGrids`], ESRI ASCII files or
//! rasters built in code). Each valid column is split into layers of equal
//! thickness (§3), so that the model gives displacements and strains as
//! well as a safety factor.
//!
//! | concept | file | paper |
//! |---|---|---|
//! | grids, valid columns, corner heights | `grids.rs` | §3, §5, eq. 23 |
//! | material, seismic load, settings | `material.rs` | eqs. 11–13, 16–17, 30 |
//! | 12-DOF element | [`crate::kinematics::affine3`] | eqs. 2, 23–25 |
//! | faces and Gauss points | `face.rs` | eqs. 14–28 |
//! | model and assembly | `model.rs` | eqs. 4–10, 14–30 |
//! | stiffness blocks and how the linear solvers read them | `stiffness.rs` | eq. 4 |
//! | elastic and nonlinear analyses, Fs | `analysis.rs` | §5 |
//! | what makes the stiffness ill-conditioned | `conditioning.rs` | (beyond the paper) |
//! | Hovland's column method | `hovland.rs` | ref. 1 (Hovland 1977) |
//! | the results as maps for a GIS (ESRI ASCII, GeoTIFF) | `maps.rs` | (beyond the paper) |
//! | strength-reduction Fs | `strength_reduction.rs` | (beyond the paper) |
//! | errors ([`HpmError`], joined into [`DismechError::Hpm`](crate::error::DismechError::Hpm)) | `error.rs` | (beyond the paper) |
//!
//! Composition, on the engine's slots:
//!
//! | slot | piece |
//! |---|---|
//! | shape | [`crate::shape::Column`] layers of the grid columns |
//! | pair query | a fixed adjacency: the faces between layers and columns, the slip surface under each column (no detection) |
//! | body kinematics | the 12-unknown element of [`crate::kinematics::affine3`] (3D counterpart of DDA's [`crate::kinematics::Affine2`]) |
//! | contact law | penalty springs between elements; [`crate::law::MohrCoulombSpring`] on the slip surface (the Coulomb core shared with the DEM and DDA laws) |
//! | integrator | none: one load step (initial-stiffness iteration) |
//! | linear solver | any [`crate::linsolve::LinearSolver`] of the [`BlockMatrix`] stiffness |
//!
//! The slip springs are a [`crate::law::MohrCoulombSpring`] (a
//! [`crate::law::TangentLaw`]`<3>`), the global solve any
//! [`crate::linsolve::LinearSolver`] of the [`BlockMatrix`] stiffness,
//! factored once and reused by the elastic, nonlinear and
//! strength-reduction analyses: faer's sparse Cholesky
//! ([`crate::linsolve::SparseCholesky`], the default [`HpmSolver`]) or, for
//! large slopes, conjugate gradients preconditioned by one dense block per
//! grid column ([`HpmIterativeSolver`]).
//!
//! Choices where the paper is silent or garbled (also in the reproduction
//! report): the errata's `k_n = (1 − ν) E' / ((1 + ν)(1 − 2ν) h)`; p = 100
//! by default; the `(s, t, n)` frame made orthonormal; the global safety
//! factor, as the stress ratio `Σ (c + σ tan φ) A / Σ |τ| A` and, after
//! Hovland's assumption of one sliding direction, as
//! `Σ (c + σ tan φ) A / Σ (τ · d_i) A` (see `analysis.rs`), each refused
//! where nothing drives the slide or where its strength
//! `Σ (c + σ tan φ) A` is not positive (the surface in tension beyond
//! `c / tan φ`); corner heights interpolated from the cell-centre values
//! of the rasters; a slip spring that opens loses its cohesion over an
//! opening of `c / k_n` rather than at once ([`crate::law::MohrCoulombSpring`]).
//! Where the paper's choices are departed from: below a water table the
//! elements take the seepage force of the table's slope
//! ([`Element::seepage`]) and the seismic force acts on their total
//! weight ([`HpmModel::loads`]), so that submerged weight, seepage and
//! seismic force are those of the total weight and the hydrostatic pore
//! pressure that Hovland's method of [`crate::slope`] takes; the paper
//! (eqs. 8–11) has neither, and its example no water table.

mod analysis;
mod conditioning;
mod error;
mod face;
mod grids;
mod hovland;
mod maps;
mod material;
mod model;
mod stiffness;
mod strength_reduction;

pub use crate::kinematics::affine3::{
    displacement_at, elasticity, element_stiffness, shape_matrix, strain_tensor, ElementDofs,
    ELEMENT_DOF,
};
pub use analysis::{
    linear_motions, Convergence, DrivingForce, HpmIterate, HpmIterativeSolver, HpmMultigridSolver,
    HpmResult, HpmSolver, NonlinearSettings, SafetyFactorKind, SafetyFactorTerm, SpringTraction,
    SurfacePoint, EQUILIBRIUM_TOLERANCE, MIN_DRIVING_RATIO,
};
pub use conditioning::{IllConditioning, INCOMPRESSIBLE_MARGIN, STIFF_PENALTY, THIN_COLUMN_RATIO};
pub use error::HpmError;
pub use face::{bilinear_face, side_face, spring_matrix, FacePoint, Side, SlipPoint};
pub use grids::{NamedRaster, SlopeGrids, MIN_GRID_SIDE};
pub use hovland::{hovland, Hovland, HovlandColumn};
pub use maps::{ColumnMaps, MapProblem, HOVLAND_MAP_NAMES, HPM_MAP_NAMES};
pub use material::{HpmMaterial, HpmSettings, Seismic, MAX_SEISMIC_COEFFICIENT};
pub use model::{
    Element, GridColumn, HpmModel, Interface, MemoryParts, SlipSpring, WeightStratum,
    SYMBOLIC_WORDS_PER_ENTRY,
};
pub use stiffness::BlockMatrix;
pub use strength_reduction::{
    strength_reduction, strength_reduction_observed, StrengthReduction, MAX_REDUCTION_FACTOR,
    MIN_REDUCTION_FACTOR,
};
