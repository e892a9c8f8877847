//! # dismech — discrete mechanics of granular and blocky geomaterials
//!
//! A model in dismech is a *composition*: one piece per slot, run by one
//! of a few drivers. The four published methods the crate reproduces are
//! four such compositions, and a new model — polygons in the DEM, ellipses
//! under an implicit Newton step, blocks in a limit analysis — is a new
//! choice of pieces, not a new engine.
//!
//! ## The slots
//!
//! | slot | trait(s) | pieces | module |
//! |---|---|---|---|
//! | shape | [`shape::Shape`], [`shape::Shape2`] | [`shape::Circle`], [`shape::Ellipse`], [`shape::Polygon`] (convex or concave), [`shape::Segment`], [`shape::Column`] (3D) | [`shape`] |
//! | pair query | [`query::contact_manifold_2d`] (one dispatcher; several points where a face meets a face); [`query::variation::GapVariation`] (gap and shear with first and second variations, for implicit drivers) | one routine per pair of 2D shapes; a pair without one is a typed error naming both | [`query`] |
//! | body kinematics | [`kinematics::Kinematics`] | [`kinematics::Rigid2`] (3 unknowns), [`kinematics::Affine2`] (DDA's 6), [`kinematics::Fixed`]; [`kinematics::affine3`] (HPM's 12, 3D) | [`kinematics`] |
//! | contact law | [`law::ContactLaw`] (force), [`law::TangentLaw`] (consistent tangent), [`law::StrengthLaw`] (strength), [`law::BoundedStiffness`] (stable step) | [`law::SpringDashpotCoulomb`], [`law::PenaltyCoulomb`], [`law::MohrCoulombSpring`] on one Coulomb core ([`law::coulomb`]); [`law::RigidPlastic`]; checks for any law in [`law::conformance`] | [`law`] |
//! | integrator | [`integrate::ExplicitIntegrator`], [`integrate::ImplicitIntegrator`] | [`integrate::ExplicitEuler`], [`integrate::Newmark`] (any β, γ), [`integrate::QuasiStatic`], [`integrate::Restarting`] | [`integrate`] |
//! | linear solver | [`linsolve::LinearSolver`] (analyse once, factor many, solve many) | [`linsolve::SparseLu`], [`linsolve::SparseCholesky`], [`linsolve::ConjugateGradient`] with [`linsolve::BlockJacobi`], [`linsolve::LumpedMassSolver`] | [`linsolve`] |
//! | LP solver | [`lp::LpSolver`] | [`lp::LinearProgramSolver`] (Clarabel) | [`lp`] |
//!
//! A driver names in its bounds the capabilities it needs, so a piece that
//! lacks one does not compile with it: an implicit integrator in the
//! explicit driver, a law without a tangent in the implicit driver, a law
//! without a strength in a limit analysis, a law without a stiffness bound
//! in the explicit driver (unless its stability check is explicitly
//! waived).
//!
//! ## The drivers
//!
//! | driver | generic over | module |
//! |---|---|---|
//! | explicit dynamics (DEM) | law `L: ContactLaw<2> + BoundedStiffness<2>`, integrator `I: ExplicitIntegrator`; any 2D shapes through the manifold dispatcher; rigid bodies | [`explicit::ExplicitDynamics`] |
//! | implicit dynamics: open–close, Newton with line search, Δt control | kinematics `K: Kinematics<N>`, law `L: TangentLaw<2>` (per pair of body groups), integrator `I: ImplicitIntegrator`, linear solver `S: LinearSolver`; any 2D shapes through the variation queries | [`implicit::ImplicitDynamics`] |
//! | limit analysis (rigid-plastic LP) | LP solver `S: LpSolver`; bodies of any shape; any `StrengthLaw` per contact; a driven plate or a live load | [`limit::analyse`], [`limit::analyse_static`] |
//! | HPM slope analysis (elastic, nonlinear, strength reduction) | linear solver `S: LinearSolver<BlockMatrix>` (Cholesky or PCG); the 12-unknown element of [`kinematics::affine3`]; [`law::MohrCoulombSpring`] on the Coulomb core | [`hpm::HpmSolver`] |
//! | slope search over a DEM: Hovland's 3D columns on thousands of trial surfaces, the map of the lowest Fs per cell (Scoops3D, r.slope.stability) | trial family `F: slope::TrialFamily` (spheres on Scoops3D's grid, random spheres or ellipsoids) with its `slope::TrialSurface`; rayon, streaming, deterministic | [`slope::search`] |
//!
//! ## The four papers as compositions
//!
//! | method (paper) | type or constructor | pieces |
//! |---|---|---|
//! | ellipse DEM (000, Katsuki & Ishikawa 1990) | [`dem::DemSimulation`]`<SpringDashpotCoulomb>` = `ExplicitDynamics<SpringDashpotCoulomb, ExplicitEuler>` | ellipses and circles, the exact ellipse manifold, rigid kinematics, [`law::SpringDashpotCoulomb::katsuki`] (eqs. 14–19), [`integrate::ExplicitEuler`], diagonal mass |
//! | rigid-plastic LP (002, Yamada & Tamura 2000) | [`limit::analyse`]`(&`[`limit::lattice::Lattice`]`::u_model(..).build()?, &mut LinearProgramSolver)` | circles, contacts from circle geometry, rigid kinematics (rolling or not), [`law::RigidPlastic`], Clarabel |
//! | implicit DDA (003, Hashimoto, Koyama & Kikumoto) | [`dda::DdaModel`] = `ImplicitDynamics<6, Affine2, PenaltyCoulomb, Newmark, SparseLu>` | polygons, vertex–edge variations, [`kinematics::Affine2`], [`law::PenaltyCoulomb`] (return mapping), [`integrate::Newmark`] β = ½, γ = 1, [`linsolve::SparseLu`] |
//! | HPM slope stability (001, Yamaguchi, Takeuchi & Hamasaki) | [`hpm::HpmSolver`]`<SparseCholesky>` (or `<ConjugateGradient<BlockJacobi>>`) | grid columns, fixed adjacency, [`kinematics::affine3`], [`law::MohrCoulombSpring`], a linear solver factored once |
//!
//! ```no_run
//! # fn main() -> dismech::error::Result<()> {
//! use dismech::dem::DemSimulation;
//! use dismech::explicit::DemSettings;
//! use dismech::integrate::ExplicitEuler;
//! use dismech::law::SpringDashpotCoulomb;
//! use dismech::math::{Point, Vec2};
//! use dismech::scene::{Frame, Scene};
//! // Paper 000: ellipses in a frame, explicit DEM.
//! let mut scene = Scene::new(Frame::open_box(2.0, 3.0)?, Vec2::new(0.0, -9.81))?;
//! scene.add_ellipse(Point::new(1.0, 0.5), 0.099, 0.0495, 0.0, 2690.0)?;
//! let law = SpringDashpotCoulomb::katsuki(73.55e6, 0.3, 0.25, 0.577)?;
//! let dem: DemSimulation<SpringDashpotCoulomb> =
//!     DemSimulation::new(scene, law, ExplicitEuler, DemSettings::default())?;
//! # Ok(()) }
//! ```
//!
//! ```no_run
//! # fn main() -> dismech::error::Result<()> {
//! use dismech::limit::{analyse, lattice::Lattice};
//! use dismech::lp::LinearProgramSolver;
//! // Paper 002: the rolling U-model, k = 4, n' = 1, by LP.
//! let model = Lattice::u_model(4, 4, 1, true).build()?;
//! let result = analyse(&model, &mut LinearProgramSolver::default())?;
//! # Ok(()) }
//! ```
//!
//! ```no_run
//! # fn main() -> dismech::error::Result<()> {
//! use dismech::dda::{Block, BlockMaterial, DdaModel, DdaSettings, PlaneState, Prescribed};
//! use dismech::implicit::ImplicitDynamics;
//! use dismech::integrate::Newmark;
//! use dismech::kinematics::Affine2;
//! use dismech::law::{FrictionIntegration, PenaltyCoulomb};
//! use dismech::linsolve::SparseLu;
//! use dismech::math::Point;
//! // Paper 003: a block on a fixed base, implicit DDA.
//! let rock = BlockMaterial { density: 2200.0, youngs_modulus: 14.9e9, poisson_ratio: 0.2,
//!                            plane: PlaneState::Stress };
//! let square = |x0: f64, y0: f64, x1: f64, y1: f64| {
//!     [Point::new(x0, y0), Point::new(x1, y0), Point::new(x1, y1), Point::new(x0, y1)]
//! };
//! let mut base = Block::new(&square(-2.0, -0.5, 2.0, 0.0), rock, 0)?;
//! base.prescribed = Some(Prescribed::fixed());
//! let block = Block::new(&square(-0.5, 0.0, 0.5, 0.5), rock, 1)?;
//! let law = PenaltyCoulomb::new(2e9, 0.7, FrictionIntegration::ReturnMapping)?;
//! // The same model twice: by its name, and spelled out slot by slot.
//! let dda: DdaModel = DdaModel::new(vec![base.clone(), block.clone()], law, DdaSettings::default())?;
//! let spelled: ImplicitDynamics<6, Affine2, PenaltyCoulomb, Newmark, SparseLu> =
//!     ImplicitDynamics::compose(vec![base, block], Affine2, law, Newmark::new(0.5, 1.0)?,
//!                               SparseLu::default(), DdaSettings::default())?;
//! # Ok(()) }
//! ```
//!
//! ```no_run
//! # fn main() -> dismech::error::Result<()> {
//! use dismech::grid::Raster;
//! use dismech::hpm::{HpmMaterial, HpmModel, HpmSettings, HpmSolver, NamedRaster, Seismic, SlopeGrids};
//! // Paper 001: a slab on a planar slip surface, elastic HPM by sparse Cholesky.
//! let ground = Raster::from_fn(10, 10, 0.0, 0.0, 10.0, |_, y| Some(0.36 * y))?;
//! let slip = Raster::from_fn(10, 10, 0.0, 0.0, 10.0, |_, y| Some(0.36 * y - 6.0))?;
//! let grids = SlopeGrids::new(NamedRaster::new("ground", ground), NamedRaster::new("slip", slip), None)?;
//! let model = HpmModel::new(&grids, &HpmMaterial::paper(), &HpmSettings::default())?;
//! let mut solver = HpmSolver::new(&model)?;
//! let result = solver.elastic(&model, &Seismic::none())?;
//! # Ok(()) }
//! ```
//!
//! ## Cross-compositions
//!
//! Combinations no single paper has, built from this library's pieces
//! alone. Each is run as a fixed experiment (the `compositions` module of
//! the `dismech-cli` package in `cli/`, no part of this library) by the
//! tests and by `dismech reproduce compositions`, and checked against an
//! exact solution or a second method:
//!
//! | composition | type or driver | pieces | checked against | experiment |
//! |---|---|---|---|---|
//! | polygon DEM | [`dem::DemSimulation`]`<SpringDashpotCoulomb>` | [`shape::Polygon`] in the explicit driver, polygon–wall manifold (two points), [`law::SpringDashpotCoulomb`] with a constant `k_n`, rigid kinematics, [`integrate::ExplicitEuler`] | sliding at `g (sin β − μ cos β)` ([`reference::incline`]); sticking below `tan β = μ` | `polygon_incline` |
//! | polygon DEM vs DDA | `ExplicitDynamics<SpringDashpotCoulomb, ExplicitEuler>` and `ImplicitDynamics<6, Affine2, PenaltyCoulomb, Restarting<Newmark>, SparseLu>` | the same running-bond wall of [`shape::Polygon`] blocks by both drivers | base reaction = weight in both; the bottom course compared | `block_wall` |
//! | polygon LP | [`limit::analyse`] on a [`limit::LimitModel`] | a [`shape::Polygon`] block in the limit driver, its corners as contact points, [`law::RigidPlastic`] unilateral friction, a live load, Clarabel | tipping `W w / 2h` or sliding `μ W` ([`reference::block_on_floor`]) | `polygon_lp` |
//! | packing LP | [`limit::model_from_packing`], then [`limit::analyse`] | ellipses settled by the explicit driver, then their bodies and manifolds in the limit driver | equilibrium of the dual forces; primal = dual | `packing_lp` |
//! | implicit ellipses | `ImplicitDynamics<3, Rigid2, PenaltyCoulomb, Newmark, SparseLu>` | rigid ellipses and walls, smooth–smooth and smooth–edge gap variations, return-mapping Coulomb, Newmark β = 0.5625, γ = 1 with mass damping, at a requested step of 20 explicit limits (the search distance follows fast motion) | the walls carry the weight at rest | `implicit_ellipses` |
//! | affine disc | `ImplicitDynamics<6, Affine2, PenaltyCoulomb, Newmark, SparseLu>` | a disc with DDA's six affine unknowns on a smooth boundary | rolling at `(2/3) g sin β` ([`reference::incline::disc_acceleration`]) | `affine_disc` |
//! | penalty vs LP | `ImplicitDynamics<3, Rigid2, PenaltyCoulomb, QuasiStatic, SparseLu>` against [`limit::analyse`] | a [`limit::LimitModel`] of circles turned into bodies with bonded contacts ([`law::PenaltyCoulomb::bonded_with_friction`]) and a prescribed plate | the plateau of the plate load against the LP's limit load | `penalty_vs_lp` |
//!
//! Each row, as its pieces are put together (the experiments run them at
//! full size and check them):
//!
//! ```
//! # fn main() -> dismech::error::Result<()> {
//! use dismech::dem::DemSimulation;
//! use dismech::explicit::DemSettings;
//! use dismech::integrate::ExplicitEuler;
//! use dismech::law::{Damping, NormalStiffness, SpringDashpotCoulomb};
//! use dismech::math::{Point, Vec2};
//! use dismech::scene::{Frame, Scene};
//! // Polygon DEM: a square block on the floor of a box, a constant k_n.
//! let mut scene = Scene::new(Frame::open_box(2.0, 2.0)?, Vec2::new(0.0, -9.81))?;
//! scene.add_rectangle(Point::new(1.0, 0.1), 0.2, 0.2, 0.0, 2600.0)?;
//! let law = SpringDashpotCoulomb::new(NormalStiffness::Constant(1e8), 0.25, 0.5, Damping::Critical)?;
//! let mut dem = DemSimulation::new(scene, law, ExplicitEuler, DemSettings { dt: 1e-5, ..DemSettings::default() })?;
//! for _ in 0..100 {
//!     dem.step()?;
//! }
//! assert_eq!(dem.steps(), 100);
//! # Ok(()) }
//! ```
//!
//! ```
//! # fn main() -> dismech::error::Result<()> {
//! use dismech::dda::{Block, BlockMaterial, DdaSettings, PlaneState, Prescribed};
//! use dismech::implicit::ImplicitDynamics;
//! use dismech::integrate::{Newmark, Restarting};
//! use dismech::kinematics::Affine2;
//! use dismech::law::{FrictionIntegration, PenaltyCoulomb};
//! use dismech::linsolve::SparseLu;
//! use dismech::math::Point;
//! // Polygon DEM vs DDA, the DDA side: blocks under classic DDA's static
//! // analysis (the velocities restarted at each step).
//! let rock = BlockMaterial { density: 2600.0, youngs_modulus: 3e10, poisson_ratio: 0.2,
//!                            plane: PlaneState::Strain };
//! let rect = |x0: f64, y0: f64, x1: f64, y1: f64| {
//!     [Point::new(x0, y0), Point::new(x1, y0), Point::new(x1, y1), Point::new(x0, y1)]
//! };
//! let mut base = Block::new(&rect(-1.0, -0.5, 1.0, 0.0), rock, 0)?;
//! base.prescribed = Some(Prescribed::fixed());
//! let brick = Block::new(&rect(-0.2, 0.0, 0.2, 0.2), rock, 1)?;
//! let law = PenaltyCoulomb::new(2e9, 0.6, FrictionIntegration::ReturnMapping)?;
//! let mut dda: ImplicitDynamics<6, Affine2, PenaltyCoulomb, Restarting<Newmark>, SparseLu> =
//!     ImplicitDynamics::compose(vec![base, brick], Affine2, law, Restarting(Newmark::dda()),
//!                               SparseLu::default(), DdaSettings::default())?;
//! dda.advance(1e-3)?;
//! # Ok(()) }
//! ```
//!
//! ```
//! # fn main() -> dismech::error::Result<()> {
//! use dismech::law::RigidPlastic;
//! use dismech::limit::{analyse, LimitModel, Partner};
//! use dismech::lp::LinearProgramSolver;
//! use dismech::math::{Point, Pose2, Vec2};
//! use dismech::reference::block_on_floor::BlockOnFloor;
//! use dismech::shape::Polygon;
//! // Polygon LP: a block pushed at its top tips at W w / 2h.
//! let (w, h, weight) = (0.4, 0.8, 1e3);
//! let mut model = LimitModel::new(1e-9)?;
//! let block = model.add_shape(Polygon::rectangle(w, h)?.into(), Pose2::new(0.0, h / 2.0, 0.0), true)?;
//! model.set_load(block, Vec2::new(0.0, -weight))?;
//! let floor = model.add_support("floor", Point::origin(), Vec2::y(), Vec2::zeros())?;
//! model.add_contacts(block, Partner::Support(floor), RigidPlastic::coulomb(0.0, 1.0, true)?)?;
//! model.set_live_load(block, Vec2::x(), Point::new(0.0, h))?;
//! let limit = analyse(&model, &mut LinearProgramSolver::default())?;
//! let exact = BlockOnFloor { width: w, height: h, weight, friction: 1.0 }.tipping_load();
//! assert!((limit.load.unwrap() / exact - 1.0).abs() < 1e-6);
//! # Ok(()) }
//! ```
//!
//! ```
//! # fn main() -> dismech::error::Result<()> {
//! use dismech::dem::DemSimulation;
//! use dismech::explicit::{DemSettings, RestCriterion};
//! use dismech::integrate::ExplicitEuler;
//! use dismech::law::{RigidPlastic, SpringDashpotCoulomb};
//! use dismech::limit::{analyse, model_from_packing, PackingLimitSettings};
//! use dismech::lp::LinearProgramSolver;
//! use dismech::math::{Point, Vec2};
//! use dismech::scene::{Frame, Scene};
//! // Packing LP: ellipses settled by the explicit driver, then pushed by
//! // the left wall in a limit analysis of their contacts.
//! // Gravity leans a little to the left, so the ellipses bear on that wall.
//! let mut scene = Scene::new(Frame::open_box(0.4, 1.0)?, Vec2::new(-1.0, -9.81))?;
//! for x in [0.08, 0.24] {
//!     scene.add_ellipse(Point::new(x, 0.05), 0.08, 0.05, 0.0, 2690.0)?;
//! }
//! let law = SpringDashpotCoulomb::katsuki(73.55e6, 0.3, 0.25, 0.577)?;
//! let mut dem = DemSimulation::new(scene, law, ExplicitEuler, DemSettings::default())?;
//! dem.run_to_rest(&RestCriterion::default(), |_, _| {})?;
//! let friction = RigidPlastic::coulomb(0.0, 0.577, true)?;
//! let settings = PackingLimitSettings {
//!     rolling: true, contact_law: friction, wall_law: friction,
//!     plate_law: RigidPlastic::coulomb(0.0, 0.0, true)?,
//!     plate_wall: "left".into(), self_weight: true,
//! };
//! let model = model_from_packing(dem.scene(), dem.contacts(), &settings)?;
//! let limit = analyse(&model, &mut LinearProgramSolver::default())?;
//! assert!(limit.load.is_some_and(|p| p > 0.0));
//! # Ok(()) }
//! ```
//!
//! ```
//! # fn main() -> dismech::error::Result<()> {
//! use dismech::implicit::{Body, BodyMaterial, ImplicitDynamics, ImplicitSettings, PlaneState};
//! use dismech::integrate::Newmark;
//! use dismech::kinematics::{Affine2, Rigid2};
//! use dismech::law::{FrictionIntegration, PenaltyCoulomb};
//! use dismech::linsolve::SparseLu;
//! use dismech::math::Point;
//! use dismech::shape::Segment;
//! let rock = BodyMaterial { density: 2690.0, youngs_modulus: 1e9, poisson_ratio: 0.3,
//!                           plane: PlaneState::Strain };
//! let line = Segment::new(Point::new(-2.0, 0.0), Point::new(2.0, 0.0));
//! let law = PenaltyCoulomb::new(1e8, 0.5, FrictionIntegration::ReturnMapping)?;
//! // Implicit ellipses: rigid ellipses on a wall, Newmark β = 0.5625, γ = 1.
//! let ellipse = Body::ellipse(Point::new(0.0, 0.05), 0.1, 0.05, 0.0, rock, 1)?;
//! let mut ellipses: ImplicitDynamics<3, Rigid2, PenaltyCoulomb, Newmark, SparseLu> =
//!     ImplicitDynamics::compose(vec![Body::wall(line, 0)?, ellipse], Rigid2, law, Newmark::new(0.5625, 1.0)?,
//!                               SparseLu::default(), ImplicitSettings::default())?;
//! ellipses.advance(1e-3)?;
//! // Affine disc: a disc with DDA's six unknowns rolling on the wall.
//! let disc = Body::circle(Point::new(0.0, 0.1), 0.1, rock, 1)?;
//! let mut rolling: ImplicitDynamics<6, Affine2, PenaltyCoulomb, Newmark, SparseLu> =
//!     ImplicitDynamics::compose(vec![Body::wall(line, 0)?, disc], Affine2, law, Newmark::dda(),
//!                               SparseLu::default(), ImplicitSettings::default())?;
//! rolling.advance(1e-3)?;
//! # Ok(()) }
//! ```
//!
//! ```
//! # fn main() -> dismech::error::Result<()> {
//! use dismech::implicit::{Body, BodyMaterial, ImplicitDynamics, ImplicitSettings, PlaneState, Prescribed};
//! use dismech::integrate::QuasiStatic;
//! use dismech::kinematics::Rigid2;
//! use dismech::law::PenaltyCoulomb;
//! use dismech::linsolve::SparseLu;
//! use dismech::math::{Point, Vec2};
//! use dismech::shape::Segment;
//! // Penalty vs LP: circles with bonded contacts pushed quasi-statically by
//! // a plate moving at a prescribed speed (the LP side is `limit::analyse`).
//! let soil = BodyMaterial { density: 2000.0, youngs_modulus: 1e8, poisson_ratio: 0.3,
//!                           plane: PlaneState::Strain };
//! let floor = Body::wall(Segment::new(Point::new(-2.0, 0.0), Point::new(2.0, 0.0)), 0)?;
//! let grain = Body::circle(Point::new(0.0, 0.1), 0.1, soil, 1)?;
//! let mut plate = Body::circle(Point::new(-0.2, 0.1), 0.1, soil, 2)?;
//! plate.prescribed = Some(Prescribed::translation(|t| Vec2::new(1e-3 * t, 0.0)));
//! let law = PenaltyCoulomb::bonded_with_friction(1e9, 10.0, 0.5)?;
//! let mut pushover: ImplicitDynamics<3, Rigid2, PenaltyCoulomb, QuasiStatic, SparseLu> =
//!     ImplicitDynamics::compose(vec![floor, grain, plate], Rigid2, law, QuasiStatic,
//!                               SparseLu::default(), ImplicitSettings::default())?;
//! pushover.advance(1e-2)?;
//! # Ok(()) }
//! ```
//!
//! ```
//! # fn main() -> dismech::error::Result<()> {
//! use dismech::limit::{analyse, LimitModel, Partner};
//! use dismech::law::RigidPlastic;
//! use dismech::lp::LinearProgramSolver;
//! use dismech::math::{Point, Pose2, Vec2};
//! use dismech::shape::Polygon;
//! // A polygon block in the limit driver: corners on a floor, a live load at the top.
//! let (w, h, weight) = (0.4, 0.8, 1e3);
//! let mut model = LimitModel::new(1e-9)?;
//! let block = model.add_shape(Polygon::rectangle(w, h)?.into(), Pose2::new(0.0, h / 2.0, 0.0), true)?;
//! model.set_load(block, Vec2::new(0.0, -weight))?;
//! let floor = model.add_support("floor", Point::origin(), Vec2::y(), Vec2::zeros())?;
//! let law = RigidPlastic::from_friction_angle_deg(0.0, 30.0, true)?;
//! for x in [-w / 2.0, w / 2.0] {
//!     model.add_contact_at(block, Partner::Support(floor), law, Point::new(x, 0.0), -Vec2::y())?;
//! }
//! model.set_live_load(block, Vec2::x(), Point::new(0.0, h))?;
//! let limit = analyse(&model, &mut LinearProgramSolver::default())?;
//! # Ok(()) }
//! ```
//!
//! ```
//! # fn main() -> dismech::error::Result<()> {
//! use dismech::implicit::{Body, BodyMaterial, ImplicitDynamics, ImplicitSettings, PlaneState};
//! use dismech::integrate::Newmark;
//! use dismech::kinematics::Affine2;
//! use dismech::law::{FrictionIntegration, PenaltyCoulomb};
//! use dismech::linsolve::SparseLu;
//! use dismech::math::{Point, Vec2};
//! use dismech::shape::Segment;
//! // A disc and an ellipse as DDA bodies (six affine unknowns) on a floor.
//! let material = BodyMaterial { density: 2000.0, youngs_modulus: 1e10, poisson_ratio: 0.2, plane: PlaneState::Stress };
//! let bodies = vec![
//!     Body::<6>::circle(Point::new(0.0, 0.1), 0.1, material, 0)?,
//!     Body::<6>::ellipse(Point::new(0.5, 0.05), 0.1, 0.05, 0.0, material, 1)?,
//!     Body::<6>::wall(Segment::new(Point::new(-1.0, 0.0), Point::new(1.0, 0.0)), 2)?, // bodies on its left
//! ];
//! let law = PenaltyCoulomb::new(1e8, 0.5, FrictionIntegration::ReturnMapping)?;
//! let settings = ImplicitSettings { gravity: Vec2::new(0.0, -9.81), ..ImplicitSettings::default() };
//! let mut model = ImplicitDynamics::compose(bodies, Affine2, law, Newmark::new(0.5625, 1.0)?, SparseLu::default(), settings)?;
//! model.advance(1e-3)?;
//! # Ok(()) }
//! ```
//!
//! ## Data flow of one step
//! 1. **World**: bodies (shape, kinematics, material, state), walls,
//!    loads, contact history ([`scene`], [`implicit::Body`]).
//! 2. **Broad phase**: candidate pairs from a uniform cell grid, or a grid
//!    per size level when the sizes spread wide ([`broad_phase::CellGrid`]),
//!    or a fixed adjacency (HPM).
//! 3. **Pair query**: a manifold ([`query::manifold`]), or gaps with their
//!    variations ([`query::variation`]).
//! 4. **Contact law**: force, tangent, regime, new history ([`law`]).
//! 5. **Assembly / solve**: force sums into `M a = f`, a sparse system on
//!    a reused pattern ([`linsolve`]), or an LP ([`lp`]).
//! 6. **Integrator**: advance the state ([`integrate`]).
//! 7. **Outputs**: files written whole or not at all
//!    ([`io::write_atomically`]; the grids' writer in [`grid`]; every
//!    driver's state as ParaView files, VTK XML with a `.pvd` time index,
//!    in [`vtk`]). The
//!    reports of the reproductions (CSV tables, SVG plots,
//!    `summary.json`) are the `dismech` command's, in the `dismech-cli`
//!    package.
//! 8. **Checkpoints**: the explicit and implicit drivers save their whole
//!    state (postcard, versioned, written atomically) and resume from it
//!    to the same bits ([`checkpoint`]).
//!
//! ## Conventions
//! SI units (m, kg, s, N, Pa); 2D quantities are per metre of thickness.
//! 2D methods work in the x–y plane, y up, angles counter-clockwise from +x.
//! Angles are in radians. Friction is the coefficient μ = tan φ in every law
//! and material ([`law::friction_from_degrees`] converts an angle). Misuse is an `Err` of
//! [`error::DismechError`] naming the offending value; a run that goes
//! unstable stops with an error saying what to change. The grid files, HPM,
//! the slope search, the implicit and explicit drivers and the limit
//! analysis each have their own error, one per module
//! ([`grid::GridError`], [`hpm::HpmError`], [`slope::SlopeError`],
//! [`implicit::ImplicitError`], [`explicit::ExplicitError`],
//! [`limit::LimitError`]), joined into [`error::DismechError`] (its `Grid`,
//! `Hpm`, `Slope`, `Implicit`, `Explicit` and `Limit` variants, each with
//! `From` and the same message), which every fallible function returns.
//!
//! ## Exact references and reproductions
//! [`reference`](mod@reference) holds exact reference solutions (the rigid and compliant
//! sliding block, the planar slab's Fs, paper 002's two-element example and
//! closed forms, an independent ellipse contact, a block tipping or sliding
//! on a floor) that tests, examples and the reproductions check the
//! methods against. The reproductions of the papers are clients of this
//! library, in the `dismech` binary of the `dismech-cli` package
//! (`dismech reproduce all`): they build their scenes from these pieces,
//! run them and compare with each paper.

#![deny(missing_docs)]
// Every public fallible function says what it returns (`# Errors`); CI runs
// clippy with `-D warnings`, which makes this lint an error.
#![warn(clippy::missing_errors_doc)]

/// The linear algebra of the public API ([`math::Vec2`], [`math::Point`],
/// the `SVector` and `SMatrix` of a contact law's input, force and
/// tangent), re-exported so that a model or a law of one's own names these
/// types as `dismech::nalgebra::…` without a second dependency pinned to
/// the same version.
pub use nalgebra;

pub mod broad_phase;
pub mod checkpoint;
pub mod dda;
pub mod dem;
pub mod error;
pub mod explicit;
pub mod grid;
pub mod hpm;
pub mod implicit;
pub mod integrate;
pub mod io;
pub mod kinematics;
pub mod law;
pub mod limit;
pub mod linsolve;
pub mod lp;
pub mod math;
pub mod observe;
pub mod query;
pub mod reference;
pub mod scene;
pub mod shape;
pub mod slope;
pub mod vtk;

/// The README's code blocks, compiled as doctests so that they stay true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
