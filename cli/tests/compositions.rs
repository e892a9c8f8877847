//! The cross-compositions of the library: each combines the slots in a way
//! the papers do not, and is checked against an exact solution or a second
//! method. The `compositions` study reports the same quantities.

use dismech::limit::LimitStatus;
use dismech::math::Vec2;
use dismech_cli::compositions::packing_lp::{ellipse_packing_limit, EllipsePacking};

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

/// A rigid 0.4 m × 0.8 m block on a floor, pushed at its top: with
/// μ = tan 30° > w/2h it rocks about its leading corner at `W w/(2h)`, with
/// μ = tan 10° < w/2h it slides at `μ W`; the LP's multiplier equals the
/// closed form to 1e-6 and its dual forces are admissible.
#[test]
fn block_on_a_floor_tips_or_slides_at_the_closed_form_load() {
    use dismech::reference::BlockMechanism;
    use dismech_cli::compositions::polygon_lp::{
        block_limit, sliding_block, sliding_ratio, tipping_block, tipping_ratio,
    };
    let tipping = tipping_ratio().unwrap();
    let sliding = sliding_ratio().unwrap();
    assert!((tipping - 1.0).abs() <= 1e-6, "tipping ratio {tipping}");
    assert!((sliding - 1.0).abs() <= 1e-6, "sliding ratio {sliding}");
    for (block, mechanism) in [
        (tipping_block(), BlockMechanism::Tipping),
        (sliding_block(), BlockMechanism::Sliding),
    ] {
        let limit = block_limit(&block).unwrap();
        assert_eq!(limit.mechanism, mechanism);
        assert_eq!(limit.result.status, LimitStatus::Collapse);
        let a = limit.admissibility;
        assert!(
            a.equilibrium <= 1e-8,
            "{mechanism:?}: equilibrium {:e}",
            a.equilibrium
        );
        assert!(
            a.strength_excess <= 1e-8,
            "{mechanism:?}: strength {:e}",
            a.strength_excess
        );
        let (velocity, spin) = limit.result.velocities[0];
        match mechanism {
            // Rocking about the right corner (w/2, 0): that corner neither
            // moves along nor off the floor, the left corner lifts.
            BlockMechanism::Tipping => {
                let corner =
                    velocity + Vec2::new(spin * block.height / 2.0, spin * block.width / 2.0);
                assert!(corner.norm() <= 1e-6 * velocity.norm(), "{corner}");
                assert!(limit.result.normal_force[0].abs() <= 1e-6 * block.weight);
            }
            // Sliding with dilation tan φ and no spin.
            BlockMechanism::Sliding => {
                assert!(spin.abs() <= 1e-6 * velocity.norm(), "spin {spin}");
                approx::assert_relative_eq!(
                    velocity.y,
                    block.friction * velocity.x,
                    max_relative = 1e-6
                );
            }
        }
    }
}

/// A running-bond wall of 39 blocks at rest on a fixed base by the
/// polygon DEM (rigid blocks) and the DDA (deformable blocks), with the
/// same contact points and the same stiffness per point: the base carries
/// the weight in both, no contact slips, and the bottom course's shares of
/// the weight agree to a percent of a block's weight.
#[test]
fn running_bond_wall_rests_on_its_base_by_the_polygon_dem_and_the_dda() {
    use dismech_cli::compositions::block_wall::{dem_vs_dda, RunningBondWall};
    let wall = RunningBondWall::default();
    let blocks = wall.blocks().unwrap();
    assert!(blocks.len() >= 30, "{} blocks", blocks.len());
    let run = dem_vs_dda(&wall).unwrap();
    for (name, solution) in [("DEM", &run.dem), ("DDA", &run.dda)] {
        assert!(solution.at_rest, "{name} not at rest");
        let ratio = solution.base_reaction_ratio();
        assert!(
            (ratio - 1.0).abs() <= 0.005,
            "{name}: base reaction / weight {ratio}"
        );
        assert!(
            solution.base_reaction.x.abs() <= 1e-6 * solution.total_weight,
            "{name}: horizontal base reaction {}",
            solution.base_reaction.x
        );
        assert_eq!(solution.slipping, 0, "{name}: contacts in slip");
        assert_eq!(solution.bottom_course.len(), wall.blocks_per_course);
    }
    // The same contact points: a corner on a face is one point in both.
    assert_eq!(run.dem.contacts.len(), run.dda.contacts.len());
    assert!(
        run.bottom_course_difference < 0.01,
        "bottom course differs by {} block weights",
        run.bottom_course_difference
    );
    println!(
        "base reaction / weight: DEM {:.9}, DDA {:.9}; bottom course difference {:.3e} W_block",
        run.dem.base_reaction_ratio(),
        run.dda.base_reaction_ratio(),
        run.bottom_course_difference
    );
}

