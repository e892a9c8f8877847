//! Hovland's 3D column method (Hovland 1977, J. Geotech. Eng. Div. ASCE
//! 103(9)) evaluated directly on the columns of a trial surface, with no
//! HPM model built: the sums of [`crate::hpm::hovland()`] with the base
//! taken from the trial surface at each cell centre.
//!
//! For a column of vertical thickness `h = ground − base`, plan cell side
//! `d` and base gradient `(z_x, z_y)`: weight `W = γ h d²`, base normal
//! into the ground `n = (z_x, z_y, −1) / ρ` with `ρ = √(1 + z_x² + z_y²)`,
//! true base area `A = d² ρ`, load `w = (k_h W s_x, k_h W s_y, −W)` with
//! `s` the plan sliding direction, the base tangent along it
//! `t = (s_x, s_y, a) / √(1 + a²)` with `a = z_x s_x + z_y s_y`, and
//! `N = w · n`, `T = w · t` as in [`crate::hpm::hovland()`]. The pore
//! pressure `u = γ_w h_p` ([`super::SlipColumn::pressure_head`]) lowers the
//! normal force to `N' = max(N − u A, 0)` (a column lifted by its pore
//! pressure keeps no frictional strength, and none below zero), and
//! `Fs = Σ (c A + N' tan φ) / Σ T`.
//!
//! **Layered ground** ([`hovland_ground`], [`super::Ground`]): the weight
//! is `W = σ_v d²` with `σ_v = Σ γ_i t_i` over the layers between the base
//! and the ground, c and φ those of the layer the base passes through
//! (Scoops3D's convention, Reid, Christian & Brien, USGS 2015), and with a
//! pore-pressure ratio the pore pressure is `u = r_u σ_v` (Bishop &
//! Morgenstern 1960) in place of `γ_w h_p`.
//!
//! **Sliding direction.** The plan direction of the resultant of the
//! columns' base shear under their weight, `−Σ W (z_x, z_y) / ρ²` (the
//! horizontal part of `W` less its normal part `(W/ρ) n`): the direction
//! the slide would take as one body, as Scoops3D takes the direction of
//! the resultant (Reid, Christian & Brien, USGS 2015). It is computed in
//! one pass over the columns and is the fall line wherever the surface and
//! the ground are symmetric about a vertical plane (a sphere on a planar
//! slope). Searching the direction that minimises Fs would take several
//! passes per surface and is not done; the seismic force acts along this
//! direction.

use crate::error::Result;
use crate::hpm::MIN_DRIVING_RATIO;

use super::bishop::BishopSettings;
use super::ground::{ColumnGround, Ground, ToGround};
use super::material::{SlopeLoads, SlopeMaterial};
use super::surface::{surface_columns, Refusal, SlipColumn, SurfaceLimits, TrialSurface};
use super::terrain::Terrain;

/// The Fs of one trial surface, by Hovland's method (or Bishop's,
/// [`super::bishop_ground`]), and what it is made of.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceFs {
    /// `Σ (c A + N' tan φ) / Σ T`.
    pub safety_factor: f64,
    /// The plan sliding direction (unit vector).
    pub direction: (f64, f64),
    /// Number of columns.
    pub columns: usize,
    /// Volume of the slide `Σ h d²` (m³).
    pub volume: f64,
    /// Plan area of the slide, columns × d² (m²).
    pub area: f64,
    /// Largest vertical thickness of a column (m).
    pub depth: f64,
    /// Weight `Σ W` (N).
    pub weight: f64,
    /// Strength `Σ (c A + N' tan φ)` (N) (by Bishop's method, with its
    /// normal forces N).
    pub resisting: f64,
    /// Driving force `Σ T` (N) (by Bishop's method, whose Fs is a ratio
    /// of moments, the base shear mobilised, `resisting / Fs`).
    pub driving: f64,
}

