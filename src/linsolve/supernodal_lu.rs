//! Supernodal LU on the symmetric structure of `A + Aᵀ`, with pivoting
//! inside each supernode: the kernel of [`super::SparseLu`].
//!
//! The analysis orders `A + Aᵀ` by approximate minimum degree and takes
//! faer's supernodal Cholesky structure of it: `L` has that structure and
//! `U` its transpose. The numeric factorization is left-looking by
//! supernodes. Each supernode `s` (columns `f..e`, rows `P` below) keeps
//! the panel `[L_D\U_D; L_P]` of `(w + p) × w` values and the panel
//! `U_sPᵀ` of `p × w`; the descendants' updates are dense products; the
//! diagonal block is factored with partial pivoting restricted to its own
//! rows, `Π_s D = L_D U_D`, then `L_P = A_P U_D⁻¹` and
//! `U_sP = L_D⁻¹ Π_s A_sP`. A row exchange inside the supernode is applied
//! to the right-hand side when the forward solve reaches it, which is
//! exact because the rows exchanged belong to the supernode.
//!
//! Pivoting is bounded by the supernode: a pivot is accepted only when the
//! multipliers below it stay within `1 / τ` (threshold pivoting with
//! tolerance τ); otherwise the factorization reports a weak pivot and the
//! caller factors with cross-supernode pivoting instead.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::factor::{lu_in_place, lu_in_place_scratch};
use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_unit_lower_triangular_in_place,
};
use faer::prelude::{Reborrow, ReborrowMut};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{Pair, SymbolicSparseColMat};
use faer::{Accum, MatMut, MatRef, Par, Side};

use super::pattern::SparsePattern;
use super::{FactorizationFailure, SolveError};

const NONE: usize = usize::MAX;

/// Why a numeric factorization stopped.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Breakdown {
    /// A pivot is zero, not finite, or smaller than the tolerance times its
    /// column: pivoting across supernodes is needed.
    WeakPivot {
        /// First column (in elimination order) of the supernode.
        column: usize,
        /// Largest multiplier `|l|` it would have needed.
        multiplier: f64,
    },
}

/// The structure of the factor and where each entry of `A` goes.
#[derive(Debug, Clone)]
struct Structure {
    n: usize,
    /// `perm[i]`: the unknown eliminated at position `i`.
    perm: Vec<usize>,
    /// Column ranges of the supernodes (length: supernodes + 1).
    begin: Vec<usize>,
    /// Rows below each supernode (elimination positions, sorted).
    rows_ptr: Vec<usize>,
    rows: Vec<usize>,
    /// Offsets of the `(w + p) × w` panels of L and the `p × w` panels of Uᵀ.
    l_ptr: Vec<usize>,
    u_ptr: Vec<usize>,
    supernode_of: Vec<usize>,
    /// For each stored entry of `A`: its index in `l`, or `l.len()` plus
    /// its index in `u`.
    scatter: Vec<usize>,
    widest: usize,
}

/// A supernodal LU factor and its workspaces.
pub(crate) struct SupernodalLu {
    structure: Structure,
    l: Vec<f64>,
    u: Vec<f64>,
    /// Row order chosen inside each supernode (local indices).
    pivots: Vec<usize>,
    map: Vec<usize>,
    /// The rows of a descendant's update, as positions in the panel it
    /// updates (`map` read once per update, not once per column).
    relative: Vec<usize>,
    /// `relative` cut into runs of consecutive positions: (first row of
    /// the update, its position in the panel, length).
    runs: Vec<(usize, usize, usize)>,
    head: Vec<usize>,
    link: Vec<usize>,
    next: Vec<usize>,
    tmp: Vec<f64>,
    work: Vec<f64>,
    local_perm: Vec<usize>,
    local_perm_inv: Vec<usize>,
    lu_scratch: MemBuffer,
    /// Largest multiplier `|l|` of the last factorization.
    largest_multiplier: f64,
}

impl std::fmt::Debug for SupernodalLu {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SupernodalLu")
            .field("dimension", &self.structure.n)
            .field("supernodes", &(self.structure.begin.len() - 1))
            .field("entries", &self.entries())
            .finish_non_exhaustive()
    }
}

