//! The uniform cell grid.

use rayon::prelude::*;

use crate::math::Aabb2;

/// A uniform grid of square cells, rebuilt every step from the bodies'
/// bounding boxes: dense (every cell of the span stored) while the span
/// needs at most about 4 cells per body, sparse (only the occupied cells,
/// found by binary search) when the bodies spread wider, e.g. around a far
/// outlier.
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
    /// Their boxes, in the same order: a cell's run, and a row's run of
    /// neighbouring cells, is read from consecutive memory.
    sorted_boxes: Vec<Aabb2>,
    /// The cell of each body.
    body_cell: Vec<usize>,
    /// Scratch of the counting sort.
    fill: Vec<usize>,
    /// Whether the last layout is the sparse one.
    sparse: bool,
    /// The sparse grid's key of each body and its occupied cells, sorted.
    keys: Vec<(i64, i64)>,
    occupied: Vec<(i64, i64)>,
}

/// How many bodies one task of [`CellGrid::candidate_pairs_filtered`]
/// searches.
const PARALLEL_BODIES: usize = 512;

impl CellGrid {
    /// An empty grid.
    pub fn new() -> Self {
        Self::default()
    }

    /// Candidate pairs `(i, j)` with `i < j` whose bounding boxes (grown by
    /// `margin`) overlap, written into `pairs` (cleared first), sorted and
    /// each once.
    pub fn candidate_pairs(
        &mut self,
        boxes: &[Aabb2],
        margin: f64,
        pairs: &mut Vec<(usize, usize)>,
    ) {
        self.candidate_pairs_filtered(boxes, margin, |_, _| true, false, pairs);
    }

    /// The candidate pairs `(i, j)`, `i < j`, whose boxes (grown by
    /// `margin`) overlap and that `keep` accepts, written into `pairs`
    /// (cleared first), sorted and each once. Searched by ranges of `i`
    /// (on rayon's threads when `parallel`) and concatenated in order:
    /// the same list whatever the threads. (The partners are visited by
    /// ascending `i`, so sorting each `i`'s few partners sorts the list.)
    pub fn candidate_pairs_filtered(
        &mut self,
        boxes: &[Aabb2],
        margin: f64,
        keep: impl Fn(usize, usize) -> bool + Sync,
        parallel: bool,
        pairs: &mut Vec<(usize, usize)>,
    ) {
        pairs.clear();
        if !self.lay_out(boxes, margin) {
            return;
        }
        let grid = &*self;
        // The pairs of the bodies of one part, appended to `found`.
        let search = |part: usize, found: &mut Vec<(usize, usize)>| {
            let first = part * PARALLEL_BODIES;
            for i in first..(first + PARALLEL_BODIES).min(boxes.len()) {
                let start = found.len();
                let _: Result<(), std::convert::Infallible> =
                    grid.visit_partners(i, boxes, margin, &mut |i, j| {
                        if keep(i, j) {
                            found.push((i, j));
                        }
                        Ok(())
                    });
                found[start..].sort_unstable();
            }
        };
        let parts = boxes.len().div_ceil(PARALLEL_BODIES);
        if parallel {
            let found: Vec<Vec<(usize, usize)>> = (0..parts)
                .into_par_iter()
                // One part a task, so that the threads share out parts of
                // unequal work to the end.
                .with_max_len(1)
                .map(|part| {
                    let mut found = Vec::new();
                    search(part, &mut found);
                    found
                })
                .collect();
            pairs.reserve(found.iter().map(Vec::len).sum());
            for part in found {
                pairs.extend_from_slice(&part);
            }
        } else {
            for part in 0..parts {
                search(part, pairs);
            }
        }
        // A pair visited twice (far cells merged) is listed once.
        pairs.dedup();
    }

