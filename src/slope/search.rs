//! The search: every trial of a family evaluated by Hovland's method (or
//! Bishop's, [`SearchSettings::method`]), in
//! parallel and streaming, keeping for each cell the lowest Fs of any
//! trial surface with a column there (Scoops3D's map, Reid, Christian &
//! Brien, USGS 2015) and the few most critical surfaces.
//!
//! **Memory** does not grow with the number of trials: the trials are
//! dealt, batch after batch, to a fixed number of partial results (two per
//! thread of the current rayon pool), each holding per-cell minima (40
//! bytes a cell), the `critical` best surfaces and one column buffer.
//!
//! **Determinism.** Each trial is made from its index alone and evaluated
//! by one worker in a fixed order, so its Fs does not depend on the
//! threads. The partial results are merged by a total order, the lower Fs
//! first and, for equal Fs, the lower trial index: the minimum of a set
//! under a total order is one element whatever the order it is taken in,
//! so the maps and the critical list are bit-identical for any number of
//! threads and any dealing of the trials.

use rayon::prelude::*;

use crate::error::{require_positive, Result};

use super::bishop::BishopSettings;
use super::family::TrialFamily;
use super::ground::ToGround;
use super::hovland::{Evaluator, Method, SurfaceFs};
use super::material::SlopeLoads;
use super::surface::{Refusal, SlipColumn, SurfaceLimits};
use super::terrain::Terrain;

/// Settings of a search.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SearchSettings {
    /// Limits on the surfaces kept.
    pub limits: SurfaceLimits,
    /// How many of the most critical surfaces to keep (0 for none).
    pub critical: usize,
    /// Trials per batch (≥ 1): the progress callback is called after each.
    pub batch: u64,
    /// The limit-equilibrium method each surface is evaluated by.
    pub method: Method,
    /// Bishop's settings (its `m_α` floor), taken where `method` is
    /// [`Method::Bishop`].
    pub bishop: BishopSettings,
}

impl Default for SearchSettings {
    /// Default limits, the 10 most critical surfaces, batches of 20 000
    /// trials, Hovland's method (Bishop's with its default `m_α` floor
    /// 0.2, where chosen).
    fn default() -> Self {
        Self {
            limits: SurfaceLimits::default(),
            critical: 10,
            batch: 20_000,
            method: Method::Hovland,
            bishop: BishopSettings::default(),
        }
    }
}

/// The lowest Fs found at a cell and the surface that gave it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellMinimum {
    /// The lowest Fs of any trial surface with a column at the cell.
    pub safety_factor: f64,
    /// Index of that trial in its family.
    pub trial: u64,
    /// Its volume (m³).
    pub volume: f64,
    /// Its plan area (m²).
    pub area: f64,
    /// Its depth (m).
    pub depth: f64,
}

impl CellMinimum {
    const NONE: Self = Self {
        safety_factor: f64::INFINITY,
        trial: u64::MAX,
        volume: 0.0,
        area: 0.0,
        depth: 0.0,
    };

    fn is_some(&self) -> bool {
        self.trial != u64::MAX
    }

    /// Whether `self` comes before `other`: the lower Fs, then the lower
    /// trial index.
    fn before(&self, other: &Self) -> bool {
        (self.safety_factor, self.trial) < (other.safety_factor, other.trial)
    }
}

/// One of the most critical surfaces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CriticalSurface<S> {
    /// Index of the trial in its family.
    pub trial: u64,
    /// The surface.
    pub surface: S,
    /// Its Fs and what it is made of.
    pub result: SurfaceFs,
}

impl<S> CriticalSurface<S> {
    fn key(&self) -> (f64, u64) {
        (self.result.safety_factor, self.trial)
    }
}

/// How many trials gave an Fs and how many were refused, by reason.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SearchCounts {
    /// Trials in the family.
    pub trials: u64,
    /// Trials that gave an Fs.
    pub evaluated: u64,
    /// Trials refused, indexed by [`Refusal::index`].
    pub refused: [u64; Refusal::ALL.len()],
}

impl SearchCounts {
    /// Trials refused for `reason`.
    pub fn refused_for(&self, reason: Refusal) -> u64 {
        self.refused[reason.index()]
    }

    fn merge(&mut self, other: &Self) {
        self.evaluated += other.evaluated;
        for (a, b) in self.refused.iter_mut().zip(other.refused) {
            *a += b;
        }
    }
}

/// What a search found.
#[derive(Debug, Clone, PartialEq)]
pub struct SearchResult<S> {
    pub(super) rows: usize,
    pub(super) columns: usize,
    pub(super) lower_left: (f64, f64),
    pub(super) cell_size: f64,
    pub(super) minima: Vec<CellMinimum>,
    /// The most critical surfaces, lowest Fs first (ties: lower index).
    pub critical: Vec<CriticalSurface<S>>,
    /// Trials evaluated and refused.
    pub counts: SearchCounts,
}

impl<S> SearchResult<S> {
    /// The lowest Fs of cell (row, column) and the surface that gave it;
    /// `None` where no trial surface had a column.
    pub fn cell(&self, row: usize, column: usize) -> Option<&CellMinimum> {
        if row < self.rows && column < self.columns {
            let m = &self.minima[row * self.columns + column];
            m.is_some().then_some(m)
        } else {
            None
        }
    }

    /// The most critical surface found, if any.
    pub fn lowest(&self) -> Option<&CriticalSurface<S>> {
        self.critical.first()
    }

