//! The `dismech` command line.

mod exit_status;
mod reproduce;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use dismech::error::DismechError;
use dismech::limit::lattice::Lattice;
use dismech::limit::{analyse, LimitStatus};
use dismech::lp::LinearProgramSolver;
use dismech_cli::scenario::Overrides;
use dismech_cli::slope::{SlopeArgs, SlopeError};
use exit_status::Exit;

#[derive(Parser)]
#[command(
    name = "dismech",
    version,
    about = "Discrete mechanics of granular and blocky geomaterials"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Reproduce a paper's examples and compare with its numbers, or run the
    /// cross-compositions against exact solutions and second methods.
    ///
    /// Each study's folder is replaced whole once the study has written
    /// everything; a study that fails or is interrupted leaves the previous
    /// folder as it was. `all` runs every study, whatever became of the
    /// ones before, and ends with a table of each study's outcome.
    Reproduce {
        /// Study name (katsuki1990, yamada2000, hashimoto-dda, yamaguchi-hpm,
        /// compositions) or `all`.
        study: String,
        /// Output folder; each study writes into OUT/<study>/.
        #[arg(long, default_value = "results")]
        out: PathBuf,
        /// Hide the progress bars.
        #[arg(long)]
        quiet: bool,
    },
    /// Run a model described in a scenario file (TOML): build it from its
    /// slots, run it, and write ParaView frames (`.pvd` indices), the HPM
    /// driver's maps (ESRI ASCII and GeoTIFF) and `summary.json` into the
    /// output folder, replaced whole once all is written. `docs/scenarios.md` lists every key.
    Run {
        /// The scenario file.
        file: PathBuf,
        /// Output folder (default: beside the file, `NAME.out/`).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Hide the progress bar.
        #[arg(long)]
        quiet: bool,
        /// Take at most this many steps (runs a scenario at reduced size).
        #[arg(long)]
        max_steps: Option<u64>,
        /// Stop at this simulated time (s) at the latest.
        #[arg(long)]
        end_time: Option<f64>,
        /// Parse, build and check the scenario, then stop (nothing is run
        /// or written); with `--resume`, check also that the checkpoint
        /// resumes this scenario (readable, of its driver and model, before
        /// the run's end).
        #[arg(long)]
        check: bool,
        /// Resume the run from this checkpoint (written by the same
        /// scenario's `output.checkpoint_every`), to the same bits as the
        /// run never stopped.
        #[arg(long, value_name = "CHECKPOINT")]
        resume: Option<PathBuf>,
    },
    /// Limit load of a lattice of rigid circles by LP (paper 002's U- and
    /// L-models; R = 1, C_p = 1).
    ///
    /// Prints one JSON object whatever the outcome; the exit status tells
    /// a locked lattice (3) and a solver in trouble (5) from a found limit
    /// load (0).
    LatticeLimitLoad {
        /// Lattice: `u` (half footing, symmetry wall) or `l`.
        #[arg(long, value_parser = ["u", "l"])]
        model: String,
        /// Columns (even).
        #[arg(long)]
        m: usize,
        /// Elements per column.
        #[arg(long)]
        n: usize,
        /// Elements under the plate (U-model).
        #[arg(long, default_value_t = 1)]
        nprime: usize,
        /// Fix the rotation of every element.
        #[arg(long)]
        no_rolling: bool,
        /// Strength of the base and far walls, in units of C_p.
        #[arg(long, default_value_t = 2.0)]
        c_wall: f64,
        /// Print one JSON object (the default prints the same object).
        #[arg(long)]
        json: bool,
    },
    /// Slope stability over a terrain: search trial slip surfaces (a grid
    /// of spheres or random ellipsoids) over a DEM by Hovland's method (or
    /// Bishop's, with --method bishop) and map the lowest factor of safety
    /// of each cell.
    ///
    /// Writes into OUT (replaced whole once every file is written): the
    /// lowest Fs per cell and the volume, area and depth of the surface
    /// that gave it as ESRI ASCII grids on the DEM's grid (slope_fs.asc,
    /// slope_volume.asc, slope_area.asc, slope_depth.asc) and as GeoTIFF
    /// (slope_fs.tif, ...), the most
    /// critical surfaces (critical.csv), the map (map.svg) and
    /// summary.json. The family's sizes default to fractions of the DEM's
    /// extent (each overridable).
    Slope(Box<SlopeArgs>),
}

fn lattice_limit_load(
    model: &str,
    m: usize,
    n: usize,
    nprime: usize,
    rolling: bool,
    c_wall: f64,
) -> Result<(serde_json::Value, LimitStatus), DismechError> {
    let mut lattice = if model == "u" {
        Lattice::u_model(m, n, nprime, rolling)
    } else {
        Lattice::l_model(m, n, rolling)
    };
    lattice.wall_cohesion = c_wall;
    let built = lattice.build()?;
    let start = std::time::Instant::now();
    let result = analyse(&built, &mut LinearProgramSolver::default())?;
    let seconds = start.elapsed().as_secs_f64();
    let mut value = serde_json::json!({
        "model": model,
        "m": m,
        "n": n,
        "nprime": if model == "u" { Some(nprime) } else { None },
        "rolling": rolling,
        "c_wall": c_wall,
    });
    if let Some(object) = value.as_object_mut() {
        object.extend(dismech_cli::output::limit_summary(
            &result,
            lattice.plate_length(),
        ));
        if let Some(solver) = object.get_mut("solver").and_then(|s| s.as_object_mut()) {
            solver.insert("seconds".into(), serde_json::json!(seconds));
        }
    }
    Ok((value, result.status))
}

