//! The input of a grid-column slope analysis, as slope engineers keep it:
//! ground surface, slip surface and (optional) water table on one regular
//! grid, each read from an ESRI ASCII file or built in code (paper 001, §3
//! and §5).
//!
//! A cell is a *valid* column when both surfaces have data there and the
//! slip surface lies below the ground surface at the cell centre (§5).
//! Faces need heights at the cell corners (eq. 23): a corner takes the
//! bilinear interpolation of the four surrounding cell-centre values,
//! extrapolated linearly at the grid edge (exact for a planar surface);
//! where a surrounding cell has no data the corner takes the mean of the
//! cells around it that have data. A slip-surface corner above the ground
//! corner is lowered to the ground (zero thickness there).

use std::path::Path;

use super::error::HpmError;
use crate::error::{DismechError, Result};
use crate::grid::{read_raster, GridCellProblem, GridError, GridExtent, Raster};

/// The fewest rows, and the fewest columns, of slope grids: corner heights
/// are interpolated (and at the edge extrapolated) between two cell centres
/// along each axis, so that a plane is exact (eq. 23).
pub const MIN_GRID_SIDE: usize = 2;

/// A raster with the name of the file it came from (used in errors).
#[derive(Debug, Clone, PartialEq)]
pub struct NamedRaster {
    /// File name, or a name given in code.
    pub name: String,
    /// The values.
    pub raster: Raster,
}

impl NamedRaster {
    /// A raster named `name`.
    pub fn new(name: impl Into<String>, raster: Raster) -> Self {
        Self {
            name: name.into(),
            raster,
        }
    }

    /// Refuse `self` unless it lies on the grid of `reference` (rows,
    /// columns, cell size, lower-left corner).
    ///
    /// # Errors
    /// [`GridError::Mismatch`] naming both rasters and both grids
    /// (their [`GridExtent`]s).
    pub fn require_grid_of(&self, reference: &NamedRaster) -> Result<()> {
        let (a, b) = (&reference.raster, &self.raster);
        if a.same_grid(b) {
            return Ok(());
        }
        Err(DismechError::Grid(GridError::Mismatch {
            file: self.name.clone(),
            reference: reference.name.clone(),
            found: Box::new(GridExtent::of(b)),
            expected: Box::new(GridExtent::of(a)),
        }))
    }

    /// Read a grid file: GeoTIFF where its extension is `.tif` or `.tiff`,
    /// ESRI ASCII otherwise ([`crate::grid::read_raster`]).
    ///
    /// # Errors
    /// Those of [`crate::grid::read_esri_ascii`] or
    /// [`crate::grid::read_geotiff`].
    pub fn read(path: &Path) -> Result<Self> {
        Ok(Self::new(path.display().to_string(), read_raster(path)?))
    }
}

/// Ground surface, slip surface and water table on one grid, checked.
#[derive(Debug, Clone, PartialEq)]
pub struct SlopeGrids {
    ground: NamedRaster,
    slip: NamedRaster,
    water: Option<NamedRaster>,
    valid: Vec<bool>,
}

/// Heights at the four corners of a cell, in the order of
/// [`crate::shape::Column::new`].
pub type Corners = [f64; 4];

