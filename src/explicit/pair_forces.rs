//! The first half of a step: the contact points of each listed pair (the
//! geometry, the relative motion at each point and the law, with the
//! point's history taken from the pair itself), summed per block of
//! particles into their forces. The second half, moving the particles, is
//! in `motion.rs`.

use super::driver::ContactTarget;
use super::keys::PointKey;
use super::neighbours::{
    crosses_blocks, BlockSlots, PairForce, PairPoints, PairSlot, PointContact,
};
use super::pair_bodies::PairBody;
use crate::error::Result;
use crate::law::{ContactInput, ContactLaw, PairProperties};
use crate::math::{Aabb2, Point, Pose2, Vec2};
use crate::query::manifold::circle_circle::contact_circles;
use crate::query::manifold::circle_segment::contact_circle_segment;
use crate::query::manifold::dispatch::{contact_2d_near, contact_manifold_2d};
use crate::query::manifold::ellipse::{contact_ellipse_ellipse_oriented, OrientedEllipse};
use crate::query::{relative_increment, ContactGeometry, ContactShape};
use crate::scene::Particle;
use crate::shape::{AnyShape2, Segment};
use nalgebra::UnitComplex;

/// The force on B, the moment about A's centre and the moment about B's
/// centre of each contact point of a pair, in the manifold's order, from
/// its summary (a pair of one point) or its points and their `moments`
/// (about A's centre and B's: a caller that reads only one of them may
/// give NaN for the other).
#[inline]
pub(super) fn for_each_point<'a, S: 'a>(
    pair: &PairForce,
    points: impl FnOnce() -> &'a [PointContact<S>],
    moments: impl Fn(&PointContact<S>) -> (f64, f64),
    mut add: impl FnMut(Vec2, f64, f64),
) {
    match pair.count {
        0 => {}
        1 => add(pair.force_on_b, pair.moment_a, pair.moment_b),
        _ => {
            for p in points() {
                let (moment_a, moment_b) = moments(p);
                add(p.force_on_b, moment_a, moment_b);
            }
        }
    }
}

/// Add a contact point's force on B and its moment about B's centre to
/// B's sum `[f_x, f_y, m]`.
#[inline]
pub(super) fn add_action(sum: &mut [f64], force_on_b: Vec2, moment: f64) {
    sum[0] += force_on_b.x;
    sum[1] += force_on_b.y;
    sum[2] += moment;
}

/// Add the reaction of a contact point's force on B, `−f`, and its moment
/// about A's centre to A's sum (`x − f` rounds as `x + (−f)`).
#[inline]
fn add_reaction(sum: &mut [f64], force_on_b: Vec2, moment: f64) {
    sum[0] -= force_on_b.x;
    sum[1] -= force_on_b.y;
    sum[2] += moment;
}

/// What every pair of one step reads: the law, the step and the bodies.
pub(super) struct PairContext<'a, L> {
    pub law: &'a L,
    pub dt: f64,
    pub particles: &'a [Particle],
    /// Each particle's record (centre, increment of the previous step,
    /// mass, circle): [`PairBody`].
    pub bodies: &'a [PairBody],
    /// Each ellipse's rotation (see the driver's field).
    pub rotations: &'a [UnitComplex<f64>],
    pub walls: &'a [Segment],
    /// The walls' boxes.
    pub wall_boxes: &'a [Aabb2],
    /// Whether the law reads the width and radii of curvature (a circle
    /// pair computes its width, two ellipses their radii, only then).
    pub contact_shape: ContactShape,
}

/// B's centre, its increment of the last step and its mass; `None` for a
/// wall, whose centre is taken at each contact point (it does not move).
type Other = Option<(Point, (Vec2, f64), f64)>;

