//! Rolling resistance for any 2D law: an elastic–perfectly plastic rolling
//! spring beside the law's forces.
//!
//! Round particles roll where angular grains would lock, so a packing of
//! discs shears at a lower angle than the sand it stands for; a rolling
//! resistance restores it. The model here is the elastic–plastic spring of
//! Iwashita & Oda (1998, *J. Eng. Mech.* 124(3), 285–292) in the form Ai et
//! al. classify as type C (*Powder Technology* 206, 2011, 269–282; without
//! its viscous part):
//!
//! * the relative rotation of A with respect to B over a step,
//!   `Δθ_r = Δθ_A − Δθ_B` ([`ContactInput::rotation`]), loads a spring of
//!   stiffness `k_r = k_roll R*²`: `M_trial = M_old − k_r Δθ_r`;
//! * the moment is capped by the rolling strength `|M| ≤ μ_r R* F_n`
//!   (`F_n` the inner law's whole normal force, its dashpot included);
//! * `R* = R_A R_B / (R_A + R_B)` is the rolling radius, from the radii of
//!   curvature at the contact (a wall's is infinite, so `R* = R_A`; a
//!   polygon's vertex has radius 0 and no rolling resistance).
//!
//! The moment acts on A and its opposite on B ([`ContactLaw::moment`]),
//! beside the moments of the contact force. A common choice of `k_roll` is
//! the law's shear stiffness. Only the explicit driver applies the moment:
//! the law has no consistent tangent, so the implicit driver does not take
//! it (a compile error), nor does the limit analysis.

use super::traits::{
    BoundedStiffness, ContactInput, ContactLaw, ContactResponse, PairProperties, Regime,
    StiffnessBound,
};
use crate::error::{require_non_negative, Result};

/// The history of a contact with rolling resistance: the inner law's
/// state and the rolling moment on A.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RollingState<S> {
    /// The state of the law the rolling resistance is added to.
    pub inner: S,
    /// The rolling moment on A at the end of the step (N·m per m).
    pub moment: f64,
}

/// A 2D contact law with an elastic–perfectly plastic rolling spring added
/// (see [`crate::law`]: Iwashita & Oda 1998, type C of Ai et al. 2011):
/// a spring `k_roll R*²` on the relative rotation of A and B, its moment
/// capped at `μ_r R* F_n`, with `R*` the rolling radius
/// ([`Self::rolling_radius`]).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct RollingResistance<L> {
    inner: L,
    coefficient: f64,
    stiffness: f64,
}

impl<L: ContactLaw<2>> RollingResistance<L> {
    /// Rolling resistance of coefficient `μ_r` (dimensionless, ≥ 0: the
    /// moment is capped at `μ_r R* F_n`) and rolling stiffness
    /// `k_roll` (N/m per m, ≥ 0; the spring is `k_roll R*²` N·m/rad per m)
    /// added to `inner`.
    ///
    /// # Errors
    /// [`crate::error::DismechError::InvalidParameter`] naming
    /// `rolling coefficient` or `rolling stiffness` when it is negative or
    /// not finite.
    pub fn new(inner: L, coefficient: f64, stiffness: f64) -> Result<Self> {
        require_non_negative("rolling coefficient", coefficient)?;
        require_non_negative("rolling stiffness", stiffness)?;
        Ok(Self {
            inner,
            coefficient,
            stiffness,
        })
    }

    /// The law the rolling resistance is added to.
    pub fn inner(&self) -> &L {
        &self.inner
    }

    /// The rolling coefficient `μ_r`.
    pub fn coefficient(&self) -> f64 {
        self.coefficient
    }

    /// The rolling stiffness `k_roll` (the spring is `k_roll R*²`).
    pub fn stiffness(&self) -> f64 {
        self.stiffness
    }

    /// The rolling radius `R* = R_A R_B / (R_A + R_B)` of a pair (`R_A`
    /// against a wall; 0 where either radius is 0, as at a polygon's
    /// vertex, or not a number, and between two flat sides).
    pub fn rolling_radius(pair: &PairProperties) -> f64 {
        let (a, b) = (pair.curvature_radius_a, pair.curvature_radius_b);
        if !(a > 0.0 && b > 0.0) || (a.is_infinite() && b.is_infinite()) {
            return 0.0;
        }
        if b.is_infinite() {
            return a;
        }
        if a.is_infinite() {
            return b;
        }
        a * b / (a + b)
    }
}

impl<L: ContactLaw<2>> ContactLaw<2> for RollingResistance<L> {
    type State = RollingState<L::State>;

    fn evaluate(
        &self,
        input: &ContactInput<2>,
        state: &Self::State,
    ) -> ContactResponse<2, Self::State> {
        let response = self.inner.evaluate(input, &state.inner);
        let radius = Self::rolling_radius(&input.pair);
        let moment = if response.regime == Regime::Open || radius == 0.0 {
            0.0
        } else {
            let limit = self.coefficient * radius * response.force[0].max(0.0);
            let trial = state.moment - self.stiffness * radius * radius * input.rotation;
            trial.clamp(-limit, limit)
        };
        ContactResponse {
            force: response.force,
            spring_force: response.spring_force,
            regime: response.regime,
            state: RollingState {
                inner: response.state,
                moment,
            },
        }
    }

    /// The rolling radius needs the radii of curvature.
    fn uses_contact_shape(&self) -> bool {
        true
    }

    fn opens_without_overlap(&self) -> bool {
        self.inner.opens_without_overlap()
    }

    /// The rolling moment kept in the state, with the inner law's own.
    fn moment(&self, state: &Self::State) -> f64 {
        let inner = self.inner.moment(&state.inner);
        if inner == 0.0 {
            state.moment
        } else {
            state.moment + inner
        }
    }
}

impl<L: BoundedStiffness<2>> BoundedStiffness<2> for RollingResistance<L> {
    /// The inner law's bound, with the rolling spring `k_roll R*²` as its
    /// rolling stiffness ([`StiffnessBound::rolling`]), `R*` from the
    /// pair's radii of curvature (the explicit driver gives a particle's
    /// largest: an ellipse's flat side, `a²/b`, rolls on the stiffest
    /// spring).
    fn stiffness_bound(&self, pair: &PairProperties, overlap: f64) -> StiffnessBound {
        let mut bound = self.inner.stiffness_bound(pair, overlap);
        let radius = Self::rolling_radius(pair);
        bound.rolling += self.stiffness * radius * radius;
        bound
    }
}
