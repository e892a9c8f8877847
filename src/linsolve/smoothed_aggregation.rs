//! Smoothed-aggregation algebraic multigrid (Vaněk, Mandel & Brezina
//! 1996, "Algebraic multigrid by smoothed aggregation for second and
//! fourth order elliptic problems", Computing 56: 179–196) as a
//! preconditioner of the conjugate gradients, for matrices made of dense
//! square blocks ([`BlockSparse`]).
//!
//! # Setup, level by level
//!
//! 1. **Strength**: blocks `a ≠ b` are strongly connected when
//!    `‖A_ab‖_F ≥ θ √(‖A_aa‖_F ‖A_bb‖_F)`
//!    ([`AggregationSettings::strength_threshold`]).
//! 2. **Aggregation** of the block graph of strong connections (the three
//!    passes of Vaněk, Mandel & Brezina): a block whose strong neighbours
//!    are all free starts an aggregate with them; a block left over joins
//!    the aggregate of a strong neighbour; what remains forms aggregates
//!    of its free neighbours.
//! 3. **Tentative prolongator** `T` from the near-null space `B` (for
//!    elasticity the rigid motions, given block by block): on each
//!    aggregate the rows of `B` are factored `B_agg = Q R`; `Q` is the
//!    aggregate's block column of `T` and the `R` stacked by aggregate
//!    are the next level's near-null space, so `T B_c = B`.
//! 4. **Smoothing** of the prolongator by one damped block-Jacobi step,
//!    `P = (I − ω D⁻¹ A) T`, `ω = 4 / (3 ρ(D⁻¹ A))`, `ρ` estimated by
//!    power iterations and `D` the diagonal blocks.
//! 5. **Galerkin** coarse operator `A_c = Pᵀ A P`, formed on the block
//!    patterns.
//!
//! The coarsening stops at [`AggregationSettings::max_coarse`] unknowns
//! (or [`AggregationSettings::max_levels`]), where the level is factored
//! by the sparse Cholesky solver ([`super::SparseCholesky`]).
//!
//! # A first level given by the caller
//!
//! Where the caller knows lines of strongly coupled blocks (for HPM the
//! elements of one grid column, coupled by stiff face springs) it may give
//! the finest level's aggregates and those lines ([`LineLevel`],
//! [`SmoothedAggregation::with_lines`]): the aggregates replace steps 1–2
//! on that level, and its smoother becomes damped block-Jacobi over the
//! lines, `x ← x + w D_L⁻¹ (b − A x)` with `D_L` the dense diagonal block
//! of each line and `w = 1 / ρ(D_L⁻¹ A)`. The prolongator of that level
//! is smoothed by the same lines, `P = (I − ω D_L⁻¹ A) T` with
//! `ω = 4 / (3 ρ(D_L⁻¹ A))` (step 4 with `D_L` for `D`): on the 40 × 40 ×
//! 5 HPM slope of `benches/hpm_elastic.rs` PCG then takes 116 iterations
//! where the element blocks `D` took 127. A point (block) smoother leaves
//! errors that are smooth along the lines and rough across them, which no
//! coarse space of aggregates represents (the case of anisotropic
//! problems, where line relaxation is the classical remedy; Trottenberg,
//! Oosterlee & Schüller, *Multigrid*, 2001, § 5.1). The coarser levels are
//! aggregated and smoothed as above.
//!
//! # Application
//!
//! One V-cycle from zero: a forward block Gauss–Seidel sweep before the
//! restriction `Pᵀ r`, the correction from the coarser level, and a
//! backward sweep after it (on a level with lines: the same number of
//! line-Jacobi sweeps on each side; the residual after the coarse
//! correction `P e` is updated as `r − (A P) e`, `A P` kept from the
//! setup, where `b − A x` would multiply by the larger `A`). The backward
//! sweep is the adjoint of the forward one, Jacobi is symmetric, and the
//! coarsest solve is exact, so the cycle is a symmetric positive definite
//! operator: a valid preconditioner for PCG.

use std::sync::Mutex;

use std::ops::Range;

use nalgebra::DMatrix;
use rayon::prelude::*;

use super::{
    DiagonalBlocks, FactorizationFailure, LinearSolver, LinearSolverInfo, Preconditioner,
    SolveError, SparseCholesky, SparseMatrix, SparsePattern,
};

/// Fewest block rows a parallel task takes: below this the threads'
/// hand-over costs more than the rows (a small level or model).
const MIN_BLOCKS_A_TASK: usize = 64;

/// Fewest vector entries a parallel task takes.
const MIN_NUMBERS_A_TASK: usize = 4096;

/// A symmetric matrix of dense square blocks, read block by block.
pub trait BlockSparse {
    /// Unknowns per block.
    fn block_size(&self) -> usize;
    /// Number of block rows.
    fn block_count(&self) -> usize;
    /// Call `visit(a, b, values)` for every stored block `A_ab` of both
    /// triangles and the diagonal (`a`, `b` below [`Self::block_count`]),
    /// `values` its `block_size²` entries by rows; a block visited twice is
    /// summed. The multigrid calls it twice, for the pattern and then the
    /// numbers: both calls must visit the same blocks in the same order
    /// (a matrix that does not is refused with
    /// [`SolveError::DimensionMismatch`], as is a block out of the matrix
    /// or of another size).
    fn visit_blocks(&self, visit: &mut dyn FnMut(usize, usize, &[f64]));
}

/// Block compressed rows: block row `i` holds the blocks
/// `start[i]..start[i + 1]`, of columns `cols[k]` (sorted), each
/// `rows × cols` numbers by rows at `values[k · rows · cols ..]`.
#[derive(Debug, Clone, Default)]
struct Bsr {
    block_rows: usize,
    block_cols: usize,
    rows: usize,
    cols: usize,
    start: Vec<usize>,
    col: Vec<usize>,
    values: Vec<f64>,
}

/// `y += a · x` for dense row-major `a` (`y.len()` × `x.len()`): a
/// product by rows, which the compiler vectorises (the general
/// [`gemm_add`] with one column does not).
fn gemv_add(y: &mut [f64], a: &[f64], x: &[f64]) {
    for (yi, row) in y.iter_mut().zip(a.chunks_exact(x.len())) {
        *yi += dot(row, x);
    }
}

/// `a · b` in four interleaved sums.
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut sums = [0.0; 4];
    let (ac, bc) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = ac
        .remainder()
        .iter()
        .zip(bc.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ac.zip(bc) {
        for l in 0..4 {
            sums[l] += x[l] * y[l];
        }
    }
    (sums[0] + sums[1]) + (sums[2] + sums[3]) + tail
}

