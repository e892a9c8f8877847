//! Scenario files: a model described in TOML, built from the library's
//! pieces, run, and written out (`dismech run model.toml`).
//!
//! A scenario's tables are the slots of a composition (see the crate docs
//! of [`dismech`]): `[driver]`, `[kinematics]`, `[boundary]`,
//! `[[bodies]]`, `[law]`, `[[pair_laws]]`, `[integrator]`, `[linear_solver]`,
//! `[lp_solver]`, `[loads]`, `[run]`, `[limit_analysis]` and `[output]`.
//! A slot's `kind`
//! chooses its piece; a combination the library cannot compose is refused
//! with an error naming both keys, an unknown key is refused, and every
//! refusal names the file, the line and column, the key and the value
//! (`docs/scenarios.md` lists every key).
//!
//! | concept | file |
//! |---|---|
//! | the file's text, its spanned tree, errors placed in it | `source.rs` |
//! | the `kind` tag moved out so that values keep their spans | `retag.rs` |
//! | the tables, one file each (`[[pair_laws]]` in `law.rs`) | `driver.rs`, `bodies.rs`, `boundary.rs`, `law.rs`, `solvers.rs`, `loads.rs`, `run.rs`, `output.rs` |
//! | values checked and library errors named by their keys | `check.rs` |
//! | the models built for each driver | `explicit.rs`, `implicit.rs`, `limit.rs`, `hpm.rs` |
//! | the limit analysis of the explicit driver's final packing | `analysis.rs` |
//! | the run: progress, frames, summary, the folder written whole | `execute.rs` |
//! | checkpoints of a run and its resumption | `checkpoint.rs` |

pub mod analysis;
pub mod bodies;
pub mod boundary;
mod check;
pub mod checkpoint;
pub mod driver;
mod exact;
mod execute;
mod explicit;
pub mod fuzz;
mod hpm;
mod implicit;
pub mod law;
mod limit;
pub mod loads;
pub mod output;
pub mod retag;
pub mod run;
pub mod solvers;
pub mod source;

use std::path::{Path, PathBuf};

use dismech::error::DismechError;
use serde::Deserialize;

pub use execute::{check_resume, execute, resume, Finished};
pub use source::{KeyPath, Located, Source};

/// A scenario file as read: one field per table.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScenarioSpec {
    /// A title, copied into the summary.
    pub title: Option<String>,
    /// `[driver]`.
    pub driver: driver::DriverSpec,
    /// `[kinematics]` (implicit driver; rigid by default).
    pub kinematics: Option<solvers::KinematicsSpec>,
    /// `[boundary]` (explicit driver).
    pub boundary: Option<boundary::BoundarySpec>,
    /// `[[bodies]]`.
    #[serde(default)]
    pub bodies: Vec<bodies::BodySpec>,
    /// `[law]`.
    pub law: law::LawSpec,
    /// `[[pair_laws]]` (implicit driver): laws per pair of body groups,
    /// in place of `[law]`'s.
    #[serde(default)]
    pub pair_laws: Vec<law::PairLawSpec>,
    /// `[integrator]`.
    pub integrator: Option<solvers::IntegratorSpec>,
    /// `[linear_solver]` (implicit driver; sparse LU by default).
    pub linear_solver: Option<solvers::LinearSolverSpec>,
    /// `[lp_solver]` (limit driver; Clarabel by default).
    pub lp_solver: Option<solvers::LpSolverSpec>,
    /// `[loads]`.
    #[serde(default)]
    pub loads: loads::LoadsSpec,
    /// `[run]` (time-stepping drivers).
    pub run: Option<run::RunSpec>,
    /// `[limit_analysis]` (explicit driver): the limit analysis of the
    /// final packing.
    pub limit_analysis: Option<analysis::LimitAnalysisSpec>,
    /// `[output]`.
    #[serde(default)]
    pub output: output::OutputSpec,
}

/// Limits set on the command line over the file's `[run]`, to run a
/// scenario at reduced size.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Overrides {
    /// Take at most this many steps.
    pub max_steps: Option<u64>,
    /// Stop at this simulated time at the latest (s).
    pub end_time: Option<f64>,
}

/// Why a scenario was not run or did not finish.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ScenarioError {
    /// The file could not be read.
    #[error("{file}: cannot be read: {message}")]
    Read {
        /// The file.
        file: String,
        /// Why.
        message: String,
    },
    /// The file is refused: a syntax error, an unknown key, a value out of
    /// range, a combination the library cannot compose.
    #[error("{0}")]
    Invalid(Box<Located>),
    /// A command-line limit is out of range.
    #[error("{0}")]
    Option(String),
    /// The run stopped, or its output could not be written.
    #[error("{file}: {error}")]
    Run {
        /// The file.
        file: String,
        /// What stopped it.
        error: Box<DismechError>,
    },
}

impl From<Box<Located>> for ScenarioError {
    fn from(located: Box<Located>) -> Self {
        Self::Invalid(located)
    }
}

/// The output folder of `file` when none is given: beside it, named
/// after it (`model.toml` → `model.out/`).
pub fn default_output(file: &Path) -> PathBuf {
    let stem = file
        .file_stem()
        .map_or_else(|| "scenario".into(), |s| s.to_string_lossy().into_owned());
    file.with_file_name(format!("{stem}.out"))
}

