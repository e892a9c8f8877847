//! The linear spring + dashpot + Coulomb slip law of paper 000 (Katsuki &
//! Ishikawa 1990, eqs. 14–19), after Cundall's DEM.
//!
//! Per step, with increments `Δu_n` (approach) and `Δu_s` (shear):
//!
//! * normal: `e_n ← e_n + k_n Δu_n`, `d_n = η_n Δu_n / Δt`, `f_n = e_n + d_n`
//!   (eq. 14);
//! * shear: `e_s ← e_s + k_s Δu_s`, `d_s = η_s Δu_s / Δt`, `f_s = e_s + d_s`
//!   (eq. 16);
//! * no tension: if `e_n < 0` every force and spring is zero (eqs. 15, 17);
//!   in addition the dashpot may not pull: `f_n = max(e_n + d_n, 0)` (the
//!   paper lets a fast-opening dashpot pull; we do not);
//! * slip: if `|e_s| > μ e_n`, `e_s = μ e_n sign(e_s)` and `d_s = 0` (eq. 18);
//! * stiffness: either a constant `k_n`, or eq. (19)
//!   `k_n = π E / (2 (1 − ν²) {2/3 + ln(4 r1/B) + ln(4 r2/B)})` with the radii
//!   of curvature r1, r2 at the contact and the contact width B;
//!   `k_s = s k_n`, `η_n = 2 √(m k_n)`, `η_s = η_n √s`.
//!
//! Besides the paper's critical dashpots, [`Damping::PerMass`] gives the
//! dashpots of LAMMPS' `gran/hooke/history` (`η = m_eff γ`, with the
//! effective mass `m_eff = m_a m_b / (m_a + m_b)`), so that a DEM run can
//! be set up as the common codes set theirs up. The rest of the law is
//! unchanged: the dashpots act in the normal direction and, while the
//! contact sticks, in shear (LAMMPS keeps the shear dashpot in slip, inside
//! the capped force; here slip drops it, as eq. 18 says).
//!
//! Choices where the paper is silent, stated here and in the reproduction
//! report:
//! * `m` in `η_n` is the smaller of the two masses (the particle's own mass
//!   for a wall contact);
//! * a flat wall has no finite radius and eq. (19) would give `k_n → 0`; the
//!   wall takes the radius of the particle it touches (the mirror-image
//!   particle);
//! * `B` is bounded below by `min_width_ratio × min(r1, r2)` (default 1e-3)
//!   and above by `2 min(r1, r2)`, so that the logarithms stay finite.
//!
//! For D = 3 the shear part is a 2-vector and the slip cap scales it to
//! `‖e_s‖ = μ e_n`.

use nalgebra::SVector;

use super::coulomb::shear_step;
use super::traits::{
    BoundedStiffness, ContactInput, ContactLaw, ContactResponse, PairProperties, Regime,
    StiffnessBound, Strength, StrengthLaw, Tangent, TangentLaw,
};
use crate::error::{require_non_negative, require_positive, DismechError, Result};

/// How the normal stiffness is obtained.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub enum NormalStiffness {
    /// A constant `k_n` (N/m per m).
    Constant(f64),
    /// Paper 000 eq. (19), from Young's modulus `E` (Pa), Poisson's ratio
    /// `ν`, the radii of curvature and the contact width.
    ContactWidth {
        /// Young's modulus E (Pa).
        youngs_modulus: f64,
        /// Poisson's ratio ν.
        poisson_ratio: f64,
        /// Lower bound of B as a fraction of the smaller radius.
        min_width_ratio: f64,
    },
}

/// Dashpots of the law.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub enum Damping {
    /// No dashpots (elastic contact).
    None,
    /// `η_n = 2 √(m k_n)`, `η_s = η_n √s` (paper 000 eq. 19).
    Critical,
    /// Dashpots proportional to the effective mass of the pair,
    /// `η_n = m_eff γ_n`, `η_s = m_eff γ_s`, with
    /// `m_eff = m_a m_b / (m_a + m_b)` (the particle's own mass for a
    /// wall): LAMMPS' `gran/hooke` damping, whose `γ` are in 1/s.
    PerMass {
        /// `γ_n` (1/s).
        normal: f64,
        /// `γ_s` (1/s); LAMMPS' default is `γ_n / 2`.
        shear: f64,
    },
}

/// The effective mass `m_a m_b / (m_a + m_b)` of a pair; a wall's (or any
/// body's) infinite mass leaves the other's own.
pub fn effective_mass(mass_a: f64, mass_b: f64) -> f64 {
    if mass_b.is_infinite() {
        mass_a
    } else if mass_a.is_infinite() {
        mass_b
    } else {
        mass_a * mass_b / (mass_a + mass_b)
    }
}

/// The spring–dashpot–Coulomb law of paper 000.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SpringDashpotCoulomb {
    normal: NormalStiffness,
    stiffness_ratio: f64,
    friction: f64,
    damping: Damping,
}

