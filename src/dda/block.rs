//! A DDA block: a simple polygon with six unknowns `d = (u₀, v₀, r₀, εx, εy,
//! γxy)` about its centroid (paper 003 eqs. 14–16), its material, and the
//! element matrices of the weak form eq. (2): elastic stiffness, inertia,
//! body force and edge tractions.

use std::sync::Arc;

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use crate::error::{DismechError, Result};
use crate::math::{Point, Pose2, Vec2};
use crate::shape::{Polygon, Shape};

/// A 6-vector of block unknowns.
pub type Dof6 = SVector<f64, 6>;
/// A 6×6 block matrix.
pub type Mat6 = SMatrix<f64, 6, 6>;

/// Plane stress (the classic DDA choice) or plane strain.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PlaneState {
    /// `σ_z = 0`.
    #[default]
    Stress,
    /// `ε_z = 0`.
    Strain,
}

/// Elastic and inertial properties of a block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockMaterial {
    /// Density ρ (kg/m³).
    pub density: f64,
    /// Young's modulus E (Pa).
    pub youngs_modulus: f64,
    /// Poisson's ratio ν, in (−1, 0.5).
    pub poisson_ratio: f64,
    /// Plane stress or plane strain.
    pub plane: PlaneState,
}

/// Total displacement of the prescribed unknowns of a block as a function
/// of time since the start, `t ↦ (u₀, v₀, r₀, εx, εy, γxy)`.
pub type Motion = Arc<dyn Fn(f64) -> [f64; 6] + Send + Sync>;

/// Unknowns of a block whose values are imposed (kinematic supports).
#[derive(Clone)]
pub struct Prescribed {
    /// Which of the six unknowns are imposed.
    pub mask: [bool; 6],
    /// Their total displacement since `t = 0`.
    pub motion: Motion,
}

impl std::fmt::Debug for Prescribed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Prescribed")
            .field("mask", &self.mask)
            .finish()
    }
}

impl Prescribed {
    /// Every unknown held at zero: a fixed rigid block.
    pub fn fixed() -> Self {
        Self {
            mask: [true; 6],
            motion: Arc::new(|_| [0.0; 6]),
        }
    }

    /// A rigid block translated by `motion(t)`: rotation and strains held at zero.
    pub fn translation(motion: impl Fn(f64) -> Vec2 + Send + Sync + 'static) -> Self {
        Self {
            mask: [true; 6],
            motion: Arc::new(move |t| {
                let u = motion(t);
                [u.x, u.y, 0.0, 0.0, 0.0, 0.0]
            }),
        }
    }
}

/// One DDA block and its state.
#[derive(Debug, Clone)]
pub struct Block {
    polygon: Polygon,
    centroid: Point,
    material: BlockMaterial,
    /// Stress `(σx, σy, τxy)` (Pa), uniform in the block.
    pub stress: Vector3<f64>,
    /// Rate of the six unknowns.
    pub velocity: Dof6,
    /// Second rate of the six unknowns.
    pub acceleration: Dof6,
    /// Imposed unknowns, if any.
    pub prescribed: Option<Prescribed>,
    /// Uniform tractions (Pa) on edges, by edge index (edge k runs from
    /// vertex k to vertex k + 1); they keep their world direction.
    pub edge_tractions: Vec<(usize, Vec2)>,
    /// Total displacement of the unknowns since the start (for output).
    pub displacement: Dof6,
}

impl Block {
    /// A block from world vertices listed counter-clockwise. `index` names
    /// the block in errors: a polygon that is not simple, has zero area or
    /// runs clockwise, and a material with `ρ ≤ 0`, `E ≤ 0` or ν outside
    /// (−1, 0.5), are refused.
    pub fn new(vertices: &[Point], material: BlockMaterial, index: usize) -> Result<Self> {
        let bad = |name: &'static str, value: f64, requirement: &'static str| {
            DismechError::InvalidBlock {
                block: index,
                name,
                value,
                requirement,
            }
        };
        if !(material.density.is_finite() && material.density > 0.0) {
            return Err(bad("density", material.density, "must be finite and > 0"));
        }
        if !(material.youngs_modulus.is_finite() && material.youngs_modulus > 0.0) {
            return Err(bad(
                "Young's modulus",
                material.youngs_modulus,
                "must be finite and > 0",
            ));
        }
        if !(material.poisson_ratio.is_finite()
            && material.poisson_ratio > -1.0
            && material.poisson_ratio < 0.5)
        {
            return Err(bad(
                "Poisson's ratio",
                material.poisson_ratio,
                "must lie in (-1, 0.5)",
            ));
        }
        let (polygon, centroid) = Polygon::from_world(vertices, index)?;
        Ok(Self {
            polygon,
            centroid,
            material,
            stress: Vector3::zeros(),
            velocity: Dof6::zeros(),
            acceleration: Dof6::zeros(),
            prescribed: None,
            edge_tractions: Vec::new(),
            displacement: Dof6::zeros(),
        })
    }

