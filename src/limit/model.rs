//! The data of a limit analysis: rigid bodies of any shape, straight
//! supports, contacts with a strength, and what drives the collapse (a
//! moving support, a live load whose multiplier is sought, or the dead
//! loads themselves, whose multiplier is sought: [`LoadDriver`]).
//!
//! Nothing may be declared twice, since the LP would count it twice (a
//! body's load and its contacts' strength, a contact's strength). Two
//! points *coincide* when they are closer than the smaller of the model's
//! contact tolerance and [`COINCIDENT_FRACTION`] of the bounding radius of
//! the smaller body concerned (the contact tolerance alone can be loose,
//! e.g. the overlap of bounding circles for a DEM packing of ellipses).
//!
//! * **duplicate bodies**: two bodies whose reference points coincide.
//!   Rigid bodies do not overlap, so two of them cannot share a point;
//!   this covers the same body declared twice, whatever its shape.
//! * **duplicate contacts**: two contacts of the same pair (element with
//!   element in either order, or element with support) whose points
//!   coincide; and any second contact of a pair declared from circle
//!   geometry ([`LimitModel::add_contact`]), since two circles, or a circle
//!   and a line, touch at one point. Several points of one pair given
//!   explicitly (the corners of a face on a floor) are distinct contacts.
//!
//! Both are refused when declared ([`LimitError::DuplicateBody`],
//! [`LimitError::DuplicateContact`]), found through a hash of the
//! reference points on cells of the tolerance's size and a list of the
//! contacts of each pair, so that a model of many bodies is checked in
//! linear time.

use std::collections::HashMap;

use super::LimitError;
use crate::error::{require_finite, require_positive, DismechError, Result};
use crate::law::{Strength, StrengthLaw};
use crate::math::{perp, Point, Pose2, Vec2};
use crate::query::manifold::contact_manifold_2d;
use crate::query::manifold::polygon::contact_polygon_polygon_within;
use crate::query::Feature;
use crate::shape::{AnyShape2, Circle, Polygon};

/// A rigid element: its outline placed at its pose (the pose's position is
/// the reference point of its velocity and of its moments).
#[derive(Debug, Clone, PartialEq)]
pub struct LimitBody {
    /// Reference point (the centroid).
    pub centre: Point,
    /// The outline, in the body frame.
    pub shape: AnyShape2,
    /// Orientation of the outline (rad).
    pub angle: f64,
    /// Whether the element may rotate (rolling model) or not.
    pub rotates: bool,
    /// Known load on the element at its reference point (e.g. its weight
    /// `m g`), N per m.
    pub load: Vec2,
}

impl LimitBody {
    /// The pose of the outline.
    pub fn pose(&self) -> Pose2 {
        Pose2 {
            position: self.centre,
            angle: self.angle,
        }
    }

    /// Radius of a circular element, or the largest distance from the
    /// reference point to the outline otherwise.
    pub fn radius(&self) -> f64 {
        self.shape.as_shape().bounding_radius()
    }
}

/// Fraction of a body's bounding radius within which two points coincide
/// (see the module documentation).
pub const COINCIDENT_FRACTION: f64 = 1e-6;

/// What the LP reads of a contact's law: its linear strength
/// `|T| ≤ c + N tan φ` and whether it may open.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlasticContact {
    strength: Strength,
    unilateral: bool,
}

impl PlasticContact {
    /// The strength of any law that has one.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] when the law's cohesion or its
    /// friction coefficient tan φ is negative or not finite: a negative
    /// strength has no admissible stress (a negative friction makes the
    /// shear a contact carries fall as it is pressed harder), and the LP
    /// would read it as a dissipation that pays for motion.
    pub fn of(law: &impl StrengthLaw) -> Result<Self> {
        let strength = law.strength();
        for (name, value) in [
            ("contact law cohesion c", strength.cohesion),
            (
                "contact law friction coefficient tan(phi)",
                strength.friction,
            ),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(DismechError::InvalidParameter {
                    name,
                    value,
                    requirement: "must be finite and >= 0 (a StrengthLaw's strength |T| <= c + N tan(phi)); give the law a cohesion and a friction angle in [0, 90°)",
                });
            }
        }
        Ok(Self {
            strength,
            unilateral: law.may_open(),
        })
    }

    /// Cohesion c.
    pub fn cohesion(&self) -> f64 {
        self.strength.cohesion
    }

    /// Friction coefficient tan φ.
    pub fn friction(&self) -> f64 {
        self.strength.friction
    }

    /// Whether the contact may open.
    pub fn is_unilateral(&self) -> bool {
        self.unilateral
    }

    /// Whether the contact resists shear at all.
    pub fn resists_shear(&self) -> bool {
        self.strength.cohesion > 0.0 || self.strength.friction > 0.0
    }
}

