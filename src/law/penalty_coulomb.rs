//! The penalty Coulomb law of DDA in its two friction integrations (paper
//! 003, §2.(2), eqs. 7–10 and Fig. 1), behind [`ContactLaw`]`<2>`.
//!
//! Normal: `t_n = p_c ⟨−g_n⟩` (eq. 7), no tension. A contact exactly
//! touching (`g_n = 0`) is closed, with zero force: its tangent is then the
//! spring's, the convention of active-set methods at the kink, so that the
//! Newton step of an implicit driver sees a contact that touches without
//! load (blocks cut from joint sets start so; open, a wall of them fell
//! through its first iterate). Shear: the elastic part of
//! the shear displacement carries `t_s = p_c g_s^e` (eq. 8) with the same
//! penalty, limited by Coulomb's `|t_s| ≤ μ t_n`.
//!
//! * [`FrictionIntegration::ReturnMapping`] integrates eq. (9) by backward
//!   Euler: trial `t_s* = t_s,n + p_c Δg_s`; if `f = |t_s*| − μ t_n ≤ 0` the
//!   contact is in LOCK and `t_s = t_s*`, else it is in CLOSE (slip) and
//!   `t_s = μ t_n sgn t_s*` (eq. 10). The consistent tangent
//!   `∂(t_n, t_s)/∂(Δg_n, Δg_s)` is `[[p, 0], [0, p]]` in LOCK and
//!   `[[p, 0], [μ p sgn t_s*, 0]]` in CLOSE — the unsymmetric slip tangent
//!   that eqs. (12)–(13) express in virtual-work form (derived after
//!   Wriggers (2006), penalty friction with return mapping).
//! * [`FrictionIntegration::Conventional`] is the treatment of classic DDA
//!   that the paper criticises (Fig. 1): the shear regime of a step is the
//!   one the contact ended the previous step in. In LOCK the shear spring is
//!   linear and *uncapped* during the step; if it ends above `μ t_n` it is
//!   pulled back to `μ t_n` only in the stored state, so the excess becomes
//!   an unbalanced force of the next step. In slide the friction force is
//!   `μ t_n,n sgn`, a known load from the previous step's normal force; the
//!   contact returns to LOCK when the relative motion reverses.
//!
//! [`PenaltyCoulomb::bonded`] is the bonded (cohesive, never opening)
//! variant for penalty models of paper 002's cohesive contacts: the normal
//! spring is bilateral, `t_n = p_c (−g_n)` in compression and tension
//! alike, and the shear, integrated by the same return mapping, is capped
//! by the Mohr–Coulomb line `|t_s| ≤ c + μ t_n` — the linear strength the
//! limit analysis imposes on a bilateral contact (eq. 13 of paper 002). With
//! friction the line meets zero shear strength at the tension
//! `t_n = −c/μ`; the normal spring yields there (`t_n ≥ −c/μ`), so that the
//! force stays within the strength. Without friction the cap is `c` and the
//! tension is unlimited, as in the LP.

use nalgebra::SVector;

use super::coulomb::{project_shear, shear_step};
use super::traits::{
    BoundedStiffness, ContactInput, ContactLaw, ContactResponse, PairProperties, Regime,
    StiffnessBound, Strength, StrengthLaw, Tangent, TangentLaw,
};
use crate::error::{require_non_negative, require_positive, Result};

/// How the friction law is integrated over a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
pub enum FrictionIntegration {
    /// Classic DDA: shear capped at the next step (paper 003 Fig. 1).
    Conventional,
    /// Implicit backward-Euler return mapping (paper 003 eqs. 9–10).
    ReturnMapping,
}

impl FrictionIntegration {
    /// Short label: `conv` or `rm`.
    pub fn label(self) -> &'static str {
        match self {
            Self::Conventional => "conv",
            Self::ReturnMapping => "rm",
        }
    }
}

/// History of a DDA contact, kept from one accepted step to the next.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct PenaltyState {
    /// Normal force `t_n` (N/m, ≥ 0) at the end of the step.
    pub normal: f64,
    /// Shear force `t_s` at the end of the step (after any pull-back).
    pub shear: f64,
    /// LOCK (`Stick`), CLOSE in slip (`Slip`) or `Open`.
    pub regime: Option<Regime>,
}

/// The penalty Coulomb law of DDA, unilateral (paper 003) or bonded
/// ([`PenaltyCoulomb::bonded`]).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PenaltyCoulomb {
    penalty: f64,
    friction: f64,
    cohesion: f64,
    bonded: bool,
    integration: FrictionIntegration,
}

impl PenaltyCoulomb {
    /// A law with penalty `p_c` (N/m per m, > 0), friction coefficient
    /// `μ = tan φ` (≥ 0) and the chosen integration.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`](crate::error::DismechError::InvalidParameter)
    /// naming the value for a penalty that is not finite and positive, or a
    /// friction coefficient that is negative or not finite.
    pub fn new(penalty: f64, friction: f64, integration: FrictionIntegration) -> Result<Self> {
        require_positive("contact penalty p_c", penalty)?;
        require_non_negative("friction coefficient mu", friction)?;
        Ok(Self {
            penalty,
            friction,
            cohesion: 0.0,
            bonded: false,
            integration,
        })
    }