impl<L: ContactLaw<2>> PairContext<'_, L> {
    /// Block `block`'s pairs evaluated in the list's order and summed
    /// into `force` (its particles' `[f_x, f_y, m]`, which start from
    /// their weight and external force `applied`); a pair whose B is in a
    /// later block keeps its summary for B instead.
    ///
    /// # Errors
    /// [`DismechError::UnsupportedPair`](crate::error::DismechError::UnsupportedPair)
    /// from the first pair whose shapes have no contact routine (two
    /// segments), as [`Self::evaluate`].
    pub fn evaluate_block(
        &self,
        applied: &[Vec2],
        manifold: &mut Vec<ContactGeometry>,
        block: BlockSlots<'_, L::State>,
        force: &mut [f64],
    ) -> Result<()> {
        for (sum, weight) in force.chunks_exact_mut(3).zip(&applied[block.start..]) {
            sum.copy_from_slice(&[weight.x, weight.y, 0.0]);
        }
        let local = |i: usize| 3 * (i - block.start);
        let mut cross_out = block.cross_out.iter_mut();
        for slot in block.pairs.iter_mut() {
            let mut pair = PairForce::default();
            self.evaluate(slot, &mut pair, manifold)?;
            // (The block's particle pairs, never a wall.)
            let ContactTarget::Particle(b) = slot.target() else {
                continue;
            };
            let a = local(slot.a());
            // B's entries when B is in the block; a pair across blocks
            // keeps its summary for B instead, in the build's order of
            // those pairs.
            let b_local = if crosses_blocks(slot.a(), b) {
                let summary = cross_out.next();
                debug_assert!(summary.is_some(), "a crossing the build did not count");
                if let Some(summary) = summary {
                    *summary = pair;
                }
                None
            } else {
                Some(local(b))
            };
            for_each_point(
                &pair,
                || &slot.points,
                |point| {
                    let rolling = self.law.moment(&point.state);
                    (
                        point.moment_a(&self.bodies[slot.a()].centre, rolling),
                        point.moment_b(&self.bodies[b].centre, rolling),
                    )
                },
                |force_on_b, moment_a, moment_b| {
                    add_reaction(&mut force[a..a + 3], force_on_b, moment_a);
                    if let Some(b) = b_local {
                        add_action(&mut force[b..b + 3], force_on_b, moment_b);
                    }
                },
            );
        }
        debug_assert!(cross_out.next().is_none(), "a crossing not evaluated");
        for slot in block.walls.iter_mut() {
            let mut pair = PairForce::default();
            self.evaluate(slot, &mut pair, manifold)?;
            let a = local(slot.a());
            for_each_point(
                &pair,
                || &slot.points,
                |point| {
                    let rolling = self.law.moment(&point.state);
                    (point.moment_a(&self.bodies[slot.a()].centre, rolling), 0.0)
                },
                |force_on_b, moment_a, _| {
                    add_reaction(&mut force[a..a + 3], force_on_b, moment_a);
                },
            );
        }
        Ok(())
    }

    /// The pair's contact points now, each continuing the history of the
    /// point with the same features at the last step, and the pair's force
    /// summary; `manifold` is scratch space for pairs with a polygon,
    /// which may touch at several points (the others touch at one at most
    /// and skip it; circles against circles and walls, the commonest
    /// pairs, call their geometry directly rather than through the
    /// dispatch (two circles from their [`PairBody`] records alone), and
    /// so do two ellipses, with their rotations kept by the driver). A
    /// pair of ellipses, or of a circle and an ellipse, seeks its contact
    /// about its last contact point first.
    ///
    /// # Errors
    /// [`DismechError::UnsupportedPair`](crate::error::DismechError::UnsupportedPair)
    /// from the pair dispatch ([`contact_2d_near`], or the manifold of a
    /// pair with a polygon) for shapes it has no routine for (two
    /// segments).
    #[inline(always)]
    pub fn evaluate(
        &self,
        slot: &mut PairSlot<L::State>,
        force: &mut PairForce,
        manifold: &mut Vec<ContactGeometry>,
    ) -> Result<()> {
        // (A reference only: a pair of two circles reads no particle.)
        let pa = &self.particles[slot.a()];
        let wall;
        let (shape_b, pose_b, other): (&AnyShape2, &Pose2, Other) = match slot.target() {
            ContactTarget::Particle(b) => {
                let body_b = &self.bodies[b];
                let other = Some((body_b.centre, body_b.increment, body_b.mass));
                // Two circles: from their records alone.
                let body_a = &self.bodies[slot.a()];
                if let (Some(ca), Some(cb)) = (&body_a.circle, &body_b.circle) {
                    let single = contact_circles(
                        ca.radius(),
                        &body_a.centre,
                        cb.radius(),
                        &body_b.centre,
                        self.contact_shape,
                    );
                    *force = self.update_single(slot, single, other);
                    return Ok(());
                }
                let pb = &self.particles[b];
                if let (AnyShape2::Ellipse(ea), AnyShape2::Ellipse(eb)) = (&pa.shape, &pb.shape) {
                    let single = contact_ellipse_ellipse_oriented(
                        OrientedEllipse {
                            shape: ea,
                            pose: &pa.pose,
                            rotation: &self.rotations[slot.a()],
                        },
                        OrientedEllipse {
                            shape: eb,
                            pose: &pb.pose,
                            rotation: &self.rotations[b],
                        },
                        slot.points.first().map(|p| &p.point),
                        self.contact_shape,
                    );
                    *force = self.update_single(slot, single, other);
                    return Ok(());
                }
                (&pb.shape, &pb.pose, other)
            }
            ContactTarget::Wall(w) => {
                if !pa
                    .shape
                    .as_shape()
                    .aabb(&pa.pose)
                    .intersects(&self.wall_boxes[w])
                {
                    slot.points.clear();
                    *force = PairForce::default();
                    return Ok(());
                }
                wall = AnyShape2::Segment(self.walls[w]);
                (&wall, &WALL_POSE, None)
            }
        };
        let single = match (&pa.shape, shape_b) {
            (AnyShape2::Circle(c), AnyShape2::Segment(s)) => contact_circle_segment(c, &pa.pose, s),
            (AnyShape2::Polygon(_), _) | (_, AnyShape2::Polygon(_)) => {
                *force = self.evaluate_manifold(slot, manifold, shape_b, pose_b, other)?;
                return Ok(());
            }
            _ => contact_2d_near(
                &pa.shape,
                &pa.pose,
                shape_b,
                pose_b,
                slot.points.first().map(|p| &p.point),
            )?,
        };
        *force = self.update_single(slot, single, other);
        Ok(())
    }

    /// The pair's point from its geometry of one point at most, updated in
    /// place, and its force summary.
    #[inline(always)]
    fn update_single(
        &self,
        slot: &mut PairSlot<L::State>,
        single: Option<ContactGeometry>,
        other: Other,
    ) -> PairForce {
        let Some(geometry) = single else {
            slot.points.clear();
            return PairForce::default();
        };
        let previous = slot
            .points
            .first()
            .filter(|p| p.key.has_features(&geometry.features))
            .map(|p| (p.state.clone(), p.overlap));
        let (point, force) = self.point_contact(slot.a(), &geometry, other, previous);
        if slot.points.len() == 1 {
            slot.points[0] = point;
        } else {
            slot.points.clear();
            slot.points.push(point);
        }
        force
    }

    /// [`Self::evaluate`] for a pair with a polygon: every point of its
    /// manifold.
    #[inline(never)]
    fn evaluate_manifold(
        &self,
        slot: &mut PairSlot<L::State>,
        manifold: &mut Vec<ContactGeometry>,
        shape_b: &AnyShape2,
        pose_b: &Pose2,
        other: Other,
    ) -> Result<PairForce> {
        let pa = &self.particles[slot.a()];
        manifold.clear();
        contact_manifold_2d(&pa.shape, &pa.pose, shape_b, pose_b, manifold)?;
        let mut points = PairPoints::new();
        let mut first = PairForce::default();
        for geometry in manifold.iter() {
            let previous = slot
                .points
                .iter()
                .find(|p| p.key.has_features(&geometry.features))
                .map(|p| (p.state.clone(), p.overlap));
            let (point, force) = self.point_contact(slot.a(), geometry, other, previous);
            if points.is_empty() {
                first = force;
            }
            points.push(point);
        }
        first.count = points.len();
        slot.points = points;
        Ok(first)
    }

    /// One contact point of the pair (its relative motion, the law, and
    /// the force on B), and its summary as a pair's first point (with the
    /// moments on the two bodies).
    #[inline]
    fn point_contact(
        &self,
        a: usize,
        geometry: &ContactGeometry,
        other: Other,
        previous: Option<(L::State, f64)>,
    ) -> (PointContact<L::State>, PairForce) {
        let body_a = &self.bodies[a];
        let increment_a = body_a.increment;
        let (centre_b, increment_b, mass_b) =
            other.unwrap_or((geometry.point, (Vec2::zeros(), 0.0), f64::INFINITY));
        let mut du = relative_increment(
            geometry,
            &body_a.centre,
            (&increment_a.0, increment_a.1),
            &centre_b,
            (&increment_b.0, increment_b.1),
        );
        // The normal increment is the change of the overlap itself: exact
        // for any shape. (The relative velocity at the chord midpoint
        // misses the motion of the deepest point when a non-circular body
        // rolls, and an incremental spring fed with it gains energy.)
        if let Some((_, previous_overlap)) = previous {
            du[0] = geometry.overlap - previous_overlap;
        }
        let input = ContactInput {
            overlap: geometry.overlap,
            increment: du.into(),
            dt: self.dt,
            is_new: previous.is_none(),
            pair: PairProperties {
                curvature_radius_a: geometry.curvature_radius_a,
                curvature_radius_b: geometry.curvature_radius_b,
                width: geometry.width,
                mass_a: body_a.mass,
                mass_b,
            },
            rotation: increment_a.1 - increment_b.1,
        };
        let response = self.law.evaluate(
            &input,
            &previous.map(|(state, _)| state).unwrap_or_default(),
        );
        let force_on_b =
            geometry.normal * response.force[0] - geometry.tangent() * response.force[1];
        let point = PointContact {
            key: PointKey::new(&geometry.features, response.regime),
            state: response.state,
            overlap: geometry.overlap,
            point: geometry.point,
            normal: geometry.normal,
            force_on_b,
        };
        let rolling = self.law.moment(&point.state);
        let moment_a = point.moment_a(&body_a.centre, rolling);
        let moment_b = match other {
            Some(_) => point.moment_b(&centre_b, rolling),
            None => 0.0,
        };
        (
            point,
            PairForce {
                force_on_b,
                moment_a,
                moment_b,
                count: 1,
            },
        )
    }
}

/// The frame's walls are given in world coordinates.
const WALL_POSE: Pose2 = Pose2 {
    position: Point::new(0.0, 0.0),
    angle: 0.0,
};
