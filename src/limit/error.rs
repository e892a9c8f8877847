//! Errors of the limit analysis: [`LimitError`], joined into
//! [`DismechError::Limit`](crate::error::DismechError::Limit): a model
//! that cannot be built (contacts declared between bodies that do not
//! touch, a body or contact declared twice, a contact of a body with
//! itself, a lattice too large), one that cannot be analysed (no driver or
//! more than one, dead loads that are all zero, a plate touching nothing),
//! and an analysis whose optimum is not certified or that has no limit
//! load where one is needed. Each variant names the offending body,
//! contact, support or value.

/// Why a limit-analysis model ([`super::LimitModel`], a lattice of
/// [`super::lattice`]) cannot be built or analysed, or its result used;
/// joined into [`DismechError::Limit`](crate::error::DismechError::Limit).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LimitError {
    /// A contact was declared between bodies that do not touch.
    #[error("contact {contact} (element {body} with {partner}) is declared but the surfaces are {gap:.3e} m apart (negative: overlapping); they must touch within {tolerance:.1e} m")]
    ContactNotTouching {
        /// Index of the contact.
        contact: usize,
        /// The element.
        body: usize,
        /// What it was declared against (its Display says it in words).
        partner: super::NamedPartner,
        /// Distance between the surfaces.
        gap: f64,
        /// Accepted distance.
        tolerance: f64,
    },
    /// A driving plate has no contact.
    #[error("the moving support `{name}` (support {support}) touches no element")]
    PlateTouchesNothing {
        /// Index of the support.
        support: usize,
        /// Its name.
        name: String,
    },
    /// A limit analysis needs exactly one driver: one moving support, or a
    /// live load or the dead loads' multiplier and no moving support.
    #[error("a limit analysis needs exactly one driver: one moving support (plate), or a live load (set_live_load) or the dead loads' multiplier (multiply_dead_loads) and no moving support; found {0} moving supports")]
    DrivingSupportCount(usize),
    /// The dead loads' multiplier is sought, but every dead load is zero.
    #[error("the dead loads' multiplier is sought (multiply_dead_loads), but every body's load is zero: set the bodies' weights with set_load")]
    NoDeadLoads,
    /// A contact declared between a body and itself.
    #[error("a contact of element {body} with itself: a contact joins two elements, or an element and a support")]
    SelfContact {
        /// The element.
        body: usize,
    },
    /// Two rigid elements of a limit analysis share their reference point.
    #[error("element {body} has its reference point at ({x}, {y}), within {distance:.1e} m of that of element {existing}: two rigid elements cannot share a point (an element declared twice would double its strength and load)")]
    DuplicateBody {
        /// The element refused.
        body: usize,
        /// The element already there.
        existing: usize,
        /// Reference point x.
        x: f64,
        /// Reference point y.
        y: f64,
        /// The distance within which two reference points coincide.
        distance: f64,
    },
    /// A contact repeats one already declared: the same pair at the same
    /// point.
    #[error("contact {contact} (element {body} with {partner}) repeats contact {existing}: the same pair at the same point would count its strength twice")]
    DuplicateContact {
        /// The contact refused.
        contact: usize,
        /// The contact it repeats.
        existing: usize,
        /// The element.
        body: usize,
        /// What it was declared against (its Display says it in words).
        partner: super::NamedPartner,
    },
    /// A lattice with more elements than the limit.
    #[error("lattice of m = {m} columns × n = {n} elements exceeds the limit of {limit} elements (each needs about 13 kB for the LP and its factor); use a smaller m or n")]
    LatticeTooLarge {
        /// Columns.
        m: usize,
        /// Elements per column.
        n: usize,
        /// The largest number of elements accepted.
        limit: usize,
    },
    /// A limit analysis without a limit load was asked for one.
    #[error("the limit analysis has no limit load (status {status:?}): {what} needs a collapse")]
    NoLimitLoad {
        /// The analysis' status.
        status: super::LimitStatus,
        /// What needed the load.
        what: &'static str,
    },
    /// An LP solver reported an optimum that fails the LP's own optimality
    /// conditions at the tolerance a certified limit load needs (see
    /// [`super::CERTIFICATE_TOLERANCE`]).
    #[error("the LP solver reported an optimum ({solver_status}) that fails the optimality conditions of its LP: primal residual {primal_residual:.1e}, dual residual {dual_residual:.1e}, duality gap {gap:.1e}, where a certified limit load needs each at most {tolerance:.0e}; solve more tightly (LinearProgramSolver.tolerance 1e-9, the default, or lower)")]
    UncertifiedOptimum {
        /// The solver's own termination status.
        solver_status: String,
        /// Relative violation of the LP's rows by its solution.
        primal_residual: f64,
        /// Relative violation of stationarity and of the multipliers' signs.
        dual_residual: f64,
        /// Relative gap between the primal and dual objectives.
        gap: f64,
        /// The largest residual a certified optimum may have.
        tolerance: f64,
    },
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::DismechError;

    #[test]
    fn joined_into_dismech_error_with_the_same_message() {
        let e = LimitError::SelfContact { body: 3 };
        let joined = DismechError::from(e.clone());
        assert_eq!(joined.to_string(), e.to_string());
        assert_eq!(
            joined.to_string(),
            "a contact of element 3 with itself: a contact joins two elements, or an element and a support"
        );
        assert!(matches!(
            joined,
            DismechError::Limit(LimitError::SelfContact { body: 3 })
        ));
    }
}
