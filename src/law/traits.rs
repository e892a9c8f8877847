//! What a contact law is given, what it returns, and the capabilities a law
//! may have: a force ([`ContactLaw`]), a consistent tangent
//! ([`TangentLaw`]), a linear strength ([`StrengthLaw`]) and a stiffness
//! bound for the explicit stable step ([`BoundedStiffness`]).
//!
//! A driver states in its trait bounds which capabilities it needs, so a
//! law missing one is a compile error, not a run-time surprise:
//!
//! | driver | needs |
//! |---|---|
//! | explicit dynamics | [`ContactLaw`] + [`BoundedStiffness`] (or an explicit opt-out of the stability check) |
//! | implicit dynamics | [`TangentLaw`] |
//! | limit analysis | [`StrengthLaw`] |

use nalgebra::{SMatrix, SVector};

/// What a law needs to know about the pair, besides the motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairProperties {
    /// Radius of curvature of A at the contact (m; infinite for a flat
    /// wall). May be NaN for a law that does not
    /// [`ContactLaw::uses_contact_shape`].
    pub curvature_radius_a: f64,
    /// Radius of curvature of B at the contact (NaN as
    /// `curvature_radius_a`).
    pub curvature_radius_b: f64,
    /// Contact width B (m), e.g. the chord P1P2 of paper 000 (NaN as
    /// `curvature_radius_a`).
    pub width: f64,
    /// Mass of A (kg/m in 2D; infinite for a fixed wall).
    pub mass_a: f64,
    /// Mass of B.
    pub mass_b: f64,
}

impl PairProperties {
    /// A pair of flat rigid surfaces of infinite mass: for laws that use
    /// neither curvature nor mass (penalty laws, slip springs).
    pub fn rigid() -> Self {
        Self {
            curvature_radius_a: f64::INFINITY,
            curvature_radius_b: f64::INFINITY,
            width: 0.0,
            mass_a: f64::INFINITY,
            mass_b: f64::INFINITY,
        }
    }
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
    /// Rotation of A relative to B over the step (rad, counter-clockwise;
    /// `Δθ_A − Δθ_B`, a wall not turning): what a rolling resistance
    /// resists. 2D only: a driver without rotations (the 3D columns, the
    /// implicit driver, whose tangent has no rotational coupling) passes
    /// 0.
    pub rotation: f64,
}

/// The state a contact is in after an evaluation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum Regime {
    /// No normal force: separated, or a tension was released. A cohesive
    /// law may still carry the rest of its cohesion in shear while it
    /// opens ([`super::MohrCoulombSpring`], over an opening of `c / k_n`);
    /// every other law carries nothing.
    Open,
    /// Elastic in shear (DDA "LOCK").
    Stick,
    /// Sliding on the Coulomb limit (DDA "CLOSE" in slip).
    Slip,
}

/// The result of one evaluation.
///
/// `force[0]` is the compressive normal force (≥ 0 for a law without
/// tension) and `force[1..]` the shear force resisting the relative
/// tangential motion: the force on B is `force[0] n − force[1] t` and A
/// receives the opposite.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactResponse<const D: usize, S> {
    /// Local force components (see above).
    pub force: SVector<f64, D>,
    /// Spring (elastic) part of `force`, without dashpots.
    pub spring_force: SVector<f64, D>,
    /// Open, stick or slip.
    pub regime: Regime,
    /// The history state to keep if the step is accepted.
    pub state: S,
}

/// The consistent tangent `∂force/∂increment` of one evaluation
/// (unsymmetric in slip). Derivatives with respect to the approach
/// `Δu_n` take the overlap as moving with it (`∂overlap/∂Δu_n = 1`), as it
/// does when a driver varies the bodies' motion.
pub type Tangent<const D: usize> = SMatrix<f64, D, D>;

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

impl Strength {
    /// The shear the contact can carry under the normal force `normal`:
    /// `c + μ t_n` (written `c + μ t_n` so that `c = 0` gives `μ t_n`
    /// exactly).
    #[inline]
    pub fn limit(&self, normal: f64) -> f64 {
        self.cohesion + self.friction * normal
    }
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
    /// Rolling stiffness on the relative rotation of the two bodies
    /// (N·m/rad per m), for a law that exerts a moment
    /// ([`ContactLaw::moment`]); 0 for one that exerts none. The explicit
    /// driver bounds the rotation mode with it and the particle's
    /// inertia, at the particle's largest radius of curvature (an
    /// ellipse's `a²/b`).
    pub rolling: f64,
}

