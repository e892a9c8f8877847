//! DEM throughput on the setup of the LAMMPS anchor
//! (`../shared/anchors/lammps/in.disks2d`), printed as particle-steps per
//! second of the timed steps.
//!
//! `NX × NY` disks on a square lattice of pitch 0.14 m (centres at
//! `((i + ½) 0.14, (j + ½) 0.14)`), diameters uniform in [0.12, 0.138] m,
//! density 2690 kg/m³ with LAMMPS' masses in 2D (a sphere's mass
//! `ρ 4/3 π r³` and moment of inertia `0.4 m r²`: LAMMPS' `set density`
//! makes 2D particles spheres), horizontal velocities uniform in ±0.1 m/s,
//! walls at x = 0 and x = NX·0.14 m and a floor at y = 0, gravity 9.81 m/s².
//! Contacts: linear spring `k_n = 1.6e7 N/m`, `k_s = 2/7 k_n`, dashpots
//! `m_eff γ` with `γ_n = 2000 /s`, `γ_s = γ_n / 2`, Coulomb `μ = 0.577`;
//! `Δt = 1e-4 s`. The run settles for SETTLE steps, then STEPS steps are
//! timed.
//!
//! `--shape ellipse` replaces each disk by an ellipse of the same area
//! (`a/b = 1.5`, `a b = r²`) and the same mass, inertia `m (a² + b²)/5`,
//! all with the major axis at 45° (parallel ellipses at that angle clear
//! the lattice's neighbours; the random orientations would not). An
//! ellipse at 45° reaches 0.072 m from its centre in x and y, beyond the
//! lattice's 0.07 m from the walls, so the ellipses' box is 2 cm wider and
//! the lattice moved 1 cm right and up.
//!
//! ```text
//! cargo run --release --example dem_throughput -- --nx 100 --ny 100 --settle 20000 --steps 10000
//! cargo run --release --example dem_throughput -- --nx 200 --ny 200 --threads 2
//! cargo run --release --example dem_throughput -- --nx 316 --ny 316 --settle 4000 --steps 2000 --threads 2 --phases
//! cargo run --release --example dem_throughput -- --nx 100 --ny 100 --shape ellipse
//! ```
//!
//! `--observer` measures what an observer costs: after the settling, the
//! timed steps go in rounds of `--block` steps taken alternately by
//! `step()` and by `run_steps_observed` with the observer named
//! (`unobserved`: `dismech::observe::Unobserved`; `every100`: a closure
//! under `dismech::observe::every(100, …)` that reads the driver's time at
//! every hundredth step, as a progress bar does; `every-step`: a closure
//! called at every step, reading the time), and the median rate of each
//! is printed with their ratio. Interleaved rounds see the same packing
//! and the same load on a shared machine.
//!
//! ```text
//! cargo run --release --example dem_throughput -- --nx 100 --ny 100 --settle 5000 --steps 10000 --observer every-step
//! ```
//!
//! The random numbers are not LAMMPS' (a different generator), so the
//! packing is of the same kind, not the same disks.
//!
//! `--numbering columns` numbers the same particles column by column
//! instead of row by row, and `--numbering local` renumbers the rows'
//! numbering with `Scene::renumber_for_locality` (column by column in
//! bands 32 mean widths high, about 30 of the lattice's rows). The
//! physics is the same; the order of the force sums, and so the last
//! bits, differ, and so does the speed of large scenes (the README's
//! throughput section).

use std::time::Instant;

use clap::{Parser, ValueEnum};
use dismech::dem::DemSimulation;
use dismech::error::DismechError;
use dismech::explicit::DemSettings;
use dismech::law::{Damping, NormalStiffness, SpringDashpotCoulomb};
use dismech::math::{Point, Pose2, Vec2};
use dismech::scene::{Frame, Particle, Scene};
use dismech::shape::{AnyShape2, Circle, Ellipse, MassProperties};
use rand::{RngExt, SeedableRng};

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum ShapeChoice {
    Disk,
    Ellipse,
}

/// The order in which the lattice's particles are numbered.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Numbering {
    /// Row by row from the floor up (LAMMPS' `create_atoms` order).
    Rows,
    /// Column by column from the left wall.
    Columns,
    /// Rows, then `Scene::renumber_for_locality` (bands 32 mean widths
    /// high, about 30 rows, each column by column).
    Local,
}

/// The observer of `--observer`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum ObserverChoice {
    /// `dismech::observe::Unobserved`.
    Unobserved,
    /// A closure under `every(100, …)` reading the time.
    Every100,
    /// A closure at every step reading the time.
    EveryStep,
}

