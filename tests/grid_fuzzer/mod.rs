//! A mutational fuzzer of the grid reader ([`parse_esri_ascii`]) and of the
//! slope-grid loader ([`SlopeGrids`]), shared by `tests/grid_fuzz.rs` (a
//! few thousand cases in `cargo test`) and `examples/fuzz_grids.rs` (10^6
//! and more).
//!
//! Each case starts from a valid seed (the grids of `examples/data` and a
//! few small grids built here), changes it and runs the reader or the
//! loader on it under [`std::panic::catch_unwind`]:
//!
//! - text mutations: byte flips, a token replaced by a huge, negative,
//!   fractional, NaN or malformed number, lines dropped, duplicated or
//!   swapped, truncation, tokens inserted or deleted, header keys mangled,
//!   and huge headers on purpose: `ncols`/`nrows` set to huge values, or to
//!   a pair whose product wraps around 2^64 to exactly the number of values
//!   in the file (the most dangerous header: accepted by a reader that
//!   multiplies unchecked);
//! - for the loader, grids changed as grids before being written: cropped
//!   (at times each file differently), holes of NODATA, a corner shifted, a
//!   cell size changed, the slip surface lifted above the ground, the water
//!   table dropped; then, half of the time, text mutations on one file.
//!
//! A case is a function of (seed, index) alone, so any case can be replayed.
//! A process abort (a failed allocation) cannot be caught in the process;
//! instead every case is measured with a counting allocator and its peak
//! memory must stay below [`memory_bound`] of the input's length, and a
//! header that claims more than [`MAX_GRID_CELLS`] cells must be refused.

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::panic::{self, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::Once;

use dismech::error::{DismechError, Result};
use dismech::grid::{parse_esri_ascii, read_esri_ascii, to_esri_ascii, Raster, MAX_GRID_CELLS};
use dismech::hpm::{NamedRaster, SlopeGrids};
use rand::rngs::StdRng;
use rand::seq::IndexedRandom;
use rand::{RngExt, SeedableRng};

/// The most memory a case may hold at once: 64 bytes per byte of input
/// plus 64 KiB. The reader keeps the text's tokens of one line (32 bytes a
/// token, at least 2 bytes of text a token) and the values read so far (16
/// bytes a value); a reader that sized anything by the header alone would
/// exceed this on the huge headers.
pub fn memory_bound(input_bytes: usize) -> u64 {
    64 * input_bytes as u64 + 64 * 1024
}

/// Numbers that break careless readers, used to replace tokens.
const NASTY: &[&str] = &[
    "0",
    "1",
    "-1",
    "+1",
    "-0",
    "2",
    "3",
    "24",
    "32",
    "768",
    "10000",
    "10001",
    "100000000",
    "100000001",
    "2147483647",
    "2147483648",
    "4294967295",
    "4294967296",
    "4294967297",
    "9223372036854775807",
    "9223372036854775808",
    "18446744073709551615",
    "18446744073709551616",
    "340282366920938463463374607431768211457",
    "274177",
    "67280421310721",
    "1e30",
    "1e308",
    "1e309",
    "-1e308",
    "1.7976931348623157e308",
    "1e-320",
    "5e-324",
    "0.5",
    "24.0",
    "2.4e1",
    "-24",
    "NaN",
    "nan",
    "-nan",
    "inf",
    "-inf",
    "infinity",
    "+inf",
    "-9999",
    "0x18",
    "1_000",
    "1,5",
    "--1",
    ".",
    "e",
    "-",
    "\u{661}\u{662}",
    "\u{221e}",
];

/// Pairs (ncols, nrows) whose product overflows 64 bits.
const WRAPPING_PAIRS: &[(u64, u64)] = &[
    // 2^64 + 1: wraps to 1 cell.
    (274_177, 67_280_421_310_721),
    // 2^64: wraps to 0.
    (4_294_967_296, 4_294_967_296),
    // 2^64 - 1 = usize::MAX on 64 bits.
    (4_294_967_297, 4_294_967_295),
    (2_147_483_648, 2_147_483_648),
];

const HEADER_KEYS: &[&str] = &[
    "ncols",
    "nrows",
    "xllcorner",
    "xllcenter",
    "yllcorner",
    "yllcenter",
    "cellsize",
    "nodata_value",
];

/// What a case runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Target {
    /// [`parse_esri_ascii`] on one text.
    Reader,
    /// [`parse_esri_ascii`] on two or three texts, then [`SlopeGrids::new`].
    Loader,
    /// The same from files: [`SlopeGrids::read`].
    LoaderFromFiles,
}