/// Read `text` (the contents of `file`) into a [`ScenarioSpec`].
///
/// # Errors
/// [`Located`] at the first syntax error, unknown key, missing key or
/// value of the wrong type.
pub fn parse(source: &Source<'_>) -> Result<ScenarioSpec, Box<Located>> {
    let mut tree = source.tree();
    retag::retag(&mut tree);
    let deserializer = toml::de::Deserializer::from(tree);
    ScenarioSpec::deserialize(deserializer).map_err(|e| {
        let message = explain(e.message());
        let mut located = match e.span() {
            Some(span) => source.at_span(span, message),
            None => source.at_key(&KeyPath::default(), message),
        };
        if let Some(field) = missing_field(e.message()) {
            located.key = match e
                .span()
                .and_then(|span| source::innermost_key(source, span))
            {
                Some(table) => format!("{table}.{field}"),
                None => field.to_string(),
            };
            located.value = None;
        }
        Box::new(located)
    })
}

/// serde's message, with the tag that stood for a missing `kind` said in
/// words.
fn explain(message: &str) -> String {
    let missing = format!("unknown variant `{}`", retag::MISSING_KIND);
    match message.trim_end().strip_prefix(&missing) {
        Some(rest) => {
            let kinds = rest.trim_start_matches([',', ' ']);
            let kinds = kinds.strip_prefix("expected ").unwrap_or(kinds);
            format!(
                "no `kind` (or a `kind` that is not a string) in this table; give `kind` = {kinds}"
            )
        }
        None => message.trim_end().to_string(),
    }
}

/// The key a serde message names as missing (`missing field `x``).
fn missing_field(message: &str) -> Option<&str> {
    message.strip_prefix("missing field `")?.split('`').next()
}

/// A scenario built and checked, ready to run.
pub struct Prepared {
    /// The scenario as read.
    pub spec: ScenarioSpec,
    /// The model of its driver.
    pub model: Model,
    /// The checkpoints it writes.
    pub checkpoints: Option<checkpoint::Plan>,
}

/// The model of one driver, built from a scenario.
pub enum Model {
    /// Explicit dynamics.
    Explicit(explicit::ExplicitModel),
    /// Implicit dynamics.
    Implicit(implicit::ImplicitModel),
    /// Limit analysis.
    Limit(Box<limit::LimitPlan>),
    /// The HPM on grid columns.
    Hpm(Box<hpm::HpmPlan>),
}

/// Parse, build and check the scenario `text` read from `file`, with the
/// command-line limits `overrides`; nothing is run and nothing written.
///
/// # Errors
/// [`ScenarioError::Invalid`] naming the file, line, column, key and value
/// of the first thing refused; [`ScenarioError::Option`] for a limit out
/// of range.
pub fn prepare(file: &Path, text: &str, overrides: Overrides) -> Result<Prepared, ScenarioError> {
    if overrides.max_steps == Some(0) {
        return Err(ScenarioError::Option(
            "--max-steps 0: give at least 1 step".into(),
        ));
    }
    if let Some(t) = overrides.end_time {
        if !(t.is_finite() && t > 0.0) {
            return Err(ScenarioError::Option(format!(
                "--end-time {t}: give a finite time > 0 s"
            )));
        }
    }
    let source = Source::parse(file, text)?;
    let spec = parse(&source)?;
    if let Some(segments) = spec.output.segments {
        check::count(
            &source,
            &KeyPath::root("output").key("segments"),
            segments,
            3,
            1 << 16,
        )?;
    }
    if spec.limit_analysis.is_some() && !matches!(spec.driver, driver::DriverSpec::Explicit(_)) {
        return Err(ScenarioError::Invalid(check::combination(
            &source,
            &[
                &KeyPath::root("driver").key("kind"),
                &KeyPath::root("limit_analysis"),
            ],
            "`[limit_analysis]` analyses the explicit driver's final packing; the limit driver analyses bodies given in the file",
        )));
    }
    if !matches!(spec.driver, driver::DriverSpec::Implicit(_)) {
        refuse_groups(&source, &spec)?;
    }
    let model = match &spec.driver {
        driver::DriverSpec::Explicit(settings) => {
            Model::Explicit(explicit::build(&source, &spec, settings, overrides)?)
        }
        driver::DriverSpec::Implicit(settings) => {
            Model::Implicit(implicit::build(&source, &spec, settings, overrides)?)
        }
        driver::DriverSpec::Limit(settings) => {
            Model::Limit(Box::new(limit::build(&source, &spec, settings)?))
        }
        driver::DriverSpec::Hpm(settings) => {
            Model::Hpm(Box::new(hpm::build(&source, &spec, settings, file)?))
        }
    };
    let checkpoints = checkpoint::plan(&source, &spec, &model)?;
    Ok(Prepared {
        spec,
        model,
        checkpoints,
    })
}

/// Refuse the contact groups (`[[pair_laws]]`, a body's `group`) beside
/// a driver other than the implicit one, which alone takes a law per pair
/// of groups.
fn refuse_groups(source: &Source<'_>, spec: &ScenarioSpec) -> Result<(), Box<Located>> {
    let kind = KeyPath::root("driver").key("kind");
    let why = "contact groups choose the implicit driver's law per pair of groups; this driver takes the one `[law]`";
    if !spec.pair_laws.is_empty() {
        return Err(check::combination(
            source,
            &[&kind, &KeyPath::root("pair_laws")],
            why,
        ));
    }
    match spec.bodies.iter().position(|b| b.group().is_some()) {
        Some(k) => Err(check::combination(
            source,
            &[&kind, &KeyPath::root("bodies").index(k).key("group")],
            why,
        )),
        None => Ok(()),
    }
}

/// Read the scenario `file` and [`prepare`] it.
///
/// # Errors
/// [`ScenarioError::Read`] when the file cannot be read (or is not
/// UTF-8), and those of [`prepare`].
pub fn load(file: &Path, overrides: Overrides) -> Result<Prepared, ScenarioError> {
    let text = std::fs::read_to_string(file).map_err(|e| ScenarioError::Read {
        file: file.display().to_string(),
        message: e.to_string(),
    })?;
    prepare(file, &text, overrides)
}
