//! An analysis as maps for a GIS: one value per grid column, on the grid
//! of the slope's rasters (its corner and cell size), no data where the
//! grid has no column; written as ESRI ASCII grids and GeoTIFF
//! ([`crate::grid::RasterFormat`]); the maps are listed at
//! [`ColumnMaps`].

use std::path::{Path, PathBuf};

use super::analysis::HpmResult;
use super::error::HpmError;
use super::grids::SlopeGrids;
use super::hovland::Hovland;
use super::model::HpmModel;
use crate::error::{DismechError, Result};
use crate::grid::{write_rasters, Raster, RasterFormat};
use crate::kinematics::affine3::ELEMENT_DOF;

/// Why maps cannot be made of a result on a grid
/// ([`HpmError::MapData`]): the model is not one of the grid, or the
/// result not one of the model.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MapProblem {
    /// The model's grid has another size or cell size than the rasters'.
    #[error("the model is not one of the grid of `{ground}`: its grid has {} × {} cells of {} m, the rasters {} × {} cells of {} m", model.0, model.1, model.2, rasters.0, rasters.1, rasters.2)]
    GridSize {
        /// The ground-surface raster's name.
        ground: String,
        /// The model's rows, columns and cell size (m).
        model: (usize, usize, f64),
        /// The rasters' rows, columns and cell size (m).
        rasters: (usize, usize, f64),
    },
    /// A column of the model lies outside the grid.
    #[error("the model is not one of the grid of `{ground}`: column {column} lies in cell ({}, {}), outside the grid", cell.0, cell.1)]
    CellOutside {
        /// The ground-surface raster's name.
        ground: String,
        /// The column of the model.
        column: usize,
        /// Its cell (row, column).
        cell: (usize, usize),
    },
    /// The model's first column is not at its cell of the grid.
    #[error("the model is not one of the grid of `{ground}`: column 0 of cell ({}, {}) has its corner at ({}, {}), the cell at ({}, {})", cell.0, cell.1, corner.0, corner.1, expected.0, expected.1)]
    CornerOff {
        /// The ground-surface raster's name.
        ground: String,
        /// The column's cell (row, column).
        cell: (usize, usize),
        /// The column's lower-left corner (m).
        corner: (f64, f64),
        /// The cell's lower-left corner (m).
        expected: (f64, f64),
    },
    /// An HPM result of another model.
    #[error("the HPM result has {displacements} displacements and {tractions} slip tractions, the model {elements} elements ({} displacements) and {springs} slip springs: it is not a result of this model", ELEMENT_DOF * elements)]
    NotThisResult {
        /// Displacements of the result.
        displacements: usize,
        /// Slip tractions of the result.
        tractions: usize,
        /// Elements of the model.
        elements: usize,
        /// Slip springs of the model.
        springs: usize,
    },
    /// Hovland's terms of another model.
    #[error("Hovland's method has {hovland} columns, the model {model}: it is not Hovland's method of this model")]
    NotThisHovland {
        /// Columns of Hovland's terms.
        hovland: usize,
        /// Columns of the model.
        model: usize,
    },
}

/// The maps of [`HpmResult::maps`], in this order.
pub const HPM_MAP_NAMES: [&str; 7] = [
    "local_fs",
    "displacement_x",
    "displacement_y",
    "displacement_z",
    "displacement",
    "strain_major",
    "strain_minor",
];

/// The maps of [`Hovland::maps`], in this order.
pub const HOVLAND_MAP_NAMES: [&str; 3] = ["local_fs", "normal_force", "driving_force"];

