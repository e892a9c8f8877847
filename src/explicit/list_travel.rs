//! When the neighbour list must be built again: a bound, from how far the
//! particles have moved since the build, on how much closer any two
//! particles (or a particle and a wall) can have come.
//!
//! A pair is left out of the list when, at the build, the particles'
//! boxes or their bounding circles were apart by more than the skin `s`;
//! a wall, when its box and the particle's were. A particle's box (and
//! bounding circle) now lies within its box at the build shifted by its
//! displacement `Δxᵢ` and grown by `Rᵢ |Δφᵢ|` (`Rᵢ` its bounding radius, 0
//! for a circle, which a turn does not move). So two particles have come
//! closer by at most `|Δxₐ − Δx_b| + Rₐ|Δφₐ| + R_b|Δφ_b|`, and the list
//! holds every pair that can touch while that stays within `s` for every
//! pair left out.
//!
//! Two tests, the cheaper first:
//! - **Each particle's own travel** `|Δxᵢ| + Rᵢ|Δφᵢ|` at most `s/2` (taken
//!   in the step's move of each particle): then no two particles have
//!   come closer by more than `s`, nor a particle to a wall.
//! - **Relative travel, per block**, when the first fails and
//!   [`super::DemSettings::relative_travel`] asks for it (a pass over the
//!   particles at each such step, about a tenth of a step). Block `k` (the
//!   driver's blocks of consecutive indices) has a reference displacement
//!   `c_k` (the middle of its particles' displacements) and a spread
//!   `t_k = max_{i ∈ k} (|Δxᵢ − c_k| + Rᵢ|Δφᵢ|)`. For `a` in block `A`
//!   and `b` in block `B`,
//!   `|Δxₐ − Δx_b| + Rₐ|Δφₐ| + R_b|Δφ_b| ≤ t_A + t_B + |c_A − c_B|`, so the
//!   list holds while, for every pair of blocks, that sum is at most `s`,
//!   or at most the gap between the two blocks' boxes at the build (no
//!   particle of one can then have reached a particle of the other,
//!   listed or not); one block alone needs `2 t_A ≤ s`. A wall does not
//!   move: each particle's `|Δxᵢ| + Rᵢ|Δφᵢ|` is held below its own gap to
//!   the walls it is not listed with, kept from the build. A packing that
//!   moves as a whole (a settling column, a sliding mass) keeps its list.
//!
//! Every comparison keeps a hair (1e-9 of the bound) against rounding
//! (neither test covers a skin below about 1e-7 of the coordinates). The
//! tests decide only when the list is built, never what a step computes:
//! the forces are those of a broad phase run at every step. A pose that is
//! not finite always asks for a build.

use std::borrow::Cow;
use std::cmp::Ordering;

use rayon::prelude::*;

use crate::math::{Aabb2, Point, Vec2};
use crate::scene::Particle;
use crate::shape::AnyShape2;

/// The part of a bound a comparison keeps against rounding.
const HAIR: f64 = 1e-9;

/// The lower and upper corners of the box of `vectors` (infinite, and
/// the wrong way round, for none).
fn corners(vectors: impl Iterator<Item = Vec2>) -> (Vec2, Vec2) {
    vectors.fold(
        (Vec2::repeat(f64::INFINITY), Vec2::repeat(f64::NEG_INFINITY)),
        |(low, high), v| (low.inf(&v), high.sup(&v)),
    )
}

/// How far the particles of one block have moved since the build.
#[derive(Debug, Clone, Copy)]
struct BlockTravel {
    /// The block's reference displacement `c_k`: the middle of its
    /// particles' displacements.
    reference: Vec2,
    /// The largest `|Δxᵢ − c_k| + Rᵢ |Δφᵢ|` over the block.
    spread: f64,
    /// Whether a particle may have reached a wall it is not listed with,
    /// or a displacement or turn is not finite.
    stale: bool,
}

/// What a checkpoint keeps of [`ListTravel`]: the skin and the poses of
/// the last build, and the walls' gaps and blocks' boxes the relative test
/// measures from (the rest follows from the particles and the settings).
#[derive(serde::Serialize, serde::Deserialize)]
pub(super) struct TravelState<'a> {
    skin: f64,
    at_build: Cow<'a, [(Point, f64)]>,
    wall_gaps: Cow<'a, [f64]>,
    block_boxes: Cow<'a, [Aabb2]>,
}