/// What separates the DEM's and the DDA's bottom course is the DDA blocks'
/// strain: the difference is proportional to k/E (contact stiffness over
/// the blocks' modulus). Blocks 100 times stiffer divide it by about 100;
/// contacts and blocks both 10 times softer leave it unchanged; nearly
/// rigid DDA blocks (E × 10⁴) meet the rigid DEM blocks to 1e-5 of a
/// block's weight, so nothing else (contact points, loading path, rest
/// criteria) contributes at that level. The shear springs share the
/// weight too: DEM shear springs a quarter as stiff as the DDA's penalty
/// separate even nearly rigid blocks by a percent of a block's weight.
#[test]
fn bottom_course_difference_between_dem_and_dda_follows_k_over_e() {
    use dismech_cli::compositions::block_wall::{dem_vs_dda_variants, RunningBondWall};
    let wall = RunningBondWall::default();
    let rigid = wall.scaled(1.0, 1e4);
    let soft_shear = RunningBondWall {
        dem_stiffness_ratio: 0.25,
        ..rigid
    };
    let walls = [
        wall,
        wall.scaled(1.0, 100.0),
        wall.scaled(0.1, 0.1),
        rigid,
        soft_shear,
    ];
    let d: Vec<f64> = dem_vs_dda_variants(&walls)
        .unwrap()
        .iter()
        .map(|r| r.bottom_course_difference)
        .collect();
    println!("differences (W_block): {d:?}");
    let stiffer_blocks = d[1] / d[0];
    assert!(
        (0.008..0.015).contains(&stiffer_blocks),
        "E x 100 changes the difference by {stiffer_blocks}"
    );
    approx::assert_relative_eq!(d[2], d[0], max_relative = 0.01);
    assert!(d[3] < 1e-5, "nearly rigid DDA blocks: {}", d[3]);
    assert!(d[4] > 0.005, "DEM k_s/k_n = 0.25: {}", d[4]);
}

/// A disc as a six-unknown affine DDA body rolls down a 30° incline with
/// μ = 0.5 at `(2/3) g sin β` to 1 % at Δt = 2.5e-4 s; the error is first
/// order in the step (it doubles with the step: Newmark with γ = 1 is first
/// order). The disc's area is kept to 1e-6 at every step size: its
/// geometry is moved with the rotation made exact (classic DDA's
/// first-order rotation grew it by `r₀²` a step, more at the larger step).
#[test]
fn affine_disc_rolls_at_two_thirds_g_sin_beta() {
    use dismech_cli::compositions::affine_disc::{rolling_convergence, RollingDisc};
    let [fine, middle, coarse] = rolling_convergence(&RollingDisc::default()).unwrap();
    for run in [&fine, &middle, &coarse] {
        println!(
            "ratio {:.6}, area change {:.2e}, turn {:.2} rad, {:.2} solves/step, {} reductions",
            run.ratio(),
            run.area_change,
            run.turn,
            run.iterations_per_step,
            run.reductions
        );
    }
    assert!(
        (fine.ratio() - 1.0).abs() <= 0.01,
        "rolling ratio {}",
        fine.ratio()
    );
    let errors = [fine, middle, coarse].map(|r| (r.ratio() - 1.0).abs());
    assert!(
        errors[0] < errors[1] && errors[1] < errors[2],
        "errors {errors:?}"
    );
    // First order: doubling the step doubles the error.
    for pair in errors.windows(2) {
        let order = pair[1] / pair[0];
        assert!(
            (1.5..=2.5).contains(&order),
            "error ratio {order} ({errors:?})"
        );
    }
    for run in [&fine, &middle, &coarse] {
        assert!(
            run.area_change.abs() <= 1e-6,
            "area change {}",
            run.area_change
        );
    }
}

