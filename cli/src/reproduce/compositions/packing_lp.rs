//! A DEM-settled packing of ellipses analysed by the LP
//! ([`dismech_cli::compositions::packing_lp`]): the dual certifies the limit
//! load.

use super::{pictures, Collector, Item, Rule};
use dismech::error::Result;
use dismech_cli::compositions::packing_lp::{ellipse_packing_limit, EllipsePacking};

/// A DEM-settled packing of ellipses analysed by the LP.
pub(super) fn packing_lp(c: &mut Collector) -> Result<()> {
    let packing = EllipsePacking::default();
    let limit = ellipse_packing_limit(&packing)?;
    c.section(
        "DEM → LP: a settled packing of ellipses (`compositions::packing_lp`)",
        &format!(
            "{} ellipses (a/b = {}, a ∈ [{}, {}] m) settled by the explicit DEM with paper 000's law, then \
             analysed by the LP as rolling rigid bodies: {} bodies, {} contact points; strength C = 1 between \
             ellipses, 2 on the floor and right wall, the left wall a smooth plate pushed in. No exact \
             limit load exists; the LP certifies its own answer by its dual.",
            packing.count,
            packing.aspect,
            packing.semi_major.0,
            packing.semi_major.1,
            limit.size.0,
            limit.size.1
        ),
    );
    c.check(
        Item {
            id: "packing_lp.ellipses.equilibrium_residual",
            what: "largest out-of-balance force or moment of an ellipse under the dual contact forces and the plate load, over the force scale",
            reference: "the dual is a statically admissible field",
            unit: "-",
            note: "the equilibrium rows of the LP hold to the solver's tolerance",
        },
        Rule::AtMost(1e-8),
        limit.admissibility.equilibrium,
    );
    c.check(
        Item {
            id: "packing_lp.ellipses.strength_excess",
            what: "largest excess of a dual shear force over the strength c + μ N, over the force scale",
            reference: "every dual force within strength",
            unit: "-",
            note: "zero or rounding: the dual satisfies the strength cones",
        },
        Rule::AtMost(1e-8),
        limit.admissibility.strength_excess,
    );
    c.check(
        Item {
            id: "packing_lp.ellipses.primal_dual_gap",
            what: "|kinematic − static limit load| / max(1, |P|)",
            reference: "equal upper and lower bounds certify the limit load",
            unit: "-",
            note: "strong duality at the optimum",
        },
        Rule::AtMost(1e-8),
        limit.primal_dual_gap,
    );
    c.value(
        Item {
            id: "packing_lp.ellipses.limit_load",
            what: "limit load P / C on the left plate of the settled ellipse packing",
            reference: "none exact; certified by the checks above",
            unit: "C",
            note: "the force network at collapse is `packing_dual_forces.svg`",
        },
        None,
        limit.result.load.unwrap_or(f64::NAN),
    );
    if limit.result.load.is_some() {
        pictures::dual_forces(
            &c.dir().join("packing_dual_forces.svg"),
            &format!(
                "Settled ellipses at collapse (P = {:.4} C): dual contact forces",
                limit.result.kinematic_load.unwrap_or(f64::NAN)
            ),
            &limit.model,
            &limit.result,
        )?;
        c.file("packing_dual_forces.svg");
    }
    Ok(())
}
