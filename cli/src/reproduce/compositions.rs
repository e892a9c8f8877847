//! Cross-compositions: models that combine the library's slots in ways the
//! four papers do not, each checked against an exact solution or a second
//! method. The models and their measurements are this package's library
//! ([`dismech_cli::compositions`], shared with `tests/compositions.rs` and
//! `tests/polygon_incline.rs`); this
//! study runs them at full size and writes `summary.json`, `report.md`
//! (one table per composition: measured, reference, rule), CSV tables and
//! plots into `OUT/compositions/`.
//!
//! A composition is one entry of [`COMPOSITIONS`]: a function (one file
//! each in `compositions/`) that opens its section of the report with
//! [`Collector::section`] and adds its checks ([`Collector::check`], with a
//! [`Rule`]), reported values ([`Collector::value`]) and files
//! ([`Collector::file`]). Adding a composition is adding its file and its
//! entry.

mod implicit;
mod incline;
mod packing_lp;
mod pictures;
mod polygon_lp;
mod wall;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::StudyOptions;
use dismech::error::Result;
use dismech_cli::output::{self, Check, Reference, Reported, Summary};

/// Name of the study and of its output folder.
pub const NAME: &str = "compositions";

/// A composition of the study: adds its section, checks, values and files.
pub type Composition = fn(&mut Collector) -> Result<()>;

/// The compositions, in the order of the report.
pub const COMPOSITIONS: &[Composition] = &[
    incline::polygon_incline,
    polygon_lp::polygon_lp,
    packing_lp::packing_lp,
    wall::polygon_dem_vs_dda,
    implicit::implicit_ellipses,
    implicit::affine_disc,
    implicit::penalty_vs_lp_u4_1,
];

/// Run every composition and write the study's outputs into
/// `options.dir` (staged, to become `OUT/compositions/`).
pub fn reproduce(options: &StudyOptions) -> Result<Summary> {
    let mut collector = Collector::new(options.dir.clone());
    for composition in COMPOSITIONS {
        composition(&mut collector)?;
    }
    collector.finish()
}

/// How a check passes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Rule {
    /// `|computed − target| ≤ tolerance`.
    Near {
        /// The reference value.
        target: f64,
        /// Largest accepted difference.
        tolerance: f64,
    },
    /// `computed ≤ tolerance` (a residual or an error; the reference is 0).
    AtMost(f64),
}

impl Rule {
    /// The rule of the summary's check: a comparison with the bare
    /// reference number (0 for a residual bounded by `AtMost`).
    fn judged(self) -> output::Rule {
        match self {
            Rule::Near { target, tolerance } => {
                output::Rule::near(Reference::number(target), tolerance)
            }
            Rule::AtMost(bound) => output::Rule::AtMost(Reference::number(bound)),
        }
    }

    /// The value the reference stands for, shown in the report: the
    /// target, or 0 for a residual or an error.
    fn ideal(self) -> f64 {
        match self {
            Rule::Near { target, .. } => target,
            Rule::AtMost(_) => 0.0,
        }
    }
}

/// What a check or a value measures: its id, the quantity, the reference
/// it is compared with (in words), its unit and a one-line explanation for
/// the report.
#[derive(Debug, Clone, Copy)]
pub struct Item<'a> {
    /// Stable identifier.
    pub id: &'a str,
    /// The measured quantity.
    pub what: &'a str,
    /// The reference, in words.
    pub reference: &'a str,
    /// Unit.
    pub unit: &'a str,
    /// One line for the report: why the number is what it is.
    pub note: &'a str,
}

/// The study's outputs as they are collected.
#[derive(Debug)]
pub struct Collector {
    dir: PathBuf,
    checks: Vec<Check>,
    values: Vec<Reported>,
    files: Vec<String>,
    report: String,
}

impl Collector {
    fn new(dir: PathBuf) -> Self {
        Self {
            dir,
            checks: Vec::new(),
            values: Vec::new(),
            files: Vec::new(),
            report: String::from(
                "# Cross-compositions against exact solutions and second methods\n\n\
                 Each table lists what a composition measured, the reference it is \
                 compared with and the pass rule (checks; the study fails when one \
                 fails) or none (reported values).\n",
            ),
        }
    }