/// `c += a · b` for dense row-major `a` (m × k) and `b` (k × n).
fn gemm_add(c: &mut [f64], a: &[f64], b: &[f64], m: usize, k: usize, n: usize) {
    for i in 0..m {
        let ci = &mut c[i * n..(i + 1) * n];
        for (p, &aip) in a[i * k..(i + 1) * k].iter().enumerate() {
            if aip == 0.0 {
                continue;
            }
            for (cij, bpj) in ci.iter_mut().zip(&b[p * n..(p + 1) * n]) {
                *cij += aip * bpj;
            }
        }
    }
}

impl Bsr {
    fn block_len(&self) -> usize {
        self.rows * self.cols
    }

    fn block(&self, k: usize) -> &[f64] {
        let s = self.block_len();
        &self.values[k * s..(k + 1) * s]
    }

    fn row(&self, i: usize) -> std::ops::Range<usize> {
        self.start[i]..self.start[i + 1]
    }

    /// Assemble from unsorted `(row, col, values)` blocks, summing
    /// duplicates; [`SolveError::DimensionMismatch`] for a block out of the
    /// matrix or of another size, or a second visit unlike the first.
    fn from_blocks<M: BlockSparse + ?Sized>(matrix: &M) -> Result<Self, SolveError> {
        let b = matrix.block_size();
        let n = matrix.block_count();
        // The blocks' positions first, then their numbers straight into
        // place (no copy of the matrix on the way). A block out of the
        // matrix, of the wrong size, or a second visit that differs from
        // the first is refused.
        let mismatch = |what, expected, found| SolveError::DimensionMismatch {
            what,
            expected,
            found,
        };
        let mut problem = None;
        let mut list: Vec<(usize, usize, usize)> = Vec::new();
        matrix.visit_blocks(&mut |i, j, v| {
            if problem.is_some() {
                return;
            }
            if i.max(j) >= n {
                problem = Some(mismatch("block index of visit_blocks", n, i.max(j)));
            } else if v.len() != b * b {
                problem = Some(mismatch("block values of visit_blocks", b * b, v.len()));
            } else {
                list.push((i, j, list.len()));
            }
        });
        if let Some(problem) = problem {
            return Err(problem);
        }
        let order: Vec<(usize, usize)> = list.iter().map(|&(i, j, _)| (i, j)).collect();
        list.par_sort_unstable();
        let mut out = Self {
            block_rows: n,
            block_cols: n,
            rows: b,
            cols: b,
            start: vec![0; n + 1],
            col: Vec::with_capacity(list.len()),
            values: Vec::new(),
        };
        let mut place = vec![0; list.len()];
        let mut last: Option<(usize, usize)> = None;
        for &(i, j, visit) in &list {
            if last != Some((i, j)) {
                out.col.push(j);
                out.start[i + 1] += 1;
                last = Some((i, j));
            }
            place[visit] = out.col.len() - 1;
        }
        for i in 0..n {
            out.start[i + 1] += out.start[i];
        }
        out.values = vec![0.0; out.col.len() * b * b];
        let mut visit = 0;
        let mut same = true;
        matrix.visit_blocks(&mut |i, j, v| {
            if !same || order.get(visit) != Some(&(i, j)) || v.len() != b * b {
                same = false;
                return;
            }
            let k = place[visit];
            visit += 1;
            for (x, y) in out.values[k * b * b..(k + 1) * b * b].iter_mut().zip(v) {
                *x += y;
            }
        });
        if !same || visit != order.len() {
            return Err(mismatch(
                "blocks visited a second time by visit_blocks",
                order.len(),
                visit,
            ));
        }
        Ok(out)
    }

    /// `y = A x` (rows in parallel).
    fn apply(&self, x: &[f64], y: &mut [f64]) {
        let (r, c) = (self.rows, self.cols);
        y.par_chunks_mut(r)
            .with_min_len(MIN_BLOCKS_A_TASK)
            .enumerate()
            .for_each(|(i, yi)| {
                yi.fill(0.0);
                for k in self.row(i) {
                    let xj = &x[self.col[k] * c..(self.col[k] + 1) * c];
                    gemv_add(yi, self.block(k), xj);
                }
            });
    }

    /// The transpose.
    fn transpose(&self) -> Self {
        let (r, c) = (self.rows, self.cols);
        let mut start = vec![0; self.block_cols + 1];
        for &j in &self.col {
            start[j + 1] += 1;
        }
        for j in 0..self.block_cols {
            start[j + 1] += start[j];
        }
        let mut next = start.clone();
        let mut col = vec![0; self.col.len()];
        let mut values = vec![0.0; self.values.len()];
        for i in 0..self.block_rows {
            for k in self.row(i) {
                let j = self.col[k];
                let t = next[j];
                next[j] += 1;
                col[t] = i;
                let src = self.block(k);
                let dst = &mut values[t * r * c..(t + 1) * r * c];
                for p in 0..r {
                    for q in 0..c {
                        dst[q * r + p] = src[p * c + q];
                    }
                }
            }
        }
        Self {
            block_rows: self.block_cols,
            block_cols: self.block_rows,
            rows: c,
            cols: r,
            start,
            col,
            values,
        }
    }

    /// `self · other` on the block patterns (rows in parallel).
    fn multiply(&self, other: &Self) -> Self {
        assert_eq!(self.cols, other.rows);
        let (m, k, n) = (self.rows, self.cols, other.cols);
        let rows: Vec<(Vec<usize>, Vec<f64>)> = (0..self.block_rows)
            .into_par_iter()
            .map(|i| {
                let mut cols: Vec<usize> = Vec::new();
                for t in self.row(i) {
                    for u in other.row(self.col[t]) {
                        cols.push(other.col[u]);
                    }
                }
                cols.sort_unstable();
                cols.dedup();
                let mut values = vec![0.0; cols.len() * m * n];
                for t in self.row(i) {
                    let a = self.block(t);
                    for u in other.row(self.col[t]) {
                        let j = cols.binary_search(&other.col[u]).unwrap_or(0);
                        gemm_add(
                            &mut values[j * m * n..(j + 1) * m * n],
                            a,
                            other.block(u),
                            m,
                            k,
                            n,
                        );
                    }
                }
                (cols, values)
            })
            .collect();
        let mut out = Self {
            block_rows: self.block_rows,
            block_cols: other.block_cols,
            rows: m,
            cols: n,
            start: Vec::with_capacity(self.block_rows + 1),
            col: Vec::new(),
            values: Vec::new(),
        };
        out.start.push(0);
        for (cols, values) in rows {
            out.col.extend_from_slice(&cols);
            out.values.extend_from_slice(&values);
            out.start.push(out.col.len());
        }
        out
    }

