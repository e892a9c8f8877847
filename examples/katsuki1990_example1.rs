//! Paper 000 (Katsuki & Ishikawa 1990), Example 1, composed from the
//! library pieces: 179 circles (r = 0.07 m) settle under self-weight in a
//! rigid frame 2.0 m wide; the wall reactions are compared with the weight.
//!
//! Run with `cargo run --release --example katsuki1990_example1`.

use dismech::dem::DemSimulation;
use dismech::explicit::{DemSettings, RestCriterion};
use dismech::integrate::ExplicitEuler;
use dismech::law::SpringDashpotCoulomb;
use dismech::math::{Point, Vec2};
use dismech::scene::{Frame, Scene};

fn main() -> Result<(), dismech::error::DismechError> {
    // Material of the paper in SI units: E = 750 kgf/cm², ρ = 2.69 gf/cm³.
    let g = 9.80665;
    let (density, youngs_modulus) = (2690.0, 750.0 * g / 1e-4);
    let law = SpringDashpotCoulomb::katsuki(youngs_modulus, 0.3, 0.25, 0.577)?;

    // Shape + frame: rows of 14 and 13 circles, started without contacts.
    let mut scene = Scene::new(Frame::open_box(2.0, 3.0)?, Vec2::new(0.0, -g))?;
    let (radius, pitch) = (0.07, 2.0 / 14.0);
    let mut row = 0;
    while scene.particles.len() < 179 {
        let (count, x0) = if row % 2 == 0 {
            (14, 0.5 * pitch)
        } else {
            (13, pitch)
        };
        let count = count.min(179 - scene.particles.len());
        let offset = if count < 13 {
            ((13 - count) / 2) as f64 * pitch
        } else {
            0.0
        };
        for k in 0..count {
            let centre = Point::new(x0 + offset + k as f64 * pitch, 0.075 + 0.16 * row as f64);
            scene.add_circle(centre, radius, density)?;
        }
        row += 1;
    }

    // Contact law + explicit Euler integrator, run to rest.
    let settings = DemSettings {
        dt: 1e-4,
        ..DemSettings::default()
    };
    let mut sim = DemSimulation::new(scene, law, ExplicitEuler, settings)?;
    let outcome = sim.run_to_rest(
        &RestCriterion {
            min_time: 0.5,
            ..RestCriterion::default()
        },
        |_, _| {},
    )?;

    // Equilibrium: wall reactions against the weight.
    let weight = sim.scene().total_weight();
    let reaction = |name: &str| -sim.wall_load(sim.scene().frame.index_of(name).unwrap_or(0));
    let (left, bottom, right) = (reaction("left"), reaction("bottom"), reaction("right"));
    println!(
        "{:?} after {:.2} s ({} steps)",
        outcome.status, outcome.time, outcome.steps
    );
    println!("weight W                     = {weight:.1} N/m");
    println!(
        "sum of vertical reactions / W = {:.6}",
        (left.y + bottom.y + right.y) / weight
    );
    println!(
        "|F_left + F_right| / W        = {:.2e}",
        (left.x + right.x).abs() / weight
    );
    println!("side-wall thrust F_left / W   = {:.4}", left.x / weight);
    Ok(())
}
