//! HPM errors: [`HpmError`], joined into
//! [`DismechError::Hpm`](crate::error::DismechError::Hpm): grids with no
//! column to model, a model too large for its memory or ill-conditioned,
//! a safety factor that is undefined, a strength reduction that finds no
//! factor, maps asked of another model's result. Each variant names the
//! offending value or file.

use crate::error::{Bytes, SolveError};

/// Why an HPM model cannot be built, or an analysis of it run or give a
/// safety factor; joined into
/// [`DismechError::Hpm`](crate::error::DismechError::Hpm).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum HpmError {
    /// No cell has its slip surface below the ground surface.
    #[error("no valid column: the slip surface of {slip} lies nowhere below the ground surface of {ground}")]
    NoValidColumn {
        /// The ground-surface file.
        ground: String,
        /// The slip-surface file.
        slip: String,
    },
    /// A grid too small for a grid-column slope analysis: the corner
    /// heights and the slopes of the surfaces are interpolated between cell
    /// centres, which needs two of them along each axis.
    #[error("{file}: a grid of {rows} row(s) × {columns} column(s) is too small for a slope analysis: corner heights and the slopes of the surfaces are interpolated between cell centres, which needs at least 2 rows and 2 columns; extend the grids by a cell beyond the slide on each side")]
    GridTooSmall {
        /// The file (or the name given to the raster).
        file: String,
        /// Grid rows.
        rows: usize,
        /// Grid columns.
        columns: usize,
    },
    /// Every valid column of the grids has zero thickness: the model has
    /// no element.
    #[error("no HPM element: the {valid} valid column(s) of `{ground}` over `{slip}` have zero thickness at all four corners (the slip surface meets the ground there); lower the slip surface under the slide")]
    EmptyHpmModel {
        /// The ground-surface raster.
        ground: String,
        /// The slip-surface raster.
        slip: String,
        /// Number of valid columns.
        valid: usize,
    },
    /// An HPM model that, with what its linear solver adds, would take
    /// more memory than its budget ([`crate::hpm::HpmSettings::memory_budget`])
    /// or, with no budget set, than the system's allocator gives; refused
    /// before that memory is taken.
    #[error("an HPM model of {columns} columns × {layers} layers = {elements} elements needs about {bytes} bytes ({}) for {what}, {}", Bytes(*bytes), over_budget(*budget))]
    HpmModelTooLarge {
        /// Valid columns of the grid.
        columns: usize,
        /// Layers per column ([`crate::hpm::HpmSettings::layers`]).
        layers: usize,
        /// Their exact product.
        elements: u128,
        /// What the bytes count: the model
        /// ([`crate::hpm::HpmModel::memory_estimate`]) and the part of the
        /// linear solver being made (for the sparse Cholesky, the entries
        /// of its factor once the symbolic analysis has counted them).
        what: crate::hpm::MemoryParts,
        /// The memory counted.
        bytes: u128,
        /// The budget it is over ([`crate::hpm::HpmSettings::memory_budget`]);
        /// `None` where no budget was set and the system's allocator
        /// refused the memory.
        budget: Option<u64>,
    },
    /// The stiffness of an HPM model could not be factored, and the model
    /// has features that make it ill-conditioned.
    #[error(
        "the HPM stiffness could not be factored ({reason}); the model is ill-conditioned: {}",
        join(causes)
    )]
    IllConditioned {
        /// What makes the model ill-conditioned, each with what to change.
        causes: Vec<crate::hpm::IllConditioning>,
        /// The linear solver's error.
        reason: SolveError,
    },
    /// A safety factor asked of a slide that nothing drives along the
    /// direction it is measured in: the ratio of resisting to driving
    /// forces is undefined (infinite for a slide at rest on level ground,
    /// meaningless against a direction up the slope).
    #[error("nothing drives sliding ({what}): the driving force along the slip direction is {driving:.4e} N, the slide's weight {weight:.4e} N (a ratio of {:.3e}, not above {ratio:.0e}, or a driving force so small beside the resisting one that their ratio overflows), so its safety factor, resisting over driving forces, is undefined; a slope that dips, a seismic load, a water table that slopes or (for a given direction) a direction down the slip surface's dip drives a slide", .driving / .weight)]
    NothingDrivesSliding {
        /// Which safety factor, and the force that drives it.
        what: crate::hpm::SafetyFactorTerm,
        /// The driving force along the slip direction (N).
        driving: f64,
        /// The weight of the slide (N).
        weight: f64,
        /// The smallest driving force, as a share of the weight, that
        /// counts ([`crate::hpm::MIN_DRIVING_RATIO`]).
        ratio: f64,
    },
    /// A safety factor asked of a slide whose slip surface has no strength
    /// left: its strength `Σ (c + σ tan φ) A` is not positive, because the
    /// load puts the surface in tension beyond the apex of its
    /// Mohr–Coulomb law (σ < −c / tan φ, where `c + σ tan φ` is negative)
    /// over so much of it (a large seismic coefficient), or is so small
    /// beside the driving force that their ratio is zero. A zero or
    /// negative ratio of resisting to driving forces is no factor of
    /// safety: the slide is lifted off the surface there, not sheared
    /// along it.
    #[error("the slip surface has no strength left ({what}): Σ(c + σ tan φ)A = {strength:.4e} N against a driving force of {driving:.4e} N; the surface is in tension beyond c / tan φ, where c + σ tan φ is negative, over {:.1} % of its area, under {} of {columns} columns{}, so the ratio of resisting to driving forces would be zero or negative, no factor of safety: the slide is lifted off the surface rather than sheared along it; lower the seismic coefficient k_h or the pore pressure, check the slip surface against the direction of the load, or use the nonlinear HPM analysis, whose slip springs carry no tension", 100.0 * .area_share, .cells.len(), cell_list(cells))]
    SlipSurfaceInTension {
        /// Which safety factor, and the force that drives it.
        what: crate::hpm::SafetyFactorTerm,
        /// The slip surface's strength `Σ (c + σ tan φ) A` (N).
        strength: f64,
        /// The driving force it is set against (N).
        driving: f64,
        /// Grid cells `(row, column)` of the columns where the strength
        /// `c + σ tan φ` is negative under some part of the base, in the
        /// order of [`crate::hpm::HpmModel::columns`].
        cells: Vec<(usize, usize)>,
        /// Columns of the model.
        columns: usize,
        /// Share of the slip surface's area where the strength is negative,
        /// in [0, 1].
        area_share: f64,
    },
    /// A strength-reduction search found equilibrium at every factor it
    /// tried, up to its limit.
    #[error("strength reduction: equilibrium at every factor tried up to F = {factor:.4e}; nothing drives this slide to failure (check the slip surface and the loads)")]
    StrengthReductionNoFailure {
        /// The largest factor tried.
        factor: f64,
    },
    /// A strength-reduction search found no equilibrium at any factor it
    /// tried, down to its limit.
    #[error("strength reduction: no equilibrium even at F = {factor:.4e} (strength multiplied by {:.4e}); the slide cannot stand with a strength near the material's (see the nonlinear solve's residual)", 1.0 / .factor)]
    StrengthReductionNoEquilibrium {
        /// The smallest factor tried.
        factor: f64,
    },
    /// Maps asked of a result on a grid it does not belong to: an HPM or
    /// Hovland result of another model, or a model of another grid
    /// ([`crate::hpm::ColumnMaps`]).
    #[error("maps: {reason}")]
    MapData {
        /// What does not fit.
        reason: crate::hpm::MapProblem,
    },
}