    /// The position of block `(i, j)`.
    fn find(&self, i: usize, j: usize) -> Option<usize> {
        let range = self.row(i);
        self.col[range.clone()]
            .binary_search(&j)
            .ok()
            .map(|k| range.start + k)
    }

    /// The inverses of the diagonal blocks, by rows.
    fn diagonal_inverses(&self) -> Result<Vec<f64>, SolveError> {
        let b = self.rows;
        let inverses: Result<Vec<Vec<f64>>, SolveError> = (0..self.block_rows)
            .into_par_iter()
            .map(|i| {
                let k = self.find(i, i).ok_or(SolveError::Factorization(
                    FactorizationFailure::NoDiagonalBlock { block: i },
                ))?;
                let d = DMatrix::from_row_slice(b, b, self.block(k));
                let d = (&d + d.transpose()) * 0.5;
                let factor = d.cholesky().ok_or(SolveError::Factorization(
                    FactorizationFailure::LevelBlockNotPositiveDefinite { block: i },
                ))?;
                // Symmetric: its column-major entries are its rows.
                Ok(factor.inverse().as_slice().to_vec())
            })
            .collect();
        Ok(inverses?.concat())
    }

    /// The lower triangle in compressed columns (the matrix is symmetric).
    fn lower_triangle(&self) -> Result<SparseMatrix, SolveError> {
        let b = self.rows;
        let n = self.block_rows * b;
        let mut col_ptr = vec![0usize];
        let mut row_idx = Vec::new();
        let mut values = Vec::new();
        for i in 0..self.block_rows {
            for q in 0..b {
                let c = i * b + q;
                for k in self.row(i) {
                    let j = self.col[k];
                    if j < i {
                        continue;
                    }
                    let block = self.block(k);
                    for p in 0..b {
                        let r = j * b + p;
                        if r >= c {
                            row_idx.push(r);
                            // A_ji[p][q] = A_ij[q][p].
                            values.push(block[q * b + p]);
                        }
                    }
                }
                col_ptr.push(row_idx.len());
            }
        }
        SparseMatrix::new(SparsePattern::from_columns(n, col_ptr, row_idx)?, values)
    }
}

impl DiagonalBlocks for Bsr {
    /// The dense diagonal blocks over `ranges` of unknowns, each of whole
    /// blocks.
    fn diagonal_blocks(&self, ranges: &[Range<usize>]) -> Result<Vec<DMatrix<f64>>, SolveError> {
        let b = self.rows;
        ranges
            .par_iter()
            .map(|range| {
                if range.start % b != 0 || range.end % b != 0 || range.end > self.block_rows * b {
                    return Err(SolveError::DimensionMismatch {
                        what: "end of a line of the multigrid's first level (whole blocks, within the matrix)",
                        expected: self.block_rows * b,
                        found: range.end,
                    });
                }
                let blocks = range.start / b..range.end / b;
                let mut dense = DMatrix::zeros(range.len(), range.len());
                for i in blocks.clone() {
                    for k in self.row(i) {
                        let j = self.col[k];
                        if !blocks.contains(&j) {
                            continue;
                        }
                        let (r0, c0) = (b * (i - blocks.start), b * (j - blocks.start));
                        for (p, row) in self.block(k).chunks_exact(b).enumerate() {
                            for (q, &v) in row.iter().enumerate() {
                                dense[(r0 + p, c0 + q)] = v;
                            }
                        }
                    }
                }
                Ok(dense)
            })
            .collect()
    }
}

/// The finest level as the caller gives it: its aggregates and the lines
/// of blocks its smoother solves whole (see the module documentation).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LineLevel {
    /// The aggregate of each block of the finest level, numbered from 0
    /// with none empty.
    pub aggregates: Vec<usize>,
    /// The lines: consecutive ranges of blocks from block 0, covering
    /// every block.
    pub lines: Vec<Range<usize>>,
}

impl LineLevel {
    /// Check the aggregates and lines against a matrix of `blocks` blocks;
    /// the number of aggregates.
    fn validate(&self, blocks: usize) -> Result<usize, SolveError> {
        if self.aggregates.len() != blocks {
            return Err(SolveError::DimensionMismatch {
                what: "aggregates of the multigrid's first level (one per block)",
                expected: blocks,
                found: self.aggregates.len(),
            });
        }
        let count = self.aggregates.iter().max().map_or(0, |&g| g + 1);
        let mut used = vec![false; count];
        self.aggregates.iter().for_each(|&g| used[g] = true);
        if let Some(empty) = used.iter().position(|&u| !u) {
            return Err(SolveError::DimensionMismatch {
                what: "aggregate numbers of the multigrid's first level (from 0, none empty): the first unused",
                expected: count,
                found: empty,
            });
        }
        let mut start = 0;
        for line in &self.lines {
            if line.start != start || line.end <= line.start {
                return Err(SolveError::DimensionMismatch {
                    what: "start of a line of the multigrid's first level (lines are consecutive, not empty, from block 0)",
                    expected: start,
                    found: line.start,
                });
            }
            start = line.end;
        }
        if start != blocks {
            return Err(SolveError::DimensionMismatch {
                what: "blocks covered by the lines of the multigrid's first level",
                expected: blocks,
                found: start,
            });
        }
        Ok(count)
    }
}

/// The damped line-Jacobi smoother of a level with lines.
#[derive(Debug)]
struct LineSmoother {
    /// The lines, in unknowns (consecutive from 0).
    ranges: Vec<Range<usize>>,
    /// The Cholesky factor `L` of each line's `D_L = L Lᵀ`, its lower
    /// triangle packed by rows, the lines one after another: half the
    /// numbers of an explicit inverse, for as many operations a solve.
    factors: Vec<f64>,
    /// Where each line's factor starts in `factors`.
    offsets: Vec<usize>,
    /// `w = 1 / ρ(D_L⁻¹ A)`.
    weight: f64,
}

/// `v ← (L Lᵀ)⁻¹ v` for `L` packed by rows (`v.len()` rows).
fn cholesky_solve(factor: &[f64], v: &mut [f64]) {
    let n = v.len();
    // L y = v, by rows.
    for i in 0..n {
        let row = &factor[i * (i + 1) / 2..(i + 1) * (i + 2) / 2];
        let s = v[i] - dot(&row[..i], &v[..i]);
        v[i] = s / row[i];
    }
    // Lᵀ x = y, by the rows of L from the last.
    for i in (0..n).rev() {
        let row = &factor[i * (i + 1) / 2..(i + 1) * (i + 2) / 2];
        let xi = v[i] / row[i];
        v[i] = xi;
        for (vj, lij) in v[..i].iter_mut().zip(&row[..i]) {
            *vj -= xi * lij;
        }
    }
}

