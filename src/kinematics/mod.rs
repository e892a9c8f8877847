//! Body kinematics: how a body's degrees of freedom move its points over a
//! step, what inertia and elastic stiffness they carry, and how a committed
//! increment moves the body's geometry.
//!
//! Every 2D body moves over a step by the map
//!
//! ```text
//! x(X; d) = c + t(d) + F(d) (X − c)
//! ```
//!
//! of its start-of-step points `X`, with `c` the start-of-step reference
//! point (the centroid), `t` a translation and `F` a 2×2 matrix. The six
//! *map parameters* `Δp = (t_x, t_y, F₁₁ − 1, F₁₂, F₂₁, F₂₂ − 1)` (F row by
//! row, relative to the identity) are what a pair query differentiates
//! ([`crate::query::variation`]); a kinematics gives them as functions of
//! its `N` degrees of freedom `d`, with `P = ∂Δp/∂d` (6×N) and the
//! contraction `Σ_k w_k ∂²Δp_k/∂d²` of their second derivatives, so that a
//! scalar `g(Δp(d))` has `∇_d g = Pᵀ ∇_p g` and
//! `∇²_d g = Pᵀ ∇²_p g P + Σ_k (∇_p g)_k ∂²Δp_k/∂d²`.
//!
//! | kinematics | N | d | F | mass | elastic stiffness |
//! |---|---|---|---|---|---|
//! | [`Fixed`] | 0 | — | I | — | — |
//! | [`Rigid2`] | 3 | (u₀, v₀, θ) | R(θ), an exact rotation | diag(m, m, I) | none |
//! | [`Affine2`] | 6 | (u₀, v₀, r₀, εx, εy, γxy) of DDA (paper 003 eq. 16) | I + [[εx, γ/2 − r₀], [γ/2 + r₀, εy]], linear in d (eqs. 14–15) | ρ ∫TᵀT dA | A D on the strains |
//!
//! In 3D, [`affine3`] is the HPM element of paper 001 (12 unknowns:
//! translation, rotation and uniform strain about the centroid, `u = N(x)
//! U`, stiffness `V BᵀDB`), used by [`crate::hpm`].
//!
//! The number of degrees of freedom is a const generic parameter of the
//! trait, so the matrices are fixed-size nalgebra types.

mod affine2;
pub mod affine3;
mod fixed;
mod placed;
mod rigid2;

pub use affine2::Affine2;
pub use fixed::Fixed;
pub use placed::{PlacedEllipse, PlacedPolygon};
pub use rigid2::Rigid2;

use nalgebra::{Matrix2, Matrix3, SMatrix, SVector, Vector3};

use crate::error::Result;
use crate::math::{Point, Vec2};

/// The six map parameters `Δp = (t_x, t_y, F₁₁ − 1, F₁₂, F₂₁, F₂₂ − 1)` of
/// one body over a step.
pub type MapVector = SVector<f64, 6>;

/// A body's map over a step, `x = c + t + F (X − c)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyMap {
    /// Translation `t` of the reference point.
    pub translation: Vec2,
    /// Deformation gradient `F` (a rotation for a rigid body).
    pub gradient: Matrix2<f64>,
}

impl BodyMap {
    /// The map of the parameters `Δp`.
    pub fn from_parameters(dp: &MapVector) -> Self {
        Self {
            translation: Vec2::new(dp[0], dp[1]),
            gradient: Matrix2::new(1.0 + dp[2], dp[3], dp[4], 1.0 + dp[5]),
        }
    }

    /// Where the map takes the start-of-step point `material` of a body
    /// whose reference point was `reference`.
    pub fn apply(&self, reference: &Point, material: &Point) -> Point {
        reference + self.translation + self.gradient * (material - reference)
    }
}

/// `∂x/∂Δp` at a point whose start-of-step offset from the reference point
/// is `r = X − c`: `[[1, 0, r_x, r_y, 0, 0], [0, 1, 0, 0, r_x, r_y]]`.
pub fn point_map_jacobian(r: &Vec2) -> SMatrix<f64, 2, 6> {
    SMatrix::<f64, 2, 6>::new(1.0, 0.0, r.x, r.y, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, r.x, r.y)
}

/// Area and second moments of a body's region about its centroid, the
/// integrals every mass matrix here is made of.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AreaMoments {
    /// Area `A` (m², per metre of thickness).
    pub area: f64,
    /// `∫ (X − c)(X − c)ᵀ dA` about the centroid: `[[∫x², ∫xy], [∫xy, ∫y²]]`.
    pub second: Matrix2<f64>,
}

impl AreaMoments {
    /// Moments from the area and `[∫x², ∫y², ∫xy]` (the order of
    /// [`crate::shape::Polygon::second_moments`]).
    pub fn new(area: f64, [ixx, iyy, ixy]: [f64; 3]) -> Self {
        Self {
            area,
            second: Matrix2::new(ixx, ixy, ixy, iyy),
        }
    }

    /// The polar moment `∫|X − c|² dA`.
    pub fn polar(&self) -> f64 {
        self.second[(0, 0)] + self.second[(1, 1)]
    }
}