/// A reference load applied at a point of a body, whose multiplier λ at
/// collapse the analysis finds (the limit load is `λ |force|` along it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LiveLoad {
    /// The loaded body.
    pub body: usize,
    /// The reference force (N per m).
    pub force: Vec2,
    /// Where it acts.
    pub point: Point,
}

/// A load whose multiplier λ at collapse a limit analysis seeks (the
/// alternative is a moving support, whose limit load is the force on it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LoadDriver {
    /// A reference live load on one body, added to the dead loads
    /// ([`LimitModel::set_live_load`]): λ is its multiplier at collapse.
    Live(LiveLoad),
    /// The dead loads themselves, every body's load multiplied by λ
    /// ([`LimitModel::multiply_dead_loads`]): λ is the factor on the
    /// self-weight at collapse, so `λ < 1` means that the assembly does
    /// not stand under its own weight. Contacts without cohesion make λ
    /// either zero ([`super::LimitStatus::ZeroLoad`]: a mechanism on which
    /// the weight does work, the assembly falls at any weight) or absent
    /// ([`super::LimitStatus::Locked`]: no such mechanism, it stands under
    /// any multiple of its weight), since scaling every load scales the
    /// forces that carry them; a geometric factor (the least thickness of
    /// an arch) is then found by varying the geometry.
    DeadLoads,
}

/// A straight rigid support (wall or loading plate): the line through
/// `point` with unit `normal` pointing into the material, moving at
/// `velocity` (zero for a wall).
#[derive(Debug, Clone, PartialEq)]
pub struct Support {
    /// Name used in messages and outputs.
    pub name: String,
    /// A point of the line.
    pub point: Point,
    /// Unit normal pointing into the material.
    pub normal: Vec2,
    /// Prescribed velocity.
    pub velocity: Vec2,
}

/// What an element is in contact with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Partner {
    /// Another element.
    Body(usize),
    /// A support.
    Support(usize),
}

/// What a refused contact was declared against, with the support's name
/// ([`LimitError::ContactNotTouching`],
/// [`LimitError::DuplicateContact`]).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum NamedPartner {
    /// Another element.
    Element(usize),
    /// A support.
    Support {
        /// Index of the support.
        support: usize,
        /// Its name.
        name: String,
    },
}

impl std::fmt::Display for NamedPartner {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Element(j) => write!(f, "element {j}"),
            Self::Support { name, .. } => write!(f, "support `{name}`"),
        }
    }
}

/// A contact of element `body` with `partner`, with its geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LimitContact {
    /// The element (A).
    pub body: usize,
    /// What it touches (B).
    pub partner: Partner,
    /// The contact's strength.
    pub law: PlasticContact,
    /// Contact point.
    pub point: Point,
    /// Unit normal from A to B.
    pub normal: Vec2,
}

impl LimitContact {
    /// Unit tangent (the normal turned by +90°).
    pub fn tangent(&self) -> Vec2 {
        perp(&self.normal)
    }
}

/// Elements, supports and contacts of a limit analysis.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LimitModel {
    bodies: Vec<LimitBody>,
    supports: Vec<Support>,
    contacts: Vec<LimitContact>,
    load_driver: Option<LoadDriver>,
    tolerance: f64,
    /// Bodies by the tolerance-sized cell of their reference point.
    body_cells: HashMap<(i64, i64), Vec<usize>>,
    /// Contacts by their pair (see [`pair_key`]).
    pairs: HashMap<(usize, Partner), Vec<usize>>,
}

/// Whether `normal` (world) is the outward normal of one of the two edges
/// of `polygon` at `pose` that meet at vertex `k`, within 1e-6 in sine: a
/// contact there is the end of a face on a face.
fn on_a_face(polygon: &Polygon, pose: &Pose2, k: usize, normal: &Vec2) -> bool {
    let n = polygon.vertices().len();
    [(k + n - 1) % n, k].iter().any(|&e| {
        let m = pose.transform_vector(&polygon.edge_normal(e));
        m.dot(normal) > 0.0 && crate::math::cross(&m, normal).abs() <= 1e-6
    })
}

