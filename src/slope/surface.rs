//! Trial slip surfaces over a DEM (spheres and ellipsoids), the columns
//! each one cuts out of the ground, and why a surface may be refused.
//!
//! As in Scoops3D (Reid, Christian & Brien, USGS Techniques and Methods
//! 14-A1, 2015), the columns of a trial surface are the DEM cells whose
//! centre lies where the surface's lower half is below the ground: the
//! base of a column is the surface at the cell centre, its top the ground
//! there. A surface that reaches the edge of the grid (a column in the
//! outermost row or column) or whose footprint covers a no-data cell
//! leaves the DEM and is refused, as Scoops3D refuses surfaces that meet
//! the DEM's boundary. Every column is kept, also where the footprint cuts
//! the ground in separate patches.

use super::error::SlopeError;
use crate::error::{require_finite, require_positive, Result};

use super::terrain::Terrain;

/// A trial slip surface: the lower half of a closed surface over the plan.
pub trait TrialSurface {
    /// Names of the parameters, in the order of [`Self::parameters`] (the
    /// columns of the critical surfaces' CSV).
    const PARAMETERS: &'static [&'static str];

    /// The parameters (m, and radians for angles).
    fn parameters(&self) -> Vec<f64>;

    /// The plan box `(x_min, x_max, y_min, y_max)` outside which the
    /// surface has no point.
    fn plan_bounds(&self) -> (f64, f64, f64, f64);

    /// The surface's lower half over the plan point `(x, y)`: its height z
    /// and gradient `(∂z/∂x, ∂z/∂y)`, `None` outside the footprint or on
    /// its rim (where the gradient is infinite).
    fn base(&self, x: f64, y: f64) -> Option<(f64, (f64, f64))>;

    /// The surface's centre `(x, y, z)`: the point the axis of moment
    /// equilibrium of Bishop's method passes through
    /// ([`super::bishop_ground`]).
    fn centre(&self) -> (f64, f64, f64);
}

/// A sphere: centre `(x, y, z)` and radius (m), the trial surface of
/// Scoops3D. Its lower half is `z_b = z − √(R² − r²)` with gradient
/// `(x − x_c, y − y_c) / √(R² − r²)`, r the plan distance to the centre.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    /// x of the centre (m).
    pub x: f64,
    /// y of the centre (m).
    pub y: f64,
    /// z of the centre (m).
    pub z: f64,
    /// Radius (m).
    pub radius: f64,
}

impl Sphere {
    /// A sphere, checked.
    ///
    /// # Errors
    /// [`crate::error::DismechError::InvalidParameter`] naming the value
    /// for a centre coordinate that is not finite or a radius that is not
    /// finite and positive.
    pub fn new(x: f64, y: f64, z: f64, radius: f64) -> Result<Self> {
        require_finite("sphere centre x", x)?;
        require_finite("sphere centre y", y)?;
        require_finite("sphere centre z", z)?;
        require_positive("sphere radius", radius)?;
        Ok(Self { x, y, z, radius })
    }
}

impl TrialSurface for Sphere {
    const PARAMETERS: &'static [&'static str] = &["x", "y", "z", "radius"];

    fn parameters(&self) -> Vec<f64> {
        vec![self.x, self.y, self.z, self.radius]
    }

    fn plan_bounds(&self) -> (f64, f64, f64, f64) {
        let r = self.radius;
        (self.x - r, self.x + r, self.y - r, self.y + r)
    }

    fn base(&self, x: f64, y: f64) -> Option<(f64, (f64, f64))> {
        let (dx, dy) = (x - self.x, y - self.y);
        let s2 = self.radius * self.radius - (dx * dx + dy * dy);
        if s2 <= 0.0 {
            return None;
        }
        let s = s2.sqrt();
        Some((self.z - s, (dx / s, dy / s)))
    }

    fn centre(&self) -> (f64, f64, f64) {
        (self.x, self.y, self.z)
    }
}

