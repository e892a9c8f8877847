//! The polygon DEM on an incline ([`dismech_cli::compositions::polygon_incline`]):
//! sliding at the Coulomb acceleration, sticking below the friction angle.

use super::{Collector, Item, Rule};
use dismech::error::Result;
use dismech_cli::compositions::polygon_incline::{
    incline_slide_ratio, incline_stick_displacement, BlockOnIncline,
};

/// The polygon DEM: a rigid rectangle on an incline, sliding and sticking.
pub(super) fn polygon_incline(c: &mut Collector) -> Result<()> {
    let block = BlockOnIncline::default();
    c.section(
        "Polygon DEM: a block on an incline (`compositions::polygon_incline`)",
        &format!(
            "A {} m × {} m rectangle on a wall inclined at β, μ = tan 30°, touching at its two \
             bottom corners (k_n = {:e} N/m per corner, k_s/k_n = {}, critical dashpots, Δt = {:e} s, 1 s).",
            block.width, block.height, block.normal_stiffness, block.stiffness_ratio, block.dt
        ),
    );
    c.check(
        Item {
            id: "polygon_dem.incline_slide_ratio",
            what: "mean acceleration down a 40° slope (μ = tan 30°) after 0.1 s of settling, over the exact one",
            reference: "rigid block with Coulomb friction, a = g (sin β − μ cos β)",
            unit: "-",
            note: "the two corner points keep their features while sliding; the compliance of the springs barely matters",
        },
        Rule::Near {
            target: 1.0,
            tolerance: 0.01,
        },
        incline_slide_ratio()?,
    );
    c.check(
        Item {
            id: "polygon_dem.incline_stick_displacement",
            what: "displacement along a 20° slope (μ = tan 30°) in 1 s, over the block length",
            reference: "a rigid block sticks for tan β ≤ μ",
            unit: "-",
            note: "what moves is the elastic settling of the corner springs under the weight",
        },
        Rule::AtMost(1e-4),
        incline_stick_displacement()?,
    );
    Ok(())
}
