//! The implicit driver: bodies, laws and the workspaces of the step, and
//! the time loop with automatic reduction of the step.

use rustc_hash::FxHashMap;

use nalgebra::SVector;

use super::body::{Body, BodyGeometry};
use super::detect::{detect, ContactKey, Previous, StepContact};
use super::error::ImplicitError;
use super::laws::ContactLaws;
use super::motion;
use super::report::{ContactReport, Halvings, StepFailure, StepReport, StepTooSmall};
use super::settings::{ImplicitSettings, Predictor};
use super::step::{body_dofs, Parts, StepData, Trial};
use crate::broad_phase::CellGrid;
use crate::error::{require_positive, DismechError, Result};
use crate::integrate::ImplicitIntegrator;
use crate::kinematics::{Advance, Kinematics, PlacedEllipse, PlacedPolygon};
use crate::law::TangentLaw;
use crate::linsolve::{BlockAssembly, LinearSolver, SparseMatrix};
use crate::math::{Aabb2, Point, Vec2};
use crate::observe::{Event, Observer, Unobserved};
use crate::query::manifold::dispatch::contact_manifold_2d;
use crate::query::variation::PairContact;
use crate::query::Feature;
use crate::shape::{crossing_depth, Segment};

// Saving the run and resuming it: a child module, which reads the
// driver's fields.
#[path = "checkpoint.rs"]
mod checkpoint;

/// The search distance a step that moved a boundary point by `m` relative
/// to a neighbour leaves to the next step (and a repeated step uses): `m`
/// times this, within the settings' bounds.
const SEARCH_MARGIN: f64 = 1.5;

/// Each contact's history from the last step, `None` for a new one (what
/// a trial's [`StepData`] reads, looked up once a step).
fn histories_of<S: Clone>(
    history: &FxHashMap<ContactKey, S>,
    contacts: &[StepContact],
) -> Vec<Option<S>> {
    contacts
        .iter()
        .map(|c| history.get(&c.key()).cloned())
        .collect()
}

/// A penalty spring tying a material point of a body to its start position
/// (the fixed point of classic DDA).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedPoint {
    /// The body.
    pub body: usize,
    /// Current position of the material point (moves with the body).
    pub point: Point,
    /// Anchor it is tied to.
    pub anchor: Point,
    /// Spring stiffness (N/m per m).
    pub stiffness: f64,
}

/// Implicit dynamics (or quasi-statics) of 2D bodies with penalty
/// contacts, generic over the slots: the bodies' kinematics `K` with `N`
/// unknowns each, a contact law `L` with a consistent tangent, an implicit
/// integrator `I` and a linear solver `S`. Each step detects the contacts
/// (pair queries with first and second variations), then runs an
/// open–close iteration and Newton–Raphson with a line search; a step
/// that fails is halved down to a bound (see the [module documentation](super)).
#[derive(Debug)]
pub struct ImplicitDynamics<const N: usize, K, L: TangentLaw<2>, I, S> {
    bodies: Vec<Body<N>>,
    kinematics: K,
    laws: ContactLaws<L>,
    integrator: I,
    solver: S,
    settings: ImplicitSettings,
    fixed_points: Vec<FixedPoint>,
    time: f64,
    history: FxHashMap<ContactKey, L::State>,
    previous: Previous,
    contacts: Vec<ContactReport<L::State>>,
    grid: CellGrid,
    pairs: Vec<(usize, usize)>,
    motion_grid: CellGrid,
    motion_pairs: Vec<(usize, usize)>,
    assembly: BlockAssembly,
    requested_dt: Option<f64>,
    current_dt: f64,
    /// The search distance of the next step (adapted between
    /// `settings.search_distance` and its largest value).
    search: f64,
    solves: usize,
}

