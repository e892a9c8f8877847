//! Settings of an implicit run, validated when the driver is built.

use crate::error::{require_positive, DismechError, Result};
use crate::math::Vec2;

/// The smallest [`ImplicitSettings::min_dt_ratio`] accepted, 2⁻⁵²: a step
/// is halved at most 52 times (a smaller sub-step is below the rounding
/// of the step itself).
pub const MIN_DT_RATIO_FLOOR: f64 = f64::EPSILON;

/// Where the iteration of a step starts for the free unknowns.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub enum Predictor {
    /// The constant-acceleration motion for the bodies that ended the last
    /// step without a closed contact (free flight, where it is exact), and
    /// the start-of-step configuration for the others. A body resting in
    /// stiff contact has an end-of-step acceleration dominated by the
    /// contact modes, which paper 003's Newmark (β = ½, γ = 1) does not damp
    /// (its spectral radius tends to 1 as ωΔt grows): extrapolated, that
    /// acceleration throws the start of the iteration far from the step's
    /// solution, every step (a settled wall of 100 bricks at 1 ms: ten
    /// linear solves a step from constant acceleration, one from here).
    #[default]
    FreeFlight,
    /// The motion at constant acceleration, `Δd = Δt v₀ + ½ Δt² a₀`, for
    /// every body (classic DDA's start).
    ConstantAcceleration,
    /// The start-of-step configuration, `Δd = 0`: the contacts start in
    /// the states they ended the last step in. Free flight is linear in the
    /// increments, so it converges in one Newton iteration unless the
    /// update moves a boundary point further than the search distance (a
    /// Newton update is scaled down to that, so a body flying further needs
    /// one iteration per search distance).
    StartOfStep,
}

/// Settings of the implicit driver (open–close, Newton, Δt control).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ImplicitSettings {
    /// Gravity (m/s²).
    pub gravity: Vec2,
    /// Search distance `d₀` of contact detection (m): pairs closer than this
    /// at the start of a step are contacts of the step.
    pub search_distance: f64,
    /// Largest search distance a step may use (m), at least
    /// `search_distance`. A trial step whose boundary point moves further
    /// than the step's search distance relative to a body it could reach
    /// would miss contacts; with room above `search_distance` the step is
    /// then detected again at a search distance that covers the motion (up
    /// to this) and repeated at the same size rather than halved, and the
    /// next step starts from the search distance the last motion needed
    /// (never below `search_distance`). Equal to `search_distance` (the
    /// default) the search distance is fixed and a fast step is halved.
    /// `None` takes `search_distance`.
    pub max_search_distance: Option<f64>,
    /// Largest penetration accepted at the start (m).
    pub overlap_tolerance: f64,
    /// Most open–close iterations per step (60 by default). Where courses
    /// of a wall land on each other, a step's contacts close a few at a
    /// time over tens of iterations while the residual keeps falling; with
    /// 20, the settling wall of 1 600 bricks of `benches/dda_blocks.rs`
    /// (penalty E × 1 m) halved 18 steps after the tenth, with 60 it
    /// halves 3, and the 400-brick wall none (5 before). A step that
    /// truly cycles costs up to this many iterations before it is halved.
    pub max_open_close: usize,
    /// Most Newton iterations per step once the contact states settled.
    pub max_newton: usize,
    /// Relative residual tolerance of Newton: `‖R‖ ≤ tol · scale`, the
    /// scale being the largest load or contact force. Where the residual's
    /// round-off is larger (a very stiff penalty), Newton stops at 100 times
    /// that round-off instead.
    pub residual_tolerance: f64,
    /// Smallest step, as a fraction of the requested one (e.g. 1/64; at
    /// least [`MIN_DT_RATIO_FLOOR`]).
    pub min_dt_ratio: f64,
    /// Where each step's iteration starts.
    pub predictor: Predictor,
    /// Fraction of a slipping contact's normal stiffness added to its
    /// shear stiffness in Newton's matrix (not in the residual, so the
    /// converged state is the same). The consistent tangent of a
    /// slipping contact has no shear stiffness; without inertia
    /// ([`crate::integrate::QuasiStatic`]) a disc whose every contact
    /// slips may then turn freely and the matrix is singular. Zero keeps
    /// the exact consistent tangent (Newton's quadratic convergence).
    pub slip_regularization: f64,
    /// Where a Newton update stops for the contacts whose slip would
    /// reverse a second time (consistent laws; see the
    /// [module documentation](super)): each such contact sticks at some
    /// fraction of the update, and the update is stopped at this quantile
    /// of those fractions. 0 stops it where the first one sticks, so that
    /// none jumps across its stick band; on a wall of hundreds of such
    /// contacts that one contact shortens the update of every block. With
    /// 0.2 (the default) the update stops where a fifth of them have
    /// stuck: those may jump across their band and are stopped at a later
    /// update; the other four in five have not reached theirs. Where fewer
    /// than five contacts would reverse, ⌊0.2 n⌋ = 0 and the update stops
    /// at the first stick point, as with 0. Measured over the whole of
    /// `benches/dda_blocks.rs` (return mapping, 50 steps of 1 ms, every
    /// size, state and penalty; linear solves a step; halvings, and those
    /// after the tenth step), 0.2 against 0:
    ///
    /// | bricks | state | penalty | 0 | 0.2 |
    /// |---|---|---|---|---|
    /// | 101 | touching | E × 1 m | 1.5; 0 | 1.54; 0 |
    /// | 101 | touching | 10 E | 1.8; 0 | 1.72; 0 |
    /// | 101 | settling | E × 1 m | 3.6; 0 | 3.52; 0 |
    /// | 101 | settling | 10 E | 10.4; 2 (0) | 10.00; 2 (0) |
    /// | 399 | touching | E × 1 m | 2.8; 0 | 2.78; 0 |
    /// | 399 | touching | 10 E | 3.6; 0 | 3.46; 0 |
    /// | 399 | settling | E × 1 m | 8.0; 0 | 7.06; 0 |
    /// | 399 | settling | 10 E | 33.2; 8 (6) | 24.20; 4 (2) |
    /// | 1 610 | touching | E × 1 m | 6.1; 0 | 6.12; 0 |
    /// | 1 610 | touching | 10 E | 18.1; 5 (3) | 15.10; 2 (2) |
    /// | 1 610 | settling | E × 1 m | 24.3; 3 (3) | 18.56; 0 |
    /// | 1 610 | settling | 10 E | 126.8; 52 (51) | 79.02; 25 (24) |
    ///
    /// No row takes more than 0.04 solves a step more; the four hardest
    /// lose 17–38 % of their solves and half or all of their halvings.
    /// It must lie in [0, 1).
    pub slip_reversal_quantile: f64,
    /// Mass-proportional (Rayleigh) damping `α` (1/s): a force `−α M v`
    /// on every body, with `v` the end-of-step velocity of the integrator.
    /// It damps every motion at the rate `α/2`, rigid ones included (a
    /// body falling freely reaches `g/α`), and vanishes at rest, so it
    /// changes the path to a static state but not the state. Zero (the
    /// default) adds none.
    pub mass_damping: f64,
}

