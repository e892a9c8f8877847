//! Checks of a DEM set-up that concern the law and the shapes together.

use super::error::ExplicitError;
use crate::broad_phase::CellGrid;
use crate::error::{DismechError, Result};
use crate::law::{BoundedStiffness, ContactInput, ContactLaw, PairProperties};
use crate::math::Aabb2;
use crate::math::Pose2;
use crate::query::manifold::dispatch::contact_manifold_2d;
use crate::query::ContactGeometry;
use crate::scene::Scene;
use crate::shape::{crossing_depth, AnyShape2};

/// Refuses a start where a candidate pair of particles (from the broad
/// phase `grid` over the particles' `boxes`, visited one by one so that a
/// dense cluster is refused at its first pair rather than after all its
/// pairs are built; polygons also when their edges cross with no vertex
/// inside the other, [`crossing_depth`]) or a particle and a wall overlap
/// by more than
/// `tolerance` at their deepest point; `manifold` is scratch space.
/// Returns the largest overlap found (within the tolerance).
pub(crate) fn check_initial_overlaps(
    scene: &Scene,
    grid: &mut CellGrid,
    boxes: &[Aabb2],
    tolerance: f64,
    manifold: &mut Vec<ContactGeometry>,
) -> Result<f64> {
    let deepest = |points: &[ContactGeometry]| points.iter().map(|g| g.overlap).fold(0.0, f64::max);
    let mut largest = 0.0f64;
    grid.try_for_each_pair(boxes, 0.0, |a, b| {
        let (pa, pb) = (&scene.particles[a], &scene.particles[b]);
        // Prescribed particles may overlap each other (a rough base of
        // fixed discs): they make no pair.
        if pa.is_prescribed() && pb.is_prescribed() {
            return Ok(());
        }
        manifold.clear();
        contact_manifold_2d(&pa.shape, &pa.pose, &pb.shape, &pb.pose, manifold)?;
        let mut overlap = deepest(manifold);
        // Polygons may cross with no vertex inside the other.
        if overlap <= tolerance {
            if let (AnyShape2::Polygon(qa), AnyShape2::Polygon(qb)) = (&pa.shape, &pb.shape) {
                let world = |q: &crate::shape::Polygon, pose: &Pose2| -> Vec<crate::math::Point> {
                    q.vertices()
                        .iter()
                        .map(|v| pose.transform_point(v))
                        .collect()
                };
                if let Some(depth) = crossing_depth(&world(qa, &pa.pose), &world(qb, &pb.pose)) {
                    overlap = overlap.max(depth);
                }
            }
        }
        largest = largest.max(overlap);
        if overlap > tolerance {
            return Err(DismechError::Explicit(ExplicitError::InitialOverlap {
                a,
                b,
                overlap,
                tolerance,
            }));
        }
        Ok(())
    })?;
    for (i, p) in scene
        .particles
        .iter()
        .enumerate()
        .filter(|(_, p)| !p.is_prescribed())
    {
        for (w, wall) in scene.frame.walls().iter().enumerate() {
            let shape = AnyShape2::Segment(*wall);
            manifold.clear();
            contact_manifold_2d(&p.shape, &p.pose, &shape, &Pose2::default(), manifold)?;
            let penetration = deepest(manifold);
            largest = largest.max(penetration);
            if penetration > tolerance {
                return Err(DismechError::Explicit(ExplicitError::StartsInsideWall {
                    body: i,
                    wall: w,
                    penetration,
                    tolerance,
                    clockwise_frame: scene.frame.runs_clockwise(),
                }));
            }
        }
    }
    Ok(largest)
}

/// Refuses a particle whose state or mass properties cannot start a run:
/// a pose, velocity or external force that is not finite (a NaN written
/// into a public field would otherwise surface as an energy blow-up), or a
/// mass or moment of inertia that is not finite and positive (a radius of
/// 1e-200 m has a mass that underflows to zero), unless both are `+∞` (a
/// prescribed particle).
pub(crate) fn check_particles(scene: &Scene) -> Result<()> {
    for (i, p) in scene.particles.iter().enumerate() {
        let values = [
            ("position x", p.pose.position.x, true),
            ("position y", p.pose.position.y, true),
            ("angle", p.pose.angle, true),
            ("velocity x", p.velocity.x, true),
            ("velocity y", p.velocity.y, true),
            ("angular velocity", p.angular_velocity, true),
            ("external force x", p.external_force.x, true),
            ("external force y", p.external_force.y, true),
            ("mass", p.mass, false),
            ("moment of inertia", p.inertia, false),
        ];
        // A prescribed particle has infinite mass and inertia, both.
        let prescribed = p.mass == f64::INFINITY && p.inertia == f64::INFINITY;
        for (name, value, may_be_zero) in values {
            let requirement = if value == f64::INFINITY && !may_be_zero && !prescribed {
                "must be finite (or infinite together with the moment of inertia or the mass, for a prescribed particle: see Particle::prescribed)"
            } else if value == f64::INFINITY && !may_be_zero {
                continue;
            } else if !value.is_finite() {
                "must be finite"
            } else if !may_be_zero && value == 0.0 {
                "must be > 0 (a particle this small or this light has a mass that rounds to zero: scale the model's units)"
            } else if !may_be_zero && value < 0.0 {
                "must be > 0"
            } else {
                continue;
            };
            return Err(DismechError::Explicit(ExplicitError::InvalidParticle {
                particle: i,
                name,
                value,
                requirement,
            }));
        }
    }
    Ok(())
}

/// The smallest bounding radius of the scene's particles (infinite for a
/// scene without particles).
pub(crate) fn smallest_bounding_radius(scene: &Scene) -> f64 {
    scene
        .particles
        .iter()
        .map(|p| p.shape.as_shape().bounding_radius())
        .fold(f64::INFINITY, f64::min)
}