/// The seeds: single grid texts for the reader, grid sets for the loader.
pub struct Seeds {
    texts: Vec<String>,
    sets: Vec<(Raster, Raster, Option<Raster>)>,
}

impl Seeds {
    /// The grids of `examples/data` and a few small grids.
    pub fn new() -> Self {
        let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/data");
        let ground = read_esri_ascii(&data.join("hpm_ground.asc")).expect("shipped ground grid");
        let slip = read_esri_ascii(&data.join("hpm_slip.asc")).expect("shipped slip grid");
        let plane = |z0: f64, dz: f64| {
            Raster::from_fn(5, 4, 100.0, 200.0, 2.5, move |x, y| {
                Some(z0 + 0.2 * (x - 100.0) + dz * (y - 200.0))
            })
            .expect("small seed grid")
        };
        let holed = Raster::from_fn(4, 3, 0.0, 0.0, 1.0, |x, y| {
            (x > 1.0 || y > 1.0).then_some(x + y)
        })
        .expect("seed grid with holes");
        let texts = vec![
            std::fs::read_to_string(data.join("hpm_ground.asc")).expect("shipped grid"),
            std::fs::read_to_string(data.join("hpm_slip.asc")).expect("shipped grid"),
            "NCOLS 3\nnrows 2\nxllcenter 5.0\nyllcorner 100\ncellsize 10\nNODATA_value -9999\n1 2 -9999\n4 5.5 6\n".to_string(),
            "ncols 1\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n7\n".to_string(),
            "ncols 4\nnrows 1\nxllcorner -10\nyllcenter 0.5\ncellsize 1\nNODATA_value nan\n1 nan 3 4\n"
                .to_string(),
            to_esri_ascii(&holed),
        ];
        let sets = vec![
            (ground, slip, None),
            (plane(50.0, 0.3), plane(45.0, 0.3), Some(plane(47.0, 0.3))),
            (plane(50.0, -0.1), plane(49.0, 0.1), None),
        ];
        Self { texts, sets }
    }
}

impl Default for Seeds {
    fn default() -> Self {
        Self::new()
    }
}

/// Counts over a run.
#[derive(Debug, Default, Clone)]
pub struct Stats {
    /// Cases run.
    pub cases: u64,
    /// Cases by target.
    pub by_target: BTreeMap<String, u64>,
    /// Cases whose every file was read and, for the loader, whose grids were
    /// accepted.
    pub accepted: u64,
    /// Accepted cases by target.
    pub accepted_by_target: BTreeMap<String, u64>,
    /// Cases refused, by error kind (the variant of [`DismechError`]).
    pub refused: BTreeMap<String, u64>,
    /// Cases that panicked.
    pub panics: u64,
    /// The first panics: case index and message.
    pub panic_examples: Vec<(u64, String)>,
    /// Cases with a file whose header claims more than [`MAX_GRID_CELLS`]
    /// cells (`ncols × nrows` read as numbers, both at least 1).
    pub huge_claims: u64,
    /// Of those, cases accepted (must be 0).
    pub huge_claims_accepted: u64,
    /// Cases whose peak memory exceeded [`memory_bound`] (must be 0).
    pub over_memory_bound: u64,
    /// The first such cases: index, peak bytes, input bytes.
    pub memory_examples: Vec<(u64, u64, usize)>,
    /// The largest peak memory of a case (bytes).
    pub largest_peak: u64,
    /// The largest ratio of a case's peak memory to its [`memory_bound`].
    pub largest_share_of_bound: f64,
}