/// The affine disc rolled for ten revolutions (2 s down the 30° incline)
/// at Δt = 2.5e-4 and 1.25e-4 s: its area changes by less than 1e-6 at
/// both (the elastic strain of its contact load, −1.4e-7, turns with it),
/// where the first-order rotation of classic DDA, `r₀²` a step with `r₀`
/// up to 0.016 rad here, would have grown it by tens of percent. It still
/// rolls at `(2/3) g sin β`: the error is Newmark's (γ = 1), first order
/// and larger at the end of this run, where the disc turns 65 rad/s (1.5 %
/// at 2.5e-4 s), and halves with the step (to 1 % at 1.25e-4 s).
#[test]
fn an_affine_disc_keeps_its_area_over_ten_revolutions() {
    use dismech_cli::compositions::affine_disc::{run_rolling_disc, RollingDisc};
    let runs = [2.5e-4, 1.25e-4].map(|dt| {
        run_rolling_disc(&RollingDisc {
            duration: 2.0,
            dt,
            ..RollingDisc::default()
        })
        .unwrap()
    });
    for run in &runs {
        println!(
            "turn {:.1} rad ({:.2} revolutions), area change {:.2e}, ratio {:.5}, {} reductions",
            run.turn,
            run.turn / std::f64::consts::TAU,
            run.area_change,
            run.ratio(),
            run.reductions
        );
        assert!(
            run.turn >= 10.0 * std::f64::consts::TAU,
            "turn {}",
            run.turn
        );
        assert!(
            run.area_change.abs() < 1e-6,
            "area change {}",
            run.area_change
        );
    }
    let errors = runs.map(|r| (r.ratio() - 1.0).abs());
    assert!(errors[1] <= 0.01, "rolling ratio {}", runs[1].ratio());
    let order = errors[0] / errors[1];
    assert!(
        (1.5..=2.5).contains(&order),
        "error ratio {order} ({errors:?})"
    );
}

/// Paper 002's U-model (k = 4, n' = 1, rolling) pushed quasi-statically by
/// the implicit driver with bonded penalty contacts: the driver finds the
/// LP model's contacts, the load levels off, and its plateau is the LP's
/// limit load (paper 002 eq. 32: 5.9497 C_p, which the LP meets) to 1 % at the stiffest penalty;
/// the gap (the change of geometry over the elastic travel) falls as the
/// penalty rises.
#[test]
fn penalty_pushover_levels_off_at_the_lp_limit_load() {
    use dismech_cli::compositions::penalty_vs_lp::{penalty_vs_lp, UModelPushover};
    let setup = UModelPushover::default();
    let result = penalty_vs_lp(&setup).unwrap();
    let exact = dismech::reference::lattice_limit_load::eq32(4, 1);
    assert!(
        (result.lp_load / exact - 1.0).abs() < 1e-6,
        "LP load {} against eq. 32's {exact}",
        result.lp_load
    );
    let ratios: Vec<f64> = (0..result.curves.len())
        .map(|k| result.plateau_ratio(k))
        .collect();
    for (curve, ratio) in result.curves.iter().zip(&ratios) {
        println!(
            "penalty {:e}: plateau / LP {ratio:.5}, spread {:.2e}, {} reductions",
            curve.penalty,
            curve.plateau_spread(setup.plateau_fraction),
            curve.reductions
        );
        assert!(curve.contacts_match, "penalty {:e}", curve.penalty);
        assert!(curve.plateau_spread(setup.plateau_fraction) < 5e-3);
    }
    assert!(
        (result.checked_ratio() - 1.0).abs() <= 0.01,
        "ratio {}",
        result.checked_ratio()
    );
    assert!(
        ratios
            .windows(2)
            .all(|w| (w[1] - 1.0).abs() < (w[0] - 1.0).abs()),
        "{ratios:?}"
    );
}