/// DEM particle-steps per second on the LAMMPS anchor's setup.
#[derive(Debug, Parser)]
struct Args {
    /// Columns of the lattice.
    #[arg(long, default_value_t = 100)]
    nx: usize,
    /// Rows of the lattice.
    #[arg(long, default_value_t = 100)]
    ny: usize,
    /// Steps to settle before timing.
    #[arg(long, default_value_t = 20_000)]
    settle: u64,
    /// Steps timed.
    #[arg(long, default_value_t = 10_000)]
    steps: u64,
    /// Particle shape.
    #[arg(long, value_enum, default_value_t = ShapeChoice::Disk)]
    shape: ShapeChoice,
    /// Order of the particles' indices: the same disks at the same places
    /// either way (the random diameters and velocities are drawn row by
    /// row), numbered by rows, by columns, or renumbered for locality.
    #[arg(long, value_enum, default_value_t = Numbering::Rows)]
    numbering: Numbering,
    /// Threads of the force loop (rayon's pool).
    #[arg(long, default_value_t = 1)]
    threads: usize,
    /// Skin of the neighbour list (m), fixed; when omitted, the driver's
    /// default, tuned at each build.
    #[arg(long)]
    skin: Option<f64>,
    /// Seed of the diameters and velocities.
    #[arg(long, default_value_t = 4321)]
    seed: u64,
    /// Print where the timed steps spent their time, by phase
    /// (`ExplicitDynamics::time_phases`).
    #[arg(long)]
    phases: bool,
    /// Time the steps with and without this observer, in alternate rounds.
    #[arg(long, value_enum)]
    observer: Option<ObserverChoice>,
    /// Steps of a round of `--observer`.
    #[arg(long, default_value_t = 500)]
    block: u64,
}

const PITCH: f64 = 0.14;
const DENSITY: f64 = 2690.0;
const K_N: f64 = 1.6e7;
const GAMMA_N: f64 = 2000.0;

fn scene(args: &Args) -> Result<Scene, DismechError> {
    let margin = match args.shape {
        ShapeChoice::Disk => 0.0,
        ShapeChoice::Ellipse => 0.01,
    };
    let width = args.nx as f64 * PITCH + 2.0 * margin;
    let height = args.ny as f64 * PITCH * 1.5;
    let mut scene = Scene::new(Frame::open_box(width, height)?, Vec2::new(0.0, -9.81))?;
    let mut rng = rand::rngs::StdRng::seed_from_u64(args.seed);
    // Each site's particle, drawn row by row whatever the numbering.
    let mut sites = Vec::with_capacity(args.nx * args.ny);
    for j in 0..args.ny {
        for i in 0..args.nx {
            let r = 0.5 * (0.12 + 0.018 * rng.random::<f64>());
            let vx = 0.2 * (rng.random::<f64>() - 0.5);
            let mass = DENSITY * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
            let (shape, inertia): (AnyShape2, f64) = match args.shape {
                ShapeChoice::Disk => (Circle::new(r)?.into(), 0.4 * mass * r * r),
                ShapeChoice::Ellipse => {
                    let b = r / 1.5f64.sqrt();
                    let a = 1.5 * b;
                    (Ellipse::new(a, b)?.into(), mass * (a * a + b * b) / 5.0)
                }
            };
            let centre = Point::new(
                margin + (i as f64 + 0.5) * PITCH,
                margin + (j as f64 + 0.5) * PITCH,
            );
            let mut p = Particle::at_rest(shape, centre, MassProperties { mass, inertia });
            if args.shape == ShapeChoice::Ellipse {
                p.pose = Pose2::new(centre.x, centre.y, std::f64::consts::FRAC_PI_4);
            }
            p.velocity = Vec2::new(vx, 0.0);
            sites.push(p);
        }
    }
    match args.numbering {
        Numbering::Rows => scene.particles = sites,
        Numbering::Local => {
            scene.particles = sites;
            scene.renumber_for_locality();
        }
        Numbering::Columns => {
            for i in 0..args.nx {
                scene
                    .particles
                    .extend((0..args.ny).map(|j| sites[j * args.nx + i].clone()));
            }
        }
    }
    Ok(scene)
}

/// Peak resident memory of the process (bytes), from /proc.
fn peak_resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    // The run goes inside the pool: the stepping thread is one of its
    // workers, so the loops of each step do not wake a thread outside it.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads)
        .build()?;
    pool.install(|| run(&args))
        .map_err(|e| e as Box<dyn std::error::Error>)
}

