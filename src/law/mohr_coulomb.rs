//! A cohesive Mohr–Coulomb penalty spring without tension: the slip-surface
//! springs of HPM slope analysis (paper 001, §4(4) and §5).
//!
//! The spring works on tractions (Pa) and relative displacements (m), per
//! unit area of the surface it represents. Per evaluation, with the
//! increment `Δu = [Δu_n (approaching), Δu_s, Δu_t]`:
//!
//! * elastic predictor `e ← e + diag(k_n, k_s, k_s) Δu`;
//! * Mohr–Coulomb: if `‖(e_s, e_t)‖ > c + e_n tan φ` the shear traction is
//!   returned radially onto the limit (return mapping), the rest is plastic
//!   slip;
//! * no tension: if `e_n < 0` the normal traction is zero and the cohesion
//!   is lost over an opening of `c / k_n`: the shear is capped at
//!   `c + e_n` (the trial tension `−e_n` taken off the cohesion) and
//!   returned onto that cap as above; the spring is
//!   [`Regime::Open`](super::Regime::Open) and, from `e_n ≤ −c` on,
//!   carries nothing.
//!
//! Paper 001 says the springs carry no tension but not how a cohesive
//! spring opens. Dropping its whole force at `e_n = 0` makes the force a
//! discontinuous function of the displacement, `c` of shear lost at once,
//! and the nonlinear solve's fixed-point iteration can then cycle for
//! ever among springs that open and close (a valley under a water table at
//! unit weights of 18–19 kN/m³ did, its residual cycling about 1e-3 over
//! 3 000 iterations; it converges with the cap). The cap makes the force
//! continuous; it changes nothing in compression or for `c = 0`, and
//! within an opening of micrometres (`c / k_n`, 8 µm for `c` = 8 kPa at
//! `k_n` = 1e9 Pa/m) otherwise.
//!
//! Evaluated once from a zero state with the total relative displacement as
//! the increment, it is the total-displacement form used by the
//! nonlinear HPM solve (one load step).

use nalgebra::SVector;

use super::coulomb::shear_step;
use super::spring_dashpot::{SpringState, SpringVector};
use super::traits::{
    BoundedStiffness, ContactInput, ContactLaw, ContactResponse, PairProperties, Regime,
    StiffnessBound, Strength, StrengthLaw, Tangent, TangentLaw,
};
use crate::error::{require_non_negative, require_positive, Result};

/// The cohesive Mohr–Coulomb spring with no tension, in 3D (normal and two
/// tangents).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MohrCoulombSpring {
    normal_stiffness: f64,
    shear_stiffness: f64,
    strength: Strength,
}

impl MohrCoulombSpring {
    /// A spring with stiffnesses `k_n`, `k_s = k_t` (Pa/m), cohesion `c`
    /// (Pa) and friction coefficient `tan φ`.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`](crate::error::DismechError::InvalidParameter)
    /// naming the value for a `k_n` or `k_s` that is not finite and
    /// positive, or a cohesion or friction coefficient that is negative or
    /// not finite.
    pub fn new(
        normal_stiffness: f64,
        shear_stiffness: f64,
        cohesion: f64,
        friction: f64,
    ) -> Result<Self> {
        Ok(Self {
            normal_stiffness: require_positive("slip normal stiffness k_n", normal_stiffness)?,
            shear_stiffness: require_positive("slip shear stiffness k_s", shear_stiffness)?,
            strength: Strength {
                cohesion: require_non_negative("cohesion c", cohesion)?,
                friction: require_non_negative("friction coefficient tan(phi)", friction)?,
            },
        })
    }

    /// Evaluate from a zero state with the total relative displacement
    /// `[approach, along s, along t]` as the increment (the one-step,
    /// total-displacement form).
    pub fn evaluate_total(&self, delta: [f64; 3]) -> ContactResponse<3, SpringState<3>> {
        self.respond(&Self::total_input(delta), &SpringState::default())
            .0
    }

