//! `[[bodies]]`: the bodies, one table each, or a generator of many
//! (`circle-rows`, `lattice`).

use serde::Deserialize;

/// One entry of `[[bodies]]` (`kind` = `circle`, `ellipse`, `polygon`,
/// `rectangle`, `wall`, `circle-rows` or `lattice`).
#[derive(Debug, Clone, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BodySpec {
    /// A circle.
    Circle(CircleSpec),
    /// An ellipse.
    Ellipse(EllipseSpec),
    /// A polygon from its vertices, counter-clockwise.
    Polygon(PolygonSpec),
    /// A rectangle, centred and turned.
    Rectangle(RectangleSpec),
    /// A wall segment (implicit and limit drivers), the bodies on its
    /// left; it may move at a constant velocity (the limit driver's
    /// plate; the implicit driver's translated wall).
    Wall(WallSpec),
    /// Circles in a running bond in an open box ([`dismech::scene::CircleRows`]).
    CircleRows(CircleRowsSpec),
    /// Paper 002's lattice of rigid circles ([`dismech::limit::lattice::Lattice`]).
    Lattice(LatticeSpec),
    /// Paper 001's grid columns between a ground and a slip surface
    /// ([`dismech::hpm::SlopeGrids`]).
    GridColumns(GridColumnsSpec),
}

impl BodySpec {
    /// The `kind` as written.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Circle(_) => "circle",
            Self::Ellipse(_) => "ellipse",
            Self::Polygon(_) => "polygon",
            Self::Rectangle(_) => "rectangle",
            Self::Wall(_) => "wall",
            Self::CircleRows(_) => "circle-rows",
            Self::Lattice(_) => "lattice",
            Self::GridColumns(_) => "grid-columns",
        }
    }
}

/// [`dismech::implicit::PlaneState`].
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PlaneSpec {
    /// σ_z = 0.
    Stress,
    /// ε_z = 0.
    Strain,
}

/// A prescribed motion of a body: `kind` = `fixed` (either driver),
/// `sine` (implicit driver) or `constant-velocity` (explicit driver).
#[derive(Debug, Clone, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MotionSpec {
    /// At rest for the whole run (every unknown held at zero).
    Fixed(FixedSpec),
    /// A translation `u(t) = amplitude · direction · sin(2π frequency t)`.
    Sine(SineSpec),
    /// The body's `velocity` and `angular_velocity` kept for the whole
    /// run (explicit driver: [`dismech::scene::Particle::prescribed`]).
    ConstantVelocity(FixedSpec),
}

impl MotionSpec {
    /// The `kind` as written.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Fixed(_) => "fixed",
            Self::Sine(_) => "sine",
            Self::ConstantVelocity(_) => "constant-velocity",
        }
    }
}

/// No parameters.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FixedSpec {}

/// A sinusoidal translation.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SineSpec {
    /// Amplitude A (m).
    pub amplitude: f64,
    /// Frequency f (Hz).
    pub frequency: f64,
    /// Unit direction of the motion ([1, 0] by default).
    #[serde(default, deserialize_with = "super::exact::optional")]
    pub direction: Option<[f64; 2]>,
}

/// A circle.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CircleSpec {
    /// Centre (m).
    #[serde(deserialize_with = "super::exact::array")]
    pub centre: [f64; 2],
    /// Radius (m).
    pub radius: f64,
    /// Density ρ (kg/m³).
    pub density: Option<f64>,
    /// Young's modulus E (Pa): the implicit driver's deformable bodies.
    pub youngs_modulus: Option<f64>,
    /// Poisson's ratio ν: the implicit driver's deformable bodies.
    pub poisson_ratio: Option<f64>,
    /// `stress` (the default) or `strain`: the implicit driver's bodies.
    pub plane: Option<PlaneSpec>,
    /// Velocity of the centre (m/s) at the start; zero by default.
    #[serde(default, deserialize_with = "super::exact::optional")]
    pub velocity: Option<[f64; 2]>,
    /// Angular velocity (rad/s) at the start; zero by default.
    pub angular_velocity: Option<f64>,
    /// Prescribed motion (implicit driver).
    pub motion: Option<MotionSpec>,
    /// Contact group (implicit driver): `[[pair_laws]]` give laws per
    /// pair of groups; 0 by default.
    pub group: Option<usize>,
}

