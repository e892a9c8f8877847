//! The [`ContactLaw`] trait: relative motion at a contact → contact force.

use nalgebra::{SMatrix, SVector};

/// What a law needs to know about the pair, besides the motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairProperties {
    /// Radius of curvature of A at the contact (m; infinite for a flat wall).
    pub curvature_radius_a: f64,
    /// Radius of curvature of B at the contact.
    pub curvature_radius_b: f64,
    /// Contact width B (m), e.g. the chord P1P2 of paper 000.
    pub width: f64,
    /// Mass of A (kg/m in 2D; infinite for a fixed wall).
    pub mass_a: f64,
    /// Mass of B.
    pub mass_b: f64,
}

/// One evaluation of a law: the state of the contact and the step's motion.
///
/// `D` is the dimension of the local frame: 2 in 2D (normal, tangent), 3 for
/// the slip springs of a 3D column (normal and two tangents). Component 0 is
/// always the normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactInput<const D: usize> {
    /// Current penetration (m): positive when the surfaces overlap.
    pub overlap: f64,
    /// Relative displacement increment of B with respect to A over the step,
    /// local components: `[Δu_n (positive approaching), Δu_s, (Δu_t)]`.
    pub increment: SVector<f64, D>,
    /// Time step (s); used by rate terms (dashpots). Quasi-static callers
    /// pass any positive value and a law without rate terms ignores it.
    pub dt: f64,
    /// `true` on the first step of a contact: the law then takes the
    /// current overlap as the normal elastic increment, so that a contact
    /// that began part-way through the step does not count the approach
    /// made before touching.
    pub is_new: bool,
    /// Geometry and masses of the pair.
    pub pair: PairProperties,
}

/// The state a contact is in after an evaluation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Regime {
    /// No force: separated, or a tension was released.
    Open,
    /// Elastic in shear (DDA "LOCK").
    Stick,
    /// Sliding on the Coulomb limit (DDA "CLOSE" in slip).
    Slip,
}

/// The result of one evaluation.
///
/// `force[0]` is the compressive normal force (≥ 0) and `force[1..]` the
/// shear force resisting the relative tangential motion: the force on B is
/// `force[0] n − force[1] t` and A receives the opposite.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactResponse<const D: usize, S> {
    /// Local force components (see above).
    pub force: SVector<f64, D>,
    /// Spring (elastic) part of `force`, without dashpots.
    pub spring_force: SVector<f64, D>,
    /// Consistent tangent `∂force/∂increment`; unsymmetric in slip.
    pub tangent: SMatrix<f64, D, D>,
    /// Open, stick or slip.
    pub regime: Regime,
    /// The history state to keep if the step is accepted.
    pub state: S,
}

/// Linear strength of a contact, `|t_s| ≤ cohesion + friction · t_n`: the
/// admissible set a limit analysis (LP) imposes, and the yield function of a
/// return mapping.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Strength {
    /// Cohesion (N, or N/m in 2D per unit thickness).
    pub cohesion: f64,
    /// Friction coefficient μ = tan φ.
    pub friction: f64,
}

/// The largest stiffnesses and dashpots a law may show for a pair; the
/// explicit scheme's stable time step follows from them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StiffnessBound {
    /// Normal stiffness (N/m per m).
    pub normal: f64,
    /// Shear stiffness.
    pub shear: f64,
    /// Normal dashpot (N·s/m per m).
    pub normal_damping: f64,
    /// Shear dashpot.
    pub shear_damping: f64,
}

/// A constitutive law for one contact.
///
/// `evaluate` is a pure function of the input and the previous state: the
/// caller keeps the returned state only when the step is accepted, so that
/// implicit methods can evaluate trial states freely.
pub trait ContactLaw<const D: usize> {
    /// History carried from step to step (spring forces, elastic slip).
    type State: Clone + Default + std::fmt::Debug + Send + Sync;

    /// Force, tangent and new state for one step.
    fn evaluate(
        &self,
        input: &ContactInput<D>,
        state: &Self::State,
    ) -> ContactResponse<D, Self::State>;

    /// The law's linear strength, if it has one.
    fn strength(&self) -> Option<Strength> {
        None
    }

    /// Upper bounds of stiffness and damping for the pair, for the explicit
    /// stability limit; `None` for laws without springs (rigid-plastic).
    fn stiffness_bound(&self, _pair: &PairProperties) -> Option<StiffnessBound> {
        None
    }
}