/// An ellipsoid with a vertical axis, turned in plan: centre `(x, y, z)`,
/// semi-axes `along` (in the plan direction `azimuth`, radians
/// counter-clockwise from +x), `across` (perpendicular to it in plan) and
/// `vertical` (m), the trial surface of r.slope.stability (Mergili et
/// al., Geosci. Model Dev. 7, 2014) with its long axis along the fall line
/// but not tilted with the slope. With `u`, `v` the plan offsets along and
/// across, `q = 1 − u²/a² − v²/b²`, its lower half is
/// `z_b = z − c √q`, with `∂z_b/∂u = c u / (a² √q)` and
/// `∂z_b/∂v = c v / (b² √q)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipsoid {
    /// x of the centre (m).
    pub x: f64,
    /// y of the centre (m).
    pub y: f64,
    /// z of the centre (m).
    pub z: f64,
    /// Semi-axis along `azimuth` (m).
    pub along: f64,
    /// Horizontal semi-axis across `azimuth` (m).
    pub across: f64,
    /// Vertical semi-axis (m).
    pub vertical: f64,
    /// Plan direction of the `along` axis (radians from +x, counter-clockwise).
    pub azimuth: f64,
}

impl Ellipsoid {
    /// An ellipsoid, checked.
    ///
    /// # Errors
    /// [`crate::error::DismechError::InvalidParameter`] naming the value
    /// for a centre coordinate or azimuth that is not finite or a semi-axis
    /// that is not finite and positive.
    pub fn new(
        centre: (f64, f64, f64),
        along: f64,
        across: f64,
        vertical: f64,
        azimuth: f64,
    ) -> Result<Self> {
        require_finite("ellipsoid centre x", centre.0)?;
        require_finite("ellipsoid centre y", centre.1)?;
        require_finite("ellipsoid centre z", centre.2)?;
        require_positive("ellipsoid semi-axis along", along)?;
        require_positive("ellipsoid semi-axis across", across)?;
        require_positive("ellipsoid vertical semi-axis", vertical)?;
        require_finite("ellipsoid azimuth", azimuth)?;
        Ok(Self {
            x: centre.0,
            y: centre.1,
            z: centre.2,
            along,
            across,
            vertical,
            azimuth,
        })
    }
}

impl TrialSurface for Ellipsoid {
    const PARAMETERS: &'static [&'static str] =
        &["x", "y", "z", "along", "across", "vertical", "azimuth"];

    fn parameters(&self) -> Vec<f64> {
        vec![
            self.x,
            self.y,
            self.z,
            self.along,
            self.across,
            self.vertical,
            self.azimuth,
        ]
    }

    fn plan_bounds(&self) -> (f64, f64, f64, f64) {
        let (s, c) = self.azimuth.sin_cos();
        let (a, b) = (self.along, self.across);
        let hx = (a * a * c * c + b * b * s * s).sqrt();
        let hy = (a * a * s * s + b * b * c * c).sqrt();
        (self.x - hx, self.x + hx, self.y - hy, self.y + hy)
    }

    fn base(&self, x: f64, y: f64) -> Option<(f64, (f64, f64))> {
        let (s, c) = self.azimuth.sin_cos();
        let (dx, dy) = (x - self.x, y - self.y);
        let (u, v) = (dx * c + dy * s, -dx * s + dy * c);
        let (a2, b2) = (self.along * self.along, self.across * self.across);
        let q = 1.0 - u * u / a2 - v * v / b2;
        if q <= 0.0 {
            return None;
        }
        let root = q.sqrt();
        let (zu, zv) = (
            self.vertical * u / (a2 * root),
            self.vertical * v / (b2 * root),
        );
        Some((
            self.z - self.vertical * root,
            (zu * c - zv * s, zu * s + zv * c),
        ))
    }

    fn centre(&self) -> (f64, f64, f64) {
        (self.x, self.y, self.z)
    }
}

/// One column of a trial surface: a DEM cell whose centre lies where the
/// surface is below the ground.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlipColumn {
    /// Grid row, 0 at the top (north).
    pub row: usize,
    /// Grid column, 0 at the left (west).
    pub column: usize,
    /// Ground height at the cell centre (m).
    pub ground: f64,
    /// Height of the slip surface at the cell centre (m), below `ground`.
    pub base: f64,
    /// Gradient `(∂z/∂x, ∂z/∂y)` of the slip surface at the cell centre.
    pub gradient: (f64, f64),
    /// Pressure head of pore water on the base (m): the water table,
    /// lowered to the ground where it lies above it, less the base height,
    /// and 0 where the table lies below the base or there is none.
    pub pressure_head: f64,
}

