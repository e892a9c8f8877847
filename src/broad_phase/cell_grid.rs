//! The uniform cell grid.

use crate::math::Aabb2;

/// A uniform grid of square cells, rebuilt every step from the bodies'
/// bounding boxes.
#[derive(Debug, Clone, Default)]
pub struct CellGrid {
    cell_size: f64,
    origin: (f64, f64),
    columns: usize,
    rows: usize,
    /// Start of each cell's run in `sorted` (length cells + 1).
    cell_start: Vec<usize>,
    /// Body indices sorted by cell.
    sorted: Vec<usize>,
    /// The cell of each body.
    body_cell: Vec<usize>,
}

impl CellGrid {
    /// An empty grid.
    pub fn new() -> Self {
        Self::default()
    }

    /// Candidate pairs `(i, j)` with `i < j` whose bounding boxes (grown by
    /// `margin`) overlap, written into `pairs` (cleared first), in a
    /// deterministic order.
    pub fn candidate_pairs(
        &mut self,
        boxes: &[Aabb2],
        margin: f64,
        pairs: &mut Vec<(usize, usize)>,
    ) {
        pairs.clear();
        let n = boxes.len();
        if n < 2 {
            return;
        }
        let mut min = (f64::INFINITY, f64::INFINITY);
        let mut max = (f64::NEG_INFINITY, f64::NEG_INFINITY);
        let mut largest = 0.0f64;
        for b in boxes {
            min = (min.0.min(b.min.x), min.1.min(b.min.y));
            max = (max.0.max(b.max.x), max.1.max(b.max.y));
            largest = largest.max(b.max.x - b.min.x).max(b.max.y - b.min.y);
        }
        if !(min.0.is_finite() && min.1.is_finite() && max.0.is_finite() && max.1.is_finite()) {
            return;
        }
        self.cell_size = (largest + 2.0 * margin).max(f64::MIN_POSITIVE);
        self.origin = min;
        // Cap the grid at about 4 cells per body so a far outlier cannot
        // make it huge; a coarser grid is still correct, only slower.
        let max_cells = (4 * n).max(16) as f64;
        let mut columns = ((max.0 - min.0) / self.cell_size).floor() + 1.0;
        let mut rows = ((max.1 - min.1) / self.cell_size).floor() + 1.0;
        while columns * rows > max_cells {
            self.cell_size *= 2.0;
            columns = ((max.0 - min.0) / self.cell_size).floor() + 1.0;
            rows = ((max.1 - min.1) / self.cell_size).floor() + 1.0;
        }
        self.columns = columns as usize;
        self.rows = rows as usize;
        let cells = self.columns * self.rows;

        // Counting sort of bodies by cell.
        self.body_cell.clear();
        self.cell_start.clear();
        self.cell_start.resize(cells + 1, 0);
        for b in boxes {
            let cx = 0.5 * (b.min.x + b.max.x);
            let cy = 0.5 * (b.min.y + b.max.y);
            let cell = self.cell_of(cx, cy);
            self.body_cell.push(cell);
            self.cell_start[cell + 1] += 1;
        }
        for c in 0..cells {
            self.cell_start[c + 1] += self.cell_start[c];
        }
        self.sorted.clear();
        self.sorted.resize(n, 0);
        let mut fill = self.cell_start.clone();
        for (i, &cell) in self.body_cell.iter().enumerate() {
            self.sorted[fill[cell]] = i;
            fill[cell] += 1;
        }

        for i in 0..n {
            let cell = self.body_cell[i];
            let (col, row) = (cell % self.columns, cell / self.columns);
            let grown = boxes[i].inflated(margin);
            for dr in [-1i64, 0, 1] {
                for dc in [-1i64, 0, 1] {
                    let (r, c) = (row as i64 + dr, col as i64 + dc);
                    if r < 0 || c < 0 || r >= self.rows as i64 || c >= self.columns as i64 {
                        continue;
                    }
                    let other = r as usize * self.columns + c as usize;
                    for &j in &self.sorted[self.cell_start[other]..self.cell_start[other + 1]] {
                        if j > i && grown.intersects(&boxes[j]) {
                            pairs.push((i, j));
                        }
                    }
                }
            }
        }
        pairs.sort_unstable();
    }

    fn cell_of(&self, x: f64, y: f64) -> usize {
        let col = (((x - self.origin.0) / self.cell_size).floor().max(0.0) as usize)
            .min(self.columns - 1);
        let row =
            (((y - self.origin.1) / self.cell_size).floor().max(0.0) as usize).min(self.rows - 1);
        row * self.columns + col
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Point;
    use proptest::prelude::*;

    fn square(x: f64, y: f64, h: f64) -> Aabb2 {
        Aabb2 {
            min: Point::new(x - h, y - h),
            max: Point::new(x + h, y + h),
        }
    }

    proptest! {
        #[test]
        fn cell_grid_finds_exactly_the_overlapping_pairs(
            centres in prop::collection::vec((-5.0f64..5.0, -5.0f64..5.0, 0.05f64..0.6), 2..80)
        ) {
            let boxes: Vec<Aabb2> = centres.iter().map(|&(x, y, h)| square(x, y, h)).collect();
            let mut grid = CellGrid::new();
            let mut pairs = Vec::new();
            grid.candidate_pairs(&boxes, 0.0, &mut pairs);
            let mut brute = Vec::new();
            for i in 0..boxes.len() {
                for j in i + 1..boxes.len() {
                    if boxes[i].intersects(&boxes[j]) {
                        brute.push((i, j));
                    }
                }
            }
            prop_assert_eq!(pairs, brute);
        }
    }
}
