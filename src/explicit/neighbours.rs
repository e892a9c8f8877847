//! The neighbour list of the explicit driver: candidate pairs found once
//! with a skin and kept over the steps until the particles may have moved
//! far enough to meet a pair that is not in it (a particle by half the
//! skin, or, when asked, two particles relative to each other by the skin
//! or one to a wall by its gap); each pair carries its contact points'
//! history, so nothing is hashed or rebuilt per step.
//!
//! A pair is listed when the particles' bounding boxes are closer than the
//! skin `s` (in x and y) and so are their bounding circles; a wall, when
//! the particle's box and the wall's are closer than `s`. While no pair
//! left out can have closed its gap (`list_travel.rs` bounds that from the
//! particles' displacements since the build), the list holds every pair
//! whose boxes and bounding circles touch, a superset of the pairs that
//! touch: the narrow phase sees every pair a per-step broad phase would
//! give it that can touch. The list is therefore exact, not an
//! approximation: the forces are those of a broad phase rebuilt every
//! step.

use std::borrow::Cow;

use rayon::prelude::*;
use smallvec::SmallVec;

use super::driver::ContactTarget;
use super::keys::{PairKey, PointKey};
use super::list_travel::{ListTravel, TravelState};
use super::skin::Skin;
use crate::broad_phase::CellGrid;
use crate::math::{Aabb2, Point, Vec2};
use crate::query::moment_about;
use crate::scene::Particle;
use crate::shape::Segment;

/// One contact point of a pair: the law's history and the last step's
/// result. (Its moments about the two centres are not kept: they follow
/// from the point, the force and the law's rolling moment (read from the
/// state, [`crate::law::ContactLaw::moment`]), [`Self::moment_a`] and
/// [`Self::moment_b`], while the bodies have not moved.)
#[derive(Debug, Clone, Copy, serde::Serialize, serde::Deserialize)]
pub(super) struct PointContact<S> {
    /// The features that name the point across steps, and the law's
    /// regime at the last step.
    pub key: PointKey,
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
}

impl<S> PointContact<S> {
    /// The moment on A about A's centre `centre_a`: that of B's force,
    /// and the law's rolling moment `rolling` on A.
    #[inline]
    pub fn moment_a(&self, centre_a: &Point, rolling: f64) -> f64 {
        let of_force = moment_about(centre_a, &self.point, &(-self.force_on_b));
        // (Added only when there is one, so that a law without rolling
        // resistance gives the bits it gave before: −0 + 0 is +0.)
        if rolling == 0.0 {
            of_force
        } else {
            of_force + rolling
        }
    }

    /// The moment on B about B's centre `centre_b`: that of A's force, and
    /// the opposite of the law's rolling moment `rolling` on A (a wall has
    /// no centre: its moment is 0, which the callers take instead).
    #[inline]
    pub fn moment_b(&self, centre_b: &Point, rolling: f64) -> f64 {
        let of_force = moment_about(centre_b, &self.point, &self.force_on_b);
        if rolling == 0.0 {
            of_force
        } else {
            of_force - rolling
        }
    }
}

/// The contact points of one pair; most pairs have at most one.
pub(super) type PairPoints<S> = SmallVec<[PointContact<S>; 1]>;

/// A copy of a pair's points; one point (the common case) is copied
/// straight into the inline buffer.
#[inline]
fn copy_points<S: Clone>(points: &PairPoints<S>) -> PairPoints<S> {
    match points.as_slice() {
        [] => PairPoints::new(),
        [only] => PairPoints::from_buf([only.clone()]),
        many => many.iter().cloned().collect(),
    }
}

/// A listed pair: a particle and what it may touch, and the contact points
/// of the last step.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub(super) struct PairSlot<S> {
    /// The particle (A) and what it touches (B): a particle of higher
    /// index, or a wall.
    pub pair: PairKey,
    /// The contact points of the last step, in the manifold's order.
    pub points: PairPoints<S>,
}

impl<S> PairSlot<S> {
    /// The particle A.
    #[inline]
    pub fn a(&self) -> usize {
        self.pair.a()
    }

    /// What A may touch.
    #[inline]
    pub fn target(&self) -> ContactTarget {
        self.pair.target()
    }
}

/// A pair's force for the per-particle sums, apart from its points: the
/// first point's force and moments and how many points the pair has (a
/// pair of several points is summed from its points). Kept for the pairs
/// that cross blocks, so that adding them to B reads little memory.
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

