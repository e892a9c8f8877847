//! `[output] checkpoint_every`: a scenario's run saved every n steps, and
//! `dismech run model.toml --resume FILE` resuming it to the same bits.
//!
//! A scenario's checkpoint is the driver's checkpoint
//! ([`dismech::checkpoint`]) behind a header holding what the scenario's
//! run counts beside the driver: the steps it took (the implicit driver
//! counts calls of `advance`, which its own checkpoint does not), its
//! sub-steps and halvings, the step `dt` and a fingerprint of the
//! explicit driver's settings. The header, of [`HEADER`] bytes:
//!
//! | bytes | what |
//! |---|---|
//! | 0–7 | the signature `dismechR` |
//! | 8–11 | the format version, little-endian ([`VERSION`]) |
//! | 12 | the driver: 1 explicit, 2 implicit |
//! | 13–20 | steps taken |
//! | 21–28 | sub-steps accepted (implicit driver; 0 for the explicit one) |
//! | 29–36 | step halvings (implicit driver; 0 for the explicit one) |
//! | 37–44 | the bits of the driver's `dt` |
//! | 45–52 | the FNV-1a 64-bit hash of the explicit driver's settings; for the implicit one (whose checkpoint compares its settings itself), of its bodies' `sine` motions and its moving walls' velocities, 0 without either |
//! | 53–60 | the length of the driver's checkpoint in bytes |
//! | 61–68 | the FNV-1a 64-bit checksum of bytes 0–60 and of the driver's checkpoint |
//! | 69– | the driver's checkpoint, as [`dismech::checkpoint`] writes it |
//!
//! All words are little-endian.

use std::path::{Path, PathBuf};

pub use dismech::checkpoint::mismatch;
use dismech::checkpoint::{refused, CheckpointProblem};
use dismech::error::DismechError;

use super::check::{self, Refusal};
use super::explicit::ExplicitPlan;
use super::source::{KeyPath, Source};
use super::{Model, ScenarioSpec};

/// The first eight bytes of a scenario's checkpoint.
pub const SIGNATURE: [u8; 8] = *b"dismechR";

/// The version of the header this build writes and reads.
pub const VERSION: u32 = 1;

/// The bytes before the driver's checkpoint.
pub const HEADER: usize = 8 + 4 + 1 + 7 * 8;

/// The driver a checkpoint belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Driver {
    /// Explicit dynamics.
    Explicit,
    /// Implicit dynamics.
    Implicit,
}

impl Driver {
    fn tag(self) -> u8 {
        match self {
            Self::Explicit => 1,
            Self::Implicit => 2,
        }
    }

    /// The driver's `kind` in a scenario.
    pub fn name(self) -> &'static str {
        match self {
            Self::Explicit => "explicit",
            Self::Implicit => "implicit",
        }
    }
}

/// What the scenario's run counts beside the driver.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RunCounters {
    /// The driver.
    pub driver: Driver,
    /// Steps taken (the implicit driver: calls of `advance`).
    pub step: u64,
    /// Sub-steps accepted (implicit driver).
    pub substeps: u64,
    /// Step halvings (implicit driver).
    pub halvings: u64,
    /// The bits of the driver's `dt`.
    pub dt_bits: u64,
    /// The hash of the explicit driver's settings ([`fingerprint`]); of
    /// the implicit driver's sine motions and moving walls' velocities
    /// (`implicit::motions`).
    pub settings: u64,
}