impl SupernodalLu {
    /// Analyse `pattern`: ordering, supernodes, panels and the destination
    /// of each stored entry.
    pub(crate) fn analyse(pattern: &SparsePattern) -> Result<Self, SolveError> {
        let structure = Structure::new(pattern)?;
        let (n, ns) = (structure.n, structure.begin.len() - 1);
        let lu_scratch = MemBuffer::try_new(lu_in_place_scratch::<usize, f64>(
            structure.widest,
            structure.widest,
            Par::Seq,
            Default::default(),
        ))
        .map_err(|e| {
            SolveError::Factorization(FactorizationFailure::Workspace {
                workspace: "LU",
                message: format!("{e:?}"),
            })
        })?;
        Ok(Self {
            l: vec![0.0; structure.l_ptr[ns]],
            u: vec![0.0; structure.u_ptr[ns]],
            pivots: vec![0; n],
            map: vec![0; n],
            relative: Vec::with_capacity(n),
            runs: Vec::new(),
            head: vec![NONE; ns],
            link: vec![NONE; ns],
            next: vec![0; ns],
            tmp: Vec::new(),
            work: vec![0.0; n],
            local_perm: vec![0; structure.widest],
            local_perm_inv: vec![0; structure.widest],
            lu_scratch,
            largest_multiplier: 0.0,
            structure,
        })
    }

    /// Stored entries of L and U (the diagonal counted once).
    pub(crate) fn entries(&self) -> usize {
        self.l.len() + self.u.len()
    }

    /// Largest multiplier `|l|` of the last factorization (at most 1
    /// inside the diagonal blocks, where pivoting keeps it so).
    pub(crate) fn largest_multiplier(&self) -> f64 {
        self.largest_multiplier
    }

    /// Factor the matrix with `values` (in the order of the analysed
    /// pattern), accepting multipliers up to `1 / tolerance`.
    pub(crate) fn factor(&mut self, values: &[f64], tolerance: f64) -> Result<(), Breakdown> {
        self.largest_multiplier = 0.0;
        let st = &self.structure;
        self.l.fill(0.0);
        self.u.fill(0.0);
        let l_len = self.l.len();
        for (&dest, &value) in st.scatter.iter().zip(values) {
            if dest < l_len {
                self.l[dest] += value;
            } else {
                self.u[dest - l_len] += value;
            }
        }
        self.head.fill(NONE);
        for s in 0..st.begin.len() - 1 {
            self.map_rows(s);
            let mut d = std::mem::replace(&mut self.head[s], NONE);
            while d != NONE {
                let following = self.link[d];
                self.update(d, s);
                d = following;
            }
            self.factor_supernode(s, tolerance)?;
            let st = &self.structure;
            if st.rows_ptr[s + 1] > st.rows_ptr[s] {
                self.next[s] = 0;
                let t = st.supernode_of[st.rows[st.rows_ptr[s]]];
                self.link[s] = self.head[t];
                self.head[t] = s;
            }
        }
        Ok(())
    }

    /// Point `map` from the rows of supernode `s` to their rows in its L
    /// panel.
    fn map_rows(&mut self, s: usize) {
        let st = &self.structure;
        let (f, e) = (st.begin[s], st.begin[s + 1]);
        for r in f..e {
            self.map[r] = r - f;
        }
        for (k, &r) in st.rows[st.rows_ptr[s]..st.rows_ptr[s + 1]]
            .iter()
            .enumerate()
        {
            self.map[r] = e - f + k;
        }
    }

