//! An HPM slope model built from the grids: columns split into layers
//! (§3, Fig. 7), elements, the penalty springs between them (eqs. 14–22),
//! the slip-surface springs (eqs. 23–30), the element weights (eqs. 5–10)
//! and the assembled stiffness of eq. (4).
//!
//! Spring constants (eq. 16 with the errata's `k_n`):
//! `k_n = (1 − ν) E' / ((1 + ν)(1 − 2ν) h)`, `k_s = k_t = E' / ((1 + ν) h)`,
//! with `E' = p E` (eq. 17) between elements and `E' = E_slip` (eq. 30) on
//! the slip surface. `h` is the cell size for side faces (eq. 16); for the
//! face between two layers it is the vertical distance between the two
//! centroids (our reading of `h = h_i + h_ii`: the distances from each
//! centroid to the face); on the slip surface it is the mean thickness
//! `h_I` of the bottom element.

use nalgebra::{Point3, Vector3};

use super::error::HpmError;
use super::face::{bilinear_face, side_face, spring_matrix, FacePoint, Side, SlipPoint};
use super::grids::SlopeGrids;
use super::material::{HpmMaterial, HpmSettings, Seismic};
use super::stiffness::BlockMatrix;
use crate::error::{require_positive, DismechError, Result};
use crate::kinematics::affine3::{elasticity, element_stiffness, shape_matrix, Block, ELEMENT_DOF};
use crate::law::{MohrCoulombSpring, Strength};
use crate::shape::Column;

/// Gauss points of a face (2 × 2).
const FACE_POINTS: u128 = 4;

/// Vectors of 12 unknowns per element an analysis holds at once (loads,
/// displacements, residual, `K u`, corrections and their difference, the
/// solver's work vector), counted generously.
const SOLUTION_VECTORS: u128 = 10;

/// One element: a layer of a column.
#[derive(Debug, Clone, PartialEq)]
pub struct Element {
    /// Index of its column in [`HpmModel::columns`].
    pub column: usize,
    /// Layer, 0 at the bottom.
    pub layer: usize,
    /// The hexahedron.
    pub shape: Column,
    /// Centroid: the reference point of the rigid motion (eq. 2).
    pub centre: Point3<f64>,
    /// Volume (m³).
    pub volume: f64,
    /// Weight W_I (N), eqs. (8)–(10).
    pub weight: f64,
    /// Horizontal seepage force (N) along x and y of the pore water below
    /// the water table; zero without one.
    ///
    /// Eqs. (8)–(10) weigh the ground below the water table by `γ_sub`:
    /// its weight less the buoyancy `(γ_t − γ_sub) V_w` of its volume
    /// `V_w` below the table. That is the whole of the pore water's action
    /// only where the table is level. The pore pressure of a table at
    /// `z_w(x, y)`, hydrostatic below it (`u = γ_w (z_w − z)`, the pressure
    /// Hovland's method and the slope search take on a column's base),
    /// acts on the ground below it with `−∇u = γ_w e_z − γ_w ∇z_w` per unit
    /// volume: the buoyancy, and the seepage force `−γ_w ∇z_w`, horizontal,
    /// down the table's slope. The element takes it at its centroid, with
    /// the table's slope over the cell (the mean of its edges' slopes, as
    /// the slip surface's in [`super::hovland()`]) and `γ_w = γ_t − γ_sub`
    /// of each stratum (the buoyancy its weight already has): `seepage =
    /// −(W_dry − W) ∇z_w`, with `W_dry` the element's weight without the
    /// table. Submerged weight and seepage force together are the total
    /// weight and the pore pressure on the element's boundary: on a planar
    /// slope under a parallel table, HPM's and Hovland's Fs are those of
    /// total weight and pore pressure (`tests/hpm_exact.rs`). Paper 001
    /// weighs by `γ_sub` and has no seepage force.
    pub seepage: [f64; 2],
    /// Buoyancy (N) of its volume below the water table, `W_dry − W`;
    /// zero without one. The seismic force takes the total weight
    /// `W + buoyancy` ([`HpmModel::loads`]).
    pub buoyancy: f64,
}

/// One valid column of the grid.
#[derive(Debug, Clone, PartialEq)]
pub struct GridColumn {
    /// Grid row (0 at the top of the file) and column.
    pub cell: (usize, usize),
    /// Its elements, bottom first.
    pub elements: std::ops::Range<usize>,
    /// The whole column (slip surface to ground surface).
    pub shape: Column,
}