/// FNV-1a, 64 bits.
pub fn fnv(parts: &[&[u8]]) -> u64 {
    parts
        .iter()
        .flat_map(|p| p.iter())
        .fold(0xcbf2_9ce4_8422_2325, |hash, &b| {
            (hash ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
        })
}

/// The hash of `value`'s JSON (the explicit driver's settings).
pub fn fingerprint<T: serde::Serialize>(value: &T) -> u64 {
    fnv(&[serde_json::to_string(value).unwrap_or_default().as_bytes()])
}

/// The file a run writes its checkpoint of step `step` to, in `dir`.
pub fn file_name(dir: &Path, step: u64) -> PathBuf {
    dir.join(format!("step-{step:010}.ckpt"))
}

/// `driver`'s checkpoint behind the header of `counters`.
pub fn encode(counters: &RunCounters, driver: &[u8]) -> Vec<u8> {
    let mut bytes = Vec::with_capacity(HEADER + driver.len());
    bytes.extend_from_slice(&SIGNATURE);
    bytes.extend_from_slice(&VERSION.to_le_bytes());
    bytes.push(counters.driver.tag());
    for word in [
        counters.step,
        counters.substeps,
        counters.halvings,
        counters.dt_bits,
        counters.settings,
        driver.len() as u64,
    ] {
        bytes.extend_from_slice(&word.to_le_bytes());
    }
    let sum = fnv(&[&bytes, driver]);
    bytes.extend_from_slice(&sum.to_le_bytes());
    bytes.extend_from_slice(driver);
    bytes
}

/// The counters and the driver's checkpoint in `bytes` (read from
/// `origin`, named in errors), for the driver `expected`.
///
/// # Errors
/// [`DismechError::Checkpoint`]: not a scenario's checkpoint (a driver's
/// own checkpoint is named as such), another version, another driver's,
/// truncated, or a checksum that does not match.
pub fn decode<'b>(
    bytes: &'b [u8],
    origin: &str,
    expected: Driver,
) -> Result<(RunCounters, &'b [u8]), DismechError> {
    if bytes.starts_with(b"dismechK") {
        return Err(refused(
            origin,
            CheckpointProblem::Corrupt(
                "a driver's own checkpoint (signature `dismechK`), not a scenario's: resume a file written by a scenario's `checkpoint_every`".into(),
            ),
        ));
    }
    let signature = &bytes[..bytes.len().min(SIGNATURE.len())];
    if signature != &SIGNATURE[..signature.len()] {
        return Err(refused(origin, CheckpointProblem::NotACheckpoint));
    }
    if bytes.len() < HEADER {
        return Err(refused(
            origin,
            CheckpointProblem::Truncated {
                expected: HEADER as u64,
                found: bytes.len() as u64,
            },
        ));
    }
    let word = |at: usize| {
        let mut w = [0u8; 8];
        w.copy_from_slice(&bytes[at..at + 8]);
        u64::from_le_bytes(w)
    };
    let mut v = [0u8; 4];
    v.copy_from_slice(&bytes[8..12]);
    let version = u32::from_le_bytes(v);
    if version != VERSION {
        return Err(refused(
            origin,
            CheckpointProblem::UnsupportedVersion {
                found: version,
                supported: VERSION,
            },
        ));
    }
    let driver = match bytes[12] {
        1 => Driver::Explicit,
        2 => Driver::Implicit,
        other => {
            return Err(refused(
                origin,
                CheckpointProblem::Corrupt(format!("driver tag {other}")),
            ))
        }
    };
    if driver != expected {
        return Err(refused(
            origin,
            CheckpointProblem::WrongDriver {
                found: driver.name().into(),
                expected: expected.name(),
            },
        ));
    }
    let payload = &bytes[HEADER..];
    let length = word(53);
    if (payload.len() as u64) < length {
        return Err(refused(
            origin,
            CheckpointProblem::Truncated {
                expected: (HEADER as u64).saturating_add(length),
                found: bytes.len() as u64,
            },
        ));
    }
    if payload.len() as u64 > length {
        return Err(refused(
            origin,
            CheckpointProblem::Corrupt(format!(
                "{} bytes follow the driver's checkpoint",
                payload.len() as u64 - length
            )),
        ));
    }
    if fnv(&[&bytes[..HEADER - 8], payload]) != word(HEADER - 8) {
        return Err(refused(
            origin,
            CheckpointProblem::Corrupt("the checksum does not match the contents".into()),
        ));
    }
    let counters = RunCounters {
        driver,
        step: word(13),
        substeps: word(21),
        halvings: word(29),
        dt_bits: word(37),
        settings: word(45),
    };
    Ok((counters, payload))
}

/// `error` with its origin (a driver's checkpoint read from bytes) set to
/// `origin`.
pub fn from_file(error: DismechError, origin: &str) -> DismechError {
    match error {
        DismechError::Checkpoint { problem, .. } => refused(origin, problem),
        other => other,
    }
}

