//! What in an HPM model spoils the accuracy of its solves, named with what
//! to change.
//!
//! The stiffness of eq. (4) mixes the elements' own stiffness (∝ E V) with
//! penalty springs (∝ p E A / h) and slip springs whose normal stiffness
//! grows as `1 / (1 − 2ν)`. Three features make it ill-conditioned, so
//! that a solve in double precision leaves an out-of-balance force well
//! above rounding, or a factorization fails:
//!
//! | feature | flagged when | measured (slab of 5 × 4 cells of 10 m, 6 m thick, dipping 22°) |
//! |---|---|---|
//! | ν → 0.5 | `1 − 2ν <` [`INCOMPRESSIBLE_MARGIN`] | relative residual ≈ 8·10⁻¹⁴ / (1 − 2ν): 4·10⁻⁹ at ν = 0.49999, 3.6·10⁻⁴ at ν = 0.4999999999 |
//! | slip surface within ε of the ground | mean column thickness `<` [`THIN_COLUMN_RATIO`] × cell size | 1.2·10⁻⁹ at 10⁻⁴, 1.3·10⁻⁸ at 10⁻⁵; at 10⁻⁶ the Cholesky factorization fails |
//! | large penalty factor p | `p >` [`STIFF_PENALTY`] | ≈ 5·10⁻¹⁵ p: 5·10⁻⁹ at p = 10⁶, 5·10⁻³ at p = 10¹² |
//!
//! The thresholds sit where the residual is still two or more orders below
//! the equilibrium tolerance ([`super::EQUILIBRIUM_TOLERANCE`]), so that a
//! solve that misses it because of one of them finds it named.

use super::model::HpmModel;

/// `1 − 2ν` below which ν is flagged as nearly incompressible (ν > 0.49995).
pub const INCOMPRESSIBLE_MARGIN: f64 = 1e-4;

/// Mean thickness of a column over its cell size below which the column is
/// flagged as thin.
pub const THIN_COLUMN_RATIO: f64 = 1e-4;

/// Penalty factor p (eq. 17) above which the springs between elements are
/// flagged as too stiff.
pub const STIFF_PENALTY: f64 = 1e6;

/// A feature of an HPM model that makes its stiffness ill-conditioned; its
/// message says what to change.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum IllConditioning {
    /// Poisson's ratio close to 0.5: the normal stiffness
    /// `(1 − ν) / ((1 + ν)(1 − 2ν))` grows without bound.
    NearlyIncompressible {
        /// ν.
        poisson_ratio: f64,
    },
    /// The thinnest column: the slip surface lies within a small fraction
    /// of the cell size of the ground, so its elements are far softer than
    /// the springs around them.
    ThinColumn {
        /// Grid row and column of the cell.
        cell: (usize, usize),
        /// Mean thickness of the column (m).
        thickness: f64,
        /// Cell size (m).
        cell_size: f64,
    },
    /// A penalty factor p so large that the springs between elements dwarf
    /// the elements' own stiffness.
    StiffPenalty {
        /// p.
        penalty: f64,
    },
}

impl std::fmt::Display for IllConditioning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::NearlyIncompressible { poisson_ratio } => write!(
                f,
                "Poisson's ratio nu = {poisson_ratio} is within {:.1e} of 0.5 and the normal stiffness grows as 1/(1 - 2 nu): use nu <= {}",
                0.5 - poisson_ratio,
                0.5 * (1.0 - INCOMPRESSIBLE_MARGIN)
            ),
            Self::ThinColumn {
                cell,
                thickness,
                cell_size,
            } => write!(
                f,
                "the slip surface lies within {thickness:.3e} m of the ground in grid row {}, column {} ({:.1e} of the {cell_size} m cell): lower the slip surface or raise the ground there to at least {:.1e} m, or leave the cell out of the slide",
                cell.0,
                cell.1,
                thickness / cell_size,
                THIN_COLUMN_RATIO * cell_size
            ),
            Self::StiffPenalty { penalty } => write!(
                f,
                "the penalty factor p = {penalty:e} makes the springs between elements far stiffer than the elements: use p <= {STIFF_PENALTY:e} (the paper's p = 100 suffices)"
            ),
        }
    }
}

impl HpmModel {
    /// The features of this model that make its stiffness ill-conditioned
    /// (see the thresholds in the module documentation); empty for a
    /// well-conditioned model. A thin column is reported once, the thinnest.
    pub fn ill_conditioning(&self) -> Vec<IllConditioning> {
        let mut found = Vec::new();
        let nu = self.material.poisson_ratio;
        if 1.0 - 2.0 * nu < INCOMPRESSIBLE_MARGIN {
            found.push(IllConditioning::NearlyIncompressible { poisson_ratio: nu });
        }
        let cell_size = self.grid.2;
        let thinnest = self
            .columns
            .iter()
            .map(|c| (c.cell, c.shape.volume() / (cell_size * cell_size)))
            .min_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((cell, thickness)) = thinnest {
            if thickness < THIN_COLUMN_RATIO * cell_size {
                found.push(IllConditioning::ThinColumn {
                    cell,
                    thickness,
                    cell_size,
                });
            }
        }
        if self.settings.penalty > STIFF_PENALTY {
            found.push(IllConditioning::StiffPenalty {
                penalty: self.settings.penalty,
            });
        }
        found
    }
}
