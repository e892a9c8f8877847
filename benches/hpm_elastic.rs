//! Speed and memory of one elastic HPM solve at the size of issue 5: a
//! 100 × 100-column slope (10 m cells) with 5 layers, 50 000 elements and
//! 600 000 DOF. A timed run rather than a criterion loop (one solve takes
//! seconds); it prints the time of each stage, the stored entries of the
//! stiffness, the peak resident memory of the process and the memory the
//! budget (`HpmSettings::memory_budget`) counts for the model and its solver.
//!
//! Run: `cargo bench --bench hpm_elastic` (optionally `-- 60 3` for a
//! 60 × 60-column grid with 3 layers; add `pcg` for conjugate gradients
//! with column blocks instead of the sparse Cholesky factor, to a relative
//! residual of 1e-8, or `tol=1e-6` for another residual; `amg` for
//! conjugate gradients preconditioned by smoothed-aggregation multigrid,
//! `amg pcg` for both side by side on the same model, `theta=0.08` for
//! another strength threshold of the aggregation, `modes=12` for all
//! linear motions as near-null space, `sweeps=2` for two Gauss–Seidel
//! sweeps a side; `plan=2` for the column multigrid, whose finest level
//! solves whole columns and aggregates squares of 2 × 2 columns
//! (`HpmSolver::column_multigrid`); the multigrid runs also print the CPU
//! time of all threads, which, unlike the wall time, does not grow while
//! other processes share the cores; `mtx=DIR` writes the stiffness, the load vector and the
//! rigid motions (`B.mtx`; `B12.mtx` with the uniform strains) in Matrix
//! Market files under DIR for `benches/hpm_pyamg.py` and stops).

use std::time::Instant;

use dismech::grid::Raster;
use dismech::hpm::{
    HpmMaterial, HpmModel, HpmSettings, HpmSolver, NamedRaster, Seismic, SlopeGrids,
};
use dismech::linsolve::{AggregationSettings, CgSettings, LinearSolverInfo};

/// Peak resident memory (VmHWM) of this process, in MiB, where /proc has it.
fn peak_memory_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

/// CPU time of this process (all its threads, user and system), in
/// seconds, where /proc has it: unlike the wall time, it does not grow
/// when other processes share the cores.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // Fields after the command name (in parentheses): utime and stime are
    // the 12th and 13th, in clock ticks (100 a second).
    let rest = stat.rsplit_once(')').map_or("", |(_, r)| r);
    let ticks: f64 = rest
        .split_whitespace()
        .skip(11)
        .take(2)
        .filter_map(|t| t.parse::<f64>().ok())
        .sum();
    ticks / 100.0
}

