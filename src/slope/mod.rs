//! Slope stability over real terrain: a search over trial slip surfaces
//! on a digital elevation model, evaluated by Hovland's 3D column method
//! (or Bishop's simplified method in 3D, Hungr 1987),
//! and the map of the lowest factor of safety per cell, on ground of one
//! material or of layers, dry, under a water table or with a pore-pressure
//! ratio.
//!
//! The slope engineer's tools work this way: Scoops3D (Reid, Christian &
//! Brien, USGS Techniques and Methods 14-A1, 2015) evaluates a systematic
//! grid of trial spheres over a DEM and maps, for every cell, the lowest
//! Fs of any trial surface through it; r.slope.stability (Mergili et al.,
//! Geosci. Model Dev. 7, 2014) samples random ellipsoids. Here:
//!
//! | concept | items | file |
//! |---|---|---|
//! | the ground | [`Terrain`] (DEM, optional water table and bedrock: [`Terrain::with_bedrock`] truncates the trial surfaces), [`Terrain::fall_line`] | `terrain.rs` |
//! | strength and loads | [`SlopeMaterial`] (c, μ = tan φ, γ), [`SlopeLoads`] (k_h, γ_w) | `material.rs` |
//! | layered ground, r_u | [`Ground`] (strength [`Layer`]s bounded by elevation rasters, Scoops3D's convention), [`PoreRatio`] (Bishop & Morgenstern's r_u), [`ColumnGround`] | `ground.rs` |
//! | trial surfaces | [`TrialSurface`]: [`Sphere`], [`Ellipsoid`]; [`surface_columns`], [`SlipColumn`], [`SurfaceLimits`], [`Refusal`] | `surface.rs` |
//! | Hovland per surface | [`hovland_columns`], [`hovland_ground`], [`Evaluator`], [`SurfaceFs`], [`Method`] | `hovland.rs` |
//! | Bishop's simplified method in 3D per surface (Hungr 1987) | [`bishop_columns`], [`bishop_ground`], [`BishopFailure`], [`BishopSettings`] (the `m_α` floor, default [`MIN_M_ALPHA`]) | `bishop.rs` |
//! | families | [`TrialFamily`]: [`SphereGrid`] (Scoops3D), [`SphereRandom`], [`EllipsoidRandom`] (r.slope.stability); [`Steps`] | `family.rs` |
//! | the search | [`search`], [`SearchSettings`], [`SearchResult`], [`CellMinimum`], [`CriticalSurface`], [`SearchCounts`] | `search.rs` |
//! | HPM re-analysis of a surface (paper 001) | [`hpm_reanalysis`], [`HpmReanalysis`], [`HpmStiffness`], [`surface_raster`] | `reanalysis.rs` |
//! | outputs | rasters on the DEM's grid (ESRI ASCII, GeoTIFF), [`SearchResult::write_maps`], [`SearchResult::write_maps_as`], [`SearchResult::write_critical_csv`] | `output.rs` |
//! | errors | [`SlopeError`] (joined into [`DismechError::Slope`](crate::error::DismechError::Slope)), [`LayerProblem`] | `error.rs`, `layer_problem.rs` |
//!
//! No HPM model is built per surface of the search (that would be far
//! too slow for thousands of surfaces; the few most critical are
//! re-analysed by HPM afterwards, [`hpm_reanalysis`]): the columns are the DEM cells themselves, the
//! base the trial surface at each cell centre.
//!
//! ```no_run
//! # fn main() -> dismech::error::Result<()> {
//! use dismech::grid::Raster;
//! use dismech::hpm::NamedRaster;
//! use dismech::slope::{search, SearchSettings, SlopeLoads, SlopeMaterial, SphereGrid, Steps, Terrain};
//! // A 30° planar slope descending towards −y, 40 × 40 cells of 2 m.
//! let dem = Raster::from_fn(40, 40, 0.0, 0.0, 2.0, |_, y| Some(y * 30f64.to_radians().tan()))?;
//! let terrain = Terrain::new(NamedRaster::new("dem", dem), None)?;
//! let material = SlopeMaterial { cohesion: 5e3, friction_coefficient: 0.6, unit_weight: 19e3 };
//! let family = SphereGrid::new(4, Steps::checked("heights", 5.0, 20.0, 4, false)?,
//!                              Steps::checked("radii", 10.0, 40.0, 7, true)?)?;
//! let result = search(&terrain, &material, &SlopeLoads::default(), &family,
//!                     &SearchSettings::default(), |done, total| eprint!("\r{done}/{total}"))?;
//! result.write_maps(std::path::Path::new("out"), "slope")?;
//! result.write_critical_csv(std::path::Path::new("out/critical.csv"))?;
//! # Ok(()) }
//! ```

mod bishop;
mod error;
mod family;
mod ground;
mod hovland;
mod layer_problem;
mod material;
mod output;
mod reanalysis;
mod search;
mod surface;
mod terrain;

pub use bishop::{
    bishop_columns, bishop_ground, BishopFailure, BishopSettings, BISHOP_MAX_ITERATIONS,
    BISHOP_TOLERANCE, MIN_M_ALPHA,
};
pub use error::SlopeError;
pub use family::{EllipsoidRandom, SphereGrid, SphereRandom, Steps, TrialFamily};
pub use ground::{ColumnGround, Ground, Layer, PoreRatio, ToGround};
pub use hovland::{hovland_columns, hovland_ground, Evaluator, Method, SurfaceFs};
pub use layer_problem::LayerProblem;
pub use material::{SlopeLoads, SlopeMaterial, WATER_UNIT_WEIGHT};
pub use output::MAP_NAMES;
pub use reanalysis::{hpm_reanalysis, surface_raster, HpmReanalysis, HpmStiffness};
pub use search::{
    search, CellMinimum, CriticalSurface, SearchCounts, SearchResult, SearchSettings,
};
pub use surface::{
    surface_columns, Ellipsoid, Refusal, SlipColumn, Sphere, SurfaceLimits, TrialSurface,
};
pub use terrain::{Terrain, MIN_DEM_SIDE};
