//! The tests that measure the memory a call takes, built as their own test
//! binary: allocation-counter's counting global allocator is linked into
//! this binary only (it counts per thread, so the tests still run in
//! parallel). The other integration tests are `tests/integration.rs`.
//!
//! Run one file's tests with `cargo test --release --test memory FILE::`.

// The seeded grid fuzzer, shared with `examples/fuzz_grids.rs`.
mod grid_fuzzer;

mod geotiff_input;
mod grid_fuzz;
mod grid_input;
mod hpm_hardening;
