//! The implicit driver beyond classic DDA: ellipses settled at a large time
//! step ([`dismech_cli::compositions::implicit_ellipses`]), a disc as a DDA body
//! ([`dismech_cli::compositions::affine_disc`]) and paper 002's U-model pushed
//! by bonded penalty contacts against its LP limit load
//! ([`dismech_cli::compositions::penalty_vs_lp`]).

use super::{Collector, Item, Rule};
use dismech::error::Result;
use dismech::reference::lattice_limit_load::eq32;
use dismech_cli::compositions::affine_disc::{rolling_convergence, RollingDisc};
use dismech_cli::compositions::implicit_ellipses::{settle, EllipseBox};
use dismech_cli::compositions::penalty_vs_lp::{penalty_vs_lp, UModelPushover};
use dismech_cli::output::plot::{line_chart, Series};
use dismech_cli::output::write_csv;

/// Ellipses settled in a box by the implicit driver.
pub(super) fn implicit_ellipses(c: &mut Collector) -> Result<()> {
    let setup = EllipseBox::default();
    let settled = settle(&setup)?;
    c.section(
        "Implicit ellipses: a box settled at 20 explicit limits (`compositions::implicit_ellipses`)",
        &format!(
            "{} rigid ellipses (a/b = {}, a ∈ [{}, {}] m, ρ = {} kg/m³) stacked in {} columns and \
             released in a box of three walls; penalty Coulomb contacts (k = {:e} N/m per m, μ = {}, \
             return mapping), Newmark β = {}, γ = {}, sparse LU. Requested Δt = {:.4e} s, {} times \
             the explicit limit 2√(m/k) = {:.4e} s of the lightest ellipse on one spring (rotation and \
             several contacts only lower that limit). Rest: no boundary point faster than {:e} m/s; \
             mass-proportional damping α = {} /s (it vanishes at rest) makes the rocking of ellipses \
             balanced on one contact die out. Search distance {} m; a step whose boundary points move \
             further relative to a neighbour is detected again at a search distance covering the \
             motion (up to {} m) and repeated at its size. At most {} open–close and {} Newton \
             iterations a step: a step whose iteration fails is halved, and doubled again after a \
             success. While the columns collapse (ellipses turn at up to {:.0} rad/s, the largest at \
             the end of a step) impacts, contacts opening and closing and slip reversing make the \
             iterations fail and steps are halved; the last step not taken whole ended at {:.2} s, and the {} steps \
             from there to the end at {:.2} s were taken whole at the requested size. The mean \
             accepted sub-step over the whole run is reported beside the requested step.",
            setup.count,
            setup.aspect,
            setup.semi_major.0,
            setup.semi_major.1,
            setup.density,
            setup.columns,
            setup.penalty,
            setup.friction,
            setup.newmark.0,
            setup.newmark.1,
            settled.dt,
            setup.step_ratio,
            settled.dt_explicit,
            setup.rest_speed,
            setup.mass_damping,
            setup.search_distance,
            setup.max_search_distance,
            setup.max_iterations,
            setup.max_iterations,
            settled.peak_spin,
            settled.last_halved_at,
            settled.final_whole_steps(),
            settled.time
        ),
    );
    c.check(
        Item {
            id: "implicit_ellipses.vertical_reaction_ratio",
            what: "Σ vertical wall forces on the ellipses at rest over their weight",
            reference: "static equilibrium of the packing",
            unit: "-",
            note: "at rest the walls carry the weight; what remains is the rest criterion's motion",
        },
        Rule::Near {
            target: 1.0,
            tolerance: 5e-3,
        },
        if settled.at_rest {
            settled.reaction_ratio()
        } else {
            f64::NAN
        },
    );
    for (id, what, unit, note, value) in [
        (
            "implicit_ellipses.step_ratio",
            "requested time step over the explicit limit",
            "-",
            "the step every advance asks for",
            settled.step_ratio(),
        ),
        (
            "implicit_ellipses.accepted_step_ratio",
            "mean accepted sub-step over the explicit limit",
            "-",
            "below the requested ratio while the columns collapse: see the halvings",
            settled.accepted_step_ratio(),
        ),
        (
            "implicit_ellipses.whole_step_fraction",
            "steps taken whole (one sub-step of the requested size) over all steps",
            "-",
            "the others fell in the collapse",
            settled.whole_steps as f64 / settled.steps.max(1) as f64,
        ),
        (
            "implicit_ellipses.last_halving_time",
            "time at the end of the last step not taken whole (halved, or in sub-steps after a halving)",
            "s",
            "every later step was taken whole",
            settled.last_halved_at,
        ),
        (
            "implicit_ellipses.final_whole_steps",
            "steps from the last one not taken whole to rest, each one sub-step of the requested size",
            "-",
            "the packing settles at the requested step",
            settled.final_whole_steps() as f64,
        ),
        (
            "implicit_ellipses.redetections",
            "steps detected again at a larger search distance and repeated at their size",
            "-",
            "fast steps of the collapse that were not halved",
            settled.redetections as f64,
        ),
        (
            "implicit_ellipses.peak_spin",
            "largest angular speed of an ellipse at the end of a step",
            "rad/s",
            "the collapse of the columns",
            settled.peak_spin,
        ),
        (
            "implicit_ellipses.halvings.too_fast",
            "halvings because a boundary point moved beyond the largest search distance",
            "-",
            "the motion bound of a step, once the search distance cannot grow",
            settled.halvings.too_fast as f64,
        ),
        (
            "implicit_ellipses.halvings.newton",
            "halvings because Newton did not converge",
            "-",
            "stick/slip states still changing at the iteration bound",
            settled.halvings.newton as f64,
        ),
        (
            "implicit_ellipses.halvings.open_close",
            "halvings because the open/closed states did not settle",
            "-",
            "contacts still opening and closing at the iteration bound",
            settled.halvings.open_close as f64,
        ),
        (
            "implicit_ellipses.iterations_per_step",
            "linear solves (open–close and Newton iterations, failed sub-steps included) per requested step",
            "-",
            "the failed attempts before a halving dominate",
            settled.iterations_per_step(),
        ),
        (
            "implicit_ellipses.settling_time",
            "simulated time to rest",
            "s",
            "from release to the rest criterion",
            settled.time,
        ),
    ] {
        c.value(
            Item {
                id,
                what,
                reference: "none",
                unit,
                note,
            },
            None,
            value,
        );
    }
    Ok(())
}

