//! The geometry of one contact point and the relative kinematics at it.

use crate::math::{cross, perp, Point, Vec2};

/// The part of one body's boundary a contact point belongs to.
///
/// Polygons number their vertices counter-clockwise from 0 in the order they
/// were given, and edge `k` runs from vertex `k` to vertex `k + 1` (the last
/// edge closes the outline). A wall (segment) is `Edge(0)` from `Vertex(0)`
/// (its start) to `Vertex(1)` (its end). A smooth body (circle, ellipse) is
/// always `Whole`.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
pub enum Feature {
    /// The whole boundary: the body contributes one point to the pair.
    Whole,
    /// Vertex `k`.
    Vertex(usize),
    /// Edge `k` (from vertex `k` to vertex `k + 1`).
    Edge(usize),
}

/// The features of A and B that make one contact point; with the pair of
/// bodies it names the point across steps, so that a contact law's history
/// follows it while the bodies slide a little.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
pub struct ContactFeatures {
    /// The feature of body A.
    pub a: Feature,
    /// The feature of body B.
    pub b: Feature,
}

impl ContactFeatures {
    /// The single point of a pair that has at most one (any pair without a
    /// polygon).
    pub const WHOLE: Self = Self {
        a: Feature::Whole,
        b: Feature::Whole,
    };

    /// The same features seen from B.
    pub fn swapped(self) -> Self {
        Self {
            a: self.b,
            b: self.a,
        }
    }
}

/// Whether a contact's width and radii of curvature are wanted: only some
/// contact laws read them ([`crate::law::ContactLaw::uses_contact_shape`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactShape {
    /// Computed.
    Computed,
    /// Left NaN where they would cost work of their own (a circle pair's
    /// width, an ellipse pair's radii of curvature).
    Skipped,
}

/// The geometry of a contact between body A and body B.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactGeometry {
    /// The contact point (world): the midpoint of the chord P1P2 joining the
    /// two intersection points of the boundaries (paper 000, §2(3)).
    pub point: Point,
    /// Unit normal pointing from A into B (perpendicular to the chord).
    pub normal: Vec2,
    /// Penetration depth along the normal (m); positive when overlapping.
    pub overlap: f64,
    /// Contact width B = |P1P2| (m), used by the stiffness of eq. (19).
    /// NaN where a circle pair was asked for [`ContactShape::Skipped`].
    pub width: f64,
    /// Radius of curvature of A's boundary at the contact (m;
    /// `f64::INFINITY` for a flat wall or a polygon's edge, 0 at a polygon's
    /// vertex). NaN where an ellipse pair was asked for
    /// [`ContactShape::Skipped`].
    pub curvature_radius_a: f64,
    /// Radius of curvature of B's boundary at the contact (NaN as
    /// `curvature_radius_a`).
    pub curvature_radius_b: f64,
    /// Which features of A and B make this point.
    pub features: ContactFeatures,
}

impl ContactGeometry {
    /// Unit tangent: the normal turned by +90°.
    #[inline]
    pub fn tangent(&self) -> Vec2 {
        perp(&self.normal)
    }

    /// The same contact seen from B: the normal flips, radii and features
    /// swap; the point, overlap and width stay.
    pub fn flipped(&self) -> Self {
        Self {
            normal: -self.normal,
            curvature_radius_a: self.curvature_radius_b,
            curvature_radius_b: self.curvature_radius_a,
            features: self.features.swapped(),
            ..*self
        }
    }
}

/// Relative displacement increment of B with respect to A at the contact
/// point, in the local frame: `[Δu_n, Δu_s]`.
///
/// With lever arms `r_A = x_c − x_A`, `r_B = x_c − x_B`, and body increments
/// `(Δx, Δφ)`, the contact point of each body moves by `Δx + Δφ × r`; the
/// relative increment is `Δu = (Δx_B + Δφ_B × r_B) − (Δx_A + Δφ_A × r_A)`
/// and
///
/// * `Δu_n = −Δu · n` (positive when the bodies approach), and
/// * `Δu_s = Δu · t`, with `t` the normal turned by +90°.
///
/// This is the vector form of paper 000's missing eqs. (12)–(13). For a
/// circle, `r` is parallel to `n`, so rotation changes only `Δu_s`; for an
/// ellipse the lever arm is not parallel to the normal and rotation moves the
/// contact point normally too. (The DEM takes the normal increment of a
/// continuing contact from the change of overlap instead, which equals this
/// `Δu_n` for circles and stays exact for rolling ellipses.)
#[inline]
pub fn relative_increment(
    geometry: &ContactGeometry,
    centre_a: &Point,
    increment_a: (&Vec2, f64),
    centre_b: &Point,
    increment_b: (&Vec2, f64),
) -> [f64; 2] {
    let r_a = geometry.point - centre_a;
    let r_b = geometry.point - centre_b;
    let point_a = increment_a.0 + perp(&r_a) * increment_a.1;
    let point_b = increment_b.0 + perp(&r_b) * increment_b.1;
    let du = point_b - point_a;
    [-du.dot(&geometry.normal), du.dot(&geometry.tangent())]
}

/// The moment about `centre` of a force `force` applied at `point`.
#[inline]
pub fn moment_about(centre: &Point, point: &Point, force: &Vec2) -> f64 {
    cross(&(point - centre), force)
}
