//! Slope-search errors: [`SlopeError`], joined into
//! [`DismechError::Slope`](crate::error::DismechError::Slope): a DEM
//! without data or too small, ground whose layers or pore pressure cannot
//! be used, a range given upside down, ground that an HPM re-analysis
//! cannot take. Each variant names the offending value or file.

use crate::error::Number;

/// Why a slope search (its terrain, ground, trial surfaces) or an HPM
/// re-analysis of its surfaces cannot be run; joined into
/// [`DismechError::Slope`](crate::error::DismechError::Slope).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SlopeError {
    /// A digital elevation model with no cell of ground data, given to a
    /// slope search ([`crate::slope`]).
    #[error("{file}: none of its {rows} row(s) × {columns} column(s) has ground data (every cell is no-data); a slope search needs a digital elevation model with data")]
    NoGroundData {
        /// The file (or the name given to the raster).
        file: String,
        /// Grid rows.
        rows: usize,
        /// Grid columns.
        columns: usize,
    },
    /// A digital elevation model too small for a slope search
    /// ([`crate::slope`]): a trial surface may not touch the grid's edge, so
    /// at least one cell must lie inside it.
    #[error("{file}: a grid of {rows} row(s) × {columns} column(s) is too small for a slope search: a trial surface whose columns touch the edge of the grid leaves it and is refused, so at least 3 rows and 3 columns are needed (one inner cell); extend the grid beyond the slope")]
    DemTooSmall {
        /// The file (or the name given to the raster).
        file: String,
        /// Grid rows.
        rows: usize,
        /// Grid columns.
        columns: usize,
    },
    /// A strength layer of the ground of a slope search that cannot be
    /// used ([`crate::slope::Layer`]): its bottom raster off the DEM's
    /// grid, a bottom missing or given where it must not be, no layer.
    #[error("layer `{layer}`: {problem}")]
    InvalidLayer {
        /// The layer's name.
        layer: String,
        /// What is wrong, with the offending file or value.
        problem: crate::slope::LayerProblem,
    },
    /// A pore-pressure ratio r_u outside `[0, 1)` ([`crate::slope::PoreRatio`]).
    #[error("pore-pressure ratio r_u = {} from {source_name} at {}: must be finite, >= 0 and < 1 (u = r_u sigma_v; r_u = 1 would leave no effective stress)", Number(*value), cell_name(cell))]
    PoreRatioOutOfRange {
        /// The constant, or the raster's file.
        source_name: String,
        /// The raster's cell `(row, column)`, from 0 at the top left;
        /// `None` for a constant (every cell).
        cell: Option<(usize, usize)>,
        /// The value given.
        value: f64,
    },
    /// Two sources of pore pressure given at once to a slope search: the
    /// water table and a pore-pressure ratio r_u.
    #[error("pore pressure given twice: the water table {water} and the pore-pressure ratio r_u {ratio}; give one of them")]
    PorePressureTwice {
        /// The water table's file.
        water: String,
        /// The r_u constant or file.
        ratio: String,
    },
    /// A range of values whose lower bound lies above its upper bound
    /// (e.g. the radii of a search of trial spheres).
    #[error("invalid {name}: its lower bound {} lies above its upper bound {}; give min <= max", Number(*low), Number(*high))]
    InvalidRange {
        /// The range's name (e.g. `radius range`).
        name: &'static str,
        /// The lower bound given.
        low: f64,
        /// The upper bound given.
        high: f64,
    },
    /// A floor of Bishop's `m_α`
    /// ([`crate::slope::BishopSettings::with_m_alpha_floor`]) outside
    /// (0, 1].
    #[error("Bishop's m_alpha floor = {}: must be finite and lie in (0, 1] (default 0.2, Whitman & Bailey 1967)", Number(*value))]
    MAlphaFloorOutOfRange {
        /// The floor given.
        value: f64,
    },
    /// Ground that an HPM re-analysis of a trial surface
    /// ([`crate::slope::hpm_reanalysis`]) cannot take: a layer bottom or a
    /// pore-pressure ratio with no data where a column needs it.
    #[error("HPM re-analysis cannot take this ground: {reason}")]
    HpmGround {
        /// What the ground has that HPM cannot take.
        reason: String,
    },
}

/// `row R, column C` for a raster's cell, `every cell` for none.
fn cell_name(cell: &Option<(usize, usize)>) -> String {
    match cell {
        Some((row, column)) => format!("row {row}, column {column}"),
        None => "every cell".to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::DismechError;

    #[test]
    fn joined_into_dismech_error_with_the_same_message() {
        let e = SlopeError::PoreRatioOutOfRange {
            source_name: "ru.asc".into(),
            cell: Some((2, 3)),
            value: 1.5,
        };
        let joined = DismechError::from(e.clone());
        assert_eq!(joined.to_string(), e.to_string());
        assert_eq!(
            joined.to_string(),
            "pore-pressure ratio r_u = 1.5 from ru.asc at row 2, column 3: must be finite, >= 0 and < 1 (u = r_u sigma_v; r_u = 1 would leave no effective stress)"
        );
        assert!(matches!(
            joined,
            DismechError::Slope(SlopeError::PoreRatioOutOfRange { value, .. }) if value == 1.5
        ));
    }
}