    /// A bonded cohesive contact with penalty `p_c` (> 0) and cohesion `c`
    /// (≥ 0, N/m): a bilateral normal spring that carries tension, and a
    /// shear spring capped at `c` by return mapping; it never opens
    /// ([`StrengthLaw::may_open`] is `false`). The penalty model of paper
    /// 002's contact of strength `C_p`.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`](crate::error::DismechError::InvalidParameter)
    /// naming the value for a penalty that is not finite and positive, or a
    /// cohesion that is negative or not finite.
    pub fn bonded(penalty: f64, cohesion: f64) -> Result<Self> {
        Self::bonded_with_friction(penalty, cohesion, 0.0)
    }

    /// [`Self::bonded`] with friction: the shear cap is the Mohr–Coulomb
    /// line `c + μ t_n`, and the tension is limited to `c/μ` (the apex of
    /// the line) for `μ > 0`.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`](crate::error::DismechError::InvalidParameter)
    /// naming the value for a penalty that is not finite and positive, or a
    /// cohesion or friction coefficient that is negative or not finite.
    pub fn bonded_with_friction(penalty: f64, cohesion: f64, friction: f64) -> Result<Self> {
        let law = Self::new(penalty, friction, FrictionIntegration::ReturnMapping)?;
        Ok(Self {
            cohesion: require_non_negative("contact cohesion c", cohesion)?,
            bonded: true,
            ..law
        })
    }

    /// The penalty `p_c`.
    pub fn penalty(&self) -> f64 {
        self.penalty
    }

    /// The friction coefficient μ.
    pub fn friction(&self) -> f64 {
        self.friction
    }

    /// The integration in use.
    pub fn integration(&self) -> FrictionIntegration {
        self.integration
    }

    /// The cohesion `c` (zero unless bonded).
    pub fn cohesion(&self) -> f64 {
        self.cohesion
    }

    /// Whether the contact is bonded (bilateral, cohesive).
    pub fn is_bonded(&self) -> bool {
        self.bonded
    }

    fn strength_of(&self) -> Strength {
        Strength {
            cohesion: self.cohesion,
            friction: self.friction,
        }
    }

    /// Backward-Euler return mapping: the Coulomb core, with the strength
    /// taken at `t_n` whose derivative with respect to the approach is
    /// `k_n`.
    fn return_mapping(
        &self,
        t_n: f64,
        k_n: f64,
        input: &ContactInput<2>,
        state: &PenaltyState,
    ) -> Out {
        let p = self.penalty;
        let previous = SVector::<f64, 2>::new(0.0, state.shear);
        let step = shear_step(
            &self.strength_of(),
            p,
            &previous,
            &input.increment,
            t_n,
            k_n,
        );
        Out {
            shear: step.force[1],
            d_shear: [step.tangent[(1, 0)], step.tangent[(1, 1)]],
            stored: step.force[1],
            regime: step.regime,
        }
    }

    fn conventional(&self, t_n: f64, input: &ContactInput<2>, state: &PenaltyState) -> Out {
        let p = self.penalty;
        let limit = self.strength_of().limit(t_n);
        match state.regime {
            Some(Regime::Slip) => {
                // Sliding: friction from the previous normal force, a known
                // load for the whole step; back to LOCK at the next step if
                // the relative motion reversed.
                let sign = state.shear.signum();
                let shear = self.friction * state.normal * sign;
                let (stored, regime) = if sign * input.increment[1] >= 0.0 {
                    (limit * sign, Regime::Slip)
                } else {
                    (shear.clamp(-limit, limit), Regime::Stick)
                };
                Out {
                    shear,
                    d_shear: [0.0, 0.0],
                    stored,
                    regime,
                }
            }
            _ => {
                // LOCK: linear spring, capped only in the stored state (the
                // core's projection).
                let trial = state.shear + p * input.increment[1];
                let regime = if trial.abs() > limit {
                    Regime::Slip
                } else {
                    Regime::Stick
                };
                let stored = project_shear(&SVector::<f64, 2>::new(0.0, trial), limit)[1];
                Out {
                    shear: trial,
                    d_shear: [0.0, p],
                    stored,
                    regime,
                }
            }
        }
    }