/// The pair of a contact, the same whichever element of two is named first.
fn pair_key(body: usize, partner: Partner) -> (usize, Partner) {
    match partner {
        Partner::Body(j) => (body.min(j), Partner::Body(body.max(j))),
        Partner::Support(_) => (body, partner),
    }
}

impl LimitModel {
    /// An empty model; contacts must touch within `tolerance` (m).
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming `contact tolerance` when
    /// `tolerance` is not finite and positive.
    pub fn new(tolerance: f64) -> Result<Self> {
        Ok(Self {
            tolerance: require_positive("contact tolerance", tolerance)?,
            ..Self::default()
        })
    }

    /// Add a circular element; returns its index.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming the value for a radius
    /// that is not finite and positive or a centre that is not finite;
    /// [`LimitError::DuplicateBody`] when an element already has its
    /// reference point at `centre` (as [`LimitModel::add_shape`]).
    pub fn add_body(&mut self, centre: Point, radius: f64, rotates: bool) -> Result<usize> {
        require_positive("element radius", radius)?;
        let circle = Circle::new(radius)?;
        self.add_shape(circle.into(), Pose2::new(centre.x, centre.y, 0.0), rotates)
    }

    /// Add an element of any shape at `pose` (its position is the reference
    /// point of velocities, loads and moments); returns its index.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for a pose that is not finite;
    /// [`LimitError::DuplicateBody`] when an element
    /// already has its reference point where this one has (see the module
    /// documentation).
    pub fn add_shape(&mut self, shape: AnyShape2, pose: Pose2, rotates: bool) -> Result<usize> {
        require_finite("element centre x", pose.position.x)?;
        require_finite("element centre y", pose.position.y)?;
        require_finite("element angle", pose.angle)?;
        let index = self.bodies.len();
        let radius = shape.as_shape().bounding_radius();
        let cell = self.cell(&pose.position);
        for dx in -1..=1 {
            for dy in -1..=1 {
                let near = (cell.0.saturating_add(dx), cell.1.saturating_add(dy));
                let Some(others) = self.body_cells.get(&near) else {
                    continue;
                };
                for &existing in others {
                    let other = &self.bodies[existing];
                    let within = self.coincidence(radius.min(other.radius()));
                    if (other.centre - pose.position).norm() <= within {
                        return Err(LimitError::DuplicateBody {
                            body: index,
                            existing,
                            x: pose.position.x,
                            y: pose.position.y,
                            distance: within,
                        }
                        .into());
                    }
                }
            }
        }
        self.body_cells.entry(cell).or_default().push(index);
        self.bodies.push(LimitBody {
            centre: pose.position,
            shape,
            angle: pose.angle,
            rotates,
            load: Vec2::zeros(),
        });
        Ok(self.bodies.len() - 1)
    }

    /// The distance within which two points of bodies whose smaller
    /// bounding radius is `radius` coincide.
    fn coincidence(&self, radius: f64) -> f64 {
        self.tolerance.min(COINCIDENT_FRACTION * radius)
    }

    /// The tolerance-sized cell holding `point` (saturating far away).
    fn cell(&self, point: &Point) -> (i64, i64) {
        (
            (point.x / self.tolerance).floor() as i64,
            (point.y / self.tolerance).floor() as i64,
        )
    }

    /// Record contact `contact` unless it repeats one of its pair: at a
    /// coinciding point, or at all when `one_point` (circle geometry)
    /// ([`LimitError::DuplicateContact`]).
    fn push_contact(
        &mut self,
        contact: LimitContact,
        partner_name: NamedPartner,
        one_point: bool,
    ) -> Result<usize> {
        let index = self.contacts.len();
        let key = pair_key(contact.body, contact.partner);
        let mut radius = self.bodies[contact.body].radius();
        if let Partner::Body(j) = contact.partner {
            radius = radius.min(self.bodies[j].radius());
        }
        let within = self.coincidence(radius);
        let same_pair = self.pairs.get(&key).map(Vec::as_slice).unwrap_or(&[]);
        if let Some(&existing) = same_pair
            .iter()
            .find(|&&c| one_point || (self.contacts[c].point - contact.point).norm() <= within)
        {
            return Err(LimitError::DuplicateContact {
                contact: index,
                existing,
                body: contact.body,
                partner: partner_name,
            }
            .into());
        }
        self.pairs.entry(key).or_default().push(index);
        self.contacts.push(contact);
        Ok(index)
    }

