//! # dismech-cli — the `dismech` command's experiments and reports
//!
//! The library [`dismech`] holds the pieces, the drivers and the paper
//! compositions; this crate holds what the `dismech` command runs on top
//! of them and is no part of the library's API:
//!
//! - [`compositions`]: the cross-compositions, fixed experiments that
//!   combine the slots in ways the four papers do not (a polygon block on an
//!   incline, a polygon block in the limit analysis, a DEM packing analysed
//!   by the LP, a block wall by the DEM and the DDA, ellipses in the
//!   implicit driver, a disc with DDA's affine unknowns, penalty contacts
//!   against the LP), each with the quantities its checks compare;
//! - [`slope`]: `dismech slope`, the slope search over a DEM with its
//!   rasters, critical surfaces and map;
//! - [`scenario`]: scenario files, a model described in TOML slot by
//!   slot, built, run and written out (`dismech run model.toml`);
//! - [`output`]: the reproductions' reports: the pass rule of each check,
//!   `summary.json`, console and report listings, study folders swapped in
//!   whole, CSV tables and SVG plots.
//!
//! The `dismech` binary (`dismech reproduce <study>`, `dismech
//! lattice-limit-load`, `dismech slope`) runs the studies built from both.

#![deny(missing_docs)]

pub mod compositions;
pub mod output;
pub mod scenario;
pub mod slope;
