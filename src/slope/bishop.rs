//! Bishop's simplified method in 3D (Hungr, "An extension of Bishop's
//! simplified method of slope stability analysis to three dimensions",
//! Géotechnique 37(1), 1987) on the columns of a trial surface: the same
//! columns, weights, base strengths, pore pressures, seismic load and
//! sliding direction as Hovland's method ([`super::hovland_ground`]; the
//! column quantities are computed by the same code), but each column's
//! normal force taken from its vertical equilibrium and the Fs from the
//! moment equilibrium of the whole slide about a horizontal axis.
//!
//! **Notation** (per column, as in [`super::hovland_ground`]): weight `W`,
//! base gradient `(z_x, z_y)`, `ρ = √(1 + z_x² + z_y²)`, so that the base's
//! true dip γ has `cos γ = 1/ρ`; plan sliding direction `s`; the base's
//! slope along it `a = z_x s_x + z_y s_y` and its dip along the sliding
//! direction α, `sin α = −a / √(1 + a²)` (positive where the base descends
//! in the direction of sliding); true base area `A = d² ρ`; c, φ of the
//! layer the base passes through; pore pressure u (`γ_w h_p` or `r_u σ_v`).
//!
//! **Normal force** (Hungr 1987: the vertical equilibrium of a column with
//! the vertical shear forces between columns neglected, as in Bishop's
//! simplified method): `N cos γ + S sin α = W`, with the mobilised base
//! shear `S = (c A + (N − u A) tan φ) / F` acting against the sliding
//! direction, gives
//!
//! ```text
//! N = (W − (c A − u A tan φ) sin α / F) / m_α,   m_α = cos γ + sin α tan φ / F.
//! ```
//!
//! A column whose effective normal force `N − u A` comes out negative has
//! no frictional strength left (as in Hovland's method here): its N is
//! taken from the same equilibrium with φ = 0, `N = (W − c A sin α / F) / cos γ`,
//! and `N' = 0`. The horizontal seismic force `k_h W` does not enter the
//! vertical equilibrium.
//!
//! **Moment equilibrium** about the axis through the surface's centre
//! ([`super::TrialSurface::centre`]; for a sphere, its centre), horizontal
//! and perpendicular to the sliding direction:
//!
//! ```text
//! F = Σ (c A + N' tan φ) R / Σ (W x − N f + k_h W e)
//! ```
//!
//! with, for the column's base point P (the surface at the cell centre)
//! and `r = P − C`, the axis `ê = (s_y, −s_x, 0)` and the lever vector
//! `l = ê × r`: the shear's arm `R = t · l` (t the unit base tangent along
//! the sliding direction), the weight's arm `x = −l_z` (the horizontal
//! distance from the axis along the sliding direction, positive upslope of
//! the axis), the normal force's arm `f = n · l` (n the unit base normal
//! into the ground; zero for a sphere, whose normals pass through the
//! centre, nonzero for an ellipsoid) and the seismic force's arm
//! `e = z_C − z_m`, the height of the axis above the column's mid-height
//! (the centroid of a column of one unit weight; taken for layered columns
//! too). These are the terms of Hungr's moment equation, written as the
//! exact moments of the forces about the axis. On a plane cut through the
//! centre along the sliding direction (a 2D section) they are Bishop's 2D
//! terms: `R` the radius, `x = R sin α`.
//!
//! **Iteration**: F appears on both sides; it is found by fixed-point
//! iteration from Hovland's Fs of the same columns until two iterates
//! agree to [`BISHOP_TOLERANCE`] relative, at most [`BISHOP_MAX_ITERATIONS`]
//! times (most surfaces settle in tens of iterations; a few coarse ones,
//! of under 30 columns, converge slowly: of the 47 128 of 100 000 random
//! ellipsoids over the shipped terrain that gave an Fs, 54 needed more
//! than 200, none more than 1000). A surface with no driving moment about
//! the axis is refused as [`Refusal::NothingDrives`].
//!
//! **The known defect of Bishop's method**: where a base rises steeply in
//! the sliding direction (sin α < 0, at the toe), `m_α` falls towards zero
//! and N grows without bound. A column with `m_α` at or below a floor,
//! [`MIN_M_ALPHA`] = 0.2 unless [`BishopSettings::with_m_alpha_floor`]
//! sets another (Whitman & Bailey, J. Soil Mech. Found. Div. ASCE 93(4),
//! 1967, advise against trusting Bishop's method below 0.2), refuses the
//! surface, naming the column ([`BishopFailure::SmallMAlpha`]); a search
//! counts it as [`Refusal::SmallMAlpha`].
//!
//! (Hungr's equation numbers are not given here: the text of the paper was
//! not at hand when this was written; the equations above are derived from
//! the method's stated assumptions and checked by the tests:
//! tests/slope_bishop.rs.)