/// Where a run writes its checkpoints: `dir` (given as a path relative
/// to the scenario file's folder) or, by default, beside the output
/// folder `out`, named after it (`NAME.checkpoints` for `NAME.out`,
/// `DIR.checkpoints` for any other `DIR`).
pub fn folder(file: &Path, out: &Path, dir: Option<&str>) -> PathBuf {
    match dir {
        Some(d) => file
            .parent()
            .map_or_else(|| PathBuf::from(d), |parent| parent.join(d)),
        None => {
            let name = out
                .file_name()
                .map_or_else(|| "run".into(), |n| n.to_string_lossy().into_owned());
            let stem = name.strip_suffix(".out").unwrap_or(&name);
            out.with_file_name(format!("{stem}.checkpoints"))
        }
    }
}

/// The step of a checkpoint's file name (`step-NNNNNNNNNN.ckpt`, ten
/// digits or more), none for any other name.
pub fn step_of(name: &str) -> Option<u64> {
    let digits = name.strip_prefix("step-")?.strip_suffix(".ckpt")?;
    if digits.len() < 10 || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    digits.parse().ok()
}

/// Remove from `dir` the checkpoints of steps below `newest` (the one just
/// written) but the `keep − 1` of the highest steps: `keep` checkpoints
/// are left, the newest included. Files of other names, anything that is
/// not a file, and checkpoints of steps above `newest` (an earlier run's,
/// in the same folder; the run writes over them as it gets there), are
/// left alone. Two runs given one folder share its step names, and so
/// prune (and overwrite) each other's checkpoints.
///
/// # Errors
/// [`DismechError::Output`] naming the folder when it cannot be listed, or
/// a file that cannot be removed (one removed meanwhile is not an error).
pub fn prune(dir: &Path, newest: u64, keep: usize) -> Result<(), DismechError> {
    let output_error = |path: &Path, e: std::io::Error| DismechError::Output {
        path: path.display().to_string(),
        message: e.to_string(),
    };
    let mut older: Vec<(u64, PathBuf)> = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(|e| output_error(dir, e))? {
        let entry = entry.map_err(|e| output_error(dir, e))?;
        let name = entry.file_name();
        let Some(step) = name.to_str().and_then(step_of) else {
            continue;
        };
        // Only files: a folder that happens to bear a checkpoint's name is
        // not one.
        if !entry.file_type().is_ok_and(|t| t.is_file()) {
            continue;
        }
        if step < newest {
            older.push((step, entry.path()));
        }
    }
    older.sort_unstable();
    let remove = older.len().saturating_sub(keep.saturating_sub(1));
    for (_, path) in &older[..remove] {
        match std::fs::remove_file(path) {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
            Err(e) => return Err(output_error(path, e)),
        }
    }
    Ok(())
}

/// The checkpoints a scenario asks for.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// Steps between two checkpoints (≥ 1).
    pub every: u64,
    /// `output.checkpoint_dir` as written.
    pub dir: Option<String>,
    /// `output.keep_checkpoints`: how many to keep (≥ 1); all when none.
    pub keep: Option<usize>,
}