/// Hovland's sums over `columns` on a grid of cell side `cell_size`, the
/// limits checked first. The material and the loads are taken as given
/// (an [`Evaluator`] checks them once).
///
/// # Errors
/// (A refusal, not a [`crate::error::DismechError`].) The refusal of the
/// first limit the columns fail ([`Refusal::TooFewColumns`],
/// [`Refusal::Volume`], [`Refusal::Area`], [`Refusal::Depth`]);
/// [`Refusal::NothingDrives`] when the plan resultant of the base shear or
/// `Σ T` is not above [`MIN_DRIVING_RATIO`] × `Σ W`, or the ratio is not
/// finite; [`Refusal::NoStrength`] when `Σ (c A + N' tan φ)` is not
/// positive.
pub fn hovland_columns(
    columns: &[SlipColumn],
    cell_size: f64,
    material: &SlopeMaterial,
    loads: &SlopeLoads,
    limits: &SurfaceLimits,
) -> std::result::Result<SurfaceFs, Refusal> {
    let gamma = material.unit_weight;
    let (c, mu) = (material.cohesion, material.friction_coefficient);
    hovland_core(columns, cell_size, loads, limits, |k| {
        Some(ColumnGround {
            vertical_stress: gamma * (k.ground - k.base),
            cohesion: c,
            friction_coefficient: mu,
            ratio_pore_pressure: None,
        })
    })
}

/// Hovland's sums over `columns` on layered ground: each column's weight
/// `σ_v d²` with `σ_v = Σ γ_i t_i` over the layers between its base and the
/// ground, the base strength that of the layer the base passes through,
/// and the pore pressure `r_u σ_v` where the ground has a pore-pressure
/// ratio, `γ_w h_p` ([`SlipColumn::pressure_head`]) otherwise
/// ([`Ground::column`]; Scoops3D's convention, Reid, Christian & Brien,
/// USGS 2015). A one-layer ground gives [`hovland_columns`]'s result bit
/// for bit. The ground is taken as given (an [`Evaluator`] checks it
/// against the terrain once).
///
/// # Errors
/// (A refusal, not a [`crate::error::DismechError`].) Those of
/// [`hovland_columns`]; [`Refusal::NoData`] when a layer's bottom or the
/// r_u raster has no data at a column that needs it.
pub fn hovland_ground(
    columns: &[SlipColumn],
    cell_size: f64,
    ground: &Ground,
    loads: &SlopeLoads,
    limits: &SurfaceLimits,
) -> std::result::Result<SurfaceFs, Refusal> {
    hovland_core(columns, cell_size, loads, limits, |k| {
        ground.column(k.row, k.column, k.ground, k.base)
    })
}

/// What the limits and the sliding direction of a surface's columns give,
/// the same for every limit-equilibrium method ([`hovland_core`],
/// [`super::bishop`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct SurfaceSetup {
    /// `Σ h d²` (m³).
    pub volume: f64,
    /// Columns × d² (m²).
    pub area: f64,
    /// The thickest column (m).
    pub depth: f64,
    /// `Σ W` (N).
    pub weight: f64,
    /// The plan sliding direction (unit vector).
    pub direction: (f64, f64),
}

/// The limits checked on `columns`, then the sliding direction: the plan
/// resultant of the base shear under the weight (see the module's
/// documentation).
///
/// # Errors
/// (A refusal.) The limits' refusals, [`Refusal::NoData`] and
/// [`Refusal::NothingDrives`] as in [`hovland_columns`].
pub(super) fn surface_setup(
    columns: &[SlipColumn],
    cell_size: f64,
    limits: &SurfaceLimits,
    at: &impl Fn(&SlipColumn) -> Option<ColumnGround>,
) -> std::result::Result<SurfaceSetup, Refusal> {
    let cell_area = cell_size * cell_size;
    if columns.len() < limits.min_columns {
        return Err(Refusal::TooFewColumns);
    }
    let mut thickness_sum = 0.0;
    let mut depth = 0.0f64;
    for k in columns {
        let h = k.ground - k.base;
        thickness_sum += h;
        depth = depth.max(h);
    }
    let volume = thickness_sum * cell_area;
    let area = columns.len() as f64 * cell_area;
    let within = |v: f64, (lo, hi): (f64, f64)| v >= lo && v <= hi;
    if !within(volume, limits.volume) {
        return Err(Refusal::Volume);
    }
    if !within(area, limits.area) {
        return Err(Refusal::Area);
    }
    if !within(depth, limits.depth) {
        return Err(Refusal::Depth);
    }
    // The plan resultant of the base shear under the weight.
    let (mut hx, mut hy, mut weight) = (0.0, 0.0, 0.0);
    for k in columns {
        let w = at(k).ok_or(Refusal::NoData)?.vertical_stress * cell_area;
        let (zx, zy) = k.gradient;
        let rho2 = 1.0 + zx * zx + zy * zy;
        hx -= w * zx / rho2;
        hy -= w * zy / rho2;
        weight += w;
    }
    let plan = hx.hypot(hy);
    // `>` is false for NaN: a NaN resultant drives nothing.
    if plan.partial_cmp(&(MIN_DRIVING_RATIO * weight)) != Some(std::cmp::Ordering::Greater) {
        return Err(Refusal::NothingDrives);
    }
    Ok(SurfaceSetup {
        volume,
        area,
        depth,
        weight,
        direction: (hx / plan, hy / plan),
    })
}

