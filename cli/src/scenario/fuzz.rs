//! A fuzzer of scenario files: valid files mutated (keys deleted,
//! duplicated or renamed; values of the wrong type or at extremes; tables
//! swapped; files truncated; random bytes) and read, built and checked
//! by [`super::prepare`] (nothing is run). Every outcome is counted: a
//! valid file, a refusal that names its key and line, a refusal that does
//! not (a finding), or a panic (a finding). Seeded and deterministic.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

use super::{prepare, Overrides, ScenarioError};

/// A small seeded generator (SplitMix64): deterministic mutations without
/// a dependency.
#[derive(Debug, Clone)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// A generator from `seed`.
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A number in `0..n` (`n` ≥ 1).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n.max(1) as u64) as usize
    }

    /// One element of `items` (not empty).
    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// Values put in place of a value: wrong types, extremes, NaN as a string
/// and as a float, empty and nested arrays, tables.
pub const VALUES: &[&str] = &[
    "\"NaN\"",
    "nan",
    "-nan",
    "inf",
    "-inf",
    "0",
    "-0.0",
    "-1",
    "1e308",
    "-1e308",
    "1e-320",
    "9223372036854775807",
    "-9223372036854775808",
    "4294967296",
    "0.5",
    "2",
    "\"\"",
    "\"abc\"",
    "true",
    "false",
    "[]",
    "[[]]",
    "[1.0]",
    "[1.0, 2.0, 3.0]",
    "[\"a\", 1]",
    "{}",
    "{ kind = \"fixed\" }",
    "{ kind = 3 }",
    "1979-05-27T07:32:00Z",
    "[nan, inf]",
    "[0.0, 0.0]",
    "[-1e308, 1e308]",
    "\"circle\"",
];

/// Keys put in place of a key: known keys in the wrong place, unknown
/// ones, odd spellings.
pub const KEYS: &[&str] = &[
    "kind",
    "radius",
    "density",
    "dt",
    "friction",
    "friction_angle",
    "count",
    "per_row",
    "m",
    "n",
    "loaded",
    "centre",
    "vertices",
    "motion",
    "velocity",
    "youngs_modulus",
    "poisson_ratio",
    "steps",
    "end_time",
    "max_steps",
    "segments",
    "frames_every",
    "checkpoint_every",
    "checkpoint_dir",
    "keep_checkpoints",
    "plate_wall",
    "self_weight",
    "contacts",
    "ground",
    "slip",
    "water",
    "layers",
    "seismic",
    "unit_weight",
    "gravity",
    "bodies",
    "law",
    "unknown",
    "Radius",
    "\"quoted key\"",
    "a.b",
    "cohesion",
    "width",
    "height",
    "penalty",
    "nonlinear",
    "tolerance",
    "max_iterations",
    "group",
    "slip_reversal_quantile",
    "groups",
    "pair_laws",
];

/// Table headers put in place of a header.
pub const HEADERS: &[&str] = &[
    "[driver]",
    "[law]",
    "[[bodies]]",
    "[boundary]",
    "[integrator]",
    "[run]",
    "[output]",
    "[loads]",
    "[kinematics]",
    "[linear_solver]",
    "[lp_solver]",
    "[limit_analysis]",
    "[limit_analysis.walls]",
    "[bodies]",
    "[[law]]",
    "[nothing]",
    "[law.extra]",
    "[[loads.forces]]",
    "[[loads.tractions]]",
    "[[pair_laws]]",
];

/// The `kind` values of every slot, put in place of a `kind`.
pub const KINDS: &[&str] = &[
    "explicit",
    "implicit",
    "limit",
    "katsuki",
    "spring-dashpot-coulomb",
    "penalty-coulomb",
    "rigid-plastic",
    "circle",
    "ellipse",
    "polygon",
    "rectangle",
    "wall",
    "circle-rows",
    "lattice",
    "open-box",
    "walls",
    "rigid",
    "affine",
    "explicit-euler",
    "newmark",
    "quasi-static",
    "sparse-lu",
    "clarabel",
    "to-rest",
    "steps",
    "time",
    "fixed",
    "sine",
    "",
];

/// `text` with one to three mutations.
pub fn mutate(text: &str, rng: &mut SplitMix64) -> String {
    let mut text = text.to_string();
    for _ in 0..1 + rng.below(3) {
        text = mutate_once(&text, rng);
    }
    text
}