/// The checkpoints of `[output]`, checked against the driver and the run
/// of `model`.
///
/// # Errors
/// A refusal naming `output.checkpoint_every` (0, beside the limit
/// driver, or not a multiple of a run to rest's `run.check_every`) or
/// `output.checkpoint_dir` (empty, or given without
/// `checkpoint_every`).
pub(crate) fn plan(
    source: &Source<'_>,
    spec: &ScenarioSpec,
    model: &Model,
) -> Result<Option<Plan>, Refusal> {
    let output = KeyPath::root("output");
    let every_key = output.key("checkpoint_every");
    let dir_key = output.key("checkpoint_dir");
    let keep_key = output.key("keep_checkpoints");
    if let Some(keep) = spec.output.keep_checkpoints {
        check::require(
            source,
            &keep_key,
            keep,
            keep >= 1,
            "must be at least 1: the newest checkpoint is kept (leave the key out to keep all)",
        )?;
    }
    if let Some(dir) = &spec.output.checkpoint_dir {
        if dir.is_empty() || dir.contains('\0') {
            return Err(Box::new(source.at_key(
                &dir_key,
                "give a folder's path (relative to the scenario file's folder)",
            )));
        }
    }
    let Some(every) = spec.output.checkpoint_every else {
        if spec.output.checkpoint_dir.is_some() {
            return Err(check::combination(
                source,
                &[&dir_key, &every_key],
                "a folder of checkpoints needs `checkpoint_every`, the steps between two",
            ));
        }
        if spec.output.keep_checkpoints.is_some() {
            return Err(check::combination(
                source,
                &[&keep_key, &every_key],
                "checkpoints to keep need `checkpoint_every`, the steps between two",
            ));
        }
        return Ok(None);
    };
    check::require(
        source,
        &every_key,
        every,
        every >= 1,
        "must be at least 1 (leave the key out for no checkpoints)",
    )?;
    match model {
        Model::Limit(_) | Model::Hpm(_) => return Err(check::combination(
            source,
            &[&KeyPath::root("driver").key("kind"), &every_key],
            "a limit or HPM analysis takes no steps: checkpoints serve the explicit and implicit drivers",
        )),
        Model::Explicit(m) => {
            if let ExplicitPlan::ToRest(c) = m.plan {
                if every % c.check_every.max(1) != 0 {
                    return Err(check::combination(
                        source,
                        &[&every_key, &KeyPath::root("run").key("check_every")],
                        &format!(
                            "a run to rest is saved at its rest checks: give a multiple of check_every = {}",
                            c.check_every
                        ),
                    ));
                }
            }
        }
        Model::Implicit(_) => {}
    }
    Ok(Some(Plan {
        every,
        dir: spec.output.checkpoint_dir.clone(),
        keep: spec.output.keep_checkpoints,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn counters() -> RunCounters {
        RunCounters {
            driver: Driver::Implicit,
            step: 7,
            substeps: 9,
            halvings: 1,
            dt_bits: 1e-3f64.to_bits(),
            settings: 0,
        }
    }

    #[test]
    fn a_checkpoint_reads_back_and_damage_is_refused() {
        let bytes = encode(&counters(), b"dismechK-payload");
        let (back, payload) = decode(&bytes, "f", Driver::Implicit).unwrap();
        assert_eq!(back, counters());
        assert_eq!(payload, b"dismechK-payload");
        for cut in 0..bytes.len() {
            assert!(
                decode(&bytes[..cut], "f", Driver::Implicit).is_err(),
                "{cut}"
            );
        }
        for at in 0..bytes.len() {
            let mut flipped = bytes.clone();
            flipped[at] ^= 0x04;
            assert!(decode(&flipped, "f", Driver::Implicit).is_err(), "{at}");
        }
        assert!(matches!(
            decode(&bytes, "f", Driver::Explicit),
            Err(DismechError::Checkpoint {
                problem: CheckpointProblem::WrongDriver { .. },
                ..
            })
        ));
    }

    #[test]
    fn pruning_keeps_the_newest_and_leaves_other_files() {
        let dir = std::env::temp_dir().join(format!("dismech-prune-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        for step in [10, 20, 30, 40, 50] {
            std::fs::write(file_name(&dir, step), b"x").unwrap();
        }
        for other in ["notes.txt", "step-12.ckpt", ".step-0000000060.ckpt.tmp1"] {
            std::fs::write(dir.join(other), b"x").unwrap();
        }
        // A folder named like an old checkpoint is neither removed nor an
        // error.
        std::fs::create_dir(file_name(&dir, 5)).unwrap();
        prune(&dir, 40, 2).unwrap();
        let mut names: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(
            names,
            [
                ".step-0000000060.ckpt.tmp1",
                "notes.txt",
                "step-0000000005.ckpt",
                "step-0000000030.ckpt",
                "step-0000000040.ckpt",
                "step-0000000050.ckpt",
                "step-12.ckpt",
            ]
        );
        prune(&dir, 50, 1).unwrap();
        assert!(!file_name(&dir, 40).exists() && file_name(&dir, 50).exists());
        assert_eq!(step_of("step-0000000050.ckpt"), Some(50));
        assert_eq!(step_of("step-00000000x0.ckpt"), None);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn the_default_folder_sits_beside_the_output() {
        let file = Path::new("a/model.toml");
        assert_eq!(
            folder(file, Path::new("a/model.out"), None),
            Path::new("a/model.checkpoints")
        );
        assert_eq!(
            folder(file, Path::new("/tmp/x"), None),
            Path::new("/tmp/x.checkpoints")
        );
        assert_eq!(
            folder(file, Path::new("/tmp/x"), Some("ck")),
            Path::new("a/ck")
        );
    }
}
