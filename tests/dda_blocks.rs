//! DDA on block systems as rock engineers build them: blocks cut from
//! joint sets share their corners, the joints are closed or open by a few
//! micrometres, the penalty is the blocks' Young's modulus times a metre
//! (or ten times that), E = 10 GPa, Δt = 1 ms. Each model is run through
//! the public API with both friction integrations of paper 003.

use dismech::dda::{
    Block, BlockMaterial, DdaModel, DdaSettings, FrictionIntegration, PenaltyCoulomb, PlaneState,
    Prescribed, StepFailure,
};
use dismech::error::DismechError;
use dismech::implicit::ImplicitError;
use dismech::math::Point;

const E: f64 = 10e9;
const DENSITY: f64 = 2200.0;
const G: f64 = 9.8;
/// Brick length and height (m).
const BRICK: (f64, f64) = (0.4, 0.2);

fn material() -> BlockMaterial {
    BlockMaterial {
        density: DENSITY,
        youngs_modulus: E,
        poisson_ratio: 0.2,
        plane: PlaneState::Strain,
    }
}

fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<Point> {
    vec![
        Point::new(x0, y0),
        Point::new(x1, y0),
        Point::new(x1, y1),
        Point::new(x0, y1),
    ]
}

fn fixed(vertices: &[Point]) -> Block {
    let mut base = Block::new(vertices, material(), 0).unwrap();
    base.prescribed = Some(Prescribed::fixed());
    base
}

fn law(penalty: f64, integration: FrictionIntegration) -> PenaltyCoulomb {
    PenaltyCoulomb::new(penalty, 0.6, integration).unwrap()
}

const LAWS: [FrictionIntegration; 2] = [
    FrictionIntegration::ReturnMapping,
    FrictionIntegration::Conventional,
];

/// `n` bricks stacked on a fixed brick of the same width, their corners
/// coinciding, each resting `gap` above the one below.
fn column(n: usize, gap: f64) -> Vec<Block> {
    let (w, h) = BRICK;
    let mut blocks = vec![fixed(&rect(0.0, -h, w, 0.0))];
    for k in 0..n {
        let y0 = gap + k as f64 * (h + gap);
        blocks.push(Block::new(&rect(0.0, y0, w, y0 + h), material(), k + 1).unwrap());
    }
    blocks
}

/// A running-bond wall of `courses` courses on a fixed base: even courses
/// hold `c` whole bricks, odd ones a half brick at each end and `c − 1`
/// whole ones, so the end bricks' corners coincide with those below and
/// each head joint sits over the middle of a brick. Bed joints open by
/// `bed`, head joints by `head`.
fn running_bond(courses: usize, c: usize, bed: f64, head: f64) -> Vec<Block> {
    let (w, h) = BRICK;
    let length = c as f64 * w;
    let mut blocks = vec![fixed(&rect(-0.5, -0.5, length + 0.5, 0.0))];
    let g = 0.5 * head;
    for course in 0..courses {
        let y0 = bed + course as f64 * (h + bed);
        let mut spans = Vec::new();
        if course % 2 == 0 {
            spans.extend((0..c).map(|k| (k as f64 * w + g, (k + 1) as f64 * w - g)));
        } else {
            spans.push((g, 0.5 * w - g));
            spans.extend((0..c - 1).map(|k| ((k as f64 + 0.5) * w + g, (k as f64 + 1.5) * w - g)));
            spans.push((length - 0.5 * w + g, length - g));
        }
        for (x0, x1) in spans {
            let index = blocks.len();
            blocks.push(Block::new(&rect(x0, y0, x1, y0 + h), material(), index).unwrap());
        }
    }
    blocks
}

/// A stack-bond wall: `courses` courses of `c` bricks, one above the other,
/// so that four corners meet at every crossing of the joints.
fn stack_bond(courses: usize, c: usize, bed: f64, head: f64) -> Vec<Block> {
    let (w, h) = BRICK;
    let mut blocks = vec![fixed(&rect(-0.5, -0.5, c as f64 * w + 0.5, 0.0))];
    for course in 0..courses {
        let y0 = bed + course as f64 * (h + bed);
        for k in 0..c {
            let index = blocks.len();
            let (x0, x1) = (k as f64 * w + 0.5 * head, (k + 1) as f64 * w - 0.5 * head);
            blocks.push(Block::new(&rect(x0, y0, x1, y0 + h), material(), index).unwrap());
        }
    }
    blocks
}

/// What a run shows at each step: the base's reaction over the weight and
/// the largest displacement of a block's centroid.
struct History {
    reaction_over_weight: Vec<f64>,
    largest_move: Vec<f64>,
    weight: f64,
}

