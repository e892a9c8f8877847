//! Checks every contact law of this crate passes, written once and generic
//! over the law, so that a law of one's own can be checked the same way.
//!
//! Each check takes a law, one input and one history state and returns
//! `Err(Violation)` saying what failed; drive them with random inputs and
//! histories: with the `proptest` feature, the module `strategies` draws loading
//! paths and the histories a law makes of them. The checks are grouped by what a law
//! declares: [`check_force_law`] for any [`ContactLaw`] (a law for the
//! explicit driver alone), [`check_strength_law`] for a [`StrengthLaw`],
//! [`check_tangent_law`] for a [`TangentLaw`], and [`check_all`] for a law
//! that is all three:
//!
//! ```
//! use dismech::law::{conformance, ContactInput, PairProperties, PenaltyCoulomb,
//!                    FrictionIntegration, PenaltyState};
//! use dismech::nalgebra::Vector2;
//! let law = PenaltyCoulomb::new(1e8, 0.5, FrictionIntegration::ReturnMapping).unwrap();
//! let input = ContactInput { overlap: 1e-4, increment: Vector2::new(1e-5, 2e-5), dt: 1e-3,
//!                            is_new: false, pair: PairProperties::rigid(), rotation: 0.0 };
//! let state = PenaltyState { normal: 9e3, shear: 2e3, regime: None };
//! assert!(conformance::check_all(&law, &input, &state).is_empty());
//! ```
//!
//! | check | property | run by |
//! |---|---|---|
//! | [`deterministic`] | `evaluate` twice gives the same response | [`check_force_law`] |
//! | [`contact_shape_unused`] | a law that says it reads neither the contact's width nor its radii of curvature gives the same response without them | [`check_force_law`] |
//! | [`open_without_overlap`] | no overlap, no force or moment, regime `Open` (for a law that [`ContactLaw::opens_without_overlap`]) | [`check_force_law`] |
//! | [`no_tension`] | a law that may open never pulls: `t_n ≥ 0` | [`check_strength_law`] |
//! | [`within_strength`] | the spring part of the shear stays within `c + μ t_n`, and lies on it in slip | [`check_strength_law`] |
//! | [`tangent_matches_finite_differences`] | the consistent tangent equals central differences of the force | [`check_tangent_law`] |
//! | [`pure`] | `evaluate` twice gives the same response, equal to `evaluate_with_tangent`'s | [`check_tangent_law`] |
//! | [`no_moment_with_tangent`] | a law with a tangent answers no rolling moment (the implicit driver's tangent has no rotational coupling) | [`check_tangent_law`] |

use super::traits::{ContactInput, ContactLaw, ContactResponse, Regime, StrengthLaw, TangentLaw};

#[cfg(feature = "proptest")]
pub mod strategies;

/// A failed check: which one, and what was seen.
#[derive(Debug, Clone, PartialEq)]
pub struct Violation {
    /// Name of the check.
    pub check: &'static str,
    /// What was seen, with the values.
    pub detail: String,
}

impl std::fmt::Display for Violation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.check, self.detail)
    }
}

fn fail(check: &'static str, detail: String) -> Result<(), Violation> {
    Err(Violation { check, detail })
}

/// A law that may open never pulls: `force[0] ≥ 0` and `spring_force[0] ≥ 0`.
///
/// # Errors
/// A [`Violation`] of check `no_tension`, with both normal forces, when
/// either is negative.
pub fn no_tension<L: ContactLaw<D>, const D: usize>(
    law: &L,
    input: &ContactInput<D>,
    state: &L::State,
) -> Result<(), Violation> {
    let r = law.evaluate(input, state);
    if r.force[0] < 0.0 || r.spring_force[0] < 0.0 {
        return fail(
            "no_tension",
            format!(
                "normal force {} (spring {}) is tensile",
                r.force[0], r.spring_force[0]
            ),
        );
    }
    Ok(())
}

