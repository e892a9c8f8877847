//! The explicit loop: contact forces, accelerations, the integrator.

use std::sync::OnceLock;

use rayon::prelude::*;

use super::checks::{
    check_initial_overlaps, check_law_for_polygons, check_neighbour_budget, check_particles,
    finite_bound, smallest_bounding_radius,
};
use super::error::ExplicitError;
use super::keys::pack_limits;
use super::motion::{BlockMotion, StepCheck};
use super::neighbours::{NeighbourList, PairSlot, BLOCK};
use super::pair_bodies::PairBody;
use super::pair_forces::PairContext;
use super::phases::{PhaseClock, PhaseTimes};
use super::skin::Skin;
use super::stability::{
    critical_time_step_at, OverlapReached, StabilityLimit, DEFAULT_STABILITY_OVERLAP,
};
use super::{MemoryAdvice, MemoryUse};
use crate::broad_phase::CellGrid;
use crate::error::{require_non_negative, require_positive, DismechError, Result};
use crate::integrate::{ExplicitEuler, ExplicitIntegrator};
use crate::law::{BoundedStiffness, ContactLaw, Regime};
use crate::linsolve::{solve_lumped_into, LumpedSystem};
use crate::math::{Aabb2, Point, Vec2};
use crate::observe::{Event, Observer};
use crate::query::{ContactFeatures, ContactGeometry, ContactShape};
use crate::scene::{Particle, Scene};
use crate::shape::AnyShape2;
use nalgebra::UnitComplex;

// Saving the run and resuming it: a child module, which reads the
// driver's fields.
#[path = "checkpoint.rs"]
mod checkpoint;

/// One block's share of a step's motion: its index, its particles'
/// forces (three entries each), the particles, their pair records and their
/// rotations (none in a scene without ellipses).
type BlockMove<'a> = (
    usize,
    (
        ((&'a mut [f64], &'a mut [Particle]), &'a mut [PairBody]),
        &'a mut [UnitComplex<f64>],
    ),
);

/// From this many particles on, the contact and update loops run on
/// rayon's threads (when it has more than one); below it the fork costs
/// more than it saves. The results do not depend on it.
const PARALLEL_MIN_PARTICLES: usize = 2000;

/// Settings of a DEM run; validated by [`ExplicitDynamics::new`] (and by
/// [`ExplicitDynamics::restore`], which reads them from a checkpoint).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct DemSettings {
    /// Time step Δt (s).
    pub dt: f64,
    /// Largest overlap (m) accepted between two particles, or a particle and
    /// a wall, at the start.
    pub initial_overlap_tolerance: f64,
    /// The overlaps, as a share of a particle's bounding radius, up to which
    /// the stable step is estimated ([`crate::law::BoundedStiffness`]:
    /// a law whose stiffness grows with the overlap is bounded there), in
    /// `(0, 1]`; [`ExplicitDynamics::check_overlap_stability`] (run at every
    /// check of [`ExplicitDynamics::run_to_rest`]) stops a run whose
    /// overlaps outgrow it at a time step the law no longer allows.
    /// [`DEFAULT_STABILITY_OVERLAP`] by default.
    pub stability_overlap: f64,
    /// Refuse a time step above the estimated stable limit (on by default).
    pub check_stability: bool,
    /// Skin of the neighbour list (m): pairs whose bounding boxes and
    /// bounding circles are both closer than this are listed (and the
    /// walls whose boxes are closer than this to a particle's), and the
    /// list is built again once a particle's box may have moved half of it
    /// (`|Δx| + |Δy| + R |Δφ|` since the build, `R` the bounding radius,
    /// 0 for a circle, whose box a turn does not move); see also
    /// [`Self::relative_travel`].
    /// It changes the speed, not the forces (the list holds every pair
    /// that can touch). A larger skin builds less often and lists more
    /// pairs that do not touch (a skin as large as the scene lists every
    /// pair: n² of them). `Some(s)` keeps `s` at every build; 0 builds the
    /// list at every step that moves a particle (with
    /// [`Self::relative_travel`], every step at which two particles move
    /// relative to each other). `None` (the default) starts from 0.15 of
    /// the smallest particle's bounding radius and tunes it at each build
    /// after the first, up to four times that, aiming at a build every 20
    /// steps (more often at that ceiling): the skin is
    /// multiplied by `√(20 / k)`, `k` the steps since the last build, so
    /// particles that move fast (a collapsing column, a flow) get a wider
    /// skin and fewer builds, and a settled packing keeps the least one
    /// ([`ExplicitDynamics::neighbour_skin`] gives the skin of the last
    /// build).
    pub neighbour_skin: Option<f64>,
    /// Keep the neighbour list past a particle's travel of half the skin
    /// while no two particles may have come closer by the skin, nor a
    /// particle reached a wall not listed with it: what counts is then how
    /// the particles moved relative to each other, so a packing that moves
    /// as a whole (falling, sliding) keeps its list. The bound is taken
    /// per block of 1024 particles of consecutive indices, from each
    /// particle's displacement relative to its block's; it costs a pass
    /// over the particles at each step past the half skin, about a tenth
    /// of a step, so it pays where the list would otherwise be built
    /// every 15 steps or so or more often, and slows a packing whose
    /// particles rearrange among their neighbours (off by default). The
    /// forces are the same either way.
    pub relative_travel: bool,
}

