//! The study's slope is the one shipped with the examples.

use super::*;

#[test]
fn shipped_slope_grids_are_the_reproduction_slope() {
    let (ground, slip) = representative_slope().unwrap();
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/data");
    assert_eq!(
        dismech::grid::read_esri_ascii(&dir.join("hpm_ground.asc")).unwrap(),
        ground
    );
    assert_eq!(
        dismech::grid::read_esri_ascii(&dir.join("hpm_slip.asc")).unwrap(),
        slip
    );
}