impl LineSmoother {
    /// Factor the diagonal blocks of `a` over `ranges` (in unknowns).
    fn new(a: &Bsr, ranges: Vec<Range<usize>>) -> Result<Self, SolveError> {
        let blocks = a.diagonal_blocks(&ranges)?;
        let factors: Vec<Result<Vec<f64>, SolveError>> = blocks
            .into_par_iter()
            .enumerate()
            .map(|(index, block)| {
                let l = block
                    .cholesky()
                    .ok_or(SolveError::Factorization(
                        FactorizationFailure::LineNotPositiveDefinite { line: index },
                    ))?
                    .unpack();
                let n = l.nrows();
                let mut packed = Vec::with_capacity(n * (n + 1) / 2);
                for i in 0..n {
                    packed.extend((0..=i).map(|j| l[(i, j)]));
                }
                Ok(packed)
            })
            .collect();
        // The first failing line in order is reported.
        let factors = factors.into_iter().collect::<Result<Vec<_>, _>>()?;
        let mut offsets = Vec::with_capacity(factors.len() + 1);
        offsets.push(0);
        for f in &factors {
            offsets.push(offsets.last().copied().unwrap_or(0) + f.len());
        }
        Ok(Self {
            ranges,
            factors: factors.concat(),
            offsets,
            weight: 1.0,
        })
    }

    /// The factor of line `l`.
    fn factor(&self, l: usize) -> &[f64] {
        &self.factors[self.offsets[l]..self.offsets[l + 1]]
    }

    /// `z = D_L⁻¹ r`, the lines in parallel.
    fn solve(&self, r: &[f64], z: &mut [f64]) {
        z.copy_from_slice(r);
        let mut parts = Vec::with_capacity(self.ranges.len());
        let mut rest = z;
        for range in &self.ranges {
            let (part, tail) = std::mem::take(&mut rest).split_at_mut(range.len());
            parts.push(part);
            rest = tail;
        }
        parts
            .into_par_iter()
            .enumerate()
            .for_each(|(l, part)| cholesky_solve(self.factor(l), part));
    }

    /// `x ← x + w D_L⁻¹ (b − A x)`; `x` is zero when `from_zero`.
    fn sweep(&self, a: &Bsr, rhs: &[f64], x: &mut [f64], from_zero: bool) {
        let mut residual = rhs.to_vec();
        if !from_zero {
            let mut ax = vec![0.0; x.len()];
            a.apply(x, &mut ax);
            residual
                .par_iter_mut()
                .with_min_len(MIN_NUMBERS_A_TASK)
                .zip(&ax)
                .for_each(|(r, v)| *r -= v);
        }
        self.correct(&residual, x);
    }

    /// `x ← x + w D_L⁻¹ r`.
    fn correct(&self, residual: &[f64], x: &mut [f64]) {
        let mut z = vec![0.0; x.len()];
        self.solve(residual, &mut z);
        x.par_iter_mut()
            .with_min_len(MIN_NUMBERS_A_TASK)
            .zip(&z)
            .for_each(|(xi, zi)| *xi += self.weight * zi);
    }
}

/// Settings of the hierarchy.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AggregationSettings {
    /// `θ` of the strength of connection (0: every stored block is strong).
    pub strength_threshold: f64,
    /// Unknowns at or below which a level is factored and not coarsened.
    pub max_coarse: usize,
    /// The most levels, the coarsest included.
    pub max_levels: usize,
    /// Power iterations estimating `ρ(D⁻¹ A)` for the prolongator's damping.
    pub power_iterations: usize,
    /// Block Gauss–Seidel sweeps before the coarse correction (forward)
    /// and after it (backward); on a level with lines
    /// ([`SmoothedAggregation::with_lines`]), damped line-Jacobi sweeps.
    pub sweeps: usize,
}

impl Default for AggregationSettings {
    /// `θ = 0`, at most 2 000 unknowns on the coarsest level, 10 levels,
    /// 20 power iterations, one sweep each side.
    fn default() -> Self {
        Self {
            strength_threshold: 0.0,
            max_coarse: 2000,
            max_levels: 10,
            power_iterations: 20,
            sweeps: 1,
        }
    }
}

/// One level of the hierarchy above the coarsest.
#[derive(Debug)]
struct Level {
    a: Bsr,
    /// `D⁻¹`, the inverses of the diagonal blocks, by rows (empty on a
    /// level with lines).
    inverses: Vec<f64>,
    p: Bsr,
    r: Bsr,
    /// The line smoother in place of Gauss–Seidel (a level with lines).
    lines: Option<LineSmoother>,
    /// `A P` on a level with line-Jacobi smoothing: the residual after the
    /// coarse correction `P e` is `r − (A P) e`, cheaper than `b − A x`
    /// (`A P` has a few narrow blocks a row where `A` has many square ones).
    ap: Option<Bsr>,
}

/// A smoothed-aggregation multigrid V-cycle as a PCG preconditioner (see
/// the module documentation).
#[derive(Debug, Default)]
pub struct SmoothedAggregation {
    /// Settings of the hierarchy.
    pub settings: AggregationSettings,
    /// The near-null space, block by block: block `i`'s `block_size × m`
    /// numbers by rows.
    near_null: Vec<f64>,
    /// Near-null vectors `m`.
    modes: usize,
    levels: Vec<Level>,
    coarse: Option<Mutex<SparseCholesky>>,
    coarse_size: usize,
    /// The finest level's aggregates and lines, where given.
    first: Option<LineLevel>,
}

/// The aggregates of the strong block graph of `a`: the aggregate of each
/// block and their count.
fn aggregate(a: &Bsr, theta: f64) -> (Vec<usize>, usize) {
    let n = a.block_rows;
    let norm = |k: usize| a.block(k).iter().map(|x| x * x).sum::<f64>().sqrt();
    let diag: Vec<f64> = (0..n).map(|i| a.find(i, i).map_or(0.0, norm)).collect();
    let strong: Vec<Vec<usize>> = (0..n)
        .map(|i| {
            a.row(i)
                .filter(|&k| {
                    let j = a.col[k];
                    j != i && norm(k) >= theta * (diag[i] * diag[j]).sqrt()
                })
                .map(|k| a.col[k])
                .collect()
        })
        .collect();
    const FREE: usize = usize::MAX;
    let mut agg = vec![FREE; n];
    let mut count = 0;
    // Pass 1: blocks whose strong neighbours are all free.
    for i in 0..n {
        if agg[i] == FREE && strong[i].iter().all(|&j| agg[j] == FREE) {
            agg[i] = count;
            for &j in &strong[i] {
                agg[j] = count;
            }
            count += 1;
        }
    }
    // Pass 2: join a strong neighbour's aggregate (of pass 1).
    let first = agg.clone();
    for i in 0..n {
        if agg[i] == FREE {
            if let Some(&j) = strong[i].iter().find(|&&j| first[j] != FREE) {
                agg[i] = first[j];
            }
        }
    }
    // Pass 3: what remains, with its free neighbours.
    for i in 0..n {
        if agg[i] == FREE {
            agg[i] = count;
            for &j in &strong[i] {
                if agg[j] == FREE {
                    agg[j] = count;
                }
            }
            count += 1;
        }
    }
    (agg, count)
}

