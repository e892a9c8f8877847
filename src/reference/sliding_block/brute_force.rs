//! The rigid sliding block by brute force: an independent check of the
//! event-by-event solution ([`super::rigid_sliding_block`]) and of methods
//! that follow it.

use super::Shaking;

/// The rigid sliding block (Newmark 1965) by explicit steps of 1 µs, with
/// stick when the relative velocity changes sign and the drive stays below
/// `μ g`. Returns the times `k · 1e-3 s` (k = 1, 2, …) and the relative
/// displacement at each.
pub fn brute_force_sliding(shaking: &Shaking, mu: f64, g: f64) -> (Vec<f64>, Vec<f64>) {
    let (a, w) = (shaking.amplitude, shaking.omega());
    let h = 1e-6;
    let steps = (shaking.duration / h).round() as usize;
    let (mut s, mut v) = (0.0f64, 0.0f64);
    let mut times = Vec::new();
    let mut brute = Vec::new();
    for k in 0..steps {
        let t = k as f64 * h;
        let drive = a * w * w * (w * t).sin();
        let accel = if v != 0.0 {
            drive - v.signum() * mu * g
        } else if drive.abs() > mu * g {
            drive - drive.signum() * mu * g
        } else {
            0.0
        };
        let v_new = v + h * accel;
        v = if v != 0.0 && v_new * v < 0.0 {
            0.0
        } else {
            v_new
        };
        s += h * v;
        if (k + 1) % 1000 == 0 {
            times.push((k + 1) as f64 * h);
            brute.push(s);
        }
    }
    (times, brute)
}