/// A face between two elements with its penalty springs.
#[derive(Debug, Clone, PartialEq)]
pub struct Interface {
    /// The element on the side the normal leaves.
    pub a: usize,
    /// The element the normal points into.
    pub b: usize,
    /// Gauss points (normal from a to b).
    pub points: Vec<FacePoint>,
    /// Normal stiffness k_n (Pa/m).
    pub normal_stiffness: f64,
    /// Shear stiffness k_s = k_t (Pa/m).
    pub shear_stiffness: f64,
}

/// A slip-surface spring: one Gauss point under a bottom element.
#[derive(Debug, Clone, PartialEq)]
pub struct SlipSpring {
    /// The bottom element above it.
    pub element: usize,
    /// Its column.
    pub column: usize,
    /// Position, frame and area.
    pub point: SlipPoint,
    /// Its law (stiffness and strength).
    pub law: MohrCoulombSpring,
    /// k_n (Pa/m).
    pub normal_stiffness: f64,
    /// k_s = k_t (Pa/m).
    pub shear_stiffness: f64,
    /// Pore pressure u (Pa) on the slip surface at this point, a load
    /// `−u A n` that pushes the slide off the surface, so that the spring
    /// carries the effective normal traction; zero unless
    /// [`HpmModel::set_column_pore_pressure`] gave one (a pore-pressure
    /// ratio: [`crate::slope::hpm_reanalysis`]).
    pub pore_pressure: f64,
}

/// The discretised slope.
#[derive(Debug, Clone)]
pub struct HpmModel {
    /// The material.
    pub material: HpmMaterial,
    /// The settings it was built with.
    pub settings: HpmSettings,
    /// Valid columns.
    pub columns: Vec<GridColumn>,
    /// Elements, column by column, bottom first.
    pub elements: Vec<Element>,
    /// Faces between elements.
    pub interfaces: Vec<Interface>,
    /// Slip-surface springs.
    pub slip: Vec<SlipSpring>,
    /// Grid rows and columns, and cell size.
    pub grid: (usize, usize, f64),
}

/// Faces of a column with `layers` elements, at most: between its layers,
/// and each layer's east and north sides.
fn faces_per_column(layers: u128) -> u128 {
    (layers.saturating_sub(1)).saturating_add(layers.saturating_mul(2))
}

/// Words (of 8 bytes) per entry of the compressed lower triangle that the
/// ordering and symbolic analysis of the sparse Cholesky take at most
/// while they run (faer's approximate minimum degree works on the whole
/// symmetric pattern with elbow room): 6, where 4.3 to 4.4 were measured
/// from 400 columns of 3 layers to the 10 000 columns of 5 layers of the
/// `hpm_elastic` bench.
pub const SYMBOLIC_WORDS_PER_ENTRY: u128 = 6;

/// `columns` times the bytes of a column of `layers` elements and its
/// faces, saturating.
fn per_columns(
    columns: usize,
    layers: usize,
    per_column: u128,
    per_element: u128,
    per_face: u128,
) -> u128 {
    let (columns, layers) = (columns as u128, layers as u128);
    let column = per_column
        .saturating_add(layers.saturating_mul(per_element))
        .saturating_add(faces_per_column(layers).saturating_mul(per_face));
    columns.saturating_mul(column)
}

/// What [`HpmModel::memory_estimate`] counts, for a refusal.
const MODEL_PARTS: &str = "its elements, springs, block stiffness and solution vectors";

/// What the memory of an HPM model refused for its size counts
/// ([`HpmError::HpmModelTooLarge`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MemoryParts {
    /// The model: its elements, springs, block stiffness and solution
    /// vectors ([`HpmModel::memory_estimate`]).
    Model,
    /// The model, and the sparse Cholesky solver's compressed lower
    /// triangle and the workspace of its ordering, before the factor's
    /// fill is known ([`HpmModel::cholesky_estimate`]).
    CholeskyOrdering,
    /// The model, and the sparse Cholesky solver's compressed lower
    /// triangle and its factor, counted by the symbolic analysis.
    CholeskyFactor {
        /// Entries of the factor.
        entries: usize,
    },
    /// The model, and the conjugate gradients' dense column blocks
    /// ([`HpmModel::column_blocks_estimate`]).
    ColumnBlocks,
}

impl std::fmt::Display for MemoryParts {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        const NO_FACTOR: &str = "(HpmSolver::iterative, conjugate gradients, needs no factor)";
        match self {
            Self::Model => f.write_str(MODEL_PARTS),
            Self::CholeskyOrdering => write!(
                f,
                "{MODEL_PARTS}, and the sparse Cholesky solver's compressed lower triangle and the workspace of its ordering (its factor's fill comes on top) {NO_FACTOR}"
            ),
            Self::CholeskyFactor { entries } => write!(
                f,
                "{MODEL_PARTS}, and the sparse Cholesky solver's compressed lower triangle and its factor of {entries} entries with faer's workspace {NO_FACTOR}"
            ),
            Self::ColumnBlocks => write!(
                f,
                "{MODEL_PARTS}, and the conjugate gradients' dense column blocks, (12 × layers)² numbers a column"
            ),
        }
    }
}