    /// Apply the reference live load `force` at `point` of `body`: the
    /// analysis then finds the multiplier λ of this load at collapse, and no
    /// support may move. It replaces a live load set before, or the
    /// multiplication of the dead loads.
    ///
    /// # Errors
    /// An unknown body ([`DismechError::NoSuchBody`]); a force or point
    /// that is not finite, or a force of zero magnitude
    /// ([`DismechError::InvalidParameter`]).
    pub fn set_live_load(&mut self, body: usize, force: Vec2, point: Point) -> Result<()> {
        let count = self.bodies.len();
        if body >= count {
            return Err(DismechError::NoSuchBody { index: body, count });
        }
        for (n, v) in [
            ("live load x", force.x),
            ("live load y", force.y),
            ("live load point x", point.x),
            ("live load point y", point.y),
        ] {
            require_finite(n, v)?;
        }
        require_positive("live load magnitude", force.norm())?;
        self.load_driver = Some(LoadDriver::Live(LiveLoad { body, force, point }));
        Ok(())
    }

    /// Seek the multiplier λ of the dead loads (every body's load, see
    /// [`LimitModel::set_load`]) at collapse, e.g. the factor on the
    /// self-weight of an arch ([`LoadDriver::DeadLoads`]); no support may
    /// move. It replaces a live load set before.
    pub fn multiply_dead_loads(&mut self) {
        self.load_driver = Some(LoadDriver::DeadLoads);
    }

    /// Remove the live load or the multiplication of the dead loads, so
    /// that a moving support drives the analysis again.
    pub fn clear_load_driver(&mut self) {
        self.load_driver = None;
    }

    /// The load whose multiplier is sought, if one is set.
    pub fn load_driver(&self) -> Option<&LoadDriver> {
        self.load_driver.as_ref()
    }

    /// Whether any body has a dead load (see [`LimitModel::set_load`]).
    pub fn has_dead_loads(&self) -> bool {
        self.bodies.iter().any(|b| b.load != Vec2::zeros())
    }

    /// The live load, if one is set.
    pub fn live_load(&self) -> Option<&LiveLoad> {
        match &self.load_driver {
            Some(LoadDriver::Live(live)) => Some(live),
            _ => None,
        }
    }

    /// Set the known (dead) load of element `body` at its reference point,
    /// e.g. its weight, replacing the one set before.
    ///
    /// # Errors
    /// An unknown body ([`DismechError::NoSuchBody`]); a load that is not
    /// finite ([`DismechError::InvalidParameter`]).
    pub fn set_load(&mut self, body: usize, load: Vec2) -> Result<()> {
        require_finite("load x", load.x)?;
        require_finite("load y", load.y)?;
        let count = self.bodies.len();
        let b = self
            .bodies
            .get_mut(body)
            .ok_or(DismechError::NoSuchBody { index: body, count })?;
        b.load = load;
        Ok(())
    }

    /// Add a support; `normal` is normalised. Returns its index.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming the value for a point or
    /// velocity that is not finite, or a normal whose length is zero or not
    /// finite.
    pub fn add_support(
        &mut self,
        name: &str,
        point: Point,
        normal: Vec2,
        velocity: Vec2,
    ) -> Result<usize> {
        for (n, v) in [
            ("support point x", point.x),
            ("support point y", point.y),
            ("support velocity x", velocity.x),
            ("support velocity y", velocity.y),
        ] {
            require_finite(n, v)?;
        }
        let length = require_positive("support normal length", normal.norm())?;
        self.supports.push(Support {
            name: name.to_string(),
            point,
            normal: normal / length,
            velocity,
        });
        Ok(self.supports.len() - 1)
    }

