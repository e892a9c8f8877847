//! What a step of the implicit driver reports: why a step failed, its iterations, and the contacts of the accepted state.

use crate::error::{DismechError, SolveError};
use crate::math::{Point, Vec2};
use crate::query::variation::VariationError;
use crate::query::ContactFeatures;

/// What made a step fail.
#[derive(Debug, Clone, PartialEq)]
pub enum StepFailure {
    /// The open/closed states kept changing.
    OpenCloseNotSettled {
        /// Iterations made.
        iterations: usize,
    },
    /// Newton did not reach the tolerance.
    NewtonNotConverged {
        /// Iterations made.
        iterations: usize,
        /// Last relative residual.
        residual: f64,
        /// The tolerance it was to reach (the settings' one, or the
        /// residual's round-off where that was larger).
        tolerance: f64,
    },
    /// The linear solve failed (a singular tangent), or its pattern could
    /// not be laid out.
    Solve(SolveError),
    /// The residual of the step's equations is not finite (a body's motion
    /// or a contact force overflowed).
    NonFiniteResidual,
    /// A point of a body moved further than the search distance relative
    /// to a neighbouring body.
    TooFast {
        /// The body.
        block: usize,
        /// Relative motion (m).
        motion: f64,
    },
    /// A body became invalid (a polygon turned inside out, an ellipse
    /// degenerated).
    Geometry(Box<DismechError>),
    /// The contact normal of a smooth pair could not be found.
    Variation(VariationError),
    /// A law without a consistent tangent settled its contact states, but
    /// the step's equations hold only to a residual no step of classic DDA
    /// should leave (a penalty too stiff for double precision).
    Imprecise {
        /// Relative residual at the settled states.
        residual: f64,
        /// The largest accepted.
        limit: f64,
    },
    /// The round-off of the step's equations alone (relative to the loads)
    /// is above what a step may leave: a contact stiffness times the
    /// rounding of the bodies' motion in the contact's gap makes forces of
    /// that size, so the answer would be noise.
    RoundOff {
        /// The residual's round-off over the loads.
        floor: f64,
        /// The largest accepted.
        limit: f64,
        /// The largest normal stiffness of a contact of the step (N/m per
        /// m).
        stiffness: f64,
    },
}

impl std::fmt::Display for StepFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::OpenCloseNotSettled { iterations } => write!(f, "open-close iteration did not settle in {iterations} iterations: contacts kept opening and closing; take a smaller time step (or a smaller min_dt_ratio, so that the step may be halved further) or raise max_open_close"),
            Self::NewtonNotConverged { iterations, residual, tolerance } => {
                write!(f, "Newton-Raphson did not converge in {iterations} iterations (relative residual {residual:.3e} against the tolerance {tolerance:.1e}): ")?;
                if *residual <= 1e3 * tolerance {
                    write!(f, "it stalled near the tolerance, the sign of a penalty stiff enough that rounding limits the residual; lower the contact penalty or raise residual_tolerance")
                } else {
                    write!(f, "take a smaller time step (or a smaller min_dt_ratio, so that the step may be halved further) or raise max_newton")
                }
            }
            Self::Solve(m) => write!(f, "linear solve failed: {m}"),
            Self::NonFiniteResidual => write!(f, "the residual is not finite (a motion or a force overflowed); take a smaller time step or a softer penalty"),
            Self::TooFast { block, motion } => write!(f, "a point of body {block} moved {motion:.3e} m relative to a neighbour in one step, beyond the search distance"),
            Self::Geometry(m) => write!(f, "{m}"),
            Self::Variation(m) => write!(f, "contact geometry: {m}"),
            Self::Imprecise { residual, limit } => write!(f, "the contact states settled but the equations hold only to a relative residual {residual:.3e} (more than {limit:.1e}): the contact penalty is too stiff for double precision against the bodies' stiffness and inertia; lower the penalty"),
            Self::RoundOff { floor, limit, stiffness } => write!(f, "the round-off of the step's equations is {floor:.3e} of the loads (more than {limit:.1e}): a contact stiffness of {stiffness:.3e} N/m per m turns the rounding of the bodies' motion into forces of that size; lower the penalty to about {:.1e} or below", stiffness * limit / floor * 0.01),
        }
    }
}

/// Why the steps of an [`super::ImplicitDynamics::advance`] call were
/// halved: one count per [`StepFailure`] kind.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Halvings {
    /// [`StepFailure::OpenCloseNotSettled`].
    pub open_close: usize,
    /// [`StepFailure::NewtonNotConverged`].
    pub newton: usize,
    /// [`StepFailure::TooFast`]: a motion beyond the search distance.
    pub too_fast: usize,
    /// The others: a failed linear solve, an invalid body, a contact
    /// normal not found, an imprecise solve, round-off above the limit.
    pub other: usize,
}

impl Halvings {
    /// Count one halving caused by `failure`.
    pub fn count(&mut self, failure: &StepFailure) {
        match failure {
            StepFailure::OpenCloseNotSettled { .. } => self.open_close += 1,
            StepFailure::NewtonNotConverged { .. } => self.newton += 1,
            StepFailure::TooFast { .. } => self.too_fast += 1,
            StepFailure::Solve(_)
            | StepFailure::NonFiniteResidual
            | StepFailure::Geometry(_)
            | StepFailure::Variation(_)
            | StepFailure::Imprecise { .. }
            | StepFailure::RoundOff { .. } => self.other += 1,
        }
    }