impl Stats {
    /// Add the counts of `other` (a run over other case indices).
    #[allow(dead_code)] // used by examples/fuzz_grids.rs, not by the test
    pub fn merge(&mut self, other: Stats) {
        self.cases += other.cases;
        for (k, v) in other.by_target {
            *self.by_target.entry(k).or_default() += v;
        }
        self.accepted += other.accepted;
        for (k, v) in other.accepted_by_target {
            *self.accepted_by_target.entry(k).or_default() += v;
        }
        for (k, v) in other.refused {
            *self.refused.entry(k).or_default() += v;
        }
        self.panics += other.panics;
        self.panic_examples.extend(other.panic_examples);
        self.panic_examples.truncate(5);
        self.huge_claims += other.huge_claims;
        self.huge_claims_accepted += other.huge_claims_accepted;
        self.over_memory_bound += other.over_memory_bound;
        self.memory_examples.extend(other.memory_examples);
        self.memory_examples.truncate(5);
        self.largest_peak = self.largest_peak.max(other.largest_peak);
        self.largest_share_of_bound = self
            .largest_share_of_bound
            .max(other.largest_share_of_bound);
    }

    /// Whether the run found nothing wrong: no panic, no huge header
    /// accepted, no case over the memory bound.
    pub fn clean(&self) -> bool {
        self.panics == 0 && self.huge_claims_accepted == 0 && self.over_memory_bound == 0
    }

    /// A table of the counts.
    pub fn report(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "cases                     {}", self.cases);
        for (k, v) in &self.by_target {
            let _ = writeln!(s, "  {k:<24}{v}");
        }
        let _ = writeln!(s, "accepted                  {}", self.accepted);
        for (k, v) in &self.accepted_by_target {
            let _ = writeln!(s, "  {k:<24}{v}");
        }
        let refused: u64 = self.refused.values().sum();
        let _ = writeln!(s, "refused                   {refused}");
        for (k, v) in &self.refused {
            let _ = writeln!(s, "  {k:<24}{v}");
        }
        let _ = writeln!(s, "panics                    {}", self.panics);
        for (case, message) in &self.panic_examples {
            let _ = writeln!(s, "  case {case}: {message}");
        }
        let _ = writeln!(
            s,
            "headers claiming > {MAX_GRID_CELLS} cells  {} (accepted: {})",
            self.huge_claims, self.huge_claims_accepted
        );
        let _ = writeln!(
            s,
            "largest peak memory       {} bytes (at most {:.0} % of a case's bound, 64 bytes per input byte + 64 KiB)",
            self.largest_peak,
            100.0 * self.largest_share_of_bound
        );
        let _ = writeln!(s, "cases over the bound      {}", self.over_memory_bound);
        for (case, peak, input) in &self.memory_examples {
            let _ = writeln!(s, "  case {case}: {peak} bytes for {input} bytes of input");
        }
        s
    }
}

/// The variant of an error, as a count key.
fn kind(error: &DismechError) -> String {
    let first = |debug: String| {
        debug
            .split(|c: char| !c.is_alphanumeric())
            .next()
            .unwrap_or("")
            .to_string()
    };
    match error {
        // The grid-file errors, as `GridFormat`, `GridHeader`, ...
        DismechError::Grid(grid) => format!("Grid{}", first(format!("{grid:?}"))),
        // The HPM and slope-search errors under their own names, as
        // `NoValidColumn`, `GridTooSmall`, ...
        DismechError::Hpm(hpm) => first(format!("{hpm:?}")),
        DismechError::Slope(slope) => first(format!("{slope:?}")),
        other => first(format!("{other:?}")),
    }
}

thread_local! {
    /// Set while this thread runs fuzz cases: its panics are recorded here
    /// instead of being printed.
    static CAUGHT: RefCell<Option<Option<String>>> = const { RefCell::new(None) };
}

/// Install (once) a panic hook that records the panics of fuzzing threads
/// and leaves the others to the previous hook.
fn install_panic_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            let recorded = CAUGHT.with(|c| match c.borrow_mut().as_mut() {
                Some(slot) => {
                    let message = info
                        .payload()
                        .downcast_ref::<&str>()
                        .map(|s| s.to_string())
                        .or_else(|| info.payload().downcast_ref::<String>().cloned())
                        .unwrap_or_default();
                    let at = info
                        .location()
                        .map(|l| format!(" at {}:{}", l.file(), l.line()))
                        .unwrap_or_default();
                    *slot = Some(format!("{message}{at}"));
                    true
                }
                None => false,
            });
            if !recorded {
                previous(info);
            }
        }));
    });
}