/// Particles are summed in blocks of this many consecutive indices. A
/// block's pairs (those whose A is in it) are evaluated in the list's order
/// and added at once to their particles in the block; a pair whose B lies
/// in a later block is added to B after every block has been evaluated.
/// Each particle's force is thus summed in an order fixed by the list and
/// the blocks (its weight, its pairs in the list's order save those with A
/// in an earlier block, then those in the list's order), whatever the
/// number of threads; a scene of at most one block sums in the list's
/// order.
pub(super) const BLOCK: usize = 1024;

/// Whether the pair of particles `a` and `b` lies across blocks.
#[inline]
pub(super) fn crosses_blocks(a: usize, b: usize) -> bool {
    a / BLOCK != b / BLOCK
}

/// A pair whose A and B are in different blocks, as B's block sees it.
#[derive(Debug, Clone, Copy)]
pub(super) struct CrossIn {
    /// Its force summary's index among those of the crossing pairs.
    pub summary: usize,
    /// Its index in the list.
    pub slot: usize,
    /// Its B.
    pub b: usize,
}

/// One block's share of the list, to evaluate and add up.
pub(super) struct BlockSlots<'a, S> {
    /// Its first particle.
    pub start: usize,
    /// Its particle pairs (A in the block), in the list's order.
    pub pairs: &'a mut [PairSlot<S>],
    /// The force summaries of its pairs whose B is in a later block, in
    /// the list's order.
    pub cross_out: &'a mut [PairForce],
    /// Its walls' pairs (the particle in the block), in the list's order.
    pub walls: &'a mut [PairSlot<S>],
}

/// What a checkpoint keeps of a [`NeighbourList`]: its pairs in their
/// order with their contact points, the skin and the poses of the last
/// build, whether it must be built again and how many times it was built.
/// The indices by particle and by block follow from the pairs, and are
/// computed again on restore as a build computes them.
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(bound(
    serialize = "S: serde::Serialize + Clone",
    deserialize = "S: serde::Deserialize<'de> + Clone"
))]
pub(super) struct ListState<'a, S: Clone> {
    skin: Skin,
    slots: Cow<'a, [PairSlot<S>]>,
    travel: TravelState<'a>,
    stale: bool,
    builds: u64,
}

/// The listed pairs, how their forces are gathered by blocks, and the poses the
/// list was built at.
#[derive(Debug, Clone)]
pub(super) struct NeighbourList<S> {
    /// The skin of the last build, and how the next is chosen.
    skin: Skin,
    /// Pairs: particle pairs by (A, B), then walls by (particle, wall).
    pub slots: Vec<PairSlot<S>>,
    /// Scratch of the build's counting sort.
    fill: Vec<usize>,
    /// The buffer of the next build's `slots`.
    spare: Vec<PairSlot<S>>,
    /// The force summaries of the pairs whose A and B are in different
    /// blocks, in the list's order (block `k`'s from
    /// `cross_out_start[k]`).
    cross_forces: Vec<PairForce>,
    cross_out_start: Vec<usize>,
    /// The walls' boxes (a wall's geometry is asked only when the
    /// particle's box meets its box, as a per-step broad phase would: the
    /// wall queries are one-sided and report a particle behind the wall).
    pub wall_boxes: Vec<Aabb2>,
    /// How many of the pairs are particle pairs (the walls' follow).
    particle_pairs: usize,
    /// Where each block's particle pairs start in `slots`, and where its
    /// walls' pairs start (one entry a block, `n.div_ceil(BLOCK)` of them,
    /// and one more each).
    block_pairs: Vec<usize>,
    block_walls: Vec<usize>,
    /// The pairs whose B is in block `k` and A in an earlier one are
    /// `cross_in[cross_in_start[k]..cross_in_start[k + 1]]`, in the list's
    /// order.
    cross_in_start: Vec<usize>,
    cross_in: Vec<CrossIn>,
    /// The poses of the last build, which decide when to build again.
    travel: ListTravel,
    /// Bounding radius of each particle.
    radius: Vec<f64>,
    /// Per particle: whether its motion is prescribed (two prescribed
    /// particles, or one and a wall, make no pair).
    prescribed: Vec<bool>,
    /// The wall pairs of the last build, `(particle, wall)`, in the list's
    /// order.
    wall_pairs: Vec<(usize, usize)>,
    /// Where particle `a`'s pairs, and its walls' pairs, start in
    /// `slots` (`n + 1` entries each, empty before the first build).
    first_pair: Vec<usize>,
    first_wall: Vec<usize>,
    /// Whether the list must be built before the next step.
    stale: bool,
    builds: u64,
    /// The particles' boxes at the last build.
    boxes: Vec<Aabb2>,
    /// The particle pairs of the last build, `(A, B)`, in the list's order.
    pairs: Vec<(usize, usize)>,
}

