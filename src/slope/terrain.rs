//! The ground a slope search runs over: a digital elevation model, an
//! optional water table and an optional bedrock on the same grid, checked
//! once.

use std::path::Path;

use super::error::SlopeError;
use crate::error::{DismechError, Result};
use crate::hpm::NamedRaster;

/// The fewest rows, and the fewest columns, of a DEM a search runs on: a
/// trial surface whose columns touch the grid's edge is refused (it would
/// go on beyond the grid), so at least one inner cell is needed.
pub const MIN_DEM_SIDE: usize = 3;

/// A digital elevation model (ground heights at the cell centres, m) and
/// an optional water table (heights of the phreatic surface, m) on the same
/// grid.
///
/// No-data cells of the DEM are allowed (a DEM clipped to a catchment): a
/// trial surface whose footprint covers one is refused (Scoops3D, Reid,
/// Christian & Brien, USGS 2015, refuses surfaces that meet the DEM's
/// boundary). A water table may have no data only where no trial surface
/// has a column; a surface with a column there is refused.
#[derive(Debug, Clone, PartialEq)]
pub struct Terrain {
    dem: NamedRaster,
    water: Option<NamedRaster>,
    bedrock: Option<NamedRaster>,
}

impl Terrain {
    /// Check the DEM and the water table.
    ///
    /// # Errors
    /// [`SlopeError::DemTooSmall`] for a DEM of fewer than
    /// [`MIN_DEM_SIDE`] rows or columns; [`SlopeError::NoGroundData`]
    /// when no cell of the DEM has data; [`crate::grid::GridError::Mismatch`]
    /// naming both files when the water table lies on another grid (shape,
    /// corner or cell size). (A raster holds no NaN or infinite value:
    /// [`crate::grid::Raster::new`] refuses them.)
    pub fn new(dem: NamedRaster, water: Option<NamedRaster>) -> Result<Self> {
        let (rows, columns) = (dem.raster.rows(), dem.raster.columns());
        if rows < MIN_DEM_SIDE || columns < MIN_DEM_SIDE {
            return Err(DismechError::Slope(SlopeError::DemTooSmall {
                file: dem.name.clone(),
                rows,
                columns,
            }));
        }
        if dem.raster.values().iter().all(Option::is_none) {
            return Err(DismechError::Slope(SlopeError::NoGroundData {
                file: dem.name.clone(),
                rows,
                columns,
            }));
        }
        if let Some(w) = &water {
            w.require_grid_of(&dem)?;
        }
        Ok(Self {
            dem,
            water,
            bedrock: None,
        })
    }

    /// Read the DEM and the water table from ESRI ASCII grid files (or
    /// GeoTIFF, `.tif`: [`NamedRaster::read`]).
    ///
    /// # Errors
    /// Those of [`crate::grid::read_esri_ascii`] (or
    /// [`crate::grid::read_geotiff`]) for each file, then those
    /// of [`Terrain::new`].
    pub fn read(dem: &Path, water: Option<&Path>) -> Result<Self> {
        Self::new(
            NamedRaster::read(dem)?,
            water.map(NamedRaster::read).transpose()?,
        )
    }

    /// The same terrain over a bedrock: the elevation (m) at each cell
    /// centre of a surface no slip surface goes below. A trial surface that
    /// would go deeper follows it (its base there is the bedrock, with the
    /// bedrock's slope), as Scoops3D truncates its spheres at a weak layer
    /// (Reid, Christian & Brien, USGS 2015) and r.slope.stability its
    /// ellipsoids at the base of the soil (Mergili et al., Geosci. Model
    /// Dev. 7, 2014). Where the bedrock lies above the ground there is no
    /// column. A bedrock may have no data only where no trial surface has a
    /// column (a surface with one there is refused,
    /// [`super::Refusal::NoData`]).
    ///
    /// # Errors
    /// [`crate::grid::GridError::Mismatch`] naming both files when the bedrock
    /// lies on another grid than the DEM.
    pub fn with_bedrock(mut self, bedrock: NamedRaster) -> Result<Self> {
        bedrock.require_grid_of(&self.dem)?;
        self.bedrock = Some(bedrock);
        Ok(self)
    }

