//! A rigid block on an inclined plane with Coulomb friction: from rest it
//! slides down the slope with the constant acceleration
//! `a = g (sin β − μ cos β)` when `tan β > μ`, and stays at rest otherwise
//! (the friction needed, `W sin β`, is then within `μ W cos β`).
//!
//! A uniform disc on the same slope rolls without slipping when
//! `μ ≥ tan β / 3`: the friction `F` and the gravity give `m a = m g sin β −
//! F` and `I α = F R` with `I = m R²/2` and `a = α R`, so
//! `a = (2/3) g sin β` and `F = (1/3) m g sin β`, which needs
//! `F ≤ μ m g cos β`. Otherwise it slides and spins:
//! `a = g (sin β − μ cos β)`.

/// A rigid block's acceleration down a slope of angle `slope` (rad) with
/// friction coefficient `friction` under gravity `gravity`:
/// `g (sin β − μ cos β)` when positive, otherwise 0 (it sticks).
pub fn sliding_acceleration(gravity: f64, slope: f64, friction: f64) -> f64 {
    (gravity * (slope.sin() - friction * slope.cos())).max(0.0)
}

/// A uniform disc's centre acceleration down a slope of angle `slope` (rad)
/// with friction coefficient `friction` under gravity `gravity`:
/// `(2/3) g sin β` when it rolls (`μ ≥ tan β / 3`), otherwise
/// `g (sin β − μ cos β)`.
pub fn disc_acceleration(gravity: f64, slope: f64, friction: f64) -> f64 {
    if friction >= slope.tan() / 3.0 {
        2.0 / 3.0 * gravity * slope.sin()
    } else {
        sliding_acceleration(gravity, slope, friction)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// At `μ = tan β / 3` the rolling disc and the slipping disc have the
    /// same acceleration: the two regimes meet.
    #[test]
    fn rolling_and_slipping_meet_at_the_critical_friction() {
        let (g, beta) = (9.81, 0.6f64);
        let critical = beta.tan() / 3.0;
        let rolling = disc_acceleration(g, beta, critical);
        approx::assert_relative_eq!(rolling, 2.0 / 3.0 * g * beta.sin(), epsilon = 1e-12);
        approx::assert_relative_eq!(
            rolling,
            sliding_acceleration(g, beta, critical),
            epsilon = 1e-12
        );
        assert!(disc_acceleration(g, beta, 0.5 * critical) > rolling);
    }
}