/// The tentative prolongator of `agg` (block rows `b × m`) and the
/// coarse near-null space (`m × m` a block), from `near_null` (`b × m` a
/// block, by rows), by a QR factorization per aggregate.
fn tentative(
    agg: &[usize],
    count: usize,
    near_null: &[f64],
    b: usize,
    m: usize,
) -> Result<(Bsr, Vec<f64>), SolveError> {
    let n = agg.len();
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); count];
    for (i, &g) in agg.iter().enumerate() {
        members[g].push(i);
    }
    if let Some((g, list)) = members.iter().enumerate().find(|(_, l)| l.len() * b < m) {
        return Err(SolveError::Factorization(
            FactorizationFailure::SmallAggregate {
                aggregate: g,
                unknowns: list.len() * b,
                vectors: m,
            },
        ));
    }
    // One QR factorization per aggregate, in parallel: `Q`'s rows by
    // member and `R`.
    let factors: Vec<(DMatrix<f64>, DMatrix<f64>)> = members
        .par_iter()
        .map(|list| {
            let rows = list.len() * b;
            let mut local = DMatrix::zeros(rows, m);
            for (t, &i) in list.iter().enumerate() {
                for p in 0..b {
                    for q in 0..m {
                        local[(t * b + p, q)] = near_null[(i * b + p) * m + q];
                    }
                }
            }
            let qr = local.qr();
            (qr.q(), qr.r())
        })
        .collect();
    let mut values = vec![0.0; n * b * m];
    let mut coarse = vec![0.0; count * m * m];
    for (g, (list, (q, r))) in members.iter().zip(&factors).enumerate() {
        for (t, &i) in list.iter().enumerate() {
            for p in 0..b {
                for c in 0..m {
                    values[(i * b + p) * m + c] = q[(t * b + p, c)];
                }
            }
        }
        for p in 0..m {
            for c in 0..m {
                coarse[(g * m + p) * m + c] = r[(p, c)];
            }
        }
    }
    Ok((
        Bsr {
            block_rows: n,
            block_cols: count,
            rows: b,
            cols: m,
            start: (0..=n).collect(),
            col: agg.to_vec(),
            values,
        },
        coarse,
    ))
}

/// `z = D⁻¹ r` block by block.
fn block_diagonal_apply(inverses: &[f64], b: usize, r: &[f64], z: &mut [f64]) {
    z.par_chunks_mut(b)
        .with_min_len(MIN_BLOCKS_A_TASK)
        .enumerate()
        .for_each(|(i, zi)| {
            zi.fill(0.0);
            gemv_add(
                zi,
                &inverses[i * b * b..(i + 1) * b * b],
                &r[i * b..(i + 1) * b],
            );
        });
}

/// An estimate of `ρ(D⁻¹ A)` by power iterations from a fixed start.
fn spectral_radius(a: &Bsr, inverses: &[f64], iterations: usize) -> f64 {
    power_iterations(a, iterations, |y, z| {
        block_diagonal_apply(inverses, a.rows, y, z)
    })
}

/// An estimate of `ρ(M A)` by power iterations from a fixed start, `M`
/// applied by `precondition(y, z)`: `z = M y`.
fn power_iterations(a: &Bsr, iterations: usize, precondition: impl Fn(&[f64], &mut [f64])) -> f64 {
    let n = a.block_rows * a.rows;
    let mut x: Vec<f64> = (0..n)
        .map(|i| 1.0 + ((i * 7919) % 13) as f64 / 13.0)
        .collect();
    let (mut y, mut z) = (vec![0.0; n], vec![0.0; n]);
    let mut rho = 0.0;
    for _ in 0..iterations.max(1) {
        let norm = x.iter().map(|v| v * v).sum::<f64>().sqrt();
        x.iter_mut().for_each(|v| *v /= norm);
        a.apply(&x, &mut y);
        precondition(&y, &mut z);
        rho = z.iter().map(|v| v * v).sum::<f64>().sqrt();
        std::mem::swap(&mut x, &mut z);
    }
    rho
}

/// The prolongator `P = T − ω D⁻¹ A T` from `at = A T`, `D` the diagonal
/// blocks (`inverses`, by rows).
fn smooth_by_blocks(mut at: Bsr, t: &Bsr, agg: &[usize], inverses: &[f64], omega: f64) -> Bsr {
    let (rb, cb) = (at.rows, at.cols);
    let mut values = vec![0.0; at.values.len()];
    for i in 0..at.block_rows {
        let dinv = &inverses[i * rb * rb..(i + 1) * rb * rb];
        for k in at.start[i]..at.start[i + 1] {
            let dst = &mut values[k * rb * cb..(k + 1) * rb * cb];
            gemm_add(
                dst,
                dinv,
                &at.values[k * rb * cb..(k + 1) * rb * cb],
                rb,
                rb,
                cb,
            );
            dst.iter_mut().for_each(|v| *v *= -omega);
            if at.col[k] == agg[i] {
                for (v, tv) in dst.iter_mut().zip(t.block(i)) {
                    *v += tv;
                }
            }
        }
    }
    at.values = values;
    at
}