/// Run `steps` steps of 1 ms; every step must converge.
fn run(blocks: Vec<Block>, law: PenaltyCoulomb, search: f64, steps: usize) -> History {
    let settings = DdaSettings {
        search_distance: search,
        ..DdaSettings::default()
    };
    let mut model = DdaModel::new(blocks, law, settings).unwrap();
    let weight: f64 = model.blocks()[1..]
        .iter()
        .map(|b| b.area() * DENSITY * G)
        .sum();
    let start: Vec<Point> = model.blocks().iter().map(|b| b.centroid()).collect();
    let mut history = History {
        reaction_over_weight: Vec::new(),
        largest_move: Vec::new(),
        weight,
    };
    for step in 0..steps {
        // A step that fails is an error: every step converges.
        if let Err(e) = model.advance(1e-3) {
            panic!("step {step} ({:?}): {e}", law.integration());
        }
        history
            .reaction_over_weight
            .push(-model.contact_force_on(0).y / weight);
        history.largest_move.push(
            model
                .blocks()
                .iter()
                .zip(&start)
                .map(|(b, c)| (b.centroid() - c).norm())
                .fold(0.0, f64::max),
        );
    }
    history
}

/// The largest `|R/W − 1|` from step `from` on.
fn reaction_error(history: &History, from: usize) -> f64 {
    history.reaction_over_weight[from..]
        .iter()
        .map(|r| (r - 1.0).abs())
        .fold(0.0, f64::max)
}

/// Columns of equal bricks on a fixed brick of the same width, corners
/// coinciding, closed or open by 1 µm, at a penalty of E × 1 m. The top
/// brick of two used to sink through the lower one to the base (0.200 m
/// by 0.3 s, every step `Converged`): at a corner the side edge through
/// the same point was taken as the contact edge, whose normal carries no
/// load. Now no brick moves more than the joints' closure plus five times
/// the column's weight over the penalty, and the base carries the weight
/// to 0.5 % from 20 ms on (the blocks start unloaded). With 1 µm gaps the
/// bricks land at 4 mm/s, and the impact excites the contacts' stiff mode,
/// which paper 003's Newmark (β = ½, γ = 1) barely damps (its spectral
/// radius tends to 1 as ωΔt grows): the reaction alternates about the
/// weight from step to step, ±0.7 % at 20 ms, ±0.3 % at 100 ms, and is
/// checked from 100 ms on.
#[test]
fn columns_with_coinciding_corners_stand() {
    let penalty = E;
    for (n, gap, settled) in [(2, 0.0, 20), (5, 0.0, 20), (5, 1e-6, 100)] {
        for integration in LAWS {
            let h = run(column(n, gap), law(penalty, integration), 0.01, 300);
            let compliance = h.weight / penalty;
            let bound = n as f64 * gap + 5.0 * compliance;
            let moved = h.largest_move.iter().fold(0.0f64, |m, x| m.max(*x));
            let error = reaction_error(&h, settled);
            println!(
                "{n} bricks, gaps {gap:e} m, {integration:?}: largest move {moved:.3e} m (bound {bound:.3e}), |R/W − 1| ≤ {error:.2e} from {settled} ms",
            );
            assert!(moved <= bound, "moved {moved:e} m > {bound:e} m");
            assert!(error <= 5e-3, "|R/W − 1| = {error:e}");
        }
    }
}

/// Walls with every joint closed at the start, at penalties of E and 10 E
/// × 1 m: running bond (the upper courses' vertices on the lower bricks'
/// edges, the end bricks' corners coinciding) and stack bond (four corners
/// at every crossing of the joints). Both laws used to fail at the first
/// step of the running bond (open–close not settled down to Δt = 1.6e-5
/// s). Every step converges, no brick moves more than five times the
/// wall's weight over the penalty, and over the last 100 of 200 steps the
/// base carries the wall's weight to 0.5 %.
#[test]
fn touching_walls_converge_and_carry_their_weight() {
    for (bond, blocks) in [
        ("running bond", running_bond(4, 5, 0.0, 0.0)),
        ("stack bond", stack_bond(4, 5, 0.0, 0.0)),
    ] {
        for penalty in [E, 10.0 * E] {
            for integration in LAWS {
                let h = run(blocks.clone(), law(penalty, integration), 0.01, 200);
                let error = reaction_error(&h, 100);
                let moved = h.largest_move.iter().fold(0.0f64, |m, x| m.max(*x));
                let bound = 5.0 * h.weight / penalty;
                println!(
                    "{bond}, penalty {penalty:e}, {integration:?}: |R/W − 1| ≤ {error:.2e} over the last 100 steps, largest move {moved:.3e} m (bound {bound:.3e})"
                );
                assert!(error <= 5e-3, "|R/W − 1| = {error:e}");
                assert!(moved <= bound, "moved {moved:e} m > {bound:e} m");
            }
        }
    }
}

