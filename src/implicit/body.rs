//! A body of the implicit driver: its geometry at the start of the step, its
//! material, its motion state in its `N` unknowns, what is imposed on it and
//! the loads it carries.

use std::sync::Arc;

use nalgebra::{Matrix2, Matrix3, SVector, Vector3};

use super::error::ImplicitError;
use crate::error::{require_finite, require_positive, DismechError, Result};
use crate::kinematics::{AreaMoments, PlacedEllipse, PlacedPolygon};
use crate::math::{Aabb2, Point, Pose2, Vec2};
use crate::shape::{AnyShape2, Circle, Ellipse, Segment, Shape2};

/// The geometry of a body at the start of a step.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum BodyGeometry {
    /// A simple polygon (a DDA block, a rigid block).
    Polygon(PlacedPolygon),
    /// An ellipse or a circle (an affine body keeps an ellipse an ellipse).
    Ellipse(PlacedEllipse),
    /// A straight wall, the bodies it holds on its left (start → end: a
    /// floor runs in +x); it has no area
    /// and must be fully prescribed.
    Wall(Segment),
}

impl BodyGeometry {
    /// The reference point of the body's kinematics: the centroid (the
    /// midpoint of a wall).
    pub fn reference(&self) -> Point {
        match self {
            BodyGeometry::Polygon(p) => p.centroid(),
            BodyGeometry::Ellipse(e) => e.centre(),
            BodyGeometry::Wall(s) => Point::from((s.start.coords + s.end.coords) * 0.5),
        }
    }

    /// Area and second moments about the reference point (zero for a
    /// wall).
    pub fn moments(&self) -> AreaMoments {
        match self {
            BodyGeometry::Polygon(p) => p.moments(),
            BodyGeometry::Ellipse(e) => e.moments(),
            BodyGeometry::Wall(_) => AreaMoments {
                area: 0.0,
                second: Matrix2::zeros(),
            },
        }
    }

    /// The axis-aligned bounding box.
    pub fn aabb(&self) -> Aabb2 {
        match self {
            BodyGeometry::Polygon(p) => {
                p.polygon()
                    .aabb(&Pose2::new(p.centroid().x, p.centroid().y, 0.0))
            }
            BodyGeometry::Ellipse(e) => {
                let m = e.matrix();
                let (hx, hy) = (m[(0, 0)].sqrt(), m[(1, 1)].sqrt());
                let c = e.centre();
                Aabb2::from_corners(
                    Point::new(c.x - hx, c.y - hy),
                    Point::new(c.x + hx, c.y + hy),
                )
            }
            BodyGeometry::Wall(s) => Aabb2::from_corners(s.start, s.end),
        }
    }

    /// The geometry as a shape and a pose, for the explicit pair queries
    /// (an ellipse gets its semi-axes and angle from its shape matrix; one
    /// with equal semi-axes is a circle).
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for an ellipse whose aspect ratio
    /// is above [`MAX_ASPECT_RATIO`](crate::shape::MAX_ASPECT_RATIO), the
    /// largest the explicit contact routines support ([`Ellipse::new`]).
    pub fn shape_and_pose(&self) -> Result<(AnyShape2, Pose2)> {
        Ok(match self {
            BodyGeometry::Polygon(p) => (
                AnyShape2::Polygon(p.polygon().clone()),
                Pose2::new(p.centroid().x, p.centroid().y, 0.0),
            ),
            BodyGeometry::Ellipse(e) => {
                let (a, b, angle) = principal_axes(&e.matrix());
                let c = e.centre();
                // A circle is given as a circle: the ellipse routines of
                // the explicit queries misjudge two circles that touch.
                let shape = if a - b <= 1e-12 * a {
                    AnyShape2::Circle(Circle::new(0.5 * (a + b))?)
                } else {
                    AnyShape2::Ellipse(Ellipse::new(a, b)?)
                };
                (shape, Pose2::new(c.x, c.y, angle))
            }
            BodyGeometry::Wall(s) => (AnyShape2::Segment(*s), Pose2::default()),
        })
    }
}

/// Semi-axes `a ≥ b` and the angle of the major axis of the ellipse with
/// shape matrix `m = A Aᵀ` (its eigenvalues are `a²`, `b²`).
fn principal_axes(m: &Matrix2<f64>) -> (f64, f64, f64) {
    let (p, q, r) = (m[(0, 0)], m[(0, 1)], m[(1, 1)]);
    let mean = 0.5 * (p + r);
    let radius = (0.25 * (p - r) * (p - r) + q * q).sqrt();
    let angle = 0.5 * (2.0 * q).atan2(p - r);
    (
        (mean + radius).sqrt(),
        (mean - radius).max(0.0).sqrt(),
        angle,
    )
}