impl<S: Clone + Send + Sync> NeighbourList<S> {
    /// An empty list with skin `skin`, built at the first step.
    pub fn new(skin: Skin, relative_travel: bool, particles: &[Particle]) -> Self {
        Self {
            skin,
            slots: Vec::new(),
            fill: Vec::new(),
            spare: Vec::new(),
            cross_forces: Vec::new(),
            cross_out_start: Vec::new(),
            wall_boxes: Vec::new(),
            particle_pairs: 0,
            block_pairs: Vec::new(),
            block_walls: Vec::new(),
            cross_in_start: Vec::new(),
            cross_in: Vec::new(),
            travel: ListTravel::new(BLOCK, relative_travel, particles),
            radius: particles
                .iter()
                .map(|p| p.shape.as_shape().bounding_radius())
                .collect(),
            prescribed: particles.iter().map(Particle::is_prescribed).collect(),
            stale: true,
            builds: 0,
            boxes: Vec::new(),
            pairs: Vec::new(),
            wall_pairs: Vec::new(),
            first_pair: Vec::new(),
            first_wall: Vec::new(),
        }
    }

    /// How many times the list was built.
    pub fn builds(&self) -> u64 {
        self.builds
    }

    /// The skin of the last build (m).
    pub fn skin(&self) -> f64 {
        self.skin.current()
    }

    /// The pairs whose B is in block `k` and whose A is in an earlier
    /// block, in the list's order.
    #[inline]
    pub fn cross_in(&self, k: usize) -> &[CrossIn] {
        &self.cross_in[self.cross_in_start[k]..self.cross_in_start[k + 1]]
    }

    /// The force summary of a pair that crosses blocks.
    #[inline]
    pub fn cross_force(&self, cross: &CrossIn) -> &PairForce {
        &self.cross_forces[cross.summary]
    }

    /// Each block's share of the list, mutable, in the blocks' order; and
    /// the walls' boxes.
    pub fn blocks_mut(&mut self) -> (Vec<BlockSlots<'_, S>>, &[Aabb2]) {
        let blocks = self.block_pairs.len().saturating_sub(1);
        let mut shares = Vec::with_capacity(blocks);
        let (mut pairs, mut walls) = self.slots.split_at_mut(self.particle_pairs);
        let mut cross_forces = self.cross_forces.as_mut_slice();
        for k in 0..blocks {
            let (block_pairs, rest) = std::mem::take(&mut pairs)
                .split_at_mut(self.block_pairs[k + 1] - self.block_pairs[k]);
            pairs = rest;
            let (cross_out, rest) = std::mem::take(&mut cross_forces)
                .split_at_mut(self.cross_out_start[k + 1] - self.cross_out_start[k]);
            cross_forces = rest;
            let (block_walls, rest) = std::mem::take(&mut walls)
                .split_at_mut(self.block_walls[k + 1] - self.block_walls[k]);
            walls = rest;
            shares.push(BlockSlots {
                start: k * BLOCK,
                pairs: block_pairs,
                cross_out,
                walls: block_walls,
            });
        }
        (shares, &self.wall_boxes)
    }

    /// Build the list again if the particles may have moved far enough
    /// since the last build to meet a pair it does not hold (see
    /// `list_travel.rs`), or it was never built.
    /// `parallel`: on rayon's threads.
    pub fn update(
        &mut self,
        particles: &[Particle],
        walls: &[Segment],
        grid: &mut CellGrid,
        parallel: bool,
    ) {
        if self.stale {
            self.build(particles, walls, grid, parallel);
        }
    }

    /// A bound on how far particle `i`'s box and bounding circle have
    /// moved since the build (see [`ListTravel::own_travel`]).
    #[inline]
    pub fn travel(&self, i: usize, particle: &Particle) -> f64 {
        self.travel.own_travel(i, particle)
    }