    /// Subtract the contribution of descendant `d` from supernode `s`, and
    /// link `d` to the next supernode it updates.
    fn update(&mut self, d: usize, s: usize) {
        let st = &self.structure;
        let (fd, ed) = (st.begin[d], st.begin[d + 1]);
        let (f, e) = (st.begin[s], st.begin[s + 1]);
        let (wd, w) = (ed - fd, e - f);
        let rows_d = &st.rows[st.rows_ptr[d]..st.rows_ptr[d + 1]];
        let (pd, p) = (rows_d.len(), st.rows_ptr[s + 1] - st.rows_ptr[s]);
        let pos = self.next[d];
        let reach = &rows_d[pos..];
        let n1 = reach.partition_point(|&r| r < e);
        let nr = reach.len();
        let (l_before, l_after) = self.l.split_at_mut(st.l_ptr[s]);
        let (u_before, u_after) = self.u.split_at_mut(st.u_ptr[s]);
        let ld = MatRef::from_column_major_slice_with_stride(
            &l_before[st.l_ptr[d]..st.l_ptr[d + 1]],
            wd + pd,
            wd,
            wd + pd,
        )
        .subrows(wd + pos, nr);
        let ud = MatRef::from_column_major_slice_with_stride(
            &u_before[st.u_ptr[d]..st.u_ptr[d + 1]],
            pd,
            wd,
            pd,
        )
        .subrows(pos, nr);
        // Columns of s: L and the diagonal block.
        self.tmp.resize(nr * n1, 0.0);
        product(&mut self.tmp, ld, ud.subrows(0, n1));
        let ls = &mut l_after[..st.l_ptr[s + 1] - st.l_ptr[s]];
        self.relative.clear();
        self.relative.extend(reach.iter().map(|&row| self.map[row]));
        runs_of(&self.relative, 0, &mut self.runs);
        for (&at, update) in self.relative[..n1].iter().zip(self.tmp.chunks_exact(nr)) {
            // `at` is the column's place among the rows: its column in s.
            let column = &mut ls[at * (w + p)..(at + 1) * (w + p)];
            for &(from, to, len) in &self.runs {
                for (target, value) in column[to..to + len]
                    .iter_mut()
                    .zip(&update[from..from + len])
                {
                    *target -= value;
                }
            }
        }
        // Rows of s beyond its columns: U.
        let n2 = nr - n1;
        if n2 > 0 {
            self.tmp.resize(n2 * n1, 0.0);
            product(&mut self.tmp, ud.subrows(n1, n2), ld.subrows(0, n1));
            let us = &mut u_after[..st.u_ptr[s + 1] - st.u_ptr[s]];
            runs_of(&self.relative[n1..], w, &mut self.runs);
            for (&at, update) in self.relative[..n1].iter().zip(self.tmp.chunks_exact(n2)) {
                let row = &mut us[at * p..(at + 1) * p];
                for &(from, to, len) in &self.runs {
                    for (target, value) in
                        row[to..to + len].iter_mut().zip(&update[from..from + len])
                    {
                        *target -= value;
                    }
                }
            }
        }
        let next = pos + n1;
        self.next[d] = next;
        if next < pd {
            let t = st.supernode_of[rows_d[next]];
            self.link[d] = self.head[t];
            self.head[t] = d;
        }
    }

    /// Factor the diagonal block of `s` with pivoting inside it, then its
    /// L and U panels.
    fn factor_supernode(&mut self, s: usize, tolerance: f64) -> Result<(), Breakdown> {
        let st = &self.structure;
        let (f, e) = (st.begin[s], st.begin[s + 1]);
        let w = e - f;
        let p = st.rows_ptr[s + 1] - st.rows_ptr[s];
        let panel = MatMut::from_column_major_slice_mut(
            &mut self.l[st.l_ptr[s]..st.l_ptr[s + 1]],
            w + p,
            w,
        );
        let (mut diag, mut below) = panel.split_at_row_mut(w);
        let (perm, perm_inv) = (&mut self.local_perm[..w], &mut self.local_perm_inv[..w]);
        lu_in_place(
            diag.rb_mut(),
            perm,
            perm_inv,
            Par::Seq,
            MemStack::new(&mut self.lu_scratch),
            Default::default(),
        );
        let weak = |multiplier: f64| Breakdown::WeakPivot {
            column: f,
            multiplier,
        };
        for c in 0..w {
            let pivot = diag[(c, c)];
            if pivot == 0.0 || !pivot.is_finite() {
                return Err(weak(f64::INFINITY));
            }
        }
        // L_P U_D = A_P, as U_Dᵀ L_Pᵀ = A_Pᵀ.
        solve_lower_triangular_in_place(
            diag.rb().transpose(),
            below.rb_mut().transpose_mut(),
            Par::Seq,
        );
        let mut largest = 0.0f64;
        for c in 0..w {
            for v in below.rb().col(c).iter() {
                largest = largest.max(v.abs());
            }
        }
        if largest.is_nan() || largest * tolerance > 1.0 {
            return Err(weak(largest));
        }
        self.largest_multiplier = self.largest_multiplier.max(largest);
        self.pivots[f..e].copy_from_slice(perm);
        if p > 0 {
            let us = &mut self.u[st.u_ptr[s]..st.u_ptr[s + 1]];
            // Π_s A_sP: the rows of A_sP are the columns of the Uᵀ panel.
            if perm.iter().enumerate().any(|(c, &from)| c != from) {
                self.tmp.clear();
                self.tmp.extend_from_slice(us);
                for (c, &from) in perm.iter().enumerate() {
                    us[c * p..(c + 1) * p].copy_from_slice(&self.tmp[from * p..(from + 1) * p]);
                }
            }
            let panel = MatMut::from_column_major_slice_mut(us, p, w);
            solve_unit_lower_triangular_in_place(diag.rb(), panel.transpose_mut(), Par::Seq);
        }
        Ok(())
    }

