//! The cross-compositions of the library: each combines the slots in a way
//! the papers do not, and is checked against an exact solution or a second
//! method. The `compositions` study reports the same quantities.

use dismech::compositions::packing_lp::{ellipse_packing_limit, EllipsePacking};
use dismech::limit::LimitStatus;

/// A DEM-settled packing of 120 ellipses (a/b = 2) analysed by the LP: a
/// collapse mechanism exists, the dual contact forces hold every body in
/// equilibrium to 1e-8 of the force scale and within strength, and the
/// primal and dual optima agree to 1e-8.
#[test]
fn ellipse_packing_settled_by_the_dem_is_analysed_by_the_lp() {
    let packing = EllipsePacking::default();
    assert!(packing.count >= 100);
    let limit = ellipse_packing_limit(&packing).unwrap();
    assert_eq!(limit.result.status, LimitStatus::Collapse);
    let load = limit.result.load.unwrap();
    assert!(load.is_finite() && load > 0.0, "limit load {load}");
    assert!(
        limit.admissibility.equilibrium <= 1e-8,
        "equilibrium residual {:e}",
        limit.admissibility.equilibrium
    );
    assert!(
        limit.admissibility.strength_excess <= 1e-8,
        "strength excess {:e}",
        limit.admissibility.strength_excess
    );
    assert!(
        limit.primal_dual_gap <= 1e-8,
        "primal - dual {:e}",
        limit.primal_dual_gap
    );
    println!(
        "{} bodies, {} contacts: P/C = {load}, equilibrium {:e}, gap {:e}",
        limit.size.0, limit.size.1, limit.admissibility.equilibrium, limit.primal_dual_gap
    );
}