use super::error::SlopeError;
use super::ground::{ColumnGround, Ground};
use super::hovland::SurfaceFs;
use super::hovland::{column_terms, finish, surface_setup};
use super::material::{SlopeLoads, SlopeMaterial};
use super::surface::{Refusal, SlipColumn, SurfaceLimits};
use super::terrain::Terrain;

/// The relative change of F between two iterates at which Bishop's
/// iteration stops.
pub const BISHOP_TOLERANCE: f64 = 1e-12;

/// The most iterations of Bishop's F.
pub const BISHOP_MAX_ITERATIONS: usize = 1000;

/// The default floor of `m_α` ([`BishopSettings::m_alpha_floor`]): a
/// column at or below it refuses the surface (Whitman & Bailey 1967's
/// 0.2).
pub const MIN_M_ALPHA: f64 = 0.2;

/// Settings of Bishop's method: the floor of `m_α`, at or below which a
/// column refuses its surface ([`BishopFailure::SmallMAlpha`]). Always
/// valid: the floor is checked where it is set.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BishopSettings {
    m_alpha_floor: f64,
}

impl Default for BishopSettings {
    /// The floor [`MIN_M_ALPHA`] = 0.2 (Whitman & Bailey 1967).
    fn default() -> Self {
        Self {
            m_alpha_floor: MIN_M_ALPHA,
        }
    }
}

impl BishopSettings {
    /// The settings with the floor of `m_α` at `floor`, in (0, 1]: a
    /// lower floor accepts surfaces whose toe rises more steeply, where
    /// Bishop's normal forces grow as `1/m_α`; 1 refuses any column whose
    /// base rises against the sliding direction on a frictional material.
    ///
    /// # Errors
    /// [`SlopeError::MAlphaFloorOutOfRange`] naming the value, for a floor
    /// that is not finite, at or below 0, or above 1.
    pub fn with_m_alpha_floor(self, floor: f64) -> crate::error::Result<Self> {
        if !(floor > 0.0 && floor <= 1.0) {
            return Err(crate::error::DismechError::Slope(
                SlopeError::MAlphaFloorOutOfRange { value: floor },
            ));
        }
        Ok(Self {
            m_alpha_floor: floor,
        })
    }

    /// The floor of `m_α` (default [`MIN_M_ALPHA`]).
    pub fn m_alpha_floor(&self) -> f64 {
        self.m_alpha_floor
    }
}

/// Why Bishop's method gave no Fs for a surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BishopFailure {
    /// A refusal shared with Hovland's method (limits, no data, nothing
    /// drives, no strength).
    Refused(Refusal),
    /// A column's `m_α = cos γ + sin α tan φ / F` is at or below the
    /// floor [`BishopSettings::m_alpha_floor`] (at the iterate
    /// `safety_factor`).
    SmallMAlpha {
        /// Grid row of the column.
        row: usize,
        /// Grid column of the column.
        column: usize,
        /// Its `m_α`.
        m_alpha: f64,
        /// The F at which it was found.
        safety_factor: f64,
        /// The floor it is at or below.
        floor: f64,
    },
    /// The iteration did not settle within [`BISHOP_MAX_ITERATIONS`], or
    /// gave an F that is not finite and positive.
    NotConverged {
        /// Iterations made.
        iterations: usize,
        /// The last iterate.
        safety_factor: f64,
    },
}

impl std::fmt::Display for BishopFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Refused(r) => write!(f, "surface refused: {r}"),
            Self::SmallMAlpha {
                row,
                column,
                m_alpha,
                safety_factor,
                floor,
            } => write!(
                f,
                "Bishop's m_alpha = {m_alpha} at the column of row {row}, column {column} (F = {safety_factor}) is at or below the floor {floor}: its base rises too steeply in the sliding direction for Bishop's method"
            ),
            Self::NotConverged {
                iterations,
                safety_factor,
            } => write!(
                f,
                "Bishop's iteration did not settle to {BISHOP_TOLERANCE} in {iterations} iterations (last F = {safety_factor})"
            ),
        }
    }
}

impl std::error::Error for BishopFailure {}