    /// Mark the list for a build when the largest travel of the step
    /// (`largest`, of [`Self::travel`]) is not a number, or exceeds half
    /// the skin and, when the relative travel is tested, the particles,
    /// now at `particles`' poses, may have come closer to each other or
    /// to a wall than the list stands (the test per block of
    /// `list_travel.rs`, on rayon's threads when `parallel`). Called once
    /// a step: each call counts a step towards the tuning of the skin.
    pub fn note_travel(&mut self, largest: f64, particles: &[Particle], parallel: bool) {
        self.skin.stepped();
        let own = largest <= self.travel.own_limit();
        if !own && (largest.is_nan() || !self.travel.relative_holds(particles, parallel)) {
            self.stale = true;
        }
    }

    fn build(
        &mut self,
        particles: &[Particle],
        walls: &[Segment],
        grid: &mut CellGrid,
        parallel: bool,
    ) {
        let n = particles.len();
        let skin = self.skin.at_build();
        let aabb = |p: &Particle| p.shape.as_shape().aabb(&p.pose);
        self.boxes.clear();
        if parallel {
            self.boxes.par_extend(particles.par_iter().map(aabb));
        } else {
            self.boxes.extend(particles.iter().map(aabb));
        }
        self.wall_boxes.clear();
        self.wall_boxes
            .extend(walls.iter().map(|w| Aabb2::from_corners(w.start, w.end)));
        // A wall is listed with a particle when their boxes are closer
        // than the skin.
        let wall_listed = |bounds: &Aabb2, wall: &Aabb2| bounds.inflated(skin).intersects(wall);
        // The poses of this build, which the travels are measured from.
        let boxes = &self.boxes;
        let (prescribed, wall_boxes) = (&self.prescribed, &self.wall_boxes);
        self.travel.built(
            skin,
            particles,
            boxes,
            wall_boxes,
            // A prescribed particle meets no wall: none to watch.
            |a, w| prescribed[a] || wall_listed(&boxes[a], &wall_boxes[w]),
            parallel,
        );
        // Of the pairs whose boxes are closer than the skin, those whose
        // bounding circles are too (a circle's box corner is far from the
        // circle: a square packing's diagonal neighbours have touching
        // boxes); a pair dropped here only when clearly beyond, against
        // rounding.
        let (radius, travel, prescribed) = (&self.radius, &self.travel, &self.prescribed);
        let circles_near = |a: usize, b: usize| {
            let reach = radius[a] + radius[b] + skin;
            let apart = (travel.centre_at_build(b) - travel.centre_at_build(a)).norm_squared();
            apart <= reach * reach * (1.0 + 1e-12) && !(prescribed[a] && prescribed[b])
        };
        grid.candidate_pairs_filtered(&self.boxes, skin, circles_near, parallel, &mut self.pairs);
        let wall_boxes = &self.wall_boxes;
        let boxes = &self.boxes;
        let walls_of = |a: usize| {
            wall_boxes
                .iter()
                .enumerate()
                .filter(move |(_, wall)| !prescribed[a] && wall_listed(&boxes[a], wall))
                .map(move |(w, _)| (a, w))
        };
        self.wall_pairs.clear();
        if parallel {
            self.wall_pairs
                .par_extend((0..n).into_par_iter().flat_map_iter(walls_of));
        } else {
            self.wall_pairs.extend((0..n).flat_map(walls_of));
        }

        // New slots in the list's order, each taking the points of the
        // same pair in the old list, found among the old pairs of its
        // particle. (The two lists swap their buffers at every build: a
        // large list is not given back to the system and asked for
        // again.)
        let mut old = std::mem::take(&mut self.slots);
        let (first_pair, first_wall) = (&self.first_pair, &self.first_wall);
        let slot_of = |a: usize, target: ContactTarget| {
            let (first, end) = match target {
                ContactTarget::Particle(_) => (first_pair.get(a), first_pair.get(a + 1)),
                ContactTarget::Wall(_) => (first_wall.get(a), first_wall.get(a + 1)),
            };
            let points = match (first, end) {
                (Some(&first), Some(&end)) => old[first..end]
                    .iter()
                    .find(|s| s.target() == target)
                    .map(|s| copy_points(&s.points))
                    .unwrap_or_default(),
                _ => PairPoints::new(),
            };
            PairSlot {
                pair: PairKey::new(a, target),
                points,
            }
        };
        let mut slots = std::mem::take(&mut self.spare);
        slots.clear();
        let particle_slot = |&(a, b): &(usize, usize)| slot_of(a, ContactTarget::Particle(b));
        let wall_slot = |&(a, w): &(usize, usize)| slot_of(a, ContactTarget::Wall(w));
        if parallel {
            slots.par_extend(
                self.pairs
                    .par_iter()
                    .map(particle_slot)
                    .chain(self.wall_pairs.par_iter().map(wall_slot)),
            );
        } else {
            slots.extend(
                self.pairs
                    .iter()
                    .map(particle_slot)
                    .chain(self.wall_pairs.iter().map(wall_slot)),
            );
        }
        // (The old slots' points are dropped on the threads too: a
        // point list that spilled to the heap is given back.)
        if parallel {
            old.par_drain(..).for_each(drop);
        } else {
            old.clear();
        }
        self.spare = old;
        self.slots = slots;
        self.index(n, parallel);
        self.stale = false;
        self.builds += 1;
    }