    /// The output folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Start the section of a composition: a title, a paragraph and the
    /// head of its table.
    pub fn section(&mut self, title: &str, text: &str) {
        let _ = write!(
            self.report,
            "\n## {title}\n\n{text}\n\n| id | measured | reference | rule | explanation |\n|---|---|---|---|---|\n"
        );
    }

    /// Free text after the table of the current section.
    pub fn text(&mut self, text: &str) {
        let _ = write!(self.report, "\n{text}\n");
    }

    /// Add a check; its description states the quantity, the reference
    /// and the pass rule.
    pub fn check(&mut self, item: Item, rule: Rule, computed: f64) {
        let reference = format!("{} ({})", fmt(rule.ideal()), item.reference);
        let judged = rule.judged();
        self.row(&item, computed, &reference, &judged.words());
        self.checks.push(Check::new(
            item.id,
            format!("{}; reference: {}", item.what, item.reference),
            item.unit,
            computed,
            &judged,
        ));
    }

    /// Add a value reported without a pass rule, beside its reference value
    /// if there is one.
    pub fn value(&mut self, item: Item, reference: Option<f64>, computed: f64) {
        let shown = reference.map_or_else(
            || item.reference.to_string(),
            |r| format!("{} ({})", fmt(r), item.reference),
        );
        self.row(&item, computed, &shown, "none (reported)");
        self.values.push(Reported {
            id: item.id.into(),
            description: format!("{}; reference: {}", item.what, item.reference),
            paper: reference,
            computed,
            unit: item.unit.into(),
        });
    }

    fn row(&mut self, item: &Item, computed: f64, reference: &str, rule: &str) {
        let unit = if item.unit == "-" {
            String::new()
        } else {
            format!(" {}", item.unit)
        };
        let _ = writeln!(
            self.report,
            "| `{}` | {}{unit} | {reference} | {rule} | {} |",
            item.id,
            fmt(computed),
            item.note
        );
    }

    /// List a file written into the output folder.
    pub fn file(&mut self, name: &str) {
        self.files.push(name.into());
    }

    fn finish(self) -> Result<Summary> {
        Summary {
            study: NAME.into(),
            paper: "none (cross-compositions)".into(),
            checks: self.checks,
            values: self.values,
            files: self.files,
        }
        .write_with_report(&self.dir, &self.report)
    }
}

/// A number for the report: integers as they are, other moderate
/// magnitudes to ten decimals (a ratio's departure from 1 shows), the rest
/// in scientific notation.
fn fmt(v: f64) -> String {
    if v == v.trunc() && v.abs() < 1e6 {
        format!("{v}")
    } else if (1e-3..1e5).contains(&v.abs()) {
        format!("{v:.10}")
    } else {
        format!("{v:.4e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A check passes by its rule, fails on NaN (a run without a result),
    /// and its description states the reference and the rule.
    #[test]
    fn checks_are_judged_by_their_rule_and_say_so() {
        let dir = std::env::temp_dir().join(format!("dismech-compositions-{}", std::process::id()));
        let mut c = Collector::new(dir);
        c.section("title", "text");
        let item = Item {
            id: "x.ratio",
            what: "a ratio",
            reference: "the exact value",
            unit: "-",
            note: "why",
        };
        let near = Rule::Near {
            target: 1.0,
            tolerance: 1e-6,
        };
        c.check(item, near, 1.0 + 5e-7);
        c.check(item, near, 1.0 + 2e-6);
        c.check(item, Rule::AtMost(1e-8), f64::NAN);
        c.value(item, None, 3.0);
        let passed: Vec<bool> = c.checks.iter().map(|k| k.passed).collect();
        assert_eq!(passed, [true, false, false]);
        assert!(c.checks[0].description.contains("the exact value"));
        assert_eq!(c.checks[0].rule.words(), "within 1e-6 of 1");
        assert_eq!(c.checks[0].reference, Some(1.0));
        assert_eq!(c.checks[0].paper, None);
        assert_eq!(c.values.len(), 1);
        assert_eq!(c.report.matches("| `x.ratio` |").count(), 4);
    }
}