    /// Declare a contact of the circular element `body` with `partner` (a
    /// circular element or a support), its geometry taken from the circles;
    /// the surfaces must touch. For other shapes give the contact point and
    /// normal with [`LimitModel::add_contact_at`].
    ///
    /// # Errors
    /// A law whose strength is negative or not finite
    /// ([`DismechError::InvalidParameter`], see [`PlasticContact::of`]), an
    /// unknown element or support, an element paired with itself
    /// ([`LimitError::SelfContact`]), a shape that is not a circle, surfaces
    /// that do not touch within the tolerance
    /// ([`LimitError::ContactNotTouching`]), or a contact of the same pair
    /// already declared ([`LimitError::DuplicateContact`]: two circles,
    /// or a circle and a line, touch at one point).
    pub fn add_contact(
        &mut self,
        body: usize,
        partner: Partner,
        law: impl StrengthLaw,
    ) -> Result<usize> {
        let law = PlasticContact::of(&law)?;
        let index = self.contacts.len();
        let count = self.bodies.len();
        let a = self
            .bodies
            .get(body)
            .ok_or(DismechError::NoSuchBody { index: body, count })?;
        let circle_of = |b: &LimitBody| match &b.shape {
            AnyShape2::Circle(c) => Ok(c.radius()),
            other => Err(DismechError::UnsupportedPair(
                "limit contact from circle geometry (use add_contact_at)",
                other.as_shape().kind().name(),
            )),
        };
        let radius_a = circle_of(a)?;
        let (point, normal, gap, name) = match partner {
            Partner::Body(j) if j == body => return Err(LimitError::SelfContact { body }.into()),
            Partner::Body(j) => {
                let b = self
                    .bodies
                    .get(j)
                    .ok_or(DismechError::NoSuchBody { index: j, count })?;
                let radius_b = circle_of(b)?;
                let d = b.centre - a.centre;
                let distance = d.norm();
                let normal = if distance > 0.0 {
                    d / distance
                } else {
                    Vec2::x()
                };
                (
                    a.centre + normal * radius_a,
                    normal,
                    distance - radius_a - radius_b,
                    NamedPartner::Element(j),
                )
            }
            Partner::Support(s) => {
                let support = self.supports.get(s).ok_or(DismechError::NoSuchBody {
                    index: s,
                    count: self.supports.len(),
                })?;
                let distance = (a.centre - support.point).dot(&support.normal);
                (
                    a.centre - support.normal * radius_a,
                    -support.normal,
                    distance - radius_a,
                    NamedPartner::Support {
                        support: s,
                        name: support.name.clone(),
                    },
                )
            }
        };
        if partner == Partner::Body(body) || gap.abs() > self.tolerance {
            return Err(LimitError::ContactNotTouching {
                contact: index,
                body,
                partner: name,
                gap,
                tolerance: self.tolerance,
            }
            .into());
        }
        self.push_contact(
            LimitContact {
                body,
                partner,
                law,
                point,
                normal,
            },
            name,
            true,
        )
    }

    /// Declare a contact of `body` with `partner` at `point` with the unit
    /// `normal` from `body` into `partner` (normalised here): one point of a
    /// contact manifold, e.g. a corner of a block on a floor or a contact
    /// of a settled DEM packing. Against a support, the point must lie on
    /// its line within the model's tolerance and the normal must point into
    /// the support.
    ///
    /// # Errors
    /// A law whose strength is negative or not finite
    /// ([`DismechError::InvalidParameter`], see [`PlasticContact::of`]), an
    /// unknown element or support, non-finite data, a support contact off
    /// its line ([`LimitError::ContactNotTouching`]), or a contact of the
    /// same pair already declared at this point
    /// ([`LimitError::DuplicateContact`]; see the module documentation).
    pub fn add_contact_at(
        &mut self,
        body: usize,
        partner: Partner,
        law: impl StrengthLaw,
        point: Point,
        normal: Vec2,
    ) -> Result<usize> {
        let law = PlasticContact::of(&law)?;
        let index = self.contacts.len();
        let count = self.bodies.len();
        if body >= count {
            return Err(DismechError::NoSuchBody { index: body, count });
        }
        for (n, v) in [
            ("contact point x", point.x),
            ("contact point y", point.y),
            ("contact normal x", normal.x),
            ("contact normal y", normal.y),
        ] {
            require_finite(n, v)?;
        }
        let length = require_positive("contact normal length", normal.norm())?;
        let normal = normal / length;
        let name = match partner {
            Partner::Body(j) if j == body => {
                return Err(LimitError::SelfContact { body }.into());
            }
            Partner::Body(j) if j >= count => {
                return Err(DismechError::NoSuchBody { index: j, count });
            }
            Partner::Body(j) => NamedPartner::Element(j),
            Partner::Support(s) => {
                let support = self.supports.get(s).ok_or(DismechError::NoSuchBody {
                    index: s,
                    count: self.supports.len(),
                })?;
                let gap = (point - support.point).dot(&support.normal);
                let facing = normal.dot(&support.normal) < 0.0;
                let name = NamedPartner::Support {
                    support: s,
                    name: support.name.clone(),
                };
                if gap.abs() > self.tolerance || !facing {
                    return Err(LimitError::ContactNotTouching {
                        contact: index,
                        body,
                        partner: name,
                        gap,
                        tolerance: self.tolerance,
                    }
                    .into());
                }
                name
            }
        };
        self.push_contact(
            LimitContact {
                body,
                partner,
                law,
                point,
                normal,
            },
            name,
            false,
        )
    }