/// Mean of four corner heights (eqs. 5–7).
fn mean(z: &[f64; 4]) -> f64 {
    0.25 * z.iter().sum::<f64>()
}

/// Slopes `(∂z/∂x, ∂z/∂y)` over a cell of side `d` of a surface with
/// corner heights `z` in the order of [`Column::new`]: the mean of the
/// slopes of its two edges along each axis.
pub(super) fn cell_slope(z: &[f64; 4], d: f64) -> (f64, f64) {
    (
        0.5 * ((z[1] - z[0]) + (z[2] - z[3])) / d,
        0.5 * ((z[3] - z[0]) + (z[2] - z[1])) / d,
    )
}

/// One stratum of a column's ground, for the weight of its elements
/// ([`HpmModel::set_column_strata`]): its bottom elevation and its unit
/// weights above and below the water table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeightStratum {
    /// Elevation of its bottom (m); `None` for the last stratum, unbounded
    /// below. The first is unbounded above.
    pub bottom: Option<f64>,
    /// Total unit weight γ_t (N/m³), above the water table.
    pub unit_weight: f64,
    /// Submerged unit weight γ_sub (N/m³), below it.
    pub submerged_unit_weight: f64,
}

impl WeightStratum {
    /// The one stratum of `material`, unbounded: the material's weights.
    fn of(material: &HpmMaterial) -> Self {
        Self {
            bottom: None,
            unit_weight: material.unit_weight,
            submerged_unit_weight: material.submerged_unit_weight,
        }
    }
}

/// Weight per unit plan area of the ground between the mean heights `hd`
/// and `hu` of an element's bottom and top, eqs. (8)–(10) taken piece by
/// piece over `strata` (top to bottom, each down to its bottom, the last
/// unbounded below, the first unbounded above) and the mean water level
/// `hw`: `Σ γ_k Δz_k`, summed from the bottom up, with `γ_sub` below
/// `hw` and `γ_t` above it. Neighbouring pieces of the same unit weight
/// on the same side of the water table are one piece (the water table
/// always cuts, even where `γ_sub = γ_t`), so that one stratum (or strata
/// of equal weights) gives eqs. (8)–(10) with the same floating-point
/// operations: `γ_t (hu − hd)`, `γ_sub (hu − hd)`, or
/// `γ_sub (hw − hd) + γ_t (hu − hw)`.
fn stratified_weight(strata: &[WeightStratum], hw: Option<f64>, hd: f64, hu: f64) -> f64 {
    let mut body = 0.0;
    // The unit weight of the piece being summed, whether it lies below
    // the water table, and its bottom.
    let mut piece: Option<(f64, bool, f64)> = None;
    let mut add = |gamma: f64, submerged: bool, from: f64| match piece {
        Some((g, wet, _)) if g == gamma && wet == submerged => {}
        Some((g, _, start)) => {
            body += g * (from - start);
            piece = Some((gamma, submerged, from));
        }
        None => piece = Some((gamma, submerged, from)),
    };
    for (i, stratum) in strata.iter().enumerate().rev() {
        let low = stratum.bottom.map_or(hd, |b| b.max(hd));
        let high = match i {
            0 => hu,
            _ => strata[i - 1].bottom.map_or(hu, |b| b.min(hu)),
        };
        if high <= low {
            continue;
        }
        match hw {
            Some(w) if w >= high => add(stratum.submerged_unit_weight, true, low),
            Some(w) if w > low => {
                add(stratum.submerged_unit_weight, true, low);
                add(stratum.unit_weight, false, w);
            }
            _ => add(stratum.unit_weight, false, low),
        }
    }
    if let Some((g, _, start)) = piece {
        body += g * (hu - start);
    }
    body
}

/// Weight of an element, eqs. (8)–(10), over `strata`
/// ([`stratified_weight`]), its buoyancy ([`Element::buoyancy`]) and its
/// horizontal seepage force ([`Element::seepage`]).
fn element_loads(
    strata: &[WeightStratum],
    shape: &Column,
    water: Option<&[f64; 4]>,
    cell_area: f64,
) -> (f64, f64, [f64; 2]) {
    let (hu, hd) = (mean(&shape.top()), mean(&shape.bottom()));
    let weight = stratified_weight(strata, water.map(mean), hd, hu) * cell_area;
    let Some(w) = water else {
        return (weight, 0.0, [0.0; 2]);
    };
    let buoyancy = stratified_weight(strata, None, hd, hu) * cell_area - weight;
    let (slope_x, slope_y) = cell_slope(w, shape.size());
    (weight, buoyancy, [-buoyancy * slope_x, -buoyancy * slope_y])
}