impl Default for DemSettings {
    fn default() -> Self {
        Self {
            dt: 1e-4,
            initial_overlap_tolerance: 1e-6,
            stability_overlap: DEFAULT_STABILITY_OVERLAP,
            check_stability: true,
            neighbour_skin: None,
            relative_travel: false,
        }
    }
}

impl DemSettings {
    /// The skin for `scene`: the setting, fixed, or tuned from 0.15 of
    /// the smallest bounding radius (for a scene without particles, which
    /// has no pairs, a huge finite one).
    fn skin_for(&self, scene: &Scene) -> Result<Skin> {
        match self.neighbour_skin {
            Some(skin) => require_non_negative("neighbour_skin", skin).map(Skin::fixed),
            None => Ok(Skin::tuned(
                0.15 * smallest_bounding_radius(scene).min(f64::MAX),
            )),
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
    /// Give up (status [`RunStatus::StepLimit`]) after this many steps of
    /// the run, whatever the simulated time reached: a run at a tiny time
    /// step ends (10⁸ by default).
    pub max_steps: u64,
    /// Give up (status [`RunStatus::WallTimeLimit`]) once the run has
    /// taken this much wall-clock time, tested at each check (none by
    /// default).
    pub max_wall_time: Option<std::time::Duration>,
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
            max_steps: 100_000_000,
            max_wall_time: None,
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
    /// [`RestCriterion::max_steps`] steps were taken first.
    StepLimit,
    /// [`RestCriterion::max_wall_time`] ran out first.
    WallTimeLimit,
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
    /// The overlap at the point (m).
    pub overlap: f64,
    /// The law's rolling moment on the particle (N·m per m,
    /// counter-clockwise; the target receives the opposite), 0 for a law
    /// without rolling resistance ([`crate::law::ContactLaw::moment`]).
    pub rolling_moment: f64,
}

/// The stable step of a scene under a law at an overlap ratio.
type StabilityAt<L> = fn(&Scene, &L, f64) -> StabilityLimit;

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
    /// The prescribed particles (infinite mass), and the work they have
    /// done on the free ones so far (J/m): energy the run is supplied
    /// with besides gravity and the initial motion.
    prescribed: Vec<usize>,
    prescribed_work: f64,
    /// Largest overlap at the start (m).
    initial_overlap: f64,
    /// The stable time step estimated at the start, when the law bounds
    /// its stiffness.
    stable_estimate: Option<f64>,
    /// The stable step at an overlap ratio, when the law bounds its
    /// stiffness ([`critical_time_step_at`] for this law).
    stability_at: Option<StabilityAt<L>>,
    /// The listed pairs with their contact points' history and last
    /// results.
    neighbours: NeighbourList<L::State>,
    /// The contact points of the pair being evaluated.
    manifold: Vec<ContactGeometry>,
    /// What the pairs read of each particle: [`PairBody`].
    bodies: Vec<PairBody>,
    /// Each ellipse's rotation, `UnitComplex::new(angle)`, kept with its
    /// pose so that its contacts do not take the sine and cosine per pair
    /// (other particles' entries are not used); empty when the scene has
    /// no ellipse.
    rotations: Vec<UnitComplex<f64>>,
    grid: CellGrid,
    system: LumpedSystem,
    /// Each particle's weight and external force, `m g + f_ext` (N/m).
    applied: Vec<Vec2>,
    /// The last step's contacts as records, made when first asked for.
    records: OnceLock<Vec<ContactRecord>>,
    /// The box of the walls grown by its own size on every side but the
    /// top (particles may be dropped from high above an open box): a
    /// particle whose centre leaves it has left the frame.
    frame_reach: Aabb2,
    /// The steps' time by phase, when asked for ([`Self::time_phases`]).
    phase_times: Option<PhaseTimes>,
}

/// Refuse a scene of `n` particles whose run the system cannot hold: the
/// driver's memory (per particle: its pair-query data, forces, masses,
/// loads, rotation and a few listed pairs) is asked of the allocator
/// before any of it is taken, and given back, so that a scene too large
/// for the machine is a typed error rather than an abort.
fn check_memory<S>(n: usize) -> Result<()> {
    let per_particle = std::mem::size_of::<PairBody>()
        + 6 * std::mem::size_of::<f64>()
        + 2 * std::mem::size_of::<Vec2>()
        + 4 * std::mem::size_of::<PairSlot<S>>();
    let bytes = (n as u128) * per_particle as u128;
    let refused = |advice: MemoryAdvice| {
        DismechError::Explicit(ExplicitError::OutOfMemory {
            what: MemoryUse::Dem { particles: n },
            bytes,
            advice,
        })
    };
    let len = usize::try_from(bytes).map_err(|_| refused(MemoryAdvice::AddressSpace))?;
    let mut probe: Vec<u8> = Vec::new();
    probe
        .try_reserve_exact(len)
        .map_err(|_| refused(MemoryAdvice::SystemRefused))?;
    Ok(())
}

/// Refuse a time step below the smallest normal double (a subnormal step
/// loses its digits when added to the clock, and the clock stalls).
fn require_normal_time_step(dt: f64) -> Result<()> {
    if dt.is_normal() {
        Ok(())
    } else {
        Err(DismechError::InvalidParameter {
            name: "time step dt",
            value: dt,
            requirement: "must be a normal number (at least 2.2e-308 s; a subnormal step does not move the clock)",
        })
    }
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
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for a time step `settings.dt` that
    /// is not finite and positive, or not a normal number;
    /// [`ExplicitError::LawUndefinedForShape`] for a scene with a polygon
    /// where the law (or its stiffness bound) gives no finite value at a
    /// vertex-on-edge contact; [`ExplicitError::UnstableTimeStep`] when
    /// `settings.check_stability` is set and `settings.dt` exceeds the
    /// estimated stable limit;
    /// [`ExplicitError::InvalidParticle`] for a particle whose pose,
    /// velocity or external force is not finite, or whose mass or moment of
    /// inertia is not finite and positive (both `+∞`, a prescribed
    /// particle, is accepted); [`DismechError::InvalidParameter`] for a
    /// negative or non-finite `initial_overlap_tolerance` or
    /// `neighbour_skin`, or a scene with 2³¹ particles or walls or more, or
    /// a polygon of 2²⁹ vertices or more; [`ExplicitError::OutOfMemory`] for
    /// a fixed `neighbour_skin` that would list more pairs than the budget
    /// ([`MAX_LISTED_PAIRS_PER_PARTICLE`](crate::explicit::MAX_LISTED_PAIRS_PER_PARTICLE)
    /// per particle), or a scene whose run the allocator refuses;
    /// [`ExplicitError::InitialOverlap`] for two particles (not both
    /// prescribed) that overlap, and [`ExplicitError::StartsInsideWall`] for
    /// a free particle that penetrates a wall, by more than
    /// `initial_overlap_tolerance`.
    pub fn new(scene: Scene, law: L, integrator: I, settings: DemSettings) -> Result<Self>
    where
        L: BoundedStiffness<2>,
    {
        require_positive("time step dt", settings.dt)?;
        check_law_for_polygons(&scene, &law, settings.dt, |pair, overlap| {
            finite_bound(&law, pair, overlap)
        })?;
        let overlap = settings.stability_overlap;
        if !(overlap.is_finite() && overlap > 0.0 && overlap <= 1.0) {
            return Err(DismechError::InvalidParameter {
                name: "stability_overlap",
                value: overlap,
                requirement: "must lie in (0, 1] (a share of a particle's bounding radius)",
            });
        }
        let limit = critical_time_step_at(&scene, &law, overlap);
        if settings.check_stability && settings.dt > limit.dt {
            return Err(DismechError::Explicit(ExplicitError::UnstableTimeStep {
                dt: settings.dt,
                limit: limit.dt,
                governing: limit.governing,
                overlap: None,
            }));
        }
        let mut sim = Self::build(scene, law, integrator, settings)?;
        sim.stable_estimate = Some(limit.dt).filter(|dt| dt.is_finite() && *dt > 0.0);
        sim.bounded_stiffness();
        Ok(sim)
    }

    /// Set up a run with a law that has no stiffness bound: the stable-step
    /// check cannot be made, and the caller takes responsibility for
    /// `settings.dt` (the run still stops if the energy blows up).
    /// `settings.check_stability` must be `false`, to say so explicitly.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] when `settings.check_stability`
    /// is `true`, or for a time step `settings.dt` that is not finite and
    /// positive, or not a normal number;
    /// [`ExplicitError::LawUndefinedForShape`] for a scene with a polygon
    /// where the law gives no finite force at a vertex-on-edge contact;
    /// [`ExplicitError::InvalidParticle`] for a particle whose pose,
    /// velocity or external force is not finite, or whose mass or moment of
    /// inertia is not finite and positive (both `+∞`, a prescribed
    /// particle, is accepted); [`DismechError::InvalidParameter`] for a
    /// negative or non-finite `initial_overlap_tolerance` or
    /// `neighbour_skin`, or a scene with 2³¹ particles or walls or more, or
    /// a polygon of 2²⁹ vertices or more; [`ExplicitError::OutOfMemory`] for
    /// a fixed `neighbour_skin` that would list more pairs than the budget
    /// ([`MAX_LISTED_PAIRS_PER_PARTICLE`](crate::explicit::MAX_LISTED_PAIRS_PER_PARTICLE)
    /// per particle), or a scene whose run the allocator refuses;
    /// [`ExplicitError::InitialOverlap`] for two particles (not both
    /// prescribed) that overlap, and [`ExplicitError::StartsInsideWall`] for
    /// a free particle that penetrates a wall, by more than
    /// `initial_overlap_tolerance`.
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
        check_law_for_polygons(&scene, &law, settings.dt, |_, _| true)?;
        Self::build(scene, law, integrator, settings)
    }

