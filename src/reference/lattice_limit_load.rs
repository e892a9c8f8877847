//! Closed forms of paper 002 (Yamada & Tamura 2000) for the lattices of
//! [`crate::limit::lattice`]: the limit loads of the U-model with and
//! without rolling (eqs. 32, 38) and the global cohesion of the L-model
//! (eq. 20), in units of the contact strength `C_p` (R = 1).
//!
//! Eq. (38) and eq. (20) are exact for their lattices; eq. (32) is the
//! paper's inductive solution, which the LP meets where Table 1 agrees with
//! it and undercuts elsewhere (e.g. k = 8, n' = 2).

/// Eq. (32): the paper's inductive solution for the rolling U-model,
/// `P/C_p = 1 + √2 (2(k/2)² − 2n'² + 4n' − 3) / (k/2 − n' + 1)`.
pub fn eq32(k: usize, loaded: usize) -> f64 {
    let (h, p) = (k as f64 / 2.0, loaded as f64);
    1.0 + std::f64::consts::SQRT_2 * (2.0 * h * h - 2.0 * p * p + 4.0 * p - 3.0) / (h - p + 1.0)
}

/// Eq. (38): the non-rolling U-model, `P/C_p = (2k − 2)√2 + 6n' − 4`.
pub fn eq38(k: usize, loaded: usize) -> f64 {
    (2.0 * k as f64 - 2.0) * std::f64::consts::SQRT_2 + 6.0 * loaded as f64 - 4.0
}

/// Eq. (20): the global cohesion of the L-model, `c_G R / C_p`, α = 45°.
pub fn eq20(m: usize) -> f64 {
    let (c, s2) = (std::f64::consts::FRAC_PI_4.cos(), 0.5);
    let m = m as f64;
    if m <= 2.0 {
        (1.0 + c) / (4.0 * s2)
    } else if m <= 4.0 {
        (3.0 + c) / (12.0 * s2)
    } else {
        (m + c - 1.0) / (4.0 * (m - 1.0) * s2)
    }
}
