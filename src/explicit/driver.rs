//! The explicit loop: contact forces, accelerations, the integrator.

use rustc_hash::FxHashMap;

use super::checks::{check_initial_overlaps, check_law_for_polygons, finite_bound};
use super::stability::critical_time_step;
use crate::broad_phase::CellGrid;
use crate::error::{require_non_negative, require_positive, DismechError, Result};
use crate::integrate::{ExplicitEuler, ExplicitIntegrator};
use crate::law::{BoundedStiffness, ContactInput, ContactLaw, PairProperties, Regime};
use crate::linsolve::{solve_lumped_into, LumpedSystem};
use crate::math::{Aabb2, Point, Pose2, Vec2};
use crate::query::manifold::dispatch::contact_manifold_2d;
use crate::query::{moment_about, relative_increment, ContactFeatures, ContactGeometry};
use crate::scene::Scene;
use crate::shape::AnyShape2;

/// Settings of a DEM run; validated by [`ExplicitDynamics::new`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DemSettings {
    /// Time step Δt (s).
    pub dt: f64,
    /// Largest overlap (m) accepted between two particles, or a particle and
    /// a wall, at the start.
    pub initial_overlap_tolerance: f64,
    /// Refuse a time step above the estimated stable limit (on by default).
    pub check_stability: bool,
}

impl Default for DemSettings {
    fn default() -> Self {
        Self {
            dt: 1e-4,
            initial_overlap_tolerance: 1e-6,
            check_stability: true,
        }
    }
}

/// When a run counts as at rest.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RestCriterion {
    /// At rest when the kinetic energy is below this fraction of the
    /// potential energy released since the start (when none is released —
    /// no gravity, nothing fell, or bodies rose — of the initial kinetic
    /// energy; a scene with neither is at rest when nothing moves).
    pub kinetic_to_released_ratio: f64,
    /// Do not stop before this simulated time (s).
    pub min_time: f64,
    /// Give up (status [`RunStatus::TimeLimit`]) after this simulated time.
    pub max_time: f64,
    /// Test the criterion every this many steps.
    pub check_every: u64,
    /// The energy test must hold at this many consecutive checks (a single
    /// check can fall on a moment when a bouncing assembly is momentarily
    /// still).
    pub consecutive_checks: u32,
    /// And the mean unbalanced force per particle (contact forces plus
    /// weight) must be below this fraction of the mean weight.
    pub unbalanced_force_ratio: f64,
}

impl Default for RestCriterion {
    fn default() -> Self {
        Self {
            kinetic_to_released_ratio: 1e-6,
            min_time: 0.1,
            max_time: 60.0,
            check_every: 100,
            consecutive_checks: 10,
            unbalanced_force_ratio: 1e-4,
        }
    }
}

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunStatus {
    /// The rest criterion was met.
    AtRest,
    /// The time limit was reached first.
    TimeLimit,
}

/// The outcome of [`ExplicitDynamics::run_to_rest`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunOutcome {
    /// At rest or out of time.
    pub status: RunStatus,
    /// Steps taken in this run.
    pub steps: u64,
    /// Simulated time at the end (s).
    pub time: f64,
    /// Kinetic energy at the end (J/m).
    pub kinetic_energy: f64,
    /// Potential energy released since the start of the simulation (J/m).
    pub released_potential_energy: f64,
    /// Mean unbalanced force per particle / mean weight at the end.
    pub unbalanced_force_ratio: f64,
    /// The kinetic energy over the energy the rest test compares it with
    /// (see [`RestCriterion::kinetic_to_released_ratio`]).
    pub rest_ratio: f64,
    /// The time step over the stable limit estimated at the start for one
    /// contact per particle (`None` for a law without a stiffness bound).
    pub dt_over_stable_estimate: Option<f64>,
    /// The most contact points any particle has at the end.
    pub most_contacts: usize,
}

impl RunOutcome {
    /// The time step over the stable limit of the particle with the most
    /// contacts at the end: the single-contact estimate over `√z`. With
    /// `z` springs of the law's stiffness to identical neighbours, the
    /// largest eigenvalue of `M⁻¹K` for that particle is at most `z` times
    /// the single contact's (Gershgorin), so its stable step is at least
    /// the single-contact one over `√z`; above it the run may neither blow
    /// up nor settle.
    pub fn dt_over_packed_estimate(&self) -> Option<f64> {
        self.dt_over_stable_estimate
            .map(|ratio| ratio * (self.most_contacts.max(1) as f64).sqrt())
    }

