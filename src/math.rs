//! Small fixed-size geometry types shared by every family.

use nalgebra::{Point2, Vector2};

pub mod real_roots;

/// A 2D vector (m, N, m/s…).
pub type Vec2 = Vector2<f64>;
/// A 2D point (m).
pub type Point = Point2<f64>;

/// Position and orientation of a 2D body: centre `(x, y)` and angle `phi`
/// (rad, counter-clockwise from +x).
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct Pose2 {
    /// Position of the reference point (the centroid for rigid bodies).
    pub position: Point,
    /// Orientation (rad, counter-clockwise).
    pub angle: f64,
}

impl Pose2 {
    /// A pose at `(x, y)` with angle `angle`.
    pub fn new(x: f64, y: f64, angle: f64) -> Self {
        Self {
            position: Point::new(x, y),
            angle,
        }
    }

    /// Map a point given in the body frame to the world frame.
    pub fn transform_point(&self, local: &Point) -> Point {
        self.position + rotate(&local.coords, self.angle)
    }

    /// Map a vector given in the body frame to the world frame.
    pub fn transform_vector(&self, local: &Vec2) -> Vec2 {
        rotate(local, self.angle)
    }

    /// Map a world vector into the body frame.
    pub fn inverse_transform_vector(&self, world: &Vec2) -> Vec2 {
        rotate(world, -self.angle)
    }

    /// Map a world point into the body frame.
    pub fn inverse_transform_point(&self, world: &Point) -> Point {
        Point::from(rotate(&(world - self.position), -self.angle))
    }
}

/// Rotate `v` counter-clockwise by `angle`.
pub fn rotate(v: &Vec2, angle: f64) -> Vec2 {
    let (s, c) = angle.sin_cos();
    Vec2::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

/// The left perpendicular of `v`: `v` turned by +90°.
#[inline]
pub fn perp(v: &Vec2) -> Vec2 {
    Vec2::new(-v.y, v.x)
}

/// The scalar 2D cross product `a × b = a.x b.y − a.y b.x`.
#[inline]
pub fn cross(a: &Vec2, b: &Vec2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Axis-aligned bounding box in 2D.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Aabb2 {
    /// Lower-left corner.
    pub min: Point,
    /// Upper-right corner.
    pub max: Point,
}

impl Aabb2 {
    /// The box spanned by two corners (in any order).
    pub fn from_corners(a: Point, b: Point) -> Self {
        Self {
            min: Point::new(a.x.min(b.x), a.y.min(b.y)),
            max: Point::new(a.x.max(b.x), a.y.max(b.y)),
        }
    }

    /// Whether two boxes overlap (touching counts).
    #[inline]
    pub fn intersects(&self, other: &Aabb2) -> bool {
        self.min.x <= other.max.x
            && other.min.x <= self.max.x
            && self.min.y <= other.max.y
            && other.min.y <= self.max.y
    }

    /// The smallest box holding both.
    pub fn merged(&self, other: &Aabb2) -> Self {
        Self {
            min: Point::new(self.min.x.min(other.min.x), self.min.y.min(other.min.y)),
            max: Point::new(self.max.x.max(other.max.x), self.max.y.max(other.max.y)),
        }
    }

    /// Whether `p` lies in the box (the boundary counts).
    #[inline]
    pub fn contains(&self, p: &Point) -> bool {
        (self.min.x..=self.max.x).contains(&p.x) && (self.min.y..=self.max.y).contains(&p.y)
    }

    /// How far apart two boxes are: the larger of their gaps along x and
    /// along y (not positive when they overlap). A shift of one box by a
    /// vector shorter than this leaves them apart.
    #[inline]
    pub fn separation(&self, other: &Aabb2) -> f64 {
        let x = (other.min.x - self.max.x).max(self.min.x - other.max.x);
        let y = (other.min.y - self.max.y).max(self.min.y - other.max.y);
        x.max(y)
    }

    /// The box grown by `margin` on every side.
    #[inline]
    pub fn inflated(&self, margin: f64) -> Self {
        Self {
            min: Point::new(self.min.x - margin, self.min.y - margin),
            max: Point::new(self.max.x + margin, self.max.y + margin),
        }
    }
}

/// SplitMix64, a small deterministic generator of uniform numbers in
/// [0, 1): random geometry drawn from a seed is the same on every run and
/// machine.
#[derive(Debug, Clone)]
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    /// The next number in [0, 1).
    pub fn next_uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
}
