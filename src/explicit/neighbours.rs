//! The neighbour list of the explicit driver: candidate pairs found once
//! with a skin and kept over the steps until some particle has moved far
//! enough to meet a pair that is not in it; each pair carries its contact
//! points' history, so nothing is hashed or rebuilt per step.
//!
//! A pair is listed when the particles' bounding boxes are closer than the
//! skin `s` (in x and y) and so are their bounding circles. A particle's
//! box and bounding circle move by at most `|Δx| + R |Δφ|` (`R` its
//! bounding radius; 0 for a circle, whose box and circle a turn does not
//! move) since the list was built; while that stays at or below `s/2`
//! for every particle, two boxes (or bounding circles) apart by more than
//! `s` at the build are still apart, so the list holds every pair whose
//! boxes and bounding circles touch, a superset of the pairs that touch:
//! the narrow phase sees every pair a per-step broad phase would give it
//! that can touch. Walls are listed per particle the same way. The list is
//! therefore exact, not an approximation: the forces are those of a broad
//! phase rebuilt every step.

use smallvec::SmallVec;

use super::driver::ContactTarget;
use crate::broad_phase::CellGrid;
use crate::law::Regime;
use crate::math::{Aabb2, Point, Vec2};
use crate::query::ContactFeatures;
use crate::scene::Particle;
use crate::shape::{AnyShape2, Segment};

/// One contact point of a pair: the law's history and the last step's
/// result.
#[derive(Debug, Clone, Copy)]
pub(super) struct PointContact<S> {
    /// The features that name the point across steps.
    pub features: ContactFeatures,
    /// The law's state after the last step.
    pub state: S,
    /// The overlap at the last step (m).
    pub overlap: f64,
    /// Contact point (world).
    pub point: Point,
    /// Normal from A to B.
    pub normal: Vec2,
    /// Force exerted by A on B.
    pub force_on_b: Vec2,
    /// Moment of B's force on A about A's centre.
    pub moment_a: f64,
    /// Moment of A's force on B about B's centre (0 for a wall).
    pub moment_b: f64,
    /// Regime of the law.
    pub regime: Regime,
}

/// The contact points of one pair; most pairs have at most one.
pub(super) type PairPoints<S> = SmallVec<[PointContact<S>; 1]>;

/// A listed pair: a particle and what it may touch, and the contact points
/// of the last step.
#[derive(Debug, Clone)]
pub(super) struct PairSlot<S> {
    /// The particle (A).
    pub a: usize,
    /// What it touches (B): a particle of higher index, or a wall.
    pub target: ContactTarget,
    /// The contact points of the last step, in the manifold's order.
    pub points: PairPoints<S>,
}

impl<S> PairSlot<S> {
    /// The order of the list: particle pairs by (A, B), then walls by
    /// (particle, wall).
    fn order(&self) -> (bool, usize, usize) {
        match self.target {
            ContactTarget::Particle(b) => (false, self.a, b),
            ContactTarget::Wall(w) => (true, self.a, w),
        }
    }
}

/// A pair's force for the per-particle sums, apart from the points so
/// that the sums read little memory: the first point's force and moments
/// and how many points the pair has (a pair of several points is summed
/// from its points).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct PairForce {
    /// Force exerted by A on B at the first point.
    pub force_on_b: Vec2,
    /// Its moment about A's centre.
    pub moment_a: f64,
    /// Its moment about B's centre.
    pub moment_b: f64,
    /// The pair's number of contact points.
    pub count: usize,
}

impl PairForce {
    /// The summary of a pair's points.
    pub fn of<S>(points: &[PointContact<S>]) -> Self {
        match points.first() {
            Some(p) => Self::of_point(p, points.len()),
            None => Self::default(),
        }
    }

    /// The summary of a pair of `points` points whose first is `first`.
    #[inline]
    pub fn of_point<S>(first: &PointContact<S>, points: usize) -> Self {
        Self {
            force_on_b: first.force_on_b,
            moment_a: first.moment_a,
            moment_b: first.moment_b,
            count: points,
        }
    }
}

/// Which side of a listed pair a particle is: the pair's index in the
/// list times two, plus one when the particle is B.
#[derive(Debug, Clone, Copy)]
pub(super) struct Incidence(usize);

