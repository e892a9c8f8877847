//! The cell grids: one uniform grid when the bodies' sizes are alike, a
//! grid per size level when they are not.

use rayon::prelude::*;

use crate::math::Aabb2;

/// The broad phase's cell grids, rebuilt every step from the bodies'
/// bounding boxes.
///
/// When every body's extent (the larger side of its box, plus twice the
/// margin) lies within a factor 2 of the largest, the bodies share one
/// uniform grid whose cell is the largest extent: each body meets its
/// partners in its cell and the eight around it. Otherwise (a wide size
/// distribution: one boulder among fine grains) one grid's cell would be
/// the boulder's and hold thousands of grains, each tested against all
/// the others of its nine cells (a cost that grows as the square of the
/// grains a cell holds); the bodies are then binned by size level
/// instead, level `k` holding the extents in `(e/2^(k+1), e/2^k]` (`e` the
/// largest), each level a grid of its own whose cell is its own largest
/// extent (the multilevel grids of LIGGGHTS' neighbour lists, the
/// hierarchical grid of collision detection). A body meets its partners of
/// every level in the cells of that level that its box, grown by one cell,
/// covers: a few cells of a level of larger bodies, the cells under its
/// box in a level of smaller ones. Each pair is found once, from its lower
/// index, so the list is the same set, in the same order, as one grid's.
///
/// Each grid is dense (every cell of its span stored) while the span needs
/// at most about 4 cells per body, sparse (only the occupied cells, found
/// by binary search) when its bodies spread wider, e.g. around a far
/// outlier.
#[derive(Debug, Clone, Default)]
pub struct CellGrid {
    /// The one grid of bodies of alike sizes.
    single: Level,
    /// Whether the last layout is the grids of several size levels.
    multilevel: bool,
    /// The grids of the size levels (those of the last layout first; empty
    /// ones are kept for their buffers).
    levels: Vec<Level>,
    /// How many levels the last layout has.
    level_count: usize,
    /// The bodies of each level (scratch of the layout).
    members: Vec<Vec<usize>>,
}

/// The most size levels; smaller bodies share the last one (correct, only
/// less selective).
const MAX_LEVELS: usize = 16;

/// One uniform grid of square cells over some of the bodies (all of them,
/// or those of one size level).
#[derive(Debug, Clone, Default)]
struct Level {
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
    /// The cell of each body (of the grid of all bodies; of each member in
    /// the members' order for a level).
    body_cell: Vec<usize>,
    /// Scratch of the counting sort.
    fill: Vec<usize>,
    /// Whether the last layout is the sparse one.
    sparse: bool,
    /// The sparse grid's key of each body (as `body_cell`) and its
    /// occupied cells, sorted.
    keys: Vec<(i64, i64)>,
    occupied: Vec<(i64, i64)>,
    /// Scratch of the parallel layout: `(cell << 32) | body`, sorted.
    packed: Vec<u64>,
}

/// The span of a set of boxes and the extremes of their larger sides.
#[derive(Debug, Clone, Copy)]
struct Bounds {
    min: (f64, f64),
    max: (f64, f64),
    largest: f64,
    smallest: f64,
}

impl Bounds {
    fn empty() -> Self {
        Self {
            min: (f64::INFINITY, f64::INFINITY),
            max: (f64::NEG_INFINITY, f64::NEG_INFINITY),
            largest: 0.0,
            smallest: f64::INFINITY,
        }
    }

    fn with(self, b: &Aabb2) -> Self {
        let side = (b.max.x - b.min.x).max(b.max.y - b.min.y);
        Self {
            min: (self.min.0.min(b.min.x), self.min.1.min(b.min.y)),
            max: (self.max.0.max(b.max.x), self.max.1.max(b.max.y)),
            largest: self.largest.max(side),
            smallest: self.smallest.min(side),
        }
    }

