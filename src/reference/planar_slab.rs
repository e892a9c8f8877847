//! The safety factor of a slab on a planar slip surface, fixed by global
//! equilibrium: the check of a 3D slope method (HPM, paper 001; Hovland)
//! where the answer is known.

/// A uniform slab on a planar slip surface dipping at `dip`, with
/// cohesion `c` and friction `tan φ` on the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarSlab {
    /// Cohesion c on the slip surface (Pa).
    pub cohesion: f64,
    /// Friction coefficient tan φ on the slip surface.
    pub friction: f64,
    /// Weight W carried by the slip surface (N): with a water table, the
    /// submerged unit weight below it.
    pub weight: f64,
    /// Plan (horizontal) area of the slab (m²); the slip surface's area is
    /// `plan_area / cos β`.
    pub plan_area: f64,
    /// Dip β of the slip surface (rad).
    pub dip: f64,
}

impl PlanarSlab {
    /// Fs under a horizontal seismic coefficient `k_h` pointing down the
    /// dip: `(cA + W(cos β − k_h sin β) tan φ) / (W(sin β + k_h cos β))`,
    /// with `A = plan_area / cos β`.
    pub fn safety_factor(&self, seismic_coefficient: f64) -> f64 {
        let kh = seismic_coefficient;
        let (s, c) = self.dip.sin_cos();
        let w = self.weight;
        (self.cohesion * self.plan_area / c + w * (c - kh * s) * self.friction) / (w * (s + kh * c))
    }
}