    /// What to change when a run did not come to rest, the time step first
    /// when it is above the packed estimate
    /// ([`Self::dt_over_packed_estimate`]). `None` when the run came to
    /// rest.
    pub fn not_at_rest_hint(&self) -> Option<String> {
        if self.status == RunStatus::AtRest {
            return None;
        }
        let dt_hint = match (self.dt_over_stable_estimate, self.dt_over_packed_estimate()) {
            (Some(single), Some(packed)) if packed > 1.0 => format!(
                "the time step is {single:.2} of the single-contact stable estimate, but a \
                 particle with {} contacts is stable only below 1/√{} of it (the time step is \
                 {packed:.2} of that): reduce dt below {:.3} of the estimate; ",
                self.most_contacts,
                self.most_contacts,
                1.0 / (self.most_contacts.max(1) as f64).sqrt()
            ),
            _ => String::new(),
        };
        Some(format!(
            "not at rest at t = {:.3} s (kinetic energy {:.3e} of the rest test's reference, \
             unbalanced force {:.3e} of the weight): {dt_hint}otherwise raise max_time or add damping",
            self.time, self.rest_ratio, self.unbalanced_force_ratio
        ))
    }
}

/// What a contact touches.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ContactTarget {
    /// Another particle.
    Particle(usize),
    /// A wall of the frame.
    Wall(usize),
}

/// One contact of the last step, for output and checks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactRecord {
    /// The particle (A).
    pub particle: usize,
    /// What it touches (B).
    pub target: ContactTarget,
    /// Contact point.
    pub point: Point,
    /// Force exerted by A on B (N/m); B exerts the opposite on A.
    pub force_on_target: Vec2,
    /// Normal from A to B.
    pub normal: Vec2,
    /// Regime of the law.
    pub regime: Regime,
    /// The features of A and B that make the point (several points of one
    /// pair differ by them).
    pub features: ContactFeatures,
}

/// What the contact history is kept by: the particle, what it touches and
/// the features of the contact point.
type HistoryKey = (usize, ContactTarget, ContactFeatures);

/// An explicit DEM simulation: a scene, a contact law and an integrator,
/// plus the workspaces of the loop.
#[derive(Debug)]
pub struct ExplicitDynamics<L: ContactLaw<2>, I: ExplicitIntegrator = ExplicitEuler> {
    scene: Scene,
    law: L,
    integrator: I,
    settings: DemSettings,
    step: u64,
    time: f64,
    initial_potential: f64,
    initial_kinetic: f64,
    /// Largest overlap at the start (m).
    initial_overlap: f64,
    /// The stable time step estimated at the start, when the law bounds
    /// its stiffness.
    stable_estimate: Option<f64>,
    /// Law state and overlap of each contact point at the previous step.
    /// (Keyed by small integers: a fast non-cryptographic hash.)
    history: FxHashMap<HistoryKey, (L::State, f64)>,
    next_history: FxHashMap<HistoryKey, (L::State, f64)>,
    /// The contact points of the pair being evaluated.
    manifold: Vec<ContactGeometry>,
    increments: Vec<(Vec2, f64)>,
    grid: CellGrid,
    boxes: Vec<Aabb2>,
    pairs: Vec<(usize, usize)>,
    system: LumpedSystem,
    acceleration: Vec<f64>,
    contacts: Vec<ContactRecord>,
    /// The box of the walls grown by its own size on every side but the
    /// top (particles may be dropped from high above an open box): a
    /// particle whose centre leaves it has left the frame.
    frame_reach: Aabb2,
}

/// See [`ExplicitDynamics::frame_reach`]. Without walls the reach is the
/// whole plane.
fn frame_reach(scene: &Scene) -> Aabb2 {
    let Some(walls) = scene.frame.bounding_box() else {
        return Aabb2 {
            min: Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
            max: Point::new(f64::INFINITY, f64::INFINITY),
        };
    };
    let size = (walls.max.x - walls.min.x).max(walls.max.y - walls.min.y);
    Aabb2 {
        min: Point::new(walls.min.x - size, walls.min.y - size),
        max: Point::new(walls.max.x + size, f64::INFINITY),
    }
}

