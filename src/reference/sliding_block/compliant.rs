//! The compliant sliding block: an elastic–perfectly-plastic shear spring
//! between block and base.

use super::{first_positive, segment_at, Shaking};

/// Exact relative displacement `s = u_block − u_base` of a rigid block of
/// mass `m` on a rigid base shaken by `shaking`, joined to it by an
/// elastic–perfectly-plastic shear spring: stiffness `k` with the elastic
/// part `y = s − s_p` and the Coulomb limit `k |y| ≤ μ m g`. `omega_c` is
/// the contact's natural frequency `Ω = √(k/m)`; the rigid solution
/// ([`super::rigid_sliding_block`]) is its limit `Ω → ∞`.
///
/// With `a₀ = A ω²` and `r = μ g`, the block's equation `m ü = −k y` with
/// `u = u_b + s` reads `s̈ = −Ω² y + a₀ sin ωt`. Event-driven, in closed
/// form:
/// * stick (`ṡ_p = 0`): `y = C₁ cos Ω(t−t₀) + C₂ sin Ω(t−t₀) + a₀ sin ωt /
///   (Ω² − ω²)` (undamped; `Ω ≠ ω`), until `|y|` reaches `r/Ω²`
///   (located on a grid of 1/64 of the shorter period and bisected);
/// * slip (`y = σ r/Ω²`, `σ = sgn ṡ`): `s̈ = −σ r + a₀ sin ωt` as in the
///   rigid case, from the velocity the spring gave the block, until `ṡ = 0`.
///
/// The block starts at rest relative to the base with the spring unloaded.
pub fn compliant_sliding_block(
    shaking: &Shaking,
    mu: f64,
    g: f64,
    omega_c: f64,
    times: &[f64],
) -> Vec<f64> {
    #[derive(Clone, Copy)]
    enum Phase {
        // (s_p, C₁, C₂)
        Stick(f64, f64, f64),
        // (s₀, ṡ₀, σ)
        Slip(f64, f64, f64),
    }
    let (w, big) = (shaking.omega(), omega_c);
    let a0 = shaking.amplitude * w * w;
    let r = mu * g;
    let limit = r / (big * big);
    let k = a0 / (big * big - w * w);
    let stick_y = |t0: f64, c: (f64, f64), t: f64| {
        let tau = big * (t - t0);
        c.0 * tau.cos() + c.1 * tau.sin() + k * (w * t).sin()
    };
    let stick_v = |t0: f64, c: (f64, f64), t: f64| {
        let tau = big * (t - t0);
        big * (c.1 * tau.cos() - c.0 * tau.sin()) + k * w * (w * t).cos()
    };
    let slip_v = |t0: f64, v0: f64, sigma: f64, t: f64| {
        v0 - sigma * r * (t - t0) - a0 / w * ((w * t).cos() - (w * t0).cos())
    };
    let slip_s = |t0: f64, s0: f64, v0: f64, sigma: f64, t: f64| {
        s0 + (v0 + a0 / w * (w * t0).cos()) * (t - t0)
            - 0.5 * sigma * r * (t - t0) * (t - t0)
            - a0 / (w * w) * ((w * t).sin() - (w * t0).sin())
    };
    // Stick constants from y and ẏ at t0.
    let constants =
        |t0: f64, y0: f64, v0: f64| (y0 - k * (w * t0).sin(), (v0 - k * w * (w * t0).cos()) / big);
    let h = std::f64::consts::TAU / big.max(w) / 64.0;
    let t_end = times.iter().copied().fold(0.0, f64::max) + 1e-9;
    let (c1, c2) = constants(0.0, 0.0, 0.0);
    let mut segments = vec![(0.0, Phase::Stick(0.0, c1, c2))];
    loop {
        let (t0, phase) = segments[segments.len() - 1];
        let next = match phase {
            Phase::Stick(sp, c1, c2) => {
                first_positive(|t| stick_y(t0, (c1, c2), t).abs() - limit, t0, h, t_end).map(|t| {
                    let y = stick_y(t0, (c1, c2), t);
                    let v = stick_v(t0, (c1, c2), t);
                    (t, Phase::Slip(sp + y, v, y.signum()))
                })
            }
            Phase::Slip(s0, v0, sigma) => {
                first_positive(|t| -sigma * slip_v(t0, v0, sigma, t), t0, h, t_end).map(|t| {
                    let y = sigma * limit;
                    let (c1, c2) = constants(t, y, 0.0);
                    (t, Phase::Stick(slip_s(t0, s0, v0, sigma, t) - y, c1, c2))
                })
            }
        };
        match next {
            Some(seg) => segments.push(seg),
            None => break,
        }
    }
    times
        .iter()
        .map(|&tq| {
            let (t0, phase) = segments[segment_at(&segments, |seg| seg.0, tq)];
            match phase {
                Phase::Stick(sp, c1, c2) => sp + stick_y(t0, (c1, c2), tq),
                Phase::Slip(s0, v0, sigma) => slip_s(t0, s0, v0, sigma, tq),
            }
        })
        .collect()
}