    /// Visit the candidate pairs `(i, j)`, `i < j`, whose boxes (grown by
    /// `margin`) overlap, without storing them, stopping at the first
    /// error `visit` returns (e.g. a check that refuses the first
    /// overlapping pair without building all pairs of a dense cluster).
    /// The order is deterministic, by ascending `i` (not by `j`), and a pair may be
    /// visited twice when far cells merge (see [`Self::candidate_pairs`]
    /// for the sorted list).
    ///
    /// # Errors
    /// The first error of `visit`.
    pub fn try_for_each_pair<E>(
        &mut self,
        boxes: &[Aabb2],
        margin: f64,
        mut visit: impl FnMut(usize, usize) -> Result<(), E>,
    ) -> Result<(), E> {
        if !self.lay_out(boxes, margin) {
            return Ok(());
        }
        for i in 0..boxes.len() {
            self.visit_partners(i, boxes, margin, &mut visit)?;
        }
        Ok(())
    }

    /// Sort the bodies into cells: a dense grid of at most about 4 cells
    /// per body, or, when the bodies spread wider than that (a far
    /// outlier), a sparse grid whose cost does not depend on the spread.
    /// `false` when there is nothing to pair (fewer than two bodies, or a
    /// box that is not finite).
    fn lay_out(&mut self, boxes: &[Aabb2], margin: f64) -> bool {
        let n = boxes.len();
        if n < 2 {
            return false;
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
            return false;
        }
        self.cell_size = (largest + 2.0 * margin).max(f64::MIN_POSITIVE);
        self.origin = min;
        let max_cells = (4 * n).max(16) as f64;
        let columns = ((max.0 - min.0) / self.cell_size).floor() + 1.0;
        let rows = ((max.1 - min.1) / self.cell_size).floor() + 1.0;
        // (Fewer than one column or row, or none at all, comes only of
        // boxes whose corners are swapped: the sparse grid takes them
        // without indexing an empty grid.)
        self.sparse = !(columns >= 1.0 && rows >= 1.0) || columns * rows > max_cells;
        if self.sparse {
            self.lay_out_sparse(boxes);
            return true;
        }
        self.columns = columns as usize;
        self.rows = rows as usize;
        let cells = self.columns * self.rows;
        // Counting sort of bodies by cell.
        self.body_cell.clear();
        self.cell_start.clear();
        self.cell_start.resize(cells + 1, 0);
        for b in boxes {
            let cell = self.cell_of(b);
            self.body_cell.push(cell);
            self.cell_start[cell + 1] += 1;
        }
        for c in 0..cells {
            self.cell_start[c + 1] += self.cell_start[c];
        }
        self.sorted.clear();
        self.sorted.resize(n, 0);
        let fill = &mut self.fill;
        fill.clear();
        fill.extend_from_slice(&self.cell_start);
        for (i, &cell) in self.body_cell.iter().enumerate() {
            self.sorted[fill[cell]] = i;
            fill[cell] += 1;
        }
        self.sort_boxes(boxes);
        true
    }

    /// The boxes in the order of `sorted`.
    fn sort_boxes(&mut self, boxes: &[Aabb2]) {
        self.sorted_boxes.clear();
        self.sorted_boxes
            .extend(self.sorted.iter().map(|&i| boxes[i]));
    }

    /// Visit body `i`'s partners `j > i` in its cell and the eight around
    /// it whose boxes overlap its box grown by `margin`.
    fn visit_partners<E>(
        &self,
        i: usize,
        boxes: &[Aabb2],
        margin: f64,
        visit: &mut impl FnMut(usize, usize) -> Result<(), E>,
    ) -> Result<(), E> {
        let grown = boxes[i].inflated(margin);
        if self.sparse {
            let (row, col) = self.keys[i];
            for dr in [-1i64, 0, 1] {
                for dc in [-1i64, 0, 1] {
                    let key = (row.saturating_add(dr), col.saturating_add(dc));
                    if (dr != 0 || dc != 0) && key == self.keys[i] {
                        continue; // saturated: the same cell again
                    }
                    let Ok(c) = self.occupied.binary_search(&key) else {
                        continue;
                    };
                    let run = self.cell_start[c]..self.cell_start[c + 1];
                    for (&j, other) in self.sorted[run.clone()].iter().zip(&self.sorted_boxes[run])
                    {
                        if j > i && grown.intersects(other) {
                            visit(i, j)?;
                        }
                    }
                }
            }
            return Ok(());
        }
        // The three rows of the cell and the eight around it; in each row
        // the three cells are consecutive in `sorted`, one run.
        let cell = self.body_cell[i];
        let (col, row) = (cell % self.columns, cell / self.columns);
        let (first_col, last_col) = (col.saturating_sub(1), (col + 1).min(self.columns - 1));
        for r in row.saturating_sub(1)..=(row + 1).min(self.rows - 1) {
            let run = self.cell_start[r * self.columns + first_col]
                ..self.cell_start[r * self.columns + last_col + 1];
            for (&j, other) in self.sorted[run.clone()].iter().zip(&self.sorted_boxes[run]) {
                if j > i && grown.intersects(other) {
                    visit(i, j)?;
                }
            }
        }
        Ok(())
    }

