//! Helpers shared by the DDA test files.

use dismech::dda::{BlockMaterial, PlaneState};
use dismech::math::Point;

/// The blocks' material of the DDA tests: ρ = 2200 kg/m³, E = 1 GPa,
/// ν = 0.25, plane stress.
pub fn material() -> BlockMaterial {
    BlockMaterial {
        density: 2200.0,
        youngs_modulus: 1e9,
        poisson_ratio: 0.25,
        plane: PlaneState::Stress,
    }
}

/// The corners of the rectangle `[x0, x1] × [y0, y1]`, counter-clockwise
/// from the lower left.
#[allow(dead_code)]
pub fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<Point> {
    vec![
        Point::new(x0, y0),
        Point::new(x1, y0),
        Point::new(x1, y1),
        Point::new(x0, y1),
    ]
}
