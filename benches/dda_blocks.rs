//! The implicit DDA on block systems as rock engineers build them, with
//! both friction integrations of paper 003 on the same wall: running-bond
//! walls of 0.4 m × 0.2 m bricks (E = 10 GPa, plane strain, μ = 0.6) on a
//! fixed base, Δt = 1 ms, search distance 10 mm, at penalties of E × 1 m
//! and 10 E × 1 m, at about 100, 400 and 1 600 bricks, in two states:
//!
//! * `touching`: every joint closed at the start (the upper courses'
//!   vertices on the lower bricks' edges, the end bricks' corners
//!   coinciding with those below), as block cutting from joint sets
//!   leaves them;
//! * `settling`: bed joints open by 10 µm and head joints by 2 mm, so the
//!   courses fall onto each other in the first steps.
//!
//! For each wall and law it prints milliseconds per step (mean, median,
//! largest), linear solves per step, open–close iterations per step,
//! halvings (all, and after the first 10 steps) and the base reaction over
//! the weight at the last step; then the ratio of the mean step of return
//! mapping to the conventional one. A timed run, not a criterion loop.
//!
//! Run: `cargo bench --bench dda_blocks` (optionally sizes, e.g. `-- 100
//! 400`, `steps=N` (50 by default), `touching` or `settling` for one state,
//! `penalty=1` or `penalty=10` for one penalty (× E × 1 m), `law=return` or
//! `law=conventional` for one friction integration, `trace` for a
//! line per step (milliseconds, solves, open–close iterations, halvings),
//! `quantile=Q` for [`DdaSettings::slip_reversal_quantile`] (the settings'
//! default, 0.2, otherwise);
//! for one core,
//! `RAYON_NUM_THREADS=1 taskset -c 0 cargo bench --bench dda_blocks`).

use std::time::Instant;

use dismech::dda::{
    Block, BlockMaterial, DdaModel, DdaSettings, FrictionIntegration, Halvings, PenaltyCoulomb,
    PlaneState, Prescribed,
};
use dismech::error::DismechError;
use dismech::implicit::ImplicitError;
use dismech::math::Point;

const E: f64 = 10e9;
const DENSITY: f64 = 2200.0;
/// Brick length and height (m).
const BRICK: (f64, f64) = (0.4, 0.2);

fn rectangle(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<Point> {
    vec![
        Point::new(x0, y0),
        Point::new(x1, y0),
        Point::new(x1, y1),
        Point::new(x0, y1),
    ]
}

fn material() -> BlockMaterial {
    BlockMaterial {
        density: DENSITY,
        youngs_modulus: E,
        poisson_ratio: 0.2,
        plane: PlaneState::Strain,
    }
}

/// Courses and whole bricks per even course of a wall of about `target`
/// bricks, about four times as long as high.
fn wall_shape(target: usize) -> (usize, usize) {
    let courses = ((target as f64 / 2.0).sqrt().round() as usize).max(1);
    let odd = courses / 2;
    let c = ((target.saturating_sub(odd)) as f64 / courses as f64).round() as usize;
    (courses, c.max(2))
}

/// A running-bond wall on a fixed base (block 0): even courses hold `c`
/// whole bricks, odd ones a half brick at each end and `c − 1` whole ones;
/// bed joints open by `bed`, head joints by `head`.
fn wall(
    courses: usize,
    c: usize,
    bed: f64,
    head: f64,
) -> Result<Vec<Block>, Box<dyn std::error::Error>> {
    let (w, h) = BRICK;
    let length = c as f64 * w;
    let mut base = Block::new(&rectangle(-0.5, -0.5, length + 0.5, 0.0), material(), 0)?;
    base.prescribed = Some(Prescribed::fixed());
    let mut blocks = vec![base];
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
            blocks.push(Block::new(
                &rectangle(x0, y0, x1, y0 + h),
                material(),
                index,
            )?);
        }
    }
    Ok(blocks)
}

/// What one run measured.
struct Run {
    mean_ms: f64,
    median_ms: f64,
    largest_ms: f64,
    solves: f64,
    open_close: f64,
    halvings: usize,
    late_halvings: usize,
    causes: Halvings,
    reaction: f64,
    failure: Option<String>,
}

