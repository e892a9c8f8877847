//! Shapes: the geometry of one body, independent of its material and motion.
//!
//! A shape is a small plain struct (`Circle`, `Segment`; `Ellipse`,
//! `Polygon` and the 3D `Column` follow the same pattern). Every shape
//! implements [`Shape`], which is object-safe and answers what any method
//! needs to know of a body's geometry: what kind it is (for the pair
//! dispatcher), its dimension, its measure (area or volume) and its mass
//! properties. 2D shapes also implement [`Shape2`], which adds what the 2D
//! broad phase and contact routines need: a bounding box in a pose. How a
//! body's unknowns move its shape is the kinematics slot's business
//! ([`crate::kinematics`]): the same polygon is a rigid DEM block (3
//! unknowns) or a deformable DDA block (6).
//!
//! The set of kinds is closed in [`ShapeKind`] so that the pair dispatcher
//! ([`crate::query::manifold::dispatch`]) can match exhaustively and answer
//! `Err(UnsupportedPair)` for a pair it lacks, never panic.

mod circle;
mod column;
mod ellipse;
mod polygon;
mod segment;
mod simple;

pub use circle::Circle;
pub use column::Column;
pub use ellipse::{Ellipse, MAX_ASPECT_RATIO};
pub use polygon::{crossing_depth, Polygon};
pub use segment::Segment;

use crate::math::{Aabb2, Pose2};

/// The kinds of shape dismech knows; used to dispatch pair queries.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ShapeKind {
    /// A disc (2D).
    Circle,
    /// A straight segment (2D), used for rigid walls and plates.
    Segment,
    /// An ellipse (2D).
    Ellipse,
    /// A simple polygon, convex or concave (2D), e.g. a DDA block.
    Polygon,
    /// A grid column element with vertical sides (3D), as in HPM.
    Column,
}

impl ShapeKind {
    /// Lower-case name used in messages.
    pub fn name(self) -> &'static str {
        match self {
            ShapeKind::Circle => "circle",
            ShapeKind::Segment => "segment",
            ShapeKind::Ellipse => "ellipse",
            ShapeKind::Polygon => "polygon",
            ShapeKind::Column => "column",
        }
    }
}

/// Mass properties of a body about its centroid.
///
/// In 2D the values are per unit thickness (kg/m, kg·m²/m) and `inertia` is
/// the polar moment about the centroid; 3D shapes report the moment about the
/// vertical axis here and the full tensor through their own API.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProperties {
    /// Mass (kg, or kg/m in 2D).
    pub mass: f64,
    /// Moment of inertia about the centroid (kg·m², or kg·m²/m in 2D).
    pub inertia: f64,
}

/// What every shape provides, whatever the method that uses it.
pub trait Shape: std::fmt::Debug + Send + Sync {
    /// The kind of shape, for dispatch.
    fn kind(&self) -> ShapeKind;
    /// Spatial dimension (2 or 3).
    fn dimension(&self) -> usize;
    /// Area (2D) or volume (3D).
    fn measure(&self) -> f64;
    /// Mass properties for a uniform density (kg/m³).
    fn mass_properties(&self, density: f64) -> MassProperties;
}

/// What 2D shapes add: bounds for the broad phase.
pub trait Shape2: Shape {
    /// The axis-aligned bounding box of the shape placed at `pose`.
    fn aabb(&self, pose: &Pose2) -> Aabb2;
    /// The largest distance from the reference point to the boundary.
    fn bounding_radius(&self) -> f64;
}

/// An owned 2D shape of any kind dismech has a 2D contact routine for; the
/// pair dispatcher matches on it.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum AnyShape2 {
    /// A disc.
    Circle(Circle),
    /// A segment (wall).
    Segment(Segment),
    /// An ellipse.
    Ellipse(Ellipse),
    /// A simple polygon, convex or concave.
    Polygon(Polygon),
}

impl AnyShape2 {
    /// The shape as a trait object.
    pub fn as_shape(&self) -> &dyn Shape2 {
        match self {
            AnyShape2::Circle(c) => c,
            AnyShape2::Segment(s) => s,
            AnyShape2::Ellipse(e) => e,
            AnyShape2::Polygon(p) => p,
        }
    }
}

impl From<Circle> for AnyShape2 {
    fn from(c: Circle) -> Self {
        AnyShape2::Circle(c)
    }
}

impl From<Ellipse> for AnyShape2 {
    fn from(e: Ellipse) -> Self {
        AnyShape2::Ellipse(e)
    }
}

impl From<Segment> for AnyShape2 {
    fn from(s: Segment) -> Self {
        AnyShape2::Segment(s)
    }
}

impl From<Polygon> for AnyShape2 {
    fn from(p: Polygon) -> Self {
        AnyShape2::Polygon(p)
    }
}