    fn merged(self, other: Self) -> Self {
        Self {
            min: (self.min.0.min(other.min.0), self.min.1.min(other.min.1)),
            max: (self.max.0.max(other.max.0), self.max.1.max(other.max.1)),
            largest: self.largest.max(other.largest),
            smallest: self.smallest.min(other.smallest),
        }
    }
}

/// The columns and rows of a dense grid of cells of `cell_size` over the
/// span `min`–`max` of `n` bodies, or `None` where the grid would be sparse:
/// more than about 4 cells per body, or fewer than one column or row (which
/// comes only of boxes whose corners are swapped: the sparse grid takes
/// them without indexing an empty grid).
fn dense_shape(n: usize, cell_size: f64, min: (f64, f64), max: (f64, f64)) -> Option<(f64, f64)> {
    let max_cells = (4 * n).max(16) as f64;
    let columns = ((max.0 - min.0) / cell_size).floor() + 1.0;
    let rows = ((max.1 - min.1) / cell_size).floor() + 1.0;
    (columns >= 1.0 && rows >= 1.0 && columns * rows <= max_cells).then_some((columns, rows))
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
        if !self.lay_out(boxes, margin, parallel) {
            return;
        }
        let grid = &*self;
        // The pairs of the bodies of one part, appended to `found`; a pair
        // visited twice (far cells merged) is listed once (all of a
        // body's pairs are found from it, so the twice-found pairs of
        // each body lie side by side once its few partners are sorted).
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
                let mut kept = start;
                for k in start..found.len() {
                    if kept == start || found[k] != found[kept - 1] {
                        found[kept] = found[k];
                        kept += 1;
                    }
                }
                found.truncate(kept);
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
            // Concatenated on the threads: each part copied into its own
            // stretch of `pairs`.
            pairs.resize(found.iter().map(Vec::len).sum(), (0, 0));
            let mut stretches = Vec::with_capacity(found.len());
            let mut rest = pairs.as_mut_slice();
            for part in &found {
                let (stretch, tail) = rest.split_at_mut(part.len());
                stretches.push(stretch);
                rest = tail;
            }
            stretches
                .into_par_iter()
                .zip(found.par_iter())
                .for_each(|(stretch, part)| stretch.copy_from_slice(part));
        } else {
            for part in 0..parts {
                search(part, pairs);
            }
        }
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
        if !self.lay_out(boxes, margin, false) {
            return Ok(());
        }
        for i in 0..boxes.len() {
            self.visit_partners(i, boxes, margin, &mut visit)?;
        }
        Ok(())
    }

    /// Whether the last layout binned the bodies by size level (sizes
    /// spread over more than a factor 2).
    pub fn is_multilevel(&self) -> bool {
        self.multilevel
    }

    /// Sort the bodies into cells: one grid when their extents are within
    /// a factor 2 of the largest (or a box has its corners swapped), else
    /// a grid per size level (see [`CellGrid`]). `false` when there is
    /// nothing to pair (fewer than two bodies, or a box that is not
    /// finite). The one grid is laid out on rayon's threads when
    /// `parallel`, to the same layout.
    fn lay_out(&mut self, boxes: &[Aabb2], margin: f64, parallel: bool) -> bool {
        let n = boxes.len();
        if n < 2 {
            return false;
        }
        // The span of the boxes and the extremes of their sides (minima
        // and maxima, the same in any order).
        let bounds = if parallel {
            boxes
                .par_iter()
                .fold(Bounds::empty, Bounds::with)
                .reduce(Bounds::empty, Bounds::merged)
        } else {
            boxes.iter().fold(Bounds::empty(), Bounds::with)
        };
        let Bounds {
            min,
            max,
            largest,
            smallest,
        } = bounds;
        if !(min.0.is_finite() && min.1.is_finite() && max.0.is_finite() && max.1.is_finite()) {
            return false;
        }
        let cell_size = (largest + 2.0 * margin).max(f64::MIN_POSITIVE);
        // (A box with swapped corners has a negative side: it takes the
        // one grid, as it always has.)
        self.multilevel = smallest >= 0.0 && smallest + 2.0 * margin <= 0.5 * cell_size;
        if !self.multilevel {
            if parallel {
                self.single.lay_out_parallel(boxes, cell_size, min, max);
            } else {
                self.single.lay_out(boxes, None, cell_size, min, max);
            }
            return true;
        }
        // Each body's level: extents in (e/2^(k+1), e/2^k] at level k.
        self.members.resize_with(MAX_LEVELS, Vec::new);
        for members in &mut self.members {
            members.clear();
        }
        let mut count = 1;
        for (i, b) in boxes.iter().enumerate() {
            let extent = (b.max.x - b.min.x).max(b.max.y - b.min.y) + 2.0 * margin;
            let (mut level, mut bound) = (0, 0.5 * cell_size);
            while level + 1 < MAX_LEVELS && extent <= bound {
                level += 1;
                bound *= 0.5;
            }
            self.members[level].push(i);
            count = count.max(level + 1);
        }
        self.level_count = count;
        if self.levels.len() < count {
            self.levels.resize_with(count, Level::default);
        }
        for (level, members) in self.levels.iter_mut().zip(&self.members).take(count) {
            level.lay_out_members(boxes, members, margin);
        }
        true
    }

    /// Visit body `i`'s partners `j > i` whose boxes overlap its box grown
    /// by `margin`: in its cell and the eight around it of the one grid,
    /// or in the cells of each level's grid that its grown box, grown by
    /// one more cell, covers.
    fn visit_partners<E>(
        &self,
        i: usize,
        boxes: &[Aabb2],
        margin: f64,
        visit: &mut impl FnMut(usize, usize) -> Result<(), E>,
    ) -> Result<(), E> {
        if !self.multilevel {
            return self.single.visit_partners(i, boxes, margin, visit);
        }
        let grown = boxes[i].inflated(margin);
        for level in &self.levels[..self.level_count] {
            level.visit_near(i, &grown, visit)?;
        }
        Ok(())
    }
}

