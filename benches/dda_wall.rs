//! Speed of the implicit DDA on a running-bond wall of rectangular blocks
//! on a fixed base under gravity, with the default settings and the
//! return-mapping law: milliseconds and Newton iterations per step, at
//! about 100, 400 and 1 600 blocks, with the linear solver's symbolic
//! analyses, fallbacks to partial pivoting and the fill of its factor
//! (stored entries of L and U against those of the tangent). A timed run
//! rather than a criterion loop (a step of the large wall takes a
//! noticeable time); the first step, where the bed joints close, takes
//! most iterations, so the mean, the median and the first step are all
//! printed.
//!
//! Run: `cargo bench --bench dda_wall` (optionally `-- 400 1600` for some
//! sizes, `steps=20` for the number of steps per size, `verbose` for every
//! step; for one core,
//! `RAYON_NUM_THREADS=1 taskset -c 0 cargo bench --bench dda_wall`).
//!
//! Bricks are 0.4 m × 0.2 m; even courses hold `c` whole bricks, odd
//! courses a half brick at each end and `c − 1` whole ones between, so
//! that the head joints of one course sit over the middle of the bricks
//! below. Head joints are open by 2 mm (inside the search distance, so
//! they are open contacts of the system) and no two vertices of adjacent
//! courses coincide. The bed joints start closed with zero overlap.

use std::time::Instant;

use dismech::dda::{
    Block, BlockMaterial, DdaModel, DdaSettings, FrictionIntegration, PenaltyCoulomb, PlaneState,
    Prescribed,
};
use dismech::linsolve::LinearSolverInfo;
use dismech::math::Point;

/// Brick length and height (m).
const BRICK: (f64, f64) = (0.4, 0.2);
/// Width of the head joints (m).
const JOINT: f64 = 0.002;

fn rectangle(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<Point> {
    vec![
        Point::new(x0, y0),
        Point::new(x1, y0),
        Point::new(x1, y1),
        Point::new(x0, y1),
    ]
}

/// Courses and whole bricks per even course of a wall of about `target`
/// blocks, about four times as long as high.
fn wall_shape(target: usize) -> (usize, usize) {
    let courses = ((target as f64 / 2.0).sqrt().round() as usize).max(1);
    // ⌈courses/2⌉ c + ⌊courses/2⌋ (c + 1) ≈ target.
    let odd = courses / 2;
    let c = ((target.saturating_sub(odd)) as f64 / courses as f64).round() as usize;
    (courses, c.max(2))
}

/// The blocks of a wall of `courses` courses, `c` whole bricks per even
/// course, on a fixed base (block 0).
fn wall(courses: usize, c: usize) -> Result<Vec<Block>, Box<dyn std::error::Error>> {
    let material = BlockMaterial {
        density: 2200.0,
        youngs_modulus: 5e9,
        poisson_ratio: 0.2,
        plane: PlaneState::Stress,
    };
    let (w, h) = BRICK;
    let length = c as f64 * w;
    let mut blocks = Vec::new();
    let mut base = Block::new(&rectangle(-0.5, -0.5, length + 0.5, 0.0), material, 0)?;
    base.prescribed = Some(Prescribed::fixed());
    blocks.push(base);
    let g = 0.5 * JOINT;
    for course in 0..courses {
        let (y0, y1) = (course as f64 * h, (course + 1) as f64 * h);
        let mut spans = Vec::new();
        if course % 2 == 0 {
            spans.extend((0..c).map(|k| (k as f64 * w + g, (k + 1) as f64 * w - g)));
        } else {
            spans.push((JOINT, 0.5 * w - g));
            spans.extend((0..c - 1).map(|k| ((k as f64 + 0.5) * w + g, (k as f64 + 1.5) * w - g)));
            spans.push((length - 0.5 * w + g, length - JOINT));
        }
        for (x0, x1) in spans {
            let index = blocks.len();
            blocks.push(Block::new(&rectangle(x0, y0, x1, y1), material, index)?);
        }
    }
    Ok(blocks)
}

fn run(target: usize, steps: usize, verbose: bool) -> Result<(), Box<dyn std::error::Error>> {
    let (courses, c) = wall_shape(target);
    let blocks = wall(courses, c)?;
    let count = blocks.len() - 1;
    let law = PenaltyCoulomb::new(1e9, 0.7, FrictionIntegration::ReturnMapping)?;
    let mut model = DdaModel::new(blocks, law, DdaSettings::default())?;
    let dt = 1e-3;
    let mut times = Vec::with_capacity(steps);
    let (mut iterations, mut open_close, mut substeps) = (0, 0, 0);
    for _ in 0..steps {
        let start = Instant::now();
        let report = model
            .advance(dt)
            .map_err(|e| format!("{count} blocks: {e}"))?;
        times.push(start.elapsed().as_secs_f64() * 1e3);
        if verbose {
            println!(
                "  step {}: {:.1} ms, {} iterations ({} open-close), {} substeps, {} reductions, {} contacts",
                times.len(),
                times[times.len() - 1],
                report.residuals.len() - 1,
                report.open_close_iterations,
                report.substeps,
                report.reductions,
                model.contacts().len()
            );
        }
        iterations += report.residuals.len() - 1;
        open_close += report.open_close_iterations;
        substeps += report.substeps;
    }
    let mean = times.iter().sum::<f64>() / steps as f64;
    let mut sorted = times.clone();
    sorted.sort_by(f64::total_cmp);
    let solver = model.linear_solver();
    println!(
        "{count} blocks ({courses} courses, {c} bricks), {} DOF, {} contacts: {mean:.1} ms/step (median {:.1}, first {:.1}); {:.2} iterations/step ({:.2} open-close), {:.2} substeps/step; {} symbolic analyses, {} fallbacks to partial pivoting; tangent {} entries, factor L+U {} entries",
        6 * (count + 1),
        model.contacts().len(),
        sorted[steps / 2],
        times[0],
        iterations as f64 / steps as f64,
        open_close as f64 / steps as f64,
        substeps as f64 / steps as f64,
        model.symbolic_analyses(),
        solver.fallbacks(),
        solver.matrix_entries(),
        solver
            .factor_entries()
            .map_or("(not reported)".to_string(), |e| e.to_string()),
    );
    Ok(())
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
        .unwrap_or(10usize)
        .max(1);
    for target in sizes {
        run(target, steps, args.iter().any(|a| a == "verbose"))?;
    }
    Ok(())
}