/// The prolongator `P = T − ω D_L⁻¹ A T` from `at = A T`, `D_L` the dense
/// diagonal blocks of the lines of `smoother` (each of whole blocks). A
/// line's rows of `P` share one block pattern: the union of its rows'
/// patterns in `A T` and `T`.
fn smooth_by_lines(at: &Bsr, t: &Bsr, agg: &[usize], smoother: &LineSmoother, omega: f64) -> Bsr {
    let (rb, cb) = (at.rows, at.cols);
    let ranges = &smoother.ranges;
    let lines: Vec<(Vec<usize>, Vec<f64>)> = ranges
        .par_iter()
        .enumerate()
        .map(|(l, range)| {
            let blocks = range.start / rb..range.end / rb;
            let mut cols: Vec<usize> = blocks
                .clone()
                .flat_map(|i| at.col[at.row(i)].iter().copied().chain([agg[i]]))
                .collect();
            cols.sort_unstable();
            cols.dedup();
            let mut x = DMatrix::zeros(range.len(), cols.len() * cb);
            for i in blocks.clone() {
                let r0 = (i - blocks.start) * rb;
                for k in at.row(i) {
                    let c0 = cols.binary_search(&at.col[k]).unwrap_or(0) * cb;
                    for (p, row) in at.block(k).chunks_exact(cb).enumerate() {
                        for (q, &v) in row.iter().enumerate() {
                            x[(r0 + p, c0 + q)] = v;
                        }
                    }
                }
            }
            // D_L⁻¹ X, column by column (stored by columns).
            let mut y = x;
            for column in y.as_mut_slice().chunks_exact_mut(range.len()) {
                cholesky_solve(smoother.factor(l), column);
            }
            let mut values = Vec::with_capacity(range.len() * cols.len() * cb);
            for i in blocks.clone() {
                let r0 = (i - blocks.start) * rb;
                for (j, &c) in cols.iter().enumerate() {
                    let own = (c == agg[i]).then(|| t.block(i));
                    for p in 0..rb {
                        for q in 0..cb {
                            let v = -omega * y[(r0 + p, j * cb + q)];
                            values.push(own.map_or(v, |own| v + own[p * cb + q]));
                        }
                    }
                }
            }
            (cols, values)
        })
        .collect();
    let mut out = Bsr {
        block_rows: at.block_rows,
        block_cols: at.block_cols,
        rows: rb,
        cols: cb,
        start: Vec::with_capacity(at.block_rows + 1),
        col: Vec::new(),
        values: Vec::new(),
    };
    out.start.push(0);
    for (range, (cols, values)) in ranges.iter().zip(lines) {
        for _ in range.start / rb..range.end / rb {
            out.col.extend_from_slice(&cols);
            out.start.push(out.col.len());
        }
        out.values.extend_from_slice(&values);
    }
    out
}

impl SmoothedAggregation {
    /// A preconditioner for matrices of blocks of `block_size` unknowns
    /// whose near-null space (for elasticity, the rigid motions) holds
    /// `modes` vectors, given block by block in `near_null`: block `i`'s
    /// `block_size × modes` numbers by rows at
    /// `near_null[i · block_size · modes ..]`.
    pub fn new(settings: AggregationSettings, near_null: Vec<f64>, modes: usize) -> Self {
        Self {
            settings,
            near_null,
            modes,
            ..Self::default()
        }
    }

    /// The hierarchy with the finest level's aggregates and line smoother
    /// given by `first` (see the module documentation); checked against
    /// the matrix at [`Preconditioner::setup`]. Where the matrix has at
    /// most [`AggregationSettings::max_coarse`] unknowns, or the given
    /// aggregates would not make a smaller level (`aggregates × modes` not
    /// below the unknowns), no level is built and the matrix is factored
    /// whole ([`SmoothedAggregation::level_sizes`] then has one entry).
    pub fn with_lines(mut self, first: LineLevel) -> Self {
        self.first = Some(first);
        self
    }

    /// The unknowns of each level, finest first, the coarsest last.
    pub fn level_sizes(&self) -> Vec<usize> {
        let mut sizes: Vec<usize> = self
            .levels
            .iter()
            .map(|l| l.a.block_rows * l.a.rows)
            .collect();
        sizes.push(self.coarse_size);
        sizes
    }

    /// Operator complexity: the stored entries of all levels' matrices
    /// over those of the finest.
    pub fn operator_complexity(&self) -> f64 {
        let fine = self.levels.first().map_or(1, |l| l.a.values.len()) as f64;
        let coarse = self
            .coarse
            .as_ref()
            .and_then(|c| c.lock().ok().map(|c| c.matrix_entries()))
            .unwrap_or(0) as f64;
        (self
            .levels
            .iter()
            .map(|l| l.a.values.len() as f64)
            .sum::<f64>()
            + coarse)
            / fine
    }

    fn build(&mut self, mut a: Bsr) -> Result<(), SolveError> {
        self.levels.clear();
        self.coarse = None;
        let mut b = a.rows;
        let mut m = self.modes;
        if self.near_null.len() != a.block_rows * b * m || m == 0 {
            return Err(SolveError::DimensionMismatch {
                what: "near-null space numbers (blocks × block size × modes)",
                expected: a.block_rows * b * m,
                found: self.near_null.len(),
            });
        }
        // The caller's first level is checked whether or not a level is
        // built (a matrix at or below `max_coarse` is factored whole).
        let first_count = match &self.first {
            Some(first) => Some(first.validate(a.block_rows)?),
            None => None,
        };
        let mut near_null = self.near_null.clone();
        let s = self.settings;
        while a.block_rows * b > s.max_coarse && self.levels.len() + 1 < s.max_levels {
            let given = self
                .first
                .as_ref()
                .zip(first_count)
                .filter(|_| self.levels.is_empty());
            // A level with lines needs no `D⁻¹`: neither its smoother nor
            // its prolongator uses them (the lines' factorization refuses a
            // block that is not positive definite).
            let inverses = match given {
                Some(_) => Vec::new(),
                None => a.diagonal_inverses()?,
            };
            let (agg, count) = match given {
                Some((first, count)) => (first.aggregates.clone(), count),
                None => aggregate(&a, s.strength_threshold),
            };
            if count * m >= a.block_rows * b {
                break;
            }
            let lines = match given {
                Some((first, _)) => {
                    let ranges: Vec<Range<usize>> =
                        first.lines.iter().map(|l| b * l.start..b * l.end).collect();
                    let mut smoother = LineSmoother::new(&a, ranges)?;
                    let rho = power_iterations(&a, s.power_iterations, |y, z| smoother.solve(y, z));
                    smoother.weight = 1.0 / rho;
                    Some((smoother, rho))
                }
                None => None,
            };
            let (t, coarse_null) = tentative(&agg, count, &near_null, b, m)?;
            let at = a.multiply(&t);
            let p = match &lines {
                Some((smoother, rho)) => {
                    smooth_by_lines(&at, &t, &agg, smoother, 4.0 / (3.0 * rho))
                }
                None => {
                    let rho = spectral_radius(&a, &inverses, s.power_iterations);
                    smooth_by_blocks(at, &t, &agg, &inverses, 4.0 / (3.0 * rho))
                }
            };
            let lines = lines.map(|(smoother, _)| smoother);
            let r = p.transpose();
            let ap = a.multiply(&p);
            let coarse = r.multiply(&ap);
            // A level with lines keeps `A P` for its residual update.
            let ap = lines.as_ref().map(|_| ap);
            self.levels.push(Level {
                a,
                inverses,
                p,
                r,
                lines,
                ap,
            });
            a = coarse;
            b = m;
            near_null = coarse_null;
            m = self.modes;
        }
        self.coarse_size = a.block_rows * b;
        let lower = a.lower_triangle()?;
        let mut solver = SparseCholesky::new();
        LinearSolver::<SparseMatrix>::factor(&mut solver, &lower)?;
        self.coarse = Some(Mutex::new(solver));
        Ok(())
    }