/// One column's quantities along the sliding direction, shared by
/// Hovland's and Bishop's methods.
#[derive(Debug, Clone, Copy)]
pub(super) struct ColumnTerms {
    /// Weight `W = σ_v d²` (N).
    pub weight: f64,
    /// `ρ = √(1 + z_x² + z_y²)`: `1/ρ` is the cosine of the base's true
    /// dip.
    pub rho: f64,
    /// The base's slope along the sliding direction, `a = z_x s_x + z_y s_y`.
    pub slope: f64,
    /// Hovland's normal force `N = w · n` (N).
    pub normal: f64,
    /// Hovland's driving force `T = w · t` (N).
    pub along: f64,
    /// True base area `A = d² ρ` (m²).
    pub base_area: f64,
    /// Pore pressure on the base `u` (Pa).
    pub pore_pressure: f64,
    /// Cohesion of the base (Pa).
    pub cohesion: f64,
    /// Friction coefficient of the base.
    pub friction: f64,
}

impl ColumnTerms {
    /// The column's share of Hovland's resisting sum, `c A + N' tan φ`.
    /// A column whose pore pressure (or seismic lift) exceeds its normal
    /// force has no frictional strength left, not a negative one: the
    /// effective normal force `N'` is taken as zero there, as
    /// limit-equilibrium codes do (Scoops3D; Reid et al. 2015).
    pub(super) fn resisting(&self) -> f64 {
        let effective = (self.normal - self.pore_pressure * self.base_area).max(0.0);
        self.cohesion * self.base_area + effective * self.friction
    }
}

/// The quantities of column `k` on ground `g` along the plan sliding
/// direction `(sx, sy)` (see the module's documentation).
pub(super) fn column_terms(
    k: &SlipColumn,
    g: &ColumnGround,
    cell_area: f64,
    (sx, sy): (f64, f64),
    loads: &SlopeLoads,
) -> ColumnTerms {
    let kh = loads.seismic_coefficient;
    let w = g.vertical_stress * cell_area;
    let (zx, zy) = k.gradient;
    let rho = (1.0 + zx * zx + zy * zy).sqrt();
    let a = zx * sx + zy * sy;
    // w = (k_h W s_x, k_h W s_y, −W); n = (z_x, z_y, −1)/ρ; t = (s_x, s_y, a)/√(1 + a²).
    let (lx, ly, lz) = (kh * w * sx, kh * w * sy, -w);
    let normal = (lx * zx + ly * zy - lz) / rho;
    let along = (lx * sx + ly * sy + lz * a) / (1.0 + a * a).sqrt();
    let base_area = cell_area * rho;
    let pore_pressure = match g.ratio_pore_pressure {
        Some(u) => u,
        None => loads.water_unit_weight * k.pressure_head,
    };
    ColumnTerms {
        weight: w,
        rho,
        slope: a,
        normal,
        along,
        base_area,
        pore_pressure,
        cohesion: g.cohesion,
        friction: g.friction_coefficient,
    }
}

/// The sums, with what the ground gives each column from `at` (`None`:
/// no data, the surface refused).
fn hovland_core(
    columns: &[SlipColumn],
    cell_size: f64,
    loads: &SlopeLoads,
    limits: &SurfaceLimits,
    at: impl Fn(&SlipColumn) -> Option<ColumnGround>,
) -> std::result::Result<SurfaceFs, Refusal> {
    let cell_area = cell_size * cell_size;
    let setup = surface_setup(columns, cell_size, limits, &at)?;
    let (mut resisting, mut driving) = (0.0, 0.0);
    for k in columns {
        let g = at(k).ok_or(Refusal::NoData)?;
        let t = column_terms(k, &g, cell_area, setup.direction, loads);
        resisting += t.resisting();
        driving += t.along;
    }
    finish(setup, columns.len(), resisting, driving)
}

