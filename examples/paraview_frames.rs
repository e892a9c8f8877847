//! A DEM settling written for ParaView: 300 discs and ellipses dropped
//! into a box, 20 frames of the run as a `.pvd` time series.
//!
//! ```text
//! cargo run --release --example paraview_frames -- target/paraview_frames
//! ```
//!
//! writes into the folder `particles.pvd`, `contacts.pvd` and `walls.pvd`
//! (open them in ParaView: *File → Open*, *Apply*, then step through time)
//! and the frames they index (`particles_000000.vtu`, …). The arrays are
//! described in the `dismech::vtk` module. `examples/render_frame.py`
//! renders a frame to PNG without a screen:
//!
//! ```text
//! python3 examples/render_frame.py target/paraview_frames --frame 4 --out frame.png
//! ```
//!
//! The particles: 20 columns × 15 rows on a 3 cm lattice, every fourth an
//! ellipse (a/b = 1.6) at a random angle, the others discs of radius
//! 0.8–1.2 cm, density 2600 kg/m³, small random sideways velocities; a
//! linear spring–dashpot law (k_n = 10⁵ N/m per m, k_s = k_n / 4, μ = 0.5,
//! critical damping); Δt = 10⁻⁴ s; 1.5 s.

use std::path::PathBuf;

use clap::Parser;
use dismech::dem::DemSimulation;
use dismech::explicit::DemSettings;
use dismech::integrate::ExplicitEuler;
use dismech::law::{Damping, NormalStiffness, SpringDashpotCoulomb};
use dismech::math::{Point, Pose2, Vec2};
use dismech::scene::{Frame, Scene};
use dismech::shape::{Circle, Ellipse};
use dismech::vtk::{dem_frame, PvdSeries, DEFAULT_SEGMENTS};
use rand::{RngExt, SeedableRng};

/// Write a DEM settling as ParaView frames.
#[derive(Debug, Parser)]
struct Args {
    /// Folder of the series (created; its earlier frames are overwritten).
    out: PathBuf,
    /// Frames written, the first at the start.
    #[arg(long, default_value_t = 20)]
    frames: usize,
    /// Simulated time (s).
    #[arg(long, default_value_t = 1.5)]
    duration: f64,
    /// Seed of the sizes, angles and velocities.
    #[arg(long, default_value_t = 7)]
    seed: u64,
}

const COLUMNS: usize = 20;
const ROWS: usize = 15;
const PITCH: f64 = 0.03;
const DENSITY: f64 = 2600.0;
const DT: f64 = 1e-4;

fn scene(seed: u64) -> Result<Scene, Box<dyn std::error::Error>> {
    let width = COLUMNS as f64 * PITCH;
    let mut scene = Scene::new(Frame::open_box(width, 0.7)?, Vec2::new(0.0, -9.81))?;
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    for row in 0..ROWS {
        for column in 0..COLUMNS {
            let centre = Point::new((column as f64 + 0.5) * PITCH, 0.25 + row as f64 * PITCH);
            let k = if (row + column) % 4 == 0 {
                let b = 0.0085;
                let angle = std::f64::consts::PI * rng.random::<f64>();
                scene.add_shape(
                    Ellipse::new(1.6 * b, b)?,
                    Pose2::new(centre.x, centre.y, angle),
                    DENSITY,
                )?
            } else {
                let r = 0.008 + 0.004 * rng.random::<f64>();
                scene.add_shape(
                    Circle::new(r)?,
                    Pose2::new(centre.x, centre.y, 0.0),
                    DENSITY,
                )?
            };
            scene.particles[k].velocity = Vec2::new(0.2 * (rng.random::<f64>() - 0.5), 0.0);
        }
    }
    Ok(scene)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    let law =
        SpringDashpotCoulomb::new(NormalStiffness::Constant(1e5), 0.25, 0.5, Damping::Critical)?;
    let settings = DemSettings {
        dt: DT,
        ..DemSettings::default()
    };
    let mut dem = DemSimulation::new(scene(args.seed)?, law, ExplicitEuler, settings)?;
    let mut series = PvdSeries::new(&args.out)?;
    let frames = args.frames.max(2);
    let steps = (args.duration / DT).round() as usize;
    series.write_frame(dem.time(), &dem_frame(&dem, DEFAULT_SEGMENTS)?)?;
    for frame in 1..frames {
        // Steps up to this frame's share of the run.
        while (dem.steps() as usize) < steps * frame / (frames - 1) {
            dem.step()?;
        }
        series.write_frame(dem.time(), &dem_frame(&dem, DEFAULT_SEGMENTS)?)?;
    }
    println!(
        "{} particles, {} frames to t = {:.3} s ({} contact points at the end); open in ParaView:",
        dem.scene().particles.len(),
        series.frames(),
        dem.time(),
        dem.contacts().len()
    );
    for name in series.piece_names() {
        println!("  {}", series.pvd_path(name).display());
    }
    Ok(())
}