    /// One V-cycle at `level` from zero: `x ≈ A_level⁻¹ b`.
    fn cycle(&self, level: usize, rhs: &[f64], x: &mut [f64]) {
        if level == self.levels.len() {
            x.copy_from_slice(rhs);
            if let Some(coarse) = &self.coarse {
                let mut solver = coarse.lock().unwrap_or_else(|e| e.into_inner());
                if solver.solve_factored(x).is_err() {
                    x.fill(0.0);
                }
            }
            return;
        }
        let Level {
            a,
            inverses,
            p,
            r,
            lines,
            ap,
        } = &self.levels[level];
        x.fill(0.0);
        for sweep in 0..self.settings.sweeps {
            match lines {
                Some(lines) => lines.sweep(a, rhs, x, sweep == 0),
                None => gauss_seidel(a, inverses, rhs, x, false),
            }
        }
        let mut residual = vec![0.0; x.len()];
        a.apply(x, &mut residual);
        residual
            .par_iter_mut()
            .with_min_len(MIN_NUMBERS_A_TASK)
            .zip(rhs)
            .for_each(|(ri, bi)| *ri = bi - *ri);
        let nc = r.block_rows * r.rows;
        let mut coarse_rhs = vec![0.0; nc];
        r.apply(&residual, &mut coarse_rhs);
        let mut coarse_x = vec![0.0; nc];
        self.cycle(level + 1, &coarse_rhs, &mut coarse_x);
        // Without sweeps there is no post-sweep to start from r (and none
        // before, so the plain correction keeps the cycle symmetric).
        if let (Some(ap), Some(lines), true) = (ap, lines, self.settings.sweeps > 0) {
            // r ← r − (A P) e, x ← x + P e, then the first post-sweep from r.
            let mut correction = vec![0.0; x.len()];
            ap.apply(&coarse_x, &mut correction);
            residual
                .par_iter_mut()
                .with_min_len(MIN_NUMBERS_A_TASK)
                .zip(&correction)
                .for_each(|(ri, ci)| *ri -= ci);
            p.apply(&coarse_x, &mut correction);
            x.par_iter_mut()
                .with_min_len(MIN_NUMBERS_A_TASK)
                .zip(&correction)
                .for_each(|(xi, ci)| *xi += ci);
            lines.correct(&residual, x);
            for _ in 1..self.settings.sweeps {
                lines.sweep(a, rhs, x, false);
            }
            return;
        }
        p.apply(&coarse_x, &mut residual);
        x.par_iter_mut()
            .with_min_len(MIN_NUMBERS_A_TASK)
            .zip(&residual)
            .for_each(|(xi, ci)| *xi += ci);
        for _ in 0..self.settings.sweeps {
            match lines {
                Some(lines) => lines.sweep(a, rhs, x, false),
                None => gauss_seidel(a, inverses, rhs, x, true),
            }
        }
    }
}

/// One block Gauss–Seidel sweep on `A x = b`, forward or backward.
fn gauss_seidel(a: &Bsr, inverses: &[f64], rhs: &[f64], x: &mut [f64], backward: bool) {
    let b = a.rows;
    let mut s = vec![0.0; b];
    let mut step = |i: usize, x: &mut [f64]| {
        s.copy_from_slice(&rhs[i * b..(i + 1) * b]);
        for k in a.row(i) {
            let j = a.col[k];
            if j == i {
                continue;
            }
            let block = a.block(k);
            let xj = &x[j * b..(j + 1) * b];
            for p in 0..b {
                let row = &block[p * b..(p + 1) * b];
                s[p] -= row.iter().zip(xj).map(|(u, v)| u * v).sum::<f64>();
            }
        }
        let xi = &mut x[i * b..(i + 1) * b];
        xi.fill(0.0);
        gemv_add(xi, &inverses[i * b * b..(i + 1) * b * b], &s);
    };
    if backward {
        for i in (0..a.block_rows).rev() {
            step(i, x);
        }
    } else {
        for i in 0..a.block_rows {
            step(i, x);
        }
    }
}

impl<A: BlockSparse + ?Sized> Preconditioner<A> for SmoothedAggregation {
    /// Build the hierarchy (see the module documentation).
    ///
    /// # Errors
    /// [`SolveError::DimensionMismatch`] for a matrix whose
    /// [`BlockSparse::visit_blocks`] breaks its contract (a block out of
    /// the matrix or of another size, a second visit unlike the first), a
    /// near-null space of another size than the matrix's, or a first level
    /// ([`SmoothedAggregation::with_lines`]) whose aggregates or lines do
    /// not fit it (checked even where the matrix is factored whole);
    /// [`SolveError::Factorization`] for a diagonal block that is not
    /// positive definite or a coarsest level the Cholesky factorization
    /// refuses.
    fn setup(&mut self, matrix: &A) -> Result<(), SolveError> {
        self.build(Bsr::from_blocks(matrix)?)
    }

    fn apply(&self, r: &[f64], z: &mut [f64]) {
        self.cycle(0, r, z);
    }