/// Named rasters of one analysis, on the grid of its slope: one value per
/// grid column, no data where the grid has no column (nor where a value is
/// not finite).
///
/// | map | HPM ([`HpmResult::maps`]) | Hovland ([`Hovland::maps`]) |
/// |---|---|---|
/// | `local_fs` | [`HpmResult::local_safety_factors`] (no data where the springs carry no shear) | `(c A + N tan φ) / T` of the column (no data where `T ≤ 0`) |
/// | `displacement_x`, `_y`, `_z`, `displacement` | the displacement (m) at the top of the column, at its centre ([`HpmResult::surface`]), and its length | — |
/// | `strain_major`, `strain_minor` | the principal plan strains there ([`SurfacePoint::principal`](super::SurfacePoint::principal)), extension positive | — |
/// | `normal_force`, `driving_force` | — | the column's base normal force N (less `u A` with a pore pressure on the slip surface) and driving force T (N) |
///
/// A local Fs of 0 marks a column whose strength `c A + N tan φ` (HPM: over
/// its springs) is not positive, as [`HpmResult::local_safety_factors`]
/// gives it.
#[derive(Debug, Clone, PartialEq)]
pub struct ColumnMaps {
    /// Each map's name ([`HPM_MAP_NAMES`], [`HOVLAND_MAP_NAMES`]) and
    /// raster.
    pub maps: Vec<(&'static str, Raster)>,
}

impl ColumnMaps {
    /// The map named `name`, if there is one.
    pub fn get(&self, name: &str) -> Option<&Raster> {
        self.maps.iter().find(|(n, _)| *n == name).map(|(_, r)| r)
    }