    /// The lowest Fs over the whole grid, if any trial gave one (known even
    /// where no critical surface is kept).
    pub fn lowest_safety_factor(&self) -> Option<f64> {
        self.minima
            .iter()
            .filter(|m| m.is_some())
            .map(|m| m.safety_factor)
            .reduce(f64::min)
    }
}

/// A worker's share: per-cell minima (allocated at its first Fs), the best
/// surfaces and the counts.
struct Partial<S> {
    /// Grid columns, for the cell index of a column.
    columns: usize,
    minima: Vec<CellMinimum>,
    critical: Vec<CriticalSurface<S>>,
    counts: SearchCounts,
    scratch: Vec<SlipColumn>,
}

impl<S: Copy> Partial<S> {
    fn new(columns: usize) -> Self {
        Self {
            columns,
            minima: Vec::new(),
            critical: Vec::new(),
            counts: SearchCounts::default(),
            scratch: Vec::new(),
        }
    }

    fn record(&mut self, cells: usize, keep: usize, trial: u64, surface: S, result: SurfaceFs) {
        self.counts.evaluated += 1;
        if self.minima.is_empty() {
            self.minima = vec![CellMinimum::NONE; cells];
        }
        let candidate = CellMinimum {
            safety_factor: result.safety_factor,
            trial,
            volume: result.volume,
            area: result.area,
            depth: result.depth,
        };
        for k in &self.scratch {
            let m = &mut self.minima[k.row * self.columns + k.column];
            if candidate.before(m) {
                *m = candidate;
            }
        }
        if keep > 0 {
            let entry = CriticalSurface {
                trial,
                surface,
                result,
            };
            let at = self.critical.partition_point(|c| c.key() < entry.key());
            if at < keep {
                self.critical.insert(at, entry);
                self.critical.truncate(keep);
            }
        }
    }

    fn merge(&mut self, other: Partial<S>, keep: usize) {
        self.counts.merge(&other.counts);
        if self.minima.is_empty() {
            self.minima = other.minima;
        } else if !other.minima.is_empty() {
            for (a, b) in self.minima.iter_mut().zip(&other.minima) {
                if b.before(a) {
                    *a = *b;
                }
            }
        }
        self.critical.extend(other.critical);
        self.critical
            .sort_by(|a, b| a.key().partial_cmp(&b.key()).expect("finite Fs"));
        self.critical.truncate(keep);
    }
}

/// Search the trial surfaces of `family` over `terrain` by Hovland's
/// method ([`super::hovland_ground`]), or Bishop's where
/// [`SearchSettings::method`] says so ([`super::bishop_ground`]), on
/// `ground` (one material,
/// `&SlopeMaterial`, or a layered [`super::Ground`] with an optional
/// pore-pressure ratio), in parallel on the current rayon
/// pool (install a `rayon::ThreadPool` to choose the threads), calling
/// `progress(done, total)` on the caller's thread after each batch of
/// [`SearchSettings::batch`] trials (hook a progress bar there).
///
/// # Errors
/// Those of [`Evaluator::new`] (ground, loads, limits);
/// [`crate::error::DismechError::InvalidParameter`] for a batch of 0
/// trials or a family with no trial over the terrain.
pub fn search<F: TrialFamily>(
    terrain: &Terrain,
    ground: &(impl ToGround + ?Sized),
    loads: &SlopeLoads,
    family: &F,
    settings: &SearchSettings,
    mut progress: impl FnMut(u64, u64),
) -> Result<SearchResult<F::Surface>> {
    let evaluator = Evaluator::new(terrain, ground, loads, &settings.limits)?
        .with_method(settings.method)
        .with_bishop(settings.bishop);
    family.validate()?;
    require_positive("search batch (trials)", settings.batch as f64)?;
    let total = family.len(terrain);
    require_positive("number of trials of the search family", total as f64)?;
    let (rows, columns) = (terrain.rows(), terrain.columns());
    let cells = rows * columns;
    let keep = settings.critical;
    let workers = 2 * rayon::current_num_threads().max(1);
    let mut partials: Vec<Partial<F::Surface>> =
        (0..workers).map(|_| Partial::new(columns)).collect();
    let mut done = 0u64;
    while done < total {
        let end = total.min(done.saturating_add(settings.batch));
        let start = done;
        partials.par_iter_mut().enumerate().for_each(|(j, part)| {
            let mut index = start + j as u64;
            while index < end {
                let outcome = family.trial(terrain, index).and_then(|surface| {
                    let mut scratch = std::mem::take(&mut part.scratch);
                    let r = evaluator.evaluate(&surface, &mut scratch);
                    part.scratch = scratch;
                    r.map(|fs| (surface, fs))
                });
                match outcome {
                    Ok((surface, fs)) => part.record(cells, keep, index, surface, fs),
                    Err(reason) => part.counts.refused[reason.index()] += 1,
                }
                index += workers as u64;
            }
        });
        done = end;
        progress(done, total);
    }
    let mut all = Partial::new(columns);
    for part in partials {
        all.merge(part, keep);
    }
    let mut counts = all.counts;
    counts.trials = total;
    let minima = if all.minima.is_empty() {
        vec![CellMinimum::NONE; cells]
    } else {
        all.minima
    };
    Ok(SearchResult {
        rows,
        columns,
        lower_left: terrain.dem().raster.lower_left(),
        cell_size: terrain.cell_size(),
        minima,
        critical: all.critical,
        counts,
    })
}
