//! Where the explicit driver's steps spend their time: the breakdown a
//! LAMMPS or LIGGGHTS run prints at its end ("Pair", "Neigh", "Modify"…),
//! for finding what does not scale with the threads.

use std::cell::Cell;
use std::fmt;
use std::time::{Duration, Instant};

/// The wall-clock time of the explicit driver's steps by phase, summed
/// since [`super::ExplicitDynamics::time_phases`] was called (taken only
/// then: four clock readings a step).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PhaseTimes {
    /// Steps timed.
    pub steps: u64,
    /// Builds of the neighbour list among them.
    pub builds: u64,
    /// Building the neighbour list (cell grid, candidate pairs, the
    /// list's slots and indices), at the steps that build it.
    pub build: Duration,
    /// The contact forces: every listed pair's query and law, summed per
    /// particle block.
    pub forces: Duration,
    /// The pairs that cross blocks added to their second particle, and
    /// every particle moved by the integrator.
    pub motion: Duration,
    /// Whether the list still holds every pair that can meet (the travel
    /// since the build).
    pub travel: Duration,
}

impl PhaseTimes {
    /// The time of all phases together.
    pub fn total(&self) -> Duration {
        self.build + self.forces + self.motion + self.travel
    }

    /// The phases with their names, in the step's order.
    pub fn phases(&self) -> [(&'static str, Duration); 4] {
        [
            ("build", self.build),
            ("forces", self.forces),
            ("motion", self.motion),
            ("travel", self.travel),
        ]
    }
}

/// A table of the phases: seconds, share of the total, and microseconds a
/// step.
impl fmt::Display for PhaseTimes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let total = self.total().as_secs_f64();
        let steps = self.steps.max(1) as f64;
        writeln!(
            f,
            "{} steps, {} list builds: {total:.4} s",
            self.steps, self.builds
        )?;
        writeln!(f, "phase    seconds     share   µs/step")?;
        for (name, time) in self.phases() {
            let s = time.as_secs_f64();
            let share = if total > 0.0 { 100.0 * s / total } else { 0.0 };
            writeln!(
                f,
                "{name:<8} {s:>9.4} {share:>8.1} % {:>9.2}",
                1e6 * s / steps
            )?;
        }
        Ok(())
    }
}

/// The laps of one step's phases: a clock read at each phase's end, or
/// never when the steps are not timed.
pub(super) struct PhaseClock {
    last: Cell<Option<Instant>>,
}

impl PhaseClock {
    /// A clock started now when `on`, else one that reads nothing.
    pub fn start(on: bool) -> Self {
        Self {
            last: Cell::new(on.then(Instant::now)),
        }
    }

    /// The time since the last lap (or the start); `None` when off.
    pub fn lap(&self) -> Option<Duration> {
        let last = self.last.get()?;
        let now = Instant::now();
        self.last.set(Some(now));
        Some(now - last)
    }
}