/// Without overlap there is no force, no moment, and the regime is `Open`. (What an
/// open contact keeps as history is the law's business: the DDA law
/// records that it opened.)
///
/// # Errors
/// A [`Violation`] of check `open_without_overlap`, with the overlap, the
/// force and the regime, when the input moved apart (its overlap made
/// negative) gives a force other than zero or a regime other than
/// [`Regime::Open`].
pub fn open_without_overlap<L: ContactLaw<D>, const D: usize>(
    law: &L,
    input: &ContactInput<D>,
    state: &L::State,
) -> Result<(), Violation> {
    let mut apart = *input;
    apart.overlap = -input.overlap.abs().max(f64::MIN_POSITIVE);
    let r = law.evaluate(&apart, state);
    let moment = law.moment(&r.state);
    if r.regime != Regime::Open || r.force.iter().any(|f| *f != 0.0) || moment != 0.0 {
        return fail(
            "open_without_overlap",
            format!(
                "overlap {} gives force {:?} and moment {} in regime {:?}",
                apart.overlap,
                r.force.as_slice(),
                moment,
                r.regime
            ),
        );
    }
    Ok(())
}

/// The spring part of the shear stays within the strength,
/// `‖t_s‖ ≤ c + μ t_n` (relative round-off `1e-12`), and lies on it in slip.
///
/// # Errors
/// A [`Violation`] of check `within_strength` when the shear of the spring
/// part exceeds `c + μ t_n`, or when in [`Regime::Slip`] it lies off that
/// limit by more than `1e-9 (1 + limit)`. An open contact is held to
/// the first only (a cohesive law may carry shear as it opens).
pub fn within_strength<L: ContactLaw<D> + StrengthLaw, const D: usize>(
    law: &L,
    input: &ContactInput<D>,
    state: &L::State,
) -> Result<(), Violation> {
    let r = law.evaluate(input, state);
    let limit = law.strength().limit(r.spring_force[0]);
    let shear = (1..D)
        .map(|i| r.spring_force[i] * r.spring_force[i])
        .sum::<f64>()
        .sqrt();
    if shear > limit * (1.0 + 1e-12) + 1e-12 {
        return fail(
            "within_strength",
            format!("|t_s| = {shear} exceeds c + mu t_n = {limit}"),
        );
    }
    if r.regime == Regime::Slip && (shear - limit).abs() > 1e-9 * (1.0 + limit) {
        return fail(
            "within_strength",
            format!("slipping with |t_s| = {shear} off the limit {limit}"),
        );
    }
    Ok(())
}

/// The consistent tangent equals central differences of the force with
/// respect to each increment component (step `h`), wherever the
/// difference does not straddle a kink (a change of regime, or a force
/// clamped to zero on one side only). An approach increment moves the
/// overlap with it (`∂overlap/∂Δu_n = 1`), as it does in a driver. The
/// tolerance is `relative · (1 + |analytic| + |fd|)` plus the round-off
/// `1e-15 |f| / h`.
///
/// # Errors
/// A [`Violation`] of check `tangent_matches_finite_differences` naming
/// the first entry `(i, j)` of the tangent, with its analytic value and
/// the difference, that is off by more than the tolerance; an open
/// contact that carries nothing, and a component whose difference
/// straddles a kink (a change of regime, a force clamped to zero, or, for
/// an open contact that carries force, one-sided differences that
/// disagree), pass.
pub fn tangent_matches_finite_differences<L: TangentLaw<D>, const D: usize>(
    law: &L,
    input: &ContactInput<D>,
    state: &L::State,
    h: f64,
    relative: f64,
) -> Result<(), Violation> {
    let (r, tangent) = law.evaluate_with_tangent(input, state);
    if r.regime == Regime::Open && r.force.iter().all(|f| *f == 0.0) {
        return Ok(());
    }
    for j in 0..D {
        let (mut plus, mut minus) = (*input, *input);
        plus.increment[j] += h;
        minus.increment[j] -= h;
        if j == 0 {
            plus.overlap += h;
            minus.overlap -= h;
        }
        let (rp, rm) = (law.evaluate(&plus, state), law.evaluate(&minus, state));
        let clamped = |f: f64| f == 0.0;
        let kink = rp.regime != r.regime
            || rm.regime != r.regime
            || (0..D).any(|i| clamped(rp.force[i]) != clamped(rm.force[i]));
        if kink {
            continue;
        }
        for i in 0..D {
            let fd = (rp.force[i] - rm.force[i]) / (2.0 * h);
            let roundoff = 1e-15 * (rp.force[i].abs() + rm.force[i].abs()) / h;
            let scale = 1.0 + tangent[(i, j)].abs() + fd.abs();
            // An open contact that carries force (a cohesive law losing its
            // cohesion) keeps its regime whether its shear sticks under the
            // falling cap or slides on it: a kink there shows as one-sided
            // differences that disagree.
            let one_sided = [
                (rp.force[i] - r.force[i]) / h,
                (r.force[i] - rm.force[i]) / h,
            ];
            if r.regime == Regime::Open
                && (one_sided[0] - one_sided[1]).abs() > relative * scale + 2.0 * roundoff
            {
                continue;
            }
            if (fd - tangent[(i, j)]).abs() > relative * scale + roundoff {
                return fail(
                    "tangent_matches_finite_differences",
                    format!(
                        "d force[{i}] / d increment[{j}] in {:?}: analytic {} vs difference {fd}",
                        r.regime,
                        tangent[(i, j)]
                    ),
                );
            }
        }
    }
    Ok(())
}