/// Write the stiffness (`K.mtx`, symmetric, lower triangle), the loads
/// without earthquake (`b.mtx`) and the rigid motions (`B.mtx`, 6
/// columns) in Matrix Market coordinate and array formats.
fn export(model: &HpmModel, dir: &std::path::Path) -> Result<(), Box<dyn std::error::Error>> {
    use std::io::Write;
    std::fs::create_dir_all(dir)?;
    let lower = model.stiffness().lower_triangle()?;
    let n = lower.dimension();
    let mut k = std::io::BufWriter::new(std::fs::File::create(dir.join("K.mtx"))?);
    writeln!(k, "%%MatrixMarket matrix coordinate real symmetric")?;
    writeln!(k, "{n} {n} {}", lower.values().len())?;
    let (ptr, rows) = (lower.pattern().col_ptr(), lower.pattern().row_idx());
    for j in 0..n {
        for (row, value) in rows[ptr[j]..ptr[j + 1]]
            .iter()
            .zip(&lower.values()[ptr[j]..ptr[j + 1]])
        {
            writeln!(k, "{} {} {value:e}", row + 1, j + 1)?;
        }
    }
    let array = |name: &str, columns: usize, values: &[f64]| -> std::io::Result<()> {
        let mut f = std::io::BufWriter::new(std::fs::File::create(dir.join(name))?);
        writeln!(f, "%%MatrixMarket matrix array real general")?;
        let rows = values.len() / columns;
        writeln!(f, "{rows} {columns}")?;
        // Array format is by columns; `values` is by rows.
        for c in 0..columns {
            for r in 0..rows {
                writeln!(f, "{:e}", values[r * columns + c])?;
            }
        }
        Ok(())
    };
    array("b.mtx", 1, &model.loads(&Seismic::none()))?;
    array("B.mtx", 6, &dismech::hpm::linear_motions(model, 6)?)?;
    array("B12.mtx", 12, &dismech::hpm::linear_motions(model, 12)?)?;
    println!(
        "wrote K.mtx ({n} unknowns, {} entries of the lower triangle), b.mtx, B.mtx to {}",
        lower.values().len(),
        dir.display()
    );
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let n = args.first().copied().unwrap_or(100);
    let layers = args.get(1).copied().unwrap_or(5);
    let d = 10.0;
    let side = n as f64 * d;
    // A 15° slope facing −y with a slide 5 to 25 m deep over the whole grid.
    let ground = Raster::from_fn(n, n, 0.0, 0.0, d, |_, y| Some(0.27 * y))?;
    let slip = Raster::from_fn(n, n, 0.0, 0.0, d, |x, y| {
        let bowl =
            (std::f64::consts::PI * x / side).sin() * (std::f64::consts::PI * y / side).sin();
        Some(0.27 * y - 5.0 - 20.0 * bowl)
    })?;
    let grids = SlopeGrids::new(
        NamedRaster::new("ground", ground),
        NamedRaster::new("slip", slip),
        None,
    )?;
    let settings = HpmSettings {
        layers,
        ..HpmSettings::default()
    };
    let t0 = Instant::now();
    let model = HpmModel::new(&grids, &HpmMaterial::paper(), &settings)?;
    let t1 = Instant::now();
    let model_s = (t1 - t0).as_secs_f64();
    let relative_tolerance = std::env::args()
        .find_map(|a| a.strip_prefix("tol=").and_then(|t| t.parse().ok()))
        .unwrap_or(1e-8);
    let settings = CgSettings {
        relative_tolerance,
        max_iterations: 100_000,
    };
    if let Some(dir) = std::env::args().find_map(|a| a.strip_prefix("mtx=").map(String::from)) {
        return export(&model, std::path::Path::new(&dir));
    }
    let amg = std::env::args().any(|a| a == "amg");
    if amg {
        let aggregation = AggregationSettings {
            strength_threshold: std::env::args()
                .find_map(|a| a.strip_prefix("theta=").and_then(|t| t.parse().ok()))
                .unwrap_or(0.0),
            sweeps: std::env::args()
                .find_map(|a| a.strip_prefix("sweeps=").and_then(|t| t.parse().ok()))
                .unwrap_or(1),
            max_levels: std::env::var("DISMECH_LEVELS")
                .ok()
                .and_then(|v| v.parse().ok())
                .unwrap_or(10),
            max_coarse: std::env::var("DISMECH_COARSE")
                .ok()
                .and_then(|v| v.parse().ok())
                .unwrap_or(2000),
            ..AggregationSettings::default()
        };
        let modes = std::env::args()
            .find_map(|a| a.strip_prefix("modes=").and_then(|t| t.parse().ok()))
            .unwrap_or(6);
        let t1 = Instant::now();
        let c1 = cpu_seconds();
        let plan: Option<usize> =
            std::env::args().find_map(|a| a.strip_prefix("plan=").and_then(|t| t.parse().ok()));
        let mut solver = match plan {
            Some(plan) => HpmSolver::column_multigrid(&model, settings, aggregation, modes, plan)?,
            None => HpmSolver::multigrid(&model, settings, aggregation, modes)?,
        };
        let t2 = Instant::now();
        let c2 = cpu_seconds();
        let result = solver.elastic(&model, &Seismic::none())?;
        let t3 = Instant::now();
        let c3 = cpu_seconds();
        let amg = solver.linear_solver().preconditioner();
        println!(
            "HPM elastic by PCG + smoothed aggregation ({modes} modes), {n} x {n} columns, {layers} layers: {} elements, {} DOF; levels {:?} unknowns, operator complexity {:.2}; model {:.2} s; assembly + hierarchy {:.2} s; PCG {:.2} s; setup + PCG {:.2} s; CPU time (all threads) of the hierarchy {:.2} s and of PCG {:.2} s; {:?}; Fs = {:.8}; peak resident memory {:?} MiB",
            model.elements.len(),
            model.dof(),
            amg.level_sizes(),
            amg.operator_complexity(),
            model_s,
            (t2 - t1).as_secs_f64(),
            (t3 - t2).as_secs_f64(),
            (t3 - t1).as_secs_f64(),
            c2 - c1,
            c3 - c2,
            result.convergence,
            result.safety_factor(&model)?,
            peak_memory_mib()
        );
    }
    if std::env::args().any(|a| a == "pcg") {
        let t1 = Instant::now();
        let mut solver = HpmSolver::iterative(&model, settings)?;
        let t2 = Instant::now();
        let result = solver.elastic(&model, &Seismic::none())?;
        let t3 = Instant::now();
        println!(
            "HPM elastic by PCG, {n} x {n} columns, {layers} layers: {} elements, {} DOF; model {:.2} s; assembly + column blocks {:.2} s; PCG {:.2} s; total {:.2} s; {:?}; Fs = {:.4}; peak resident memory {:?} MiB",
            model.elements.len(),
            model.dof(),
            model_s,
            (t2 - t1).as_secs_f64(),
            (t3 - t2).as_secs_f64(),
            model_s + (t3 - t1).as_secs_f64(),
            result.convergence,
            result.safety_factor(&model)?,
            peak_memory_mib()
        );
        let largest = result
            .displacements
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        println!(
            "relative tolerance {relative_tolerance:e}; largest |u| = {largest:.6e} m; Fs = {:.8}",
            result.safety_factor(&model)?
        );
        return Ok(());
    }
    if amg {
        return Ok(());
    }
    let t2 = Instant::now();
    let mut solver = HpmSolver::new(&model)?;
    let t3 = Instant::now();
    let result = solver.elastic(&model, &Seismic::none())?;
    let t4 = Instant::now();
    let factor = solver.linear_solver();
    let stages = factor.timings();
    println!(
        "HPM elastic, {n} x {n} columns, {layers} layers: {} elements, {} DOF, {} stored entries of the lower triangle of K",
        model.elements.len(),
        model.dof(),
        factor.matrix_entries()
    );
    let staged = stages.convert + stages.symbolic + stages.numeric;
    println!(
        "model {:.2} s; block assembly {:.2} s; compressed lower triangle {:.2} s; AMD + symbolic Cholesky {:.2} s; numeric Cholesky (faer, {:?}) {:.2} s; loads + solve + tractions {:.2} s; total {:.2} s",
        (t1 - t0).as_secs_f64(),
        ((t3 - t2).saturating_sub(staged)).as_secs_f64(),
        stages.convert.as_secs_f64(),
        stages.symbolic.as_secs_f64(),
        faer::get_global_parallelism(),
        stages.numeric.as_secs_f64(),
        (t4 - t3).as_secs_f64(),
        (t4 - t0).as_secs_f64()
    );
    let estimate = solver.memory_estimate().unwrap_or(0) as f64 / (1024.0 * 1024.0);
    println!(
        "{} stored entries of the Cholesky factor L (faer, AMD ordering); Fs = {:.4}; peak resident memory {:?} MiB; memory estimate (model, compressed lower triangle, factor and workspace, as the budget counts it) {estimate:.0} MiB",
        factor.factor_entries().unwrap_or(0),
        result.safety_factor(&model)?,
        peak_memory_mib()
    );
    Ok(())
}