/// Check the strata of [`HpmModel::set_column_strata`].
fn check_strata(strata: &[WeightStratum]) -> Result<()> {
    let Some(last) = strata.last() else {
        return Err(DismechError::InvalidParameter {
            name: "HPM weight strata (count)",
            value: 0.0,
            requirement: "at least one stratum is needed",
        });
    };
    if let Some(bottom) = last.bottom {
        return Err(DismechError::InvalidParameter {
            name: "HPM weight strata: the last stratum's bottom",
            value: bottom,
            requirement: "the last stratum is unbounded below (no bottom)",
        });
    }
    let mut above = f64::INFINITY;
    for stratum in strata {
        require_positive(
            "HPM weight stratum: unit weight gamma_t",
            stratum.unit_weight,
        )?;
        require_positive(
            "HPM weight stratum: submerged unit weight gamma_sub",
            stratum.submerged_unit_weight,
        )?;
        super::material::require_submerged_below_total(
            "HPM weight stratum: submerged unit weight gamma_sub",
            stratum.submerged_unit_weight,
            stratum.unit_weight,
        )?;
        if std::ptr::eq(stratum, last) {
            break;
        }
        let Some(bottom) = stratum.bottom else {
            return Err(DismechError::InvalidParameter {
                name: "HPM weight strata: a bottom (count of strata)",
                value: strata.len() as f64,
                requirement: "every stratum but the last needs a bottom",
            });
        };
        if !bottom.is_finite() || bottom > above {
            return Err(DismechError::InvalidParameter {
                name: "HPM weight stratum: bottom elevation",
                value: bottom,
                requirement: "must be finite and not above the bottom of the stratum above",
            });
        }
        above = bottom;
    }
    Ok(())
}

impl HpmModel {
    /// Bytes a model of `columns` columns of `layers` layers takes, at most,
    /// whichever linear solver it is given: its elements, columns, slip
    /// springs and faces with their Gauss points, its stiffness (a diagonal
    /// block per element, a coupling block per face and their block rows)
    /// and the vectors of 12 unknowns per element the analyses hold.
    /// Saturates rather than wraps for absurd sizes. What a solver adds is
    /// counted apart: [`HpmModel::cholesky_estimate`] and the factor's
    /// [`SparseCholesky::factor_bytes`](crate::linsolve::SparseCholesky::factor_bytes)
    /// for the sparse Cholesky of [`HpmSolver::new`](super::HpmSolver::new),
    /// [`HpmModel::column_blocks_estimate`] for the conjugate gradients of
    /// [`HpmSolver::iterative`](super::HpmSolver::iterative).
    pub fn memory_estimate(columns: usize, layers: usize) -> u128 {
        use std::mem::size_of;
        let block = size_of::<Block>() as u128;
        let dof = ELEMENT_DOF as u128;
        let per_element = size_of::<Element>() as u128
            + block
            + SOLUTION_VECTORS * dof * size_of::<f64>() as u128
            + size_of::<usize>() as u128;
        let per_face = size_of::<Interface>() as u128
            + FACE_POINTS * size_of::<FacePoint>() as u128
            + size_of::<(usize, usize, Block)>() as u128
            + 2 * size_of::<(usize, usize, bool)>() as u128;
        let per_column = size_of::<GridColumn>() as u128
            + FACE_POINTS
                * (size_of::<SlipSpring>()
                    + size_of::<MohrCoulombSpring>()
                    + size_of::<super::analysis::SpringTraction>()) as u128;
        per_columns(columns, layers, per_column, per_element, per_face)
    }

    /// Bytes the sparse Cholesky solver of [`HpmSolver::new`](super::HpmSolver::new)
    /// adds to [`HpmModel::memory_estimate`] before its factor, at most: the
    /// compressed lower triangle of the stiffness (a value and a row index
    /// per entry, 78 entries per element and 144 per face, and the column
    /// pointers) and the workspace of its ordering and symbolic analysis
    /// (at most [`SYMBOLIC_WORDS_PER_ENTRY`] words per entry). The factor's
    /// fill, which the symbolic analysis counts, comes on top
    /// ([`SparseCholesky::factor_bytes`](crate::linsolve::SparseCholesky::factor_bytes)).
    pub fn cholesky_estimate(columns: usize, layers: usize) -> u128 {
        let dof = ELEMENT_DOF as u128;
        let word = std::mem::size_of::<usize>() as u128;
        let entry = std::mem::size_of::<f64>() as u128 + (1 + SYMBOLIC_WORDS_PER_ENTRY) * word;
        let per_element = entry * dof * (dof + 1) / 2 + word * dof;
        let per_face = entry * dof * dof;
        per_columns(columns, layers, 0, per_element, per_face)
    }