/// Run `f`, giving the message and place of a panic in it instead of the
/// panic. The hook that records it is installed once and never removed;
/// it leaves the panics of other threads, and of this one outside such a
/// call, to the hook before it, so that the other tests of a binary keep
/// their messages.
pub fn catch_panic<T>(f: impl FnOnce() -> T) -> std::result::Result<T, String> {
    install_panic_hook();
    CAUGHT.with(|c| *c.borrow_mut() = Some(None));
    let caught = panic::catch_unwind(AssertUnwindSafe(f));
    let message = CAUGHT.with(|c| c.borrow_mut().take()).flatten();
    caught.map_err(|_| message.unwrap_or_else(|| "panic without a message".to_string()))
}

/// Byte spans of the whitespace-separated tokens of `text`.
fn tokens(text: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, b) in text.iter().chain(std::iter::once(&b' ')).enumerate() {
        match (b.is_ascii_whitespace(), start) {
            (false, None) => start = Some(i),
            (true, Some(s)) => {
                out.push((s, i));
                start = None;
            }
            _ => {}
        }
    }
    out
}

/// Byte spans of the lines of `text` (without their line feed).
fn lines(text: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = 0;
    for (i, &b) in text.iter().enumerate() {
        if b == b'\n' {
            out.push((start, i));
            start = i + 1;
        }
    }
    if start < text.len() {
        out.push((start, text.len()));
    }
    out
}

/// The header as the reader sees it: (key, value span) pairs up to the
/// first token that is not a key.
fn header_spans(text: &[u8]) -> Vec<(String, (usize, usize))> {
    let spans = tokens(text);
    let mut out = Vec::new();
    let mut k = 0;
    while k + 1 < spans.len() {
        let (s, e) = spans[k];
        let key = String::from_utf8_lossy(&text[s..e]).to_ascii_lowercase();
        if !HEADER_KEYS.contains(&key.as_str()) {
            break;
        }
        out.push((key, spans[k + 1]));
        k += 2;
    }
    out
}

/// The number of cells the header claims, when `ncols` and `nrows` both
/// read as numbers of at least 1.
///
/// Read here independently of the reader, with its rules: keys in any case,
/// each followed by its value, tokens split at any white space.
fn claimed_cells(text: &[u8]) -> Option<f64> {
    let text = String::from_utf8_lossy(text);
    let mut tokens = text.split_whitespace();
    let (mut columns, mut rows) = (None, None);
    while let Some(key) = tokens.next() {
        let key = key.to_ascii_lowercase();
        if !HEADER_KEYS.contains(&key.as_str()) {
            break;
        }
        let value = tokens.next()?.parse::<f64>().ok();
        match key.as_str() {
            "ncols" => columns = columns.or(value),
            "nrows" => rows = rows.or(value),
            _ => {}
        }
    }
    let (columns, rows) = (columns?, rows?);
    (columns >= 1.0 && rows >= 1.0).then_some(columns * rows)
}

fn replace(text: &mut Vec<u8>, (s, e): (usize, usize), with: &str) {
    text.splice(s..e, with.bytes());
}

/// The inverse of an odd number modulo 2^64 (Newton's iteration).
fn inverse_mod_2_64(odd: u64) -> u64 {
    let mut x = odd;
    for _ in 0..6 {
        x = x.wrapping_mul(2u64.wrapping_sub(odd.wrapping_mul(x)));
    }
    x
}

/// Set the value of header key `key` (the first one) to `value`.
fn set_header(text: &mut Vec<u8>, key: &str, value: &str) {
    if let Some((_, span)) = header_spans(text).into_iter().find(|(k, _)| k == key) {
        replace(text, span, value);
    }
}