    /// The input of the total-displacement form: `delta` as the increment
    /// from a zero state.
    pub fn total_input(delta: [f64; 3]) -> ContactInput<3> {
        ContactInput {
            overlap: delta[0],
            increment: SVector::from(delta),
            dt: 1.0,
            is_new: false,
            pair: PairProperties::rigid(),
            rotation: 0.0,
        }
    }

    /// Its strength: cohesion c (Pa) and friction coefficient `tan φ`.
    pub fn strength(&self) -> Strength {
        self.strength
    }

    /// The same spring with its strength replaced (strength reduction).
    pub fn with_strength(self, strength: Strength) -> Self {
        Self { strength, ..self }
    }
}

impl MohrCoulombSpring {
    /// One evaluation with its consistent tangent: the normal spring
    /// without tension, then the Coulomb core.
    fn respond(
        &self,
        input: &ContactInput<3>,
        state: &SpringState<3>,
    ) -> (ContactResponse<3, SpringState<3>>, Tangent<3>) {
        let (k_n, k_s) = (self.normal_stiffness, self.shear_stiffness);
        let du = input.increment;
        let e_n = state.spring.0[0] + k_n * du[0];
        if e_n < 0.0 {
            if self.strength.cohesion + e_n > 0.0 {
                // Opening: no normal traction, the shear capped at `c + e_n`
                // (a Coulomb line of slope 1 in the trial tension); open,
                // whether the rest of the cohesion holds the shear or not.
                let opening = Strength {
                    cohesion: self.strength.cohesion,
                    friction: 1.0,
                };
                let shear = shear_step(&opening, k_s, &state.spring.0, &du, e_n, k_n);
                let mut spring = shear.force;
                spring[0] = 0.0;
                let response = ContactResponse {
                    force: spring,
                    spring_force: spring,
                    regime: Regime::Open,
                    state: SpringState {
                        spring: SpringVector(spring),
                    },
                };
                return (response, shear.tangent);
            }
            let open = ContactResponse {
                force: SVector::zeros(),
                spring_force: SVector::zeros(),
                regime: Regime::Open,
                state: SpringState::default(),
            };
            return (open, Tangent::zeros());
        }
        let shear = shear_step(&self.strength, k_s, &state.spring.0, &du, e_n, k_n);
        let mut spring = shear.force;
        spring[0] = e_n;
        let mut tangent = shear.tangent;
        tangent[(0, 0)] = k_n;
        let response = ContactResponse {
            force: spring,
            spring_force: spring,
            regime: shear.regime,
            state: SpringState {
                spring: SpringVector(spring),
            },
        };
        (response, tangent)
    }
}

impl ContactLaw<3> for MohrCoulombSpring {
    type State = SpringState<3>;

    fn evaluate(
        &self,
        input: &ContactInput<3>,
        state: &Self::State,
    ) -> ContactResponse<3, Self::State> {
        self.respond(input, state).0
    }

    /// The slip spring follows its own displacement history (its normal
    /// spring is `k_n` times the accumulated normal displacement), not the
    /// overlap given.
    fn opens_without_overlap(&self) -> bool {
        false
    }
}

impl TangentLaw<3> for MohrCoulombSpring {
    fn evaluate_with_tangent(
        &self,
        input: &ContactInput<3>,
        state: &Self::State,
    ) -> (ContactResponse<3, Self::State>, Tangent<3>) {
        self.respond(input, state)
    }
}

impl StrengthLaw for MohrCoulombSpring {
    fn strength(&self) -> Strength {
        self.strength
    }
}

