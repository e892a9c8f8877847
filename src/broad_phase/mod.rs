//! Broad phase: candidate pairs from cell grids, in O(N) for any mix of
//! sizes.
//!
//! Bodies are binned by the cell of their bounding-box centre; a pair is a
//! candidate when the two boxes overlap and the bodies sit in the same or in
//! neighbouring cells. With the cell size at least the largest bounding-box
//! extent, no overlapping pair is missed. That is one uniform grid while
//! the bodies' extents are within a factor 2 of each other. A wide size
//! distribution, the rule in geomaterials, would make the cell the
//! largest body's and pile thousands of small bodies into each cell, whose
//! tests grow as the square of that pile (one 5 m boulder among 160 000
//! grains of 13 cm multiplied the cost of the grid by a hundred): the
//! bodies are then binned by size level, one grid per level with a cell
//! fitted to its bodies, and each body searched for in every level's cells
//! near it (the multilevel grids of LIGGGHTS' neighbour lists, the
//! hierarchical grid of collision detection). The pairs found, and their
//! order, are the same either way: each pair once, sorted. The grids keep
//! their buffers between steps, so a step allocates nothing once the
//! buffers have grown.

mod cell_grid;

pub use cell_grid::CellGrid;
