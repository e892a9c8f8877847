//! The grid fuzzer on many cases: mutated ESRI ASCII grids (byte flips,
//! nasty numbers, huge headers, lines dropped or repeated, truncation...)
//! through the grid reader and the slope-grid loader, each case under
//! `catch_unwind` and measured by a counting allocator. Prints the counts:
//! cases, accepted, refused by error kind, panics, headers over the cell
//! cap, and the largest memory a case took.
//!
//! `cargo run --release --example fuzz_grids -- [cases [seed]]` (default
//! 1 000 000 cases, seed 12). Exits with 1 if any case panicked, accepted a
//! header over the cap or outgrew its memory bound.

#[path = "../tests/grid_fuzzer/mod.rs"]
mod grid_fuzzer;

use std::process::ExitCode;
use std::time::Instant;

use rayon::prelude::*;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let number = |k: usize, default: u64| -> u64 {
        args.get(k).map_or(default, |a| {
            a.replace('_', "").parse().unwrap_or_else(|_| {
                eprintln!("usage: fuzz_grids [cases [seed]] (whole numbers); got `{a}`");
                std::process::exit(2)
            })
        })
    };
    let (cases, seed) = (number(0, 1_000_000), number(1, 12));
    let start = Instant::now();
    let chunk = 10_000;
    let stats = (0..cases.div_ceil(chunk))
        .into_par_iter()
        .map(|k| grid_fuzzer::run(seed, k * chunk..((k + 1) * chunk).min(cases)))
        .reduce(grid_fuzzer::Stats::default, |mut a, b| {
            a.merge(b);
            a
        });
    println!("seed {seed}, {:.1} s", start.elapsed().as_secs_f64());
    print!("{}", stats.report());
    if stats.clean() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
