//! The data of a limit analysis: rigid circles, supports and contacts.

use crate::contact::RigidPlastic;
use crate::error::{require_finite, require_positive, DismechError, Result};
use crate::math::{perp, Point, Vec2};

/// A rigid circular element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LimitBody {
    /// Centre.
    pub centre: Point,
    /// Radius.
    pub radius: f64,
    /// Whether the element may rotate (rolling model) or not.
    pub rotates: bool,
    /// Known load on the element (e.g. its weight `m g`), N per m.
    pub load: Vec2,
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

/// A contact of element `body` with `partner`, with its geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LimitContact {
    /// The element (A).
    pub body: usize,
    /// What it touches (B).
    pub partner: Partner,
    /// The contact's law.
    pub law: RigidPlastic,
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
    tolerance: f64,
}

impl LimitModel {
    /// An empty model; contacts must touch within `tolerance` (m).
    pub fn new(tolerance: f64) -> Result<Self> {
        Ok(Self {
            tolerance: require_positive("contact tolerance", tolerance)?,
            ..Self::default()
        })
    }

    /// Add an element; returns its index.
    pub fn add_body(&mut self, centre: Point, radius: f64, rotates: bool) -> Result<usize> {
        require_finite("element centre x", centre.x)?;
        require_finite("element centre y", centre.y)?;
        require_positive("element radius", radius)?;
        self.bodies.push(LimitBody {
            centre,
            radius,
            rotates,
            load: Vec2::zeros(),
        });
        Ok(self.bodies.len() - 1)
    }

    /// Set the known load (e.g. weight) of element `body`.
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

    /// Declare a contact of `body` with `partner`; the surfaces must touch.
    pub fn add_contact(
        &mut self,
        body: usize,
        partner: Partner,
        law: RigidPlastic,
    ) -> Result<usize> {
        let index = self.contacts.len();
        let count = self.bodies.len();
        let a = *self
            .bodies
            .get(body)
            .ok_or(DismechError::NoSuchBody { index: body, count })?;
        let (point, normal, gap, name) = match partner {
            Partner::Body(j) => {
                let b = self
                    .bodies
                    .get(j)
                    .ok_or(DismechError::NoSuchBody { index: j, count })?;
                let d = b.centre - a.centre;
                let distance = d.norm();
                let normal = if distance > 0.0 {
                    d / distance
                } else {
                    Vec2::x()
                };
                (
                    a.centre + normal * a.radius,
                    normal,
                    distance - a.radius - b.radius,
                    format!("element {j}"),
                )
            }
            Partner::Support(s) => {
                let support = self.supports.get(s).ok_or(DismechError::NoSuchBody {
                    index: s,
                    count: self.supports.len(),
                })?;
                let distance = (a.centre - support.point).dot(&support.normal);
                (
                    a.centre - support.normal * a.radius,
                    -support.normal,
                    distance - a.radius,
                    format!("support `{}`", support.name),
                )
            }
        };
        if partner == Partner::Body(body) || gap.abs() > self.tolerance {
            return Err(DismechError::ContactNotTouching {
                contact: index,
                body,
                partner: name,
                gap,
                tolerance: self.tolerance,
            });
        }
        self.contacts.push(LimitContact {
            body,
            partner,
            law,
            point,
            normal,
        });
        Ok(index)
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
