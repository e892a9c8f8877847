//! The second half of a step, per block of particles: the forces of the
//! pairs that cross into the block added, then each particle's `M a = f`
//! and its integrator's step.

use nalgebra::UnitComplex;

use super::neighbours::{NeighbourList, BLOCK};
use super::pair_bodies::PairBody;
use super::pair_forces::{add_action, for_each_point};
use crate::integrate::ExplicitIntegrator;
use crate::math::{Aabb2, Vec2};
use crate::scene::Particle;
use crate::shape::AnyShape2;

/// What the per-particle update of a step found: the largest travel since
/// the neighbour list was built, and the first particle whose force, or
/// whose new position or velocity, went wrong.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct StepCheck {
    pub travel: f64,
    pub bad_force: Option<usize>,
    pub bad_motion: Option<usize>,
}

impl StepCheck {
    /// Both parts' findings (the order does not matter: the largest
    /// travel, the first particles).
    #[inline]
    pub fn combine(self, other: Self) -> Self {
        let first = |x: Option<usize>, y: Option<usize>| match (x, y) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        // A travel that is not a number stays so (`max` would drop it).
        let travel = if self.travel.is_nan() || other.travel.is_nan() {
            f64::NAN
        } else {
            self.travel.max(other.travel)
        };
        Self {
            travel,
            bad_force: first(self.bad_force, other.bad_force),
            bad_motion: first(self.bad_motion, other.bad_motion),
        }
    }
}

/// What moving a block of particles reads besides the block.
pub(super) struct BlockMotion<'a, I> {
    pub integrator: &'a I,
    /// The diagonal mass, three entries a particle.
    pub mass: &'a [f64],
    /// Where a particle's centre must stay (see the driver's field).
    pub reach: Aabb2,
    pub dt: f64,
}

impl<I: ExplicitIntegrator> BlockMotion<'_, I> {
    /// Block `k`: the pairs that cross into it from earlier blocks, added
    /// to their B in the list's order; then per particle, when its force
    /// is finite, its velocities and position from `M a = f` (the
    /// diagonal mass: `a = f / m` per DOF, as
    /// [`crate::linsolve::solve_lumped_into`], whose checks of the masses
    /// were made at the start), an ellipse's rotation at its new angle
    /// (`rotations` is empty in a scene without ellipses), and how far
    /// its boundary has moved since the list was built. Every pair that
    /// reads the block's particles must have been evaluated. `rolling`
    /// reads a contact's rolling moment from its state
    /// ([`crate::law::ContactLaw::moment`]).
    #[allow(clippy::too_many_arguments)]
    pub fn block<S>(
        &self,
        neighbours: &NeighbourList<S>,
        rolling: impl Fn(&S) -> f64,
        k: usize,
        force: &mut [f64],
        particles: &mut [Particle],
        bodies: &mut [PairBody],
        rotations: &mut [UnitComplex<f64>],
    ) -> StepCheck
    where
        S: Clone + Send + Sync,
    {
        debug_assert!(
            force.len() == 3 * particles.len()
                && bodies.len() == particles.len()
                && (rotations.is_empty() || rotations.len() == particles.len()),
            "a block's forces, pair records or rotations do not match its particles"
        );
        let start = k * BLOCK;
        for cross in neighbours.cross_in(k) {
            let b = 3 * (cross.b - start);
            let points = || neighbours.slots[cross.slot].points.as_slice();
            // B, in this block, has not moved yet.
            let centre_b = &particles[cross.b - start].pose.position;
            for_each_point(
                neighbours.cross_force(cross),
                points,
                // (A's moment went to A in A's block: not read here.)
                |point| (f64::NAN, point.moment_b(centre_b, rolling(&point.state))),
                |force_on_b, _, moment_b| add_action(&mut force[b..b + 3], force_on_b, moment_b),
            );
        }
        let mut check = StepCheck::default();
        for (offset, ((force, p), body)) in force
            .chunks_exact_mut(3)
            .zip(particles.iter_mut())
            .zip(bodies.iter_mut())
            .enumerate()
        {
            let i = start + offset;
            if !force.iter().all(|f| f.is_finite()) {
                check = check.combine(StepCheck {
                    travel: 0.0,
                    bad_force: Some(i),
                    bad_motion: None,
                });
                continue;
            }
            let mut dx = [0.0; 3];
            let mut velocity = [p.velocity.x, p.velocity.y, p.angular_velocity];
            for d in 0..3 {
                let acceleration = force[d] / self.mass[3 * i + d];
                dx[d] = self
                    .integrator
                    .step(self.dt, acceleration, &mut velocity[d]);
            }
            p.velocity = Vec2::new(velocity[0], velocity[1]);
            p.angular_velocity = velocity[2];
            p.pose.position += Vec2::new(dx[0], dx[1]);
            p.pose.angle += dx[2];
            body.centre = p.pose.position;
            body.increment = (Vec2::new(dx[0], dx[1]), dx[2]);
            if let (Some(rotation), AnyShape2::Ellipse(_)) = (rotations.get_mut(offset), &p.shape) {
                *rotation = UnitComplex::new(p.pose.angle);
            }
            let finite = dx.iter().all(|v| v.is_finite()) && velocity.iter().all(|v| v.is_finite());
            let bad_motion = !(finite && self.reach.contains(&p.pose.position));
            check = check.combine(StepCheck {
                travel: neighbours.travel(i, p),
                bad_force: None,
                bad_motion: bad_motion.then_some(i),
            });
        }
        check
    }
}
