//! How a study ended, as the console shows it: each study's checks as it
//! ends, then one table of every study (passed, failed, could not run), and
//! the exit status of the whole run.

use std::fmt::Write as _;
use std::path::Path;

use dismech::error::Result;
use dismech_cli::output::{check_line, value_line, Summary};

use crate::exit_status::Exit;

/// How a study ended.
#[derive(Debug)]
pub struct Outcome {
    /// The study's name.
    pub study: &'static str,
    /// Its summary, written into `OUT/<study>/`, or why it could not run
    /// or could not write (the previous `OUT/<study>/` is then untouched).
    pub result: Result<Summary>,
}

impl Outcome {
    /// The exit status this study alone would give.
    pub fn exit(&self) -> Exit {
        match &self.result {
            Ok(summary) if summary.all_passed() => Exit::Success,
            Ok(_) => Exit::CheckFailed,
            Err(e) => Exit::of_error(e),
        }
    }

    /// The study's verdict in a few words.
    pub fn verdict(&self) -> String {
        match &self.result {
            Ok(summary) => {
                let failed: Vec<&str> = summary
                    .checks
                    .iter()
                    .filter(|c| !c.passed)
                    .map(|c| c.id.as_str())
                    .collect();
                if failed.is_empty() {
                    format!("passed ({} checks)", summary.checks.len())
                } else {
                    format!(
                        "FAILED ({} of {} checks failed: {})",
                        failed.len(),
                        summary.checks.len(),
                        failed.join(", ")
                    )
                }
            }
            Err(e) => format!("could not run: {e}"),
        }
    }

    /// The study's block as it ends: its checks and values, and where they
    /// were written; or why it could not run.
    pub fn block(&self, out: &Path) -> String {
        let dir = out.join(self.study);
        let mut text = String::new();
        match &self.result {
            Ok(s) => {
                let _ = writeln!(text, "{} ({})", s.study, s.paper);
                for c in &s.checks {
                    let _ = writeln!(text, "  {}", check_line(c));
                }
                for v in &s.values {
                    let _ = writeln!(text, "  {}", value_line(v));
                }
                let _ = writeln!(text, "  written to {}", dir.display());
            }
            Err(e) => {
                let _ = writeln!(
                    text,
                    "{}: could not run: {e}\n  {} left as it was",
                    self.study,
                    dir.display()
                );
            }
        }
        text
    }
}

/// The closing table: one row per study.
pub fn table(outcomes: &[Outcome]) -> String {
    let width = outcomes
        .iter()
        .map(|o| o.study.len())
        .max()
        .unwrap_or(0)
        .max("study".len());
    let mut text = format!("{:<width$}  result\n", "study");
    for o in outcomes {
        let _ = writeln!(text, "{:<width$}  {}", o.study, o.verdict());
    }
    text
}

/// The exit status of a run: success when every study passed, a failed
/// check when one failed, and otherwise the status of the first study that
/// could not run.
pub fn exit(outcomes: &[Outcome]) -> Exit {
    let mut exit = Exit::Success;
    for o in outcomes {
        match o.exit() {
            Exit::Success => {}
            Exit::CheckFailed => {
                if exit == Exit::Success {
                    exit = Exit::CheckFailed;
                }
            }
            not_run => {
                if matches!(exit, Exit::Success | Exit::CheckFailed) {
                    exit = not_run;
                }
            }
        }
    }
    exit
}