    /// One evaluation with its tangent `∂(t_n, t_s)/∂(Δg_n, Δg_s)`.
    fn respond(
        &self,
        input: &ContactInput<2>,
        state: &PenaltyState,
    ) -> (ContactResponse<2, PenaltyState>, Tangent<2>) {
        if self.bonded {
            return self.respond_bonded(input, state);
        }
        if input.overlap < 0.0 {
            let open = ContactResponse {
                force: SVector::zeros(),
                spring_force: SVector::zeros(),
                regime: Regime::Open,
                state: PenaltyState {
                    normal: 0.0,
                    shear: 0.0,
                    regime: Some(Regime::Open),
                },
            };
            return (open, Tangent::zeros());
        }
        let t_n = self.penalty * input.overlap;
        let out = match self.integration {
            FrictionIntegration::ReturnMapping => {
                self.return_mapping(t_n, self.penalty, input, state)
            }
            FrictionIntegration::Conventional => self.conventional(t_n, input, state),
        };
        out.response(t_n, self.penalty)
    }
}

impl PenaltyCoulomb {
    /// The tension at which the Mohr–Coulomb line `c + μ t_n` reaches zero
    /// (`−c/μ`, rounded towards zero so that the strength there is not
    /// negative in floating point); `−∞` without friction.
    fn apex(&self) -> f64 {
        if self.friction <= 0.0 {
            return f64::NEG_INFINITY;
        }
        let mut apex = -self.cohesion / self.friction;
        while apex < 0.0 && self.strength_of().limit(apex) < 0.0 {
            // The next float towards zero.
            apex = f64::from_bits(apex.to_bits() - 1);
        }
        apex
    }

    /// The bonded law: bilateral normal spring (yielding in tension at the
    /// apex `−c/μ` of the Mohr–Coulomb line when `μ > 0`), shear by return
    /// mapping onto `c + μ t_n`.
    fn respond_bonded(
        &self,
        input: &ContactInput<2>,
        state: &PenaltyState,
    ) -> (ContactResponse<2, PenaltyState>, Tangent<2>) {
        let spring = self.penalty * input.overlap;
        let apex = self.apex();
        let (t_n, k_n, out) = if spring > apex {
            let out = self.return_mapping(spring, self.penalty, input, state);
            (spring, self.penalty, out)
        } else {
            // At the apex the strength is zero: no shear, whatever the
            // motion (computed so, not as c + μ t_n, which round-off may
            // leave a hair below zero).
            let out = Out {
                shear: 0.0,
                d_shear: [0.0, 0.0],
                stored: 0.0,
                regime: Regime::Slip,
            };
            (apex, 0.0, out)
        };
        out.response(t_n, k_n)
    }
}

/// Shear part of one evaluation.
struct Out {
    shear: f64,
    /// `∂t_s/∂(Δg_n approach, Δg_s)`.
    d_shear: [f64; 2],
    stored: f64,
    regime: Regime,
}

impl Out {
    /// The response and tangent for normal force `t_n` (normal stiffness
    /// `k_n`) with this shear part.
    fn response(self, t_n: f64, k_n: f64) -> (ContactResponse<2, PenaltyState>, Tangent<2>) {
        let force = SVector::<f64, 2>::new(t_n, self.shear);
        let tangent = Tangent::<2>::new(k_n, 0.0, self.d_shear[0], self.d_shear[1]);
        let response = ContactResponse {
            force,
            spring_force: force,
            regime: self.regime,
            state: PenaltyState {
                normal: t_n,
                shear: self.stored,
                regime: Some(self.regime),
            },
        };
        (response, tangent)
    }
}

impl ContactLaw<2> for PenaltyCoulomb {
    type State = PenaltyState;

    /// `input.overlap` is `−g_n` of the current iterate and
    /// `input.increment[1]` the shear increment `Δg_s` of the step; the
    /// returned force is `[t_n, t_s]`.
    fn evaluate(
        &self,
        input: &ContactInput<2>,
        state: &PenaltyState,
    ) -> ContactResponse<2, PenaltyState> {
        self.respond(input, state).0
    }

    /// The penalty springs do not depend on the shapes.
    fn uses_contact_shape(&self) -> bool {
        false
    }

    /// A bonded contact pulls when apart.
    fn opens_without_overlap(&self) -> bool {
        !self.bonded
    }
}

impl TangentLaw<2> for PenaltyCoulomb {
    fn evaluate_with_tangent(
        &self,
        input: &ContactInput<2>,
        state: &PenaltyState,
    ) -> (ContactResponse<2, PenaltyState>, Tangent<2>) {
        self.respond(input, state)
    }

    /// Return mapping is the consistent integration; the conventional one
    /// is not (paper 003 Fig. 1).
    fn is_consistent(&self) -> bool {
        self.integration == FrictionIntegration::ReturnMapping
    }
}

impl StrengthLaw for PenaltyCoulomb {
    fn strength(&self) -> Strength {
        self.strength_of()
    }

    /// A bonded contact never opens.
    fn may_open(&self) -> bool {
        !self.bonded
    }
}

impl BoundedStiffness<2> for PenaltyCoulomb {
    fn stiffness_bound(&self, _pair: &PairProperties, _overlap: f64) -> StiffnessBound {
        StiffnessBound {
            normal: self.penalty,
            shear: self.penalty,
            normal_damping: 0.0,
            shear_damping: 0.0,
            rolling: 0.0,
        }
    }
}