impl Incidence {
    fn new(slot: usize, is_b: bool) -> Self {
        Self(2 * slot + usize::from(is_b))
    }

    /// The pair's index in the list.
    pub fn slot(self) -> usize {
        self.0 / 2
    }

    /// Whether the particle is the pair's B.
    pub fn is_b(self) -> bool {
        self.0 % 2 == 1
    }
}

/// The listed pairs, what each particle takes part in, and the poses the
/// list was built at.
#[derive(Debug, Clone)]
pub(super) struct NeighbourList<S> {
    skin: f64,
    /// Pairs, ordered as [`PairSlot::order`].
    pub slots: Vec<PairSlot<S>>,
    /// Scratch of the build's counting sort.
    fill: Vec<usize>,
    /// The buffer of the next build's `slots`.
    spare: Vec<PairSlot<S>>,
    /// Each pair's force summary, beside `slots`.
    pub forces: Vec<PairForce>,
    /// The walls' boxes (a wall's geometry is asked only when the
    /// particle's box meets its box, as a per-step broad phase would: the
    /// wall queries are one-sided and report a particle behind the wall).
    pub wall_boxes: Vec<Aabb2>,
    /// The pairs of particle `i` are `incidence[start[i]..start[i + 1]]`,
    /// in the list's order.
    incidence_start: Vec<usize>,
    incidence: Vec<Incidence>,
    /// Centre and angle of each particle at the build.
    reference: Vec<(Point, f64)>,
    /// Bounding radius of each particle.
    radius: Vec<f64>,
    /// How far a turn of one radian moves each particle's box and bounding
    /// circle at most: its bounding radius, or 0 for a circle about its
    /// centre (neither moves when it turns).
    turn_arm: Vec<f64>,
    /// Whether the list must be built before the next step.
    stale: bool,
    builds: u64,
    boxes: Vec<Aabb2>,
    pairs: Vec<(usize, usize)>,
}

impl<S> NeighbourList<S> {
    /// An empty list with skin `skin` (m), built at the first step.
    pub fn new(skin: f64, particles: &[Particle]) -> Self {
        Self {
            skin,
            slots: Vec::new(),
            fill: Vec::new(),
            spare: Vec::new(),
            forces: Vec::new(),
            wall_boxes: Vec::new(),
            incidence_start: Vec::new(),
            incidence: Vec::new(),
            reference: Vec::new(),
            turn_arm: particles
                .iter()
                .map(|p| match p.shape {
                    AnyShape2::Circle(_) => 0.0,
                    _ => p.shape.as_shape().bounding_radius(),
                })
                .collect(),
            radius: particles
                .iter()
                .map(|p| p.shape.as_shape().bounding_radius())
                .collect(),
            stale: true,
            builds: 0,
            boxes: Vec::new(),
            pairs: Vec::new(),
        }
    }

    /// How many times the list was built.
    pub fn builds(&self) -> u64 {
        self.builds
    }

    /// The pairs particle `i` takes part in.
    #[inline]
    pub fn incidence_of(&self, i: usize) -> &[Incidence] {
        &self.incidence[self.incidence_start[i]..self.incidence_start[i + 1]]
    }

    /// Build the list again if a particle has moved half the skin since
    /// the last build (or it was never built).
    pub fn update(&mut self, particles: &[Particle], walls: &[Segment], grid: &mut CellGrid) {
        if self.stale {
            self.build(particles, walls, grid);
        }
    }

    /// A bound on how far particle `i`'s box and bounding circle have
    /// moved since the build, `|Δx| + R |Δφ|` (`R` = 0 for a circle); while
    /// it is clearly below the build's limit it is taken without a square
    /// root, as `|Δx| + |Δy| + R |Δφ|`.
    #[inline]
    pub fn travel(&self, i: usize, particle: &Particle) -> f64 {
        let (centre, angle) = self.reference[i];
        let moved = particle.pose.position - centre;
        let turned = self.turn_arm[i] * (particle.pose.angle - angle).abs();
        let rough = moved.x.abs() + moved.y.abs() + turned;
        if rough <= self.limit() {
            rough
        } else {
            moved.norm() + turned
        }
    }

