//! Observers: one interface through which a driver's run is watched —
//! progress, output files, checkpoints, a user's own callback — instead
//! of code inside the drivers.
//!
//! A driver's observed run takes the observer by `&mut` (so that it is
//! the caller's again after the run) and calls [`Observer::observe`] with
//! itself (read,
//! not copied: every accessor of the driver is at hand) and an [`Event`]
//! saying what just happened. An observer returns `Ok(())` to go on, or an
//! error, which stops the run and is returned by it (an output that could
//! not be written stops the run that would write it).
//!
//! An implicit driver's checkpoint ([`crate::checkpoint`]) belongs after a
//! call of `advance` returns (or at its [`Event::Finished`]): taken at an
//! [`Event::SubStep`] inside a call, it holds the sub-step's state but not
//! the rest of the call's interval and its step control, so a run resumed
//! from it does not end in the same bits.
//!
//! Observers compose: a closure `FnMut(&W, &Event) -> Result<()>` is one;
//! a pair `(A, B)` calls both in order; [`every`] calls its observer at
//! every n-th step and at every other event. The frames of [`crate::vtk`]
//! are written by an observer ([`crate::vtk::DemFrames`]):
//!
//! ```
//! # fn main() -> dismech::error::Result<()> {
//! use dismech::dem::DemSimulation;
//! use dismech::explicit::{DemSettings, RestCriterion};
//! use dismech::integrate::ExplicitEuler;
//! use dismech::law::SpringDashpotCoulomb;
//! use dismech::math::{Point, Vec2};
//! use dismech::observe::{every, Event};
//! use dismech::scene::{Frame, Scene};
//! let mut scene = Scene::new(Frame::open_box(1.0, 1.0)?, Vec2::new(0.0, -9.81))?;
//! scene.add_circle(Point::new(0.5, 0.06), 0.05, 2600.0)?;
//! let law = SpringDashpotCoulomb::katsuki(73.55e6, 0.3, 0.25, 0.577)?;
//! let mut dem = DemSimulation::new(scene, law, ExplicitEuler, DemSettings::default())?;
//! let mut heights = Vec::new();
//! let record = every(100, |dem: &DemSimulation<SpringDashpotCoulomb>, event: &Event<'_>| {
//!     if let Event::Step { .. } = event {
//!         heights.push(dem.scene().particles[0].pose.position.y);
//!     }
//!     Ok(())
//! });
//! let mut record = record;
//! let outcome = dem.run_to_rest_observed(&RestCriterion::default(), &mut record)?;
//! assert_eq!(heights.len() as u64, outcome.steps / 100);
//! # Ok(()) }
//! ```
//!
//! | driver | observed run | events |
//! |---|---|---|
//! | explicit ([`crate::explicit::ExplicitDynamics`]) | [`run_to_rest_observed`](crate::explicit::ExplicitDynamics::run_to_rest_observed), [`run_steps_observed`](crate::explicit::ExplicitDynamics::run_steps_observed) | [`Event::Step`] after every step, [`Event::Check`] at every rest check, [`Event::Finished`] |
//! | implicit ([`crate::implicit::ImplicitDynamics`], DDA) | [`advance_observed`](crate::implicit::ImplicitDynamics::advance_observed) | [`Event::SubStep`] after every accepted sub-step, [`Event::Halved`] with the failure at every halving, [`Event::Finished`] at the end of the interval |
//! | HPM ([`crate::hpm::HpmSolver`]), read as a [`crate::hpm::HpmIterate`] | [`nonlinear_observed`](crate::hpm::HpmSolver::nonlinear_observed), [`strength_reduction_observed`](crate::hpm::strength_reduction_observed) | [`Event::Iteration`] at every iterate of the nonlinear solve; [`Event::Trial`] after each factor of the strength reduction |
//!
//! The limit analysis is one call of its LP solver, with no steps to
//! observe. An elastic HPM analysis is one linear solve.

use crate::error::Result;

/// What just happened in an observed run. More kinds of event may come
/// (a match on it needs a `_` arm).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Event<'a> {
    /// A step was taken: the driver's step count and time after it.
    Step {
        /// Steps taken since the driver was built.
        step: u64,
        /// Time reached (s).
        time: f64,
    },
    /// A check of a run to rest (every
    /// [`crate::explicit::RestCriterion::check_every`] steps), with the
    /// ratio its rest test reads (kinetic to supplied energy).
    Check {
        /// Time reached (s).
        time: f64,
        /// Kinetic energy over the energy supplied.
        rest_ratio: f64,
    },
    /// A sub-step of the implicit driver was accepted (its equations
    /// solved and its state committed).
    SubStep {
        /// Sub-steps accepted so far in this call of
        /// [`crate::implicit::ImplicitDynamics::advance_observed`].
        substep: usize,
        /// Time reached (s).
        time: f64,
        /// The sub-step's size (s).
        dt: f64,
    },
    /// A trial sub-step of the implicit driver failed and is halved: what
    /// failed, and the size it is tried at next.
    Halved {
        /// Time of the state it starts from (s).
        time: f64,
        /// The size that failed (s).
        dt: f64,
        /// Why.
        reason: &'a crate::implicit::StepFailure,
    },
    /// An iterate of an iterative analysis was evaluated (HPM's nonlinear
    /// solve, [`crate::hpm::HpmSolver::nonlinear_observed`]): its number,
    /// 0 for the start, its relative out-of-balance force, and whether it
    /// is the iterate the analysis returns (converged, at its iteration
    /// limit, or not finite).
    Iteration {
        /// Corrections applied so far.
        iteration: usize,
        /// `‖F − F_int(U)‖ / ‖F‖` at the iterate.
        residual: f64,
        /// Whether the analysis stops at this iterate.
        last: bool,
    },
    /// A trial of a search ended (a factor of HPM's strength reduction,
    /// [`crate::hpm::strength_reduction_observed`]): the factor tried and
    /// whether its analysis found equilibrium.
    Trial {
        /// The factor tried.
        factor: f64,
        /// Whether the analysis at it converged.
        converged: bool,
    },
    /// The run ended (at rest, or at a limit; for the implicit driver, the
    /// interval of the call was integrated); not sent when it stops with
    /// an error.
    Finished {
        /// Steps taken since the driver was built (the explicit driver),
        /// or sub-steps accepted in the call (the implicit driver).
        step: u64,
        /// Time reached (s).
        time: f64,
    },
}