/// Plane stress (the classic DDA choice) or plane strain.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub enum PlaneState {
    /// `σ_z = 0`.
    #[default]
    Stress,
    /// `ε_z = 0`.
    Strain,
}

/// Elastic and inertial properties of a body. A rigid kinematics uses
/// only the density.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BodyMaterial {
    /// Density ρ (kg/m³).
    pub density: f64,
    /// Young's modulus E (Pa).
    pub youngs_modulus: f64,
    /// Poisson's ratio ν, in (−1, 0.5).
    pub poisson_ratio: f64,
    /// Plane stress or plane strain.
    pub plane: PlaneState,
}

impl BodyMaterial {
    /// Check every value; `body` names the body in the error.
    ///
    /// # Errors
    /// [`ImplicitError::InvalidBlock`] naming `body` for a density `ρ` or a
    /// Young's modulus `E` that is not finite and positive, or a Poisson's
    /// ratio ν that is not finite or outside (−1, 0.5).
    pub fn validate(&self, body: usize) -> Result<()> {
        let bad = |name: &'static str, value: f64, requirement: &'static str| {
            DismechError::Implicit(ImplicitError::InvalidBlock {
                block: body,
                name,
                value,
                requirement,
            })
        };
        if !(self.density.is_finite() && self.density > 0.0) {
            return Err(bad("density", self.density, "must be finite and > 0"));
        }
        if !(self.youngs_modulus.is_finite() && self.youngs_modulus > 0.0) {
            return Err(bad(
                "Young's modulus",
                self.youngs_modulus,
                "must be finite and > 0",
            ));
        }
        if !(self.poisson_ratio.is_finite()
            && self.poisson_ratio > -1.0
            && self.poisson_ratio < 0.5)
        {
            return Err(bad(
                "Poisson's ratio",
                self.poisson_ratio,
                "must lie in (-1, 0.5)",
            ));
        }
        Ok(())
    }

    /// Elastic matrix `D` with `σ = D ε`, `ε = (εx, εy, γxy)`.
    pub fn elastic_matrix(&self) -> Matrix3<f64> {
        let (e, nu) = (self.youngs_modulus, self.poisson_ratio);
        let (e, nu) = match self.plane {
            PlaneState::Stress => (e, nu),
            // Plane strain is plane stress with E/(1−ν²), ν/(1−ν).
            PlaneState::Strain => (e / (1.0 - nu * nu), nu / (1.0 - nu)),
        };
        let c = e / (1.0 - nu * nu);
        Matrix3::new(
            c,
            c * nu,
            0.0,
            c * nu,
            c,
            0.0,
            0.0,
            0.0,
            c * (1.0 - nu) / 2.0,
        )
    }
}

/// Total displacement of a body's prescribed unknowns as a function of the
/// time since the start.
pub type Motion<const N: usize> = Arc<dyn Fn(f64) -> [f64; N] + Send + Sync>;

/// Unknowns of a body whose values are imposed (kinematic supports, driven
/// plates).
#[derive(Clone)]
pub struct Prescribed<const N: usize> {
    /// Which unknowns are imposed.
    pub mask: [bool; N],
    /// Their total displacement since `t = 0`.
    pub motion: Motion<N>,
}

impl<const N: usize> std::fmt::Debug for Prescribed<N> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Prescribed")
            .field("mask", &self.mask)
            .finish()
    }
}

impl<const N: usize> Prescribed<N> {
    /// Every unknown held at zero: a fixed body.
    pub fn fixed() -> Self {
        Self {
            mask: [true; N],
            motion: Arc::new(|_| [0.0; N]),
        }
    }

    /// A body translated by `motion(t)` (its first two unknowns, the
    /// translation of the reference point, in every kinematics here), the
    /// others held at zero.
    pub fn translation(motion: impl Fn(f64) -> Vec2 + Send + Sync + 'static) -> Self {
        Self {
            mask: [true; N],
            motion: Arc::new(move |t| {
                let u = motion(t);
                let mut out = [0.0; N];
                if N >= 2 {
                    out[0] = u.x;
                    out[1] = u.y;
                }
                out
            }),
        }
    }
}