impl<L: ContactLaw<2>, I: ExplicitIntegrator> ExplicitDynamics<L, I> {
    /// Set up a run: validates the settings, the initial overlaps and (when
    /// `settings.check_stability`) the time step against the stable limit
    /// estimated from the law's stiffness bound.
    pub fn new(scene: Scene, law: L, integrator: I, settings: DemSettings) -> Result<Self>
    where
        L: BoundedStiffness<2>,
    {
        require_positive("time step dt", settings.dt)?;
        check_law_for_polygons(&scene, &law, settings.dt, |pair| finite_bound(&law, pair))?;
        let limit = critical_time_step(&scene, &law);
        if settings.check_stability && settings.dt > limit.dt {
            return Err(DismechError::UnstableTimeStep {
                dt: settings.dt,
                limit: limit.dt,
                governing: limit.governing,
            });
        }
        let mut sim = Self::build(scene, law, integrator, settings)?;
        sim.stable_estimate = Some(limit.dt).filter(|dt| dt.is_finite() && *dt > 0.0);
        Ok(sim)
    }

    /// Set up a run with a law that has no stiffness bound: the stable-step
    /// check cannot be made, and the caller takes responsibility for
    /// `settings.dt` (the run still stops if the energy blows up).
    /// `settings.check_stability` must be `false`, to say so explicitly.
    pub fn with_unchecked_time_step(
        scene: Scene,
        law: L,
        integrator: I,
        settings: DemSettings,
    ) -> Result<Self> {
        if settings.check_stability {
            return Err(DismechError::InvalidParameter {
                name: "check_stability (the law has no stiffness bound)",
                value: 1.0,
                requirement: "must be false: set it to false to take responsibility for dt",
            });
        }
        check_law_for_polygons(&scene, &law, settings.dt, |_| true)?;
        Self::build(scene, law, integrator, settings)
    }

    fn build(scene: Scene, law: L, integrator: I, settings: DemSettings) -> Result<Self> {
        require_positive("time step dt", settings.dt)?;
        require_non_negative(
            "initial_overlap_tolerance",
            settings.initial_overlap_tolerance,
        )?;
        let n = scene.particles.len();
        let mut mass = Vec::with_capacity(3 * n);
        for p in &scene.particles {
            mass.extend_from_slice(&[p.mass, p.mass, p.inertia]);
        }
        let mut sim = Self {
            law,
            integrator,
            settings,
            step: 0,
            time: 0.0,
            initial_potential: 0.0,
            initial_kinetic: 0.0,
            initial_overlap: 0.0,
            stable_estimate: None,
            history: FxHashMap::default(),
            next_history: FxHashMap::default(),
            manifold: Vec::new(),
            increments: vec![(Vec2::zeros(), 0.0); n],
            grid: CellGrid::new(),
            boxes: Vec::with_capacity(n),
            pairs: Vec::new(),
            system: LumpedSystem {
                force: vec![0.0; 3 * n],
                mass,
            },
            acceleration: vec![0.0; 3 * n],
            contacts: Vec::new(),
            frame_reach: frame_reach(&scene),
            scene,
        };
        sim.initial_overlap = sim.check_initial_overlaps()?;
        sim.initial_potential = sim.potential_energy();
        sim.initial_kinetic = sim.kinetic_energy();
        Ok(sim)
    }

    /// The most contact points of any particle in the last step.
    fn most_contacts(&self) -> usize {
        let mut count = vec![0usize; self.scene.particles.len()];
        for c in &self.contacts {
            count[c.particle] += 1;
            if let ContactTarget::Particle(j) = c.target {
                count[j] += 1;
            }
        }
        count.into_iter().max().unwrap_or(0)
    }

    /// The particles' bounding boxes, into `boxes`.
    fn fill_boxes(&mut self) {
        self.boxes.clear();
        for p in &self.scene.particles {
            self.boxes.push(p.shape.as_shape().aabb(&p.pose));
        }
    }