/// History of a spring–dashpot contact: the spring forces `e_n`, `e_s`.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct SpringState<const D: usize> {
    /// Spring forces `[e_n, e_s, (e_t)]`.
    pub spring: SpringVector<D>,
}

/// A `D`-vector with a `Default` of zeros.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SpringVector<const D: usize>(pub SVector<f64, D>);

impl<const D: usize> Default for SpringVector<D> {
    fn default() -> Self {
        Self(SVector::zeros())
    }
}

impl SpringDashpotCoulomb {
    /// A law with the given normal stiffness, ratio `s = k_s / k_n`,
    /// friction coefficient `μ` and dashpots. Validates every value.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming the value for a constant
    /// `k_n`, a Young's modulus or a stiffness ratio that is not finite and
    /// positive, a Poisson's ratio that is not finite or outside
    /// `[−1, 0.5)`, a `min_width_ratio` outside `(0, 1)`, or a friction
    /// coefficient or (per-mass) damping rate that is negative or not
    /// finite.
    pub fn new(
        normal: NormalStiffness,
        stiffness_ratio: f64,
        friction: f64,
        damping: Damping,
    ) -> Result<Self> {
        match normal {
            NormalStiffness::Constant(k) => {
                require_positive("normal stiffness k_n", k)?;
            }
            NormalStiffness::ContactWidth {
                youngs_modulus,
                poisson_ratio,
                min_width_ratio,
            } => {
                require_positive("Young's modulus E", youngs_modulus)?;
                if !(poisson_ratio.is_finite() && (-1.0..0.5).contains(&poisson_ratio)) {
                    return Err(DismechError::InvalidParameter {
                        name: "Poisson's ratio",
                        value: poisson_ratio,
                        requirement: "must lie in [-1, 0.5)",
                    });
                }
                if !(min_width_ratio.is_finite() && min_width_ratio > 0.0 && min_width_ratio < 1.0)
                {
                    return Err(DismechError::InvalidParameter {
                        name: "min_width_ratio",
                        value: min_width_ratio,
                        requirement: "must lie in (0, 1)",
                    });
                }
            }
        }
        require_positive("stiffness ratio s", stiffness_ratio)?;
        require_non_negative("friction coefficient mu", friction)?;
        if let Damping::PerMass { normal, shear } = damping {
            require_non_negative("normal damping gamma_n (1/s)", normal)?;
            require_non_negative("shear damping gamma_s (1/s)", shear)?;
        }
        Ok(Self {
            normal,
            stiffness_ratio,
            friction,
            damping,
        })
    }

    /// Paper 000's law: eq. (19) stiffness, critical dashpots.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming the value for a Young's
    /// modulus or stiffness ratio that is not finite and positive, a
    /// Poisson's ratio that is not finite or outside `[−1, 0.5)`, or a
    /// friction coefficient that is negative or not finite.
    pub fn katsuki(
        youngs_modulus: f64,
        poisson_ratio: f64,
        stiffness_ratio: f64,
        friction: f64,
    ) -> Result<Self> {
        Self::new(
            NormalStiffness::ContactWidth {
                youngs_modulus,
                poisson_ratio,
                min_width_ratio: 1e-3,
            },
            stiffness_ratio,
            friction,
            Damping::Critical,
        )
    }

    /// Friction coefficient μ.
    pub fn friction(&self) -> f64 {
        self.friction
    }

    /// Normal stiffness `k_n` for a pair (eq. 19 or the constant).
    #[inline]
    pub fn normal_stiffness(&self, pair: &PairProperties) -> f64 {
        match self.normal {
            NormalStiffness::Constant(k) => k,
            NormalStiffness::ContactWidth {
                youngs_modulus,
                poisson_ratio,
                min_width_ratio,
            } => {
                // (Given, as this law says it reads them: NaN here would
                // pass silently, `max` dropping it.)
                debug_assert!(
                    ![pair.width, pair.curvature_radius_a, pair.curvature_radius_b]
                        .iter()
                        .any(|v| v.is_nan()),
                    "the contact-width stiffness needs the width and the radii of curvature"
                );
                let (r1, r2) = effective_radii(pair);
                let r_min = r1.min(r2);
                let width = pair.width.max(min_width_ratio * r_min).min(2.0 * r_min);
                width_stiffness(youngs_modulus, poisson_ratio, r1, r2, width)
            }
        }
    }

    #[inline]
    fn damping_coefficients(&self, k_n: f64, pair: &PairProperties) -> (f64, f64) {
        match self.damping {
            Damping::None => (0.0, 0.0),
            Damping::Critical => {
                let m = pair.mass_a.min(pair.mass_b);
                let eta_n = 2.0 * (m * k_n).sqrt();
                (eta_n, eta_n * self.stiffness_ratio.sqrt())
            }
            Damping::PerMass { normal, shear } => {
                let m = effective_mass(pair.mass_a, pair.mass_b);
                (m * normal, m * shear)
            }
        }
    }
}