/// `lattice-limit-load`: the JSON object on stdout, the outcome in the
/// exit status (and in words on stderr when no limit load was found).
fn lattice_command(
    model: &str,
    m: usize,
    n: usize,
    nprime: usize,
    rolling: bool,
    c_wall: f64,
) -> Exit {
    match lattice_limit_load(model, m, n, nprime, rolling, c_wall) {
        Ok((value, status)) => {
            println!("{value}");
            let exit = Exit::of_limit(&status);
            if exit != Exit::Success {
                eprintln!("no limit load ({status:?}): {}", exit.meaning());
            }
            exit
        }
        Err(e) => {
            eprintln!("error: {e}");
            Exit::of_error(&e)
        }
    }
}

/// `reproduce`: every study named, each printed as it ends, then the table
/// of outcomes.
fn reproduce_command(study: &str, out: &Path, progress: bool) -> Exit {
    let studies = match reproduce::select(study) {
        Ok(studies) => studies,
        Err(e) => {
            eprintln!("error: {e}");
            return Exit::of_error(&e);
        }
    };
    let outcomes = reproduce::run_all(&studies, out, progress, |o| {
        print!("{}", o.block(out));
    });
    println!("\n{}", reproduce::outcome::table(&outcomes));
    reproduce::outcome::exit(&outcomes)
}

/// `run`: the scenario built, run and written; the outcome in the exit
/// status (a refused file is bad input; a limit analysis exits as
/// `lattice-limit-load` does).
fn run_command(
    file: &Path,
    out: Option<&Path>,
    progress: bool,
    overrides: Overrides,
    check: bool,
    resume: Option<&Path>,
) -> Exit {
    use dismech_cli::scenario::{self, ScenarioError};
    let outcome = scenario::load(file, overrides).and_then(|prepared| {
        if check {
            match resume {
                Some(checkpoint) => {
                    let step = scenario::check_resume(prepared, file, checkpoint)?;
                    println!(
                        "{}: the scenario is valid and resumes from {} (step {step})",
                        file.display(),
                        checkpoint.display()
                    );
                }
                None => println!("{}: the scenario is valid", file.display()),
            }
            return Ok(None);
        }
        let out = out.map_or_else(|| scenario::default_output(file), Path::to_path_buf);
        match resume {
            Some(checkpoint) => scenario::resume(prepared, file, &out, progress, checkpoint),
            None => scenario::execute(prepared, file, &out, progress),
        }
        .map(Some)
    });
    match outcome {
        Ok(None) => Exit::Success,
        Ok(Some(finished)) => {
            println!("{}", finished.summary["outcome"]);
            println!("written: {}", finished.out.display());
            finished
                .limit_status
                .map_or(Exit::Success, |s| Exit::of_limit(&s))
        }
        Err(e) => {
            eprintln!("error: {e}");
            match &e {
                ScenarioError::Run { error, .. } => Exit::of_error(error),
                ScenarioError::Read { .. }
                | ScenarioError::Invalid(_)
                | ScenarioError::Option(_) => Exit::BadInput,
            }
        }
    }
}

/// `slope`: the search, its folder and its summary; the exit status of an
/// error from the library's error, bad input for an option refused.
fn slope_command(args: &SlopeArgs) -> Exit {
    match dismech_cli::slope::run(args) {
        Ok(report) => {
            println!("{report}");
            Exit::Success
        }
        Err(e) => {
            eprintln!("error: {e}");
            match &e {
                SlopeError::Run(error) => Exit::of_error(error),
                SlopeError::Argument { .. }
                | SlopeError::Unused { .. }
                | SlopeError::NoSurface { .. }
                | SlopeError::HpmAboveKeep { .. } => Exit::BadInput,
            }
        }
    }
}

fn main() -> ExitCode {
    let help = Exit::help();
    let mut command = Cli::command().after_help(help.clone());
    let names: Vec<String> = command
        .get_subcommands()
        .map(|c| c.get_name().to_string())
        .collect();
    for name in names {
        command = command.mut_subcommand(name, |c| c.after_help(help.clone()));
    }
    let matches = command.get_matches();
    let cli = Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit());
    let exit = match cli.command {
        Command::LatticeLimitLoad {
            model,
            m,
            n,
            nprime,
            no_rolling,
            c_wall,
            json: _,
        } => lattice_command(&model, m, n, nprime, !no_rolling, c_wall),
        Command::Reproduce { study, out, quiet } => reproduce_command(&study, &out, !quiet),
        Command::Slope(args) => slope_command(&args),
        Command::Run {
            file,
            out,
            quiet,
            max_steps,
            end_time,
            check,
            resume,
        } => run_command(
            &file,
            out.as_deref(),
            !quiet,
            Overrides {
                max_steps,
                end_time,
            },
            check,
            resume.as_deref(),
        ),
    };
    exit.into()
}