/// A disc as a six-unknown affine DDA body rolling down an incline.
pub(super) fn affine_disc(c: &mut Collector) -> Result<()> {
    let setup = RollingDisc::default();
    let runs = rolling_convergence(&setup)?;
    c.section(
        "Affine disc: a DDA body on a smooth boundary rolls (`compositions::affine_disc`)",
        &format!(
            "A disc of radius {} m (ρ = {} kg/m³, E = {:e} Pa, ν = {}) with DDA's six affine unknowns \
             on a {}° incline, μ = {} (it rolls: μ ≥ tan β / 3), penalty {:e} N/m per m, Newmark β = ½, \
             γ = 1, for {} s; the centre's acceleration is the curvature of a parabola fitted from {} s. \
             The error is first order in Δt (Newmark with γ = 1 is first order): the run is repeated \
             at 2 Δt and 4 Δt. The body's geometry is moved with its rotation made exact at the end of \
             each step (DDA's first-order rotation would grow its area by r₀² a step), so its area \
             changes by its elastic strain alone.",
            setup.radius,
            setup.density,
            setup.youngs_modulus,
            setup.poisson_ratio,
            setup.slope.to_degrees().round(),
            setup.friction,
            setup.penalty,
            setup.duration,
            setup.settling_time
        ),
    );
    c.check(
        Item {
            id: "affine_disc.rolling_ratio",
            what: &format!(
                "centre acceleration down a 30° slope (μ = 0.5) at Δt = {:e} s over the rolling disc's",
                setup.dt
            ),
            reference: "a uniform disc rolling without slip, a = (2/3) g sin β",
            unit: "-",
            note: "short of 1 by the first-order time error (below)",
        },
        Rule::Near {
            target: 1.0,
            tolerance: 0.01,
        },
        runs[0].ratio(),
    );
    for (run, factor) in runs.iter().zip(["1", "2", "4"]) {
        c.value(
            Item {
                id: &format!("affine_disc.dt_times_{factor}.ratio"),
                what: &format!("acceleration ratio at {factor} Δt"),
                reference: "(2/3) g sin β",
                unit: "-",
                note: "the error halves with the step",
            },
            Some(1.0),
            run.ratio(),
        );
        c.value(
            Item {
                id: &format!("affine_disc.dt_times_{factor}.area_change"),
                what: &format!("relative area change over the run at {factor} Δt"),
                reference: "a rigid rotation keeps the area",
                unit: "-",
                note: "the elastic strain alone: the rotation is exact at the end of each step",
            },
            Some(0.0),
            run.area_change,
        );
    }
    Ok(())
}