    fn check_initial_overlaps(&mut self) -> Result<f64> {
        self.fill_boxes();
        check_initial_overlaps(
            &self.scene,
            &mut self.grid,
            &self.boxes,
            self.settings.initial_overlap_tolerance,
            &mut self.manifold,
        )
    }

    /// The scene as it is now.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The contact law.
    pub fn law(&self) -> &L {
        &self.law
    }

    /// Simulated time (s).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.step
    }

    /// The contacts of the last step.
    pub fn contacts(&self) -> &[ContactRecord] {
        &self.contacts
    }

    /// Total kinetic energy (J/m).
    pub fn kinetic_energy(&self) -> f64 {
        self.scene
            .particles
            .iter()
            .map(|p| p.kinetic_energy())
            .sum()
    }

    /// Potential energy of gravity and the constant external forces,
    /// `−Σ (m g + f_ext)·x` (J/m).
    pub fn potential_energy(&self) -> f64 {
        let g = self.scene.gravity;
        self.scene
            .particles
            .iter()
            .map(|p| -(p.mass * g + p.external_force).dot(&p.pose.position.coords))
            .sum()
    }

    /// Sum of the forces the particles exert on wall `wall` in the last step
    /// (N/m); the wall's reaction on the particles is its negative.
    pub fn wall_load(&self, wall: usize) -> Vec2 {
        self.contacts
            .iter()
            .filter(|c| c.target == ContactTarget::Wall(wall))
            .map(|c| c.force_on_target)
            .sum()
    }

    /// Mean over particles of the unbalanced force `|Σ f|` (contacts plus
    /// gravity, from the last step), divided by the mean weight.
    pub fn unbalanced_force_ratio(&self) -> f64 {
        let n = self.scene.particles.len();
        if n == 0 {
            return 0.0;
        }
        let net: f64 = (0..n)
            .map(|i| Vec2::new(self.system.force[3 * i], self.system.force[3 * i + 1]).norm())
            .sum();
        let weight = self.scene.total_weight();
        if weight > 0.0 {
            net / weight
        } else {
            net
        }
    }

    fn update_pairs(&mut self) {
        self.fill_boxes();
        self.grid.candidate_pairs(&self.boxes, 0.0, &mut self.pairs);
    }

    /// Evaluate one contact, accumulate its forces into the force vector and
    /// record it.
    fn apply_contact(
        &mut self,
        a: usize,
        target: ContactTarget,
        geometry: &ContactGeometry,
        centre_b: Point,
        increment_b: (Vec2, f64),
        mass_b: f64,
    ) {
        let pa = &self.scene.particles[a];
        let increment_a = self.increments[a];
        let mut du = relative_increment(
            geometry,
            &pa.pose.position,
            (&increment_a.0, increment_a.1),
            &centre_b,
            (&increment_b.0, increment_b.1),
        );
        let key = (a, target, geometry.features);
        let previous = self.history.get(&key);
        // The normal increment is the change of the overlap itself: exact
        // for any shape. (The relative velocity at the chord midpoint misses
        // the motion of the deepest point when a non-circular body rolls,
        // and an incremental spring fed with it gains energy.)
        if let Some((_, previous_overlap)) = previous {
            du[0] = geometry.overlap - previous_overlap;
        }
        let input = ContactInput {
            overlap: geometry.overlap,
            increment: du.into(),
            dt: self.settings.dt,
            is_new: previous.is_none(),
            pair: PairProperties {
                curvature_radius_a: geometry.curvature_radius_a,
                curvature_radius_b: geometry.curvature_radius_b,
                width: geometry.width,
                mass_a: pa.mass,
                mass_b,
            },
        };
        let default_state = L::State::default();
        let response = self
            .law
            .evaluate(&input, previous.map_or(&default_state, |(state, _)| state));
        let force_on_b =
            geometry.normal * response.force[0] - geometry.tangent() * response.force[1];
        let moment_a = moment_about(&pa.pose.position, &geometry.point, &(-force_on_b));
        self.system.force[3 * a] -= force_on_b.x;
        self.system.force[3 * a + 1] -= force_on_b.y;
        self.system.force[3 * a + 2] += moment_a;
        if let ContactTarget::Particle(b) = target {
            let moment_b = moment_about(&centre_b, &geometry.point, &force_on_b);
            self.system.force[3 * b] += force_on_b.x;
            self.system.force[3 * b + 1] += force_on_b.y;
            self.system.force[3 * b + 2] += moment_b;
        }
        self.next_history
            .insert(key, (response.state, geometry.overlap));
        self.contacts.push(ContactRecord {
            particle: a,
            target,
            point: geometry.point,
            force_on_target: force_on_b,
            normal: geometry.normal,
            regime: response.regime,
            features: geometry.features,
        });
    }

    /// Advance one step.
    pub fn step(&mut self) -> Result<()> {
        let n = self.scene.particles.len();
        let g = self.scene.gravity;
        for (i, p) in self.scene.particles.iter().enumerate() {
            self.system.force[3 * i] = p.mass * g.x + p.external_force.x;
            self.system.force[3 * i + 1] = p.mass * g.y + p.external_force.y;
            self.system.force[3 * i + 2] = 0.0;
        }
        self.contacts.clear();
        self.next_history.clear();

        // Particle pairs from the broad phase; each contact point of a pair
        // in the order the manifold gives them.
        self.update_pairs();
        let mut manifold = std::mem::take(&mut self.manifold);
        for k in 0..self.pairs.len() {
            let (a, b) = self.pairs[k];
            let (pa, pb) = (&self.scene.particles[a], &self.scene.particles[b]);
            manifold.clear();
            contact_manifold_2d(&pa.shape, &pa.pose, &pb.shape, &pb.pose, &mut manifold)?;
            let (centre_b, mass_b) = (pb.pose.position, pb.mass);
            for geometry in &manifold {
                self.apply_contact(
                    a,
                    ContactTarget::Particle(b),
                    geometry,
                    centre_b,
                    self.increments[b],
                    mass_b,
                );
            }
        }
        // Walls: few, tested against each particle's box.
        for a in 0..n {
            for w in 0..self.scene.frame.walls().len() {
                let wall = self.scene.frame.walls()[w];
                let wall_box = Aabb2::from_corners(wall.start, wall.end);
                if !wall_box.intersects(&self.boxes[a]) {
                    continue;
                }
                let pa = &self.scene.particles[a];
                let shape = AnyShape2::Segment(wall);
                manifold.clear();
                contact_manifold_2d(
                    &pa.shape,
                    &pa.pose,
                    &shape,
                    &Pose2::default(),
                    &mut manifold,
                )?;
                for geometry in &manifold {
                    self.apply_contact(
                        a,
                        ContactTarget::Wall(w),
                        geometry,
                        geometry.point,
                        (Vec2::zeros(), 0.0),
                        f64::INFINITY,
                    );
                }
            }
        }
        self.manifold = manifold;
        std::mem::swap(&mut self.history, &mut self.next_history);

        for (i, f) in self.system.force.iter().enumerate() {
            if !f.is_finite() {
                return Err(self.non_finite(i / 3, "force"));
            }
        }
        solve_lumped_into(&self.system, &mut self.acceleration)?;
        let dt = self.settings.dt;
        for i in 0..n {
            let p = &mut self.scene.particles[i];
            let mut dx = [0.0; 3];
            let mut velocity = [p.velocity.x, p.velocity.y, p.angular_velocity];
            for d in 0..3 {
                dx[d] = self
                    .integrator
                    .step(dt, self.acceleration[3 * i + d], &mut velocity[d]);
            }
            p.velocity = Vec2::new(velocity[0], velocity[1]);
            p.angular_velocity = velocity[2];
            p.pose.position += Vec2::new(dx[0], dx[1]);
            p.pose.angle += dx[2];
            self.increments[i] = (Vec2::new(dx[0], dx[1]), dx[2]);
            if !(dx.iter().all(|v| v.is_finite()) && velocity.iter().all(|v| v.is_finite())) {
                return Err(self.non_finite(i, "position or velocity"));
            }
            if !self.frame_reach.contains(&p.pose.position) {
                // Flung out by an unstable step rather than pushed out by
                // its loads: say so.
                if let Some(blow_up) = self.energy_blow_up() {
                    return Err(blow_up);
                }
                let p = &self.scene.particles[i];
                return Err(DismechError::ParticleLeftFrame {
                    step: self.step,
                    time: self.time,
                    body: i,
                    x: p.pose.position.x,
                    y: p.pose.position.y,
                });
            }
        }
        self.step += 1;
        self.time += dt;
        Ok(())
    }

    /// [`DismechError::EnergyBlowUp`] when the kinetic energy exceeds
    /// twice what gravity, the external forces and the initial motion can
    /// supply (the sign of an unstable step).
    fn energy_blow_up(&self) -> Option<DismechError> {
        self.blow_up_at(
            self.kinetic_energy(),
            self.initial_potential - self.potential_energy(),
        )
    }

    /// [`Self::energy_blow_up`] for the kinetic energy and the released
    /// potential energy at hand.
    fn blow_up_at(&self, kinetic: f64, released: f64) -> Option<DismechError> {
        let available = released.max(0.0) + self.initial_kinetic;
        (kinetic > 2.0 * available + 1e-12 * self.scene.total_weight().max(1.0)).then_some(
            DismechError::EnergyBlowUp {
                step: self.step,
                kinetic,
                available,
                initial_overlap: self.initial_overlap,
            },
        )
    }

    /// The kinetic energy against the potential energy released; with
    /// none released (no gravity, nothing fell, or bodies rose), against
    /// the initial kinetic energy; with neither, 0 when nothing moves and
    /// infinite otherwise.
    fn rest_ratio(&self, kinetic: f64, released: f64) -> f64 {
        if released > 0.0 {
            kinetic / released
        } else if self.initial_kinetic > 0.0 {
            kinetic / self.initial_kinetic
        } else if kinetic == 0.0 {
            0.0
        } else {
            f64::INFINITY
        }
    }

    fn non_finite(&self, body: usize, quantity: &'static str) -> DismechError {
        DismechError::NonFinite {
            step: self.step,
            time: self.time,
            body,
            quantity,
        }
    }

    /// Run until the rest criterion holds or the time limit is reached.
    ///
    /// Stops with [`DismechError::EnergyBlowUp`] if the kinetic energy
    /// exceeds what gravity and the initial motion can supply (the sign of
    /// an unstable step). `on_check` is called at every check with the
    /// current time and the ratio the rest test reads (kinetic to released
    /// energy, see [`RestCriterion::kinetic_to_released_ratio`]; for
    /// progress reporting).
    pub fn run_to_rest(
        &mut self,
        criterion: &RestCriterion,
        mut on_check: impl FnMut(f64, f64),
    ) -> Result<RunOutcome> {
        require_positive("rest ratio", criterion.kinetic_to_released_ratio)?;
        require_positive("max_time", criterion.max_time)?;
        require_non_negative("min_time", criterion.min_time)?;
        require_non_negative("unbalanced_force_ratio", criterion.unbalanced_force_ratio)?;
        let every = criterion.check_every.max(1);
        let start = self.step;
        let mut calm_checks = 0u32;
        loop {
            self.step()?;
            if (self.step - start) % every != 0 {
                continue;
            }
            let kinetic = self.kinetic_energy();
            let released = self.initial_potential - self.potential_energy();
            if let Some(blow_up) = self.blow_up_at(kinetic, released) {
                return Err(blow_up);
            }
            let ratio = self.rest_ratio(kinetic, released);
            on_check(self.time, ratio);
            let unbalanced = self.unbalanced_force_ratio();
            if ratio < criterion.kinetic_to_released_ratio
                && unbalanced < criterion.unbalanced_force_ratio
            {
                calm_checks += 1;
            } else {
                calm_checks = 0;
            }
            let status = if self.time >= criterion.min_time
                && calm_checks >= criterion.consecutive_checks.max(1)
            {
                Some(RunStatus::AtRest)
            } else if self.time >= criterion.max_time {
                Some(RunStatus::TimeLimit)
            } else {
                None
            };
            if let Some(status) = status {
                return Ok(RunOutcome {
                    status,
                    steps: self.step - start,
                    time: self.time,
                    kinetic_energy: kinetic,
                    released_potential_energy: released,
                    unbalanced_force_ratio: unbalanced,
                    rest_ratio: ratio,
                    dt_over_stable_estimate: self.stable_estimate.map(|l| self.settings.dt / l),
                    most_contacts: self.most_contacts(),
                });
            }
        }
    }
}
