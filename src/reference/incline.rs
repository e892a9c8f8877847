//! A rigid block on an inclined plane with Coulomb friction: from rest it
//! slides down the slope with the constant acceleration
//! `a = g (sin β − μ cos β)` when `tan β > μ`, and stays at rest otherwise
//! (the friction needed, `W sin β`, is then within `μ W cos β`).

/// A rigid block's acceleration down a slope of angle `slope` (rad) with
/// friction coefficient `friction` under gravity `gravity`:
/// `g (sin β − μ cos β)` when positive, otherwise 0 (it sticks).
pub fn sliding_acceleration(gravity: f64, slope: f64, friction: f64) -> f64 {
    (gravity * (slope.sin() - friction * slope.cos())).max(0.0)
}
