//! Trials per second of the slope search (the aim: 10⁶ random
//! ellipsoids on a 100 × 100-cell DEM in under 30 s on 2 cores, 30 µs a
//! trial) on the terrain shipped in examples/data/terrain (100 × 100 cells
//! of 75 m), and how the cost of a trial grows with its footprint: random
//! ellipsoids in three bands of size (semi-axis along the fall line 300–600,
//! 600–1200 and 1200–1875 m; across 0.5–1 times that; vertical a fifth of
//! the longest along, centres 0–187.5 m above the ground), 20 000 trials an
//! iteration, and the default sphere grid of `dismech slope` (37 500
//! trials). Before each band it prints the mean number of columns of the
//! trials that cut the ground, the size the cost follows.
//!
//! Run: `cargo bench --bench slope_search` (criterion prints the trials per
//! second as its throughput; `RAYON_NUM_THREADS=1` for one thread).

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use dismech::law::friction_from_degrees;
use dismech::slope::{
    search, surface_columns, EllipsoidRandom, SearchSettings, SlopeLoads, SlopeMaterial,
    SphereGrid, Steps, Terrain, TrialFamily,
};

fn terrain() -> Terrain {
    let dem = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/data/terrain/jacksboro_fault.asc");
    Terrain::read(&dem, None).expect("the shipped terrain reads")
}

/// The mean number of columns of the first `n` trials that cut the ground.
fn mean_columns<F: TrialFamily>(terrain: &Terrain, family: &F, n: u64) -> f64 {
    let mut columns = Vec::new();
    let (mut sum, mut cut) = (0usize, 0usize);
    for i in 0..n.min(family.len(terrain)) {
        let Ok(surface) = family.trial(terrain, i) else {
            continue;
        };
        if surface_columns(terrain, &surface, &mut columns).is_ok() && !columns.is_empty() {
            sum += columns.len();
            cut += 1;
        }
    }
    sum as f64 / cut.max(1) as f64
}

fn bench_search(c: &mut Criterion) {
    let terrain = terrain();
    let material = SlopeMaterial {
        cohesion: 15e3,
        friction_coefficient: friction_from_degrees(28.0).expect("28° is an angle"),
        unit_weight: 20e3,
    };
    let loads = SlopeLoads::default();
    let settings = SearchSettings::default();
    let mut group = c.benchmark_group("slope search, 100 × 100 DEM");
    group.sample_size(10);
    const TRIALS: u64 = 20_000;
    for along in [(300.0, 600.0), (600.0, 1200.0), (1200.0, 1875.0)] {
        let family = EllipsoidRandom::new(
            TRIALS,
            1,
            (0.0, 187.5),
            along,
            (0.5, 1.0),
            (75.0, along.1 / 5.0),
        )
        .expect("a valid family");
        println!(
            "ellipsoids along {}–{} m: {:.1} columns a trial that cuts the ground",
            along.0,
            along.1,
            mean_columns(&terrain, &family, 5_000)
        );
        group.throughput(Throughput::Elements(TRIALS));
        group.bench_function(
            format!("ellipsoids, along {}–{} m", along.0, along.1),
            |b| {
                b.iter(|| {
                    search(&terrain, &material, &loads, &family, &settings, |_, _| {})
                        .expect("the search runs")
                })
            },
        );
    }
    let spheres = SphereGrid::new(
        4,
        Steps::checked("heights", 75.0, 1875.0, 6, false).expect("valid heights"),
        Steps::checked("radii", 300.0, 2500.0, 10, true).expect("valid radii"),
    )
    .expect("a valid grid");
    println!(
        "sphere grid: {:.1} columns a trial that cuts the ground",
        mean_columns(&terrain, &spheres, spheres.len(&terrain))
    );
    group.throughput(Throughput::Elements(spheres.len(&terrain)));
    group.bench_function("spheres, the default grid", |b| {
        b.iter(|| {
            search(&terrain, &material, &loads, &spheres, &settings, |_, _| {})
                .expect("the search runs")
        })
    });
    group.finish();
}

criterion_group!(benches, bench_search);
criterion_main!(benches);
