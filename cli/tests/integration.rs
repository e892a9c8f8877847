//! The command's integration tests, one module per file of this folder,
//! built and linked as one test binary (one per file would link the whole
//! program once per file). Run one file's tests with `cargo test --release
//! -p dismech-cli --test integration FILE::` (say `slope::`).

// What the tests of `dismech slope` share.
mod slope_common;

mod cli;
mod compositions;
mod polygon_incline;
mod scenarios;
mod slope;
mod slope_bishop;
mod slope_refusals;