    /// Write every map as `{prefix}_{name}.{asc|tif}` in `folder` (created
    /// if needed), in each of `formats`, each file atomically
    /// ([`write_rasters`]); returns the paths, map by map and format by
    /// format.
    ///
    /// # Errors
    /// [`DismechError::Output`] naming the path of a file that cannot be
    /// written (it is then not there).
    pub fn write(
        &self,
        folder: &Path,
        prefix: &str,
        formats: &[RasterFormat],
    ) -> Result<Vec<PathBuf>> {
        let named: Vec<(&str, &Raster)> = self.maps.iter().map(|(n, r)| (*n, r)).collect();
        write_rasters(folder, prefix, &named, formats)
    }
}

/// Check that `model` was built on the grid of `grids` (rows, columns and
/// cell size, and its first column at its cell), and give each column's
/// cell as an index into that grid's values.
fn column_cells(model: &HpmModel, grids: &SlopeGrids) -> Result<Vec<usize>> {
    let raster = &grids.ground().raster;
    let (rows, columns, d) = model.grid;
    let ground = || grids.ground().name.clone();
    let mismatch = |reason: MapProblem| DismechError::Hpm(HpmError::MapData { reason });
    let rasters = (raster.rows(), raster.columns(), raster.cell_size());
    if (rows, columns, d) != rasters {
        return Err(mismatch(MapProblem::GridSize {
            ground: ground(),
            model: (rows, columns, d),
            rasters,
        }));
    }
    let mut cells = Vec::with_capacity(model.columns.len());
    for (k, column) in model.columns.iter().enumerate() {
        let (r, c) = column.cell;
        if r >= rows || c >= columns {
            return Err(mismatch(MapProblem::CellOutside {
                ground: ground(),
                column: k,
                cell: (r, c),
            }));
        }
        cells.push(r * columns + c);
    }
    if let Some(first) = model.columns.first() {
        let (r, c) = first.cell;
        let (x, y) = first.shape.origin();
        let (xc, yc) = raster.cell_centre(r, c);
        let (x_ll, y_ll) = (xc - 0.5 * d, yc - 0.5 * d);
        if (x - x_ll).abs() > 1e-9 * d.max(x_ll.abs())
            || (y - y_ll).abs() > 1e-9 * d.max(y_ll.abs())
        {
            return Err(mismatch(MapProblem::CornerOff {
                ground: ground(),
                cell: (r, c),
                corner: (x, y),
                expected: (x_ll, y_ll),
            }));
        }
    }
    Ok(cells)
}

/// A raster on the grid of `grids` holding `value(k)` at the cell of
/// column `k`, no data elsewhere.
fn column_raster(
    grids: &SlopeGrids,
    cells: &[usize],
    value: impl Fn(usize) -> Option<f64>,
) -> Result<Raster> {
    let raster = &grids.ground().raster;
    let mut values = vec![None; raster.rows() * raster.columns()];
    for (k, &cell) in cells.iter().enumerate() {
        values[cell] = value(k).filter(|v| v.is_finite());
    }
    let (x0, y0) = raster.lower_left();
    Raster::new(
        raster.columns(),
        raster.rows(),
        x0,
        y0,
        raster.cell_size(),
        values,
    )
}

impl HpmResult {
    /// The maps of this analysis of `model`, built on `grids`: local Fs,
    /// displacement at the top of each column (components and length) and
    /// principal plan strains there ([`HPM_MAP_NAMES`]; see
    /// [`ColumnMaps`]), each a raster on the grid of `grids`.
    ///
    /// # Errors
    /// [`HpmError::MapData`] when `model` was not built on the grid of
    /// `grids` ([`MapProblem::GridSize`], [`MapProblem::CellOutside`],
    /// [`MapProblem::CornerOff`]), or this result is not an analysis of
    /// `model` ([`MapProblem::NotThisResult`]: its displacements not 12 per
    /// element, its tractions not one per slip spring).
    pub fn maps(&self, model: &HpmModel, grids: &SlopeGrids) -> Result<ColumnMaps> {
        if self.displacements.len() != ELEMENT_DOF * model.elements.len()
            || self.tractions.len() != model.slip.len()
        {
            return Err(DismechError::Hpm(HpmError::MapData {
                reason: MapProblem::NotThisResult {
                    displacements: self.displacements.len(),
                    tractions: self.tractions.len(),
                    elements: model.elements.len(),
                    springs: model.slip.len(),
                },
            }));
        }
        let cells = column_cells(model, grids)?;
        let local = self.local_safety_factors(model);
        let surface = self.surface(model);
        let map = |f: &dyn Fn(usize) -> f64| column_raster(grids, &cells, |k| Some(f(k)));
        let maps = vec![
            ("local_fs", map(&|k| local[k])?),
            ("displacement_x", map(&|k| surface[k].displacement.x)?),
            ("displacement_y", map(&|k| surface[k].displacement.y)?),
            ("displacement_z", map(&|k| surface[k].displacement.z)?),
            ("displacement", map(&|k| surface[k].displacement.norm())?),
            ("strain_major", map(&|k| surface[k].principal[0])?),
            ("strain_minor", map(&|k| surface[k].principal[1])?),
        ];
        debug_assert!(maps.iter().map(|(n, _)| *n).eq(HPM_MAP_NAMES));
        Ok(ColumnMaps { maps })
    }
}

impl Hovland {
    /// The maps of Hovland's method for the columns of `model`, built on
    /// `grids`: each column's own ratio `(c A + N tan φ) / T` (0 where its
    /// strength is not positive, no data where `T ≤ 0`: the column holds
    /// the slide back or does not drive it), its normal force N and its
    /// driving force T ([`HOVLAND_MAP_NAMES`]).
    ///
    /// # Errors
    /// [`HpmError::MapData`] when `model` was not built on the grid of
    /// `grids` ([`MapProblem::GridSize`], [`MapProblem::CellOutside`],
    /// [`MapProblem::CornerOff`]), or these are not Hovland's terms of
    /// `model` ([`MapProblem::NotThisHovland`]: not one per column).
    pub fn maps(&self, model: &HpmModel, grids: &SlopeGrids) -> Result<ColumnMaps> {
        if self.columns.len() != model.columns.len() {
            return Err(DismechError::Hpm(HpmError::MapData {
                reason: MapProblem::NotThisHovland {
                    hovland: self.columns.len(),
                    model: model.columns.len(),
                },
            }));
        }
        let cells = column_cells(model, grids)?;
        let strengths = model.column_strengths();
        let local = |k: usize| {
            let t = &self.columns[k];
            let s = &strengths[k];
            let strength = s.cohesion * t.area + t.normal * s.friction;
            if t.driving <= 0.0 {
                None
            } else if strength <= 0.0 {
                Some(0.0)
            } else {
                Some(strength / t.driving)
            }
        };
        let maps = vec![
            ("local_fs", column_raster(grids, &cells, local)?),
            (
                "normal_force",
                column_raster(grids, &cells, |k| Some(self.columns[k].normal))?,
            ),
            (
                "driving_force",
                column_raster(grids, &cells, |k| Some(self.columns[k].driving))?,
            ),
        ];
        debug_assert!(maps.iter().map(|(n, _)| *n).eq(HOVLAND_MAP_NAMES));
        Ok(ColumnMaps { maps })
    }
}