/// One body and its state.
#[derive(Debug, Clone)]
pub struct Body<const N: usize> {
    geometry: BodyGeometry,
    material: BodyMaterial,
    /// Stress `(σx, σy, τxy)` (Pa), uniform in the body (zero for rigid
    /// kinematics).
    pub stress: Vector3<f64>,
    /// Rate of the unknowns.
    pub velocity: SVector<f64, N>,
    /// Second rate of the unknowns.
    pub acceleration: SVector<f64, N>,
    /// Imposed unknowns, if any.
    pub prescribed: Option<Prescribed<N>>,
    /// Uniform tractions (Pa) on polygon edges, by edge index (edge k runs
    /// from vertex k to vertex k + 1); they keep their world direction.
    pub edge_tractions: Vec<(usize, Vec2)>,
    /// Total displacement of the unknowns since the start (for output).
    pub displacement: SVector<f64, N>,
    /// Contact group: contacts between groups may follow different laws
    /// (see [`super::ContactLaws`]). 0 by default.
    pub group: usize,
}

impl<const N: usize> Body<N> {
    fn with(geometry: BodyGeometry, material: BodyMaterial) -> Self {
        Self {
            geometry,
            material,
            stress: Vector3::zeros(),
            velocity: SVector::zeros(),
            acceleration: SVector::zeros(),
            prescribed: None,
            edge_tractions: Vec::new(),
            displacement: SVector::zeros(),
            group: 0,
        }
    }

    /// A polygon body from world vertices listed counter-clockwise (a DDA
    /// block). `index` names the body in errors: a polygon that is not
    /// simple, has zero area or runs clockwise, and a material with
    /// `ρ ≤ 0`, `E ≤ 0` or ν outside (−1, 0.5), are refused.
    ///
    /// # Errors
    /// [`ImplicitError::InvalidBlock`] naming `index` for a density or
    /// Young's modulus that is not finite and positive, or a Poisson's
    /// ratio outside (−1, 0.5) ([`BodyMaterial::validate`]);
    /// [`DismechError::InvalidPolygon`] naming `index` for fewer than
    /// three vertices, a vertex that is not finite, two consecutive
    /// vertices that coincide, crossing edges, moments of area that
    /// overflow, or vertices that run clockwise or enclose no area
    /// ([`PlacedPolygon::from_world`]).
    pub fn new(vertices: &[Point], material: BodyMaterial, index: usize) -> Result<Self> {
        material.validate(index)?;
        let polygon = PlacedPolygon::from_world(vertices, index)?;
        Ok(Self::with(BodyGeometry::Polygon(polygon), material))
    }

    /// An ellipse with semi-axes `a`, `b` (any order), axis `a` at `angle`
    /// (rad), centred at `centre`.
    ///
    /// # Errors
    /// [`ImplicitError::InvalidBlock`] naming `index` for a bad material (as
    /// [`Body::new`]); [`DismechError::InvalidParameter`] for a semi-axis
    /// that is not finite and positive, an angle or centre that is not
    /// finite, or semi-axes so far apart that the shape matrix is singular
    /// ([`PlacedEllipse::new`]).
    pub fn ellipse(
        centre: Point,
        a: f64,
        b: f64,
        angle: f64,
        material: BodyMaterial,
        index: usize,
    ) -> Result<Self> {
        material.validate(index)?;
        require_positive("semi-axis a", a)?;
        require_positive("semi-axis b", b)?;
        require_finite("ellipse angle", angle)?;
        let (s, c) = angle.sin_cos();
        let axes = Matrix2::new(c, -s, s, c) * Matrix2::new(a, 0.0, 0.0, b);
        Ok(Self::with(
            BodyGeometry::Ellipse(PlacedEllipse::new(centre, axes)?),
            material,
        ))
    }

    /// A disc of `radius` centred at `centre`.
    ///
    /// # Errors
    /// [`ImplicitError::InvalidBlock`] naming `index` for a bad material (as
    /// [`Body::new`]); [`DismechError::InvalidParameter`] for a radius that
    /// is not finite and positive or a centre that is not finite.
    pub fn circle(
        centre: Point,
        radius: f64,
        material: BodyMaterial,
        index: usize,
    ) -> Result<Self> {
        Self::ellipse(centre, radius, radius, 0.0, material, index)
    }