impl Default for ImplicitSettings {
    fn default() -> Self {
        Self {
            gravity: Vec2::new(0.0, -9.8),
            search_distance: 0.01,
            max_search_distance: None,
            overlap_tolerance: 1e-6,
            max_open_close: 60,
            max_newton: 20,
            residual_tolerance: 1e-10,
            min_dt_ratio: 1.0 / 64.0,
            predictor: Predictor::default(),
            slip_regularization: 0.0,
            slip_reversal_quantile: 0.2,
            mass_damping: 0.0,
        }
    }
}

impl ImplicitSettings {
    /// The largest search distance a step may use (m).
    pub fn largest_search_distance(&self) -> f64 {
        self.max_search_distance
            .unwrap_or(self.search_distance)
            .max(self.search_distance)
    }

    /// Check every value.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming the value for a
    /// `search_distance`, `overlap_tolerance` or `residual_tolerance` that
    /// is not finite and positive, a `max_search_distance` that is not
    /// finite or below `search_distance`, a `slip_regularization` or
    /// `mass_damping` that is negative or not finite, a
    /// `slip_reversal_quantile` outside `[0, 1)`, a `min_dt_ratio`
    /// outside `[2⁻⁵², 1]`, or a `gravity` that is not finite.
    pub fn validate(&self) -> Result<()> {
        require_positive("search distance d0", self.search_distance)?;
        require_positive("overlap tolerance", self.overlap_tolerance)?;
        if let Some(max) = self.max_search_distance {
            if !(max.is_finite() && max >= self.search_distance) {
                return Err(DismechError::InvalidParameter {
                    name: "max_search_distance",
                    value: max,
                    requirement: "must be finite and at least search_distance",
                });
            }
        }
        require_positive("residual tolerance", self.residual_tolerance)?;
        crate::error::require_non_negative("slip regularization", self.slip_regularization)?;
        crate::error::require_non_negative("mass damping", self.mass_damping)?;
        if !(self.slip_reversal_quantile >= 0.0 && self.slip_reversal_quantile < 1.0) {
            return Err(DismechError::InvalidParameter {
                name: "slip_reversal_quantile",
                value: self.slip_reversal_quantile,
                requirement: "must lie in [0, 1)",
            });
        }
        if !(self.min_dt_ratio >= MIN_DT_RATIO_FLOOR && self.min_dt_ratio <= 1.0) {
            return Err(DismechError::InvalidParameter {
                name: "min_dt_ratio",
                value: self.min_dt_ratio,
                requirement: "must lie in [2^-52, 1] (at most 52 halvings of a step)",
            });
        }
        if !(self.gravity.x.is_finite() && self.gravity.y.is_finite()) {
            return Err(DismechError::InvalidParameter {
                name: "gravity",
                value: self.gravity.norm(),
                requirement: "must be finite",
            });
        }
        Ok(())
    }
}
