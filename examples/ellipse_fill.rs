//! The ellipse DEM of paper 000 composed from the library pieces: flat
//! ellipses (a = 2b, the area of a 0.07 m circle) settle under self-weight
//! in a rigid frame 1.2 m wide; the wall reactions are compared with the
//! weight and the mean orientation of the particles is printed.
//!
//! Run with `cargo run --release --example ellipse_fill`.

use dismech::dem::DemSimulation;
use dismech::explicit::{DemSettings, RestCriterion};
use dismech::integrate::ExplicitEuler;
use dismech::law::SpringDashpotCoulomb;
use dismech::math::{Point, Vec2};
use dismech::scene::{Frame, Scene};

fn main() -> Result<(), dismech::error::DismechError> {
    let g = 9.80665;
    // Paper 000's material in SI units.
    let law = SpringDashpotCoulomb::katsuki(750.0 * g / 1e-4, 0.3, 0.25, 0.577)?;
    let (a, b) = (0.07 * 2f64.sqrt(), 0.07 / 2f64.sqrt());

    // Staggered rows of flat ellipses, started without contacts.
    let mut scene = Scene::new(Frame::open_box(1.2, 4.0)?, Vec2::new(0.0, -g))?;
    let pitch = 1.2 / 6.0;
    for row in 0..12 {
        let (count, x0) = if row % 2 == 0 {
            (6, 0.5 * pitch)
        } else {
            (5, pitch)
        };
        for k in 0..count {
            let centre = Point::new(
                x0 + k as f64 * pitch,
                b + 0.005 + row as f64 * (2.0 * b + 0.01),
            );
            // A small tilt per particle, so that the rows do not stay perfect.
            let tilt = 0.05 * ((row * 7 + k * 3) % 5) as f64 - 0.1;
            scene.add_ellipse(centre, a, b, tilt, 2690.0)?;
        }
    }

    let settings = DemSettings {
        dt: 1e-4,
        ..DemSettings::default()
    };
    let mut sim = DemSimulation::new(scene, law, ExplicitEuler, settings)?;
    let rest = RestCriterion {
        min_time: 0.5,
        ..RestCriterion::default()
    };
    let outcome = sim.run_to_rest(&rest, |_, _| {})?;

    let weight = sim.scene().total_weight();
    let vertical: f64 = (0..sim.scene().frame.walls().len())
        .map(|w| -sim.wall_load(w).y)
        .sum();
    let orientation = sim
        .scene()
        .particles
        .iter()
        .map(|p| p.pose.angle.rem_euclid(std::f64::consts::PI))
        .map(|t| t.min(std::f64::consts::PI - t).to_degrees())
        .sum::<f64>()
        / sim.scene().particles.len() as f64;
    println!(
        "{:?} after {:.2} s ({} steps)",
        outcome.status, outcome.time, outcome.steps
    );
    println!(
        "sum of vertical wall reactions / W = {:.6}",
        vertical / weight
    );
    println!("mean |tilt| of the major axes       = {orientation:.1}°");
    Ok(())
}
