//! The `dismech` command line.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use dismech::reproduce::{self, StudyOptions};

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
    /// Reproduce a paper's examples and compare with its numbers.
    Reproduce {
        /// Study name (katsuki1990) or `all`.
        study: String,
        /// Output folder; each study writes into OUT/<study>/.
        #[arg(long, default_value = "results")]
        out: PathBuf,
        /// Hide the progress bars.
        #[arg(long)]
        quiet: bool,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
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
