//! From a DEM packing to a limit analysis: the composition that turns a
//! settled assembly (positions, contacts, weights) into the rigid-plastic
//! LP of the same assembly.

use super::model::{LimitModel, Partner};
use crate::error::{require_positive, DismechError, Result};
use crate::explicit::{ContactRecord, ContactTarget};
use crate::law::RigidPlastic;
use crate::scene::Scene;
use crate::shape::AnyShape2;

/// How a packing becomes a limit-analysis model.
#[derive(Debug, Clone, PartialEq)]
pub struct PackingLimitSettings {
    /// Whether the elements may rotate.
    pub rolling: bool,
    /// Law of particle–particle contacts.
    pub contact_law: RigidPlastic,
    /// Law of particle–wall contacts.
    pub wall_law: RigidPlastic,
    /// Law of the contacts with the driven wall.
    pub plate_law: RigidPlastic,
    /// Name of the frame wall that becomes the loading plate, driven along
    /// its inner normal at unit speed.
    pub plate_wall: String,
    /// Include the particles' weights (from the scene's gravity) as known
    /// loads.
    pub self_weight: bool,
}

/// Build the limit-analysis model of a packing: one rigid element per
/// particle (of its own shape and pose), one support per frame wall, one
/// contact per DEM contact point of the last step (every point of a
/// manifold). Contacts between circles (and of circles with walls) take
/// their geometry from the circles and must touch within the largest DEM
/// overlap; contacts of other shapes take the DEM's contact point and
/// normal.
///
/// # Errors
/// [`DismechError::InvalidParameter`] when `settings.plate_wall` names no
/// wall of the frame, when the scene has a prescribed particle (infinite
/// mass: it has no counterpart here), or a contact record has a point that is not finite
/// or a normal of zero length; [`DismechError::NoSuchBody`] for a record
/// naming a particle the scene does not have, and
/// [`DismechError::DegenerateWall`] for one naming a wall the frame does
/// not have; [`super::LimitError::DuplicateBody`] for two particles whose
/// centres coincide ([`LimitModel::add_shape`]);
/// [`super::LimitError::SelfContact`] for a record of a particle with itself;
/// [`super::LimitError::ContactNotTouching`] for two circles, or a circle and a
/// wall, farther apart than the tolerance (1.01 times the largest overlap
/// of the records), or a record of another shape with a wall whose normal
/// does not point into the wall; [`super::LimitError::DuplicateContact`] for a
/// record that repeats one of its pair (a second record of two circles, or
/// of a circle and a wall, or one at a point of the pair already taken),
/// as [`LimitModel::add_contact`] and [`LimitModel::add_contact_at`].
pub fn model_from_packing(
    scene: &Scene,
    contacts: &[ContactRecord],
    settings: &PackingLimitSettings,
) -> Result<LimitModel> {
    let plate =
        scene
            .frame
            .index_of(&settings.plate_wall)
            .ok_or(DismechError::InvalidParameter {
                name: "plate wall (no frame wall has that name)",
                value: f64::NAN,
                requirement: "must name a wall of the frame, e.g. `left`",
            })?;
    let count = scene.particles.len();
    let particle = |i: usize| {
        scene
            .particles
            .get(i)
            .ok_or(DismechError::NoSuchBody { index: i, count })
    };
    let wall = |w: usize| {
        scene
            .frame
            .walls()
            .get(w)
            .ok_or(DismechError::DegenerateWall {
                wall: w,
                reason: "a contact names a wall the frame does not have",
            })
    };
    let mut largest_overlap = 0.0f64;
    for c in contacts {
        let a = particle(c.particle)?;
        let ra = a.shape.as_shape().bounding_radius();
        let overlap = match c.target {
            ContactTarget::Particle(j) => {
                let b = particle(j)?;
                ra + b.shape.as_shape().bounding_radius()
                    - (b.pose.position - a.pose.position).norm()
            }
            ContactTarget::Wall(w) => {
                let wall = wall(w)?;
                ra - (a.pose.position - wall.start).dot(&wall.inner_normal())
            }
        };
        largest_overlap = largest_overlap.max(overlap);
    }
    // A prescribed particle has no counterpart here: the limit model's
    // fixed boundaries are straight supports.
    if let Some(i) = scene.particles.iter().position(|p| p.is_prescribed()) {
        return Err(DismechError::InvalidParameter {
            name: "mass of a packing particle (prescribed)",
            value: scene.particles[i].mass,
            requirement: "must be finite: a prescribed (fixed or driven) particle has no counterpart in the limit model, whose fixed boundaries are the frame's walls as supports",
        });
    }
    let mut model = LimitModel::new(require_positive(
        "contact tolerance",
        1.01 * largest_overlap + 1e-12,
    )?)?;
    for p in &scene.particles {
        let i = match &p.shape {
            AnyShape2::Circle(circle) => {
                model.add_body(p.pose.position, circle.radius(), settings.rolling)?
            }
            other => model.add_shape(other.clone(), p.pose, settings.rolling)?,
        };
        if settings.self_weight {
            model.set_load(i, scene.gravity * p.mass)?;
        }
    }
    for (w, segment) in scene.frame.walls().iter().enumerate() {
        let normal = segment.inner_normal();
        let velocity = if w == plate { normal } else { normal * 0.0 };
        model.add_support(
            scene.frame.name(w).unwrap_or("wall"),
            segment.start,
            normal,
            velocity,
        )?;
    }
    let is_circle = |i: usize| matches!(scene.particles[i].shape, AnyShape2::Circle(_));
    for c in contacts {
        let (partner, law, circles) = match c.target {
            ContactTarget::Particle(j) => (
                Partner::Body(j),
                settings.contact_law,
                is_circle(c.particle) && is_circle(j),
            ),
            ContactTarget::Wall(w) if w == plate => (
                Partner::Support(w),
                settings.plate_law,
                is_circle(c.particle),
            ),
            ContactTarget::Wall(w) => (
                Partner::Support(w),
                settings.wall_law,
                is_circle(c.particle),
            ),
        };
        if circles {
            model.add_contact(c.particle, partner, law)?;
        } else {
            // A wall contact's point lies half the overlap inside the wall:
            // put it on the wall line, where the support is.
            let point = match c.target {
                ContactTarget::Wall(w) => {
                    let segment = wall(w)?;
                    let n = segment.inner_normal();
                    c.point - n * (c.point - segment.start).dot(&n)
                }
                ContactTarget::Particle(_) => c.point,
            };
            model.add_contact_at(c.particle, partner, law, point, c.normal)?;
        }
    }
    Ok(model)
}