/// Eq. (19) of paper 000.
fn width_stiffness(e: f64, nu: f64, r1: f64, r2: f64, width: f64) -> f64 {
    let denom = 2.0 / 3.0 + (4.0 * r1 / width).ln() + (4.0 * r2 / width).ln();
    std::f64::consts::PI * e / (2.0 * (1.0 - nu * nu) * denom)
}

/// Radii of curvature with a flat surface replaced by the other body's.
fn effective_radii(pair: &PairProperties) -> (f64, f64) {
    let (a, b) = (pair.curvature_radius_a, pair.curvature_radius_b);
    match (a.is_finite(), b.is_finite()) {
        (true, true) => (a, b),
        (true, false) => (a, a),
        (false, true) => (b, b),
        (false, false) => (1.0, 1.0),
    }
}

impl SpringDashpotCoulomb {
    /// One evaluation with its consistent tangent.
    #[inline]
    fn respond<const D: usize>(
        &self,
        input: &ContactInput<D>,
        state: &SpringState<D>,
    ) -> (ContactResponse<D, SpringState<D>>, Tangent<D>) {
        let open = ContactResponse {
            force: SVector::zeros(),
            spring_force: SVector::zeros(),
            regime: Regime::Open,
            state: SpringState::default(),
        };
        if input.overlap <= 0.0 {
            return (open, Tangent::zeros());
        }
        let k_n = self.normal_stiffness(&input.pair);
        let k_s = self.stiffness_ratio * k_n;
        let (eta_n, eta_s) = self.damping_coefficients(k_n, &input.pair);
        let du = input.increment;
        let elastic_normal_increment = if input.is_new { input.overlap } else { du[0] };
        let e_n = state.spring.0[0] + k_n * elastic_normal_increment;
        if e_n < 0.0 {
            return (open, Tangent::zeros());
        }
        let rate = 1.0 / input.dt;
        let d_n = eta_n * du[0] * rate;
        // The dashpot may not pull the surfaces together.
        let f_n = (e_n + d_n).max(0.0);
        let normal_tangent = if e_n + d_n > 0.0 {
            k_n + eta_n * rate
        } else {
            0.0
        };

        // Shear: the Coulomb core (eq. 18); no shear dashpot in slip.
        let strength = Strength {
            cohesion: 0.0,
            friction: self.friction,
        };
        let shear = shear_step(&strength, k_s, &state.spring.0, &du, e_n, k_n);
        let mut spring = shear.force;
        let mut force = shear.force;
        let mut tangent = shear.tangent;
        spring[0] = e_n;
        force[0] = f_n;
        tangent[(0, 0)] = normal_tangent;
        if shear.regime == Regime::Stick {
            for i in 1..D {
                force[i] = spring[i] + eta_s * du[i] * rate;
                tangent[(i, i)] = k_s + eta_s * rate;
            }
        }
        let response = ContactResponse {
            force,
            spring_force: spring,
            regime: shear.regime,
            state: SpringState {
                spring: SpringVector(spring),
            },
        };
        (response, tangent)
    }
}

impl<const D: usize> ContactLaw<D> for SpringDashpotCoulomb {
    type State = SpringState<D>;

    #[inline]
    fn evaluate(
        &self,
        input: &ContactInput<D>,
        state: &SpringState<D>,
    ) -> ContactResponse<D, SpringState<D>> {
        self.respond(input, state).0
    }

    /// Only the stiffness of eq. (19) reads the width and the radii.
    fn uses_contact_shape(&self) -> bool {
        matches!(self.normal, NormalStiffness::ContactWidth { .. })
    }
}

impl<const D: usize> TangentLaw<D> for SpringDashpotCoulomb {
    fn evaluate_with_tangent(
        &self,
        input: &ContactInput<D>,
        state: &SpringState<D>,
    ) -> (ContactResponse<D, SpringState<D>>, Tangent<D>) {
        self.respond(input, state)
    }
}

impl StrengthLaw for SpringDashpotCoulomb {
    fn strength(&self) -> Strength {
        Strength {
            cohesion: 0.0,
            friction: self.friction,
        }
    }
}

impl<const D: usize> BoundedStiffness<D> for SpringDashpotCoulomb {
    /// For eq. (19), the largest `k_n` is reached at the largest contact
    /// width, `B = 2 min(r1, r2)`, whatever the overlap.
    fn stiffness_bound(&self, pair: &PairProperties, _overlap: f64) -> StiffnessBound {
        let widest = PairProperties {
            width: f64::INFINITY,
            ..*pair
        };
        let k_n = self.normal_stiffness(&widest);
        let (eta_n, eta_s) = self.damping_coefficients(k_n, pair);
        StiffnessBound {
            normal: k_n,
            shear: self.stiffness_ratio * k_n,
            normal_damping: eta_n,
            shear_damping: eta_s,
            rolling: 0.0,
        }
    }
}
