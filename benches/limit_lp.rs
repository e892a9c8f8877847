//! Speed of the rigid-plastic LP: assembly and solve of the rolling U-model
//! at k = 40 (1 600 elements) and k = 100 (10 000 elements, n' = 25), in
//! the kinematic (velocities) and the static (forces) formulation.

use criterion::{criterion_group, criterion_main, Criterion};
use dismech::limit::lattice::Lattice;
use dismech::limit::{analyse, analyse_static};
use dismech::lp::LinearProgramSolver;

fn bench_lp(c: &mut Criterion) {
    let mut group = c.benchmark_group("rolling U-model limit load");
    group.sample_size(10);
    for (k, np) in [(40usize, 10usize), (100, 25)] {
        let lattice = Lattice::u_model(k, k, np, true);
        group.bench_function(format!("kinematic, k = {k}, n' = {np}"), |b| {
            b.iter(|| {
                let model = lattice.build().map_err(|e| e.to_string())?;
                analyse(&model, &mut LinearProgramSolver::default()).map_err(|e| e.to_string())
            })
        });
        group.bench_function(format!("static, k = {k}, n' = {np}"), |b| {
            b.iter(|| {
                let model = lattice.build().map_err(|e| e.to_string())?;
                analyse_static(&model, &mut LinearProgramSolver::default())
                    .map_err(|e| e.to_string())
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench_lp);
criterion_main!(benches);