    /// Bytes the conjugate gradients of
    /// [`HpmSolver::iterative`](super::HpmSolver::iterative) add to
    /// [`HpmModel::memory_estimate`]: a dense block of `(12 × layers)²`
    /// numbers per column, the block-Jacobi preconditioner (no factor's
    /// fill, no compressed copy of the stiffness).
    pub fn column_blocks_estimate(columns: usize, layers: usize) -> u128 {
        (ELEMENT_DOF as u128)
            .saturating_mul(layers as u128)
            .saturating_pow(2)
            .saturating_mul(std::mem::size_of::<f64>() as u128)
            .saturating_mul(columns as u128)
    }

    /// Refuse `bytes` (the model's and what a solver adds, as `what`
    /// says) when they are over the model's memory budget `budget`
    /// ([`HpmSettings::memory_budget`]), or, with no budget set, when the
    /// system's allocator will not give them: they are asked for and given
    /// back at once (nothing is written, so no page is touched). Bytes
    /// beyond the address space are refused either way.
    pub(super) fn check_budget(
        budget: Option<u64>,
        columns: usize,
        layers: usize,
        bytes: u128,
        what: MemoryParts,
    ) -> Result<()> {
        // Beyond the address space nothing fits, whatever the budget.
        let fits = usize::try_from(bytes).is_ok_and(|len| match budget {
            Some(budget) => bytes <= u128::from(budget),
            None => Vec::<u8>::new().try_reserve_exact(len).is_ok(),
        });
        if fits {
            return Ok(());
        }
        Err(DismechError::Hpm(HpmError::HpmModelTooLarge {
            columns,
            layers,
            elements: columns as u128 * layers as u128,
            what,
            bytes,
            budget,
        }))
    }

    /// The strength of each column's slip springs, in the order of
    /// [`Self::columns`]: the material's, unless
    /// [`Self::set_column_strength`] gave the column its own.
    pub fn column_strengths(&self) -> Vec<Strength> {
        let own = Strength {
            cohesion: self.material.cohesion,
            friction: self.material.friction(),
        };
        let mut strengths = vec![own; self.columns.len()];
        for spring in &self.slip {
            strengths[spring.column] = spring.law.strength();
        }
        strengths
    }

    /// Column `column` (an index into [`Self::columns`]).
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for a column the model does not
    /// have.
    fn grid_column(&self, column: usize) -> Result<&GridColumn> {
        self.columns
            .get(column)
            .ok_or(DismechError::InvalidParameter {
                name: "HPM column index",
                value: column as f64,
                requirement: "must be below the model's number of columns",
            })
    }

    /// Put the pore pressure `u` (Pa) on the slip surface under column
    /// `column` (an index into [`Self::columns`]): at each of its slip
    /// springs a load `−u A n` on the slide, normal to the surface and away
    /// from it, so that the springs carry the effective normal traction
    /// `σ' = σ − u` and their strength is `c + σ' tan φ`. With the weights
    /// the total ones (no water table), a pore-pressure ratio's `u = r_u
    /// σ_v` (Bishop & Morgenstern 1960) on a planar slab gives its exact
    /// `Fs = (c + (cos² β − r_u) σ_v tan φ) / (σ_v sin β cos β)`
    /// (`tests/hpm_exact.rs`). It replaces a pressure set before.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for a column the model does not
    /// have, or a pressure that is negative or not finite.
    pub fn set_column_pore_pressure(&mut self, column: usize, pressure: f64) -> Result<()> {
        self.grid_column(column)?;
        crate::error::require_non_negative("pore pressure u on the slip surface", pressure)?;
        for spring in self.slip.iter_mut().filter(|s| s.column == column) {
            spring.pore_pressure = pressure;
        }
        Ok(())
    }

    /// The pore pressure on the slip surface under each column, in the
    /// order of [`Self::columns`] ([`Self::set_column_pore_pressure`]).
    pub fn column_pore_pressures(&self) -> Vec<f64> {
        let mut pressures = vec![0.0; self.columns.len()];
        for spring in &self.slip {
            pressures[spring.column] = spring.pore_pressure;
        }
        pressures
    }