/// The poses of the last build, which decide when the list must be built
/// again (see the module's docs).
#[derive(Debug, Clone)]
pub(super) struct ListTravel {
    skin: f64,
    /// The particles of consecutive indices taken together.
    block: usize,
    /// Whether the relative travel is tested
    /// ([`super::DemSettings::relative_travel`]); without it the walls'
    /// gaps and the blocks' boxes are not kept.
    relative: bool,
    /// Each particle's centre and angle at the build.
    at_build: Vec<(Point, f64)>,
    /// Each particle's least gap between its box and the box of a wall
    /// not listed with it (infinite when every wall is listed, or there
    /// is none), less the hair.
    wall_gaps: Vec<f64>,
    /// How far a turn of one radian moves each particle's box and bounding
    /// circle at most: its bounding radius, or 0 for a circle about its
    /// centre (neither moves when it turns).
    turn_arm: Vec<f64>,
    /// Each block's box at the build: the union of its particles' boxes.
    block_boxes: Vec<Aabb2>,
}

impl ListTravel {
    /// Nothing built yet, for `particles` taken in blocks of `block`, the
    /// relative travel tested if `relative`.
    pub fn new(block: usize, relative: bool, particles: &[Particle]) -> Self {
        Self {
            skin: 0.0,
            block,
            relative,
            at_build: Vec::new(),
            wall_gaps: Vec::new(),
            turn_arm: particles
                .iter()
                .map(|p| match p.shape {
                    AnyShape2::Circle(_) => 0.0,
                    _ => p.shape.as_shape().bounding_radius(),
                })
                .collect(),
            block_boxes: Vec::new(),
        }
    }