/// Limits on the trial surfaces a search keeps; a surface outside them is
/// refused before its Fs is computed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceLimits {
    /// The fewest columns (≥ 1).
    pub min_columns: usize,
    /// Volume range `(min, max)` (m³): `Σ (ground − base) d²`.
    pub volume: (f64, f64),
    /// Plan area range `(min, max)` (m²): columns × d².
    pub area: (f64, f64),
    /// Depth range `(min, max)` (m): the largest vertical thickness
    /// `ground − base` of a column.
    pub depth: (f64, f64),
}

impl Default for SurfaceLimits {
    /// At least 4 columns; no limit on volume, area or depth.
    fn default() -> Self {
        Self {
            min_columns: 4,
            volume: (0.0, f64::INFINITY),
            area: (0.0, f64::INFINITY),
            depth: (0.0, f64::INFINITY),
        }
    }
}

impl SurfaceLimits {
    /// Check the values.
    ///
    /// # Errors
    /// [`crate::error::DismechError::InvalidParameter`] for no column
    /// allowed (`min_columns` 0) or a bound that is negative or NaN (an
    /// upper bound may be infinite); [`crate::slope::SlopeError::InvalidRange`]
    /// for a range whose minimum lies above its maximum.
    pub fn validate(&self) -> Result<()> {
        require_positive("surface limits: min_columns", self.min_columns as f64)?;
        for (name, (lo, hi)) in [
            ("surface limits: volume range", self.volume),
            ("surface limits: area range", self.area),
            ("surface limits: depth range", self.depth),
        ] {
            crate::error::require_non_negative(name, lo)?;
            if hi.is_nan() || hi < 0.0 {
                return Err(crate::error::DismechError::InvalidParameter {
                    name,
                    value: hi,
                    requirement: "its upper bound must be >= 0 (infinite for no limit)",
                });
            }
            if lo > hi {
                return Err(crate::error::DismechError::Slope(
                    SlopeError::InvalidRange {
                        name,
                        low: lo,
                        high: hi,
                    },
                ));
            }
        }
        Ok(())
    }
}

/// Why a trial surface gave no Fs. These are not errors: a search counts
/// them ([`super::SearchCounts`]) and goes on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Refusal {
    /// The family's trial has its centre outside the grid or over a
    /// no-data cell (its height above the ground is not defined there).
    CentreOffDem,
    /// A column lies in the grid's outermost row or column: the surface
    /// would go on beyond the DEM.
    LeavesDem,
    /// The footprint covers a no-data cell of the DEM, or a column lacks
    /// data it needs (water table, bedrock, a layer's bottom, r_u).
    NoData,
    /// Fewer columns than [`SurfaceLimits::min_columns`] (none where the
    /// surface stays above the ground).
    TooFewColumns,
    /// Volume outside [`SurfaceLimits::volume`].
    Volume,
    /// Plan area outside [`SurfaceLimits::area`].
    Area,
    /// Depth outside [`SurfaceLimits::depth`].
    Depth,
    /// Nothing drives the slide: the plan resultant of the base shear, or
    /// the driving force along it, is not above
    /// [`crate::hpm::MIN_DRIVING_RATIO`] of the weight (level ground).
    NothingDrives,
    /// The strength `Σ (c A + N' tan φ)` is not positive (pore pressure or
    /// a seismic force lifting the columns off their bases).
    NoStrength,
    /// Bishop's method: a column's `m_α` is at or below the floor
    /// [`super::BishopSettings::m_alpha_floor`] ([`super::BishopFailure::SmallMAlpha`]).
    SmallMAlpha,
    /// Bishop's method: the iteration of F did not settle
    /// ([`super::BishopFailure::NotConverged`]).
    NotConverged,
}

impl Refusal {
    /// Every reason, in the order of [`Refusal::index`].
    pub const ALL: [Refusal; 11] = [
        Refusal::CentreOffDem,
        Refusal::LeavesDem,
        Refusal::NoData,
        Refusal::TooFewColumns,
        Refusal::Volume,
        Refusal::Area,
        Refusal::Depth,
        Refusal::NothingDrives,
        Refusal::NoStrength,
        Refusal::SmallMAlpha,
        Refusal::NotConverged,
    ];