    fn build(scene: Scene, law: L, integrator: I, settings: DemSettings) -> Result<Self> {
        let mut sim = Self::assemble(scene, law, integrator, settings)?;
        sim.initial_overlap = sim.check_initial_overlaps()?;
        sim.initial_potential = sim.potential_energy();
        sim.initial_kinetic = sim.kinetic_energy();
        Ok(sim)
    }

    /// The driver of a scene, its settings and the scene checked (all but
    /// the overlaps), before any step: the start of [`Self::build`], and
    /// of a restore from a checkpoint, which then puts the run's state in.
    /// Let the run check its stable step at the overlaps it reaches
    /// ([`Self::check_overlap_stability`]): the law bounds its stiffness.
    pub(super) fn bounded_stiffness(&mut self)
    where
        L: BoundedStiffness<2>,
    {
        self.stability_at = Some(critical_time_step_at::<L>);
    }

    fn assemble(scene: Scene, law: L, integrator: I, settings: DemSettings) -> Result<Self> {
        require_positive("time step dt", settings.dt)?;
        require_normal_time_step(settings.dt)?;
        check_particles(&scene)?;
        require_non_negative(
            "initial_overlap_tolerance",
            settings.initial_overlap_tolerance,
        )?;
        pack_limits(&scene)?;
        let n = scene.particles.len();
        let skin = settings.skin_for(&scene)?;
        let mut grid = CellGrid::new();
        if let Some(fixed) = settings.neighbour_skin {
            check_neighbour_budget(
                &scene,
                &mut grid,
                fixed,
                std::mem::size_of::<PairSlot<L::State>>(),
            )?;
        }
        check_memory::<L::State>(n)?;
        let mut mass = Vec::with_capacity(3 * n);
        for p in &scene.particles {
            mass.extend_from_slice(&[p.mass, p.mass, p.inertia]);
        }
        let sim = Self {
            law,
            integrator,
            settings,
            step: 0,
            time: 0.0,
            initial_potential: 0.0,
            initial_kinetic: 0.0,
            prescribed: (scene.particles.iter().enumerate())
                .filter(|(_, p)| p.is_prescribed())
                .map(|(i, _)| i)
                .collect(),
            prescribed_work: 0.0,
            initial_overlap: 0.0,
            stable_estimate: None,
            stability_at: None,
            neighbours: NeighbourList::new(skin, settings.relative_travel, &scene.particles),
            manifold: Vec::new(),
            bodies: scene.particles.iter().map(PairBody::of).collect(),
            rotations: if scene
                .particles
                .iter()
                .any(|p| matches!(p.shape, AnyShape2::Ellipse(_)))
            {
                scene
                    .particles
                    .iter()
                    .map(|p| UnitComplex::new(p.pose.angle))
                    .collect()
            } else {
                Vec::new()
            },
            grid,
            system: LumpedSystem {
                force: vec![0.0; 3 * n],
                mass,
            },
            records: OnceLock::new(),
            phase_times: None,
            applied: scene
                .particles
                .iter()
                .map(|p| {
                    if p.is_prescribed() {
                        // Nothing moves a prescribed particle.
                        Vec2::zeros()
                    } else {
                        Vec2::new(
                            p.mass * scene.gravity.x + p.external_force.x,
                            p.mass * scene.gravity.y + p.external_force.y,
                        )
                    }
                })
                .collect(),
            frame_reach: frame_reach(&scene),
            scene,
        };
        // The masses, checked once (the loop divides by them).
        solve_lumped_into(&sim.system, &mut Vec::new())?;
        Ok(sim)
    }