/// `text` with one mutation.
fn mutate_once(text: &str, rng: &mut SplitMix64) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    if lines.is_empty() {
        lines.push(String::new());
    }
    let assignments: Vec<usize> = (0..lines.len())
        .filter(|&k| lines[k].contains('=') && !lines[k].trim_start().starts_with('#'))
        .collect();
    let headers: Vec<usize> = (0..lines.len())
        .filter(|&k| lines[k].trim_start().starts_with('['))
        .collect();
    let line = |rng: &mut SplitMix64, of: &[usize], all: usize| -> usize {
        if of.is_empty() {
            rng.below(all)
        } else {
            *rng.pick(of)
        }
    };
    match rng.below(10) {
        0 => {
            let k = line(rng, &assignments, lines.len());
            lines.remove(k);
        }
        1 => {
            let k = line(rng, &assignments, lines.len());
            let copy = lines[k].clone();
            lines.insert(k + 1, copy);
        }
        2 => {
            let k = line(rng, &assignments, lines.len());
            if let Some((_, value)) = lines[k].split_once('=') {
                lines[k] = format!("{} ={value}", rng.pick(KEYS));
            }
        }
        3 | 4 => {
            let k = line(rng, &assignments, lines.len());
            if let Some((key, _)) = lines[k].split_once('=') {
                lines[k] = format!("{key}= {}", rng.pick(VALUES));
            }
        }
        5 => {
            let k = line(rng, &headers, lines.len());
            lines[k] = rng.pick(HEADERS).to_string();
        }
        6 => {
            let kinds: Vec<usize> = (0..lines.len())
                .filter(|&k| lines[k].contains("kind"))
                .collect();
            let k = line(rng, &kinds, lines.len());
            if let Some((key, _)) = lines[k].split_once('=') {
                lines[k] = format!("{key}= \"{}\"", rng.pick(KINDS));
            }
        }
        7 => {
            let cut = rng.below(text.len() + 1);
            let mut cut = cut;
            while !text.is_char_boundary(cut) {
                cut -= 1;
            }
            return text[..cut].to_string();
        }
        8 => {
            let mut bytes = text.as_bytes().to_vec();
            let at = rng.below(bytes.len() + 1);
            let noise: Vec<u8> = (0..1 + rng.below(8))
                .map(|_| rng.next_u64() as u8)
                .collect();
            bytes.splice(at..at, noise);
            return String::from_utf8_lossy(&bytes).into_owned();
        }
        _ => {
            // A number scaled to an extreme or its sign turned.
            let k = line(rng, &assignments, lines.len());
            if let Some((key, value)) = lines[k].split_once('=') {
                let factor = rng.pick(&["1e300", "-1", "0", "1e-300", "1e6"]).to_string();
                let scaled = value
                    .split([',', '[', ']'])
                    .find_map(|v| v.trim().parse::<f64>().ok())
                    .map(|v| v * factor.parse::<f64>().unwrap_or(1.0));
                if let Some(v) = scaled {
                    lines[k] = format!("{key}= {v:?}");
                }
            }
        }
    }
    let mut out = lines.join("\n");
    out.push('\n');
    out
}

/// The key of a refusal placed at the file's root ([`super::source::KeyPath`]'s
/// empty path).
const ROOT_KEY: &str = "(the file)";

/// What the fuzzer saw.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Tally {
    /// Files read.
    pub files: u64,
    /// Files accepted (a mutation can leave a valid file).
    pub valid: u64,
    /// Files refused with an error naming a key and a line.
    pub refused: u64,
    /// Refusals that name no key (or only the file's root), with the first
    /// few messages. (Every refusal has a line: a key's, or the file's
    /// first.)
    pub unnamed: Vec<String>,
    /// Panics, with the first few files that caused them.
    pub panics: Vec<String>,
}

/// Read `text` as the scenario `file` (parse, build, check; nothing run)
/// and count the outcome in `tally`.
pub fn check_one(file: &Path, text: &str, tally: &mut Tally) {
    tally.files += 1;
    let outcome = catch_unwind(AssertUnwindSafe(|| {
        prepare(file, text, Overrides::default())
    }));
    match outcome {
        Ok(Ok(_)) => tally.valid += 1,
        Ok(Err(ScenarioError::Invalid(located))) => {
            // A refusal placed at the file's root (`(the file)`) names no
            // key: every table and value the schema has is a key.
            if located.key.is_empty() || located.key == ROOT_KEY {
                tally.unnamed.push(located.to_string());
            } else {
                tally.refused += 1;
            }
        }
        Ok(Err(other)) => tally.unnamed.push(other.to_string()),
        Err(_) => tally.panics.push(text.to_string()),
    }
}

/// Mutate each of `seeds` (name, text) `per_seed` times from `seed` and
/// check every mutant.
pub fn run(seeds: &[(String, String)], per_seed: u64, seed: u64) -> Tally {
    let mut rng = SplitMix64::new(seed);
    let mut tally = Tally::default();
    for _ in 0..per_seed {
        for (name, text) in seeds {
            let mutant = mutate(text, &mut rng);
            check_one(Path::new(name), &mutant, &mut tally);
        }
    }
    tally
}
