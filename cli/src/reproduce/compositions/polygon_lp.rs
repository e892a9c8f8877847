//! The limit analysis of a polygon ([`dismech_cli::compositions::polygon_lp`]):
//! a block on a floor that tips or slides, against
//! [`dismech::reference::block_on_floor`], in both regimes and over a sweep
//! of the friction coefficient.

use super::{Collector, Item, Rule};
use dismech::error::Result;
use dismech::reference::BlockOnFloor;
use dismech_cli::compositions::polygon_lp::{block_limit, sliding_block, tipping_block};
use dismech_cli::output::plot::{line_chart, Series};
use dismech_cli::output::write_csv;

/// The limit analysis of a polygon: a block on a floor pushed at its top,
/// in both regimes and over a sweep of μ.
pub(super) fn polygon_lp(c: &mut Collector) -> Result<()> {
    let (tip, slide) = (
        block_limit(&tipping_block())?,
        block_limit(&sliding_block())?,
    );
    let b = tip.block;
    c.section(
        "Limit analysis of a polygon: a block tipping or sliding (`compositions::polygon_lp`)",
        &format!(
            "A rigid {} m × {} m rectangle of weight W = {} N/m on a floor, unilateral Coulomb contacts \
             (c = 0, associated flow) at its two bottom corners, a horizontal live load at the middle of \
             its top; the LP finds the load's multiplier. Exact: `W min(μ, w/2h)` \
             (`reference::block_on_floor`), rocking about the leading corner when μ > w/2h = {}, sliding \
             when μ < w/2h.",
            b.width,
            b.height,
            b.weight,
            b.critical_friction()
        ),
    );
    for (limit, id, what, closed_form) in [
        (
            &tip,
            "polygon_lp.tipping_ratio",
            "LP limit load of the block with μ = tan 30° over the rocking load",
            "W w/(2h), rocking about the leading corner",
        ),
        (
            &slide,
            "polygon_lp.sliding_ratio",
            "LP limit load of the block with μ = tan 10° over the sliding load",
            "μ W, sliding with dilation tan φ",
        ),
    ] {
        c.check(
            Item {
                id,
                what,
                reference: closed_form,
                unit: "-",
                note: "the LP's optimum is the vertex of the exact mechanism; the interior-point solution is exact to its tolerance",
            },
            Rule::Near {
                target: 1.0,
                tolerance: 1e-6,
            },
            limit.ratio,
        );
    }
    let (sweep, worst_ratio, worst_equilibrium) = friction_sweep(&b)?;
    c.check(
        Item {
            id: "polygon_lp.sweep_max_error",
            what: "largest |LP / closed form − 1| over φ = 1°, 2°, …, 45°",
            reference: "exact agreement with W min(μ, w/2h)",
            unit: "-",
            note: "both regimes and the switch between them at μ = w/2h (`block_regimes.svg`)",
        },
        Rule::AtMost(1e-6),
        worst_ratio,
    );
    c.check(
        Item {
            id: "polygon_lp.equilibrium_residual",
            what: "largest out-of-balance force or moment of the block under its dual contact forces, weight and live load, over the force scale, over the sweep",
            reference: "a statically admissible field, the lower bound",
            unit: "-",
            note: "`limit::admissibility` of every solved LP",
        },
        Rule::AtMost(1e-8),
        worst_equilibrium,
    );
    write_csv(
        &c.dir().join("block_regimes.csv"),
        &["phi_deg", "mu", "lp_over_w", "exact_over_w"],
        &sweep,
    )?;
    c.file("block_regimes.csv");
    let series = [
        Series {
            name: "LP multiplier P / W".into(),
            points: sweep.iter().map(|r| (r[1], r[2])).collect(),
            markers: true,
        },
        Series {
            name: "sliding μ".into(),
            points: vec![(0.0, 0.0), (b.critical_friction(), b.critical_friction())],
            markers: false,
        },
        Series {
            name: "tipping w/(2h)".into(),
            points: vec![
                (b.critical_friction(), b.critical_friction()),
                (1.0, b.critical_friction()),
            ],
            markers: false,
        },
    ];
    line_chart(
        &c.dir().join("block_regimes.svg"),
        "Block on a floor pushed at its top: limit load against μ",
        "friction coefficient μ = tan φ",
        "limit load P / W",
        &series,
    )?;
    c.file("block_regimes.svg");
    Ok(())
}

/// The block of `block`'s size over φ = 1° … 45°: rows `(φ, μ, LP / W,
/// exact / W)`, the largest relative error and the largest equilibrium
/// residual.
fn friction_sweep(block: &BlockOnFloor) -> Result<(Vec<Vec<f64>>, f64, f64)> {
    let mut rows = Vec::new();
    let (mut worst_ratio, mut worst_equilibrium) = (0.0f64, 0.0f64);
    for degrees in 1..=45 {
        let mu = (degrees as f64).to_radians().tan();
        let limit = block_limit(&BlockOnFloor {
            friction: mu,
            ..*block
        })?;
        let load = limit.result.load.unwrap_or(f64::NAN);
        worst_ratio = worst_ratio.max((limit.ratio - 1.0).abs());
        worst_equilibrium = worst_equilibrium.max(limit.admissibility.equilibrium);
        if !limit.ratio.is_finite() {
            worst_ratio = f64::NAN;
        }
        rows.push(vec![
            degrees as f64,
            mu,
            load / block.weight,
            limit.exact / block.weight,
        ]);
    }
    Ok((rows, worst_ratio, worst_equilibrium))
}