/// A search distance as large as a brick (0.2 m on a wall of 0.2 m bricks)
/// used to make a vertex level with the bricks' tops a contact of a far
/// edge, from behind: base reaction 1155 × the weight, bricks flung 4.9 m,
/// every step `Converged`. The same wall now settles as with 10 mm, at a
/// search distance of a brick and of the whole wall's length and more (10
/// m, every pair of bricks a pair of the step): over the last 100 of 300
/// steps the base carries the weight to 0.5 %, and no brick moves more
/// than its bed joints' closure and a millimetre.
#[test]
fn a_search_distance_as_large_as_a_brick_settles_the_wall() {
    for (search, integration) in [0.2, 10.0]
        .into_iter()
        .flat_map(|s| LAWS.into_iter().map(move |l| (s, l)))
    {
        let h = run(
            running_bond(4, 5, 1e-5, 0.002),
            law(E, integration),
            search,
            300,
        );
        let error = reaction_error(&h, 200);
        let moved = h.largest_move.iter().fold(0.0f64, |m, x| m.max(*x));
        println!("search {search} m, {integration:?}: |R/W − 1| ≤ {error:.2e} over the last 100 steps, largest move {moved:.3e} m");
        assert!(error <= 5e-3, "|R/W − 1| = {error:e}");
        assert!(moved <= 4.0 * 1e-5 + 1e-3, "moved {moved:e} m");
    }
}

/// Newton's test of convergence knows the round-off of the equations: at a
/// penalty of 1e8 E × 1 m (1e18) a column of five bricks converged only to
/// a relative residual of 1e-7 against the tolerance 1e-10, and its steps
/// were halved until the run failed; the residual's round-off (a contact's
/// stiffness times the rounding of the two bodies' motions in its gap) is
/// now the tolerance there, and the column stands, every step whole. At
/// 1e22 that round-off alone is above what a step may leave, and the step
/// is refused, with the penalty to go down to.
#[test]
fn a_penalty_stiff_to_round_off_converges_or_is_refused_naming_a_penalty() {
    let model = |penalty: f64| {
        DdaModel::new(
            column(5, 0.0),
            law(penalty, FrictionIntegration::ReturnMapping),
            DdaSettings::default(),
        )
        .unwrap()
    };
    let mut stiff = model(1e18);
    let weight: f64 = stiff.blocks()[1..]
        .iter()
        .map(|b| b.area() * DENSITY * G)
        .sum();
    let mut halvings = 0;
    for _ in 0..100 {
        let report = stiff.advance(1e-3).unwrap();
        halvings += report.reductions;
    }
    let ratio = -stiff.contact_force_on(0).y / weight;
    println!("1e18: {halvings} halvings, R/W = {ratio}");
    assert_eq!(halvings, 0);
    assert!((ratio - 1.0).abs() <= 5e-3);
    let mut too_stiff = model(1e22);
    let Err(DismechError::Implicit(ImplicitError::StepFailed { reason, .. })) =
        too_stiff.advance(1e-3)
    else {
        panic!("the step at 1e22 was not refused")
    };
    let reason = &reason;
    println!("1e22: {reason}");
    assert!(matches!(reason, StepFailure::RoundOff { .. }), "{reason}");
    assert!(reason.to_string().contains("lower the penalty to about"));
}

/// Stopping an update at a quantile of the stick points of the contacts
/// whose slip would reverse again, rather than at the first, settles the
/// same wall: a settling running bond of 205 bricks (bed joints open by
/// 10 µm) at E × 1 m, every step converging, the base carrying the weight
/// to 0.5 % over the last 100 of 300 steps, with 0 and with the default
/// 0.2;
/// the two take different numbers of linear solves (the setting acts). A
/// quantile outside [0, 1) is refused naming it.
#[test]
fn a_quantile_of_the_stick_points_settles_the_wall() {
    let mut solves = Vec::new();
    for quantile in [0.0, 0.2] {
        let settings = DdaSettings {
            slip_reversal_quantile: quantile,
            ..DdaSettings::default()
        };
        let law = law(E, FrictionIntegration::ReturnMapping);
        let mut model = DdaModel::new(running_bond(10, 20, 1e-5, 0.002), law, settings).unwrap();
        let weight: f64 = model.blocks()[1..]
            .iter()
            .map(|b| b.area() * DENSITY * G)
            .sum();
        let (mut total, mut error) = (0, 0.0f64);
        for step in 0..300 {
            let report = model
                .advance(1e-3)
                .unwrap_or_else(|e| panic!("quantile {quantile}, step {step}: {e}"));
            total += report.iterations;
            if step >= 200 {
                error = error.max((-model.contact_force_on(0).y / weight - 1.0).abs());
            }
        }
        println!("quantile {quantile}: {total} linear solves in 300 steps, |R/W − 1| ≤ {error:.2e} over the last 100");
        assert!(error <= 5e-3, "quantile {quantile}: |R/W − 1| = {error:e}");
        solves.push(total);
    }
    assert_ne!(solves[0], solves[1]);
    for bad in [1.0, -0.1, f64::NAN] {
        let settings = DdaSettings {
            slip_reversal_quantile: bad,
            ..DdaSettings::default()
        };
        let refused = DdaModel::new(
            running_bond(1, 2, 0.0, 0.0),
            law(E, FrictionIntegration::ReturnMapping),
            settings,
        );
        assert!(
            matches!(
                refused,
                Err(DismechError::InvalidParameter {
                    name: "slip_reversal_quantile",
                    ..
                })
            ),
            "{bad}: {:?}",
            refused.err()
        );
    }
}