/// The messages of `items`, separated by semicolons.
fn join<T: std::fmt::Display>(items: &[T]) -> String {
    items
        .iter()
        .map(|i| i.to_string())
        .collect::<Vec<_>>()
        .join("; ")
}

/// Why the memory of an HPM model is refused and what to change.
fn over_budget(budget: Option<u64>) -> String {
    match budget {
        Some(budget) => format!(
            "more than its memory budget HpmSettings::memory_budget = {budget} bytes ({}); raise HpmSettings::memory_budget where the machine has the memory (None asks the system), or use fewer layers, or crop or coarsen the grid",
            Bytes(u128::from(budget))
        ),
        None => "more than the system's allocator gives (HpmSettings::memory_budget is None, so the system was asked); use fewer layers, crop or coarsen the grid, or run on a machine with more memory".into(),
    }
}

/// ` (grid cells (row, column) (r, c), …)` naming the first few of
/// `cells`, or nothing.
fn cell_list(cells: &[(usize, usize)]) -> String {
    const SHOWN: usize = 6;
    if cells.is_empty() {
        return String::new();
    }
    let mut text = String::from(" (grid cells (row, column) ");
    let shown: Vec<String> = cells
        .iter()
        .take(SHOWN)
        .map(|(r, c)| format!("({r}, {c})"))
        .collect();
    text.push_str(&shown.join(", "));
    if cells.len() > SHOWN {
        text.push_str(&format!(" and {} more", cells.len() - SHOWN));
    }
    text.push(')');
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::DismechError;

    #[test]
    fn joined_into_dismech_error_with_the_same_message() {
        let e = HpmError::StrengthReductionNoFailure { factor: 8.0 };
        let joined = DismechError::from(e.clone());
        assert_eq!(joined.to_string(), e.to_string());
        assert_eq!(
            joined.to_string(),
            "strength reduction: equilibrium at every factor tried up to F = 8.0000e0; nothing drives this slide to failure (check the slip surface and the loads)"
        );
        assert!(matches!(
            joined,
            DismechError::Hpm(HpmError::StrengthReductionNoFailure { factor }) if factor == 8.0
        ));
    }
}
