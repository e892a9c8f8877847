//! Why a strength layer of a slope's ground cannot be used
//! ([`SlopeError::InvalidLayer`](super::SlopeError::InvalidLayer)).

use crate::error::DismechError;

/// Why a strength layer cannot be used; its Display is the message's text.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LayerProblem {
    /// No layer at all.
    #[error("no layer given: the ground needs at least one")]
    NoLayer,
    /// The layer's material is refused ([`super::SlopeMaterial::validate`]).
    #[error("{0}")]
    Material(Box<DismechError>),
    /// The layer's bottom raster is not on the DEM's grid
    /// ([`crate::grid::GridError::Mismatch`]).
    #[error("{0}")]
    BottomOffGrid(Box<DismechError>),
    /// A layer other than the last without a bottom raster.
    #[error(
        "layer {index} of {count} has no bottom raster: only the last layer is unbounded below"
    )]
    NoBottom {
        /// The layer's place, from 1 at the top.
        index: usize,
        /// The number of layers.
        count: usize,
    },
    /// The last layer with a bottom raster.
    #[error("the last layer has a bottom raster ({bottom}): the last layer is unbounded below; add a layer under it")]
    LastHasBottom {
        /// The bottom raster's name.
        bottom: String,
    },
}