/// An ellipse.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EllipseSpec {
    /// Centre (m).
    #[serde(deserialize_with = "super::exact::array")]
    pub centre: [f64; 2],
    /// Semi-major axis a (m).
    pub semi_major: f64,
    /// Semi-minor axis b (m).
    pub semi_minor: f64,
    /// Angle of the major axis from +x (rad); 0 by default.
    pub angle: Option<f64>,
    /// Density ρ (kg/m³).
    pub density: Option<f64>,
    /// Young's modulus E (Pa): the implicit driver's deformable bodies.
    pub youngs_modulus: Option<f64>,
    /// Poisson's ratio ν: the implicit driver's deformable bodies.
    pub poisson_ratio: Option<f64>,
    /// `stress` (the default) or `strain`: the implicit driver's bodies.
    pub plane: Option<PlaneSpec>,
    /// Velocity of the centre (m/s) at the start; zero by default.
    #[serde(default, deserialize_with = "super::exact::optional")]
    pub velocity: Option<[f64; 2]>,
    /// Angular velocity (rad/s) at the start; zero by default.
    pub angular_velocity: Option<f64>,
    /// Prescribed motion (implicit driver).
    pub motion: Option<MotionSpec>,
    /// Contact group (implicit driver): `[[pair_laws]]` give laws per
    /// pair of groups; 0 by default.
    pub group: Option<usize>,
}

/// A polygon.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PolygonSpec {
    /// Vertices (m), counter-clockwise.
    #[serde(deserialize_with = "super::exact::each")]
    pub vertices: Vec<[f64; 2]>,
    /// Density ρ (kg/m³).
    pub density: Option<f64>,
    /// Young's modulus E (Pa): the implicit driver's deformable bodies.
    pub youngs_modulus: Option<f64>,
    /// Poisson's ratio ν: the implicit driver's deformable bodies.
    pub poisson_ratio: Option<f64>,
    /// `stress` (the default) or `strain`: the implicit driver's bodies.
    pub plane: Option<PlaneSpec>,
    /// Velocity of the centre (m/s) at the start; zero by default.
    #[serde(default, deserialize_with = "super::exact::optional")]
    pub velocity: Option<[f64; 2]>,
    /// Angular velocity (rad/s) at the start; zero by default.
    pub angular_velocity: Option<f64>,
    /// Prescribed motion (implicit driver).
    pub motion: Option<MotionSpec>,
    /// Contact group (implicit driver): `[[pair_laws]]` give laws per
    /// pair of groups; 0 by default.
    pub group: Option<usize>,
}

/// A rectangle.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RectangleSpec {
    /// Centre (m).
    #[serde(deserialize_with = "super::exact::array")]
    pub centre: [f64; 2],
    /// Width (m).
    pub width: f64,
    /// Height (m).
    pub height: f64,
    /// Angle of the rectangle's base from +x (rad); 0 by default.
    pub angle: Option<f64>,
    /// Density ρ (kg/m³).
    pub density: Option<f64>,
    /// Young's modulus E (Pa): the implicit driver's deformable bodies.
    pub youngs_modulus: Option<f64>,
    /// Poisson's ratio ν: the implicit driver's deformable bodies.
    pub poisson_ratio: Option<f64>,
    /// `stress` (the default) or `strain`: the implicit driver's bodies.
    pub plane: Option<PlaneSpec>,
    /// Velocity of the centre (m/s) at the start; zero by default.
    #[serde(default, deserialize_with = "super::exact::optional")]
    pub velocity: Option<[f64; 2]>,
    /// Angular velocity (rad/s) at the start; zero by default.
    pub angular_velocity: Option<f64>,
    /// Prescribed motion (implicit driver).
    pub motion: Option<MotionSpec>,
    /// Contact group (implicit driver): `[[pair_laws]]` give laws per
    /// pair of groups; 0 by default.
    pub group: Option<usize>,
}

/// A wall segment, fixed or (limit driver) moving.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WallSpec {
    /// Start point (m).
    #[serde(deserialize_with = "super::exact::array")]
    pub start: [f64; 2],
    /// End point (m); the bodies lie on the left of start → end.
    #[serde(deserialize_with = "super::exact::array")]
    pub end: [f64; 2],
    /// Velocity: in the limit driver the wall is the plate that drives
    /// the collapse; in the implicit driver the wall is translated at it
    /// (`u(t) = v t`). Fixed when absent.
    #[serde(default, deserialize_with = "super::exact::optional")]
    pub velocity: Option<[f64; 2]>,
    /// Contact group (implicit driver): `[[pair_laws]]` give laws per
    /// pair of groups; 0 by default.
    pub group: Option<usize>,
}

