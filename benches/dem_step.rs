//! Speed of one explicit DEM step on a settled filling (Example 1 size),
//! and of the broad phase alone.

use criterion::{criterion_group, criterion_main, Criterion};
use dismech::broad_phase::CellGrid;
use dismech::math::Aabb2;
use dismech::reproduce::katsuki1990::{settle, FillConfig};

fn bench_dem(c: &mut Criterion) {
    let (mut sim, _) = match settle(&FillConfig::paper(), |_, _| {}) {
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