/// The Fs `resisting / driving` of a surface, refused where nothing
/// drives it or it has no strength.
pub(super) fn finish(
    setup: SurfaceSetup,
    columns: usize,
    resisting: f64,
    driving: f64,
) -> std::result::Result<SurfaceFs, Refusal> {
    let safety_factor = resisting / driving;
    if !(driving > MIN_DRIVING_RATIO * setup.weight && safety_factor.is_finite()) {
        return Err(Refusal::NothingDrives);
    }
    if resisting.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return Err(Refusal::NoStrength);
    }
    Ok(SurfaceFs {
        safety_factor,
        direction: setup.direction,
        columns,
        volume: setup.volume,
        area: setup.area,
        depth: setup.depth,
        weight: setup.weight,
        resisting,
        driving,
    })
}

/// The limit-equilibrium method a surface is evaluated by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Method {
    /// Hovland's method ([`hovland_ground`]).
    #[default]
    Hovland,
    /// Bishop's simplified method in 3D (Hungr 1987,
    /// [`super::bishop_ground`]).
    Bishop,
}

/// Hovland's (or Bishop's) method on trial surfaces over one terrain, with
/// the material, loads and limits checked once.
#[derive(Debug, Clone)]
pub struct Evaluator<'a> {
    terrain: &'a Terrain,
    ground: Ground,
    loads: SlopeLoads,
    limits: SurfaceLimits,
    method: Method,
    bishop: BishopSettings,
}

impl<'a> Evaluator<'a> {
    /// Check the ground (one material, `&SlopeMaterial`, or a layered
    /// [`Ground`]), the loads and the limits; the surfaces are evaluated
    /// by Hovland's method unless [`Evaluator::with_method`] says
    /// otherwise.
    ///
    /// # Errors
    /// Those of [`Ground::validate_on`] (for one material, those of
    /// [`SlopeMaterial::validate`]), [`SlopeLoads::validate`] and
    /// [`SurfaceLimits::validate`].
    pub fn new(
        terrain: &'a Terrain,
        ground: &(impl ToGround + ?Sized),
        loads: &SlopeLoads,
        limits: &SurfaceLimits,
    ) -> Result<Self> {
        let ground = ground.to_ground();
        ground.validate_on(terrain)?;
        loads.validate()?;
        limits.validate()?;
        Ok(Self {
            terrain,
            ground,
            loads: *loads,
            limits: *limits,
            method: Method::Hovland,
            bishop: BishopSettings::default(),
        })
    }

    /// The evaluator with `method`.
    pub fn with_method(mut self, method: Method) -> Self {
        self.method = method;
        self
    }

    /// The method the surfaces are evaluated by.
    pub fn method(&self) -> Method {
        self.method
    }

    /// The evaluator with Bishop's settings `bishop` (its `m_α` floor),
    /// taken where the method is [`Method::Bishop`].
    pub fn with_bishop(mut self, bishop: BishopSettings) -> Self {
        self.bishop = bishop;
        self
    }

    /// Bishop's settings (default [`BishopSettings::default`]).
    pub fn bishop(&self) -> BishopSettings {
        self.bishop
    }

    /// The terrain.
    pub fn terrain(&self) -> &'a Terrain {
        self.terrain
    }

    /// The ground.
    pub fn ground(&self) -> &Ground {
        &self.ground
    }

    /// The columns of `surface` ([`surface_columns`]) into `scratch`, then
    /// the Fs by the evaluator's method: Hovland's ([`hovland_ground`]) or
    /// Bishop's ([`super::bishop_ground`], moments about the axis through
    /// [`TrialSurface::centre`]).
    ///
    /// # Errors
    /// (A refusal, not a [`crate::error::DismechError`].) Those of
    /// [`surface_columns`], then of [`hovland_ground`] or
    /// [`super::bishop_ground`] (as [`Refusal::SmallMAlpha`] and
    /// [`Refusal::NotConverged`]).
    pub fn evaluate<S: TrialSurface>(
        &self,
        surface: &S,
        scratch: &mut Vec<SlipColumn>,
    ) -> std::result::Result<SurfaceFs, Refusal> {
        surface_columns(self.terrain, surface, scratch)?;
        match self.method {
            Method::Hovland => hovland_ground(
                scratch,
                self.terrain.cell_size(),
                &self.ground,
                &self.loads,
                &self.limits,
            ),
            Method::Bishop => super::bishop::bishop_ground(
                scratch,
                self.terrain,
                &self.ground,
                &self.loads,
                &self.limits,
                surface.centre(),
                &self.bishop,
            )
            .map_err(Refusal::from),
        }
    }
}