    /// Give the slip springs under column `column` (an index into
    /// [`Self::columns`]) the strength `strength` in place of the
    /// material's: the strength of the layer the slip surface crosses
    /// there, on layered ground. Every safety factor, local factor and the
    /// nonlinear analysis take each spring's own strength.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for a column the model does not
    /// have, or a cohesion or friction coefficient that is negative or not
    /// finite.
    pub fn set_column_strength(&mut self, column: usize, strength: Strength) -> Result<()> {
        self.grid_column(column)?;
        crate::error::require_non_negative("cohesion c", strength.cohesion)?;
        crate::error::require_non_negative("friction coefficient tan(phi)", strength.friction)?;
        for spring in self.slip.iter_mut().filter(|s| s.column == column) {
            spring.law = spring.law.with_strength(strength);
        }
        Ok(())
    }

    /// Weigh the elements of column `column` (an index into
    /// [`Self::columns`]) by the unit weights of `strata` in place of the
    /// material's: the strata of a layered ground at the column, top to
    /// bottom, each with its own unit weights above and below the water
    /// table of `grids` (the grids the model was built on). Each element
    /// weighs `Σ γ_k Δz_k d²` over the pieces of its height, between the
    /// means of its corner heights, that the strata's bottoms and the mean
    /// water level cut (eqs. 8–10 piece by piece); one stratum of the
    /// material's weights gives the weights [`Self::new`] gave, bit for
    /// bit. The stiffness does not change; every load, safety factor and
    /// analysis takes the new weights.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for a column the model does not
    /// have, no stratum, a unit weight that is not finite and positive, a
    /// submerged unit weight above its stratum's unit weight, a
    /// bottom given to the last stratum or missing from another, bottoms
    /// that are not finite or rise downwards, or grids of other rows,
    /// columns or cell size than the model's.
    pub fn set_column_strata(
        &mut self,
        grids: &SlopeGrids,
        column: usize,
        strata: &[WeightStratum],
    ) -> Result<()> {
        let grid_column = self.grid_column(column)?;
        check_strata(strata)?;
        let raster = &grids.ground().raster;
        let (rows, columns, d) = self.grid;
        for (name, given, built) in [
            ("HPM weight strata: rows of the grids", raster.rows(), rows),
            (
                "HPM weight strata: columns of the grids",
                raster.columns(),
                columns,
            ),
        ] {
            if given != built {
                return Err(DismechError::InvalidParameter {
                    name,
                    value: given as f64,
                    requirement: "must be those of the grids the model was built on",
                });
            }
        }
        if raster.cell_size() != d {
            return Err(DismechError::InvalidParameter {
                name: "HPM weight strata: cell size of the grids",
                value: raster.cell_size(),
                requirement: "must be that of the grids the model was built on",
            });
        }
        let (r, c) = grid_column.cell;
        let (_, _, water) = grids.corners(r, c);
        for e in grid_column.elements.clone() {
            let element = &mut self.elements[e];
            (element.weight, element.buoyancy, element.seepage) =
                element_loads(strata, &element.shape, water.as_ref(), d * d);
        }
        Ok(())
    }

