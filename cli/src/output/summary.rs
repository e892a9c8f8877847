//! The machine-readable summary of a reproduction: `DIR/<study>/summary.json`.

use std::path::Path;

use serde::Serialize;

use super::rule::Rule;
use dismech::error::{DismechError, Result};
use dismech::io::write_atomically;

/// One judged quantity: a computed value, the [`Rule`] it must pass and,
/// beside it, the paper's value if the paper gives one.
///
/// `rule`, `reference` and `passed` are derived from the same [`Rule`] by
/// [`Check::new`]; `paper` is compared with only when `paper_tested` says
/// so, otherwise it is shown beside the check for the reader.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Check {
    /// Stable identifier, e.g. `ex1.vertical_reaction_ratio`.
    pub id: String,
    /// What is compared, in words.
    pub description: String,
    /// The paper's value, if the paper gives one (tested by the rule or
    /// not: see `paper_tested`).
    pub paper: Option<f64>,
    /// The value computed in this run.
    pub computed: f64,
    /// Unit of `paper` and `computed` (`"-"` for ratios).
    pub unit: String,
    /// The accepted difference of a "within" rule; 0 for a bound or a
    /// condition.
    pub tolerance: f64,
    /// Whether the check passed.
    pub passed: bool,
    /// The pass rule; written in words, with the values it compares with.
    #[serde(serialize_with = "rule_in_words")]
    pub rule: Rule,
    /// The value the rule compares `computed` with (for alternatives, the
    /// one met, else the first); `None` when the rule is a condition on
    /// other numbers.
    pub reference: Option<f64>,
    /// Whether the rule compares `computed` with `paper`; when false, the
    /// paper's value is only shown beside the check.
    pub paper_tested: bool,
}

impl Check {
    /// A check of `computed` by `rule`. The paper's value is the one the
    /// rule compares with, if any; see [`Check::beside_paper`] for a paper
    /// value the rule does not test.
    pub fn new(
        id: impl Into<String>,
        description: impl Into<String>,
        unit: impl Into<String>,
        computed: f64,
        rule: &Rule,
    ) -> Self {
        let paper = rule.paper_value();
        Self {
            id: id.into(),
            description: description.into(),
            paper,
            computed,
            unit: unit.into(),
            tolerance: rule.tolerance(),
            passed: rule.passes(computed),
            rule: rule.clone(),
            reference: rule.reference_for(computed).map(|r| r.value),
            paper_tested: paper.is_some(),
        }
    }

    /// Show the paper's value `paper` beside a check whose rule does not
    /// compare with it (a trend, a different slope, a misprint).
    pub fn beside_paper(mut self, paper: f64) -> Self {
        if !self.paper_tested {
            self.paper = Some(paper);
        }
        self
    }

    /// The paper's value when the rule does not compare with it.
    pub fn untested_paper(&self) -> Option<f64> {
        self.paper.filter(|_| !self.paper_tested)
    }
}

fn rule_in_words<S: serde::Serializer>(rule: &Rule, s: S) -> std::result::Result<S::Ok, S::Error> {
    s.serialize_str(&rule.words())
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
