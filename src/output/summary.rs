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

/// The summary of one study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Study name, e.g. `katsuki1990`.
    pub study: String,
    /// File name of the paper in `papers/`.
    pub paper: String,
    /// The checks.
    pub checks: Vec<Check>,
    /// Files written by the study (relative to the study folder).
    pub files: Vec<String>,
}

impl Summary {
    /// Whether every check passed.
    pub fn all_passed(&self) -> bool {
        self.checks.iter().all(|c| c.passed)
    }

    /// The check with id `id`.
    pub fn check(&self, id: &str) -> Option<&Check> {
        self.checks.iter().find(|c| c.id == id)
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