/// One random change of the text.
fn mutate(rng: &mut StdRng, text: &mut Vec<u8>) {
    let nasty = |rng: &mut StdRng| -> String {
        match rng.random_range(0..10) {
            0 => rng.random::<u64>().to_string(),
            1 => format!("{}", f64::from_bits(rng.random::<u64>())),
            2 => format!("{:e}", rng.random_range(-1e12..1e12)),
            _ => NASTY.choose(rng).copied().unwrap_or("0").to_string(),
        }
    };
    match rng.random_range(0..16) {
        // A byte flipped.
        0 if !text.is_empty() => {
            let at = rng.random_range(0..text.len());
            text[at] = match rng.random_range(0..4) {
                0 => rng.random(),
                _ => *b"0123456789-+.eE \n\tnaNiIfx\r\0"
                    .choose(rng)
                    .unwrap_or(&b'0'),
            };
        }
        // A token replaced by a nasty number.
        1 | 2 => {
            let spans = tokens(text);
            if let Some(&span) = spans.choose(rng) {
                let with = nasty(rng);
                replace(text, span, &with);
            }
        }
        // Huge header: ncols and/or nrows set to huge or nasty values.
        3 | 4 => {
            let with = nasty(rng);
            let key = if rng.random_bool(0.5) {
                "ncols"
            } else {
                "nrows"
            };
            set_header(text, key, &with);
            if rng.random_bool(0.5) {
                let other = if key == "ncols" { "nrows" } else { "ncols" };
                let with = nasty(rng);
                set_header(text, other, &with);
            }
        }
        // Huge header whose product wraps around 2^64, to the number of
        // values in the file or to a known small number.
        5 | 6 => {
            let header = header_spans(text);
            let values = tokens(text).len().saturating_sub(2 * header.len()) as u64;
            let (c, r) = if rng.random_bool(0.3) {
                *WRAPPING_PAIRS.choose(rng).unwrap_or(&WRAPPING_PAIRS[0])
            } else {
                let c = rng.random::<u64>() | 1;
                (c, values.wrapping_mul(inverse_mod_2_64(c)))
            };
            let (c, r) = if rng.random_bool(0.5) { (c, r) } else { (r, c) };
            set_header(text, "ncols", &c.to_string());
            set_header(text, "nrows", &r.to_string());
        }
        // Another header value replaced (cell size, corner, NODATA).
        7 => {
            let header = header_spans(text);
            if let Some((_, span)) = header.choose(rng) {
                let with = nasty(rng);
                replace(text, *span, &with);
            }
        }
        // A line dropped.
        8 => {
            let ls = lines(text);
            if let Some(&(s, e)) = ls.choose(rng) {
                text.drain(s..(e + 1).min(text.len()));
            }
        }
        // A line duplicated.
        9 => {
            let ls = lines(text);
            if let Some(&(s, e)) = ls.choose(rng) {
                let mut copy = text[s..e].to_vec();
                copy.push(b'\n');
                text.splice(s..s, copy);
            }
        }
        // Two lines swapped.
        10 => {
            let ls = lines(text);
            if ls.len() >= 2 {
                let a = rng.random_range(0..ls.len());
                let b = rng.random_range(0..ls.len());
                let (a, b) = (ls[a.min(b)], ls[a.max(b)]);
                if a != b {
                    let (la, lb) = (text[a.0..a.1].to_vec(), text[b.0..b.1].to_vec());
                    text.splice(b.0..b.1, la);
                    text.splice(a.0..a.1, lb);
                }
            }
        }
        // Truncated.
        11 if !text.is_empty() => {
            let at = rng.random_range(0..text.len());
            text.truncate(at);
        }
        // A token inserted.
        12 => {
            let at = rng.random_range(0..=text.len());
            let with = format!(" {} ", nasty(rng));
            text.splice(at..at, with.bytes());
        }
        // A token deleted.
        13 => {
            let spans = tokens(text);
            if let Some(&span) = spans.choose(rng) {
                replace(text, span, "");
            }
        }
        // A header key mangled: case, centre/corner, misspelt, or a header
        // line inserted anywhere.
        14 => {
            let spans = tokens(text);
            let header = header_spans(text);
            if let Some(k) = (!header.is_empty()).then(|| rng.random_range(0..header.len())) {
                let key = spans[2 * k];
                let word = String::from_utf8_lossy(&text[key.0..key.1]).to_string();
                let with = match rng.random_range(0..4) {
                    0 => word.to_ascii_uppercase(),
                    1 => word.replace("corner", "center"),
                    2 => word.replace("center", "corner"),
                    _ => word[..word.len() - 1].to_string(),
                };
                replace(text, key, &with);
            }
        }
        _ => {
            let ls = lines(text);
            let at = ls.choose(rng).map_or(0, |&(s, _)| s);
            let line = format!(
                "{} {}\n",
                HEADER_KEYS.choose(rng).unwrap_or(&"ncols"),
                nasty(rng)
            );
            text.splice(at..at, line.bytes());
        }
    }
}

