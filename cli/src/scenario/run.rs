//! `[run]`: how long a time-stepping driver runs.

use serde::Deserialize;

/// When the run stops (`kind` = `to-rest`, `steps` or `time`).
#[derive(Debug, Clone, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum RunSpec {
    /// Until the assembly is at rest ([`dismech::explicit::RestCriterion`]):
    /// explicit driver.
    ToRest(ToRestSpec),
    /// A number of steps.
    Steps(StepsSpec),
    /// Up to a simulated time, in steps of the driver's `dt`.
    Time(TimeSpec),
}

impl RunSpec {
    /// The `kind` as written.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::ToRest(_) => "to-rest",
            Self::Steps(_) => "steps",
            Self::Time(_) => "time",
        }
    }
}

/// The rest criterion; every key has the library's default.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ToRestSpec {
    /// At rest below this ratio of kinetic to released energy.
    pub kinetic_to_released_ratio: Option<f64>,
    /// Not before this time (s).
    pub min_time: Option<f64>,
    /// Give up at this time (s).
    pub max_time: Option<f64>,
    /// Test every this many steps.
    pub check_every: Option<u64>,
    /// Consecutive checks that must pass.
    pub consecutive_checks: Option<u32>,
    /// And the mean unbalanced force below this share of the mean weight.
    pub unbalanced_force_ratio: Option<f64>,
    /// Give up after this many steps.
    pub max_steps: Option<u64>,
}

/// A number of steps.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepsSpec {
    /// Steps to take (≥ 1).
    pub steps: u64,
}

/// Up to a simulated time.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimeSpec {
    /// End time (s); `round(end_time / dt)` steps are taken.
    pub end_time: f64,
}