impl Level {
    /// Lay out the bodies `members` (all of them when `None`), whose boxes
    /// span `min` to `max`, in cells of `cell_size`: a dense grid of at
    /// most about 4 cells per body, or, when the bodies spread wider than
    /// that (a far outlier), a sparse grid whose cost does not depend on
    /// the spread.
    fn lay_out(
        &mut self,
        boxes: &[Aabb2],
        members: Option<&[usize]>,
        cell_size: f64,
        min: (f64, f64),
        max: (f64, f64),
    ) {
        let n = members.map_or(boxes.len(), <[usize]>::len);
        self.cell_size = cell_size;
        self.origin = min;
        let shape = dense_shape(n, cell_size, min, max);
        self.sparse = shape.is_none();
        let Some((columns, rows)) = shape else {
            self.lay_out_sparse(boxes, members);
            return;
        };
        self.columns = columns as usize;
        self.rows = rows as usize;
        let cells = self.columns * self.rows;
        // Counting sort of bodies by cell.
        self.body_cell.clear();
        self.cell_start.clear();
        self.cell_start.resize(cells + 1, 0);
        let mut count = |b: &Aabb2| {
            let cell = self.cell_of(b);
            self.body_cell.push(cell);
            self.cell_start[cell + 1] += 1;
        };
        match members {
            None => boxes.iter().for_each(&mut count),
            Some(members) => members.iter().for_each(|&i| count(&boxes[i])),
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
        if let Some(members) = members {
            self.sorted.iter_mut().for_each(|k| *k = members[*k]);
        }
        self.sort_boxes(boxes);
    }

    /// [`Self::lay_out`] of all the bodies on rayon's threads, to the same
    /// layout: the bodies sorted by `(cell, index)` (the counting sort's
    /// order) in one parallel sort of the two packed in a `u64`, and each
    /// cell's start found in the sorted keys. A grid too large for the
    /// packing, or a sparse one, is laid out by [`Self::lay_out`].
    fn lay_out_parallel(
        &mut self,
        boxes: &[Aabb2],
        cell_size: f64,
        min: (f64, f64),
        max: (f64, f64),
    ) {
        let n = boxes.len();
        let (columns, rows) = match dense_shape(n, cell_size, min, max) {
            Some((columns, rows)) if n < 1 << 32 && columns * rows < 4_294_967_296.0 => {
                (columns, rows)
            }
            _ => {
                self.lay_out(boxes, None, cell_size, min, max);
                return;
            }
        };
        self.sparse = false;
        self.cell_size = cell_size;
        self.origin = min;
        self.columns = columns as usize;
        self.rows = rows as usize;
        let cells = self.columns * self.rows;
        let mut keys = std::mem::take(&mut self.packed);
        keys.clear();
        let grid = &*self;
        keys.par_extend(
            boxes
                .par_iter()
                .enumerate()
                .map(|(i, b)| ((grid.cell_of(b) as u64) << 32) | i as u64),
        );
        self.body_cell.clear();
        self.body_cell
            .par_extend(keys.par_iter().map(|key| (key >> 32) as usize));
        keys.par_sort_unstable();
        self.sorted.clear();
        self.sorted
            .par_extend(keys.par_iter().map(|key| (key & 0xffff_ffff) as usize));
        self.cell_start.clear();
        self.cell_start.par_extend(
            (0..=cells)
                .into_par_iter()
                .map(|c| keys.partition_point(|key| key >> 32 < c as u64)),
        );
        self.sorted_boxes.clear();
        let sorted = &self.sorted;
        self.sorted_boxes
            .par_extend(sorted.par_iter().map(|&i| boxes[i]));
        self.packed = keys;
    }

    /// Lay out the bodies of one size level (indices ascending), in cells
    /// of their own largest extent.
    fn lay_out_members(&mut self, boxes: &[Aabb2], members: &[usize], margin: f64) {
        if members.is_empty() {
            self.sorted.clear();
            self.sorted_boxes.clear();
            return;
        }
        let mut min = (f64::INFINITY, f64::INFINITY);
        let mut max = (f64::NEG_INFINITY, f64::NEG_INFINITY);
        let mut largest = 0.0f64;
        for &i in members {
            let b = &boxes[i];
            min = (min.0.min(b.min.x), min.1.min(b.min.y));
            max = (max.0.max(b.max.x), max.1.max(b.max.y));
            largest = largest.max(b.max.x - b.min.x).max(b.max.y - b.min.y);
        }
        let cell_size = (largest + 2.0 * margin).max(f64::MIN_POSITIVE);
        self.lay_out(boxes, Some(members), cell_size, min, max);
    }

    /// The boxes in the order of `sorted`.
    fn sort_boxes(&mut self, boxes: &[Aabb2]) {
        self.sorted_boxes.clear();
        self.sorted_boxes
            .extend(self.sorted.iter().map(|&i| boxes[i]));
    }

    /// Visit body `i`'s partners `j > i` in its cell and the eight around
    /// it whose boxes overlap its box grown by `margin` (the grid of all
    /// bodies).
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
                    self.visit_cells(i, &grown, c..c + 1, visit)?;
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
            self.visit_cells(
                i,
                &grown,
                r * self.columns + first_col..r * self.columns + last_col + 1,
                visit,
            )?;
        }
        Ok(())
    }

    /// Visit the bodies `j > i` of the consecutive cells `cells` (of the
    /// dense grid, or occupied cells of the sparse one) whose boxes
    /// overlap `grown`.
    #[inline]
    fn visit_cells<E>(
        &self,
        i: usize,
        grown: &Aabb2,
        cells: std::ops::Range<usize>,
        visit: &mut impl FnMut(usize, usize) -> Result<(), E>,
    ) -> Result<(), E> {
        let run = self.cell_start[cells.start]..self.cell_start[cells.end];
        for (&j, other) in self.sorted[run.clone()].iter().zip(&self.sorted_boxes[run]) {
            if j > i && grown.intersects(other) {
                visit(i, j)?;
            }
        }
        Ok(())
    }

    /// Visit the bodies `j > i` of this grid whose boxes overlap `grown`
    /// (body `i`'s box grown by the margin; `i` need not be in the grid):
    /// those of the cells that `grown`, grown by one more cell, covers. A
    /// body whose box meets `grown` has its centre within half its extent,
    /// at most half a cell, of `grown`; the other half cell keeps the
    /// rounding of the cells' indices. When `grown` is no wider than a
    /// cell, the cells within one of its centre's hold them all.
    fn visit_near<E>(
        &self,
        i: usize,
        grown: &Aabb2,
        visit: &mut impl FnMut(usize, usize) -> Result<(), E>,
    ) -> Result<(), E> {
        if self.sorted.is_empty() {
            return Ok(());
        }
        let index = |x: f64, origin: f64| ((x - origin) / self.cell_size).floor();
        // A body no larger than the cells (grown by the margin) meets only
        // bodies whose centres are within a cell of its own: the cell of
        // its centre and the eight around it, as in the one grid.
        let ((low_x, high_x), (low_y, high_y)) =
            if (grown.max.x - grown.min.x).max(grown.max.y - grown.min.y) <= self.cell_size {
                let centre = (
                    0.5 * (grown.min.x + grown.max.x),
                    0.5 * (grown.min.y + grown.max.y),
                );
                ((centre.0, centre.0), (centre.1, centre.1))
            } else {
                ((grown.min.x, grown.max.x), (grown.min.y, grown.max.y))
            };
        let (first_col, last_col) = (
            index(low_x, self.origin.0) - 1.0,
            index(high_x, self.origin.0) + 1.0,
        );
        let (first_row, last_row) = (
            index(low_y, self.origin.1) - 1.0,
            index(high_y, self.origin.1) + 1.0,
        );
        if !self.sparse {
            let (max_col, max_row) = ((self.columns - 1) as f64, (self.rows - 1) as f64);
            if last_col < 0.0 || last_row < 0.0 || first_col > max_col || first_row > max_row {
                return Ok(());
            }
            let (first_col, last_col) =
                (first_col.max(0.0) as usize, last_col.min(max_col) as usize);
            let (first_row, last_row) =
                (first_row.max(0.0) as usize, last_row.min(max_row) as usize);
            for r in first_row..=last_row {
                self.visit_cells(
                    i,
                    grown,
                    r * self.columns + first_col..r * self.columns + last_col + 1,
                    visit,
                )?;
            }
            return Ok(());
        }
        // The sparse grid's keys (saturating, as the bodies' are).
        let (first_col, last_col) = (first_col as i64, last_col as i64);
        let (first_row, last_row) = (first_row as i64, last_row as i64);
        let within = |&(r, c): &(i64, i64)| {
            (first_row..=last_row).contains(&r) && (first_col..=last_col).contains(&c)
        };
        let spanned = i128::from(last_row) - i128::from(first_row) + 1;
        if spanned > self.occupied.len() as i128 {
            // Fewer occupied cells than rows to search: each one once.
            for (c, _) in self.occupied.iter().enumerate().filter(|(_, k)| within(k)) {
                self.visit_cells(i, grown, c..c + 1, visit)?;
            }
            return Ok(());
        }
        for r in first_row..=last_row {
            let start = self.occupied.partition_point(|&k| k < (r, first_col));
            let end = start + self.occupied[start..].partition_point(|&k| k <= (r, last_col));
            self.visit_cells(i, grown, start..end, visit)?;
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
    fn lay_out_sparse(&mut self, boxes: &[Aabb2], members: Option<&[usize]>) {
        let keys: Vec<(i64, i64)> = match members {
            None => boxes.iter().map(|b| self.cell_key(b)).collect(),
            Some(members) => members.iter().map(|&i| self.cell_key(&boxes[i])).collect(),
        };
        let n = keys.len();
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
        if let Some(members) = members {
            self.sorted.iter_mut().for_each(|k| *k = members[*k]);
        }
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
            (grid.single.cell_size - 0.8).abs() < 1e-12,
            "cell size {}",
            grid.single.cell_size
        );
        assert_eq!(grid.single.cell_start.len(), boxes.len() + 1);
    }

    /// All pairs `(i, j)`, `i < j`, whose boxes overlap, `i`'s grown by
    /// `margin`: the answer the grids must give.
    fn brute_force(boxes: &[Aabb2], margin: f64) -> Vec<(usize, usize)> {
        (0..boxes.len())
            .flat_map(|i| (i + 1..boxes.len()).map(move |j| (i, j)))
            .filter(|&(i, j)| boxes[i].inflated(margin).intersects(&boxes[j]))
            .collect()
    }

    proptest! {
        /// Sizes spread over four orders of magnitude (boulders among
        /// grains, grains among dust, some far away): the grids of the
        /// size levels find exactly the brute force's pairs, in its order,
        /// sorted or visited one by one, on one thread or rayon's.
        #[test]
        fn size_levels_find_exactly_the_overlapping_pairs(
            bodies in prop::collection::vec(
                (-20.0f64..20.0, -20.0f64..20.0, 0.0f64..1.0, 0u8..6), 2..400),
            outlier in prop::option::of((-1e9f64..1e9, -1e9f64..1e9)),
            margin in prop_oneof![Just(0.0), 0.0f64..0.05],
        ) {
            let mut boxes: Vec<Aabb2> = bodies
                .iter()
                .map(|&(x, y, h, level)| square(x, y, 0.001 + h * 0.1 * 4f64.powi(i32::from(level) - 2)))
                .collect();
            if let Some((x, y)) = outlier {
                boxes.push(square(x, y, 0.01));
                boxes.push(square(x + 0.015, y, 0.01));
                boxes.push(square(x, y + 1.0, 3.0));
            }
            let brute = brute_force(&boxes, margin);
            let mut grid = CellGrid::new();
            let mut pairs = Vec::new();
            grid.candidate_pairs(&boxes, margin, &mut pairs);
            prop_assert_eq!(&pairs, &brute);
            for parallel in [false, true] {
                grid.candidate_pairs_filtered(&boxes, margin, |_, _| true, parallel, &mut pairs);
                prop_assert_eq!(&pairs, &brute);
            }
            let mut visited = Vec::new();
            let _: Result<(), ()> = grid.try_for_each_pair(&boxes, margin, |i, j| {
                visited.push((i, j));
                Ok(())
            });
            prop_assert!(visited.windows(2).all(|w| w[0].0 <= w[1].0), "not by ascending i");
            visited.sort_unstable();
            visited.dedup();
            prop_assert_eq!(&visited, &brute);
        }
    }

    /// One boulder 80 grain widths across among 10 000 grains of alike
    /// sizes: the grains are binned apart from the boulder (their cells
    /// are a grain's, not the boulder's), and the pairs are the brute
    /// force's; the grains alone take the one grid.
    #[test]
    fn a_boulder_among_grains_takes_a_level_of_its_own() {
        let mut boxes: Vec<Aabb2> = (0..10_000)
            .map(|k| {
                let h = 0.4 + 0.05 * ((k * 7919) % 13) as f64 / 13.0;
                square((k % 100) as f64, (k / 100) as f64, h)
            })
            .collect();
        let mut grid = CellGrid::new();
        let mut pairs = Vec::new();
        grid.candidate_pairs(&boxes, 0.01, &mut pairs);
        assert!(!grid.is_multilevel());
        boxes.insert(5_000, square(50.0, 99.0 + 40.0 - 0.3, 40.0));
        grid.candidate_pairs(&boxes, 0.01, &mut pairs);
        assert!(grid.is_multilevel());
        assert_eq!(grid.level_count, 7);
        assert!(grid.levels[0].cell_size > 80.0);
        assert!(grid.levels[6].cell_size < 1.0);
        assert_eq!(pairs, brute_force(&boxes, 0.01));
        assert!(pairs.iter().any(|&(i, j)| i == 5_000 || j == 5_000));
    }
}