fn run(
    blocks: Vec<Block>,
    penalty: f64,
    integration: FrictionIntegration,
    steps: usize,
    trace: bool,
    quantile: f64,
) -> Result<Run, Box<dyn std::error::Error>> {
    let law = PenaltyCoulomb::new(penalty, 0.6, integration)?;
    let settings = DdaSettings {
        slip_reversal_quantile: quantile,
        ..DdaSettings::default()
    };
    let mut model = DdaModel::new(blocks, law, settings)?;
    let weight: f64 = model.blocks()[1..]
        .iter()
        .map(|b| b.area() * DENSITY * 9.8)
        .sum();
    let mut times = Vec::with_capacity(steps);
    let (mut solves, mut open_close, mut halvings, mut late_halvings) = (0, 0, 0, 0);
    let mut causes = Halvings::default();
    let mut failure = None;
    for step in 0..steps {
        let start = Instant::now();
        let outcome = model.advance(1e-3);
        times.push(start.elapsed().as_secs_f64() * 1e3);
        let (report, failed) = match outcome {
            Ok(report) => (report, None),
            Err(DismechError::Implicit(ImplicitError::StepFailed { reason, report, .. })) => {
                (*report, Some(reason))
            }
            Err(e) => return Err(e.into()),
        };
        solves += report.iterations;
        open_close += report.open_close_iterations;
        halvings += report.reductions;
        causes.add(&report.halvings);
        if step >= 10 {
            late_halvings += report.reductions;
        }
        if trace {
            println!(
                "step {step:>3} {:>8.1} ms solves {:>3} open-close {:>3} halvings {}",
                times[step], report.iterations, report.open_close_iterations, report.reductions
            );
        }
        if let Some(reason) = failed {
            failure = Some(format!("step {step}: {reason}"));
            break;
        }
    }
    let n = times.len() as f64;
    let mut sorted = times.clone();
    sorted.sort_by(f64::total_cmp);
    Ok(Run {
        mean_ms: times.iter().sum::<f64>() / n,
        median_ms: sorted[sorted.len() / 2],
        largest_ms: sorted[sorted.len() - 1],
        solves: solves as f64 / n,
        open_close: open_close as f64 / n,
        halvings,
        late_halvings,
        causes,
        reaction: -model.contact_force_on(0).y / weight,
        failure,
    })
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut sizes: Vec<usize> = args.iter().filter_map(|a| a.parse().ok()).collect();
    if sizes.is_empty() {
        sizes = vec![100, 400, 1600];
    }
    let steps = args
        .iter()
        .find_map(|a| a.strip_prefix("steps=").and_then(|s| s.parse().ok()))
        .unwrap_or(50usize)
        .max(1);
    let trace = args.iter().any(|a| a == "trace");
    let quantile = args
        .iter()
        .find_map(|a| a.strip_prefix("quantile=").and_then(|s| s.parse().ok()))
        .unwrap_or(DdaSettings::default().slip_reversal_quantile);
    let states: Vec<(&str, f64, f64)> = [("touching", 0.0, 0.0), ("settling", 1e-5, 0.002)]
        .into_iter()
        .filter(|(name, _, _)| {
            !args.iter().any(|a| a == "touching" || a == "settling")
                || args.iter().any(|a| a == name)
        })
        .collect();
    let integrations: Vec<FrictionIntegration> = [
        ("return", FrictionIntegration::ReturnMapping),
        ("conventional", FrictionIntegration::Conventional),
    ]
    .into_iter()
    .filter(|(name, _)| {
        !args.iter().any(|a| a.starts_with("law="))
            || args.iter().any(|a| a.strip_prefix("law=") == Some(name))
    })
    .map(|(_, integration)| integration)
    .collect();
    if integrations.is_empty() {
        return Err("law= takes `return` or `conventional`".into());
    }
    let penalties: Vec<f64> = match args.iter().find_map(|a| {
        a.strip_prefix("penalty=")
            .and_then(|s| s.parse::<f64>().ok())
    }) {
        Some(k) => vec![k],
        None => vec![1.0, 10.0],
    };
    println!(
        "{:>6} {:>9} {:>7} {:>5} {:>8} {:>8} {:>8} {:>7} {:>6} {:>9} {:>9} {:>8}",
        "bricks",
        "state",
        "penalty",
        "law",
        "ms/step",
        "median",
        "largest",
        "solves",
        "o-c",
        "halvings",
        "after 10",
        "R/W"
    );
    for &target in &sizes {
        let (courses, c) = wall_shape(target);
        for &(state, bed, head) in &states {
            for &k in &penalties {
                let mut means = Vec::new();
                for &integration in &integrations {
                    let blocks = wall(courses, c, bed, head)?;
                    let count = blocks.len() - 1;
                    let r = run(blocks, k * E, integration, steps, trace, quantile)?;
                    println!(
                        "{count:>6} {state:>9} {:>7} {:>5} {:>8.1} {:>8.1} {:>8.1} {:>7.2} {:>6.2} {:>9} {:>9} {:>8.5}  {}{}",
                        format!("{k} E"),
                        integration.label(),
                        r.mean_ms,
                        r.median_ms,
                        r.largest_ms,
                        r.solves,
                        r.open_close,
                        r.halvings,
                        r.late_halvings,
                        r.reaction,
                        if r.halvings > 0 {
                            format!(
                                "(open-close {}, Newton {}, too fast {}, other {})",
                                r.causes.open_close,
                                r.causes.newton,
                                r.causes.too_fast,
                                r.causes.other
                            )
                        } else {
                            String::new()
                        },
                        r.failure.map_or(String::new(), |f| format!("  FAILED at {f}")),
                    );
                    means.push(r.mean_ms);
                }
                if let [return_mapping, conventional] = means[..] {
                    println!(
                        "{:>6} {state:>9} {:>7} return mapping / conventional: {:.2}",
                        "",
                        format!("{k} E"),
                        return_mapping / conventional
                    );
                }
            }
        }
    }
    Ok(())
}
