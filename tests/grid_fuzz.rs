//! The grid fuzzer (`tests/grid_fuzzer`) on 20 000 cases: mutated
//! grid files through the reader and the slope-grid loader never panic,
//! never take memory out of proportion to their length, and a header
//! claiming more cells than the cap is always refused. The same fuzzer runs
//! 10^6 cases and more with `cargo run --release --example fuzz_grids`.

use crate::grid_fuzzer;

use grid_fuzzer::{case_input, run, Seeds};

/// The seed of the run in `cargo test`.
const SEED: u64 = 12;

/// The number of cases in `cargo test` (about a second).
const CASES: u64 = 20_000;

#[test]
fn fuzzed_grid_files_never_panic_nor_outgrow_their_memory_bound() {
    let stats = run(SEED, 0..CASES);
    eprintln!("{}", stats.report());
    assert!(stats.clean(), "{}", stats.report());
    // The run reaches what it aims at: huge headers, grids accepted by the
    // reader and by the loader, and every kind of refusal of a grid.
    assert!(stats.huge_claims >= CASES / 10, "{}", stats.report());
    for target in ["Reader", "Loader", "LoaderFromFiles"] {
        assert!(
            stats.accepted_by_target.get(target).copied().unwrap_or(0) > 0,
            "no {target} case accepted:\n{}",
            stats.report()
        );
    }
    for kind in [
        "GridFormat",
        "GridHeader",
        "GridTooLarge",
        "GridMismatch",
        "GridCell",
        "NoValidColumn",
    ] {
        assert!(
            stats.refused.contains_key(kind),
            "no case refused with {kind}:\n{}",
            stats.report()
        );
    }
}

#[test]
fn a_fuzz_case_is_replayed_from_its_seed_and_index() {
    let seeds = Seeds::new();
    for index in [0, 1, 977, CASES - 1] {
        assert_eq!(
            case_input(&seeds, SEED, index),
            case_input(&seeds, SEED, index)
        );
    }
    assert_ne!(case_input(&seeds, SEED, 0), case_input(&seeds, SEED, 1));
}