impl SlopeGrids {
    /// Check the rasters and find the valid columns.
    ///
    /// # Errors
    /// Rasters on different grids ([`GridError::Mismatch`]); a grid
    /// of fewer than [`MIN_GRID_SIDE`] rows or columns
    /// ([`HpmError::GridTooSmall`], naming its size: the corner heights
    /// and slopes need two cell centres along each axis);
    /// a cell of the slide without ground data
    /// ([`GridCellProblem::NoGround`]), a slip-surface hole inside the
    /// slide ([`GridCellProblem::SlipSurfaceHole`]), or a water table
    /// without data over a valid column ([`GridCellProblem::NoWaterTable`])
    /// ([`GridError::Cell`], naming file, row and column); no valid
    /// column ([`HpmError::NoValidColumn`]).
    pub fn new(ground: NamedRaster, slip: NamedRaster, water: Option<NamedRaster>) -> Result<Self> {
        for other in std::iter::once(&slip).chain(water.as_ref()) {
            other.require_grid_of(&ground)?;
        }
        let (rows, columns) = (ground.raster.rows(), ground.raster.columns());
        if rows < MIN_GRID_SIDE || columns < MIN_GRID_SIDE {
            // One cell centre along an axis gives no slope along it: a
            // slope along a single row would be analysed as level ground.
            return Err(DismechError::Hpm(HpmError::GridTooSmall {
                file: ground.name.clone(),
                rows,
                columns,
            }));
        }
        let mut valid = vec![false; rows * columns];
        for r in 0..rows {
            for c in 0..columns {
                match (ground.raster.get(r, c), slip.raster.get(r, c)) {
                    (Some(g), Some(s)) => valid[r * columns + c] = s < g,
                    (None, Some(_)) => {
                        return Err(cell_error(&ground, r, c, GridCellProblem::NoGround))
                    }
                    _ => {}
                }
            }
        }
        // A slip-surface hole: no data between valid cells of its row or column.
        for r in 0..rows {
            for c in 0..columns {
                if slip.raster.get(r, c).is_some() {
                    continue;
                }
                let row_hole = (0..c).any(|k| valid[r * columns + k])
                    && (c + 1..columns).any(|k| valid[r * columns + k]);
                let column_hole = (0..r).any(|k| valid[k * columns + c])
                    && (r + 1..rows).any(|k| valid[k * columns + c]);
                if row_hole || column_hole {
                    return Err(cell_error(&slip, r, c, GridCellProblem::SlipSurfaceHole));
                }
            }
        }
        if !valid.iter().any(|&v| v) {
            return Err(DismechError::Hpm(HpmError::NoValidColumn {
                ground: ground.name.clone(),
                slip: slip.name.clone(),
            }));
        }
        if let Some(w) = &water {
            for (k, _) in valid.iter().enumerate().filter(|(_, &v)| v) {
                let (r, c) = (k / columns, k % columns);
                if w.raster.get(r, c).is_none() {
                    return Err(cell_error(w, r, c, GridCellProblem::NoWaterTable));
                }
            }
        }
        Ok(Self {
            ground,
            slip,
            water,
            valid,
        })
    }

    /// Read the three grids from ESRI ASCII (or GeoTIFF) files
    /// ([`NamedRaster::read`]).
    ///
    /// # Errors
    /// Those of [`crate::grid::read_esri_ascii`] (or
    /// [`crate::grid::read_geotiff`]) for each file (a path that
    /// is not a regular file, a file far larger than its header's grid can
    /// need, a header over [`crate::grid::MAX_GRID_CELLS`] cells: each
    /// refused before the values are read), then those of
    /// [`SlopeGrids::new`]; grids that
    /// differ in shape, corner or cell size are refused before any cell is
    /// looked at.
    pub fn read(ground: &Path, slip: &Path, water: Option<&Path>) -> Result<Self> {
        Self::new(
            NamedRaster::read(ground)?,
            NamedRaster::read(slip)?,
            water.map(NamedRaster::read).transpose()?,
        )
    }

    /// The ground surface.
    pub fn ground(&self) -> &NamedRaster {
        &self.ground
    }

    /// The slip surface.
    pub fn slip(&self) -> &NamedRaster {
        &self.slip
    }

    /// The water table, if given.
    pub fn water(&self) -> Option<&NamedRaster> {
        self.water.as_ref()
    }

    /// Whether cell (row, column) is a valid column.
    pub fn is_valid(&self, row: usize, column: usize) -> bool {
        row < self.ground.raster.rows()
            && column < self.ground.raster.columns()
            && self.valid[row * self.ground.raster.columns() + column]
    }

    /// The valid cells `(row, column)`, row-major.
    pub fn valid_cells(&self) -> Vec<(usize, usize)> {
        let columns = self.ground.raster.columns();
        (0..self.valid.len())
            .filter(|&k| self.valid[k])
            .map(|k| (k / columns, k % columns))
            .collect()
    }

