//! Helpers shared by the DDA test files.

use dismech::dda::{BlockMaterial, PlaneState};

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
