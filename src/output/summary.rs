//! The machine-readable summary of a reproduction: `DIR/<study>/summary.json`.

use std::path::Path;

use serde::Serialize;

use super::write_atomically;
use crate::error::{DismechError, Result};

/// One compared quantity.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Check {
    /// Stable identifier, e.g. `ex1.vertical_reaction_ratio`.
    pub id: String,
    /// What is compared, in words.
    pub description: String,
    /// The paper's value, if the paper gives one.
    pub paper: Option<f64>,
    /// The value computed in this run.
    pub computed: f64,
    /// Unit of `paper` and `computed` (`"-"` for ratios).
    pub unit: String,
    /// Tolerance of the check, in the sense of `description`.
    pub tolerance: f64,
    /// Whether the check passed.
    pub passed: bool,
}

/// A number a study reports beside the paper's without a pass/fail
/// judgement: where the paper sets no target for it, or where the target is
/// not met and the description (and the study's report) says so. Unlike a
/// [`Check`], it never makes `reproduce` fail.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Reported {
    /// Stable identifier, e.g. `sliding.max_rel_error.rm.dt0.001.penalty2e4`.
    pub id: String,
    /// What it is, and how it compares with the paper, in words.
    pub description: String,
    /// The paper's value or target, if the paper gives one.
    pub paper: Option<f64>,
    /// The value computed in this run (NaN, written `null`, when the run
    /// did not complete).
    pub computed: f64,
    /// Unit of `paper` and `computed` (`"-"` for ratios).
    pub unit: String,
}

/// The summary of one study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Study name, e.g. `katsuki1990`.
    pub study: String,
    /// File name of the paper in `papers/`.
    pub paper: String,
    /// The checks.
    pub checks: Vec<Check>,
    /// Values reported without a judgement.
    pub values: Vec<Reported>,
    /// Files written by the study (relative to the study folder).
    pub files: Vec<String>,
}

impl Summary {
    /// Whether every check passed.
    pub fn all_passed(&self) -> bool {
        self.checks.iter().all(|c| c.passed)
    }

    /// The reported value with id `id`.
    pub fn value(&self, id: &str) -> Option<&Reported> {
        self.values.iter().find(|v| v.id == id)
    }

    /// The check with id `id`.
    pub fn check(&self, id: &str) -> Option<&Check> {
        self.checks.iter().find(|c| c.id == id)
    }

    /// Write the study's Markdown `report` as `dir/report.md`, list it in
    /// `files`, then write `summary.json`; each file atomically.
    pub fn write_with_report(mut self, dir: &Path, report: &str) -> Result<Self> {
        write_atomically(&dir.join("report.md"), report.as_bytes())?;
        self.files.push("report.md".into());
        self.write(dir)?;
        Ok(self)
    }

    /// Write `summary.json` into `dir` atomically.
    pub fn write(&self, dir: &Path) -> Result<()> {
        let path = dir.join("summary.json");
        let json = serde_json::to_string_pretty(self).map_err(|e| DismechError::Output {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        write_atomically(&path, json.as_bytes())
    }
}