    /// The indices of the list's pairs `self.pairs` and `self.wall_pairs`
    /// (in `self.slots`) for `n` particles: where each particle's pairs and
    /// each block's start, the pairs that cross blocks, and their force
    /// summaries (written by the next step's evaluation). Where each
    /// particle's pairs start is found on rayon's threads when `parallel`.
    fn index(&mut self, n: usize, parallel: bool) {
        // Where each particle's pairs and walls start, for the next build
        // (the pairs are sorted by their first particle).
        let count_from = |first: &mut Vec<usize>, offset: usize, pairs: &[(usize, usize)]| {
            first.clear();
            if parallel {
                first.par_extend(
                    (0..=n)
                        .into_par_iter()
                        .map(|a| offset + pairs.partition_point(|&(i, _)| i < a)),
                );
                return;
            }
            first.resize(n + 1, 0);
            for &(a, _) in pairs {
                first[a + 1] += 1;
            }
            first[0] = offset;
            for a in 0..n {
                first[a + 1] += first[a];
            }
        };
        count_from(&mut self.first_pair, 0, &self.pairs);
        count_from(&mut self.first_wall, self.pairs.len(), &self.wall_pairs);
        self.particle_pairs = self.pairs.len();
        // Where each block's pairs start.
        let blocks = n.div_ceil(BLOCK);
        let (pairs, walls) = self.slots.split_at(self.particle_pairs);
        self.block_pairs.clear();
        self.block_walls.clear();
        for k in 0..=blocks {
            let first = (k * BLOCK).min(n);
            self.block_pairs
                .push(pairs.partition_point(|s| s.a() < first));
            self.block_walls
                .push(self.particle_pairs + walls.partition_point(|s| s.a() < first));
        }
        // The pairs that cross blocks: their summaries by A's block in the
        // list's order, and where each goes by B's block (a stable order by
        // B's block, which keeps the list's order in each).
        let block_of = |i: usize| i / BLOCK;
        let crosses = |&(a, b): &(usize, usize)| crosses_blocks(a, b);
        self.cross_out_start.clear();
        self.cross_in_start.clear();
        self.cross_in.clear();
        if parallel {
            let pairs = &self.pairs;
            self.cross_in.par_extend(
                pairs
                    .par_iter()
                    .enumerate()
                    .filter(|(_, pair)| crosses(pair))
                    .map(|(slot, &(_, b))| CrossIn {
                        summary: 0,
                        slot,
                        b,
                    }),
            );
            // In the list's order, so sorted by A's block.
            self.cross_in
                .par_iter_mut()
                .enumerate()
                .for_each(|(summary, cross)| cross.summary = summary);
            let crossing = &self.cross_in;
            self.cross_out_start.par_extend(
                (0..=blocks)
                    .into_par_iter()
                    .map(|k| crossing.partition_point(|c| block_of(pairs[c.slot].0) < k)),
            );
            self.cross_in.par_sort_by_key(|c| block_of(c.b));
            let crossing = &self.cross_in;
            self.cross_in_start.par_extend(
                (0..=blocks)
                    .into_par_iter()
                    .map(|k| crossing.partition_point(|c| block_of(c.b) < k)),
            );
        } else {
            self.cross_out_start.resize(blocks + 1, 0);
            self.cross_in_start.resize(blocks + 1, 0);
            for &(a, b) in self.pairs.iter().filter(|pair| crosses(pair)) {
                self.cross_out_start[block_of(a) + 1] += 1;
                self.cross_in_start[block_of(b) + 1] += 1;
            }
            for k in 0..blocks {
                self.cross_out_start[k + 1] += self.cross_out_start[k];
                self.cross_in_start[k + 1] += self.cross_in_start[k];
            }
            let fill = &mut self.fill;
            fill.clear();
            fill.extend_from_slice(&self.cross_in_start);
            self.cross_in.resize(
                self.cross_in_start[blocks],
                CrossIn {
                    summary: 0,
                    slot: 0,
                    b: 0,
                },
            );
            let mut summary = 0;
            for (slot, &(a, b)) in self.pairs.iter().enumerate() {
                if crosses(&(a, b)) {
                    self.cross_in[fill[block_of(b)]] = CrossIn { summary, slot, b };
                    fill[block_of(b)] += 1;
                    summary += 1;
                }
            }
        }
        let summaries = self.cross_in.len();
        // Written by the step's evaluation, which follows every build.
        self.cross_forces.clear();
        self.cross_forces.resize(summaries, PairForce::default());
    }