    /// Add the counts of `other`.
    pub fn add(&mut self, other: &Halvings) {
        self.open_close += other.open_close;
        self.newton += other.newton;
        self.too_fast += other.too_fast;
        self.other += other.other;
    }

    /// All halvings.
    pub fn total(&self) -> usize {
        self.open_close + self.newton + self.too_fast + self.other
    }
}

/// Record of one [`super::ImplicitDynamics::advance`] call: of the whole
/// interval when it returns it, of the call up to the failure in
/// [`super::ImplicitError::StepFailed`].
#[derive(Debug, Clone, PartialEq)]
pub struct StepReport {
    /// Sub-steps taken.
    pub substeps: usize,
    /// How many times the step was halved.
    pub reductions: usize,
    /// Why: the failures that caused the halvings, by kind.
    pub halvings: Halvings,
    /// How many times a sub-step was detected again at a larger search
    /// distance and repeated at the same size
    /// ([`super::ImplicitSettings::max_search_distance`]).
    pub redetections: usize,
    /// Smallest sub-step used (s).
    pub smallest_dt: f64,
    /// Relative residual norms of every iteration of the last sub-step.
    pub residuals: Vec<f64>,
    /// Length of the update after each residual of `residuals` but the
    /// last: 1 is the full Newton update (after its scaling to the search
    /// distance), shortened where a contact whose slip would reverse a
    /// second time sticks, then by the backtracking line search.
    pub step_lengths: Vec<f64>,
    /// Open–close iterations of the last sub-step.
    pub open_close_iterations: usize,
    /// Iterations (linear solves) of the whole call: every sub-step, the
    /// failed ones included.
    pub iterations: usize,
}

/// A contact after the last accepted step.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ContactReport<S> {
    /// Body A (the vertex or smooth side) and body B (the edge side).
    pub bodies: (usize, usize),
    /// Which features of A and B touch.
    pub features: ContactFeatures,
    /// The history kept for the next step (after any pull-back).
    pub state: S,
    /// `(t_n, t_s)` in the equilibrium of the step (before the pull-back of
    /// the conventional law).
    pub force: (f64, f64),
    /// Force on body A at the contact (N/m); B receives the opposite.
    pub force_on_a: Vec2,
    /// Unit normal from B into A: the direction the normal force pushes A.
    pub normal: Vec2,
    /// A's material point of the contact at the end of the step (world).
    pub point: Point,
    /// The normal gap at the end of the step (m): positive apart (a
    /// contact within the search distance that is open), negative where
    /// the bodies overlap (the penetration of a penalty contact, `t_n / k_n`
    /// for a linear one).
    pub gap: f64,
    /// The shear displacement of the step at the contact (m), along the
    /// contact's tangent: the relative slide of the two material points
    /// since the start of the step.
    pub shear: f64,
}

#[cfg(test)]
mod tests {
    use super::StepFailure;

    /// A failed step's reason says what to change: a residual that stalled
    /// near its tolerance points at the penalty, one far above it at the
    /// step.
    #[test]
    fn newton_failure_says_what_to_change() {
        let stalled = StepFailure::NewtonNotConverged {
            iterations: 20,
            residual: 3.3e-10,
            tolerance: 1e-10,
        }
        .to_string();
        assert!(stalled.contains("lower the contact penalty"), "{stalled}");
        assert!(stalled.contains("residual_tolerance"), "{stalled}");
        let far = StepFailure::NewtonNotConverged {
            iterations: 20,
            residual: 1e-3,
            tolerance: 1e-10,
        }
        .to_string();
        assert!(far.contains("smaller time step"), "{far}");
        let cycling = StepFailure::OpenCloseNotSettled { iterations: 20 }.to_string();
        assert!(cycling.contains("max_open_close"), "{cycling}");
    }

    /// The failures of the pieces a step calls keep their typed errors, so
    /// that a caller can match on them, and their messages.
    #[test]
    fn failures_of_the_pieces_keep_their_types() {
        use crate::error::{DismechError, FactorizationFailure, SolveError};
        let singular = SolveError::Factorization(FactorizationFailure::StructurallySingular {
            message: "zero pivot in column 3".into(),
        });
        let failure = StepFailure::Solve(singular.clone());
        assert!(matches!(&failure, StepFailure::Solve(e) if *e == singular));
        assert!(failure.to_string().contains("zero pivot in column 3"));
        let body = DismechError::InvalidPolygon {
            block: 4,
            reason: "it turned inside out",
        };
        let failure = StepFailure::Geometry(Box::new(body.clone()));
        assert!(matches!(&failure, StepFailure::Geometry(e) if **e == body));
        assert_eq!(failure.to_string(), body.to_string());
    }
}

/// Why a time step is too small for the implicit driver's clock
/// ([`crate::implicit::ImplicitError::TimeStepTooSmall`]).
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum StepTooSmall {
    /// Its smallest sub-step `dt × min_dt_ratio` is not a normal number:
    /// the halving would never end.
    #[error("its smallest sub-step dt × min_dt_ratio = {smallest:e} s is not a normal number; take a larger dt or min_dt_ratio")]
    SubStepNotNormal {
        /// The smallest sub-step `dt × min_dt_ratio` (s).
        smallest: f64,
    },
    /// Added to the time reached, it leaves the clock unchanged in double
    /// precision.
    #[error(
        "added to the time reached it leaves it unchanged in double precision; take a larger dt"
    )]
    ClockUnchanged,
}