    /// The stored numbers of the levels' matrices, prolongators,
    /// restrictions and diagonal inverses, and of the coarsest factor.
    fn entries(&self) -> usize {
        let levels: usize = self
            .levels
            .iter()
            .map(|l| {
                l.a.values.len()
                    + l.ap.as_ref().map_or(0, |ap| ap.values.len())
                    + l.p.values.len()
                    + l.r.values.len()
                    + l.inverses.len()
                    + l.lines.as_ref().map_or(0, |s| s.factors.len())
            })
            .sum();
        let coarse = self
            .coarse
            .as_ref()
            .and_then(|c| c.lock().ok().and_then(|c| c.factor_entries()))
            .unwrap_or(0);
        levels + coarse
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chain of `n` blocks of 2 unknowns, block tridiagonal and
    /// diagonally dominant (symmetric positive definite).
    struct Chain(usize);

    impl BlockSparse for Chain {
        fn block_size(&self) -> usize {
            2
        }
        fn block_count(&self) -> usize {
            self.0
        }
        fn visit_blocks(&self, visit: &mut dyn FnMut(usize, usize, &[f64])) {
            for i in 0..self.0 {
                visit(i, i, &[4.0, 1.0, 1.0, 3.0 + 0.01 * i as f64]);
                if i + 1 < self.0 {
                    visit(i, i + 1, &[-1.0, -0.2, -0.2, -1.0]);
                    visit(i + 1, i, &[-1.0, -0.2, -0.2, -1.0]);
                }
            }
        }
    }

    /// A chain whose block `bad` is indefinite.
    struct IndefiniteAt(usize, usize);

    impl BlockSparse for IndefiniteAt {
        fn block_size(&self) -> usize {
            2
        }
        fn block_count(&self) -> usize {
            self.0
        }
        fn visit_blocks(&self, visit: &mut dyn FnMut(usize, usize, &[f64])) {
            Chain(self.0).visit_blocks(&mut |i, j, values| {
                if i == j && i == self.1 {
                    visit(i, j, &[-4.0, 1.0, 1.0, 3.0]);
                } else {
                    visit(i, j, values);
                }
            });
        }
    }

    /// A matrix whose blocks come out of range, of another size, or
    /// differently on the second visit.
    struct Unruly {
        kind: usize,
        visits: std::cell::Cell<usize>,
    }

    impl BlockSparse for Unruly {
        fn block_size(&self) -> usize {
            2
        }
        fn block_count(&self) -> usize {
            10
        }
        fn visit_blocks(&self, visit: &mut dyn FnMut(usize, usize, &[f64])) {
            let second = self.visits.get() > 0;
            self.visits.set(self.visits.get() + 1);
            Chain(10).visit_blocks(&mut |i, j, values| match self.kind {
                0 if i == 9 && j == 9 => visit(10, 10, values),
                1 if i == 3 && j == 3 => visit(i, j, &values[..3]),
                2 if second && i == 5 && j == 5 => {}
                _ => visit(i, j, values),
            });
        }
    }

    /// A matrix that breaks `visit_blocks`' contract is refused, not a
    /// panic.
    #[test]
    fn a_matrix_breaking_the_visit_contract_is_refused() {
        for (kind, what) in [
            (0, "block index of visit_blocks"),
            (1, "block values of visit_blocks"),
            (2, "blocks visited a second time by visit_blocks"),
        ] {
            let matrix = Unruly {
                kind,
                visits: std::cell::Cell::new(0),
            };
            let mut amg =
                SmoothedAggregation::new(AggregationSettings::default(), vec![1.0; 20], 1);
            let refused = Preconditioner::<Unruly>::setup(&mut amg, &matrix);
            assert!(
                matches!(refused, Err(SolveError::DimensionMismatch { what: w, .. }) if w == what),
                "{kind}: {refused:?}"
            );
        }
    }

    /// A line whose blocks together are not positive definite is named by
    /// its index among the lines given.
    #[test]
    fn an_indefinite_line_is_named() {
        let blocks = 40;
        let settings = AggregationSettings {
            max_coarse: 4,
            ..AggregationSettings::default()
        };
        let first = LineLevel {
            aggregates: (0..blocks).map(|i| i / 4).collect(),
            lines: (0..blocks / 2).map(|l| 2 * l..2 * l + 2).collect(),
        };
        let mut amg =
            SmoothedAggregation::new(settings, vec![1.0; blocks * 2], 1).with_lines(first);
        let failure = Preconditioner::<IndefiniteAt>::setup(&mut amg, &IndefiniteAt(blocks, 13));
        assert!(
            matches!(
                failure,
                Err(SolveError::Factorization(
                    FactorizationFailure::LineNotPositiveDefinite { line: 6 }
                ))
            ),
            "{failure:?}"
        );
    }

    #[test]
    fn packed_cholesky_solve_matches_the_dense_solve() {
        let n = 7;
        let m = DMatrix::from_fn(n, n, |i, j| 1.0 / (1.0 + i as f64 + j as f64));
        let spd = &m * m.transpose() + DMatrix::identity(n, n);
        let l = spd.clone().cholesky().unwrap().unpack();
        let packed: Vec<f64> = (0..n)
            .flat_map(|i| (0..=i).map(move |j| (i, j)))
            .map(|(i, j)| l[(i, j)])
            .collect();
        let b: Vec<f64> = (0..n).map(|i| (i as f64).sin() + 2.0).collect();
        let mut x = b.clone();
        cholesky_solve(&packed, &mut x);
        let expected = spd
            .cholesky()
            .unwrap()
            .solve(&nalgebra::DVector::from_column_slice(&b));
        for (a, e) in x.iter().zip(expected.iter()) {
            assert!((a - e).abs() <= 1e-12 * e.abs().max(1.0), "{a} vs {e}");
        }
    }

    /// The V-cycle with a level of lines (smoother and prolongator by
    /// lines, residual updated by `A P`) is symmetric positive definite,
    /// with 1 and 2 sweeps, and symmetric with none (the coarse
    /// correction alone).
    #[test]
    fn a_cycle_with_lines_is_symmetric_and_positive() {
        let blocks = 40;
        let settings = AggregationSettings {
            max_coarse: 4,
            ..AggregationSettings::default()
        };
        let near_null = vec![1.0; blocks * 2];
        let first = LineLevel {
            aggregates: (0..blocks).map(|i| i / 4).collect(),
            lines: (0..blocks / 2).map(|l| 2 * l..2 * l + 2).collect(),
        };
        for sweeps in [0, 1, 2] {
            let mut amg = SmoothedAggregation::new(
                AggregationSettings { sweeps, ..settings },
                near_null.clone(),
                1,
            )
            .with_lines(first.clone());
            Preconditioner::<Chain>::setup(&mut amg, &Chain(blocks)).unwrap();
            assert!(amg.level_sizes().len() >= 2, "{:?}", amg.level_sizes());
            let u: Vec<f64> = (0..2 * blocks).map(|i| (0.3 * i as f64).cos()).collect();
            let v: Vec<f64> = (0..2 * blocks)
                .map(|i| 1.0 + (0.7 * i as f64).sin())
                .collect();
            let (mut mu, mut mv) = (vec![0.0; u.len()], vec![0.0; v.len()]);
            Preconditioner::<Chain>::apply(&amg, &u, &mut mu);
            Preconditioner::<Chain>::apply(&amg, &v, &mut mv);
            let (vmu, umv) = (dot(&v, &mu), dot(&u, &mv));
            assert!(
                (vmu - umv).abs() <= 1e-12 * vmu.abs().max(umv.abs()),
                "{vmu} vs {umv}"
            );
            assert!(dot(&u, &mu) > 0.0 && dot(&v, &mv) > 0.0);
        }
    }
}
