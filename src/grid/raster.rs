//! A raster: values on a regular grid of square cells.

use crate::error::{require_finite, require_positive, DismechError, Result};

/// The largest number of cells a [`Raster`] may hold: 10^8, e.g. a grid of
/// 10 000 × 10 000 cells.
///
/// A grid file states its size in its header; the reader checks that size
/// against this cap before it allocates anything, so no header can make it
/// ask for more memory than a workstation has. 10^8 cells hold 1.6 GB of
/// values (16 bytes a cell) and need at least 200 MB of text to write down:
/// a digital elevation model of 10 km × 10 km at 1 m, far more than any
/// slope the HPM can solve (its bench of 100 × 100 columns and 5 layers
/// already takes 7.4 GiB by sparse Cholesky), so the cap refuses no grid the
/// analyses could use.
pub const MAX_GRID_CELLS: usize = 100_000_000;

/// `columns × rows`, checked: both at least 1 and the product at most
/// [`MAX_GRID_CELLS`] (computed exactly, so it cannot wrap).
fn cell_count(columns: usize, rows: usize) -> Result<usize> {
    require_positive("raster columns", columns as f64)?;
    require_positive("raster rows", rows as f64)?;
    match columns.checked_mul(rows) {
        Some(cells) if cells <= MAX_GRID_CELLS => Ok(cells),
        _ => Err(DismechError::InvalidParameter {
            name: "raster cell count (columns × rows)",
            value: columns as f64 * rows as f64,
            requirement: "must be at most MAX_GRID_CELLS = 10^8",
        }),
    }
}

/// Values on `rows × columns` square cells of side `cell_size`, row 0 the
/// northernmost (top) row as in an ESRI ASCII file; `None` marks a cell
/// without data.
#[derive(Debug, Clone, PartialEq)]
pub struct Raster {
    columns: usize,
    rows: usize,
    /// x of the lower-left corner of the grid (m).
    x_lower_left: f64,
    /// y of the lower-left corner of the grid (m).
    y_lower_left: f64,
    cell_size: f64,
    values: Vec<Option<f64>>,
}

/// Centre of cell (row, column) of a grid with `rows` rows, row 0 at the top.
fn cell_centre(x0: f64, y0: f64, rows: usize, cell: f64, row: usize, column: usize) -> (f64, f64) {
    (
        x0 + (column as f64 + 0.5) * cell,
        y0 + (rows as f64 - row as f64 - 0.5) * cell,
    )
}

impl Raster {
    /// A raster from its values, row-major with row 0 at the top.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming the value for no column or
    /// no row, more than [`MAX_GRID_CELLS`] cells, a lower-left corner that
    /// is not finite, a cell size that is not finite and positive, a right
    /// or top edge that overflows to infinity, a number of values other
    /// than `columns × rows`, or a value that is not finite (`None` marks a
    /// cell without data).
    pub fn new(
        columns: usize,
        rows: usize,
        x_lower_left: f64,
        y_lower_left: f64,
        cell_size: f64,
        values: Vec<Option<f64>>,
    ) -> Result<Self> {
        let cells = cell_count(columns, rows)?;
        require_finite("raster x of the lower-left corner", x_lower_left)?;
        require_finite("raster y of the lower-left corner", y_lower_left)?;
        require_positive("raster cell size", cell_size)?;
        require_finite(
            "raster x of the right edge",
            x_lower_left + columns as f64 * cell_size,
        )?;
        require_finite(
            "raster y of the top edge",
            y_lower_left + rows as f64 * cell_size,
        )?;
        if values.len() != cells {
            return Err(DismechError::InvalidParameter {
                name: "raster value count",
                value: values.len() as f64,
                requirement: "must equal columns × rows",
            });
        }
        if let Some(v) = values.iter().flatten().find(|v| !v.is_finite()) {
            return Err(DismechError::InvalidParameter {
                name: "raster value",
                value: *v,
                requirement: "must be finite (use None for a cell without data)",
            });
        }
        Ok(Self {
            columns,
            rows,
            x_lower_left,
            y_lower_left,
            cell_size,
            values,
        })
    }

    /// A raster whose value at each cell is `f(x, y)` at the cell centre.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] as [`Raster::new`]: no column or
    /// no row, or more than [`MAX_GRID_CELLS`] cells, checked before `f` is
    /// called; a corner, cell size or edge that is not finite (or a cell
    /// size not positive), or a value `f` returns that is not finite.
    pub fn from_fn(
        columns: usize,
        rows: usize,
        x_lower_left: f64,
        y_lower_left: f64,
        cell_size: f64,
        f: impl Fn(f64, f64) -> Option<f64>,
    ) -> Result<Self> {
        let values = (0..cell_count(columns, rows)?)
            .map(|k| {
                let (x, y) = cell_centre(
                    x_lower_left,
                    y_lower_left,
                    rows,
                    cell_size,
                    k / columns,
                    k % columns,
                );
                f(x, y)
            })
            .collect();
        Self::new(columns, rows, x_lower_left, y_lower_left, cell_size, values)
    }

    /// Number of columns.
    pub fn columns(&self) -> usize {
        self.columns
    }

    /// Number of rows.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Side of a cell (m).
    pub fn cell_size(&self) -> f64 {
        self.cell_size
    }

    /// The lower-left corner of the grid.
    pub fn lower_left(&self) -> (f64, f64) {
        (self.x_lower_left, self.y_lower_left)
    }

    /// The value of cell (row, column), `None` outside the grid or without
    /// data.
    pub fn get(&self, row: usize, column: usize) -> Option<f64> {
        if row < self.rows && column < self.columns {
            self.values[row * self.columns + column]
        } else {
            None
        }
    }

    /// The centre `(x, y)` of cell (row, column).
    pub fn cell_centre(&self, row: usize, column: usize) -> (f64, f64) {
        cell_centre(
            self.x_lower_left,
            self.y_lower_left,
            self.rows,
            self.cell_size,
            row,
            column,
        )
    }

    /// The values, row-major, row 0 at the top.
    pub fn values(&self) -> &[Option<f64>] {
        &self.values
    }

    /// Whether `other` lies on the same grid (shape, corner and cell size,
    /// within 1e-9 of a cell).
    pub fn same_grid(&self, other: &Raster) -> bool {
        let tol = 1e-9 * self.cell_size;
        self.columns == other.columns
            && self.rows == other.rows
            && (self.cell_size - other.cell_size).abs() <= tol
            && (self.x_lower_left - other.x_lower_left).abs() <= tol
            && (self.y_lower_left - other.y_lower_left).abs() <= tol
    }
}