    /// Overwrite `x` (holding `b`) with the solution of `A x = b`.
    pub(crate) fn solve_in_place(&mut self, x: &mut [f64]) {
        let st = &self.structure;
        let y = &mut self.work;
        for (yi, &from) in y.iter_mut().zip(&st.perm) {
            *yi = x[from];
        }
        let ns = st.begin.len() - 1;
        self.tmp.resize(st.widest, 0.0);
        for s in 0..ns {
            let (f, e) = (st.begin[s], st.begin[s + 1]);
            let w = e - f;
            let rows = &st.rows[st.rows_ptr[s]..st.rows_ptr[s + 1]];
            let ld = w + rows.len();
            let ls = &self.l[st.l_ptr[s]..st.l_ptr[s + 1]];
            for (c, &from) in self.pivots[f..e].iter().enumerate() {
                self.tmp[c] = y[f + from];
            }
            y[f..e].copy_from_slice(&self.tmp[..w]);
            for c in 0..w {
                let yc = y[f + c];
                if yc == 0.0 {
                    continue;
                }
                let col = &ls[c * ld..(c + 1) * ld];
                for r in c + 1..w {
                    y[f + r] -= col[r] * yc;
                }
                for (&row, &l) in rows.iter().zip(&col[w..]) {
                    y[row] -= l * yc;
                }
            }
        }
        for s in (0..ns).rev() {
            let (f, e) = (st.begin[s], st.begin[s + 1]);
            let w = e - f;
            let rows = &st.rows[st.rows_ptr[s]..st.rows_ptr[s + 1]];
            let (p, ld) = (rows.len(), w + rows.len());
            let ls = &self.l[st.l_ptr[s]..st.l_ptr[s + 1]];
            let us = &self.u[st.u_ptr[s]..st.u_ptr[s + 1]];
            for c in 0..w {
                let sum: f64 = rows
                    .iter()
                    .zip(&us[c * p..(c + 1) * p])
                    .map(|(&row, &u)| u * y[row])
                    .sum();
                y[f + c] -= sum;
            }
            for c in (0..w).rev() {
                let col = &ls[c * ld..c * ld + w];
                y[f + c] /= col[c];
                let yc = y[f + c];
                for r in 0..c {
                    y[f + r] -= col[r] * yc;
                }
            }
        }
        for (yi, &to) in y.iter().zip(&st.perm) {
            x[to] = *yi;
        }
    }
}

/// Cut `positions` (increasing) into runs of consecutive values, each
/// `(index in positions, its value − offset, length)`, into `runs`.
fn runs_of(positions: &[usize], offset: usize, runs: &mut Vec<(usize, usize, usize)>) {
    runs.clear();
    let mut start = 0;
    for k in 1..=positions.len() {
        if k == positions.len() || positions[k] != positions[k - 1] + 1 {
            runs.push((start, positions[start] - offset, k - start));
            start = k;
        }
    }
}

/// `out = a bᵀ`, column-major `a.nrows() × b.nrows()` (faer's matmul; a
/// plain loop measured no faster on the small products of the DDA).
fn product(out: &mut [f64], a: MatRef<'_, f64>, b: MatRef<'_, f64>) {
    let dst = MatMut::from_column_major_slice_mut(out, a.nrows(), b.nrows());
    matmul(dst, Accum::Replace, a, b.transpose(), 1.0, Par::Seq);
}

