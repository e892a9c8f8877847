//! The horizontal load that sets a rigid block on a frictional floor in
//! motion: rocking about a bottom corner or sliding, in closed form (the
//! exact answer of the rigid-plastic limit analysis of one block).
//!
//! A rigid `w × h` block of weight `W` stands on a rigid floor; its two
//! bottom corners touch the floor through unilateral Coulomb contacts
//! (`c = 0`, friction `μ = tan φ`, associated flow). A horizontal force
//! `P` acts at the height `h` of its top. The block's motion is a velocity
//! `(u, v)` of its centroid and a spin `ω`; at the corner `(±w/2, −h/2)`
//! (from the centroid) the velocity is `(u + ω h/2, v ± ω w/2)`. A
//! unilateral contact with associated flow may separate and slide, but its
//! normal (opening) rate must be at least `tan φ` times its slip rate,
//! and it dissipates nothing (no cohesion). The upper bound theorem then
//! reads: with the load's power normalised, `u − ω h/2 = 1` at the top,
//! the least `P` is the least work rate `W v` against gravity over the
//! admissible mechanisms,
//!
//! `P = W min_ω [ μ |1 + ω h| + |ω| w / 2 ]`,
//!
//! a convex piecewise-linear function of `ω` with its minimum at a kink:
//!
//! * `ω = 0`, **sliding** with dilation: both corners slip at unit rate
//!   and rise at `μ`, `P = μ W`;
//! * `ω = −1/h`, **rocking** about the leading corner (which neither slips
//!   nor opens) while the trailing corner lifts, `P = W w / (2h)`.
//!
//! So `P = W min(μ, w / 2h)`: the block tips when `μ > w/(2h)` and slides
//! when `μ < w/(2h)`. The same numbers follow from statics (a lower
//! bound): sliding needs `P = μ N` with `N = W`; tipping needs the moment
//! `P h` about the leading corner to reach `W w/2`. With associated flow
//! the sliding mechanism lifts the block (`v = μ` per unit slip); its power
//! against gravity `μ W` equals the frictional dissipation of the
//! non-associated Coulomb block, so the two laws share the limit load here.

/// How the block starts to move at its limit load.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BlockMechanism {
    /// Rotation about the bottom corner on the side the load pushes to.
    Tipping,
    /// Translation along the floor (with dilation `tan φ` under associated
    /// flow).
    Sliding,
}

/// A rigid `width × height` block of weight `weight` on a floor with
/// friction `friction = tan φ` at its two bottom corners.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockOnFloor {
    /// Width `w` along the floor (m).
    pub width: f64,
    /// Height `h` (m); the horizontal load acts at the top.
    pub height: f64,
    /// Weight `W` (N per m of thickness).
    pub weight: f64,
    /// Friction coefficient `μ = tan φ` of the corner contacts.
    pub friction: f64,
}

impl BlockOnFloor {
    /// The load that rocks the block about its leading corner,
    /// `W w / (2h)`.
    pub fn tipping_load(&self) -> f64 {
        self.weight * self.width / (2.0 * self.height)
    }

    /// The load that slides the block, `μ W`.
    pub fn sliding_load(&self) -> f64 {
        self.friction * self.weight
    }

    /// The friction coefficient at which both mechanisms need the same
    /// load, `w / (2h)`.
    pub fn critical_friction(&self) -> f64 {
        self.width / (2.0 * self.height)
    }

    /// The mechanism of the smaller load (tipping at a tie).
    pub fn mechanism(&self) -> BlockMechanism {
        if self.friction >= self.critical_friction() {
            BlockMechanism::Tipping
        } else {
            BlockMechanism::Sliding
        }
    }

    /// The limit load `W min(μ, w/2h)`.
    pub fn limit_load(&self) -> f64 {
        self.tipping_load().min(self.sliding_load())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed form is the minimum over the spins of the upper-bound
    /// function `μ|1 + ωh| + |ω| w/2`, sampled densely.
    #[test]
    fn closed_form_is_the_least_upper_bound_over_spins() {
        for friction in [0.1, 0.2, 0.25, 0.4, 1.0] {
            let block = BlockOnFloor {
                width: 0.4,
                height: 0.8,
                weight: 3.0,
                friction,
            };
            let h = block.height;
            let least = (-4000..=4000)
                .map(|k| k as f64 / 1000.0 / h)
                .map(|w| friction * (1.0 + w * h).abs() + w.abs() * block.width / 2.0)
                .fold(f64::INFINITY, f64::min)
                * block.weight;
            assert!((least - block.limit_load()).abs() < 1e-12, "{friction}");
        }
    }
}