    /// Build the model; validates the material and settings.
    ///
    /// # Errors
    /// An invalid material or setting ([`DismechError::InvalidParameter`],
    /// naming it: see [`HpmMaterial::validate`] and
    /// [`HpmSettings::validate`]); [`HpmError::HpmModelTooLarge`] when
    /// the valid columns times the layers would take more memory
    /// ([`HpmModel::memory_estimate`]) than the budget
    /// [`HpmSettings::memory_budget`], or, with none set, than the system's
    /// allocator gives, refused before any element is made;
    /// [`HpmError::EmptyHpmModel`]
    /// when every valid column has zero thickness at all four corners (its
    /// slip corners, lowered to the ground, leave no volume), so that there
    /// is no element to analyse.
    pub fn new(grids: &SlopeGrids, material: &HpmMaterial, settings: &HpmSettings) -> Result<Self> {
        material.validate()?;
        settings.validate()?;
        let raster = &grids.ground().raster;
        let (rows, grid_columns, d) = (raster.rows(), raster.columns(), raster.cell_size());
        let (x_ll, y_ll) = raster.lower_left();
        let layers = settings.layers;
        let (fn_, fs) = material.spring_factors();
        let e_pen = settings.penalty * material.youngs_modulus;
        let friction = material.friction();
        if !e_pen.is_finite() {
            return Err(DismechError::InvalidParameter {
                name: "penalty factor p",
                value: settings.penalty,
                requirement: "p × E (the modulus of the springs between elements) must be finite",
            });
        }

        let valid = grids.valid_cells();
        Self::check_budget(
            settings.memory_budget,
            valid.len(),
            layers,
            Self::memory_estimate(valid.len(), layers),
            MemoryParts::Model,
        )?;
        // Within the budget, so these products are far below usize::MAX.
        let mut columns = Vec::with_capacity(valid.len());
        let mut elements = Vec::with_capacity(valid.len() * layers);
        let mut slip = Vec::with_capacity(valid.len() * FACE_POINTS as usize);
        let mut index = vec![usize::MAX; rows * grid_columns];
        for (r, c) in valid {
            let (ground, slip_z, water) = grids.corners(r, c);
            let origin = (x_ll + c as f64 * d, y_ll + (rows - r - 1) as f64 * d);
            let shape = Column::new(origin.0, origin.1, d, slip_z, ground)?;
            if shape.volume() <= 0.0 {
                // Zero thickness at every corner: nothing to analyse.
                continue;
            }
            let k = columns.len();
            index[r * grid_columns + c] = k;
            let first = elements.len();
            for (layer, part) in shape.layers(layers)?.into_iter().enumerate() {
                let (weight, buoyancy, seepage) =
                    element_loads(&[WeightStratum::of(material)], &part, water.as_ref(), d * d);
                elements.push(Element {
                    column: k,
                    layer,
                    centre: part.centroid(),
                    volume: part.volume(),
                    weight,
                    seepage,
                    buoyancy,
                    shape: part,
                });
            }
            // Slip springs under the bottom element (eqs. 27–30).
            let bottom = &elements[first];
            let h = mean(&bottom.shape.top()) - mean(&bottom.shape.bottom());
            let k_n = fn_ * material.slip_modulus / h;
            let k_s = material
                .slip_shear_stiffness
                .unwrap_or(fs * material.slip_modulus / h);
            let law = MohrCoulombSpring::new(k_n, k_s, material.cohesion, friction)?;
            for point in bilinear_face(origin, d, &slip_z) {
                slip.push(SlipSpring {
                    element: first,
                    column: k,
                    point,
                    law,
                    normal_stiffness: k_n,
                    shear_stiffness: k_s,
                    pore_pressure: 0.0,
                });
            }
            columns.push(GridColumn {
                cell: (r, c),
                elements: first..elements.len(),
                shape,
            });
        }

        if elements.is_empty() {
            return Err(DismechError::Hpm(HpmError::EmptyHpmModel {
                ground: grids.ground().name.clone(),
                slip: grids.slip().name.clone(),
                valid: grids.valid_cells().len(),
            }));
        }

        let mut interfaces =
            Vec::with_capacity(columns.len() * faces_per_column(layers as u128) as usize);
        // Between layers (eqs. 20–22): the normal of the shared bilinear face
        // points up, from the lower element into the upper.
        for column in &columns {
            for e in column.elements.start..column.elements.end - 1 {
                let (lower, upper) = (&elements[e], &elements[e + 1]);
                let h = upper.centre.z - lower.centre.z;
                let points = bilinear_face(lower.shape.origin(), d, &lower.shape.top())
                    .into_iter()
                    .map(|p| FacePoint {
                        normal: -p.point.normal,
                        ..p.point
                    })
                    .collect();
                interfaces.push(Interface {
                    a: e,
                    b: e + 1,
                    points,
                    normal_stiffness: fn_ * e_pen / h,
                    shear_stiffness: fs * e_pen / h,
                });
            }
        }
        // Side faces between the same layer of neighbouring columns (eqs. 14–19).
        for (k, column) in columns.iter().enumerate() {
            let (r, c) = column.cell;
            let east = (c + 1 < grid_columns).then(|| index[r * grid_columns + c + 1]);
            let north = (r > 0).then(|| index[(r - 1) * grid_columns + c]);
            for (neighbour, side) in [(east, Side::East), (north, Side::North)] {
                let Some(other) = neighbour.filter(|&o| o != usize::MAX) else {
                    continue;
                };
                for layer in 0..layers {
                    let (a, b) = (
                        columns[k].elements.start + layer,
                        columns[other].elements.start + layer,
                    );
                    let s = &elements[a].shape;
                    interfaces.push(Interface {
                        a,
                        b,
                        points: side_face(s.origin(), d, &s.bottom(), &s.top(), side),
                        normal_stiffness: fn_ * e_pen / d,
                        shear_stiffness: fs * e_pen / d,
                    });
                }
            }
        }
        Ok(Self {
            material: *material,
            settings: *settings,
            columns,
            elements,
            interfaces,
            slip,
            grid: (rows, grid_columns, d),
        })
    }

    /// Number of unknowns (12 per element).
    pub fn dof(&self) -> usize {
        ELEMENT_DOF * self.elements.len()
    }

