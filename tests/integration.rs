//! The library's integration tests, one module per file of this folder,
//! built and linked as one test binary: each binary links the whole library
//! and instantiates its generic drivers again, so one binary rather than
//! one per file saves most of the test build. The tests that measure what
//! a call allocates are the other binary, `tests/memory.rs`.
//!
//! Run one file's tests with `cargo test --release --test integration
//! FILE::` (say `dda_blocks::`).

// What several files share.
mod common;
mod dda_common;
mod kill_common;
mod variation_common;

mod checkpoint_damage;
mod checkpoint_explicit;
mod checkpoint_implicit;
mod constructor_fuzz;
mod contact_law_properties;
mod dda;
mod dda_blocks;
mod dda_hardening;
mod dem_exact;
mod dem_hardening;
mod dem_neighbours;
mod dem_prescribed;
mod dem_stiffness_bound;
mod earth_pressure;
mod ellipse_contact;
mod gis_rasters;
mod hpm_exact;
mod implicit_driver;
mod kinematics;
mod limit_analysis;
mod limit_dead_loads;
mod limit_hardening;
mod observers;
mod polygon_contact;
mod polygon_dem;
mod rolling_resistance;
mod slope_bedrock;
mod slope_bishop;
mod slope_extruded;
mod slope_hpm;
mod slope_layers;
mod slope_search;
mod solve_errors;
mod variation_geometry;
mod variations;
mod vtk_output;
