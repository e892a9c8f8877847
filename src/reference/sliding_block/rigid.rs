//! The rigid sliding block (Newmark 1965).

use super::{first_positive, segment_at, Shaking};

/// Exact relative displacement `s = u_block − u_base` of a rigid block on a
/// rigid base shaken by `shaking`, with friction coefficient `mu` and
/// gravity `g` (Newmark 1965), at the given times. The block starts at
/// rest relative to the base. Event-driven: in slip (`σ = sgn ṡ`),
/// `s̈ = −σ μ g + A ω² sin ωt` is integrated in closed form, the end of slip
/// (`ṡ = 0`) is located by bracketing and bisection, and a stick phase ends
/// in closed form when `|A ω² sin ωt|` exceeds `μ g`.
pub fn rigid_sliding_block(shaking: &Shaking, mu: f64, g: f64, times: &[f64]) -> Vec<f64> {
    let (a, w) = (shaking.amplitude, shaking.omega());
    let r = mu * g;
    let aw2 = a * w * w;
    // Segments (t0, s0, sd0, sigma); sigma = 0 for stick.
    let mut segments: Vec<(f64, f64, f64, f64)> = Vec::new();
    let t_end = times.iter().copied().fold(0.0, f64::max) + 1e-9;
    let velocity = |t0: f64, sd0: f64, sigma: f64, t: f64| {
        sd0 - sigma * r * (t - t0) - a * w * ((w * t).cos() - (w * t0).cos())
    };
    let position = |t0: f64, s0: f64, sd0: f64, sigma: f64, t: f64| {
        s0 + (sd0 + a * w * (w * t0).cos()) * (t - t0)
            - 0.5 * sigma * r * (t - t0) * (t - t0)
            - a * ((w * t).sin() - (w * t0).sin())
    };
    let (mut t, mut s) = (0.0, 0.0);
    let mut sigma = 0.0;
    let pi = std::f64::consts::PI;
    while t < t_end {
        segments.push((t, s, 0.0, sigma));
        if sigma == 0.0 {
            if aw2 <= r {
                break;
            }
            let theta1 = (r / aw2).asin();
            let theta = (w * t).rem_euclid(pi);
            let next = if theta < theta1 {
                t + (theta1 - theta) / w
            } else if theta > pi - theta1 {
                t + (pi - theta + theta1) / w
            } else {
                t
            };
            t = next;
            sigma = (w * t).sin().signum();
            continue;
        }
        // Slip from (t, s, ṡ = 0) with sign sigma: find the first ṡ = 0.
        let h = 1.0 / (shaking.frequency * 4000.0);
        let (t0, s0) = (t, s);
        let Some(end) = first_positive(|t| -sigma * velocity(t0, 0.0, sigma, t), t0, h, t_end)
        else {
            break;
        };
        t = end;
        s = position(t0, s0, 0.0, sigma, t);
        sigma = if (aw2 * (w * t).sin()).abs() <= r {
            0.0
        } else {
            (w * t).sin().signum()
        };
    }
    times
        .iter()
        .map(|&tq| {
            let (t0, s0, sd0, sg) = segments[segment_at(&segments, |seg| seg.0, tq)];
            if sg == 0.0 {
                s0
            } else {
                position(t0, s0, sd0, sg, tq)
            }
        })
        .collect()
}