impl BoundedStiffness<3> for MohrCoulombSpring {
    fn stiffness_bound(&self, _pair: &PairProperties, _overlap: f64) -> StiffnessBound {
        StiffnessBound {
            normal: self.normal_stiffness,
            shear: self.shear_stiffness,
            normal_damping: 0.0,
            shear_damping: 0.0,
            rolling: 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mohr_coulomb_spring_caps_shear_at_cohesion_plus_friction_and_opens_in_tension() {
        let law = MohrCoulombSpring::new(10.0, 5.0, 2.0, 0.5).unwrap();
        // Stick: within the limit 2 + 0.5·10 = 7.
        let r = law.evaluate_total([1.0, 0.6, 0.8]);
        assert_eq!(r.regime, Regime::Stick);
        assert_eq!(r.force, SVector::from([10.0, 3.0, 4.0]));
        // Slip: trial shear 15 capped to 7 along the trial direction.
        let r = law.evaluate_total([1.0, 1.8, 2.4]);
        assert_eq!(r.regime, Regime::Slip);
        assert!((r.force[1].hypot(r.force[2]) - 7.0).abs() < 1e-12);
        assert!((r.force[1] / r.force[2] - 0.75).abs() < 1e-12);
        // Opened beyond c / k_n = 0.2: nothing carried, cohesion included.
        for opening in [0.2, 0.3] {
            let r = law.evaluate_total([-opening, 0.1, 0.0]);
            assert_eq!(r.regime, Regime::Open);
            assert_eq!(r.force, SVector::<f64, 3>::zeros());
        }
        assert!(MohrCoulombSpring::new(1.0, 1.0, -1.0, 0.5).is_err());
    }

    #[test]
    fn an_opening_spring_loses_its_cohesion_over_c_over_k_n_continuously() {
        let (k_n, c) = (10.0, 2.0);
        let law = MohrCoulombSpring::new(k_n, 5.0, c, 0.5).unwrap();
        // Opened by 0.1 (trial tension 1): open, no normal traction, the
        // shear capped at c − 1 = 1; a smaller shear is kept whole.
        let r = law.evaluate_total([-0.1, 1.8, 2.4]);
        assert_eq!(r.regime, Regime::Open);
        assert_eq!(r.force[0], 0.0);
        assert!((r.force[1].hypot(r.force[2]) - 1.0).abs() < 1e-12);
        assert!((r.force[1] / r.force[2] - 0.75).abs() < 1e-12);
        let r = law.evaluate_total([-0.1, 0.06, 0.08]);
        assert_eq!(r.regime, Regime::Open);
        assert_eq!(r.force, SVector::from([0.0, 0.3, 0.4]));
        // The force is continuous in the normal displacement: at closing
        // (the cap c) and at c / k_n (nothing), for a shear beyond the cap.
        let shear = |du_n: f64| law.evaluate_total([du_n, 1.8, 2.4]).force;
        let h = 1e-12;
        assert!(
            (shear(h) - shear(-h)).norm() < 1e-10,
            "{} vs {}",
            shear(h),
            shear(-h)
        );
        assert!((shear(h)[1].hypot(shear(h)[2]) - c).abs() < 1e-10);
        let edge = -c / k_n;
        assert!((shear(edge + h) - shear(edge - h)).norm() < 1e-10);
        assert_eq!(shear(edge - h), SVector::<f64, 3>::zeros());
    }

    #[test]
    fn mohr_coulomb_tangent_matches_finite_differences_in_slip() {
        let law = MohrCoulombSpring::new(10.0, 5.0, 2.0, 0.5).unwrap();
        // Closed, and opening (normal displacement −0.1 of the 0.2 over
        // which the cohesion is lost), each slipping and sticking.
        for du in [
            [1.0, 1.8, -2.4],
            [1.0, 0.06, -0.08],
            [-0.1, 1.8, -2.4],
            [-0.1, 0.06, -0.08],
        ] {
            let (r, tangent) = law.evaluate_with_tangent(
                &MohrCoulombSpring::total_input(du),
                &SpringState::default(),
            );
            let h = 1e-7;
            for j in 0..3 {
                let mut p = du;
                p[j] += h;
                let f = law.evaluate_total(p).force;
                for i in 0..3 {
                    let fd = (f[i] - r.force[i]) / h;
                    assert!(
                        (fd - tangent[(i, j)]).abs() < 1e-5,
                        "{du:?} ({i},{j}): {fd} vs {}",
                        tangent[(i, j)]
                    );
                }
            }
        }
    }
}