/// Circles in a running bond, filling an open box from the floor.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CircleRowsSpec {
    /// Number of circles.
    pub count: usize,
    /// Radius (m).
    pub radius: f64,
    /// Circles in a full row.
    pub per_row: usize,
    /// Vertical distance between rows (m).
    pub row_pitch: f64,
    /// Gap between the lowest row and the floor (m).
    pub clearance: f64,
    /// Density (kg/m³).
    pub density: f64,
}

/// Paper 002's lattice.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LatticeSpec {
    /// `u` (half footing, smooth symmetry wall) or `l`.
    pub model: LatticeModel,
    /// Columns m (even, ≥ 2).
    pub m: usize,
    /// Elements per column n (≥ 1).
    pub n: usize,
    /// Elements under the plate n' (U-model), in 1..=n.
    pub loaded: Option<usize>,
    /// Whether the elements may rotate (true by default).
    pub rolling: Option<bool>,
    /// Element radius R (m); 1 by default.
    pub radius: Option<f64>,
    /// Strength of the base and far walls (N/m); 2 C_p by default.
    pub wall_cohesion: Option<f64>,
}

/// Which lattice.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LatticeModel {
    /// Half footing, plate on n' elements, smooth symmetry wall.
    U,
    /// The plate on the whole first column.
    L,
}

/// The material, start and motion of a single body, borrowed from its
/// table.
#[derive(Debug, Clone, Copy)]
pub struct Common<'a> {
    /// Density ρ (kg/m³).
    pub density: Option<f64>,
    /// Young's modulus E (Pa).
    pub youngs_modulus: Option<f64>,
    /// Poisson's ratio ν.
    pub poisson_ratio: Option<f64>,
    /// Plane stress or strain.
    pub plane: Option<PlaneSpec>,
    /// Velocity at the start (m/s).
    pub velocity: Option<[f64; 2]>,
    /// Angular velocity at the start (rad/s).
    pub angular_velocity: Option<f64>,
    /// Prescribed motion.
    pub motion: Option<&'a MotionSpec>,
}

macro_rules! common_of {
    ($($spec:ty),*) => {$(
        impl $spec {
            /// The body's material, start and motion.
            pub fn common(&self) -> Common<'_> {
                Common {
                    density: self.density,
                    youngs_modulus: self.youngs_modulus,
                    poisson_ratio: self.poisson_ratio,
                    plane: self.plane,
                    velocity: self.velocity,
                    angular_velocity: self.angular_velocity,
                    motion: self.motion.as_ref(),
                }
            }
        }
    )*};
}

common_of!(CircleSpec, EllipseSpec, PolygonSpec, RectangleSpec);

impl BodySpec {
    /// The material, start and motion of a single body (none for a wall or
    /// a generator).
    pub fn common(&self) -> Option<Common<'_>> {
        match self {
            Self::Circle(b) => Some(b.common()),
            Self::Ellipse(b) => Some(b.common()),
            Self::Polygon(b) => Some(b.common()),
            Self::Rectangle(b) => Some(b.common()),
            Self::Wall(_) | Self::CircleRows(_) | Self::Lattice(_) | Self::GridColumns(_) => None,
        }
    }
}

impl BodySpec {
    /// The contact group given by the `group` key of a single body or a
    /// wall (none for a generator, which takes no such key).
    pub fn group(&self) -> Option<usize> {
        match self {
            Self::Circle(b) => b.group,
            Self::Ellipse(b) => b.group,
            Self::Polygon(b) => b.group,
            Self::Rectangle(b) => b.group,
            Self::Wall(b) => b.group,
            Self::CircleRows(_) | Self::Lattice(_) | Self::GridColumns(_) => None,
        }
    }
}

/// The columns of a slope: ESRI ASCII grids of the ground, the slip
/// surface and, optionally, the water table, on one lattice.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridColumnsSpec {
    /// The ground's elevations (a path relative to the scenario file's
    /// folder).
    pub ground: String,
    /// The slip surface's elevations.
    pub slip: String,
    /// The water table's elevations.
    pub water: Option<String>,
}