/// Apply 1 to 4 random changes.
fn mutate_some(rng: &mut StdRng, text: &mut Vec<u8>) {
    let n = rng.random_range(1..=4);
    for _ in 0..n {
        mutate(rng, text);
    }
}

/// The cells (row, column) of `r` from `r0..r1`, `c0..c1`, as a raster
/// (the same place on the ground).
fn crop(r: &Raster, (r0, r1): (usize, usize), (c0, c1): (usize, usize)) -> Raster {
    let values = (r0..r1)
        .flat_map(|i| (c0..c1).map(move |j| r.get(i, j)))
        .collect();
    let (x0, y0) = r.lower_left();
    let d = r.cell_size();
    Raster::new(
        c1 - c0,
        r1 - r0,
        x0 + c0 as f64 * d,
        y0 + (r.rows() - r1) as f64 * d,
        d,
        values,
    )
    .expect("a crop of a valid raster")
}

fn random_window(
    rng: &mut StdRng,
    rows: usize,
    columns: usize,
) -> ((usize, usize), (usize, usize)) {
    let span = |rng: &mut StdRng, n: usize| {
        let a = rng.random_range(0..n);
        let b = rng.random_range(a + 1..=n);
        (a, b)
    };
    (span(rng, rows), span(rng, columns))
}

/// `r` with its values or its place changed as a grid.
fn vary(rng: &mut StdRng, r: &Raster, lift: bool) -> Raster {
    let mut values = r.values().to_vec();
    let holes = rng.random_range(0..3);
    for _ in 0..holes {
        let k = rng.random_range(0..values.len());
        values[k] = None;
    }
    if lift {
        for v in values.iter_mut().flatten() {
            if rng.random_bool(0.3) {
                *v += 1e3;
            }
        }
    }
    let (mut x0, mut y0) = r.lower_left();
    let mut d = r.cell_size();
    match rng.random_range(0..20) {
        0 => x0 += d * rng.random_range(-2.0..2.0),
        1 => y0 += 1e-12 * d,
        2 => d *= 2.0,
        _ => {}
    }
    Raster::new(r.columns(), r.rows(), x0, y0, d, values).expect("a varied valid raster")
}

/// The files of one case: names and bytes.
type Files = Vec<(String, Vec<u8>)>;

/// Build the input of case `index`: its target and its files.
pub fn case_input(seeds: &Seeds, seed: u64, index: u64) -> (Target, Files) {
    let mut rng = StdRng::seed_from_u64(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ index);
    let target = match rng.random_range(0..256) {
        0..=127 => Target::Reader,
        128..=254 => Target::Loader,
        _ => Target::LoaderFromFiles,
    };
    if target == Target::Reader {
        let mut text = seeds
            .texts
            .choose(&mut rng)
            .expect("seed texts")
            .clone()
            .into_bytes();
        mutate_some(&mut rng, &mut text);
        return (target, vec![("grid.asc".to_string(), text)]);
    }
    let (ground, slip, water) = seeds.sets.choose(&mut rng).expect("seed sets");
    let window = random_window(&mut rng, ground.rows(), ground.columns());
    let mut grids = vec![
        ("ground.asc", crop(ground, window.0, window.1)),
        ("slip.asc", crop(slip, window.0, window.1)),
    ];
    if let Some(w) = water {
        if rng.random_bool(0.8) {
            grids.push(("water.asc", crop(w, window.0, window.1)));
        }
    }
    // At times one grid cropped elsewhere: grids that do not match.
    if rng.random_bool(0.1) {
        let k = rng.random_range(0..grids.len());
        let other = random_window(&mut rng, ground.rows(), ground.columns());
        let source = [ground, slip, water.as_ref().unwrap_or(ground)][k];
        grids[k].1 = crop(source, other.0, other.1);
    }
    let mut files: Files = grids
        .iter()
        .map(|(name, r)| {
            let varied = if rng.random_bool(0.5) {
                vary(&mut rng, r, *name == "slip.asc")
            } else {
                r.clone()
            };
            (name.to_string(), to_esri_ascii(&varied).into_bytes())
        })
        .collect();
    if rng.random_bool(0.5) {
        let k = rng.random_range(0..files.len());
        mutate_some(&mut rng, &mut files[k].1);
    }
    (target, files)
}