/// Paper 002's U-model pushed by the implicit penalty driver.
pub(super) fn penalty_vs_lp_u4_1(c: &mut Collector) -> Result<()> {
    let setup = UModelPushover::default();
    let result = penalty_vs_lp(&setup)?;
    let last = result.curves.len() - 1;
    c.section(
        "Penalty vs LP: paper 002's U-model (k = 4, n' = 1, rolling) pushed quasi-statically (`compositions::penalty_vs_lp`)",
        &format!(
            "The LP model turned contact for contact into rigid discs and walls with bonded penalty \
             contacts (tension carried, shear capped at c + μ t_n by return mapping), the plate \
             translated in {} quasi-static steps over 300/p R. The LP is of the undeformed lattice; \
             the penalty model's geometry changes over the elastic travel to the plateau, which \
             shrinks as 1/p: the plateau approaches the LP load as the penalty rises. The plateau is \
             the mean load of the last {} of the steps.",
            setup.steps, setup.plateau_fraction
        ),
    );
    c.check(
        Item {
            id: "penalty_vs_lp.u4_1.ratio",
            what: &format!(
                "plateau of the plate load at penalty {:e} C_p/R over the LP limit load",
                setup.penalties[last]
            ),
            reference: "the LP's rigid-plastic limit load (paper 002 eq. 32: (1 + 3.5 √2) C_p = 5.9497 C_p)",
            unit: "-",
            note: "short of 1 by the change of geometry over the elastic travel",
        },
        Rule::Near {
            target: 1.0,
            tolerance: 0.01,
        },
        result.checked_ratio(),
    );
    c.value(
        Item {
            id: "penalty_vs_lp.u4_1.lp_load",
            what: "the LP limit load",
            reference: "paper 002 eq. 32, (1 + 3.5 √2) C_p; Table 1 gives 5.95",
            unit: "C_p",
            note: "Clarabel on the undeformed lattice",
        },
        Some(eq32(4, 1)),
        result.lp_load,
    );
    let mut rows = Vec::new();
    let mut series = Vec::new();
    for (k, curve) in result.curves.iter().enumerate() {
        c.value(
            Item {
                id: &format!("penalty_vs_lp.u4_1.penalty_{:e}.ratio", curve.penalty),
                what: &format!("plateau over the LP load at penalty {:e}", curve.penalty),
                reference: "the LP limit load",
                unit: "-",
                note: "the trend over three penalties",
            },
            Some(1.0),
            result.plateau_ratio(k),
        );
        rows.extend(
            curve
                .travel
                .iter()
                .zip(&curve.load)
                .map(|(&u, &p)| vec![curve.penalty, u, u * curve.penalty, p]),
        );
        series.push(Series {
            name: format!("penalty {:e}", curve.penalty),
            points: curve
                .travel
                .iter()
                .zip(&curve.load)
                .map(|(&u, &p)| (u * curve.penalty, p))
                .collect(),
            markers: false,
        });
    }
    let span = setup.travel_force;
    series.push(Series {
        name: "LP limit load".into(),
        points: vec![(0.0, result.lp_load), (span, result.lp_load)],
        markers: false,
    });
    write_csv(
        &c.dir().join("penalty_pushover.csv"),
        &["penalty", "travel", "travel_times_penalty", "plate_load"],
        &rows,
    )?;
    c.file("penalty_pushover.csv");
    line_chart(
        &c.dir().join("penalty_pushover.svg"),
        "U-model k = 4, n' = 1: plate load of bonded penalty models and the LP limit load",
        "plate travel × penalty (C_p)",
        "plate load (C_p)",
        &series,
    )?;
    c.file("penalty_pushover.svg");
    Ok(())
}