    /// The cell `(row, column)` of a box's centre, unbounded (saturating
    /// far away, which only merges far cells).
    fn cell_key(&self, b: &Aabb2) -> (i64, i64) {
        let cx = 0.5 * (b.min.x + b.max.x);
        let cy = 0.5 * (b.min.y + b.max.y);
        (
            ((cy - self.origin.1) / self.cell_size).floor() as i64,
            ((cx - self.origin.0) / self.cell_size).floor() as i64,
        )
    }

    /// The sparse grid: the bodies sorted by cell, and each body's
    /// neighbouring cells found by binary search among the occupied ones
    /// (`O(n log n)` however far apart the bodies are).
    fn lay_out_sparse(&mut self, boxes: &[Aabb2]) {
        let n = boxes.len();
        let keys: Vec<(i64, i64)> = boxes.iter().map(|b| self.cell_key(b)).collect();
        self.keys = keys;
        self.sorted.clear();
        self.sorted.extend(0..n);
        let keys = &self.keys;
        self.sorted.sort_by_key(|&i| (keys[i], i));
        // Occupied cells and where their bodies start in `sorted`.
        self.occupied.clear();
        self.cell_start.clear();
        for (k, &i) in self.sorted.iter().enumerate() {
            if self.occupied.last() != Some(&keys[i]) {
                self.occupied.push(keys[i]);
                self.cell_start.push(k);
            }
        }
        self.cell_start.push(n);
        self.sort_boxes(boxes);
        self.columns = 0;
        self.rows = 0;
        self.body_cell.clear();
    }

    /// The dense grid's cell of a box's centre (clamped to the grid): the
    /// quotient's `floor`, clamped, without the call. A non-negative
    /// quotient truncates as `floor` would; a negative one (a box whose
    /// corners are swapped) or NaN casts to 0, as `floor` and the clamp
    /// to the first cell gave; a far one saturates and is clamped.
    fn cell_of(&self, b: &Aabb2) -> usize {
        let cx = 0.5 * (b.min.x + b.max.x);
        let cy = 0.5 * (b.min.y + b.max.y);
        let row = (((cy - self.origin.1) / self.cell_size) as usize).min(self.rows - 1);
        let col = (((cx - self.origin.0) / self.cell_size) as usize).min(self.columns - 1);
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

        /// With bodies far apart (outliers up to 1e12 away) the sparse grid
        /// finds the same pairs as the brute force.
        #[test]
        fn cell_grid_with_far_outliers_finds_exactly_the_overlapping_pairs(
            centres in prop::collection::vec((-5.0f64..5.0, -5.0f64..5.0, 0.05f64..0.6), 2..60),
            outliers in prop::collection::vec((-1e12f64..1e12, -1e12f64..1e12), 1..4),
            margin in 0.0f64..0.2,
        ) {
            let mut boxes: Vec<Aabb2> = centres.iter().map(|&(x, y, h)| square(x, y, h)).collect();
            boxes.extend(outliers.iter().map(|&(x, y)| square(x, y, 0.3)));
            // and one twin of an outlier, touching it
            let (x, y) = outliers[0];
            boxes.push(square(x + 0.5, y, 0.3));
            let mut grid = CellGrid::new();
            let mut pairs = Vec::new();
            grid.candidate_pairs(&boxes, margin, &mut pairs);
            let mut brute = Vec::new();
            for i in 0..boxes.len() {
                for j in i + 1..boxes.len() {
                    if boxes[i].inflated(margin).intersects(&boxes[j]) {
                        brute.push((i, j));
                    }
                }
            }
            prop_assert_eq!(pairs, brute);
        }
    }

