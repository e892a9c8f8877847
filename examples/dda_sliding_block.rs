//! Paper 003 (Hashimoto, Koyama & Kikumoto), the sliding block under
//! shaking, composed from the library pieces: two polygon blocks, the
//! penalty Coulomb law with return mapping, Newmark (β = ½, γ = 1) and the
//! sparse Newton solve inside `DdaModel`. The block's displacement relative
//! to the base is printed beside the exact rigid solution (Newmark 1965).
//!
//! Run with `cargo run --release --example dda_sliding_block`.

use dismech::dda::{
    Block, BlockMaterial, DdaModel, DdaSettings, FrictionIntegration, PenaltyCoulomb, PlaneState,
    Prescribed,
};
use dismech::math::{Point, Vec2};
use dismech::reference::{rigid_sliding_block, Shaking};

fn rectangle(x0: f64, y0: f64, x1: f64, y1: f64) -> [Point; 4] {
    [
        Point::new(x0, y0),
        Point::new(x1, y0),
        Point::new(x1, y1),
        Point::new(x0, y1),
    ]
}

fn main() -> Result<(), dismech::error::DismechError> {
    // Material of the paper in SI units: 21.56 kN/m³ with g = 9.8 m/s².
    let g = 9.8;
    let rock = BlockMaterial {
        density: 21.56e3 / g,
        youngs_modulus: 14.9e9,
        poisson_ratio: 0.2,
        plane: PlaneState::Stress,
    };
    let mu = 36.4f64.to_radians().tan();
    let penalty = 2e9; // 2e6 kN/m
                       // f = 2 Hz, peak acceleration 1.5 μ g, three cycles.
    let shaking = Shaking::with_peak_acceleration(1.5 * mu * g, 2.0, 3.0);
    let (a, w) = (shaking.amplitude, shaking.omega());

    // Shapes: a base driven by u_b = A sin ωt, a block resting on it in
    // equilibrium (each corner carries half the weight).
    let mut base = Block::new(&rectangle(-3.0, -0.5, 3.0, 0.0), rock, 0)?;
    base.prescribed = Some(Prescribed::translation(move |t| {
        Vec2::new(a * (w * t).sin(), 0.0)
    }));
    let settle = 0.5 * rock.density * 2.0 * 0.25 * g / penalty;
    let mut block = Block::new(&rectangle(-1.0, -settle, 1.0, 0.25 - settle), rock, 1)?;
    base.velocity[0] = a * w;
    block.velocity[0] = a * w;

    // Contact law + model (Newmark and the sparse solver live inside).
    let law = PenaltyCoulomb::new(penalty, mu, FrictionIntegration::ReturnMapping)?;
    let settings = DdaSettings {
        gravity: Vec2::new(0.0, -g),
        search_distance: 0.02,
        overlap_tolerance: 1e-3,
        ..DdaSettings::default()
    };
    let mut model = DdaModel::new(vec![base, block], law, settings)?;

    let dt = 0.001;
    println!("    t (s)   DDA s (mm)   exact s (mm)");
    for step in 1..=(shaking.duration / dt).round() as usize {
        if let Err(e) = model.advance(dt) {
            eprintln!("stopped: {e}");
            break;
        }
        if step % 100 == 0 {
            let b = model.blocks();
            let s = b[1].displacement[0] - b[0].displacement[0];
            let exact = rigid_sliding_block(&shaking, mu, g, &[model.time()])[0];
            println!("{:9.3} {:12.4} {:14.4}", model.time(), s * 1e3, exact * 1e3);
        }
    }
    Ok(())
}