fn run(args: &Args) -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
    let law = SpringDashpotCoulomb::new(
        NormalStiffness::Constant(K_N),
        2.0 / 7.0,
        0.577,
        Damping::PerMass {
            normal: GAMMA_N,
            shear: GAMMA_N / 2.0,
        },
    )?;
    let settings = DemSettings {
        dt: 1e-4,
        neighbour_skin: args.skin,
        ..DemSettings::default()
    };
    let scene = scene(args)?;
    let n = scene.particles.len();
    let rss_before = peak_resident_bytes();
    let mut sim = DemSimulation::new(scene, law, dismech::integrate::ExplicitEuler, settings)?;
    let started = Instant::now();
    for _ in 0..args.settle {
        sim.step()?;
    }
    let settle_seconds = started.elapsed().as_secs_f64();
    let builds = sim.neighbour_list_builds();
    if args.phases {
        sim.time_phases();
    }
    if let Some(choice) = args.observer {
        return compare_observer(&mut sim, args, choice, n);
    }
    let timed = Instant::now();
    for _ in 0..args.steps {
        sim.step()?;
    }
    let seconds = timed.elapsed().as_secs_f64();
    let rate = (n as f64) * (args.steps as f64) / seconds;
    let rss = match (rss_before, peak_resident_bytes()) {
        (Some(before), Some(after)) => format!(
            "{:.0} B/particle",
            after.saturating_sub(before) as f64 / n as f64
        ),
        _ => "unknown".into(),
    };
    println!(
        "{:?} n={n} numbering={:?} threads={} settle={} ({settle_seconds:.2} s) steps={} in {seconds:.3} s: \
         {rate:.4e} particle-steps/s; neighbour list built {} times (skin {:.4} m at the last build); peak memory of the run {rss}; \
         kinetic energy {:.4e} J; {:.2} contact points per particle at the end (each pair once, walls included)",
        args.shape,
        args.numbering,
        args.threads,
        args.settle,
        args.steps,
        sim.neighbour_list_builds() - builds,
        sim.neighbour_skin(),
        sim.kinetic_energy(),
        sim.contacts().len() as f64 / n as f64
    );
    if let Some(phases) = sim.phase_times() {
        print!("{phases}");
    }
    Ok(())
}

type Sim = DemSimulation<SpringDashpotCoulomb>;

/// The median of `rates`.
fn median(mut rates: Vec<f64>) -> f64 {
    rates.sort_by(f64::total_cmp);
    let k = rates.len() / 2;
    if rates.len() % 2 == 1 {
        rates[k]
    } else {
        0.5 * (rates[k - 1] + rates[k])
    }
}

/// `--observer`: rounds of `block` steps, alternately plain and observed,
/// and the median rate of each.
fn compare_observer(
    sim: &mut Sim,
    args: &Args,
    choice: ObserverChoice,
    n: usize,
) -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
    use dismech::observe::{every, Event, Unobserved};
    let block = args.block.max(1);
    let rounds = (args.steps / (2 * block)).max(1);
    let mut latest = 0.0;
    let mut read = |sim: &Sim, _: &Event<'_>| -> dismech::error::Result<()> {
        latest = sim.time();
        Ok(())
    };
    let (mut plain, mut observed) = (Vec::new(), Vec::new());
    let rate = |seconds: f64| n as f64 * block as f64 / seconds;
    for _ in 0..rounds {
        let t = Instant::now();
        for _ in 0..block {
            sim.step()?;
        }
        plain.push(rate(t.elapsed().as_secs_f64()));
        let t = Instant::now();
        match choice {
            ObserverChoice::Unobserved => sim.run_steps_observed(block, &mut Unobserved)?,
            ObserverChoice::Every100 => {
                sim.run_steps_observed(block, &mut every(100, &mut read))?
            }
            ObserverChoice::EveryStep => sim.run_steps_observed(block, &mut read)?,
        }
        observed.push(rate(t.elapsed().as_secs_f64()));
    }
    let (plain, observed) = (median(plain), median(observed));
    println!(
        "{:?} n={n} threads={} settle={} rounds={rounds} of {block} steps each way: \
         step() {plain:.4e} particle-steps/s, run_steps_observed with {choice:?} {observed:.4e} particle-steps/s \
         (medians); observed / plain = {:.4} (time at the end {:.4} s)",
        args.shape,
        args.threads,
        args.settle,
        observed / plain,
        sim.time(),
    );
    let _ = latest;
    Ok(())
}
