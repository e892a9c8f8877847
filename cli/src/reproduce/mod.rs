//! Reproductions of the papers' examples, and the cross-compositions
//! checked against exact solutions and second methods: each builds its
//! scenes from the library pieces, runs them, compares with the paper or
//! the reference and writes its numbers, plots and `summary.json` into
//! `OUT/<study>/`.
//!
//! A study writes into a staging folder beside `OUT/<study>/` that takes
//! its place only once the study has written everything
//! ([`StagedFolder`]): a study that fails or is killed leaves the previous
//! results whole. `all` runs every study, whatever became of the ones
//! before it.

pub mod compositions;
pub mod fill_patterns;
pub mod hashimoto_dda;
pub mod katsuki1990;
pub mod outcome;
pub mod yamada2000;
pub mod yamaguchi_hpm;

use std::path::{Path, PathBuf};

use dismech::error::{DismechError, Result};
use dismech_cli::output::{StagedFolder, Summary};
pub use outcome::Outcome;

/// Options of one study's run.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyOptions {
    /// The folder the study writes into: a staging folder that becomes
    /// `OUT/<study>/` once the study has written everything.
    pub dir: PathBuf,
    /// Show progress bars on the terminal.
    pub progress: bool,
}

/// A study: its name (and output folder) and how it runs.
#[derive(Debug, Clone, Copy)]
pub struct Study {
    /// Name, as given on the command line.
    pub name: &'static str,
    /// Runs the study, writing into [`StudyOptions::dir`].
    pub run: fn(&StudyOptions) -> Result<Summary>,
}

/// The studies that exist, in the order `all` runs them.
pub const STUDIES: &[Study] = &[
    Study {
        name: "katsuki1990",
        run: katsuki1990::reproduce,
    },
    Study {
        name: "yamada2000",
        run: yamada2000::reproduce,
    },
    Study {
        name: "hashimoto-dda",
        run: hashimoto_dda::reproduce,
    },
    Study {
        name: "yamaguchi-hpm",
        run: yamaguchi_hpm::reproduce,
    },
    Study {
        name: compositions::NAME,
        run: compositions::reproduce,
    },
];

/// The studies `name` stands for: one study, or every study for `all`.
pub fn select(name: &str) -> Result<Vec<Study>> {
    if name == "all" {
        return Ok(STUDIES.to_vec());
    }
    STUDIES
        .iter()
        .find(|s| s.name == name)
        .map(|s| vec![*s])
        .ok_or_else(|| {
            let known: Vec<&str> = STUDIES.iter().map(|s| s.name).collect();
            DismechError::UnknownStudy(name.to_string(), known.join(", "))
        })
}

/// Run one study into a staging folder and put it in place of
/// `out/<study>/` once everything is written.
pub fn run_study(study: &Study, out: &Path, progress: bool) -> Result<Summary> {
    let folder = StagedFolder::new(&out.join(study.name))?;
    let options = StudyOptions {
        dir: folder.path().to_path_buf(),
        progress,
    };
    let summary = (study.run)(&options)?;
    folder.commit()?;
    Ok(summary)
}

/// Run every study of `studies`, whether or not the ones before passed or
/// ran; `done` is called as each ends.
pub fn run_all(
    studies: &[Study],
    out: &Path,
    progress: bool,
    mut done: impl FnMut(&Outcome),
) -> Vec<Outcome> {
    studies
        .iter()
        .map(|study| {
            let outcome = Outcome {
                study: study.name,
                result: run_study(study, out, progress),
            };
            done(&outcome);
            outcome
        })
        .collect()
}

#[cfg(test)]
mod tests;