/// Run the reader or loader on a case's files.
fn run_target(target: Target, files: &Files, dir: &Path) -> Result<()> {
    let text = |k: usize| String::from_utf8_lossy(&files[k].1).into_owned();
    let parse = |k: usize| -> Result<NamedRaster> {
        Ok(NamedRaster::new(
            files[k].0.clone(),
            parse_esri_ascii(&text(k), &files[k].0)?,
        ))
    };
    let grids = match target {
        Target::Reader => {
            let r = parse(0)?.raster;
            assert_eq!(r.values().len(), r.rows() * r.columns());
            assert!(r.values().len() <= MAX_GRID_CELLS);
            return Ok(());
        }
        Target::Loader => SlopeGrids::new(
            parse(0)?,
            parse(1)?,
            files.get(2).map(|_| parse(2)).transpose()?,
        )?,
        Target::LoaderFromFiles => {
            let paths: Vec<PathBuf> = files.iter().map(|(name, _)| dir.join(name)).collect();
            SlopeGrids::read(&paths[0], &paths[1], paths.get(2).map(PathBuf::as_path))?
        }
    };
    // What the model builder asks of accepted grids: every valid cell's
    // corners, and cells just outside the grid.
    let (rows, columns) = (
        grids.ground().raster.rows(),
        grids.ground().raster.columns(),
    );
    for (r, c) in grids.valid_cells() {
        let _ = grids.corners(r, c);
    }
    assert!(!grids.is_valid(rows, 0) && !grids.is_valid(0, columns));
    Ok(())
}

/// One case's result.
struct CaseResult {
    outcome: std::result::Result<Result<()>, String>,
    peak: u64,
    input: usize,
    huge_claim: bool,
}

fn run_case(seeds: &Seeds, seed: u64, index: u64, dir: &Path) -> (Target, CaseResult) {
    let (target, files) = case_input(seeds, seed, index);
    if target == Target::LoaderFromFiles {
        for (name, bytes) in &files {
            std::fs::write(dir.join(name), bytes).expect("writing a fuzz case file");
        }
    }
    let input = files.iter().map(|(_, b)| b.len()).sum();
    let huge_claim = files
        .iter()
        .any(|(_, b)| claimed_cells(b).is_some_and(|cells| cells > MAX_GRID_CELLS as f64));
    let mut caught = None;
    let info = allocation_counter::measure(|| {
        caught = Some(catch_panic(|| run_target(target, &files, dir)));
    });
    let outcome = caught.expect("the case ran");
    (
        target,
        CaseResult {
            outcome,
            peak: info.bytes_max,
            input,
            huge_claim,
        },
    )
}

/// Run cases `range` of the run seeded by `seed`.
pub fn run(seed: u64, range: std::ops::Range<u64>) -> Stats {
    install_panic_hook();
    let seeds = Seeds::new();
    let dir = std::env::temp_dir().join(format!(
        "dismech-grid-fuzz-{}-{}",
        std::process::id(),
        range.start
    ));
    std::fs::create_dir_all(&dir).expect("a scratch folder for file cases");
    let mut stats = Stats::default();
    for index in range {
        let (target, result) = run_case(&seeds, seed, index, &dir);
        stats.cases += 1;
        *stats.by_target.entry(format!("{target:?}")).or_default() += 1;
        stats.huge_claims += u64::from(result.huge_claim);
        match &result.outcome {
            Ok(Ok(())) => {
                stats.accepted += 1;
                *stats
                    .accepted_by_target
                    .entry(format!("{target:?}"))
                    .or_default() += 1;
                stats.huge_claims_accepted += u64::from(result.huge_claim);
            }
            Ok(Err(e)) => *stats.refused.entry(kind(e)).or_default() += 1,
            Err(message) => {
                stats.panics += 1;
                if stats.panic_examples.len() < 5 {
                    stats.panic_examples.push((index, message.clone()));
                }
            }
        }
        stats.largest_peak = stats.largest_peak.max(result.peak);
        stats.largest_share_of_bound = stats
            .largest_share_of_bound
            .max(result.peak as f64 / memory_bound(result.input) as f64);
        if result.peak > memory_bound(result.input) {
            stats.over_memory_bound += 1;
            if stats.memory_examples.len() < 5 {
                stats
                    .memory_examples
                    .push((index, result.peak, result.input));
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    stats
}
