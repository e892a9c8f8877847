//! Outputs: files written whole or not at all, the machine-readable
//! `summary.json` of a reproduction, CSV tables and SVG plots.

mod atomic;
pub mod map;
pub mod plot;
mod summary;

pub use atomic::{write_atomically, write_csv};
pub use summary::{Check, Reported, Summary};
