//! Reproductions of the papers' examples, and the cross-compositions
//! checked against exact solutions and second methods: each builds its
//! scenes from the library pieces, runs them, compares with the paper or
//! the reference and writes its numbers, plots and `summary.json` into
//! `OUT/<study>/`.

pub mod compositions;
pub mod fill_patterns;
pub mod hashimoto_dda;
pub mod katsuki1990;
pub mod yamada2000;
pub mod yamaguchi_hpm;

use std::path::PathBuf;

use dismech::error::{DismechError, Result};
use dismech::output::Summary;

/// Options shared by every study.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyOptions {
    /// Output folder; each study writes into `out/<study>/`.
    pub out: PathBuf,
    /// Show progress bars on the terminal.
    pub progress: bool,
}

/// The studies that exist, by name.
pub const STUDIES: &[&str] = &[
    "katsuki1990",
    "yamada2000",
    "hashimoto-dda",
    "yamaguchi-hpm",
    compositions::NAME,
];

/// Run the study `name` (or every study for `all`).
pub fn run(name: &str, options: &StudyOptions) -> Result<Vec<Summary>> {
    match name {
        "all" => STUDIES.iter().map(|s| run_one(s, options)).collect(),
        other => Ok(vec![run_one(other, options)?]),
    }
}

fn run_one(name: &str, options: &StudyOptions) -> Result<Summary> {
    match name {
        "katsuki1990" => katsuki1990::reproduce(options),
        "yamada2000" => yamada2000::reproduce(options),
        "hashimoto-dda" => hashimoto_dda::reproduce(options),
        "yamaguchi-hpm" => yamaguchi_hpm::reproduce(options),
        compositions::NAME => compositions::reproduce(options),
        other => Err(DismechError::UnknownStudy(
            other.to_string(),
            STUDIES.join(", "),
        )),
    }
}