impl From<Refusal> for BishopFailure {
    fn from(r: Refusal) -> Self {
        Self::Refused(r)
    }
}

impl From<BishopFailure> for Refusal {
    /// The search's count of a failure: [`Refusal::SmallMAlpha`],
    /// [`Refusal::NotConverged`] or the refusal itself.
    fn from(f: BishopFailure) -> Self {
        match f {
            BishopFailure::Refused(r) => r,
            BishopFailure::SmallMAlpha { .. } => Refusal::SmallMAlpha,
            BishopFailure::NotConverged { .. } => Refusal::NotConverged,
        }
    }
}

/// Bishop's 3D Fs of `columns` (of a surface over `terrain`) on one
/// material, moments about the horizontal axis through `centre` across
/// the sliding direction, `m_α` floored by `settings`; the limits checked
/// first. The material and
/// loads are taken as given (an [`super::Evaluator`] checks them once).
///
/// The result's `resisting` is `Σ (c A + N' tan φ)` with Bishop's N, and
/// its `driving` is `resisting / F`, the base shear mobilised.
///
/// # Errors
/// (Not a [`crate::error::DismechError`].) [`BishopFailure::Refused`]
/// with the refusals of [`super::hovland_columns`], and with
/// [`Refusal::NothingDrives`] also where the driving moment
/// `Σ (W x − N f + k_h W e)` about the axis is not positive (a nearly
/// level surface, or one whose weight lies mostly downslope of its
/// centre), [`Refusal::NoStrength`] where the resisting moment is not;
/// [`BishopFailure::SmallMAlpha`] naming the column, for an `m_α` at or
/// below [`BishopSettings::m_alpha_floor`];
/// [`BishopFailure::NotConverged`].
pub fn bishop_columns(
    columns: &[SlipColumn],
    terrain: &Terrain,
    material: &SlopeMaterial,
    loads: &SlopeLoads,
    limits: &SurfaceLimits,
    centre: (f64, f64, f64),
    settings: &BishopSettings,
) -> std::result::Result<SurfaceFs, BishopFailure> {
    let gamma = material.unit_weight;
    let (c, mu) = (material.cohesion, material.friction_coefficient);
    bishop_core(columns, terrain, loads, limits, centre, settings, |k| {
        Some(ColumnGround {
            vertical_stress: gamma * (k.ground - k.base),
            cohesion: c,
            friction_coefficient: mu,
            ratio_pore_pressure: None,
        })
    })
}

/// [`bishop_columns`] on layered ground, each column's weight, strength
/// and pore pressure as in [`super::hovland_ground`] ([`Ground::column`]).
///
/// # Errors
/// Those of [`bishop_columns`]; [`BishopFailure::Refused`] with
/// [`Refusal::NoData`] as in [`super::hovland_ground`].
pub fn bishop_ground(
    columns: &[SlipColumn],
    terrain: &Terrain,
    ground: &Ground,
    loads: &SlopeLoads,
    limits: &SurfaceLimits,
    centre: (f64, f64, f64),
    settings: &BishopSettings,
) -> std::result::Result<SurfaceFs, BishopFailure> {
    bishop_core(columns, terrain, loads, limits, centre, settings, |k| {
        ground.column(k.row, k.column, k.ground, k.base)
    })
}

/// A column's fixed quantities in Bishop's iteration.
#[derive(Debug, Clone, Copy)]
struct BishopColumn {
    row: usize,
    column: usize,
    weight: f64,
    cos_gamma: f64,
    sin_alpha: f64,
    /// `c A`.
    cohesion_force: f64,
    /// `u A`.
    pore_force: f64,
    friction: f64,
    /// Arms: shear R, weight x, normal f, seismic e.
    shear_arm: f64,
    weight_arm: f64,
    normal_arm: f64,
    seismic_arm: f64,
}

impl BishopColumn {
    /// `(N, N')` at F, or the column's `m_α` where it is at or below
    /// `floor`.
    fn normal(&self, f: f64, floor: f64) -> Result<(f64, f64), f64> {
        let m_alpha = self.cos_gamma + self.sin_alpha * self.friction / f;
        if m_alpha.partial_cmp(&floor) != Some(std::cmp::Ordering::Greater) {
            return Err(m_alpha);
        }
        let n = (self.weight
            - (self.cohesion_force - self.pore_force * self.friction) * self.sin_alpha / f)
            / m_alpha;
        let effective = n - self.pore_force;
        if effective >= 0.0 {
            Ok((n, effective))
        } else {
            let n = (self.weight - self.cohesion_force * self.sin_alpha / f) / self.cos_gamma;
            Ok((n, 0.0))
        }
    }
}