    /// The most contact points of any free particle in the last step.
    fn most_contacts(&self) -> usize {
        let mut count = vec![0usize; self.scene.particles.len()];
        for slot in &self.neighbours.slots {
            count[slot.a()] += slot.points.len();
            if let ContactTarget::Particle(j) = slot.target() {
                count[j] += slot.points.len();
            }
        }
        // A prescribed particle's contacts do not set a free one's modes.
        for &i in &self.prescribed {
            count[i] = 0;
        }
        count.into_iter().max().unwrap_or(0)
    }

    fn check_initial_overlaps(&mut self) -> Result<f64> {
        let boxes: Vec<Aabb2> = self
            .scene
            .particles
            .iter()
            .map(|p| p.shape.as_shape().aabb(&p.pose))
            .collect();
        check_initial_overlaps(
            &self.scene,
            &mut self.grid,
            &boxes,
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

    /// The contacts of the last step: particle pairs by (A, B), then walls
    /// by (particle, wall), each pair's points in the manifold's order.
    /// Made from the neighbour list when first asked for after a step (a
    /// run that never asks makes none).
    pub fn contacts(&self) -> &[ContactRecord] {
        self.records.get_or_init(|| {
            self.neighbours
                .slots
                .iter()
                .flat_map(|slot| {
                    slot.points.iter().map(move |p| ContactRecord {
                        particle: slot.a(),
                        target: slot.target(),
                        point: p.point,
                        force_on_target: p.force_on_b,
                        normal: p.normal,
                        regime: p.key.regime(),
                        features: p.key.features(),
                        overlap: p.overlap,
                        rolling_moment: self.law.moment(&p.state),
                    })
                })
                .collect()
        })
    }

    /// The largest overlap of the last step's contacts as a share of the
    /// smaller bounding radius of the pair (the particle's against a wall),
    /// with the particle (A) and what it touches; `None` without contacts.
    pub fn largest_overlap_ratio(&self) -> Option<(f64, usize, ContactTarget)> {
        let radius = |i: usize| self.scene.particles[i].shape.as_shape().bounding_radius();
        let mut largest: Option<(f64, usize, ContactTarget)> = None;
        for slot in &self.neighbours.slots {
            let r = match slot.target() {
                ContactTarget::Particle(b) => radius(slot.a()).min(radius(b)),
                ContactTarget::Wall(_) => radius(slot.a()),
            };
            for p in &slot.points {
                let ratio = p.overlap / r;
                if largest.is_none_or(|(l, _, _)| ratio > l) {
                    largest = Some((ratio, slot.a(), slot.target()));
                }
            }
        }
        largest
    }

    /// Check that the time step is still stable at the overlaps the run has
    /// reached: where the largest overlap ratio
    /// ([`Self::largest_overlap_ratio`]) exceeds
    /// [`DemSettings::stability_overlap`], the stable step is estimated
    /// again at that ratio. A law whose stiffness does not grow with the
    /// overlap always passes; so does a run whose stability check is off
    /// (or whose law has no stiffness bound). [`Self::run_to_rest`] runs it
    /// at every check; a caller of [`Self::step`] runs it when it likes.
    ///
    /// # Errors
    /// [`ExplicitError::UnstableTimeStep`] when the time step exceeds the
    /// stable step at the overlap reached, naming the pair, the overlap
    /// and the setting to change.
    pub fn check_overlap_stability(&self) -> Result<()> {
        let (Some(at), true) = (self.stability_at, self.settings.check_stability) else {
            return Ok(());
        };
        let Some((ratio, a, target)) = self.largest_overlap_ratio() else {
            return Ok(());
        };
        if ratio <= self.settings.stability_overlap {
            return Ok(());
        }
        let limit = at(&self.scene, &self.law, ratio);
        if self.settings.dt <= limit.dt {
            return Ok(());
        }
        Err(DismechError::Explicit(ExplicitError::UnstableTimeStep {
            dt: self.settings.dt,
            limit: limit.dt,
            governing: limit.governing,
            overlap: Some(OverlapReached {
                step: self.step,
                particle: a,
                target,
                ratio,
                stability_overlap: self.settings.stability_overlap,
            }),
        }))
    }

    /// Time the steps by phase from now on ([`PhaseTimes`]: the list's
    /// builds, the contact forces, the motion, the list's travel),
    /// starting again from zero if they were being timed. A run that does
    /// not ask reads no clock.
    pub fn time_phases(&mut self) {
        self.phase_times = Some(PhaseTimes::default());
    }

    /// The steps' time by phase since [`Self::time_phases`]; `None` when
    /// it was not called.
    pub fn phase_times(&self) -> Option<&PhaseTimes> {
        self.phase_times.as_ref()
    }

    /// How many times the neighbour list has been built.
    pub fn neighbour_list_builds(&self) -> u64 {
        self.neighbours.builds()
    }

    /// The skin of the neighbour list's last build (m; before the first,
    /// the skin it will start from): see [`DemSettings::neighbour_skin`].
    pub fn neighbour_skin(&self) -> f64 {
        self.neighbours.skin()
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
    /// `−Σ (m g + f_ext)·x` (J/m), over the free (not prescribed)
    /// particles.
    pub fn potential_energy(&self) -> f64 {
        let g = self.scene.gravity;
        self.scene
            .particles
            .iter()
            .filter(|p| !p.is_prescribed())
            .map(|p| -(p.mass * g + p.external_force).dot(&p.pose.position.coords))
            .sum()
    }

    /// Sum of the forces the particles exert on wall `wall` in the last step
    /// (N/m); the wall's reaction on the particles is its negative.
    pub fn wall_load(&self, wall: usize) -> Vec2 {
        self.neighbours
            .slots
            .iter()
            .filter(|slot| slot.target() == ContactTarget::Wall(wall))
            .flat_map(|slot| slot.points.iter().map(|p| p.force_on_b))
            .sum()
    }

    /// The force and moment summed on `particle` in the last step (N/m,
    /// N·m/m; zero before the first): its contacts plus its weight and
    /// external force. For a prescribed particle, which carries no weight,
    /// it is the force of its contacts alone: what a driven plate or a
    /// fixed base must exert is its negative.
    ///
    /// # Errors
    /// [`DismechError::NoSuchBody`] for an index the scene does not have.
    pub fn force_on(&self, particle: usize) -> Result<(Vec2, f64)> {
        let count = self.scene.particles.len();
        if particle >= count {
            return Err(DismechError::NoSuchBody {
                index: particle,
                count,
            });
        }
        let f = &self.system.force[3 * particle..3 * particle + 3];
        Ok((Vec2::new(f[0], f[1]), f[2]))
    }

    /// Mean over the free particles of the unbalanced force `|Σ f|`
    /// (contacts plus gravity, from the last step), divided by the mean
    /// weight.
    pub fn unbalanced_force_ratio(&self) -> f64 {
        let n = self.scene.particles.len();
        if n == 0 {
            return 0.0;
        }
        let net: f64 = (0..n)
            .filter(|&i| !self.scene.particles[i].is_prescribed())
            .map(|i| Vec2::new(self.system.force[3 * i], self.system.force[3 * i + 1]).norm())
            .sum();
        let weight = self.scene.total_weight();
        if weight > 0.0 {
            net / weight
        } else {
            net
        }
    }

    /// Advance one step.
    ///
    /// After an error the scene, the forces and the contacts are not
    /// specified (some particles may have moved, some forces and contact
    /// histories be of this step): the run has gone wrong and should not
    /// be continued.
    ///
    /// The forces are summed per particle in a fixed order (its weight,
    /// then its pairs in the list's order but for those whose A lies in an
    /// earlier block of particles, then those; each pair's points in the
    /// manifold's order), whatever the number of threads, so a run is the
    /// same to the last bit on one thread or many.
    ///
    /// # Errors
    /// [`ExplicitError::NonFinite`] naming the particle and the step when a
    /// force, position or velocity is NaN or infinite;
    /// [`ExplicitError::EnergyBlowUp`] when a particle leaves the frame while
    /// the kinetic energy exceeds twice what the loads and the initial
    /// motion can supply (an unstable step), and
    /// [`ExplicitError::ParticleLeftFrame`] when it leaves otherwise;
    /// [`DismechError::UnsupportedPair`] for a pair of shapes with no
    /// contact routine (two segments, which a scene the constructors
    /// accepted does not hold).
    pub fn step(&mut self) -> Result<()> {
        let n = self.scene.particles.len();
        let dt = self.settings.dt;
        let parallel = n >= PARALLEL_MIN_PARTICLES && rayon::current_num_threads() > 1;
        self.records = OnceLock::new();
        let clock = PhaseClock::start(self.phase_times.is_some());
        let builds = self.neighbours.builds();
        self.neighbours.update(
            &self.scene.particles,
            self.scene.frame.walls(),
            &mut self.grid,
            parallel,
        );
        let built = clock.lap();

        // Per block: each pair's contact points, added at once to its
        // particles in the block (the weight and external force first); a
        // pair whose B is in a later block keeps its summary for B.
        let (blocks, wall_boxes) = self.neighbours.blocks_mut();
        let context = PairContext {
            law: &self.law,
            dt,
            particles: &self.scene.particles,
            bodies: &self.bodies,
            rotations: &self.rotations,
            walls: self.scene.frame.walls(),
            wall_boxes,
            contact_shape: if self.law.uses_contact_shape() {
                ContactShape::Computed
            } else {
                ContactShape::Skipped
            },
        };
        let applied = &self.applied;
        let block_forces = self.system.force.chunks_mut(3 * BLOCK);
        if parallel {
            blocks
                .into_par_iter()
                .zip(block_forces.collect::<Vec<_>>())
                // One block a task: blocks differ in work (a packing's
                // floor against its surface), and a thread that runs out
                // steals single blocks rather than waiting for a run of
                // them.
                .with_max_len(1)
                .try_for_each_init(Vec::new, |manifold, (block, force)| {
                    context.evaluate_block(applied, manifold, block, force)
                })?;
        } else {
            for (block, force) in blocks.into_iter().zip(block_forces) {
                context.evaluate_block(applied, &mut self.manifold, block, force)?;
            }
        }
        let forced = clock.lap();

        // Per block: the pairs that cross into it from earlier blocks,
        // then its particles moved (see `BlockMotion::block`).
        let motion = BlockMotion {
            integrator: &self.integrator,
            mass: &self.system.mass,
            reach: self.frame_reach,
            dt,
        };
        let neighbours = &self.neighbours;
        let law = &self.law;
        let rotations: Vec<&mut [UnitComplex<f64>]> = if self.rotations.is_empty() {
            (0..n.div_ceil(BLOCK))
                .map(|_| <&mut [_]>::default())
                .collect()
        } else {
            self.rotations.chunks_mut(BLOCK).collect()
        };
        let move_block = |(k, (((force, particles), bodies), rotations)): BlockMove<'_>| {
            motion.block(
                neighbours,
                |state| law.moment(state),
                k,
                force,
                particles,
                bodies,
                rotations,
            )
        };
        let (force, particles, bodies) = (
            &mut self.system.force,
            &mut self.scene.particles,
            &mut self.bodies,
        );
        let check = if parallel {
            (force.par_chunks_mut(3 * BLOCK))
                .zip(particles.par_chunks_mut(BLOCK))
                .zip(bodies.par_chunks_mut(BLOCK))
                .zip(rotations)
                .enumerate()
                .with_max_len(1) // (as above)
                .map(move_block)
                .reduce(StepCheck::default, StepCheck::combine)
        } else {
            (force.chunks_mut(3 * BLOCK))
                .zip(particles.chunks_mut(BLOCK))
                .zip(bodies.chunks_mut(BLOCK))
                .zip(rotations)
                .enumerate()
                .map(move_block)
                .fold(StepCheck::default(), StepCheck::combine)
        };
        let moved = clock.lap();
        self.neighbours
            .note_travel(check.travel, &self.scene.particles, parallel);
        if let Some(times) = &mut self.phase_times {
            let noted = clock.lap();
            times.steps += 1;
            times.builds += self.neighbours.builds() - builds;
            times.build += built.unwrap_or_default();
            times.forces += forced.unwrap_or_default();
            times.motion += moved.unwrap_or_default();
            times.travel += noted.unwrap_or_default();
        }
        if let Some(i) = check.bad_force {
            return Err(self.non_finite(i, "force"));
        }
        if let Some(i) = check.bad_motion {
            let (dx, turn) = self.bodies[i].increment;
            let p = &self.scene.particles[i];
            let finite = dx.iter().all(|v| v.is_finite())
                && turn.is_finite()
                && p.velocity.iter().all(|v| v.is_finite())
                && p.angular_velocity.is_finite();
            if !finite {
                return Err(self.non_finite(i, "position or velocity"));
            }
            // Flung out by an unstable step rather than pushed out by its
            // loads: say so.
            if let Some(blow_up) = self.energy_blow_up() {
                return Err(blow_up);
            }
            return Err(DismechError::Explicit(ExplicitError::ParticleLeftFrame {
                step: self.step,
                time: self.time,
                body: i,
                x: p.pose.position.x,
                y: p.pose.position.y,
            }));
        }
        // The power a prescribed particle supplies is minus that of the
        // contact forces on it (it moves whatever they are).
        for &i in &self.prescribed {
            let p = &self.scene.particles[i];
            let f = &self.system.force[3 * i..3 * i + 3];
            self.prescribed_work -=
                (f[0] * p.velocity.x + f[1] * p.velocity.y + f[2] * p.angular_velocity) * dt;
        }
        self.step += 1;
        self.time += dt;
        Ok(())
    }

    /// [`ExplicitError::EnergyBlowUp`] when the kinetic energy exceeds
    /// twice what gravity, the external forces, the initial motion and
    /// the work of the prescribed particles can supply (the sign of an
    /// unstable step).
    fn energy_blow_up(&self) -> Option<DismechError> {
        self.blow_up_at(
            self.kinetic_energy(),
            self.initial_potential - self.potential_energy(),
        )
    }

    /// [`Self::energy_blow_up`] for the kinetic energy and the released
    /// potential energy at hand.
    fn blow_up_at(&self, kinetic: f64, released: f64) -> Option<DismechError> {
        let available = released.max(0.0) + self.initial_kinetic + self.prescribed_work.max(0.0);
        (kinetic > 2.0 * available + 1e-12 * self.scene.total_weight().max(1.0)).then_some(
            DismechError::Explicit(ExplicitError::EnergyBlowUp {
                step: self.step,
                kinetic,
                available,
                initial_overlap: self.initial_overlap,
            }),
        )
    }

    /// The kinetic energy against the potential energy released plus the
    /// work of the prescribed particles; with neither (no gravity, nothing
    /// fell, or bodies rose, and no driven body), against
    /// the initial kinetic energy; with neither, 0 when nothing moves and
    /// infinite otherwise.
    fn rest_ratio(&self, kinetic: f64, released: f64) -> f64 {
        let supplied = released.max(0.0) + self.prescribed_work.max(0.0);
        if supplied > 0.0 {
            kinetic / supplied
        } else if self.initial_kinetic > 0.0 {
            kinetic / self.initial_kinetic
        } else if kinetic == 0.0 {
            0.0
        } else {
            f64::INFINITY
        }
    }

    fn non_finite(&self, body: usize, quantity: &'static str) -> DismechError {
        DismechError::Explicit(ExplicitError::NonFinite {
            step: self.step,
            time: self.time,
            body,
            quantity,
        })
    }

    /// Run until the rest criterion holds or the time limit is reached.
    ///
    /// Stops with [`ExplicitError::EnergyBlowUp`] if the kinetic energy
    /// exceeds what gravity and the initial motion can supply (the sign of
    /// an unstable step). `on_check` is called at every check with the
    /// current time and the ratio the rest test reads (kinetic to released
    /// energy, see [`RestCriterion::kinetic_to_released_ratio`]; for
    /// progress reporting).
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for a
    /// `kinetic_to_released_ratio` or `max_time` that is not finite and
    /// positive, a `min_time` or `unbalanced_force_ratio` that is negative
    /// or not finite, or `max_steps` of 0 (checked before any step);
    /// [`ExplicitError::EnergyBlowUp`] at a check where the kinetic energy
    /// exceeds twice the energy supplied; any error of [`Self::step`]
    /// (after which the run should not be continued).
    pub fn run_to_rest(
        &mut self,
        criterion: &RestCriterion,
        mut on_check: impl FnMut(f64, f64),
    ) -> Result<RunOutcome> {
        self.run_to_rest_observed(criterion, &mut |_: &Self, event: &Event<'_>| {
            if let Event::Check { time, rest_ratio } = *event {
                on_check(time, rest_ratio);
            }
            Ok(())
        })
    }

    /// [`Self::run_to_rest`] with an [`Observer`]: called with the driver
    /// after every step ([`Event::Step`]), at every rest check
    /// ([`Event::Check`], with the ratio the rest test reads) and when the
    /// run ends ([`Event::Finished`]).
    ///
    /// # Errors
    /// As [`Self::run_to_rest`], and any error of the observer, which stops
    /// the run at that event.
    pub fn run_to_rest_observed(
        &mut self,
        criterion: &RestCriterion,
        observer: &mut (impl Observer<Self> + ?Sized),
    ) -> Result<RunOutcome> {
        require_positive("rest ratio", criterion.kinetic_to_released_ratio)?;
        require_positive("max_time", criterion.max_time)?;
        require_non_negative("min_time", criterion.min_time)?;
        require_non_negative("unbalanced_force_ratio", criterion.unbalanced_force_ratio)?;
        if criterion.max_steps == 0 {
            return Err(DismechError::InvalidParameter {
                name: "max_steps",
                value: 0.0,
                requirement: "must be at least 1",
            });
        }
        let every = criterion.check_every.max(1);
        let start = self.step;
        let clock = std::time::Instant::now();
        let mut calm_checks = 0u32;
        loop {
            self.step_observed(observer)?;
            let taken = self.step - start;
            if taken % every != 0 && taken < criterion.max_steps {
                continue;
            }
            let kinetic = self.kinetic_energy();
            let released = self.initial_potential - self.potential_energy();
            // An overlap beyond the one the step was checked at is the more
            // specific cause of a growing energy: said first.
            self.check_overlap_stability()?;
            if let Some(blow_up) = self.blow_up_at(kinetic, released) {
                return Err(blow_up);
            }
            let ratio = self.rest_ratio(kinetic, released);
            observer.observe(
                self,
                &Event::Check {
                    time: self.time,
                    rest_ratio: ratio,
                },
            )?;
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
            } else if taken >= criterion.max_steps {
                Some(RunStatus::StepLimit)
            } else if criterion
                .max_wall_time
                .is_some_and(|limit| clock.elapsed() >= limit)
            {
                Some(RunStatus::WallTimeLimit)
            } else {
                None
            };
            if let Some(status) = status {
                self.finished(observer)?;
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

    /// Take `steps` steps, calling `observer` after each ([`Event::Step`])
    /// and at the end ([`Event::Finished`]).
    ///
    /// # Errors
    /// Any error of [`Self::step`], or of the observer, which stops the run
    /// there.
    pub fn run_steps_observed(
        &mut self,
        steps: u64,
        observer: &mut (impl Observer<Self> + ?Sized),
    ) -> Result<()> {
        for _ in 0..steps {
            self.step_observed(observer)?;
        }
        self.finished(observer)
    }

    /// [`Self::step`], then [`Event::Step`] to `observer`.
    fn step_observed(&mut self, observer: &mut (impl Observer<Self> + ?Sized)) -> Result<()> {
        self.step()?;
        observer.observe(
            self,
            &Event::Step {
                step: self.step,
                time: self.time,
            },
        )
    }

    /// [`Event::Finished`] to `observer`.
    fn finished(&self, observer: &mut (impl Observer<Self> + ?Sized)) -> Result<()> {
        observer.observe(
            self,
            &Event::Finished {
                step: self.step,
                time: self.time,
            },
        )
    }
}

#[cfg(test)]
mod tests {
    use super::{check_memory, ExplicitError, MemoryUse};
    use crate::error::DismechError;
    use crate::law::SpringState;

    /// The memory of a DEM is asked of the allocator before it is taken:
    /// a scene whose bytes exceed the address space, or that the system
    /// cannot give (10^15 particles, some 500 PB), is refused as
    /// `OutOfMemory` naming its size; an ordinary one passes.
    #[test]
    fn memory_the_system_cannot_give_is_refused_before_it_is_taken() {
        assert!(check_memory::<SpringState<2>>(1000).is_ok());
        for (n, says) in [
            (1_000_000_000_000_000usize, "the system refused the memory"),
            (usize::MAX, "more than the address space"),
        ] {
            match check_memory::<SpringState<2>>(n) {
                Err(DismechError::Explicit(ExplicitError::OutOfMemory {
                    what,
                    bytes,
                    advice,
                })) => {
                    assert!(what.to_string().contains(&n.to_string()), "{what}");
                    assert_eq!(what, MemoryUse::Dem { particles: n });
                    assert!(bytes >= n as u128 * 100, "{bytes}");
                    assert!(advice.to_string().contains(says), "{advice}");
                }
                other => panic!("{n} particles: {other:?}"),
            }
        }
    }
}