/// How a body's `N` degrees of freedom move its points over a step.
///
/// Implementations are small strategy values (usually zero-sized); a driver
/// generic over `K: Kinematics<N>` asks them for the map parameters of an
/// iterate, for the chain rule from map parameters to degrees of freedom,
/// and for the body's mass and elastic stiffness.
pub trait Kinematics<const N: usize> {
    /// Whether `Δp` is linear in `d` (`Δp = P d`, no second derivatives):
    /// then a pair's local variables are linear in `d` too and the chain
    /// rule has no curvature term.
    const LINEAR: bool;

    /// The map parameters `Δp(d)`.
    fn map_parameters(&self, d: &SVector<f64, N>) -> MapVector;

    /// `P = ∂Δp/∂d` (6×N).
    fn map_jacobian(&self, d: &SVector<f64, N>) -> SMatrix<f64, 6, N>;

    /// `Σ_k w_k ∂²Δp_k/∂d²` (N×N): the curvature term of the chain rule for
    /// a scalar whose gradient in `Δp` is `w`. Zero when [`Self::LINEAR`].
    fn map_curvature(&self, d: &SVector<f64, N>, w: &MapVector) -> SMatrix<f64, N, N>;

    /// Mass matrix `ρ ∫ (∂x/∂d)ᵀ (∂x/∂d) dA` of a body with the given area
    /// moments and density `ρ`, so that `½ ḋᵀ M ḋ` is its kinetic energy.
    fn mass(&self, moments: &AreaMoments, density: f64) -> SMatrix<f64, N, N>;

    /// Elastic stiffness `∫ Bᵀ D B dA` for the plane elastic matrix `D`
    /// (`σ = D ε`, `ε = (εx, εy, γxy)`); zero for a rigid body.
    fn stiffness(&self, moments: &AreaMoments, elastic: &Matrix3<f64>) -> SMatrix<f64, N, N>;

    /// The uniform strain `(εx, εy, γxy)` of the increment `d` (zero for a
    /// rigid body): the strain a stress increment `D ε` follows from.
    fn strain(&self, _d: &SVector<f64, N>) -> Vector3<f64> {
        Vector3::zeros()
    }

    /// The generalised force `∫ Bᵀ σ dA` of a uniform stress `σ` (zero for
    /// a rigid body): the internal force of the stress a body carries.
    fn stress_force(&self, _moments: &AreaMoments, _stress: &Vector3<f64>) -> SVector<f64, N> {
        SVector::zeros()
    }

    /// The body's map `x = c + t + F (X − c)` at `d`.
    fn map(&self, d: &SVector<f64, N>) -> BodyMap {
        BodyMap::from_parameters(&self.map_parameters(d))
    }

    /// The map a committed increment `d` applies to the body's geometry
    /// at the end of a step: [`Self::map`] unless the kinematics corrects
    /// it (DDA's affine body makes its rotation exact there, see
    /// [`Affine2`]).
    fn committed_map(&self, d: &SVector<f64, N>) -> BodyMap {
        self.map(d)
    }

    /// `∂x/∂d` (2×N) at the point whose start-of-step offset from the
    /// reference point is `r`: loads, tractions and velocities of a point.
    fn point_jacobian(&self, d: &SVector<f64, N>, r: &Vec2) -> SMatrix<f64, 2, N> {
        point_map_jacobian(r) * self.map_jacobian(d)
    }
}

/// How a committed increment `d` moves a body's geometry `G` (a pose, a
/// polygon, an ellipse) to the start of the next step.
pub trait Advance<G, const N: usize>: Kinematics<N> {
    /// The geometry after the increment `d`; `body` names the body if the
    /// result is invalid (e.g. a polygon turned inside out).
    ///
    /// # Errors
    /// [`crate::error::DismechError::InvalidPolygon`] when a moved polygon
    /// is no longer simple or counter-clockwise,
    /// [`crate::error::DismechError::InvalidParameter`] when a moved ellipse
    /// degenerates.
    fn advance(&self, geometry: &G, d: &SVector<f64, N>, body: usize) -> Result<G>;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn body_map_of_zero_parameters_is_the_identity() {
        let m = BodyMap::from_parameters(&MapVector::zeros());
        let (c, x) = (Point::new(1.0, -2.0), Point::new(0.3, 0.7));
        approx::assert_relative_eq!(m.apply(&c, &x), x, epsilon = 1e-15);
    }

    #[test]
    fn point_map_jacobian_is_the_derivative_of_the_map() {
        let (c, x) = (Point::new(1.0, -2.0), Point::new(0.3, 0.7));
        let dp = MapVector::new(0.1, -0.2, 0.05, 0.3, -0.1, 0.02);
        let j = point_map_jacobian(&(x - c));
        // The map is affine in Δp with no constant part beyond X.
        let moved = BodyMap::from_parameters(&dp).apply(&c, &x);
        approx::assert_relative_eq!(moved.coords, x.coords + j * dp, epsilon = 1e-15);
    }
}