    /// Position in [`Refusal::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }
}

impl std::fmt::Display for Refusal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::CentreOffDem => {
                "its centre lies outside the grid or over a cell without ground data"
            }
            Self::LeavesDem => "a column lies on the grid's edge: the surface goes on beyond the DEM",
            Self::NoData => {
                "its footprint covers a cell without ground data, or a column lacks data it needs (water table, bedrock, a layer's bottom, r_u)"
            }
            Self::TooFewColumns => "it cuts fewer columns than the limits' least",
            Self::Volume => "its volume lies outside the limits",
            Self::Area => "its plan area lies outside the limits",
            Self::Depth => "its depth lies outside the limits",
            Self::NothingDrives => "nothing drives the slide (level ground)",
            Self::NoStrength => {
                "its strength is not positive (pore pressure or a seismic force lifts the columns off their bases)"
            }
            Self::SmallMAlpha => "a column's m_alpha is at or below Bishop's floor",
            Self::NotConverged => "Bishop's iteration of F did not settle",
        })
    }
}

/// The columns the trial surface cuts out of the terrain, into `columns`
/// (cleared first), in grid order (row by row from the top). Over a
/// bedrock ([`Terrain::with_bedrock`]) a base below it is raised to it and
/// takes its gradient ([`Terrain::bedrock_at`]).
///
/// # Errors
/// (A refusal, not a [`crate::error::DismechError`].)
/// [`Refusal::NoData`] when a cell of the footprint has no ground data or a
/// column has no water-table or bedrock data; [`Refusal::LeavesDem`] when a column lies
/// on the grid's edge.
pub fn surface_columns<S: TrialSurface>(
    terrain: &Terrain,
    surface: &S,
    columns: &mut Vec<SlipColumn>,
) -> std::result::Result<(), Refusal> {
    columns.clear();
    let dem = &terrain.dem().raster;
    let water = terrain.water().map(|w| &w.raster);
    let bedrock = terrain.bedrock().is_some();
    let (rows, cols) = (dem.rows(), dem.columns());
    let (x0, y0) = dem.lower_left();
    let d = dem.cell_size();
    let (xmin, xmax, ymin, ymax) = surface.plan_bounds();
    // Cells whose centre may lie in the box, one more on each side against
    // rounding (the surface's own test decides).
    let clamp = |v: f64, n: usize| -> usize {
        if v.is_nan() || v <= 0.0 {
            0
        } else if v >= (n - 1) as f64 {
            n - 1
        } else {
            v as usize
        }
    };
    let c_lo = clamp(((xmin - x0) / d - 0.5).floor() - 1.0, cols);
    let c_hi = clamp(((xmax - x0) / d - 0.5).ceil() + 1.0, cols);
    let r_lo = clamp((rows as f64 - 0.5 - (ymax - y0) / d).floor() - 1.0, rows);
    let r_hi = clamp((rows as f64 - 0.5 - (ymin - y0) / d).ceil() + 1.0, rows);
    for r in r_lo..=r_hi {
        for c in c_lo..=c_hi {
            let (x, y) = dem.cell_centre(r, c);
            let Some((mut base, mut gradient)) = surface.base(x, y) else {
                continue;
            };
            let Some(ground) = dem.get(r, c) else {
                return Err(Refusal::NoData);
            };
            if base >= ground {
                continue;
            }
            if bedrock {
                let Some((rock, slope)) = terrain.bedrock_at(r, c) else {
                    return Err(Refusal::NoData);
                };
                if base < rock {
                    (base, gradient) = (rock, slope);
                    if base >= ground {
                        continue;
                    }
                }
            }
            if r == 0 || c == 0 || r + 1 == rows || c + 1 == cols {
                return Err(Refusal::LeavesDem);
            }
            let pressure_head = match water {
                None => 0.0,
                Some(w) => match w.get(r, c) {
                    None => return Err(Refusal::NoData),
                    Some(table) => (table.min(ground) - base).max(0.0),
                },
            };
            columns.push(SlipColumn {
                row: r,
                column: c,
                ground,
                base,
                gradient,
                pressure_head,
            });
        }
    }
    Ok(())
}