    /// The largest travel the list stands: half the skin, less a hair so
    /// that the rounding of the boxes cannot lose a pair whose gap was
    /// exactly the skin.
    fn limit(&self) -> f64 {
        0.5 * self.skin * (1.0 - 1e-9)
    }

    /// Mark the list for a build when the largest travel of the step
    /// exceeds [`Self::limit`] (or is not a number).
    pub fn note_travel(&mut self, largest: f64) {
        if largest.is_nan() || largest > self.limit() {
            self.stale = true;
        }
    }

    fn build(&mut self, particles: &[Particle], walls: &[Segment], grid: &mut CellGrid) {
        let n = particles.len();
        self.boxes.clear();
        self.boxes
            .extend(particles.iter().map(|p| p.shape.as_shape().aabb(&p.pose)));
        grid.candidate_pairs(&self.boxes, self.skin, &mut self.pairs);
        // Of those, the pairs whose bounding circles are also closer than
        // the skin (a circle's box corner is far from the circle: a square
        // packing's diagonal neighbours have touching boxes); a pair
        // dropped here only when clearly beyond, against rounding.
        let radius = &self.radius;
        let skin = self.skin;
        self.pairs.retain(|&(a, b)| {
            let reach = radius[a] + radius[b] + skin;
            let apart = (particles[b].pose.position - particles[a].pose.position).norm_squared();
            apart <= reach * reach * (1.0 + 1e-12)
        });
        self.wall_boxes.clear();
        self.wall_boxes
            .extend(walls.iter().map(|w| Aabb2::from_corners(w.start, w.end)));
        let wall_boxes = &self.wall_boxes;

        // New slots in the list's order, each taking the points of the
        // same pair in the old list (both are sorted: a merge).
        // (The two lists swap their buffers at every build: a large list
        // is not given back to the system and asked for again.)
        let mut previous_slots = std::mem::take(&mut self.slots);
        let mut old = previous_slots.drain(..).peekable();
        let mut slots = std::mem::take(&mut self.spare);
        slots.clear();
        let particle_pairs = self
            .pairs
            .iter()
            .map(|&(a, b)| (a, ContactTarget::Particle(b)));
        let boxes = &self.boxes;
        let wall_pairs = (0..n).flat_map(|a| {
            let grown = boxes[a].inflated(skin);
            wall_boxes
                .iter()
                .enumerate()
                .filter(move |(_, wall)| grown.intersects(wall))
                .map(move |(w, _)| (a, ContactTarget::Wall(w)))
        });
        for (a, target) in particle_pairs.chain(wall_pairs) {
            let mut slot = PairSlot {
                a,
                target,
                points: PairPoints::new(),
            };
            let order = slot.order();
            while old.peek().is_some_and(|s| s.order() < order) {
                old.next();
            }
            if let Some(previous) = old.next_if(|s| s.order() == order) {
                slot.points = previous.points;
            }
            slots.push(slot);
        }
        drop(old);
        self.spare = previous_slots;
        // The summaries are written by the step's evaluation, which
        // follows every build.
        self.forces.clear();
        self.forces.resize(slots.len(), PairForce::default());
        self.slots = slots;

        // Each particle's pairs, in the list's order (a counting sort).
        self.incidence_start.clear();
        self.incidence_start.resize(n + 1, 0);
        for slot in &self.slots {
            self.incidence_start[slot.a + 1] += 1;
            if let ContactTarget::Particle(b) = slot.target {
                self.incidence_start[b + 1] += 1;
            }
        }
        for i in 0..n {
            self.incidence_start[i + 1] += self.incidence_start[i];
        }
        let fill = &mut self.fill;
        fill.clear();
        fill.extend_from_slice(&self.incidence_start);
        self.incidence.clear();
        self.incidence
            .resize(self.incidence_start[n], Incidence::new(0, false));
        for (k, slot) in self.slots.iter().enumerate() {
            self.incidence[fill[slot.a]] = Incidence::new(k, false);
            fill[slot.a] += 1;
            if let ContactTarget::Particle(b) = slot.target {
                self.incidence[fill[b]] = Incidence::new(k, true);
                fill[b] += 1;
            }
        }

        self.reference.clear();
        self.reference
            .extend(particles.iter().map(|p| (p.pose.position, p.pose.angle)));
        self.stale = false;
        self.builds += 1;
    }
}