/// A constitutive law for one contact: relative motion and history to
/// force.
///
/// `evaluate` is a pure function of the input and the previous state: the
/// caller keeps the returned state only when the step is accepted, so that
/// implicit methods can evaluate trial states freely. A law is shared by
/// the threads that evaluate a step's contacts, hence `Sync`.
pub trait ContactLaw<const D: usize>: Sync {
    /// History carried from step to step (spring forces, elastic slip).
    type State: Clone + Default + std::fmt::Debug + Send + Sync;

    /// Force and new state for one step.
    fn evaluate(
        &self,
        input: &ContactInput<D>,
        state: &Self::State,
    ) -> ContactResponse<D, Self::State>;

    /// Whether the force depends on the width or the radii of curvature
    /// of [`PairProperties`]. A law that answers `false` may be given NaN
    /// there: a driver then spares the geometry that costs them (a circle
    /// pair's width, an ellipse pair's two radii, about a tenth of its
    /// contact).
    fn uses_contact_shape(&self) -> bool {
        true
    }

    /// Whether contact is found by the overlap: without overlap the law
    /// gives no force and the regime `Open` (checked by
    /// [`super::conformance::open_without_overlap`]). A bonded contact,
    /// which pulls when apart, or a spring that follows its own
    /// displacement history rather than the overlap answers `false`.
    fn opens_without_overlap(&self) -> bool {
        true
    }

    /// The rolling moment on A about the out-of-plane axis (N·m per m,
    /// counter-clockwise; B receives the opposite) of a contact whose
    /// history is `state`, beside the moments of its force about the two
    /// centres: 0 for a law without rolling resistance (the default).
    ///
    /// A law with rolling resistance ([`super::RollingResistance`]) keeps
    /// its moment in its history, as a spring keeps its force, and the
    /// explicit driver reads it from the state of each evaluation: so a
    /// contact of a law without one stores nothing more. Only the
    /// explicit 2D driver applies it; the implicit driver's tangent has no
    /// rotational coupling, and a [`TangentLaw`] answers 0
    /// ([`super::conformance::no_moment_with_tangent`]).
    fn moment(&self, state: &Self::State) -> f64 {
        let _ = state;
        0.0
    }
}

/// A law with a consistent tangent, as implicit (Newton) drivers need.
pub trait TangentLaw<const D: usize>: ContactLaw<D> {
    /// Force, new state and the tangent `∂force/∂increment` of one step.
    /// The response equals [`ContactLaw::evaluate`]'s.
    fn evaluate_with_tangent(
        &self,
        input: &ContactInput<D>,
        state: &Self::State,
    ) -> (ContactResponse<D, Self::State>, Tangent<D>);

    /// Whether the force is an implicit function of the step's motion with
    /// this tangent as its exact derivative, so that Newton converges on
    /// it. A law integrated explicitly within a step (DDA's conventional
    /// friction) answers `false`: an implicit driver then accepts a step
    /// once the open/closed states settle, as classic DDA does.
    fn is_consistent(&self) -> bool {
        true
    }
}

/// A law with a linear strength `|t_s| ≤ c + μ t_n`, as a limit analysis
/// needs (the LP's admissible set).
pub trait StrengthLaw {
    /// The strength.
    fn strength(&self) -> Strength;

    /// Whether the contact may open (carries no tension). A bilateral
    /// contact (cohesive, never opening) answers `false`.
    fn may_open(&self) -> bool {
        true
    }
}

/// A law whose stiffness and damping are bounded for a pair, so that the
/// explicit scheme's stable step can be estimated.
///
/// The bound may grow with the overlap (a Hertzian `k_n ∝ √δ`): the
/// explicit driver asks for it at the largest overlap it assumes,
/// [`crate::explicit::DemSettings::stability_overlap`] of a particle's
/// bounding radius, and checks during a run that the overlaps stay
/// within it ([`crate::explicit::ExplicitDynamics::check_overlap_stability`]).
pub trait BoundedStiffness<const D: usize>: ContactLaw<D> {
    /// Upper bounds of stiffness and damping for the pair at every
    /// overlap up to `overlap` (m). A linear law ignores `overlap`.
    fn stiffness_bound(&self, pair: &PairProperties, overlap: f64) -> StiffnessBound;
}
