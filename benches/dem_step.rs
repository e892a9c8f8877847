//! Speed of one explicit DEM step on a settled filling (paper 000's
//! Example 1: 179 circles in a 2.0 m frame), and of the broad phase alone.

use criterion::{criterion_group, criterion_main, Criterion};
use dismech::broad_phase::CellGrid;
use dismech::dem::{DemSettings, DemSimulation, RestCriterion};
use dismech::error::DismechError;
use dismech::integrate::ExplicitEuler;
use dismech::law::SpringDashpotCoulomb;
use dismech::math::Aabb2;
use dismech::scene::CircleRows;

/// Example 1 settled: ρ = 2.69 gf/cm³, E = 750 kgf/cm², ν = 0.3,
/// k_s/k_n = 0.25, μ = 0.577, Δt = 1e-4 s, g = 9.80665 m/s², and the
/// study's rest criterion.
fn settled_example1() -> Result<DemSimulation<SpringDashpotCoulomb, ExplicitEuler>, DismechError> {
    let g = 9.80665;
    let rows = CircleRows {
        count: 179,
        radius: 0.07,
        width: 2.0,
        height: 3.0,
        per_row: 14,
        row_pitch: 0.16,
        clearance: 0.005,
        density: 2.69 * 1e-3 / 1e-6,
    };
    let law = SpringDashpotCoulomb::katsuki(750.0 * g / 1e-4, 0.3, 0.25, 0.577)?;
    let settings = DemSettings {
        dt: 1e-4,
        ..DemSettings::default()
    };
    let mut sim = DemSimulation::new(rows.scene(g)?, law, ExplicitEuler, settings)?;
    let rest = RestCriterion {
        kinetic_to_released_ratio: 1e-6,
        min_time: 0.5,
        max_time: 30.0,
        check_every: 100,
        consecutive_checks: 10,
        unbalanced_force_ratio: 1e-4,
    };
    sim.run_to_rest(&rest, |_, _| {})?;
    Ok(sim)
}

fn bench_dem(c: &mut Criterion) {
    let mut sim = match settled_example1() {
        Ok(s) => s,
        Err(e) => panic!("settling the benchmark filling failed: {e}"),
    };
    c.bench_function("dem step, 179 settled circles", |b| {
        b.iter(|| sim.step().map_err(|e| e.to_string()))
    });
    let boxes: Vec<Aabb2> = sim
        .scene()
        .particles
        .iter()
        .map(|p| p.shape.as_shape().aabb(&p.pose))
        .collect();
    let mut grid = CellGrid::new();
    let mut pairs = Vec::new();
    c.bench_function("cell grid pairs, 179 circles", |b| {
        b.iter(|| grid.candidate_pairs(&boxes, 0.0, &mut pairs))
    });
}

criterion_group!(benches, bench_dem);
criterion_main!(benches);
