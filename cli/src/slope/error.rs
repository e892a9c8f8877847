//! Why `dismech slope` stopped: each error names the option and the value
//! (or the file) at fault.

use dismech::error::DismechError;
use dismech::slope::{Refusal, SearchCounts};

/// Why `dismech slope` stopped without writing its folder.
#[derive(Debug, thiserror::Error)]
pub enum SlopeError {
    /// An option's value is refused: the library's error, with the option
    /// and the value as given.
    #[error("{flag} {value}: {error}")]
    Argument {
        /// The option (`--dem`, `--stride`, …).
        flag: &'static str,
        /// Its value as given.
        value: String,
        /// What is wrong with it.
        #[source]
        error: Box<DismechError>,
    },
    /// An option of the other family was given (it would be ignored).
    #[error("{flag} {value}: not an option of --search {family} (it would be ignored)")]
    Unused {
        /// The option.
        flag: &'static str,
        /// Its value as given.
        value: String,
        /// The family searched.
        family: &'static str,
    },
    /// No trial surface of the family gave a factor of safety: every one
    /// left the DEM, stayed above the ground or fell outside the limits
    /// (or, with `--bedrock`, was cut off by a bedrock at or near the
    /// ground).
    #[error(
        "no trial surface gave a factor of safety: of {} trials, {} (the family `{family}` does not fit the DEM of {} m × {} m, cells of {} m: choose sizes that cut the ground inside it{})",
        .counts.trials, refusals(.counts).join(", "), .dem.0, .dem.1, .dem.2, bedrock_hint(.bedrock.as_deref())
    )]
    NoSurface {
        /// The family as options.
        family: String,
        /// The DEM's width and height (m) and cell size (m).
        dem: (f64, f64, f64),
        /// Trials and refusals.
        counts: Box<SearchCounts>,
        /// The `--bedrock` file, where one was given.
        bedrock: Option<String>,
    },
    /// `--hpm K` asks for more surfaces than `--keep` lists (the HPM
    /// results go into the list of critical.csv).
    #[error("--hpm {hpm}: re-analyses more surfaces than --keep {keep} lists in critical.csv (where the HPM Fs are written): give --keep {hpm} or more, or --hpm {keep} or fewer")]
    HpmAboveKeep {
        /// `--hpm`.
        hpm: usize,
        /// `--keep`.
        keep: usize,
    },
    /// The search or the outputs failed (the error names the file).
    #[error(transparent)]
    Run(Box<DismechError>),
}

impl SlopeError {
    /// An option's value refused by `error`.
    pub fn argument(flag: &'static str, value: &str, error: DismechError) -> Self {
        Self::Argument {
            flag,
            value: value.to_string(),
            error: Box::new(error),
        }
    }
}

impl From<DismechError> for SlopeError {
    fn from(error: DismechError) -> Self {
        Self::Run(Box::new(error))
    }
}

/// The part of [`SlopeError::NoSurface`]'s message on `--bedrock`.
fn bedrock_hint(bedrock: Option<&str>) -> String {
    match bedrock {
        None => String::new(),
        Some(file) => format!(
            "; or the bedrock --bedrock {file} cuts them off: a surface is raised to the bedrock where it goes below it, and has no column where the bedrock lies at or above the ground, so a bedrock at or near the ground leaves too few columns or none"
        ),
    }
}

/// A refusal in the words of a summary.
pub fn refusal_words(reason: Refusal) -> &'static str {
    match reason {
        Refusal::CentreOffDem => "centre over no ground data",
        Refusal::LeavesDem => "leave the DEM",
        Refusal::NoData => "cover a no-data cell",
        Refusal::TooFewColumns => "too few columns",
        Refusal::Volume => "volume outside --volume",
        Refusal::Area => "area outside --area",
        Refusal::Depth => "depth outside --depth",
        Refusal::NothingDrives => "nothing drives the slide",
        Refusal::NoStrength => "no strength left",
        Refusal::SmallMAlpha => {
            "Bishop's m_alpha at or below its floor (--m-alpha-floor) at a column"
        }
        Refusal::NotConverged => "Bishop's iteration did not settle",
    }
}

/// The refusals of `counts`, largest first, as `n reason` items.
pub fn refusals(counts: &SearchCounts) -> Vec<String> {
    let mut items: Vec<(u64, Refusal)> = Refusal::ALL
        .iter()
        .map(|&r| (counts.refused_for(r), r))
        .filter(|(n, _)| *n > 0)
        .collect();
    items.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
    items
        .into_iter()
        .map(|(n, r)| format!("{n} {}", refusal_words(r)))
        .collect()
}