    /// The bedrock, if any.
    pub fn bedrock(&self) -> Option<&NamedRaster> {
        self.bedrock.as_ref()
    }

    /// The bedrock at cell (row, column): its height and its gradient
    /// `(∂z/∂x, ∂z/∂y)` from central differences of the neighbouring cells
    /// (one-sided where a neighbour has no data, 0 along an axis with
    /// neither); `None` without a bedrock or where it has no data.
    pub fn bedrock_at(&self, row: usize, column: usize) -> Option<(f64, (f64, f64))> {
        let b = &self.bedrock.as_ref()?.raster;
        let z = b.get(row, column)?;
        let d = self.cell_size();
        let diff = |lo: Option<f64>, hi: Option<f64>| match (lo, hi) {
            (Some(a), Some(c)) => (c - a) / (2.0 * d),
            (None, Some(c)) => (c - z) / d,
            (Some(a), None) => (z - a) / d,
            (None, None) => 0.0,
        };
        let west = column.checked_sub(1).and_then(|c| b.get(row, c));
        let east = b.get(row, column + 1);
        // Row 0 is the top (north): y grows towards smaller rows.
        let south = b.get(row + 1, column);
        let north = row.checked_sub(1).and_then(|r| b.get(r, column));
        Some((z, (diff(west, east), diff(south, north))))
    }

    /// The digital elevation model.
    pub fn dem(&self) -> &NamedRaster {
        &self.dem
    }

    /// The water table, if any.
    pub fn water(&self) -> Option<&NamedRaster> {
        self.water.as_ref()
    }

    /// Grid rows.
    pub fn rows(&self) -> usize {
        self.dem.raster.rows()
    }

    /// Grid columns.
    pub fn columns(&self) -> usize {
        self.dem.raster.columns()
    }

    /// Side of a cell (m).
    pub fn cell_size(&self) -> f64 {
        self.dem.raster.cell_size()
    }

    /// The ground height of cell (row, column), `None` outside the grid or
    /// without data.
    pub fn ground(&self, row: usize, column: usize) -> Option<f64> {
        self.dem.raster.get(row, column)
    }

    /// The cell `(row, column)` holding the point `(x, y)`, `None` outside
    /// the grid.
    pub fn cell_at(&self, x: f64, y: f64) -> Option<(usize, usize)> {
        let (x0, y0) = self.dem.raster.lower_left();
        let d = self.cell_size();
        let c = ((x - x0) / d).floor();
        let r_from_bottom = ((y - y0) / d).floor();
        if !(c >= 0.0 && r_from_bottom >= 0.0) {
            return None;
        }
        let (c, rb) = (c as usize, r_from_bottom as usize);
        if c >= self.columns() || rb >= self.rows() {
            return None;
        }
        Some((self.rows() - 1 - rb, c))
    }

    /// The fall line of the ground at cell (row, column): the horizontal
    /// unit vector down the steepest slope, from central differences of the
    /// neighbouring cells (one-sided where a neighbour is missing); `None`
    /// where the cell has no data or the ground is level there.
    pub fn fall_line(&self, row: usize, column: usize) -> Option<(f64, f64)> {
        let g = self.ground(row, column)?;
        let d = self.cell_size();
        let diff = |lo: Option<f64>, hi: Option<f64>| match (lo, hi) {
            (Some(a), Some(b)) => (b - a) / (2.0 * d),
            (None, Some(b)) => (b - g) / d,
            (Some(a), None) => (g - a) / d,
            (None, None) => 0.0,
        };
        let west = column.checked_sub(1).and_then(|c| self.ground(row, c));
        let east = self.ground(row, column + 1);
        // Row 0 is the top (north): y grows towards smaller rows.
        let south = self.ground(row + 1, column);
        let north = row.checked_sub(1).and_then(|r| self.ground(r, column));
        let (gx, gy) = (diff(west, east), diff(south, north));
        let n = gx.hypot(gy);
        (n > 0.0).then(|| (-gx / n, -gy / n))
    }
}
