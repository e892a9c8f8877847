//! A block on a horizontal base shaken by `u_b(t) = A sin ωt`, held by
//! Coulomb friction `μ` under gravity `g`: the relative displacement
//! `s = u_block − u_base` in closed form, event by event (stick, slip).
//!
//! * [`rigid_sliding_block`]: rigid block on a rigid base (Newmark 1965,
//!   *Effects of earthquakes on dams and embankments*): in slip
//!   `s̈ = −σ μ g + A ω² sin ωt` with `σ = sgn ṡ`; the block sticks while
//!   `|A ω² sin ωt| ≤ μ g`.
//! * [`compliant_sliding_block`]: the same block joined to the base by an
//!   elastic–perfectly-plastic shear spring of natural frequency
//!   `Ω = √(k/m)`, whose limit `Ω → ∞` is the rigid solution. It is the
//!   exact answer of a penalty method (DDA, paper 003 §3.(2)) whose
//!   contacts have the shear stiffness `k`.
//!
//! * [`brute_force_sliding`]: the rigid block by 1 µs explicit steps, an
//!   independent check of both.
//!
//! All start at rest relative to the base.

mod brute_force;
mod compliant;
mod rigid;

pub use brute_force::brute_force_sliding;
pub use compliant::compliant_sliding_block;
pub use rigid::rigid_sliding_block;

/// The horizontal base shaking `u_b(t) = A sin(2π f t)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shaking {
    /// Amplitude A (m).
    pub amplitude: f64,
    /// Frequency f (Hz).
    pub frequency: f64,
    /// Duration (s).
    pub duration: f64,
}

impl Shaking {
    /// Circular frequency ω = 2π f.
    pub fn omega(&self) -> f64 {
        std::f64::consts::TAU * self.frequency
    }

    /// `cycles` cycles at `frequency` (Hz) with the peak base acceleration
    /// `A ω² = peak` (m/s²): the amplitude is `peak / ω²`. At a fixed
    /// `peak / (μ g)` the rigid solution is the same curve in the phase
    /// `ωt`, scaled by `A` (Newmark 1965).
    pub fn with_peak_acceleration(peak: f64, frequency: f64, cycles: f64) -> Self {
        let w = std::f64::consts::TAU * frequency;
        Self {
            amplitude: peak / (w * w),
            frequency,
            duration: cycles / frequency,
        }
    }
}

/// Index of the segment (ordered by start time `start`) that holds time `t`.
pub(super) fn segment_at<S>(segments: &[S], start: impl Fn(&S) -> f64, t: f64) -> usize {
    segments
        .partition_point(|seg| start(seg) <= t)
        .saturating_sub(1)
}

/// The first time in `(t0, t_end]` at which `f` turns positive, found on
/// a grid of spacing `h` and refined by bisection to round-off; `None` if
/// `f ≤ 0` on the whole grid.
pub(super) fn first_positive(f: impl Fn(f64) -> f64, t0: f64, h: f64, t_end: f64) -> Option<f64> {
    let mut lo = t0;
    let mut hi = t0 + h;
    while f(hi) <= 0.0 {
        if hi >= t_end {
            return None;
        }
        lo = hi;
        hi += h;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
        if hi - lo < 1e-15 * (1.0 + hi) {
            break;
        }
    }
    Some(hi)
}