    /// Declare every contact of `body` with `partner` that their outlines
    /// give, each with `law`; returns the indices of the new contacts.
    ///
    /// The points come from the pair query
    /// ([`crate::query::manifold`]), with the model's tolerance as the
    /// distance within which surfaces touch:
    /// * two circles, or a circle and a support: the one point of
    ///   [`LimitModel::add_contact`];
    /// * two polygons: the polygon manifold counted within the tolerance
    ///   ([`crate::query::manifold::polygon::contact_polygon_polygon_within`]):
    ///   a face on a face gives its two ends, so blocks cut to fit (the
    ///   voussoirs of an arch, whose corners coincide to rounding) touch
    ///   at both ends of each joint; two corners that meet at a point only
    ///   make no contact (no face gives its normal; leaving it out errs
    ///   on the safe side of the upper bound), and a pair that touches
    ///   only so gives an empty list;
    /// * a polygon and a support: every vertex within the tolerance of the
    ///   support's line;
    /// * an ellipse and a support: the ellipse's lowest point towards the
    ///   support, where it lies within the tolerance of the line;
    /// * other pairs of elements: the points of
    ///   [`crate::query::manifold::contact_manifold_2d`], which need the
    ///   outlines to overlap.
    ///
    /// Points of the pair that coincide (see the module documentation) are
    /// declared once. The pair's points are declared all or none: after an
    /// error the model is as it was.
    ///
    /// # Errors
    /// As [`LimitModel::add_contact_at`] for each point (e.g.
    /// [`LimitError::DuplicateContact`] where the pair already has a
    /// contact at one of them);
    /// [`LimitError::ContactNotTouching`] when the outlines give no
    /// point (they do not touch within the tolerance), with the distance
    /// between their reference points as the gap where no better one is
    /// known; [`DismechError::UnsupportedPair`] for a shape the pair query
    /// does not pair (a segment element).
    pub fn add_contacts(
        &mut self,
        body: usize,
        partner: Partner,
        law: impl StrengthLaw + Copy,
    ) -> Result<Vec<usize>> {
        let count = self.bodies.len();
        let a = self
            .bodies
            .get(body)
            .ok_or(DismechError::NoSuchBody { index: body, count })?
            .clone();
        let circle = |b: &LimitBody| matches!(b.shape, AnyShape2::Circle(_));
        // The contact points and normals, or how far apart the outlines are
        // when they give none (the support's nearest vertex, else the
        // distance of the reference points).
        let mut points: Vec<(Point, Vec2)> = Vec::new();
        let mut heights: Vec<(Point, f64)> = Vec::new();
        let mut apart: Option<f64> = None;
        let name = match partner {
            Partner::Body(j) if j == body => return Err(LimitError::SelfContact { body }.into()),
            Partner::Body(j) => {
                let b = self
                    .bodies
                    .get(j)
                    .ok_or(DismechError::NoSuchBody { index: j, count })?
                    .clone();
                if circle(&a) && circle(&b) {
                    return Ok(vec![self.add_contact(body, partner, law)?]);
                }
                let mut manifold = Vec::new();
                match (&a.shape, &b.shape) {
                    (AnyShape2::Polygon(pa), AnyShape2::Polygon(pb)) => {
                        contact_polygon_polygon_within(
                            pa,
                            &a.pose(),
                            pb,
                            &b.pose(),
                            self.tolerance,
                            &mut manifold,
                        );
                        // Two corners that meet at a point only (their
                        // merged normal lies on no face of either) have
                        // no contact normal: they are left out, the safe
                        // side of an upper bound.
                        let found = manifold.len();
                        manifold.retain(|g| match (g.features.a, g.features.b) {
                            (Feature::Vertex(i), Feature::Vertex(k)) => {
                                on_a_face(pa, &a.pose(), i, &g.normal)
                                    && on_a_face(pb, &b.pose(), k, &(-g.normal))
                            }
                            _ => true,
                        });
                        if manifold.is_empty() && found > 0 {
                            // They touch, at corners only: no contact.
                            return Ok(Vec::new());
                        }
                    }
                    (sa, sb) => contact_manifold_2d(sa, &a.pose(), sb, &b.pose(), &mut manifold)?,
                }
                points.extend(manifold.iter().map(|g| (g.point, g.normal)));
                if points.is_empty() {
                    apart = Some((b.centre - a.centre).norm());
                }
                NamedPartner::Element(j)
            }
            Partner::Support(s) => {
                let support = self
                    .supports
                    .get(s)
                    .ok_or(DismechError::NoSuchBody {
                        index: s,
                        count: self.supports.len(),
                    })?
                    .clone();
                let height = |p: &Point| (p - support.point).dot(&support.normal);
                match &a.shape {
                    AnyShape2::Circle(_) => {
                        return Ok(vec![self.add_contact(body, partner, law)?]);
                    }
                    AnyShape2::Polygon(polygon) => {
                        heights.extend(polygon.world_vertices(&a.pose()).map(|v| (v, height(&v))));
                    }
                    AnyShape2::Ellipse(ellipse) => {
                        // The support point of the ellipse along −n: in the
                        // body frame p = D² u / |D u|, D = diag(a, b).
                        let u = a.pose().inverse_transform_vector(&(-support.normal));
                        let (ea, eb) = (ellipse.a(), ellipse.b());
                        let scale = (ea * ea * u.x * u.x + eb * eb * u.y * u.y).sqrt();
                        let local = Point::new(ea * ea * u.x / scale, eb * eb * u.y / scale);
                        let lowest = a.pose().transform_point(&local);
                        heights.push((lowest, height(&lowest)));
                    }
                    other => {
                        return Err(DismechError::UnsupportedPair(
                            other.as_shape().kind().name(),
                            "support",
                        ))
                    }
                }
                points.extend(
                    heights
                        .iter()
                        .filter(|(_, h)| h.abs() <= self.tolerance)
                        .map(|&(p, _)| (p, -support.normal)),
                );
                if points.is_empty() {
                    apart = heights.iter().map(|p| p.1).reduce(f64::min);
                }
                NamedPartner::Support {
                    support: s,
                    name: support.name.clone(),
                }
            }
        };
        if let Some(gap) = apart {
            return Err(LimitError::ContactNotTouching {
                contact: self.contacts.len(),
                body,
                partner: name,
                gap,
                tolerance: self.tolerance,
            }
            .into());
        }
        let mut added = Vec::with_capacity(points.len());
        let mut radius = a.radius();
        if let Partner::Body(j) = partner {
            radius = radius.min(self.bodies[j].radius());
        }
        let within = self.coincidence(radius);
        let mut taken: Vec<Point> = Vec::with_capacity(points.len());
        for (point, normal) in points {
            if taken.iter().any(|t| (t - point).norm() <= within) {
                continue;
            }
            taken.push(point);
            match self.add_contact_at(body, partner, law, point, normal) {
                Ok(index) => added.push(index),
                Err(e) => {
                    // All the pair's points or none: take back those added.
                    let key = pair_key(body, partner);
                    if let Some(listed) = self.pairs.get_mut(&key) {
                        listed.retain(|c| !added.contains(c));
                    }
                    if let Some(&first) = added.first() {
                        self.contacts.truncate(first);
                    }
                    return Err(e);
                }
            }
        }
        Ok(added)
    }

    /// The elements.
    pub fn bodies(&self) -> &[LimitBody] {
        &self.bodies
    }

    /// The supports.
    pub fn supports(&self) -> &[Support] {
        &self.supports
    }

    /// The contacts.
    pub fn contacts(&self) -> &[LimitContact] {
        &self.contacts
    }
}
