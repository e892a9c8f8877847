//! The `dismech` command line.

mod reproduce;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use dismech::error::DismechError;
use dismech::limit::analyse;
use dismech::limit::lattice::Lattice;
use dismech::lp::LinearProgramSolver;
use reproduce::StudyOptions;

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
    /// Limit load of a lattice of rigid circles by LP (paper 002's U- and
    /// L-models; R = 1, C_p = 1).
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
}

fn lattice_limit_load(
    model: &str,
    m: usize,
    n: usize,
    nprime: usize,
    rolling: bool,
    c_wall: f64,
) -> Result<serde_json::Value, DismechError> {
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
    Ok(serde_json::json!({
        "model": model,
        "m": m,
        "n": n,
        "nprime": if model == "u" { Some(nprime) } else { None },
        "rolling": rolling,
        "c_wall": c_wall,
        "status": format!("{:?}", result.status),
        "p_over_cp": result.load,
        "kinematic_p_over_cp": result.kinematic_load,
        "static_p_over_cp": result.static_load,
        "plate_length": lattice.plate_length(),
        "solver": {
            "name": "clarabel",
            "status": result.solver_status,
            "iterations": result.iterations,
            "variables": result.lp_size.0,
            "equality_rows": result.lp_size.1,
            "nonzeros": result.lp_size.2,
            "seconds": seconds,
        }
    }))
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::LatticeLimitLoad {
            model,
            m,
            n,
            nprime,
            no_rolling,
            c_wall,
            json: _,
        } => match lattice_limit_load(&model, m, n, nprime, !no_rolling, c_wall) {
            Ok(value) => {
                println!("{value}");
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::FAILURE
            }
        },
        Command::Reproduce { study, out, quiet } => {
            let options = StudyOptions {
                out: out.clone(),
                progress: !quiet,
            };
            match reproduce::run(&study, &options) {
                Ok(summaries) => {
                    let mut all_passed = true;
                    for s in &summaries {
                        println!("{} ({})", s.study, s.paper);
                        for c in &s.checks {
                            let paper = c
                                .paper
                                .map(|p| format!("{p}"))
                                .unwrap_or_else(|| "-".into());
                            println!(
                                "  [{}] {:<34} computed {:>12.6e}  paper {:>8}  tol {:.1e}",
                                if c.passed { "pass" } else { "FAIL" },
                                c.id,
                                c.computed,
                                paper,
                                c.tolerance
                            );
                        }
                        for v in &s.values {
                            let paper = v
                                .paper
                                .map(|p| format!("{p}"))
                                .unwrap_or_else(|| "-".into());
                            println!(
                                "  [value] {:<33} computed {:>12.6e}  paper {:>8}",
                                v.id, v.computed, paper
                            );
                        }
                        println!("  written to {}", out.join(&s.study).display());
                        all_passed &= s.all_passed();
                    }
                    if all_passed {
                        ExitCode::SUCCESS
                    } else {
                        eprintln!("some checks failed (see summary.json)");
                        ExitCode::from(2)
                    }
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::FAILURE
                }
            }
        }
    }
}
