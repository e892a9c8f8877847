//! The costs of a wide size distribution and of a large polygon: the DEM's
//! set-up, step and broad phase on 160 000 grains on a square lattice
//! (pitch 0.14 m, radii 0.060–0.069 m, the `polydisperse` example's
//! scene), alone and with one boulder of 40 times the median radius (5.2 m
//! across) resting on them; and the validation of a 100 000-vertex polygon.

use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use dismech::broad_phase::CellGrid;
use dismech::dem::DemSimulation;
use dismech::error::DismechError;
use dismech::explicit::DemSettings;
use dismech::integrate::ExplicitEuler;
use dismech::law::{Damping, NormalStiffness, SpringDashpotCoulomb};
use dismech::math::{Aabb2, Point, SplitMix64, Vec2};
use dismech::scene::{Frame, Particle, Scene};
use dismech::shape::{Circle, MassProperties, Polygon};

const SIDE: usize = 400;
const PITCH: f64 = 0.14;
const MEDIAN_RADIUS: f64 = 0.0645;

fn disk(r: f64, centre: Point) -> Result<Particle, DismechError> {
    let mass = 2690.0 * std::f64::consts::PI * r * r;
    Ok(Particle::at_rest(
        Circle::new(r)?.into(),
        centre,
        MassProperties {
            mass,
            inertia: 0.5 * mass * r * r,
        },
    ))
}

/// 400 × 400 grains, and a boulder of `boulder` median radii (none at 0).
fn scene(boulder: f64) -> Result<Scene, DismechError> {
    let width = SIDE as f64 * PITCH;
    let top = SIDE as f64 * PITCH;
    let boulder = boulder * MEDIAN_RADIUS;
    let mut scene = Scene::new(
        Frame::open_box(width, 1.5 * top + 2.0 * boulder)?,
        Vec2::new(0.0, -9.81),
    )?;
    let mut random = SplitMix64(4321);
    for j in 0..SIDE {
        for i in 0..SIDE {
            let r = 0.060 + 0.009 * random.next_uniform();
            let centre = Point::new((i as f64 + 0.5) * PITCH, (j as f64 + 0.5) * PITCH);
            let mut p = disk(r, centre)?;
            p.velocity = Vec2::new(0.2 * (random.next_uniform() - 0.5), 0.0);
            scene.particles.push(p);
        }
    }
    if boulder > 0.0 {
        scene.particles.push(disk(
            boulder,
            Point::new(0.5 * width, top + boulder + 0.01),
        )?);
    }
    Ok(scene)
}

fn simulation(
    scene: Scene,
) -> Result<DemSimulation<SpringDashpotCoulomb, ExplicitEuler>, DismechError> {
    let law = SpringDashpotCoulomb::new(
        NormalStiffness::Constant(1.6e7),
        2.0 / 7.0,
        0.577,
        Damping::PerMass {
            normal: 2000.0,
            shear: 1000.0,
        },
    )?;
    let settings = DemSettings {
        dt: 1e-4,
        ..DemSettings::default()
    };
    DemSimulation::new(scene, law, ExplicitEuler, settings)
}

fn bench_polydisperse(c: &mut Criterion) {
    let mut group = c.benchmark_group("polydisperse");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(4));
    for (name, boulder) in [
        ("160 000 grains", 0.0),
        ("160 000 grains and a boulder", 40.0),
    ] {
        let scene = match scene(boulder) {
            Ok(s) => s,
            Err(e) => panic!("the benchmark's scene is valid: {e}"),
        };
        let boxes: Vec<Aabb2> = scene
            .particles
            .iter()
            .map(|p| p.shape.as_shape().aabb(&p.pose))
            .collect();
        let mut grid = CellGrid::new();
        let mut pairs = Vec::new();
        group.bench_function(format!("cell grid pairs, {name}"), |b| {
            b.iter(|| grid.candidate_pairs(&boxes, 0.01, &mut pairs))
        });
        group.bench_function(format!("dem set-up, {name}"), |b| {
            b.iter(|| {
                simulation(scene.clone())
                    .map(|s| s.steps())
                    .map_err(|e| e.to_string())
            })
        });
        let mut sim = match simulation(scene) {
            Ok(s) => s,
            Err(e) => panic!("the benchmark's simulation starts: {e}"),
        };
        group.bench_function(format!("dem step, {name}"), |b| {
            b.iter(|| sim.step().map_err(|e| e.to_string()))
        });
    }
    group.finish();
}

/// A circle of 100 000 vertices with a notch every 1000 (not convex).
fn bench_polygon(c: &mut Criterion) {
    let n = 100_000;
    let vertices: Vec<Point> = (0..n)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / n as f64;
            let r = if k % 1000 == 0 { 0.5 } else { 1.0 };
            Point::new(r * t.cos(), r * t.sin())
        })
        .collect();
    let mut group = c.benchmark_group("polygon");
    group.sample_size(10);
    group.bench_function("validate 100 000 vertices", |b| {
        b.iter(|| {
            Polygon::from_world(&vertices, 0)
                .map(|(p, _)| p.vertices().len())
                .map_err(|e| e.to_string())
        })
    });
    group.finish();
}

criterion_group!(benches, bench_polydisperse, bench_polygon);
criterion_main!(benches);
