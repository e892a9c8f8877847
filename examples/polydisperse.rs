//! The cost of a wide size distribution: `NX × NY` disks on a square
//! lattice of pitch 0.14 m (radii uniform in [0.060, 0.069] m, the
//! `dem_throughput` example's grains), and, with `--boulder R`, one disk of
//! R times the median radius resting a hair above the lattice's middle
//! (R = 40: a 5.2 m boulder). Prints the time of the set-up
//! (`DemSimulation::new`, which checks the initial overlaps through the
//! broad phase), of the first step (the first build of the neighbour list)
//! and the milliseconds per step of the next STEPS steps.
//!
//! ```text
//! cargo run --release --example polydisperse -- --nx 400 --ny 400 --steps 40
//! cargo run --release --example polydisperse -- --nx 400 --ny 400 --steps 40 --boulder 40
//! ```

use std::time::Instant;

use clap::Parser;
use dismech::dem::DemSimulation;
use dismech::error::DismechError;
use dismech::explicit::DemSettings;
use dismech::law::{Damping, NormalStiffness, SpringDashpotCoulomb};
use dismech::math::{Point, Vec2};
use dismech::scene::{Frame, Particle, Scene};
use dismech::shape::{Circle, MassProperties};
use rand::{RngExt, SeedableRng};

/// Set-up and step times of a lattice of grains with one boulder.
#[derive(Debug, Parser)]
struct Args {
    /// Columns of the lattice.
    #[arg(long, default_value_t = 400)]
    nx: usize,
    /// Rows of the lattice.
    #[arg(long, default_value_t = 400)]
    ny: usize,
    /// Steps timed after the first.
    #[arg(long, default_value_t = 40)]
    steps: u64,
    /// The boulder's radius in median radii of the grains (none when 0).
    #[arg(long, default_value_t = 0.0)]
    boulder: f64,
    /// Threads (rayon's pool).
    #[arg(long, default_value_t = 1)]
    threads: usize,
    /// Seed of the radii and velocities.
    #[arg(long, default_value_t = 4321)]
    seed: u64,
}

const PITCH: f64 = 0.14;
const DENSITY: f64 = 2690.0;
const R_MIN: f64 = 0.060;
const R_SPREAD: f64 = 0.009;

fn disk(r: f64, centre: Point) -> Result<Particle, DismechError> {
    let mass = DENSITY * std::f64::consts::PI * r * r;
    Ok(Particle::at_rest(
        Circle::new(r)?.into(),
        centre,
        MassProperties {
            mass,
            inertia: 0.5 * mass * r * r,
        },
    ))
}

fn scene(args: &Args) -> Result<Scene, DismechError> {
    let width = args.nx as f64 * PITCH;
    let top = args.ny as f64 * PITCH;
    let boulder = args.boulder * (R_MIN + 0.5 * R_SPREAD);
    let height = 1.5 * top + 2.0 * boulder;
    let mut scene = Scene::new(Frame::open_box(width, height)?, Vec2::new(0.0, -9.81))?;
    let mut rng = rand::rngs::StdRng::seed_from_u64(args.seed);
    for j in 0..args.ny {
        for i in 0..args.nx {
            let r = R_MIN + R_SPREAD * rng.random::<f64>();
            let centre = Point::new((i as f64 + 0.5) * PITCH, (j as f64 + 0.5) * PITCH);
            let mut p = disk(r, centre)?;
            p.velocity = Vec2::new(0.2 * (rng.random::<f64>() - 0.5), 0.0);
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

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads)
        .build()?;
    pool.install(|| run(&args))
        .map_err(|e| e as Box<dyn std::error::Error>)
}

fn run(args: &Args) -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
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
    let scene = scene(args)?;
    let n = scene.particles.len();
    let started = Instant::now();
    let mut sim = DemSimulation::new(scene, law, dismech::integrate::ExplicitEuler, settings)?;
    let set_up = started.elapsed().as_secs_f64();
    let first = Instant::now();
    sim.step()?;
    let first = first.elapsed().as_secs_f64();
    let timed = Instant::now();
    for _ in 0..args.steps {
        sim.step()?;
    }
    let per_step = timed.elapsed().as_secs_f64() / args.steps.max(1) as f64;
    println!(
        "n={n} boulder={} threads={}: set-up {:.3} s, first step {:.1} ms, {:.2} ms a step over {} steps \
         ({} list builds), kinetic energy {:.6e} J",
        args.boulder,
        args.threads,
        set_up,
        1e3 * first,
        1e3 * per_step,
        args.steps,
        sim.neighbour_list_builds(),
        sim.kinetic_energy()
    );
    Ok(())
}