    /// What a checkpoint keeps (borrowed).
    pub fn state(&self) -> ListState<'_, S> {
        ListState {
            skin: self.skin,
            slots: Cow::Borrowed(&self.slots),
            travel: self.travel.state(),
            stale: self.stale,
            builds: self.builds,
        }
    }

    /// Back to a checkpoint's `state` for `particles` and `walls` (the
    /// list made by [`Self::new`] for them): the pairs and their points,
    /// the skin, the poses of the last build, and the indices computed
    /// from the pairs as the build computes them.
    ///
    /// # Errors
    /// What is wrong when the state does not fit the scene: a pair naming
    /// a particle or a wall it does not have, pairs out of the build's
    /// order or that no build lists (two prescribed particles, a
    /// prescribed particle and a wall), poses of the build that do not
    /// match the particles, a skin that is not valid, or a list never
    /// built that holds pairs.
    pub fn restore(
        &mut self,
        state: ListState<'_, S>,
        particles: &[Particle],
        walls: &[Segment],
    ) -> std::result::Result<(), String> {
        let n = particles.len();
        if !state.skin.is_valid() {
            return Err(format!(
                "the neighbour list's skin {:?} is not valid",
                state.skin
            ));
        }
        let built = state.builds > 0;
        let fresh = state.slots.is_empty() && state.stale;
        if !built && !fresh {
            return Err("a neighbour list never built holds pairs".into());
        }
        let (mut pairs, mut wall_pairs) = (Vec::new(), Vec::new());
        for slot in state.slots.iter() {
            let a = slot.a();
            let refused = |what: &str| {
                Err(format!(
                    "the neighbour list's pair {} of particle {a} with {:?} {what}",
                    pairs.len() + wall_pairs.len(),
                    slot.target()
                ))
            };
            if a >= n {
                return refused(&format!("names a particle beyond the {n} of the scene"));
            }
            match slot.target() {
                ContactTarget::Particle(b) => {
                    if b >= n || b <= a {
                        return refused("does not name a particle after A in the scene");
                    }
                    if !wall_pairs.is_empty() || pairs.last().is_some_and(|&last| last >= (a, b)) {
                        return refused("is out of the build's order");
                    }
                    if self.prescribed[a] && self.prescribed[b] {
                        return refused("joins two prescribed particles");
                    }
                    pairs.push((a, b));
                }
                ContactTarget::Wall(w) => {
                    if w >= walls.len() {
                        return refused(&format!(
                            "names a wall beyond the {} of the scene",
                            walls.len()
                        ));
                    }
                    if wall_pairs.last().is_some_and(|&last| last >= (a, w)) {
                        return refused("is out of the build's order");
                    }
                    if self.prescribed[a] {
                        return refused("joins a prescribed particle to a wall");
                    }
                    wall_pairs.push((a, w));
                }
            }
        }
        self.travel.restore(state.travel, n, built)?;
        self.skin = state.skin;
        self.stale = state.stale;
        self.builds = state.builds;
        self.slots = state.slots.into_owned();
        self.pairs = pairs;
        self.wall_pairs = wall_pairs;
        self.wall_boxes.clear();
        if built {
            self.wall_boxes
                .extend(walls.iter().map(|w| Aabb2::from_corners(w.start, w.end)));
            self.index(n, false);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::SpringState;

    /// A listed pair with its point of a spring–dashpot law takes 96
    /// bytes on a 64-bit machine (its key 8, its point 80, the point vector's length 8): each
    /// step reads and writes every slot, and a large scene's list does
    /// not fit in the caches.
    #[test]
    #[cfg(target_pointer_width = "64")]
    fn a_slot_takes_96_bytes() {
        assert_eq!(std::mem::size_of::<PointContact<SpringState<2>>>(), 80);
        assert_eq!(std::mem::size_of::<PairSlot<SpringState<2>>>(), 96);
    }
}