fn bishop_core(
    columns: &[SlipColumn],
    terrain: &Terrain,
    loads: &SlopeLoads,
    limits: &SurfaceLimits,
    centre: (f64, f64, f64),
    settings: &BishopSettings,
    at: impl Fn(&SlipColumn) -> Option<ColumnGround>,
) -> std::result::Result<SurfaceFs, BishopFailure> {
    let floor = settings.m_alpha_floor;
    let cell_size = terrain.cell_size();
    let cell_area = cell_size * cell_size;
    let setup = surface_setup(columns, cell_size, limits, &at)?;
    let (sx, sy) = setup.direction;
    let (ex, ey) = (sy, -sx);
    let kh = loads.seismic_coefficient;
    let dem = &terrain.dem().raster;
    let mut cols = Vec::with_capacity(columns.len());
    // Hovland's sums, the start of the iteration.
    let (mut resisting, mut driving) = (0.0, 0.0);
    for k in columns {
        let g = at(k).ok_or(Refusal::NoData)?;
        let t = column_terms(k, &g, cell_area, setup.direction, loads);
        resisting += t.resisting();
        driving += t.along;
        let (x, y) = dem.cell_centre(k.row, k.column);
        let (rx, ry, rz) = (x - centre.0, y - centre.1, k.base - centre.2);
        // l = ê × r with ê = (e_x, e_y, 0).
        let (lx, ly, lz) = (ey * rz, -ex * rz, ex * ry - ey * rx);
        let (zx, zy) = k.gradient;
        let along_norm = (1.0 + t.slope * t.slope).sqrt();
        cols.push(BishopColumn {
            row: k.row,
            column: k.column,
            weight: t.weight,
            cos_gamma: 1.0 / t.rho,
            sin_alpha: -t.slope / along_norm,
            cohesion_force: t.cohesion * t.base_area,
            pore_force: t.pore_pressure * t.base_area,
            friction: t.friction,
            shear_arm: (sx * lx + sy * ly + t.slope * lz) / along_norm,
            weight_arm: -lz,
            normal_arm: (zx * lx + zy * ly - lz) / t.rho,
            seismic_arm: centre.2 - 0.5 * (k.ground + k.base),
        });
    }
    // Hovland's refusals (nothing drives, no strength) hold for Bishop.
    let mut f = finish(setup, columns.len(), resisting, driving)?.safety_factor;
    for iteration in 1..=BISHOP_MAX_ITERATIONS {
        let (mut moment_resisting, mut moment_driving, mut strength) = (0.0, 0.0, 0.0);
        for b in &cols {
            let (n, effective) =
                b.normal(f, floor)
                    .map_err(|m_alpha| BishopFailure::SmallMAlpha {
                        row: b.row,
                        column: b.column,
                        m_alpha,
                        safety_factor: f,
                        floor,
                    })?;
            let s = b.cohesion_force + effective * b.friction;
            strength += s;
            moment_resisting += s * b.shear_arm;
            moment_driving +=
                b.weight * b.weight_arm - n * b.normal_arm + kh * b.weight * b.seismic_arm;
        }
        // NaN compares as nothing. No driving moment about the axis (a
        // nearly level surface, or one whose weight lies mostly on the
        // other side of its centre): nothing drives it, as in Hovland's
        // method; no resisting moment: no strength.
        if moment_driving.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return Err(Refusal::NothingDrives.into());
        }
        if moment_resisting.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return Err(Refusal::NoStrength.into());
        }
        let next = moment_resisting / moment_driving;
        if !(next.is_finite() && next > 0.0) {
            return Err(BishopFailure::NotConverged {
                iterations: iteration,
                safety_factor: next,
            });
        }
        let settled = (next - f).abs() <= BISHOP_TOLERANCE * next;
        f = next;
        if settled {
            return Ok(SurfaceFs {
                safety_factor: f,
                direction: setup.direction,
                columns: columns.len(),
                volume: setup.volume,
                area: setup.area,
                depth: setup.depth,
                weight: setup.weight,
                resisting: strength,
                driving: strength / f,
            });
        }
    }
    Err(BishopFailure::NotConverged {
        iterations: BISHOP_MAX_ITERATIONS,
        safety_factor: f,
    })
}