/// 64 ellipses (a/b = 2) settled in a box by the implicit driver (rigid
/// bodies, Newmark β = 0.5625, γ = 1, return-mapping Coulomb) at a
/// requested step of 20 explicit limits come to rest, the last 0.1 s at
/// least in whole steps of that size, and the walls carry their weight to
/// 0.5 %.
#[test]
fn implicit_ellipses_come_to_rest_on_the_walls() {
    use dismech_cli::compositions::implicit_ellipses::{settle, EllipseBox};
    let setup = EllipseBox::default();
    assert!(setup.count >= 50 && setup.aspect == 2.0);
    let settled = settle(&setup).unwrap();
    println!(
        "reaction / weight {:.7}, step ratio {} (accepted sub-steps {:.2}), {:.1} solves/step, {} steps ({} whole; the last step not whole ended at {:.3} s, then {} whole steps), {} reductions ({:?}), {} redetections, rest at {:.3} s",
        settled.reaction_ratio(),
        settled.step_ratio(),
        settled.accepted_step_ratio(),
        settled.iterations_per_step(),
        settled.steps,
        settled.whole_steps,
        settled.last_halved_at,
        settled.final_whole_steps(),
        settled.reductions,
        settled.halvings,
        settled.redetections,
        settled.time
    );
    assert_eq!(settled.halvings.total(), settled.reductions);
    assert!(settled.at_rest, "largest speed {} m/s", settled.max_speed);
    assert!(settled.step_ratio() >= 20.0 * (1.0 - 1e-12));
    // It settles at the requested step: the steps of its last 0.1 s (and
    // more) are each taken whole.
    assert!(
        settled.final_whole_steps() as f64 * settled.dt >= 0.1,
        "{} whole steps at the end",
        settled.final_whole_steps()
    );
    assert!(
        (settled.reaction_ratio() - 1.0).abs() <= 5e-3,
        "reaction ratio {}",
        settled.reaction_ratio()
    );
}

/// A limit model the penalty pushover cannot take is refused with a reason
/// to match on: an element that is not a circle, or no moving support.
#[test]
fn a_limit_model_without_a_penalty_counterpart_is_refused_with_a_typed_reason() {
    use dismech::error::{DismechError, PenaltyRefusal};
    use dismech::limit::LimitModel;
    use dismech::math::{Point, Pose2};
    use dismech::shape::Polygon;
    use dismech_cli::compositions::penalty_vs_lp::pushover_model;

    let mut discs = LimitModel::new(1e-9).unwrap();
    discs.add_body(Point::new(0.0, 1.0), 1.0, true).unwrap();
    match pushover_model(&discs, 1e6, 0.1) {
        Err(err @ DismechError::PenaltyModel(PenaltyRefusal::MovingSupports { count: 0 })) => {
            assert!(err.to_string().contains("0 supports move"), "{err}");
        }
        Err(other) => panic!("{other:?}"),
        Ok(_) => panic!("a model without a plate was accepted"),
    }
    let mut blocks = LimitModel::new(1e-9).unwrap();
    blocks.add_body(Point::new(0.0, 1.0), 1.0, true).unwrap();
    blocks
        .add_shape(
            Polygon::rectangle(1.0, 1.0).unwrap().into(),
            Pose2::new(3.0, 1.0, 0.0),
            true,
        )
        .unwrap();
    match pushover_model(&blocks, 1e6, 0.1) {
        Err(err @ DismechError::PenaltyModel(PenaltyRefusal::NotACircle { element: 1 })) => {
            assert!(
                err.to_string().contains("element 1 is not a circle"),
                "{err}"
            );
        }
        Err(other) => panic!("{other:?}"),
        Ok(_) => panic!("a polygon element was accepted"),
    }
}