    /// The polygon in its centroid frame.
    pub fn polygon(&self) -> &Polygon {
        &self.polygon
    }

    /// The centroid (world).
    pub fn centroid(&self) -> Point {
        self.centroid
    }

    /// The pose of the centroid frame (no rotation: the polygon's
    /// vertices are kept in world orientation).
    pub fn pose(&self) -> Pose2 {
        Pose2::new(self.centroid.x, self.centroid.y, 0.0)
    }

    /// The material.
    pub fn material(&self) -> &BlockMaterial {
        &self.material
    }

    /// Area (m², per metre of thickness).
    pub fn area(&self) -> f64 {
        self.polygon.measure()
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.polygon.vertices().len()
    }

    /// Vertex `k` in the world frame.
    pub fn vertex(&self, k: usize) -> Point {
        let v = self.polygon.vertices();
        self.centroid + v[k % v.len()].coords
    }

    /// `[T(x, y)]` of eq. (15) at the world point `p`.
    pub fn displacement_matrix(&self, p: &Point) -> SMatrix<f64, 2, 6> {
        Polygon::dda_displacement_matrix(p.x - self.centroid.x, p.y - self.centroid.y)
    }

    /// Elastic matrix `D` with `σ = D ε`, `ε = (εx, εy, γxy)`.
    pub fn elastic_matrix(&self) -> Matrix3<f64> {
        let (e, nu) = (self.material.youngs_modulus, self.material.poisson_ratio);
        let (e, nu) = match self.material.plane {
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

    /// Elastic stiffness `A D` on the strain unknowns (from `∫σ·δε dΩ`, eq. 2).
    pub fn stiffness(&self) -> Mat6 {
        let mut k = Mat6::zeros();
        k.fixed_view_mut::<3, 3>(3, 3)
            .copy_from(&(self.elastic_matrix() * self.area()));
        k
    }

    /// Internal force of the current stress, `A (0, 0, 0, σx, σy, τxy)`.
    pub fn stress_force(&self) -> Dof6 {
        let mut f = Dof6::zeros();
        f.fixed_rows_mut::<3>(3)
            .copy_from(&(self.stress * self.area()));
        f
    }

    /// Consistent mass `ρ ∫ Tᵀ T dΩ` (from `∫ρ ü·δu dΩ`, eq. 2), exact from
    /// the polygon's area and second moments: with `T = T₀ + x Tx + y Ty`
    /// about the centroid, `∫TᵀT = A T₀ᵀT₀ + Ixx TxᵀTx + Iyy TyᵀTy + Ixy
    /// (TxᵀTy + TyᵀTx)`.
    pub fn mass(&self) -> Mat6 {
        let t0 = Polygon::dda_displacement_matrix(0.0, 0.0);
        let tx = Polygon::dda_displacement_matrix(1.0, 0.0) - t0;
        let ty = Polygon::dda_displacement_matrix(0.0, 1.0) - t0;
        let [ixx, iyy, ixy] = self.polygon.second_moments();
        let m = t0.transpose() * t0 * self.area()
            + tx.transpose() * tx * ixx
            + ty.transpose() * ty * iyy
            + (tx.transpose() * ty + ty.transpose() * tx) * ixy;
        m * self.material.density
    }

    /// External load: body force `ρ A g` on (u₀, v₀) plus the edge
    /// tractions, `∫ Tᵀ t dΓ = L Tᵀ(midpoint) t` (T is linear along an edge).
    pub fn external_force(&self, gravity: &Vec2) -> Dof6 {
        let mut f = Dof6::zeros();
        let w = self.material.density * self.area();
        f[0] = w * gravity.x;
        f[1] = w * gravity.y;
        for &(edge, traction) in &self.edge_tractions {
            let (a, b) = (self.vertex(edge), self.vertex(edge + 1));
            let mid = Point::from((a.coords + b.coords) * 0.5);
            f += self.displacement_matrix(&mid).transpose() * traction * (b - a).norm();
        }
        f
    }

    /// Accept a step's increment `d`: move the vertices by `T d` (eq. 14),
    /// add `D ε` to the stress, and rebuild the polygon about its new
    /// centroid. `index` names the block if the polygon became invalid.
    pub fn apply_increment(&mut self, d: &Dof6, index: usize) -> Result<()> {
        let moved: Vec<Point> = (0..self.vertex_count())
            .map(|k| {
                let p = self.vertex(k);
                p + self.displacement_matrix(&p) * d
            })
            .collect();
        let (polygon, centroid) = Polygon::from_world(&moved, index)?;
        self.stress += self.elastic_matrix() * d.fixed_rows::<3>(3);
        self.polygon = polygon;
        self.centroid = centroid;
        self.displacement += d;
        Ok(())
    }
}