/// Watches a run of a driver `W`.
pub trait Observer<W: ?Sized> {
    /// Called at each event with the driver as it is after it.
    ///
    /// # Errors
    /// Whatever the observer cannot do (an output not written); the run
    /// stops and returns it.
    fn observe(&mut self, world: &W, event: &Event<'_>) -> Result<()>;
}

impl<W: ?Sized, F> Observer<W> for F
where
    F: FnMut(&W, &Event<'_>) -> Result<()>,
{
    fn observe(&mut self, world: &W, event: &Event<'_>) -> Result<()> {
        self(world, event)
    }
}

impl<W: ?Sized, A: Observer<W>, B: Observer<W>> Observer<W> for (A, B) {
    fn observe(&mut self, world: &W, event: &Event<'_>) -> Result<()> {
        self.0.observe(world, event)?;
        self.1.observe(world, event)
    }
}

/// No observer: an observed run without one.
#[derive(Debug, Clone, Copy, Default)]
pub struct Unobserved;

impl<W: ?Sized> Observer<W> for Unobserved {
    fn observe(&mut self, _: &W, _: &Event<'_>) -> Result<()> {
        Ok(())
    }
}

/// An observer called at every `n`-th [`Event::Step`] (steps `n`, `2n`,
/// … of the driver's count), at every `n`-th [`Event::Iteration`] (by its
/// number: 0, `n`, `2n`, …) and at the last, at every `n`-th [`Event::SubStep`] it is told
/// of (counted across the calls it observes, so that `every(5, o)` over
/// calls of one sub-step each sees every fifth), and at every other event.
#[derive(Debug, Clone)]
pub struct Every<O> {
    n: u64,
    substeps: u64,
    observer: O,
}

/// `observer` at every `n`-th step (every step for `n` = 0 or 1) and at
/// every other event.
pub fn every<O>(n: u64, observer: O) -> Every<O> {
    Every {
        n: n.max(1),
        substeps: 0,
        observer,
    }
}

impl<O> Every<O> {
    /// The observer, back from the run.
    pub fn into_inner(self) -> O {
        self.observer
    }
}

impl<W: ?Sized, O: Observer<W>> Observer<W> for Every<O> {
    fn observe(&mut self, world: &W, event: &Event<'_>) -> Result<()> {
        match event {
            Event::Step { step, .. } if step % self.n != 0 => Ok(()),
            Event::Iteration {
                iteration, last, ..
            } if !*last && (*iteration as u64) % self.n != 0 => Ok(()),
            Event::SubStep { .. } => {
                self.substeps += 1;
                if self.substeps % self.n == 0 {
                    self.observer.observe(world, event)
                } else {
                    Ok(())
                }
            }
            _ => self.observer.observe(world, event),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_passes_every_nth_step_and_every_other_event() {
        let mut seen = Vec::new();
        let mut o = every(3, |_: &(), e: &Event<'_>| {
            seen.push(format!("{e:?}"));
            Ok(())
        });
        for step in 1..=7 {
            o.observe(&(), &Event::Step { step, time: 0.0 }).unwrap();
        }
        o.observe(&(), &Event::Finished { step: 7, time: 0.0 })
            .unwrap();
        assert_eq!(seen.len(), 3);
        assert!(seen[0].starts_with("Step { step: 3,"), "{seen:?}");
        assert!(seen[1].starts_with("Step { step: 6,"), "{seen:?}");
        assert!(seen[2].starts_with("Finished"), "{seen:?}");
    }

    #[test]
    fn every_passes_every_nth_iteration_and_the_last() {
        let mut seen = Vec::new();
        let mut o = every(10, |_: &(), e: &Event<'_>| {
            if let Event::Iteration { iteration, .. } = e {
                seen.push(*iteration);
            }
            Ok(())
        });
        for iteration in 0..=95 {
            let event = Event::Iteration {
                iteration,
                residual: 1.0,
                last: iteration == 95,
            };
            o.observe(&(), &event).unwrap();
        }
        assert_eq!(seen, [0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 95]);
    }

    #[test]
    fn a_pair_calls_both_and_stops_at_the_first_error() {
        let mut calls = 0;
        let mut failing = (
            |_: &(), _: &Event| -> Result<()> {
                Err(crate::error::DismechError::InvalidParameter {
                    name: "test",
                    value: 0.0,
                    requirement: "none",
                })
            },
            |_: &(), _: &Event| -> Result<()> {
                calls += 1;
                Ok(())
            },
        );
        assert!(failing
            .observe(&(), &Event::Step { step: 1, time: 0.0 })
            .is_err());
        assert_eq!(calls, 0);
    }
}
