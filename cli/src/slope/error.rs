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
    /// left the DEM, stayed above the ground or fell outside the limits.
    #[error(
        "no trial surface gave a factor of safety: of {} trials, {} (the family `{family}` does not fit the DEM of {} m × {} m, cells of {} m: choose sizes that cut the ground inside it)",
        .counts.trials, refusals(.counts).join(", "), .dem.0, .dem.1, .dem.2
    )]
    NoSurface {
        /// The family as options.
        family: String,
        /// The DEM's width and height (m) and cell size (m).
        dem: (f64, f64, f64),
        /// Trials and refusals.
        counts: Box<SearchCounts>,
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