    /// What a checkpoint keeps.
    pub fn state(&self) -> TravelState<'_> {
        TravelState {
            skin: self.skin,
            at_build: Cow::Borrowed(&self.at_build),
            wall_gaps: Cow::Borrowed(&self.wall_gaps),
            block_boxes: Cow::Borrowed(&self.block_boxes),
        }
    }

    /// Back to a checkpoint's `state`, for `n` particles, built (`built`)
    /// or not yet.
    ///
    /// # Errors
    /// What is wrong, when the poses, gaps or boxes do not match `n`
    /// particles (a list not built has none) and the way the travel is
    /// tested.
    pub fn restore(
        &mut self,
        state: TravelState<'_>,
        n: usize,
        built: bool,
    ) -> std::result::Result<(), String> {
        let relative = built && self.relative;
        let expected = |count: usize, on: bool| if on { count } else { 0 };
        let counts = [
            (
                state.at_build.len(),
                expected(n, built),
                "poses of the build",
            ),
            (
                state.wall_gaps.len(),
                expected(n, relative),
                "gaps to the walls",
            ),
            (
                state.block_boxes.len(),
                expected(n.div_ceil(self.block), relative),
                "boxes of the blocks",
            ),
        ];
        for (found, expected, what) in counts {
            if found != expected {
                return Err(format!(
                    "the neighbour list holds {found} {what} where {expected} were expected"
                ));
            }
        }
        if !(state.skin.is_finite() && state.skin >= 0.0) {
            return Err(format!(
                "the neighbour list's skin {} is not valid",
                state.skin
            ));
        }
        self.skin = state.skin;
        self.at_build = state.at_build.into_owned();
        self.wall_gaps = state.wall_gaps.into_owned();
        self.block_boxes = state.block_boxes.into_owned();
        Ok(())
    }

    /// Each particle's centre at the last build.
    pub fn centre_at_build(&self, i: usize) -> Point {
        self.at_build[i].0
    }

    /// A build with skin `skin` at the particles' present poses: `boxes`
    /// are their boxes, `wall_boxes` the walls', and `listed(a, w)`
    /// whether wall `w` is listed with particle `a`. The tests until the
    /// next build measure from these poses against this skin. On rayon's
    /// threads when `parallel` (the same values).
    pub fn built(
        &mut self,
        skin: f64,
        particles: &[Particle],
        boxes: &[Aabb2],
        wall_boxes: &[Aabb2],
        listed: impl Fn(usize, usize) -> bool + Sync,
        parallel: bool,
    ) {
        self.skin = skin;
        self.at_build.clear();
        let pose = |p: &Particle| (p.pose.position, p.pose.angle);
        if parallel {
            self.at_build.par_extend(particles.par_iter().map(pose));
        } else {
            self.at_build.extend(particles.iter().map(pose));
        }
        self.wall_gaps.clear();
        self.block_boxes.clear();
        if !self.relative {
            return;
        }
        let wall_gap = |(a, bounds): (usize, &Aabb2)| {
            let gap = wall_boxes
                .iter()
                .enumerate()
                .filter(|&(w, _)| !listed(a, w))
                .map(|(_, wall)| bounds.separation(wall))
                .fold(f64::INFINITY, f64::min);
            gap * (1.0 - HAIR)
        };
        let union = |chunk: &[Aabb2]| {
            chunk[1..]
                .iter()
                .fold(chunk[0], |union, bounds| union.merged(bounds))
        };
        if parallel {
            self.wall_gaps
                .par_extend(boxes.par_iter().enumerate().map(wall_gap));
            self.block_boxes
                .par_extend(boxes.par_chunks(self.block).map(union));
        } else {
            self.wall_gaps
                .extend(boxes.iter().enumerate().map(wall_gap));
            self.block_boxes.extend(boxes.chunks(self.block).map(union));
        }
    }

    /// The largest travel the first test stands: half the skin, less the
    /// hair.
    pub fn own_limit(&self) -> f64 {
        0.5 * self.skin * (1.0 - HAIR)
    }

    /// A bound on how far particle `i`'s box and bounding circle have
    /// moved since the build, `|Δx| + R |Δφ|`; while it is clearly within
    /// [`Self::own_limit`] it is taken without a square root, as
    /// `|Δx| + |Δy| + R |Δφ|`.
    #[inline]
    pub fn own_travel(&self, i: usize, particle: &Particle) -> f64 {
        let (centre, angle) = self.at_build[i];
        let moved = particle.pose.position - centre;
        let turned = self.turn_arm[i] * (particle.pose.angle - angle).abs();
        let rough = moved.x.abs() + moved.y.abs() + turned;
        if rough <= self.own_limit() {
            rough
        } else {
            moved.norm() + turned
        }
    }

    /// Block `k`'s travel: the middle of its displacements, then the
    /// spread about it and the walls.
    fn block_travel(&self, k: usize, particles: &[Particle]) -> BlockTravel {
        let first = k * self.block;
        let displacement =
            |offset: usize, p: &Particle| p.pose.position - self.at_build[first + offset].0;
        let (low, high) = corners(
            particles
                .iter()
                .enumerate()
                .map(|(offset, p)| displacement(offset, p)),
        );
        let reference = 0.5 * (low + high);
        let mut travel = BlockTravel {
            reference,
            spread: 0.0,
            stale: false,
        };
        for (offset, p) in particles.iter().enumerate() {
            let i = first + offset;
            let moved = displacement(offset, p);
            let turned = self.turn_arm[i] * (p.pose.angle - self.at_build[i].1).abs();
            let wall_gap = self.wall_gaps[i];
            travel.spread = travel.spread.max((moved - reference).norm() + turned);
            // Towards the walls not listed, without a square root while
            // clearly short of the gap (|v| ≤ |v_x| + |v_y|); a travel
            // that is not finite fails both comparisons, even against an
            // infinite gap.
            let rough = moved.x.abs() + moved.y.abs() + turned;
            let apart = rough < wall_gap || moved.norm() + turned < wall_gap;
            travel.stale |= !apart;
        }
        travel
    }

    /// Whether the list still holds every pair that can touch, the
    /// particles now at `particles`' poses, by the relative travel per
    /// block (the second test of the module's docs); the blocks on
    /// rayon's threads when `parallel`. `false` when the relative travel
    /// is not tested.
    pub fn relative_holds(&self, particles: &[Particle], parallel: bool) -> bool {
        if !self.relative {
            return false;
        }
        let of_block = |(k, block): (usize, &[Particle])| self.block_travel(k, block);
        let travels: Vec<BlockTravel> = if parallel {
            particles
                .par_chunks(self.block)
                .enumerate()
                .map(of_block)
                .collect()
        } else {
            particles
                .chunks(self.block)
                .enumerate()
                .map(of_block)
                .collect()
        };
        if travels.iter().any(|t| t.stale) {
            return false;
        }
        let within = self.skin * (1.0 - HAIR);
        // Any pair of blocks within the widest spreads and the spread of
        // the references: no pair of blocks needs a look.
        let widest = travels.iter().fold(0.0f64, |m, t| m.max(t.spread));
        let (low, high) = corners(travels.iter().map(|t| t.reference));
        let references = if travels.is_empty() {
            0.0
        } else {
            (high - low).norm()
        };
        let bound = 2.0 * widest + references;
        bound.partial_cmp(&within) == Some(Ordering::Less) || self.blocks_hold(&travels, within)
    }

    /// The test pair of blocks by pair of blocks.
    fn blocks_hold(&self, travels: &[BlockTravel], within: f64) -> bool {
        travels.iter().enumerate().all(|(a, ta)| {
            2.0 * ta.spread <= within
                && travels[a + 1..].iter().enumerate().all(|(offset, tb)| {
                    let b = a + 1 + offset;
                    let gap = self.block_boxes[a].separation(&self.block_boxes[b]);
                    let closer = ta.spread + tb.spread + (ta.reference - tb.reference).norm();
                    closer <= within.max(gap * (1.0 - HAIR))
                })
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::SplitMix64;
    use crate::scene::{Frame, Scene};

    /// Whenever the test says the list holds, no pair the list left out
    /// can touch: every pair of particles whose boxes and bounding circles
    /// now meet was listed (both within the skin at the build), and so
    /// was every wall whose box a particle's box now meets. Random
    /// circles and ellipses in blocks of four, moved in up to 20 steps
    /// (each measured from the references the last one set) until the
    /// test fails: all by one shift a step (up to 0.3 skin along x and y),
    /// each block by a random one of up to a fifth of the skin more, each
    /// particle about its block's place by up to 0.05 skin, with a turn.
    #[test]
    fn a_list_that_holds_misses_no_pair_that_can_touch() {
        let skin = 0.05;
        let mut random = SplitMix64(7);
        let mut uniform = |low: f64, high: f64| low + (high - low) * random.next_uniform();
        let (mut held, mut failed) = (0, 0);
        for _ in 0..400 {
            let mut scene = Scene::new(Frame::open_box(4.0, 4.0).unwrap(), Vec2::zeros()).unwrap();
            for _ in 0..(uniform(2.0, 30.0) as usize) {
                let centre = Point::new(uniform(0.5, 3.5), uniform(0.5, 3.5));
                if uniform(0.0, 1.0) < 0.5 {
                    scene.add_circle(centre, uniform(0.05, 0.2), 1.0).unwrap();
                } else {
                    let (a, b) = (uniform(0.1, 0.3), uniform(0.05, 0.1));
                    let angle = uniform(0.0, 6.0);
                    scene.add_ellipse(centre, a, b, angle, 1.0).unwrap();
                }
            }
            let walls = [
                Aabb2::from_corners(Point::new(-4.0, 0.0), Point::new(8.0, 0.0)),
                Aabb2::from_corners(Point::new(uniform(0.0, 4.0), -4.0), Point::new(4.0, 8.0)),
            ];
            let particles = &mut scene.particles;
            let n = particles.len();
            let box_of = |p: &Particle| p.shape.as_shape().aabb(&p.pose);
            let boxes: Vec<Aabb2> = particles.iter().map(box_of).collect();
            let wall_listed = |a: usize, w: usize| boxes[a].inflated(skin).intersects(&walls[w]);
            // The neighbour list's rule: boxes and bounding circles within
            // the skin.
            let centres: Vec<Point> = particles.iter().map(|p| p.pose.position).collect();
            let listed = |a: usize, b: usize| {
                let radius = |i: usize| particles[i].shape.as_shape().bounding_radius();
                let reach = radius(a) + radius(b) + skin;
                boxes[a].inflated(skin).intersects(&boxes[b])
                    && (centres[b] - centres[a]).norm() <= reach
            };
            let listed: Vec<Vec<bool>> = (0..n)
                .map(|a| (0..n).map(|b| listed(a, b)).collect())
                .collect();
            let mut travel = ListTravel::new(4, true, particles);
            travel.built(skin, particles, &boxes, &walls, wall_listed, false);
            let mut shifts = vec![Vec2::zeros(); n.div_ceil(4)];
            let all = Vec2::new(uniform(-1.0, 1.0), uniform(-1.0, 1.0)) * (0.3 * skin);
            let apart = uniform(0.0, 0.2) * skin;
            for _ in 0..20 {
                for shift in shifts.iter_mut() {
                    *shift += all + Vec2::new(uniform(-1.0, 1.0), uniform(-1.0, 1.0)) * apart;
                }
                for (k, chunk) in particles.chunks_mut(4).enumerate() {
                    for (offset, p) in chunk.iter_mut().enumerate() {
                        let i = 4 * k + offset;
                        let own = Vec2::new(uniform(-1.0, 1.0), uniform(-1.0, 1.0)) * (0.05 * skin);
                        p.pose.position = centres[i] + shifts[k] + own;
                        p.pose.angle += uniform(-0.02, 0.02);
                    }
                }
                if !travel.relative_holds(particles, false) {
                    failed += 1;
                    break;
                }
                held += 1;
                let now: Vec<Aabb2> = particles.iter().map(box_of).collect();
                for a in 0..n {
                    for b in a + 1..n {
                        let (pa, pb) = (&particles[a], &particles[b]);
                        let reach = pa.shape.as_shape().bounding_radius()
                            + pb.shape.as_shape().bounding_radius();
                        let circles_meet = (pb.pose.position - pa.pose.position).norm() <= reach;
                        let may_touch = now[a].intersects(&now[b]) && circles_meet;
                        assert!(!may_touch || listed[a][b], "({a}, {b})");
                    }
                    for (w, wall) in walls.iter().enumerate() {
                        assert!(
                            !now[a].intersects(wall) || wall_listed(a, w),
                            "({a}, wall {w})"
                        );
                    }
                }
            }
        }
        println!("held {held}, failed {failed}");
        assert!(held > 100 && failed > 100, "held {held}, failed {failed}");
    }

    /// Circles of radius 0.1 at `centres`, taken in blocks of `block`,
    /// built with `walls`: the travel and its particles.
    fn circles(
        centres: &[(f64, f64)],
        block: usize,
        walls: &[Aabb2],
    ) -> (ListTravel, Vec<Particle>) {
        let mut scene = Scene::new(Frame::open_box(10.0, 10.0).unwrap(), Vec2::zeros()).unwrap();
        for &(x, y) in centres {
            scene.add_circle(Point::new(x, y), 0.1, 1.0).unwrap();
        }
        let particles = scene.particles;
        let boxes: Vec<Aabb2> = particles
            .iter()
            .map(|p| p.shape.as_shape().aabb(&p.pose))
            .collect();
        let mut travel = ListTravel::new(block, true, &particles);
        travel.built(
            SKIN,
            &particles,
            &boxes,
            walls,
            |a, w| boxes[a].inflated(SKIN).intersects(&walls[w]),
            false,
        );
        (travel, particles)
    }

    const SKIN: f64 = 0.01;

    /// Whether the list holds after particle `i` of `particles` moved by
    /// `moves[i]` along x.
    fn holds_after(
        travel: &ListTravel,
        particles: &mut [Particle],
        block: usize,
        moves: &[f64],
    ) -> bool {
        for (p, step) in particles.iter_mut().zip(moves) {
            p.pose.position.x += step;
        }
        travel.relative_holds(particles, block > 1)
    }

    /// Two particles in one block closing on each other hold the list
    /// until they have come closer by the skin, however far apart they
    /// were: the list is built against the skin alone.
    #[test]
    fn one_block_holds_until_its_particles_close_by_the_skin() {
        for (closing, holds) in [(0.99 * SKIN, true), (1.01 * SKIN, false)] {
            let (travel, mut particles) = circles(&[(1.0, 1.0), (3.0, 1.0)], 2, &[]);
            let half = 0.5 * closing;
            assert_eq!(
                holds_after(&travel, &mut particles, 2, &[half, -half]),
                holds,
                "{closing}"
            );
        }
    }

    /// How many steps of `moves` (m along x, per particle) the list
    /// holds, at most 1 000.
    fn steps_held(centres: &[(f64, f64)], block: usize, moves: &[f64]) -> usize {
        let (travel, mut particles) = circles(centres, block, &[]);
        (0..1000)
            .take_while(|_| holds_after(&travel, &mut particles, block, moves))
            .count()
    }

    /// Two blocks of one particle each, 0.5 m apart between their boxes
    /// and closing by 0.008 m a step, hold the list for the 62 steps
    /// (0.496 m) before they may have closed that gap; blocks whose boxes
    /// meet hold it only until they may have closed by the skin, however
    /// far apart the two particles are.
    #[test]
    fn two_blocks_hold_until_they_may_have_closed_their_gap() {
        let far = 1.0 + 0.2 + 0.5;
        let step = 0.4 * SKIN;
        assert_eq!(steps_held(&[(1.0, 1.0), (far, 1.0)], 1, &[step, -step]), 62);
        // The first block reaches over the second's box with a particle
        // 1 m higher; closing by 0.0022 m a step, they hold for 4 steps
        // (0.0088 m).
        let centres = [(1.0, 1.0), (far - 0.05, 2.0), (far, 1.0)];
        let step = 0.11 * SKIN;
        assert_eq!(steps_held(&centres, 2, &[step, step, -step]), 4);
    }

    /// A block moving as a whole holds the list: after one step, its
    /// reference is its displacement, and its spread stays what the
    /// particles move about it.
    #[test]
    fn a_block_moving_as_a_whole_holds_the_list() {
        let (travel, mut particles) = circles(&[(1.0, 1.0), (1.3, 1.0), (3.0, 1.0)], 2, &[]);
        let step = 0.3 * SKIN;
        for k in 0..100 {
            assert!(
                holds_after(&travel, &mut particles, 2, &[step, step, step]),
                "step {k}"
            );
        }
    }

    /// A particle falling 0.0041 m a step holds the list for the 97 steps
    /// (0.398 m) before it may have reached the floor 0.4 m below its box,
    /// a wall it is not listed with.
    #[test]
    fn a_particle_holds_until_it_may_reach_a_wall() {
        let floor = [Aabb2::from_corners(
            Point::new(-5.0, 0.0),
            Point::new(5.0, 0.0),
        )];
        let (travel, mut particles) = circles(&[(1.0, 0.5)], 1, &floor);
        let held = (0..1000)
            .take_while(|_| {
                particles[0].pose.position.y -= 0.41 * SKIN;
                travel.relative_holds(&particles, false)
            })
            .count();
        assert_eq!(held, 97);
    }

    /// A position or angle that is not finite never holds the list, with
    /// walls or without.
    #[test]
    fn a_pose_that_is_not_finite_does_not_hold_the_list() {
        let floor = [Aabb2::from_corners(
            Point::new(-5.0, 0.0),
            Point::new(5.0, 0.0),
        )];
        for walls in [&floor[..], &[]] {
            for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                for field in 0..3 {
                    let (travel, mut particles) = circles(&[(1.0, 1.0), (1.5, 1.0)], 2, walls);
                    let pose = &mut particles[1].pose;
                    match field {
                        0 => pose.position.x = bad,
                        1 => pose.position.y = bad,
                        _ => pose.angle = bad,
                    }
                    assert!(
                        !travel.relative_holds(&particles, false),
                        "{bad} in field {field}"
                    );
                }
            }
        }
    }

    /// A turn counts: an ellipse (a = 0.3 m, b = 0.05 m) turning 0.001
    /// rad a step about its centre, under a circle 0.011 m above its box
    /// (not listed with a skin of 0.01 m) near its tip, asks for a build
    /// before the two boxes meet, although neither centre moves.
    #[test]
    fn a_turning_ellipse_asks_for_a_build_before_its_box_meets_another() {
        let mut scene = Scene::new(Frame::open_box(10.0, 10.0).unwrap(), Vec2::zeros()).unwrap();
        scene
            .add_ellipse(Point::new(1.0, 1.0), 0.3, 0.05, 0.0, 1.0)
            .unwrap();
        scene
            .add_circle(Point::new(1.25, 1.05 + 0.011 + 0.05), 0.05, 1.0)
            .unwrap();
        let mut particles = scene.particles;
        let box_of = |p: &Particle| p.shape.as_shape().aabb(&p.pose);
        let boxes: Vec<Aabb2> = particles.iter().map(box_of).collect();
        assert!(!boxes[0].inflated(SKIN).intersects(&boxes[1]), "listed");
        let mut travel = ListTravel::new(2, true, &particles);
        travel.built(SKIN, &particles, &boxes, &[], |_, _| false, false);
        let (mut asked, mut met) = (None, None);
        for step in 1..=500 {
            particles[0].pose.angle += 0.001;
            if asked.is_none() && !travel.relative_holds(&particles, false) {
                asked = Some(step);
            }
            if met.is_none() && box_of(&particles[0]).intersects(&box_of(&particles[1])) {
                met = Some(step);
            }
        }
        let (asked, met) = (asked.unwrap(), met.unwrap());
        println!("a build asked at step {asked}, the boxes meet at step {met}");
        assert!(asked < met, "asked at {asked}, met at {met}");
    }
}