impl Structure {
    fn new(pattern: &SparsePattern) -> Result<Self, SolveError> {
        let n = pattern.dimension();
        let failed = |stage: &'static str, e: &dyn std::fmt::Debug| {
            SolveError::Factorization(FactorizationFailure::Analysis {
                stage,
                message: format!("{e:?}"),
            })
        };
        // The lower triangle of the pattern of A + Aᵀ, with the diagonal.
        let (col_ptr, row_idx) = (pattern.col_ptr(), pattern.row_idx());
        let mut pairs = Vec::with_capacity(n + row_idx.len());
        for j in 0..n {
            pairs.push(Pair { row: j, col: j });
            for &i in &row_idx[col_ptr[j]..col_ptr[j + 1]] {
                pairs.push(Pair {
                    row: i.max(j),
                    col: i.min(j),
                });
            }
        }
        let (lower, _) = SymbolicSparseColMat::try_new_from_indices(n, n, &pairs)
            .map_err(|e| failed("symbolic LU analysis, pattern of A + Aᵀ", &e))?;
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let symbolic =
            factorize_symbolic_cholesky(lower.rb(), Side::Lower, SymmetricOrdering::Amd, params)
                .map_err(|e| failed("symbolic LU analysis, ordering and supernodes", &e))?;
        let SymbolicCholeskyRaw::Supernodal(supernodal) = symbolic.raw() else {
            return Err(failed(
                "symbolic LU analysis, supernodes",
                &"a simplicial structure was returned",
            ));
        };
        let (perm, perm_inv) = match symbolic.perm() {
            Some(p) => (p.arrays().0.to_vec(), p.arrays().1.to_vec()),
            None => ((0..n).collect(), (0..n).collect()),
        };
        let ns = supernodal.n_supernodes();
        let mut begin: Vec<usize> = supernodal.supernode_begin().to_vec();
        begin.push(n);
        let (mut rows_ptr, mut rows) = (vec![0], Vec::new());
        let (mut l_ptr, mut u_ptr) = (vec![0], vec![0]);
        let mut supernode_of = vec![0; n];
        let mut widest = 1;
        for s in 0..ns {
            let start = rows.len();
            rows.extend_from_slice(supernodal.supernode(s).pattern());
            rows[start..].sort_unstable();
            rows_ptr.push(rows.len());
            let (w, p) = (begin[s + 1] - begin[s], rows.len() - start);
            l_ptr.push(l_ptr[s] + (w + p) * w);
            u_ptr.push(u_ptr[s] + p * w);
            supernode_of[begin[s]..begin[s + 1]].fill(s);
            widest = widest.max(w);
        }
        let mut structure = Self {
            n,
            perm,
            begin,
            rows_ptr,
            rows,
            l_ptr,
            u_ptr,
            supernode_of,
            scatter: Vec::with_capacity(row_idx.len()),
            widest,
        };
        for j in 0..n {
            for &i in &row_idx[col_ptr[j]..col_ptr[j + 1]] {
                let dest = structure
                    .destination(perm_inv[i], perm_inv[j])
                    .ok_or_else(|| failed("symbolic LU analysis, scatter", &(i, j)))?;
                structure.scatter.push(dest);
            }
        }
        Ok(structure)
    }

    /// Where entry `(i, j)` (elimination positions) is stored: an index in
    /// `l`, or the length of `l` plus an index in `u`.
    fn destination(&self, i: usize, j: usize) -> Option<usize> {
        let panel_row = |s: usize, r: usize| -> Option<usize> {
            let (f, e) = (self.begin[s], self.begin[s + 1]);
            if r < e {
                return Some(r - f);
            }
            let rows = &self.rows[self.rows_ptr[s]..self.rows_ptr[s + 1]];
            rows.binary_search(&r).ok().map(|k| e - f + k)
        };
        if i >= j {
            let s = self.supernode_of[j];
            let (f, e) = (self.begin[s], self.begin[s + 1]);
            let ld = e - f + self.rows_ptr[s + 1] - self.rows_ptr[s];
            return Some(self.l_ptr[s] + (j - f) * ld + panel_row(s, i)?);
        }
        let s = self.supernode_of[i];
        let (f, e) = (self.begin[s], self.begin[s + 1]);
        let p = self.rows_ptr[s + 1] - self.rows_ptr[s];
        if j < e {
            return Some(self.l_ptr[s] + (j - f) * (e - f + p) + (i - f));
        }
        let k = panel_row(s, j)? - (e - f);
        let l_len = self.l_ptr[self.l_ptr.len() - 1];
        Some(l_len + self.u_ptr[s] + (i - f) * p + k)
    }
}
