//! A polygon block on an incline in the explicit DEM (the `polygon_incline`
//! composition): sliding at the Coulomb acceleration on a steep slope, at
//! rest on a gentle one, on its two corners without tipping.

use dismech_cli::compositions::polygon_incline::{
    incline_slide_ratio, incline_stick_displacement, run_block_on_incline, BlockOnIncline,
};

#[test]
fn rectangle_on_a_40_degree_incline_slides_at_the_coulomb_acceleration() {
    let ratio = incline_slide_ratio().unwrap();
    eprintln!("measured / exact acceleration on 40°, mu = tan 30°: {ratio:.6}");
    assert!((ratio - 1.0).abs() < 0.01, "ratio {ratio}");
}

#[test]
fn rectangle_on_a_20_degree_incline_sticks() {
    let moved = incline_stick_displacement().unwrap();
    eprintln!("displacement in 1 s on 20°, mu = tan 30°: {moved:.3e} of the block length");
    assert!(moved < 1e-4, "moved {moved} of its length");
}

#[test]
fn sliding_block_keeps_its_two_contact_points_and_does_not_tip() {
    let run = run_block_on_incline(&BlockOnIncline::default()).unwrap();
    // v²/2 = a s from rest: the displacement agrees with the acceleration.
    let expected = 0.5 * run.exact_acceleration * 1.0;
    assert!((run.displacement - expected).abs() < 0.01 * expected + 1e-3);
    assert!(run.rotation.abs() < 1e-4, "rotation {}", run.rotation);
}
