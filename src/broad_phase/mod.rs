//! Broad phase: candidate pairs from a uniform cell grid, in O(N).
//!
//! Bodies are binned by the cell of their bounding-box centre; a pair is a
//! candidate when the two boxes overlap and the bodies sit in the same or in
//! neighbouring cells. With the cell size at least the largest bounding-box
//! extent, no overlapping pair is missed. The grid keeps its buffers between
//! steps, so a step allocates nothing once the buffers have grown.

mod cell_grid;

pub use cell_grid::CellGrid;