    proptest! {
        /// The filtered search, in tasks of 512 bodies on one thread or
        /// rayon's, gives the serial list filtered by `keep`, in the same
        /// order, dense or sparse.
        #[test]
        fn the_filtered_search_gives_the_serial_list_filtered(
            centres in prop::collection::vec((-30.0f64..30.0, -30.0f64..30.0, 0.05f64..0.8), 2..1500),
            outlier in prop::option::of((-1e12f64..1e12, -1e12f64..1e12)),
            margin in 0.0f64..0.2,
            modulus in 1usize..4,
        ) {
            let mut boxes: Vec<Aabb2> = centres.iter().map(|&(x, y, h)| square(x, y, h)).collect();
            if let Some((x, y)) = outlier {
                boxes.push(square(x, y, 0.3));
                boxes.push(square(x + 0.5, y, 0.3));
            }
            let mut grid = CellGrid::new();
            let mut serial = Vec::new();
            grid.candidate_pairs(&boxes, margin, &mut serial);
            serial.retain(|&(i, j)| (i + j) % modulus == 0);
            for parallel in [false, true] {
                let mut filtered = Vec::new();
                grid.candidate_pairs_filtered(&boxes, margin, |i, j| (i + j) % modulus == 0, parallel, &mut filtered);
                prop_assert_eq!(&filtered, &serial);
            }
        }
    }

    /// Boxes whose corners are swapped (min beyond max) in x, in y or in
    /// both, so that the span has less than one column or row, are taken
    /// without a panic; grids one column wide and one row high find the
    /// brute force's pairs.
    #[test]
    fn swapped_boxes_and_one_column_or_row_grids_are_taken() {
        let swapped = |x: f64, y: f64, flip_x: bool, flip_y: bool| {
            let b = square(x, y, 0.4);
            Aabb2 {
                min: Point::new(
                    if flip_x { b.max.x } else { b.min.x },
                    if flip_y { b.max.y } else { b.min.y },
                ),
                max: Point::new(
                    if flip_x { b.min.x } else { b.max.x },
                    if flip_y { b.min.y } else { b.max.y },
                ),
            }
        };
        let mut grid = CellGrid::new();
        let mut pairs = Vec::new();
        for (flip_x, flip_y) in [(true, false), (false, true), (true, true)] {
            let boxes: Vec<Aabb2> = (0..5)
                .map(|k| swapped(k as f64, 0.5 * k as f64, flip_x, flip_y))
                .collect();
            grid.candidate_pairs(&boxes, 0.0, &mut pairs);
        }
        for line in [
            (0..30)
                .map(|k| square(0.0, 0.7 * k as f64, 0.4))
                .collect::<Vec<_>>(),
            (0..30).map(|k| square(0.7 * k as f64, 0.0, 0.4)).collect(),
        ] {
            grid.candidate_pairs(&line, 0.0, &mut pairs);
            let brute: Vec<(usize, usize)> = (0..line.len())
                .flat_map(|i| (i + 1..line.len()).map(move |j| (i, j)))
                .filter(|&(i, j)| line[i].intersects(&line[j]))
                .collect();
            assert_eq!(pairs, brute);
            assert_eq!(pairs.len(), 29);
        }
    }

    /// One body a kilometre away does not coarsen the grid: its neighbours
    /// are still tested cell by cell (the sparse grid holds one cell per
    /// occupied cell, not the whole span).
    #[test]
    fn a_far_outlier_does_not_coarsen_the_grid() {
        let mut boxes: Vec<Aabb2> = (0..400)
            .map(|k| square((k % 20) as f64, (k / 20) as f64, 0.4))
            .collect();
        boxes.push(square(1e3, 1e3, 0.4));
        let mut grid = CellGrid::new();
        let mut pairs = Vec::new();
        grid.candidate_pairs(&boxes, 0.0, &mut pairs);
        assert!(pairs.is_empty());
        assert!(
            (grid.cell_size - 0.8).abs() < 1e-12,
            "cell size {}",
            grid.cell_size
        );
        assert_eq!(grid.cell_start.len(), boxes.len() + 1);
    }
}
