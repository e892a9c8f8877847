//! Outputs: files written whole or not at all, study folders swapped in
//! whole, the machine-readable `summary.json` of a reproduction with the
//! rule of each check, its console and report listings, CSV tables and SVG
//! plots.

mod csv;
mod folder;
mod limit_json;
mod listing;
pub mod map;
pub mod plot;
mod rule;
mod summary;

pub use csv::write_csv;
pub use folder::StagedFolder;
pub use limit_json::limit_summary;
pub use listing::{check_line, checks_table, value_line};
pub use rule::{number, Reference, Rule};
pub use summary::{Check, Reported, Summary};