    /// Corner heights (ground, slip, water) of cell (row, column); the slip
    /// corners are lowered to the ground where they lie above it.
    pub fn corners(&self, row: usize, column: usize) -> (Corners, Corners, Option<Corners>) {
        let at = |raster: &Raster| -> Corners {
            // Corner order (x0, y0), (x0 + d, y0), (x0 + d, y0 + d), (x0, y0 + d);
            // node row index grows southwards like the grid rows.
            [
                node_value(raster, row + 1, column),
                node_value(raster, row + 1, column + 1),
                node_value(raster, row, column + 1),
                node_value(raster, row, column),
            ]
        };
        let ground = at(&self.ground.raster);
        let mut slip = at(&self.slip.raster);
        for k in 0..4 {
            slip[k] = slip[k].min(ground[k]);
        }
        (ground, slip, self.water.as_ref().map(|w| at(&w.raster)))
    }
}

fn cell_error(
    raster: &NamedRaster,
    row: usize,
    column: usize,
    problem: GridCellProblem,
) -> DismechError {
    DismechError::Grid(GridError::Cell {
        file: raster.name.clone(),
        row,
        column,
        problem,
    })
}

/// The value at grid node (node_row, node_column): node row 0 is the top
/// edge of the grid, node row `rows` the bottom edge.
fn node_value(raster: &Raster, node_row: usize, node_column: usize) -> f64 {
    // Two cells bracketing (or, at the edge, next to) the node along an axis
    // and the node's fractional position from the first cell centre.
    let stencil = |node: usize, count: usize| -> (usize, usize, f64) {
        if count == 1 {
            return (0, 0, 0.0);
        }
        let first = node.saturating_sub(1).min(count - 2);
        (first, first + 1, node as f64 - (first as f64 + 0.5))
    };
    let (r0, r1, fr) = stencil(node_row, raster.rows());
    let (c0, c1, fc) = stencil(node_column, raster.columns());
    let cells = [
        (raster.get(r0, c0), (1.0 - fr) * (1.0 - fc)),
        (raster.get(r0, c1), (1.0 - fr) * fc),
        (raster.get(r1, c0), fr * (1.0 - fc)),
        (raster.get(r1, c1), fr * fc),
    ];
    if cells.iter().all(|(v, _)| v.is_some()) {
        return cells.iter().map(|(v, w)| v.unwrap_or(0.0) * w).sum();
    }
    // Mean of the (up to four) cells touching the node that have data.
    let touching = [
        (node_row.wrapping_sub(1), node_column.wrapping_sub(1)),
        (node_row.wrapping_sub(1), node_column),
        (node_row, node_column.wrapping_sub(1)),
        (node_row, node_column),
    ];
    let values: Vec<f64> = touching
        .iter()
        .filter_map(|&(r, c)| raster.get(r, c))
        .collect();
    if values.is_empty() {
        f64::NAN
    } else {
        values.iter().sum::<f64>() / values.len() as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plane(rows: usize, columns: usize, f: impl Fn(f64, f64) -> f64) -> Raster {
        Raster::from_fn(columns, rows, 0.0, 0.0, 10.0, |x, y| Some(f(x, y))).unwrap()
    }

    #[test]
    fn corner_heights_of_a_plane_are_exact_at_the_grid_edge() {
        let g = NamedRaster::new("g", plane(3, 4, |x, y| 100.0 + 0.1 * x + 0.3 * y));
        let s = NamedRaster::new("s", plane(3, 4, |x, y| 90.0 + 0.1 * x + 0.3 * y));
        let grids = SlopeGrids::new(g, s, None).unwrap();
        // Cell (0, 0) is the top-left cell: x in [0, 10], y in [20, 30].
        let (ground, slip, _) = grids.corners(0, 0);
        let exact = [
            100.0 + 0.3 * 20.0,
            100.0 + 1.0 + 0.3 * 20.0,
            100.0 + 1.0 + 0.3 * 30.0,
            100.0 + 0.3 * 30.0,
        ];
        for k in 0..4 {
            assert!((ground[k] - exact[k]).abs() < 1e-12, "{ground:?}");
            assert!((slip[k] - (exact[k] - 10.0)).abs() < 1e-12, "{slip:?}");
        }
    }
}
