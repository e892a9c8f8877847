//! Fuzz the scenario reader: every file of `examples/scenarios/` mutated
//! many times (keys deleted, duplicated, renamed; values of the wrong type
//! or at extremes; tables swapped; files truncated; random bytes), each
//! mutant parsed, built and checked (not run). Prints the files read, the
//! valid ones, the refusals that name their key and line, the refusals
//! that do not and the panics (both findings), and the time taken.
//!
//! Run with `cargo run --release -p dismech-cli --example fuzz_scenarios
//! -- [MUTANTS] [SEED]` (100 000 mutants and seed 1 by default).

use std::time::Instant;

use dismech_cli::scenario::fuzz;

fn main() -> std::process::ExitCode {
    let mut args = std::env::args().skip(1);
    let total: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(100_000);
    let seed: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(1);
    let folder = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/scenarios");
    let mut seeds = Vec::new();
    for entry in std::fs::read_dir(folder)
        .expect("examples/scenarios is readable")
        .flatten()
    {
        let path = entry.path();
        if path.extension().is_some_and(|e| e == "toml") {
            let text = std::fs::read_to_string(&path).expect("a scenario is readable");
            seeds.push((path.display().to_string(), text));
        }
    }
    seeds.sort();
    let per_seed = total.div_ceil(seeds.len() as u64);
    let start = Instant::now();
    let tally = fuzz::run(&seeds, per_seed, seed);
    let seconds = start.elapsed().as_secs_f64();
    println!(
        "{} mutated files from {} scenarios (seed {seed}) in {seconds:.1} s: {} valid, {} refused naming a key and a line, {} refused without, {} panics",
        tally.files,
        seeds.len(),
        tally.valid,
        tally.refused,
        tally.unnamed.len(),
        tally.panics.len()
    );
    for message in tally.unnamed.iter().take(5) {
        println!("refusal without a key or a line: {message}");
    }
    for text in tally.panics.iter().take(3) {
        println!("panic on:\n{text}\n---");
    }
    if tally.unnamed.is_empty() && tally.panics.is_empty() {
        std::process::ExitCode::SUCCESS
    } else {
        std::process::ExitCode::FAILURE
    }
}