    /// The elastic stiffness of eq. (4): element stiffnesses (eq. 25),
    /// penalty springs between elements (eqs. 18, 19, 22) and the elastic
    /// slip springs (eq. 22, slip).
    pub fn stiffness(&self) -> BlockMatrix {
        let mut k = self.free_stiffness();
        for spring in &self.slip {
            let e = &self.elements[spring.element];
            let p = &spring.point.point;
            let ks =
                spring_matrix(&p.normal, spring.normal_stiffness, spring.shear_stiffness) * p.area;
            let n = shape_matrix(&e.centre, &p.position);
            k.diagonal_mut()[spring.element] += n.transpose() * ks * n;
        }
        k
    }

    /// The stiffness of the elements and the springs between them, without
    /// the slip springs: singular (six rigid-body modes of the slide).
    pub fn free_stiffness(&self) -> BlockMatrix {
        let d = elasticity(self.material.youngs_modulus, self.material.poisson_ratio);
        let mut k = BlockMatrix::with_capacity(self.elements.len(), self.interfaces.len());
        for (e, element) in self.elements.iter().enumerate() {
            k.diagonal_mut()[e] += element_stiffness(element.volume, &d);
        }
        for face in &self.interfaces {
            let (ea, eb) = (&self.elements[face.a], &self.elements[face.b]);
            let mut coupling = Block::zeros();
            for p in &face.points {
                let ks =
                    spring_matrix(&p.normal, face.normal_stiffness, face.shear_stiffness) * p.area;
                let na = shape_matrix(&ea.centre, &p.position);
                let nb = shape_matrix(&eb.centre, &p.position);
                k.diagonal_mut()[face.a] += na.transpose() * ks * na;
                k.diagonal_mut()[face.b] += nb.transpose() * ks * nb;
                coupling -= na.transpose() * ks * nb;
            }
            k.add_coupling(face.a, face.b, coupling);
        }
        k
    }

    /// The load vector: weights W_I (eqs. 8–10), the seismic force
    /// `k_h W_I` along the unit horizontal direction of `seismic` (eqs.
    /// 11–13) and the seepage force below a water table
    /// ([`Element::seepage`]), at each element's centroid, and the pore
    /// pressure on the slip surface ([`SlipSpring::pore_pressure`]) at the
    /// springs' points. A zero
    /// coefficient adds no seismic force whatever the direction. Below
    /// a water table the seismic force is `k_h` times the total weight
    /// `W_I + buoyancy` (soil and pore water move together), as the slope
    /// search's Hovland ([`crate::slope`]) takes it; eq. (11) takes W_I of
    /// eqs. (8)–(10), the submerged weight. With the seepage force this
    /// makes the loads those of total weight and pore pressure, seismic
    /// included.
    pub fn loads(&self, seismic: &Seismic) -> Vec<f64> {
        let (cx, cy) = if seismic.coefficient == 0.0 {
            (0.0, 0.0)
        } else {
            seismic.unit()
        };
        let mut f = vec![0.0; self.dof()];
        for (e, element) in self.elements.iter().enumerate() {
            let h = seismic.coefficient * (element.weight + element.buoyancy);
            f[ELEMENT_DOF * e] = h * cx + element.seepage[0];
            f[ELEMENT_DOF * e + 1] = h * cy + element.seepage[1];
            f[ELEMENT_DOF * e + 2] = -element.weight;
        }
        for spring in self.slip.iter().filter(|s| s.pore_pressure != 0.0) {
            let p = &spring.point.point;
            let element = &self.elements[spring.element];
            let force = -p.normal * (spring.pore_pressure * p.area);
            let generalised = shape_matrix(&element.centre, &p.position).transpose() * force;
            for (k, value) in generalised.iter().enumerate() {
                f[ELEMENT_DOF * spring.element + k] += value;
            }
        }
        f
    }

    /// Total weight of the slide (N).
    pub fn total_weight(&self) -> f64 {
        self.elements.iter().map(|e| e.weight).sum()
    }

    /// The relative displacement `[approach along n, along s, along t]` of
    /// a slip spring (eq. 27) for the displacements `u`.
    pub fn slip_displacement(&self, spring: &SlipSpring, u: &[f64]) -> Vector3<f64> {
        let e = &self.elements[spring.element];
        let dofs = &u[ELEMENT_DOF * spring.element..ELEMENT_DOF * (spring.element + 1)];
        let n = shape_matrix(&e.centre, &spring.point.point.position);
        let disp = n * crate::kinematics::affine3::ElementDofs::from_column_slice(dofs);
        let p = &spring.point;
        Vector3::new(p.point.normal.dot(&disp), p.s.dot(&disp), p.t.dot(&disp))
    }
}