/// `evaluate` is a pure function: two calls agree, and agree with
/// `evaluate_with_tangent`.
///
/// # Errors
/// A [`Violation`] of check `pure`, with the three responses, when two
/// calls of `evaluate`, or `evaluate` and `evaluate_with_tangent`, give
/// different responses.
pub fn pure<L, const D: usize>(
    law: &L,
    input: &ContactInput<D>,
    state: &L::State,
) -> Result<(), Violation>
where
    L: TangentLaw<D>,
    L::State: PartialEq,
{
    let first = law.evaluate(input, state);
    let second = law.evaluate(input, state);
    let (third, _) = law.evaluate_with_tangent(input, state);
    let same = |a: &ContactResponse<D, L::State>, b: &ContactResponse<D, L::State>| a == b;
    if !same(&first, &second) || !same(&first, &third) {
        return fail(
            "pure",
            format!("two evaluations differ: {first:?} / {second:?} / {third:?}"),
        );
    }
    Ok(())
}

/// A law that does not [`ContactLaw::uses_contact_shape`] gives the same
/// response with NaN width and radii of curvature as with the input's.
/// It compares [`ContactLaw::evaluate`] only (the explicit driver, which
/// acts on the answer, calls nothing else), exactly: a law whose response
/// is NaN of itself fails it.
///
/// # Errors
/// A [`Violation`] of check `contact_shape_unused`, with both responses,
/// when a law that does not [`ContactLaw::uses_contact_shape`] responds
/// differently with the width and radii of curvature set to NaN; a law
/// that uses them passes.
pub fn contact_shape_unused<L, const D: usize>(
    law: &L,
    input: &ContactInput<D>,
    state: &L::State,
) -> Result<(), Violation>
where
    L: ContactLaw<D>,
    L::State: PartialEq,
{
    if law.uses_contact_shape() {
        return Ok(());
    }
    let mut without = *input;
    without.pair.width = f64::NAN;
    without.pair.curvature_radius_a = f64::NAN;
    without.pair.curvature_radius_b = f64::NAN;
    let (with, nan) = (law.evaluate(input, state), law.evaluate(&without, state));
    if with != nan {
        return fail(
            "contact_shape_unused",
            format!(
                "the law says it reads neither width nor radii, yet {with:?} becomes {nan:?} without them"
            ),
        );
    }
    Ok(())
}

/// `evaluate` is a pure function: two calls with the same input and state
/// give the same response (the check of a law that has no tangent; a
/// [`TangentLaw`] runs [`pure`], which also compares the tangent's
/// response).
///
/// # Errors
/// A [`Violation`] of check `deterministic`, with both responses, when two
/// calls of `evaluate` differ.
pub fn deterministic<L, const D: usize>(
    law: &L,
    input: &ContactInput<D>,
    state: &L::State,
) -> Result<(), Violation>
where
    L: ContactLaw<D>,
    L::State: PartialEq,
{
    let (first, second) = (law.evaluate(input, state), law.evaluate(input, state));
    if first != second {
        return fail(
            "deterministic",
            format!("two evaluations differ: {first:?} / {second:?}"),
        );
    }
    Ok(())
}

