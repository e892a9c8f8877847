//! ParaView output: VTK XML files of every driver's state, and a `.pvd`
//! time index over them.
//!
//! A driver's state becomes a [`VtkFrame`]: a few named datasets, each one
//! file. [`PvdSeries`] owns an output folder and writes frame after frame
//! into it, each piece `NAME` as `NAME_000000.vtu` (or `.vtp`),
//! `NAME_000001.vtu`, … and the index `NAME.pvd` that ParaView opens as
//! one time series; every file is written whole or not at all, and an
//! index lists a frame only once all its files are written. The frame
//! functions are plain functions of a driver's state, so that a loop (or
//! an observer called after each step) writes a frame wherever it likes:
//!
//! ```no_run
//! # fn main() -> dismech::error::Result<()> {
//! use dismech::dem::DemSimulation;
//! use dismech::explicit::DemSettings;
//! use dismech::integrate::ExplicitEuler;
//! use dismech::law::SpringDashpotCoulomb;
//! use dismech::math::{Point, Vec2};
//! use dismech::scene::{Frame, Scene};
//! use dismech::vtk::{dem_frame, PvdSeries, DEFAULT_SEGMENTS};
//! let mut scene = Scene::new(Frame::open_box(1.0, 1.0)?, Vec2::new(0.0, -9.81))?;
//! scene.add_circle(Point::new(0.5, 0.2), 0.05, 2600.0)?;
//! let law = SpringDashpotCoulomb::katsuki(73.55e6, 0.3, 0.25, 0.577)?;
//! let mut dem = DemSimulation::new(scene, law, ExplicitEuler, DemSettings::default())?;
//! let mut series = PvdSeries::new("run")?; // run/particles.pvd, run/contacts.pvd, run/walls.pvd
//! for _ in 0..20 {
//!     for _ in 0..500 {
//!         dem.step()?;
//!     }
//!     series.write_frame(dem.time(), &dem_frame(&dem, DEFAULT_SEGMENTS)?)?;
//! }
//! # Ok(()) }
//! ```
//!
//! | concept | file |
//! |---|---|
//! | the datasets (PolyData, UnstructuredGrid, their arrays) and their XML writer | `xml.rs` |
//! | a frame, the series and its `.pvd` indices | `series.rs` |
//! | outlines of 2D shapes, the contact lines the 2D frames share | `outline.rs` |
//! | explicit DEM: [`dem_frame`] | `dem.rs` |
//! | implicit driver and DDA: [`implicit_frame`], [`bodies_frame`] | `implicit.rs` |
//! | limit analysis: [`limit_frame`] | `limit.rs` |
//! | HPM: [`hpm_frame`] | `hpm.rs` |
//! | the frames of a DEM run written by an observer: [`DemFrames`] | `observe.rs` |
//!
//! ## The files
//!
//! VTK XML, version 1.0, every array inline as base64 binary
//! (little-endian, a `UInt64` byte count before each array, no
//! compression): the values are the `f64`s' own bits, and infinite values
//! (a prescribed particle's mass, a local factor of safety where nothing
//! shears) stay infinite. No library beyond the standard one writes them.
//! 2D models lie in the plane z = 0; every vector has three components
//! (z = 0 in 2D) so that ParaView shows it as a vector and glyphs it.
//! Tensors have nine, row by row (`xx, xy, xz, yx, …, zz`). SI units
//! throughout; 2D forces are per metre of thickness (N/m), 2D moments
//! N·m/m.
//!
//! Codes: `kind` is 0 a circle, 1 an ellipse, 2 a polygon, 3 a segment (a
//! wall) ([`kind`]); `regime` is 0 open, 1 stick, 2 slip. Flags
//! (`prescribed`, `fixed`, `rotates`, `target_is_wall`,
//! `partner_is_support`) are 0 or 1.
//!
//! **Contacts**, in every 2D frame: one poly-line per contact point, from
//! A's centre through the contact point to B's centre (to the contact
//! point alone where B is a wall or a support), so that a *Tube* filter
//! scaled by `normal_force` draws the force chains. Cell data:
//!
//! | array | meaning | unit |
//! |---|---|---|
//! | `point` | the contact point | m |
//! | `normal` | unit normal from A to B | – |
//! | `force` | force A exerts on B (B exerts its opposite on A) | N/m |
//! | `normal_force` | `force · normal`: compression positive | N/m |
//! | `shear_force` | `force · tangent`, the tangent the normal turned by +90° | N/m |
//!
//! ### Explicit DEM ([`dem_frame`]): `particles.vtu`, `contacts.vtp`, `walls.vtp`
//!
//! `particles`: cell `k` is particle `k`'s outline (a circle or an ellipse
//! as a polygon of `segments` sides, starting on the body's x axis so that
//! it turns with the particle; a polygon as it is). Cell data: `id`,
//! `kind`, `prescribed`, `radius` (the largest distance from the centre
//! to the outline: a circle's radius; m), `centre` (m), `rotation` (rad,
//! counter-clockwise), `velocity` (m/s), `angular_velocity` (rad/s),
//! `mass` (kg/m; infinite for a prescribed particle), `force` and
//! `moment` (the sum on the particle in the last step, contacts plus
//! weight, [`crate::explicit::ExplicitDynamics::force_on`]; N/m, N·m/m).
//!
//! `contacts` (one per point of [`crate::explicit::ExplicitDynamics::contacts`]):
//! the common arrays, and `particle` (A), `target` (B: a particle's or a
//! wall's index), `target_is_wall`, `regime`, `overlap` (m).
//!
//! `walls`: a line per wall of the frame; `id`, `load` (the force of the
//! particles on the wall, N/m).
//!
//! ### Implicit driver and DDA ([`implicit_frame`]): `bodies.vtu`, `contacts.vtp`
//!
//! `bodies`: cell `k` is body `k`'s current outline (a polygon's vertices,
//! deformed for DDA's affine blocks; an ellipse or a circle as a polygon
//! of `segments` sides, `kind` 0 only while its semi-axes are equal to
//! 1e-12: a DDA disc strained by its weight is an ellipse; a wall as a
//! line). Point data: `velocity`, the
//! velocity of each outline point by the body's kinematics (m/s). Cell
//! data: `id`, `kind`, `group`, `fixed` (every unknown prescribed), `area`
//! (m²/m), `centroid` (m), `velocity` (of the centroid, m/s),
//! `angular_velocity` (the spin, half the skew part of the rate of the
//! deformation gradient, rad/s), `displacement` (of the centroid since the
//! start, m), `stress` (Pa, tensile positive: DDA's uniform stress, σz
//! zero in plane stress and `ν (σx + σy)` in plane strain; zero for rigid
//! kinematics), `dof_velocity` and `dof_displacement` (the kinematics' own
//! `N` unknowns: their rates and totals since the start; DDA's are
//! `(u₀, v₀, r₀, εx, εy, γxy)`).
//!
//! `contacts` (one per [`crate::implicit::ContactReport`]; A is the vertex
//! or smooth side, B the edge side, and the contact point is A's material
//! point): the common arrays (the report's normal and force on A turned
//! into the convention above: `normal = −report.normal`,
//! `force = −report.force_on_a`), and `body_a`, `body_b`, `gap` (m,
//! negative where the bodies overlap), `shear` (the step's shear
//! displacement, m), `law_force` (the law's `(t_n, t_s)`, N/m).
//!
//! ### Limit analysis ([`limit_frame`]): `bodies.vtu`, `contacts.vtp`, `supports.vtp`
//!
//! One frame (write it at time 0). The velocities are those of the
//! collapse mechanism, with the driver at unit speed (a plate at 1 m/s,
//! or the live load's unit power): their scale is arbitrary.
//!
//! `bodies`: cell `k` is body `k`'s outline. Point data: `velocity`,
//! `v + ω × r` of the mechanism at each outline point (*Warp By Vector*
//! with a scale factor draws the mechanism). Cell data: `id`, `kind`,
//! `rotates`, `centre` (m), `load` (the dead load, N/m), `velocity`,
//! `angular_velocity`.
//!
//! `contacts` (one per [`crate::limit::LimitContact`]): the common arrays
//! from the dual forces (`normal_force` is the result's normal force;
//! `shear_force` is the *negative* of the result's shear force, which is
//! counted against the slip of B along the tangent), and `body`,
//! `partner`, `partner_is_support`, `slip` and `opening` (rates, m/s),
//! `cohesion` (N/m), `friction` (tan φ).
//!
//! `supports`: a line per support, centred where it passes nearest the
//! middle of the bodies' box and as long as the box's diagonal; `id`,
//! `normal` (into the material), `velocity`.
//!
//! ### HPM ([`hpm_frame`]): `elements.vtu`, `slip.vtp`
//!
//! 3D. `elements`: cell `k` is element `k` (a layer of a grid column) as a
//! hexahedron with its own eight corners (bottom face, then top face).
//! Point data: `displacement` (m), the element's linear field at each
//! corner (HPM's elements are independent fields: the corners of two
//! neighbours differ by what their penalty springs stretch). Cell data:
//! `id`, `column` (index in the model's columns), `layer` (0 at the
//! bottom), `cell` (the grid's row and column), `centre` (m), `volume`
//! (m³), `weight` (N), `displacement` (of the centroid, m), `rotation`
//! (rad), `strain` (the uniform strain tensor, tensile positive),
//! `local_safety_factor` (of the element's column; 0 where its strength
//! is not positive, infinite where nothing shears it).
//!
//! `slip`: a vertex per slip-surface spring (a Gauss point of a column's
//! base). Cell data: `element`, `column`, `area` (m²), `normal` (down,
//! into the ground), `normal_traction` (Pa, compression positive),
//! `shear_traction` (Pa, the vector resisting the soil's slip),
//! `regime`, `displacement` (of the soil at the point, m).
//!
//! ## In ParaView
//!
//! *File → Open* the `.pvd` files of the folder (e.g. `particles.pvd` and
//! `contacts.pvd`), *Apply*; the time controls step through the frames.
//! Colour the particles by `velocity` (*Magnitude*) or `id`; for force
//! chains, *Tube* on `contacts` with *Vary Radius* by `normal_force`
//! (*By Absolute Scalar*). A single `.vtu`/`.vtp` opens as one state. In
//! Python, `vtkXMLUnstructuredGridReader` and `vtkXMLPolyDataReader` read
//! the files (`tests/vtk_read_back.py`, `examples/render_frame.py`).

mod dem;
mod hpm;
mod implicit;
mod limit;
mod observe;
mod outline;
mod problem;
mod series;
mod xml;

pub use dem::dem_frame;
pub use hpm::hpm_frame;
pub use implicit::{bodies_frame, implicit_frame};
pub use limit::limit_frame;
pub use observe::DemFrames;
pub use outline::{kind, DEFAULT_SEGMENTS};
pub use problem::{DataKind, VtkProblem};
pub use series::{pvd_text, write_dataset, Piece, PvdEntry, PvdSeries, VtkFrame};
pub use xml::{cell_type, Cells, DataArray, Dataset, PolyData, UnstructuredGrid, Values};