/// The most pairs a neighbour list may hold per particle (and 10 000 in
/// all for a small scene): a packed disc has about 6 neighbours and a skin
/// of a few radii lists some tens; a list of hundreds per particle is a
/// skin as large as the scene (every pair listed, n² of them, 19 GB for
/// 20 000 discs), refused before it is built.
pub const MAX_LISTED_PAIRS_PER_PARTICLE: usize = 256;

/// Refuse a fixed neighbour skin `skin` that would list more pairs than
/// the budget ([`MAX_LISTED_PAIRS_PER_PARTICLE`] per particle): the
/// candidate pairs of the particles' boxes widened by the skin are counted
/// (the count stops at the budget, so this costs at most the budget's
/// pairs), `pair_bytes` a listed pair's size for the message.
pub(crate) fn check_neighbour_budget(
    scene: &Scene,
    grid: &mut CellGrid,
    skin: f64,
    pair_bytes: usize,
) -> Result<()> {
    let n = scene.particles.len();
    let budget = (MAX_LISTED_PAIRS_PER_PARTICLE * n).max(10_000);
    let boxes: Vec<Aabb2> = scene
        .particles
        .iter()
        .map(|p| p.shape.as_shape().aabb(&p.pose))
        .collect();
    let mut pairs = 0usize;
    let over = grid.try_for_each_pair(&boxes, skin, |_, _| {
        pairs += 1;
        if pairs > budget {
            Err(())
        } else {
            Ok(())
        }
    });
    if over.is_ok() {
        return Ok(());
    }
    // Every pair, where the skin spans the scene; at least the budget.
    let all = (n as u128) * (n as u128 - 1) / 2;
    let smallest = smallest_bounding_radius(scene);
    Err(DismechError::Explicit(ExplicitError::OutOfMemory {
        what: super::MemoryUse::NeighbourList {
            skin,
            particles: n,
            budget,
            pairs: all,
        },
        bytes: all * pair_bytes as u128,
        advice: super::MemoryAdvice::SkinTooWide {
            smallest_radius: smallest,
        },
    }))
}

/// The geometry of a polygon's contact point: a vertex (radius of curvature
/// 0) on a flat edge or wall (infinite radius), contact width 0.
fn vertex_on_flat(mass: f64) -> PairProperties {
    PairProperties {
        curvature_radius_a: 0.0,
        curvature_radius_b: f64::INFINITY,
        width: 0.0,
        mass_a: mass,
        mass_b: mass,
    }
}

/// Whether the stiffness bound of `law` at `pair` and `overlap` is finite.
pub(crate) fn finite_bound<L: BoundedStiffness<2>>(
    law: &L,
    pair: &PairProperties,
    overlap: f64,
) -> bool {
    let b = law.stiffness_bound(pair, overlap);
    [b.normal, b.shear, b.normal_damping, b.shear_damping]
        .iter()
        .all(|v| v.is_finite())
}

/// Refuses a law that gives no finite force or stiffness at a polygon's
/// vertex-on-edge contact.
///
/// Paper 000's eq. (19) takes the stiffness from the radii of curvature and
/// the contact width, `k_n ∝ 1 / (2/3 + ln(4 r1/B) + ln(4 r2/B))`; at a
/// vertex `r = 0`, on an edge `r = ∞` and `B = 0`, and the formula has no
/// value (a corner on a face is not a Hertz-like contact of two curved
/// surfaces). Rather than invent radii, polygons need a law whose stiffness
/// does not depend on them, such as a constant `k_n`. The law is probed with
/// a small first loading of such a contact, and its stiffness bound with the
/// same geometry when the law has one (`bound_finite` says whether the
/// bound at a pair and overlap is finite; pass `|_, _| true` for a law
/// without a bound).
/// A prescribed polygon is probed with the mass of the lightest free
/// particle, the body its vertices will meet.
pub(crate) fn check_law_for_polygons<L: ContactLaw<2>>(
    scene: &Scene,
    law: &L,
    dt: f64,
    bound_finite: impl Fn(&PairProperties, f64) -> bool,
) -> Result<()> {
    let lightest_free = scene
        .particles
        .iter()
        .filter(|p| !p.is_prescribed())
        .map(|p| p.mass)
        .fold(f64::INFINITY, f64::min);
    for (body, p) in scene.particles.iter().enumerate() {
        let AnyShape2::Polygon(polygon) = &p.shape else {
            continue;
        };
        let mass = if p.is_prescribed() {
            if lightest_free.is_finite() {
                lightest_free
            } else {
                continue;
            }
        } else {
            p.mass
        };
        let pair = vertex_on_flat(mass);
        let overlap = 1e-6 * crate::shape::Shape2::bounding_radius(polygon);
        let bound_finite = bound_finite(&pair, overlap);
        let response = law.evaluate(
            &ContactInput {
                overlap,
                increment: [overlap, 0.0].into(),
                dt,
                is_new: true,
                pair,
                rotation: 0.0,
            },
            &L::State::default(),
        );
        let response_finite = response
            .force
            .iter()
            .chain(response.spring_force.iter())
            .all(|v| v.is_finite());
        if !(bound_finite && response_finite) {
            return Err(DismechError::Explicit(ExplicitError::LawUndefinedForShape {
                body,
                shape: "polygon",
                contact: "a vertex on an edge (radii of curvature 0 and infinite, contact width 0)",
                advice: "a stiffness from the radii of curvature (paper 000 eq. 19) has no value there: use a constant normal stiffness",
            }));
        }
    }
    Ok(())
}