/// Collects the violations of `checks`.
fn violations(checks: impl IntoIterator<Item = Result<(), Violation>>) -> Vec<Violation> {
    checks.into_iter().filter_map(Result::err).collect()
}

/// The checks of what every [`ContactLaw`] declares, on one input:
/// [`deterministic`], [`contact_shape_unused`] and, for a law that
/// [`ContactLaw::opens_without_overlap`], [`open_without_overlap`]. A law
/// meant only for the explicit driver (a force, no tangent, no linear
/// strength) is checked by this alone.
pub fn check_force_law<L, const D: usize>(
    law: &L,
    input: &ContactInput<D>,
    state: &L::State,
) -> Vec<Violation>
where
    L: ContactLaw<D>,
    L::State: PartialEq,
{
    let mut checks = vec![
        deterministic(law, input, state),
        contact_shape_unused(law, input, state),
    ];
    if law.opens_without_overlap() {
        checks.push(open_without_overlap(law, input, state));
    }
    violations(checks)
}

/// The checks of a [`StrengthLaw`]: [`no_tension`] (when the law
/// [`StrengthLaw::may_open`]) and [`within_strength`].
pub fn check_strength_law<L, const D: usize>(
    law: &L,
    input: &ContactInput<D>,
    state: &L::State,
) -> Vec<Violation>
where
    L: ContactLaw<D> + StrengthLaw,
{
    let mut checks = Vec::new();
    if law.may_open() {
        checks.push(no_tension(law, input, state));
    }
    checks.push(within_strength(law, input, state));
    violations(checks)
}

/// The checks of a [`TangentLaw`]: [`tangent_matches_finite_differences`]
/// (`h = 1e-7 · (|increment| + |overlap|)`, relative tolerance `1e-6`),
/// [`pure`] and [`no_moment_with_tangent`].
pub fn check_tangent_law<L, const D: usize>(
    law: &L,
    input: &ContactInput<D>,
    state: &L::State,
) -> Vec<Violation>
where
    L: TangentLaw<D>,
    L::State: PartialEq,
{
    let size = input.increment.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let h = 1e-7 * (size + input.overlap.abs()).max(f64::MIN_POSITIVE);
    violations([
        tangent_matches_finite_differences(law, input, state, h, 1e-6),
        pure(law, input, state),
        no_moment_with_tangent(law, input, state),
    ])
}

/// A law with a consistent tangent answers no rolling moment
/// ([`ContactLaw::moment`]): the implicit driver, which needs the
/// tangent, has no rotational coupling in it and applies no moment.
///
/// # Errors
/// A [`Violation`] of check `no_moment_with_tangent`, with the moment,
/// when the response carries one.
pub fn no_moment_with_tangent<L: TangentLaw<D>, const D: usize>(
    law: &L,
    input: &ContactInput<D>,
    state: &L::State,
) -> Result<(), Violation> {
    let (r, _) = law.evaluate_with_tangent(input, state);
    let moment = law.moment(&r.state);
    if moment != 0.0 {
        return fail(
            "no_moment_with_tangent",
            format!("a law with a tangent answered the rolling moment {moment}"),
        );
    }
    Ok(())
}

/// Every check, on one input, of a law with a tangent and a linear
/// strength (the laws of this crate): [`check_force_law`],
/// [`check_strength_law`] and [`check_tangent_law`]. Returns the
/// violations (empty when the law passes). A law that has no tangent or
/// no linear strength runs the parts it has.
pub fn check_all<L, const D: usize>(
    law: &L,
    input: &ContactInput<D>,
    state: &L::State,
) -> Vec<Violation>
where
    L: TangentLaw<D> + StrengthLaw,
    L::State: PartialEq,
{
    let mut out = check_force_law(law, input, state);
    out.extend(check_strength_law(law, input, state));
    out.extend(check_tangent_law(law, input, state));
    out
}