impl<const N: usize, K, L, I, S> ImplicitDynamics<N, K, L, I, S>
where
    K: Kinematics<N> + Advance<PlacedPolygon, N> + Advance<PlacedEllipse, N>,
    L: TangentLaw<2>,
    I: ImplicitIntegrator,
    S: LinearSolver<SparseMatrix>,
{
    /// A model of `bodies` composed from the slots. Refuses invalid
    /// settings and bodies that overlap at the start by more than
    /// `settings.overlap_tolerance`: a vertex or a smooth boundary inside
    /// another body, or two polygons whose edges cross (the error names
    /// both bodies).
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for a setting out of its range
    /// ([`ImplicitSettings::validate`]), or an ellipse near another body at
    /// the start whose aspect ratio is above
    /// [`MAX_ASPECT_RATIO`](crate::shape::MAX_ASPECT_RATIO) (the overlap
    /// check at the start runs the explicit pair queries,
    /// [`BodyGeometry::shape_and_pose`]);
    /// [`ImplicitError::InvalidEdgeTraction`] for an edge traction on an
    /// edge the body does not have, on a body that is not a polygon, or
    /// that is not finite; [`ImplicitError::InvalidBlock`] for a body whose
    /// load (weight and edge tractions) is not finite;
    /// [`ImplicitError::BlocksOverlap`] naming the vertex and both bodies
    /// when a vertex (or a smooth boundary) lies inside another body by
    /// more than `settings.overlap_tolerance`, and
    /// [`ImplicitError::BlocksCross`] when two polygons' edges cross by more
    /// than it.
    pub fn compose(
        bodies: Vec<Body<N>>,
        kinematics: K,
        laws: impl Into<ContactLaws<L>>,
        integrator: I,
        solver: S,
        settings: ImplicitSettings,
    ) -> Result<Self> {
        settings.validate()?;
        for (index, body) in bodies.iter().enumerate() {
            body.validate_edge_tractions(index)?;
            let load = super::step::external_force(&kinematics, body, &settings.gravity);
            if let Some(value) = load.iter().copied().find(|v| !v.is_finite()) {
                return Err(DismechError::Implicit(ImplicitError::InvalidBlock {
                    block: index,
                    name: "load (weight and edge tractions)",
                    value,
                    requirement: "must be finite: lower the density, the gravity or the tractions",
                }));
            }
        }
        let settings_search = settings.search_distance;
        let assembly = BlockAssembly::new(bodies.len(), N, &[])?;
        let mut model = Self {
            bodies,
            kinematics,
            laws: laws.into(),
            integrator,
            solver,
            settings,
            fixed_points: Vec::new(),
            time: 0.0,
            history: FxHashMap::default(),
            previous: Previous::default(),
            contacts: Vec::new(),
            grid: CellGrid::new(),
            pairs: Vec::new(),
            motion_grid: CellGrid::new(),
            motion_pairs: Vec::new(),
            assembly,
            requested_dt: None,
            current_dt: 0.0,
            search: settings_search,
            solves: 0,
        };
        model.find_pairs();
        model.check_initial_overlaps()?;
        Ok(model)
    }

    /// Refuse a start where two bodies overlap by more than the tolerance,
    /// measured by the explicit pair query of their shapes, or where two
    /// polygons' edges cross ([`crossing_depth`]).
    fn check_initial_overlaps(&self) -> Result<()> {
        let tolerance = self.settings.overlap_tolerance;
        let mut manifold = Vec::new();
        for &(i, j) in &self.pairs {
            let (gi, gj) = (self.bodies[i].geometry(), self.bodies[j].geometry());
            if matches!((gi, gj), (BodyGeometry::Wall(_), BodyGeometry::Wall(_))) {
                continue;
            }
            let ((si, pi), (sj, pj)) = (gi.shape_and_pose()?, gj.shape_and_pose()?);
            manifold.clear();
            contact_manifold_2d(&si, &pi, &sj, &pj, &mut manifold)?;
            let Some(deepest) = manifold
                .iter()
                .filter(|g| g.overlap > tolerance)
                .max_by(|a, b| a.overlap.total_cmp(&b.overlap))
            else {
                // Polygons may cross with no vertex inside the other.
                if let (Some(a), Some(b)) = (self.bodies[i].polygon(), self.bodies[j].polygon()) {
                    let world = |p: &PlacedPolygon| -> Vec<Point> {
                        (0..p.vertex_count()).map(|v| p.vertex(v)).collect()
                    };
                    if let Some(depth) = crossing_depth(&world(a), &world(b)) {
                        if depth > tolerance {
                            return Err(DismechError::Implicit(ImplicitError::BlocksCross {
                                a: i,
                                b: j,
                                depth,
                                tolerance,
                            }));
                        }
                    }
                }
                continue;
            };
            // Name the body whose vertex (or whole boundary) penetrates.
            let (vertex_block, vertex, edge_block) = match deepest.features.a {
                Feature::Vertex(v) => (i, v, j),
                _ => match deepest.features.b {
                    Feature::Vertex(v) => (j, v, i),
                    _ => (i, 0, j),
                },
            };
            return Err(DismechError::Implicit(ImplicitError::BlocksOverlap {
                vertex_block,
                vertex,
                edge_block,
                depth: deepest.overlap,
                tolerance,
            }));
        }
        Ok(())
    }

    /// Add a fixed point: the material point `point` of `body` is tied to
    /// its present position by a spring of `stiffness`.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming `fixed-point stiffness`
    /// when `stiffness` is not finite and positive;
    /// [`DismechError::NoSuchBody`] when the model has no body `body`.
    pub fn add_fixed_point(&mut self, body: usize, point: Point, stiffness: f64) -> Result<()> {
        require_positive("fixed-point stiffness", stiffness)?;
        if body >= self.bodies.len() {
            return Err(DismechError::NoSuchBody {
                index: body,
                count: self.bodies.len(),
            });
        }
        self.fixed_points.push(FixedPoint {
            body,
            point,
            anchor: point,
            stiffness,
        });
        Ok(())
    }

    /// The bodies.
    pub fn bodies(&self) -> &[Body<N>] {
        &self.bodies
    }

    /// The blocks (the bodies, by the name DDA gives them).
    pub fn blocks(&self) -> &[Body<N>] {
        &self.bodies
    }

    /// Simulated time (s).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The contact laws.
    pub fn laws(&self) -> &ContactLaws<L> {
        &self.laws
    }

    /// The law of contacts between groups no pair of the table names.
    pub fn law(&self) -> &L {
        self.laws.default_law()
    }

    /// The bodies' kinematics.
    pub fn kinematics(&self) -> &K {
        &self.kinematics
    }

    /// The integrator.
    pub fn integrator(&self) -> &I {
        &self.integrator
    }

    /// The settings.
    pub fn settings(&self) -> &ImplicitSettings {
        &self.settings
    }

    /// Contacts of the last accepted step.
    pub fn contacts(&self) -> &[ContactReport<L::State>] {
        &self.contacts
    }

    /// The linear solver of the Newton iterations (its analyses, fill and
    /// fallbacks).
    pub fn linear_solver(&self) -> &S {
        &self.solver
    }

    /// How many symbolic analyses the linear solver made so far.
    pub fn symbolic_analyses(&self) -> usize {
        self.solver.symbolic_analyses()
    }

    /// Stored entries of the linear solver's last factor.
    pub fn factor_entries(&self) -> Option<usize> {
        self.solver.factor_entries()
    }

    /// The candidate pairs of the next step: boxes within its search
    /// distance.
    fn find_pairs(&mut self) {
        let boxes: Vec<Aabb2> = self.bodies.iter().map(|b| b.geometry().aabb()).collect();
        self.grid
            .candidate_pairs(&boxes, self.search, &mut self.pairs);
    }

    /// The search distance in use (m): `settings.search_distance`, or more
    /// when [`ImplicitSettings::max_search_distance`] lets it follow the
    /// bodies' motion.
    pub fn search_distance(&self) -> f64 {
        self.search
    }

    fn prescribed_mask(&self) -> Vec<bool> {
        let mut mask = vec![false; N * self.bodies.len()];
        for (i, b) in self.bodies.iter().enumerate() {
            if let Some(p) = &b.prescribed {
                mask[N * i..N * i + N].copy_from_slice(&p.mask);
            }
        }
        mask
    }

    /// One trial step of size `dt` from the current state.
    fn trial(
        &mut self,
        dt: f64,
        contacts: &[StepContact],
    ) -> std::result::Result<Trial<L::State>, StepFailure> {
        let nb = self.bodies.len();
        let mask = self.prescribed_mask();
        let mut d = vec![0.0; N * nb];
        for (i, b) in self.bodies.iter().enumerate() {
            if let Some(p) = &b.prescribed {
                let (u0, u1) = ((p.motion)(self.time), (p.motion)(self.time + dt));
                for k in 0..N {
                    if p.mask[k] {
                        d[N * i + k] = u1[k] - u0[k];
                    }
                }
            }
        }
        // The start of the iteration for the free unknowns.
        let mut in_contact = vec![false; nb];
        if self.settings.predictor == Predictor::FreeFlight {
            for &(a, _, b, _) in self.history.keys() {
                in_contact[a] = true;
                in_contact[b] = true;
            }
        }
        for (i, b) in self.bodies.iter().enumerate() {
            let extrapolate = match self.settings.predictor {
                Predictor::FreeFlight => !in_contact[i],
                Predictor::ConstantAcceleration => true,
                Predictor::StartOfStep => false,
            };
            for k in 0..N {
                if !mask[N * i + k] {
                    d[N * i + k] = if extrapolate {
                        dt * b.velocity[k] + 0.5 * dt * dt * b.acceleration[k]
                    } else {
                        0.0
                    };
                }
            }
        }
        let coeffs = self.integrator.coefficients(dt);
        self.update_pattern(contacts, &mask)?;
        let data = StepData {
            bodies: &self.bodies,
            kinematics: &self.kinematics,
            laws: &self.laws,
            contacts,
            histories: histories_of(&self.history, contacts),
            dt,
            slip_regularization: self.settings.slip_regularization,
            slip_reversal_quantile: self.settings.slip_reversal_quantile,
            search: self.search,
        };
        let parts: Parts<N> = data.parts(
            &coeffs,
            &self.settings.gravity,
            self.settings.mass_damping,
            &self.fixed_points,
            mask,
        );
        data.iterate(
            d,
            &parts,
            &mut self.assembly,
            &mut self.solver,
            &self.settings,
            &mut self.solves,
        )
    }

    /// The residual and the tangent's product with `v` at the iterate `d`
    /// of a step of size `dt` from the current state (for tests of the
    /// linearisation).
    #[cfg(test)]
    pub(super) fn residual_and_product(
        &mut self,
        dt: f64,
        d: &[f64],
        v: &[f64],
    ) -> (Vec<f64>, Vec<f64>, Vec<i8>) {
        self.find_pairs();
        let contacts =
            detect(&self.bodies, &self.pairs, self.search, &self.previous).expect("detection");
        let mask = self.prescribed_mask();
        let coeffs = self.integrator.coefficients(dt);
        self.update_pattern(&contacts, &mask).expect("pattern");
        let data = StepData {
            bodies: &self.bodies,
            kinematics: &self.kinematics,
            laws: &self.laws,
            contacts: &contacts,
            histories: histories_of(&self.history, &contacts),
            dt,
            slip_regularization: self.settings.slip_regularization,
            slip_reversal_quantile: self.settings.slip_reversal_quantile,
            search: self.search,
        };
        let parts: Parts<N> = data.parts(
            &coeffs,
            &self.settings.gravity,
            self.settings.mass_damping,
            &self.fixed_points,
            mask,
        );
        let eval = data
            .assemble(d, &parts, &mut self.assembly, true)
            .expect("assembly");
        let mut product = vec![0.0; d.len()];
        self.assembly.matrix().mul_vec(v, &mut product);
        (eval.r, product, eval.regimes)
    }

    /// The block pattern of the tangent for `contacts`: a block for every
    /// pair of bodies in contact, unless all unknowns of one of them are
    /// prescribed (its rows and columns then hold only its diagonal). Kept,
    /// with the solver's analysis, while the pairs are unchanged.
    fn update_pattern(
        &mut self,
        contacts: &[StepContact],
        mask: &[bool],
    ) -> std::result::Result<(), StepFailure> {
        let held = |b: usize| mask[N * b..N * b + N].iter().all(|m| *m);
        let pairs: Vec<(usize, usize)> = contacts
            .iter()
            .map(|c| (c.a, c.b))
            .filter(|&(a, b)| !held(a) && !held(b))
            .collect();
        let pairs = BlockAssembly::normalised(&pairs);
        if !self.assembly.has_layout(self.bodies.len(), N, &pairs) {
            self.assembly =
                BlockAssembly::new(self.bodies.len(), N, &pairs).map_err(StepFailure::Solve)?;
        }
        Ok(())
    }

    /// The body and the largest motion, over the increment `d`, of a
    /// boundary point of a body relative to another body it could reach
    /// ([`motion::relative_motion`]): the pairs are those whose boxes, each
    /// grown by the largest motion of its own boundary, come within the
    /// step's search distance — the pairs near each other at the start and
    /// any pair a fast body may run into within the step.
    fn fastest_point(&mut self, d: &[f64]) -> (usize, f64) {
        let d0 = self.search;
        let own: Vec<f64> = (0..self.bodies.len())
            .map(|i| motion::own_motion(&self.kinematics, &self.bodies[i], &body_dofs::<N>(d, i)))
            .collect();
        let boxes: Vec<Aabb2> = self
            .bodies
            .iter()
            .zip(&own)
            .map(|(b, m)| b.geometry().aabb().inflated(*m))
            .collect();
        let mut pairs = std::mem::take(&mut self.motion_pairs);
        self.motion_grid.candidate_pairs(&boxes, d0, &mut pairs);
        let mut worst = (0, 0.0f64);
        for &(i, j) in &pairs {
            if self.bodies[i].is_fixed() && self.bodies[j].is_fixed() {
                continue;
            }
            for (a, b) in [(i, j), (j, i)] {
                let (da, db) = (body_dofs::<N>(d, a), body_dofs::<N>(d, b));
                let m = motion::relative_motion(
                    &self.kinematics,
                    (&self.bodies[a], &da),
                    (&self.bodies[b], &db),
                    d0,
                    own[b],
                );
                if m > worst.1 {
                    worst = (a, m);
                }
            }
        }
        self.motion_pairs = pairs;
        worst
    }

    /// The geometry of body `i` after its increment `d_i`.
    fn advanced(&self, i: usize, d_i: &SVector<f64, N>) -> Result<BodyGeometry> {
        Ok(match self.bodies[i].geometry() {
            BodyGeometry::Polygon(p) => BodyGeometry::Polygon(self.kinematics.advance(p, d_i, i)?),
            BodyGeometry::Ellipse(e) => BodyGeometry::Ellipse(self.kinematics.advance(e, d_i, i)?),
            BodyGeometry::Wall(s) => {
                let c = self.bodies[i].centroid();
                let map = self.kinematics.committed_map(d_i);
                BodyGeometry::Wall(Segment::new(map.apply(&c, &s.start), map.apply(&c, &s.end)))
            }
        })
    }

    /// Accept a trial: move the bodies, update their stress, velocities and
    /// accelerations (the integrator), keep the contact states.
    fn commit(
        &mut self,
        contacts: &[StepContact],
        trial: &Trial<L::State>,
    ) -> std::result::Result<(), StepFailure> {
        let mut moved = self.bodies.clone();
        for (i, b) in moved.iter_mut().enumerate() {
            let di = body_dofs::<N>(&trial.d, i);
            let geometry = self
                .advanced(i, &di)
                .map_err(|e| StepFailure::Geometry(Box::new(e)))?;
            b.set_geometry(geometry);
            b.stress += b.material().elastic_matrix() * self.kinematics.strain(&di);
            b.displacement += di;
            for k in 0..N {
                let (mut v, mut a) = (b.velocity[k], b.acceleration[k]);
                self.integrator.finish(trial.dt, di[k], &mut v, &mut a);
                b.velocity[k] = v;
                b.acceleration[k] = a;
            }
        }
        for fp in &mut self.fixed_points {
            let di = body_dofs::<N>(&trial.d, fp.body);
            let c = self.bodies[fp.body].centroid();
            fp.point = self.kinematics.committed_map(&di).apply(&c, &fp.point);
        }
        // Contact reports in the accepted configuration; history for the
        // contacts that did not open.
        self.history.clear();
        self.contacts.clear();
        self.previous = Previous::default();
        for (k, c) in contacts.iter().enumerate() {
            let (da, db) = (body_dofs::<N>(&trial.d, c.a), body_dofs::<N>(&trial.d, c.b));
            let (dp_a, dp_b) = (
                self.kinematics.map_parameters(&da),
                self.kinematics.map_parameters(&db),
            );
            let variation = c
                .geometry
                .map_variation(&dp_a, &dp_b)
                .map_err(StepFailure::Variation)?;
            let (t_n, t_s) = trial.forces[k];
            // ∂g/∂t_A: the change of the gap with a translation of A.
            let grad_n = Vec2::new(variation.grad_gap[0], variation.grad_gap[1]);
            let grad_s = Vec2::new(variation.grad_shear[0], variation.grad_shear[1]);
            let material = match &c.geometry {
                PairContact::VertexEdge(v) => v.vertex,
                PairContact::SmoothEdge(s) => s.material,
                PairContact::SmoothSmooth(s) => s.material_a,
            };
            let point = self
                .kinematics
                .committed_map(&da)
                .apply(&self.bodies[c.a].centroid(), &material);
            let key = c.key();
            if trial.regimes[k] != 0 {
                self.history.insert(key, trial.states[k].clone());
                if let (Feature::Vertex(v), Feature::Edge(e)) = (c.features.a, c.features.b) {
                    self.previous.edges.insert((c.a, v, c.b), e);
                }
            }
            if let PairContact::SmoothSmooth(s) = &c.geometry {
                if let Ok(angle) = s.normal_angle(&dp_a, &dp_b) {
                    self.previous.angles.insert(key, angle);
                }
            }
            self.contacts.push(ContactReport {
                bodies: (c.a, c.b),
                features: c.features,
                state: trial.states[k].clone(),
                force: (t_n, t_s),
                force_on_a: grad_n * t_n - grad_s * t_s,
                normal: grad_n.try_normalize(0.0).unwrap_or_else(Vec2::zeros),
                point,
                gap: variation.gap,
                shear: variation.shear,
            });
        }
        self.bodies = moved;
        self.time += trial.dt;
        Ok(())
    }

    /// Total contact force on `body` from the contacts of the last
    /// accepted step (N/m).
    pub fn contact_force_on(&self, body: usize) -> Vec2 {
        self.contacts.iter().fold(Vec2::zeros(), |f, c| {
            if c.bodies.0 == body {
                f + c.force_on_a
            } else if c.bodies.1 == body {
                f - c.force_on_a
            } else {
                f
            }
        })
    }

    /// Advance the model by `dt` (s), in sub-steps if a step has to be
    /// reduced, and report how ([`StepReport`]). A step that cannot be
    /// completed within the reduction bound is an error, as an unstable
    /// step of the explicit driver is: the model is left at the last
    /// accepted state, and the error says what failed and what to change.
    ///
    /// # Errors
    /// [`ImplicitError::StepFailed`] with the time reached, the smallest
    /// sub-step tried, the reason ([`StepFailure`]) and the report of the
    /// call so far, when a sub-step cannot be completed even at the
    /// smallest step; [`DismechError::InvalidParameter`] for a time step that is not
    /// finite and positive; [`ImplicitError::TimeStepTooSmall`] for one
    /// whose smallest sub-step (`dt × min_dt_ratio`) is not a normal
    /// number (the halving would never end), or which does not move the
    /// clock on from the time reached. A step is halved only while its half
    /// still moves the clock.
    pub fn advance(&mut self, dt: f64) -> Result<StepReport> {
        self.advance_observed(dt, &mut Unobserved)
    }

    /// [`Self::advance`] with an [`Observer`]: called with the model after
    /// every accepted sub-step ([`Event::SubStep`]), at every halving with
    /// what failed ([`Event::Halved`]), and once the interval is integrated
    /// ([`Event::Finished`]).
    ///
    /// # Errors
    /// As [`Self::advance`], and any error of the observer, which stops the
    /// call at that event (the model keeps the sub-steps accepted before
    /// it).
    pub fn advance_observed(
        &mut self,
        dt: f64,
        observer: &mut (impl Observer<Self> + ?Sized),
    ) -> Result<StepReport> {
        require_positive("time step dt", dt)?;
        let smallest = dt * self.settings.min_dt_ratio;
        let too_small = |reason: StepTooSmall| {
            DismechError::Implicit(ImplicitError::TimeStepTooSmall {
                dt,
                time: self.time,
                reason,
            })
        };
        if !smallest.is_normal() {
            return Err(too_small(StepTooSmall::SubStepNotNormal { smallest }));
        }
        if self.time + dt == self.time {
            return Err(too_small(StepTooSmall::ClockUnchanged));
        }
        if self.requested_dt != Some(dt) {
            self.requested_dt = Some(dt);
            self.current_dt = dt;
        }
        let end = self.time + dt;
        let mut report = StepReport {
            substeps: 0,
            reductions: 0,
            halvings: Halvings::default(),
            redetections: 0,
            smallest_dt: dt,
            residuals: Vec::new(),
            step_lengths: Vec::new(),
            open_close_iterations: 0,
            iterations: 0,
        };
        let solves = self.solves;
        let (least, most) = (
            self.settings.search_distance,
            self.settings.largest_search_distance(),
        );
        // The search distance that covers a step's motion, within bounds.
        let search_after = |motion: f64| (SEARCH_MARGIN * motion).clamp(least, most);
        while end - self.time > 1e-12 * dt {
            let h = self.current_dt.min(end - self.time);
            let outcome = loop {
                self.find_pairs();
                let outcome = detect(&self.bodies, &self.pairs, self.search, &self.previous)
                    .map_err(StepFailure::Variation)
                    .and_then(|contacts| {
                        let trial = self.trial(h, &contacts)?;
                        let (block, motion) = self.fastest_point(&trial.d);
                        if motion > self.search {
                            return Err(StepFailure::TooFast { block, motion });
                        }
                        self.commit(&contacts, &trial)?;
                        Ok((trial, motion))
                    });
                match outcome {
                    // Detect again at a search distance that covers the
                    // motion, and repeat the step at the same size.
                    Err(StepFailure::TooFast { motion, .. }) if self.search < most => {
                        self.search = search_after(motion);
                        report.redetections += 1;
                    }
                    _ => break outcome,
                }
            };
            match outcome {
                Ok((trial, motion)) => {
                    self.search = search_after(motion);
                    report.substeps += 1;
                    report.smallest_dt = report.smallest_dt.min(h);
                    report.residuals = trial.residuals;
                    report.step_lengths = trial.step_lengths;
                    report.open_close_iterations = trial.open_close;
                    self.current_dt = (2.0 * self.current_dt).min(dt);
                    observer.observe(
                        self,
                        &Event::SubStep {
                            substep: report.substeps,
                            time: self.time,
                            dt: h,
                        },
                    )?;
                }
                Err(reason) => {
                    // Halved down to the smallest sub-step, or to the
                    // smallest that still moves the clock on.
                    if h / 2.0 >= smallest * (1.0 - 1e-12) && self.time + h / 2.0 > self.time {
                        self.current_dt = h / 2.0;
                        report.reductions += 1;
                        report.halvings.count(&reason);
                        observer.observe(
                            self,
                            &Event::Halved {
                                time: self.time,
                                dt: h,
                                reason: &reason,
                            },
                        )?;
                    } else {
                        report.iterations = self.solves - solves;
                        return Err(DismechError::Implicit(ImplicitError::StepFailed {
                            time: self.time,
                            dt: h,
                            reason,
                            report: Box::new(report),
                        }));
                    }
                }
            }
        }
        report.iterations = self.solves - solves;
        observer.observe(
            self,
            &Event::Finished {
                step: report.substeps as u64,
                time: self.time,
            },
        )?;
        Ok(report)
    }
}