    /// A fixed wall, the bodies it holds on its left (start → end: a floor
    /// runs in +x).
    ///
    /// # Errors
    /// [`DismechError::DegenerateWall`] naming `index` for a wall of zero
    /// length or with an end point that is not finite.
    pub fn wall(segment: Segment, index: usize) -> Result<Self> {
        let finite = [segment.start, segment.end]
            .iter()
            .all(|p| p.x.is_finite() && p.y.is_finite());
        if !finite || segment.length() <= 0.0 {
            return Err(DismechError::DegenerateWall {
                wall: index,
                reason: "its end points must be finite and distinct",
            });
        }
        let material = BodyMaterial {
            density: 1.0,
            youngs_modulus: 1.0,
            poisson_ratio: 0.0,
            plane: PlaneState::Stress,
        };
        let mut body = Self::with(BodyGeometry::Wall(segment), material);
        body.prescribed = Some(Prescribed::fixed());
        Ok(body)
    }

    /// The geometry at the start of the next step.
    pub fn geometry(&self) -> &BodyGeometry {
        &self.geometry
    }

    /// Replace the geometry (the driver, after a committed step).
    pub(super) fn set_geometry(&mut self, geometry: BodyGeometry) {
        self.geometry = geometry;
    }

    /// The material.
    pub fn material(&self) -> &BodyMaterial {
        &self.material
    }

    /// The reference point (centroid) of the body's kinematics.
    pub fn centroid(&self) -> Point {
        self.geometry.reference()
    }

    /// Area (m², per metre of thickness; zero for a wall).
    pub fn area(&self) -> f64 {
        self.geometry.moments().area
    }

    /// The polygon of a polygon body.
    pub fn polygon(&self) -> Option<&PlacedPolygon> {
        match &self.geometry {
            BodyGeometry::Polygon(p) => Some(p),
            _ => None,
        }
    }

    /// Number of polygon vertices (0 for other shapes).
    pub fn vertex_count(&self) -> usize {
        self.polygon().map_or(0, PlacedPolygon::vertex_count)
    }

    /// Polygon vertex `k` in the world frame (the centroid for other
    /// shapes).
    pub fn vertex(&self, k: usize) -> Point {
        self.polygon().map_or(self.centroid(), |p| p.vertex(k))
    }

    /// Check the edge tractions of the body numbered `index`: each names
    /// an edge of a polygon (`0 ≤ edge < vertex count`; a traction on an
    /// ellipse, a circle or a wall has no edge to act on) and is finite.
    ///
    /// # Errors
    /// [`ImplicitError::InvalidEdgeTraction`] naming the body and the edge
    /// for a traction on a body that is not a polygon, on an edge index at
    /// or beyond the vertex count, or with a component that is not finite.
    pub fn validate_edge_tractions(&self, index: usize) -> Result<()> {
        let edges = self.vertex_count();
        for &(edge, traction) in &self.edge_tractions {
            let reason = if self.polygon().is_none() {
                EdgeTractionProblem::NotAPolygon
            } else if edge >= edges {
                EdgeTractionProblem::NoSuchEdge { edges }
            } else if !(traction.x.is_finite() && traction.y.is_finite()) {
                EdgeTractionProblem::NotFinite {
                    x: traction.x,
                    y: traction.y,
                }
            } else {
                continue;
            };
            return Err(DismechError::Implicit(ImplicitError::InvalidEdgeTraction {
                body: index,
                edge,
                reason,
            }));
        }
        Ok(())
    }

    /// Whether every unknown is imposed.
    pub fn is_fixed(&self) -> bool {
        self.prescribed
            .as_ref()
            .is_some_and(|p| p.mask.iter().all(|m| *m))
    }
}

/// What is wrong with an edge traction
/// ([`crate::implicit::ImplicitError::InvalidEdgeTraction`]).
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum EdgeTractionProblem {
    /// The body is not a polygon: it has no edge to load.
    #[error("the body is not a polygon and has no edges; apply a load to a polygon's edge")]
    NotAPolygon,
    /// The edge index is at or beyond the polygon's edge count.
    #[error("the block has {edges} edges, numbered 0 to {}", .edges - 1)]
    NoSuchEdge {
        /// The polygon's number of edges.
        edges: usize,
    },
    /// A component of the traction is not finite.
    #[error("the traction ({x}, {y}) Pa is not finite")]
    NotFinite {
        /// The traction's x component (Pa).
        x: f64,
        /// Its y component (Pa).
        y: f64,
    },
}
