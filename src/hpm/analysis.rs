//! Elastic and nonlinear HPM analyses of a slope model, and what they give:
//! the slip-spring tractions, the global and local safety factors, surface
//! displacements and surface principal strains (paper 001, §5).
//!
//! * **Elastic**: one sparse Cholesky solve of eq. (4); the slip springs
//!   are linear and may carry tension. The result reports the solve's true
//!   relative residual `‖F − K U‖ / ‖F‖`, recomputed from U, and is
//!   [`Convergence::Converged`] only when it is at most
//!   [`EQUILIBRIUM_TOLERANCE`] (and an iterative solver met its own
//!   criterion).
//! * **Nonlinear**: the slip springs follow [`MohrCoulombSpring`] (c, φ,
//!   return mapping, no tension, an opening spring's cohesion lost over an
//!   opening of `c / k_n`). The global equations are solved by the
//!   initial-stiffness method with Aitken's relaxation: the elastic
//!   stiffness, factorised once, is applied to the out-of-balance force
//!   `F − F_int(U)` and the correction scaled by Aitken's factor until
//!   `‖F − F_int‖ ≤ tol ‖F‖` (Euclidean norms over all DOFs); the load is
//!   applied in one step. A run that does not reach the tolerance within
//!   the iteration limit reports [`Convergence::NotConverged`] with its
//!   last residual: there is no equilibrium it could find. A residual that
//!   is not finite (NaN, infinite) stops the iteration at once and is never
//!   converged.
//!
//! A result that is not converged lists what in the model may spoil the
//! solve ([`HpmResult::ill_conditioning`], from
//! [`HpmModel::ill_conditioning`]), each with what to change; a
//! factorization that fails on such a model is a
//! [`HpmError::IllConditioned`] naming them.
//!
//! **Safety factors.** The paper states Fs for each run (§5, Table 2) but
//! not its formula; two definitions are offered.
//!
//! * *Stress ratio* ([`HpmResult::safety_factor`], the usual definition for
//!   spring methods): `Fs = Σ (c + σ tan φ) A / Σ |τ| A` over all slip
//!   springs, and the local factor of a column the same ratio over the
//!   springs under it; σ is the normal traction (compression positive) and
//!   `|τ| = √(τ_s² + τ_t²)`. Every spring's shear counts as driving,
//!   whatever its direction.
//! * *Along the sliding direction* ([`HpmResult::sliding_safety_factor`]):
//!   `Fs = Σ (c + σ tan φ) A / Σ (τ · d_i) A`, where `τ = τ_s s + τ_t t` is
//!   the shear traction vector of a spring and `d_i` the unit tangent of
//!   the slip surface at the spring whose plan projection points along one
//!   horizontal sliding direction `ĥ` of the whole slide (the tangent plane
//!   cut by the vertical plane through `ĥ`). `ĥ` is the plan direction of
//!   the resultant shear force `Σ τ A` of the springs. This is the
//!   assumption of Hovland's column method (ref. 1; [`crate::hpm::hovland()`]):
//!   the slide moves as one body in one plan direction, and only the shear
//!   along it drives; shear across it (which the springs carry where the
//!   slide is squeezed laterally on a curved surface) resists nothing and
//!   drives nothing. Since `τ · d_i ≤ |τ|`, this Fs is never below the
//!   stress ratio. On a plane every `d_i` is the same `d`, so the
//!   denominator is `(Σ τ A) · d`, the driving component of the resultant
//!   the slide's equilibrium fixes: both definitions reduce to the exact
//!   `(cA + N tan φ) / T` of a planar slab when the springs carry the
//!   load along d (tested in `tests/hpm_exact.rs`).
//!
//! Either Fs is a ratio of the strength the slip surface offers to the
//! shear that drives the slide, so it is given only where something drives
//! it: the horizontal part of the springs' resultant shear force `Σ τ A`
//! (which balances the horizontal loads and the horizontal push of the
//! slip surface) above [`MIN_DRIVING_RATIO`] of the slide's weight, and for
//! the second definition the shear along the direction too. On a level
//! slip surface without seismic load or seepage force that resultant is
//! rounding alone: the
//! springs still carry shear (the soil squeezed over the surface), which
//! would make the stress ratio a finite number (9.07 for a 6 m slab of
//! 3 × 4 cells on level ground) while Hovland's Fs is infinite, and the Fs
//! along the sliding direction 2.6e14 (a direction of rounding); none of
//! them means anything, and
//! both are refused with [`HpmError::NothingDrivesSliding`] naming the
//! driving force and the weight. The local factors
//! ([`HpmResult::local_safety_factors`]) stay the stress ratio of each
//! column, a measure of the strength mobilised there.
//!
//! **Tension.** The strength `c + σ tan φ` of Mohr–Coulomb has its apex at
//! `σ = −c / tan φ`; the elastic analysis' linear slip springs carry any
//! tension, and beyond the apex their term in `Σ (c + σ tan φ) A` is
//! negative. The sum is kept as the definition reads (the paper's slopes
//! have such springs under the crest, statically too: 3 % of the
//! representative slope's springs, whose Fs the reproduction compares
//! with the paper's), but where it is not positive, as under a seismic
//! coefficient that lifts the slide off the surface, the ratio would be
//! zero or negative, which is no factor of safety: every Fs is refused
//! there with [`HpmError::SlipSurfaceInTension`], naming the columns
//! in tension beyond the apex and their share of the area (Hovland's Fs
//! likewise, column by column). A local factor is 0 where the column's
//! strength is not positive. The nonlinear analysis' springs carry no
//! tension, so its strength is at least `c A`.

use nalgebra::Vector3;

use super::conditioning::IllConditioning;
use super::error::HpmError;
use super::material::Seismic;
use super::model::{HpmModel, MemoryParts, SlipSpring};
use super::stiffness::BlockMatrix;
use crate::error::{DismechError, Result};
use crate::kinematics::affine3::{displacement_at, strain_tensor, ElementDofs, ELEMENT_DOF};
use crate::law::{MohrCoulombSpring, Regime, Strength};
use crate::linsolve::{
    AggregationSettings, BlockJacobi, CgSettings, ConjugateGradient, LineLevel, LinearSolver,
    SmoothedAggregation, SolveStats, SparseCholesky,
};
use crate::observe::{Event, Observer, Unobserved};

/// Relative out-of-balance force `‖F − F_int‖ / ‖F‖` accepted as
/// equilibrium: by the elastic analysis always, by the nonlinear one by
/// default ([`NonlinearSettings::tolerance`]).
pub const EQUILIBRIUM_TOLERANCE: f64 = 1e-6;

/// Iteration limits of the nonlinear solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NonlinearSettings {
    /// Relative out-of-balance force accepted as equilibrium.
    pub tolerance: f64,
    /// Iteration limit.
    pub max_iterations: usize,
}

impl Default for NonlinearSettings {
    /// `tol =` [`EQUILIBRIUM_TOLERANCE`] (`1e-6`), 3000 iterations.
    fn default() -> Self {
        Self {
            tolerance: EQUILIBRIUM_TOLERANCE,
            max_iterations: 3000,
        }
    }
}

impl NonlinearSettings {
    /// Check the values; errors name the field.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for a tolerance that is not a
    /// finite number in (0, 1) (0 is never reached; at 1 the unloaded state
    /// passes for equilibrium), or an iteration limit of 0 (no iteration
    /// could correct the unloaded state).
    pub fn validate(&self) -> Result<()> {
        let tol = self.tolerance;
        if !(tol.is_finite() && tol > 0.0 && tol < 1.0) {
            return Err(DismechError::InvalidParameter {
                name: "NonlinearSettings::tolerance (relative out-of-balance force)",
                value: tol,
                requirement: "must be a finite number in (0, 1), e.g. 1e-6",
            });
        }
        if self.max_iterations == 0 {
            return Err(DismechError::InvalidParameter {
                name: "NonlinearSettings::max_iterations",
                value: 0.0,
                requirement: "must be at least 1, e.g. 3000",
            });
        }
        Ok(())
    }
}

/// The smallest driving force, as a share of the slide's weight, for which
/// a safety factor is given: below it (or a driving force that points up
/// the slope) nothing drives sliding, and the ratio of resisting to driving
/// forces is refused with [`HpmError::NothingDrivesSliding`] rather
/// than returned as a huge, negative or NaN number. At 1e-6 of the weight
/// the Fs of a frictional slide would be about a million; a level slip
/// surface leaves a driving force of rounding (and of the nonlinear
/// solve's residual, at most its tolerance, 1e-6 by default) alone.
pub const MIN_DRIVING_RATIO: f64 = 1e-6;

/// Where the slip surface is in tension beyond `c / tan φ`, the apex of
/// its Mohr–Coulomb strength (`c + σ tan φ < 0`).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Tension {
    /// Grid cells of the columns with a negative strength under some part
    /// of the base.
    pub cells: Vec<(usize, usize)>,
    /// Columns of the model.
    pub columns: usize,
    /// Share of the slip surface's area with a negative strength.
    pub area_share: f64,
}

impl Tension {
    /// The columns (grid cells) and the share of the area where a part of
    /// the base, `(column, area, strength)` for each part, has a negative
    /// strength.
    pub(super) fn of(model: &HpmModel, parts: impl Iterator<Item = (usize, f64, f64)>) -> Self {
        let mut lifted = vec![false; model.columns.len()];
        let (mut total, mut negative) = (0.0, 0.0);
        for (column, area, strength) in parts {
            total += area;
            if strength < 0.0 {
                negative += area;
                lifted[column] = true;
            }
        }
        Self {
            cells: model
                .columns
                .iter()
                .zip(&lifted)
                .filter(|(_, l)| **l)
                .map(|(c, _)| c.cell)
                .collect(),
            columns: model.columns.len(),
            area_share: if total > 0.0 { negative / total } else { 0.0 },
        }
    }
}

/// Which safety factor of a slide a refusal concerns
/// ([`HpmError::NothingDrivesSliding`],
/// [`HpmError::SlipSurfaceInTension`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SafetyFactorKind {
    /// HPM's stress ratio `Σ(c + σ tan φ)A / Σ|τ|A`
    /// ([`HpmResult::safety_factor`]).
    StressRatio,
    /// HPM's factor along the sliding direction,
    /// `Σ(c + σ tan φ)A / Σ(τ·d_i)A` ([`HpmResult::sliding_safety_factor`]).
    SlidingDirection,
    /// HPM's factor along a given plan direction
    /// ([`HpmResult::safety_factor_along`]).
    AlongDirection {
        /// The direction's unit x component.
        x: f64,
        /// Its unit y component.
        y: f64,
    },
    /// Hovland's method ([`crate::hpm::hovland`]), sliding towards an
    /// azimuth.
    Hovland {
        /// The azimuth, in degrees from +x in `[0, 360)`.
        towards_deg: f64,
    },
}

/// The force that drives a safety factor's slide
/// ([`SafetyFactorTerm::force`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DrivingForce {
    /// The horizontal part of the slip springs' resultant shear force
    /// (which gives the sliding direction).
    ResultantShear,
    /// The slip springs' shear `Σ|τ|A`.
    SpringShear,
    /// The slip springs' shear along the direction, `Σ(τ·d_i)A`.
    ShearAlong,
    /// Hovland's sum of the columns' driving forces, `Σ T`.
    ColumnDriving,
}

/// A safety factor and the force that drives it, as a refusal names them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SafetyFactorTerm {
    /// The safety factor asked for.
    pub factor: SafetyFactorKind,
    /// The force found too small, or set against no strength.
    pub force: DrivingForce,
}

impl std::fmt::Display for SafetyFactorTerm {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.factor {
            SafetyFactorKind::StressRatio => {
                f.write_str("HPM stress ratio Σ(c + σ tan φ)A / Σ|τ|A")?
            }
            SafetyFactorKind::SlidingDirection => {
                f.write_str("HPM along the sliding direction, Σ(c + σ tan φ)A / Σ(τ·d_i)A")?
            }
            SafetyFactorKind::AlongDirection { x, y } => {
                write!(f, "HPM along the plan direction ({x:.4}, {y:.4})")?
            }
            SafetyFactorKind::Hovland { towards_deg } => write!(
                f,
                "Hovland's method sliding towards {towards_deg:.1}° from +x"
            )?,
        }
        f.write_str(match self.force {
            DrivingForce::ResultantShear => {
                ": the horizontal part of the slip springs' resultant shear force"
            }
            DrivingForce::SpringShear => ": the slip springs' shear, Σ|τ|A",
            DrivingForce::ShearAlong => ": the slip springs' shear along it, Σ(τ·d_i)A",
            DrivingForce::ColumnDriving => ": Σ T",
        })
    }
}

/// The safety factor `resisting / driving` of a slide of weight `weight`.
///
/// # Errors
/// [`HpmError::NothingDrivesSliding`] (naming the forces as `what`
/// says) where the driving force is not above [`MIN_DRIVING_RATIO`] of the
/// weight (`>` is false for NaN: a NaN driving force drives nothing) or so
/// small beside the resisting one that the ratio overflows (a unit weight
/// of 1e-308); else [`HpmError::SlipSurfaceInTension`] (naming where,
/// as `tension()` says) where the ratio is not positive: the resisting
/// strength `Σ (c + σ tan φ) A` is zero or negative (the surface in
/// tension beyond `c / tan φ`), or so small that the ratio underflows.
pub(super) fn resisting_over_driving(
    resisting: f64,
    driving: f64,
    weight: f64,
    what: SafetyFactorTerm,
    tension: impl FnOnce() -> Tension,
) -> Result<f64> {
    let ratio = resisting / driving;
    if !(driving > MIN_DRIVING_RATIO * weight && ratio.is_finite()) {
        return Err(DismechError::Hpm(HpmError::NothingDrivesSliding {
            what,
            driving,
            weight,
            ratio: MIN_DRIVING_RATIO,
        }));
    }
    if ratio > 0.0 {
        Ok(ratio)
    } else {
        let Tension {
            cells,
            columns,
            area_share,
        } = tension();
        Err(DismechError::Hpm(HpmError::SlipSurfaceInTension {
            what,
            strength: resisting,
            driving,
            cells,
            columns,
            area_share,
        }))
    }
}

/// Whether a solve reached equilibrium.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Convergence {
    /// The relative out-of-balance force is within the tolerance.
    Converged {
        /// Iterations (0 for the elastic solve by a direct solver, whose
        /// residual is that of the direct solve).
        iterations: usize,
        /// Final relative out-of-balance force.
        residual: f64,
    },
    /// The iteration limit was reached, the residual is above the
    /// tolerance (an ill-conditioned elastic solve) or it is not finite.
    NotConverged {
        /// Iterations made.
        iterations: usize,
        /// The last relative out-of-balance force.
        residual: f64,
    },
}

impl Convergence {
    /// Whether equilibrium was found.
    pub fn converged(&self) -> bool {
        matches!(self, Convergence::Converged { .. })
    }

    /// Iterations made, converged or not.
    pub fn iterations(&self) -> usize {
        match *self {
            Convergence::Converged { iterations, .. }
            | Convergence::NotConverged { iterations, .. } => iterations,
        }
    }

    /// The last relative out-of-balance force, converged or not.
    pub fn residual(&self) -> f64 {
        match *self {
            Convergence::Converged { residual, .. }
            | Convergence::NotConverged { residual, .. } => residual,
        }
    }
}

/// The state of one slip spring after a solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringTraction {
    /// Normal traction σ (Pa, compression positive).
    pub normal: f64,
    /// Shear traction along (s, t) (Pa), resisting the slip of the soil.
    pub shear: [f64; 2],
    /// Open, stick or slip (the elastic analysis reports stick or, in
    /// tension, open with its tension kept).
    pub regime: Regime,
}

impl SpringTraction {
    /// `|τ|`.
    pub fn shear_magnitude(&self) -> f64 {
        self.shear[0].hypot(self.shear[1])
    }
}

/// What a surface column shows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// Centre of the top face (m).
    pub position: nalgebra::Point3<f64>,
    /// Its displacement (m).
    pub displacement: Vector3<f64>,
    /// Principal strains (ε1 ≥ ε2) of the horizontal strain of the top
    /// element, tension positive.
    pub principal: [f64; 2],
    /// Angle of the ε1 direction from +x (radians).
    pub angle: f64,
}

/// The outcome of an analysis.
#[derive(Debug, Clone, PartialEq)]
pub struct HpmResult {
    /// Displacements, 12 per element.
    pub displacements: Vec<f64>,
    /// Tractions of the slip springs, in the order of [`HpmModel::slip`].
    pub tractions: Vec<SpringTraction>,
    /// Whether equilibrium was found.
    pub convergence: Convergence,
    /// When not converged, what in the model may have spoiled the solve
    /// ([`HpmModel::ill_conditioning`]), each with what to change; empty
    /// when converged.
    pub ill_conditioning: Vec<IllConditioning>,
}

/// The elastic stiffness of a model and a linear solver `S` for it,
/// factored once for all the analyses of the model: by default faer's
/// sparse Cholesky ([`HpmSolver::new`]), or preconditioned conjugate
/// gradients with one dense block per grid column
/// ([`HpmSolver::iterative`], [`HpmIterativeSolver`]), whose memory grows
/// with the stiffness rather than with a factor's fill.
#[derive(Debug)]
pub struct HpmSolver<S = SparseCholesky> {
    stiffness: BlockMatrix,
    solver: S,
    /// The bytes the model's memory budget was checked against.
    memory_estimate: Option<u128>,
}

/// HPM analyses by preconditioned conjugate gradients.
pub type HpmIterativeSolver = HpmSolver<ConjugateGradient<BlockJacobi>>;

/// HPM analyses by conjugate gradients preconditioned by smoothed
/// aggregation multigrid ([`HpmSolver::multigrid`]).
pub type HpmMultigridSolver = HpmSolver<ConjugateGradient<SmoothedAggregation>>;

/// The linear motions `u(x) = t + G (x − o)` of the whole model in each
/// element's 12 unknowns, `o` the mean of the centroids: block `e` holds
/// `12 × modes` numbers by rows. The first 6 modes are the rigid motions
/// (the translations along x, y, z and the rotations about them: an
/// element's centroid `c` moves by `t + θ × (c − o)`, its rotation
/// unknowns are `θ`, its strain 0), the near-null space of the stiffness;
/// with `modes = 12` the uniform strains follow (`ε_xx, ε_yy, ε_zz, γ_yz,
/// γ_zx, γ_xy`: the centroid moves by `E (c − o)`), which the elements
/// represent exactly ([`crate::kinematics::affine3`]).
///
/// # Errors
/// [`DismechError::InvalidParameter`] naming `modes` when it is neither 6
/// nor 12.
pub fn linear_motions(model: &HpmModel, modes: usize) -> Result<Vec<f64>> {
    if modes != 6 && modes != 12 {
        return Err(DismechError::InvalidParameter {
            name: "near-null space modes",
            value: modes as f64,
            requirement: "must be 6 (the rigid motions) or 12 (with the uniform strains)",
        });
    }
    let n = model.elements.len().max(1) as f64;
    let origin = model
        .elements
        .iter()
        .fold(Vector3::zeros(), |s, e| s + e.centre.coords)
        / n;
    let mut out = vec![0.0; model.elements.len() * ELEMENT_DOF * modes];
    for (e, element) in model.elements.iter().enumerate() {
        let block = &mut out[e * ELEMENT_DOF * modes..(e + 1) * ELEMENT_DOF * modes];
        let r = element.centre.coords - origin;
        let mut set = |row: usize, col: usize, v: f64| block[row * modes + col] = v;
        for i in 0..3 {
            set(i, i, 1.0);
            // Rotation about axis i: u_c = e_i × r, ω = e_i.
            let mut axis = Vector3::zeros();
            axis[i] = 1.0;
            let u = axis.cross(&r);
            for k in 0..3 {
                set(k, 3 + i, u[k]);
            }
            set(3 + i, 3 + i, 1.0);
        }
        if modes == 12 {
            for k in 0..6 {
                let mut dofs = ElementDofs::zeros();
                dofs[6 + k] = 1.0;
                let strain = strain_tensor(&dofs);
                let u = strain * r;
                for i in 0..3 {
                    set(i, 6 + k, u[i]);
                }
                set(6 + k, 6 + k, 1.0);
            }
        }
    }
    Ok(out)
}

impl HpmSolver<SparseCholesky> {
    /// Assemble the elastic stiffness of `model` and factorise it
    /// (sparse Cholesky). The model's memory budget
    /// ([`HpmSettings::memory_budget`](super::HpmSettings::memory_budget))
    /// is checked twice: before the compressed lower triangle is made
    /// ([`HpmModel::memory_estimate`] and [`HpmModel::cholesky_estimate`]),
    /// and after the symbolic analysis, which counts the factor's fill,
    /// before the factor is allocated (the model, the compressed lower
    /// triangle and [`SparseCholesky::factor_bytes`]).
    ///
    /// # Errors
    /// [`HpmError::HpmModelTooLarge`] when the model and the solver
    /// would take more memory than the budget (or, with none, than the
    /// system's allocator gives), naming the bytes and the factor's
    /// entries; a failed factorization: [`HpmError::IllConditioned`]
    /// naming what to change when the model has a feature that makes it
    /// ill-conditioned ([`HpmModel::ill_conditioning`]), the solver's error
    /// otherwise.
    pub fn new(model: &HpmModel) -> Result<Self> {
        let (columns, layers) = (model.columns.len(), model.settings.layers);
        let budget = model.settings.memory_budget;
        let own = HpmModel::memory_estimate(columns, layers);
        let analysis = own.saturating_add(HpmModel::cholesky_estimate(columns, layers));
        HpmModel::check_budget(
            budget,
            columns,
            layers,
            analysis,
            MemoryParts::CholeskyOrdering,
        )?;
        let stiffness = model.stiffness();
        let start = std::time::Instant::now();
        let lower = stiffness
            .lower_triangle()
            .map_err(|e| name_ill_conditioning(model, e.into()))?;
        let convert = start.elapsed();
        let mut solver = SparseCholesky::new();
        solver
            .analyse_pattern(lower.pattern())
            .map_err(|e| name_ill_conditioning(model, e.into()))?;
        let word = std::mem::size_of::<usize>() as u128;
        let compressed = lower.values().len() as u128 * (std::mem::size_of::<f64>() as u128 + word)
            + (lower.dimension() as u128 + 1) * word;
        let factor = solver.factor_bytes().unwrap_or(0);
        let factored = own.saturating_add(compressed).saturating_add(factor);
        let entries = solver.factor_entries_analysed();
        HpmModel::check_budget(
            budget,
            columns,
            layers,
            factored,
            MemoryParts::CholeskyFactor { entries },
        )?;
        // The analysis' workspace may outweigh a small factor.
        let estimate = analysis.max(factored);
        LinearSolver::<crate::linsolve::SparseMatrix>::factor(&mut solver, &lower)
            .map_err(|e| name_ill_conditioning(model, e.into()))?;
        solver.record_conversion(convert);
        Ok(Self {
            stiffness,
            solver,
            memory_estimate: Some(estimate),
        })
    }

    /// Factorise an assembled stiffness ([`HpmModel::stiffness`]); no
    /// memory budget is checked (there is no model to hold one).
    ///
    /// # Errors
    /// A failed factorization ([`DismechError::Solve`]).
    pub fn from_stiffness(stiffness: BlockMatrix) -> Result<Self> {
        Self::with_solver(stiffness, SparseCholesky::new())
    }
}

impl HpmSolver<ConjugateGradient<BlockJacobi>> {
    /// Assemble the elastic stiffness of `model` for preconditioned
    /// conjugate gradients with the stopping rule `settings`, the
    /// preconditioner one dense block per grid column (all its layers).
    /// The model's memory budget
    /// ([`HpmSettings::memory_budget`](super::HpmSettings::memory_budget))
    /// is checked for the model and the column blocks
    /// ([`HpmModel::memory_estimate`] and
    /// [`HpmModel::column_blocks_estimate`]; no compressed copy of the
    /// stiffness, no factor's fill).
    ///
    /// # Errors
    /// Settings out of range ([`CgSettings::validate`]);
    /// [`HpmError::HpmModelTooLarge`] when the model and the dense
    /// column blocks, `(12 × layers)²` numbers a column, would take more
    /// memory than the budget (or, with none, than the system's allocator
    /// gives), refused before they are made; a failed factorization of a
    /// block, as for [`HpmSolver::new`].
    pub fn iterative(model: &HpmModel, settings: CgSettings) -> Result<Self> {
        settings.validate()?;
        let (columns, layers) = (model.columns.len(), model.settings.layers);
        let estimate = HpmModel::memory_estimate(columns, layers)
            .saturating_add(HpmModel::column_blocks_estimate(columns, layers));
        HpmModel::check_budget(
            model.settings.memory_budget,
            columns,
            layers,
            estimate,
            MemoryParts::ColumnBlocks,
        )?;
        let groups = model
            .columns
            .iter()
            .map(|c| ELEMENT_DOF * c.elements.start..ELEMENT_DOF * c.elements.end)
            .collect();
        let solver = ConjugateGradient::new(settings, BlockJacobi::new(groups));
        let mut this = Self::with_solver(model.stiffness(), solver)
            .map_err(|e| name_ill_conditioning(model, e))?;
        this.memory_estimate = Some(estimate);
        Ok(this)
    }
}

impl HpmSolver<ConjugateGradient<SmoothedAggregation>> {
    /// Assemble the elastic stiffness of `model` for conjugate gradients
    /// with the stopping rule `settings`, preconditioned by a
    /// smoothed-aggregation multigrid V-cycle (Vaněk, Mandel & Brezina
    /// 1996; [`SmoothedAggregation`]) on the element blocks, whose
    /// near-null space is the rigid motions, with the uniform strains when
    /// `modes` is 12 ([`linear_motions`]). No memory
    /// budget is checked.
    ///
    /// # Errors
    /// Settings out of range ([`CgSettings::validate`]); `modes` neither 6
    /// nor 12 ([`linear_motions`]); a failed setup of the hierarchy, as for
    /// [`HpmSolver::new`].
    pub fn multigrid(
        model: &HpmModel,
        settings: CgSettings,
        aggregation: AggregationSettings,
        modes: usize,
    ) -> Result<Self> {
        Self::multigrid_with(model, settings, aggregation, modes, None)
    }

    /// [`HpmSolver::multigrid`] whose finest level is built from the grid
    /// columns ([`LineLevel`]): its smoother solves each column (all its
    /// layers, coupled by the stiff springs between them, eqs. 20–22)
    /// whole, and its aggregates are the columns of `plan × plan` grid
    /// cells; its prolongator is smoothed by the same columns. A smoother
    /// on single elements leaves errors smooth along a column and rough
    /// across columns, which cost the element-block multigrid most of its
    /// iterations.
    ///
    /// # Errors
    /// As [`HpmSolver::multigrid`], and [`DismechError::InvalidParameter`]
    /// naming `plan` when it is 0; a grid column whose elements' diagonal
    /// blocks together are not positive definite is
    /// [`crate::linsolve::FactorizationFailure::LineNotPositiveDefinite`]
    /// naming its index in [`HpmModel::columns`].
    pub fn column_multigrid(
        model: &HpmModel,
        settings: CgSettings,
        aggregation: AggregationSettings,
        modes: usize,
        plan: usize,
    ) -> Result<Self> {
        settings.validate()?;
        if plan == 0 {
            return Err(DismechError::InvalidParameter {
                name: "columns per side of a multigrid aggregate (plan)",
                value: 0.0,
                requirement: "must be at least 1",
            });
        }
        let lines = column_lines(model, plan);
        Self::multigrid_with(model, settings, aggregation, modes, Some(lines))
    }

    /// The multigrid solver of `model`, its finest level `lines` where
    /// given.
    fn multigrid_with(
        model: &HpmModel,
        settings: CgSettings,
        aggregation: AggregationSettings,
        modes: usize,
        lines: Option<LineLevel>,
    ) -> Result<Self> {
        settings.validate()?;
        let mut preconditioner =
            SmoothedAggregation::new(aggregation, linear_motions(model, modes)?, modes);
        if let Some(lines) = lines {
            preconditioner = preconditioner.with_lines(lines);
        }
        let solver = ConjugateGradient::new(settings, preconditioner);
        Self::with_solver(model.stiffness(), solver).map_err(|e| name_ill_conditioning(model, e))
    }
}

/// The finest multigrid level of `model` by columns: one line per grid
/// column (its elements), and one aggregate per `plan × plan` cells of the
/// grid that hold a column, numbered in the order of their first column.
fn column_lines(model: &HpmModel, plan: usize) -> LineLevel {
    let mut number = std::collections::HashMap::new();
    let mut aggregates = vec![0; model.elements.len()];
    for column in &model.columns {
        let key = (column.cell.0 / plan, column.cell.1 / plan);
        let next = number.len();
        let g = *number.entry(key).or_insert(next);
        aggregates[column.elements.clone()].fill(g);
    }
    LineLevel {
        aggregates,
        lines: model.columns.iter().map(|c| c.elements.clone()).collect(),
    }
}

impl<S: LinearSolver<BlockMatrix>> HpmSolver<S> {
    /// Factor `stiffness` with `solver`.
    ///
    /// # Errors
    /// The solver's error ([`DismechError::Solve`]).
    pub fn with_solver(stiffness: BlockMatrix, mut solver: S) -> Result<Self> {
        solver.factor(&stiffness)?;
        Ok(Self {
            stiffness,
            solver,
            memory_estimate: None,
        })
    }

    /// The most bytes the model's memory budget was checked against: the
    /// model's [`HpmModel::memory_estimate`] and what the solver adds (for
    /// [`HpmSolver::new`] the larger of the compressed lower triangle with
    /// the ordering's workspace and of the compressed lower triangle with
    /// the factor and faer's workspace; the column blocks for
    /// [`HpmSolver::iterative`]); `None` for a solver made from a bare
    /// stiffness ([`HpmSolver::with_solver`],
    /// [`HpmSolver::from_stiffness`]). Not counted: the packing buffer
    /// faer's dense kernels keep in each thread that runs them, for the
    /// life of the process (twice the L3 cache: 64 MiB a thread on a
    /// machine with 32 MiB of L3), made once whatever the model.
    pub fn memory_estimate(&self) -> Option<u128> {
        self.memory_estimate
    }

    /// The linear solver, holding the factor (or preconditioner).
    pub fn linear_solver(&self) -> &S {
        &self.solver
    }

    /// The elastic stiffness.
    pub fn stiffness(&self) -> &BlockMatrix {
        &self.stiffness
    }

    /// `K⁻¹ b`.
    fn solve(&mut self, b: &[f64]) -> Result<(Vec<f64>, SolveStats)> {
        let mut x = b.to_vec();
        let stats = self.solver.solve_in_place(&self.stiffness, &mut x)?;
        Ok((x, stats))
    }

    /// Elastic analysis: one solve of eq. (4). The residual is
    /// `‖F − K U‖ / ‖F‖` recomputed from the returned U; the result is
    /// `NotConverged` when it is above [`EQUILIBRIUM_TOLERANCE`] or not
    /// finite, or when an iterative solver stopped at its limit (the
    /// convergence then reports its iterations).
    ///
    /// # Errors
    /// An invalid seismic load ([`Seismic::validate`]); a failed solve.
    pub fn elastic(&mut self, model: &HpmModel, seismic: &Seismic) -> Result<HpmResult> {
        seismic.validate()?;
        self.elastic_with_loads(model, &model.loads(seismic))
    }

    /// Elastic analysis under the load vector `f` (12 generalised forces
    /// per element, conjugate to the DOFs of eq. 2).
    ///
    /// # Errors
    /// A load vector whose length is not the model's unknowns, or another
    /// failed solve ([`DismechError::Solve`]).
    pub fn elastic_with_loads(&mut self, model: &HpmModel, f: &[f64]) -> Result<HpmResult> {
        let (u, stats) = self.solve(f)?;
        Ok(elastic_result(
            model,
            &self.stiffness,
            f,
            u,
            stats.iterations,
            stats.converged,
        ))
    }

    /// Nonlinear analysis with the slip strength divided by `reduction`
    /// (`c / F`, `tan φ / F`; 1 for the material's own strength). With an
    /// iterative solver the corrections `K⁻¹ r` are those of its
    /// tolerance; the out-of-balance force, evaluated exactly, decides
    /// convergence.
    ///
    /// # Errors
    /// An invalid seismic load ([`Seismic::validate`]) or setting
    /// ([`NonlinearSettings::validate`]), a `reduction` that is not finite
    /// and positive ([`DismechError::InvalidParameter`]); a failed solve.
    pub fn nonlinear(
        &mut self,
        model: &HpmModel,
        seismic: &Seismic,
        reduction: f64,
        settings: &NonlinearSettings,
    ) -> Result<HpmResult> {
        self.nonlinear_observed(model, seismic, reduction, settings, &mut Unobserved)
    }

    /// [`HpmSolver::nonlinear`], telling `observer` of every iterate
    /// ([`Event::Iteration`]: its number and relative out-of-balance force,
    /// with the iterate as an [`HpmIterate`]), the start included and the
    /// one returned last. The iterates and the result are those of
    /// [`HpmSolver::nonlinear`], bit for bit.
    ///
    /// ```
    /// # fn main() -> dismech::error::Result<()> {
    /// use dismech::grid::Raster;
    /// use dismech::hpm::{
    ///     HpmIterate, HpmMaterial, HpmModel, HpmSettings, HpmSolver, NamedRaster,
    ///     NonlinearSettings, Seismic, SlopeGrids,
    /// };
    /// use dismech::observe::Event;
    /// // A planar slab 8 m thick on a slip plane dipping 25°, 5 × 7 columns of 10 m.
    /// let plane = |offset: f64| {
    ///     Raster::from_fn(7, 5, 0.0, 0.0, 10.0, move |x, _| {
    ///         Some(500.0 - 25f64.to_radians().tan() * x + offset)
    ///     })
    /// };
    /// let grids = SlopeGrids::new(
    ///     NamedRaster::new("ground", plane(8.0)?),
    ///     NamedRaster::new("slip", plane(0.0)?),
    ///     None,
    /// )?;
    /// let material = HpmMaterial { cohesion: 10.0e3, ..HpmMaterial::paper() };
    /// let model = HpmModel::new(&grids, &material, &HpmSettings::default())?;
    /// let mut solver = HpmSolver::new(&model)?;
    /// let mut residuals = Vec::new();
    /// let mut record = |_: &HpmIterate<'_>, event: &Event<'_>| {
    ///     if let Event::Iteration { residual, .. } = event {
    ///         residuals.push(*residual);
    ///     }
    ///     Ok(())
    /// };
    /// let settings = NonlinearSettings::default();
    /// let seismic = Seismic::none();
    /// let result = solver.nonlinear_observed(&model, &seismic, 1.0, &settings, &mut record)?;
    /// // One event per iterate: the start and each correction; the last is
    /// // the result's.
    /// assert_eq!(residuals.len(), result.convergence.iterations() + 1);
    /// assert_eq!(residuals.last(), Some(&result.convergence.residual()));
    /// # Ok(()) }
    /// ```
    ///
    /// # Errors
    /// Those of [`HpmSolver::nonlinear`], and the first error the observer
    /// returns, which stops the analysis.
    pub fn nonlinear_observed<O>(
        &mut self,
        model: &HpmModel,
        seismic: &Seismic,
        reduction: f64,
        settings: &NonlinearSettings,
        observer: &mut O,
    ) -> Result<HpmResult>
    where
        O: for<'a> Observer<HpmIterate<'a>> + ?Sized,
    {
        seismic.validate()?;
        settings.validate()?;
        crate::error::require_positive("strength reduction factor", reduction)?;
        // Each spring's own strength (the material's, or its column's
        // layer: HpmModel::set_column_strength), divided by the factor.
        let laws: Vec<MohrCoulombSpring> = model
            .slip
            .iter()
            .map(|s| {
                let own = s.law.strength();
                s.law.with_strength(Strength {
                    cohesion: own.cohesion / reduction,
                    friction: own.friction / reduction,
                })
            })
            .collect();
        let f = model.loads(seismic);
        let f_norm = norm(&f);
        let mut u = vec![0.0; f.len()];
        let mut iterations = 0;
        let mut relaxation = 1.0;
        let mut last_correction: Option<Vec<f64>> = None;
        loop {
            let (residual, tractions) = self.out_of_balance(model, &laws, &f, &u);
            let relative = relative_to(norm(&residual), f_norm);
            let done = relative <= settings.tolerance;
            let last = done || iterations >= settings.max_iterations || !relative.is_finite();
            observer.observe(
                &HpmIterate {
                    model,
                    reduction,
                    displacements: &u,
                },
                &Event::Iteration {
                    iteration: iterations,
                    residual: relative,
                    last,
                },
            )?;
            if last {
                let convergence = if done {
                    Convergence::Converged {
                        iterations,
                        residual: relative,
                    }
                } else {
                    Convergence::NotConverged {
                        iterations,
                        residual: relative,
                    }
                };
                return Ok(HpmResult {
                    displacements: u,
                    tractions,
                    ill_conditioning: diagnosis(model, &convergence),
                    convergence,
                });
            }
            let (du, _) = self.solve(&residual)?;
            // Aitken's relaxation of the fixed-point iteration
            // u ← u + K⁻¹ r(u): ω_k = −ω_{k−1} d_{k−1}·(d_k − d_{k−1}) / ‖d_k − d_{k−1}‖².
            if let Some(previous) = &last_correction {
                let diff: Vec<f64> = du.iter().zip(previous).map(|(a, b)| a - b).collect();
                let denominator = dot(&diff, &diff);
                if denominator > 0.0 {
                    relaxation = (-relaxation * dot(previous, &diff) / denominator)
                        .clamp(MIN_RELAXATION, MAX_RELAXATION);
                }
            }
            for (ui, d) in u.iter_mut().zip(&du) {
                *ui += relaxation * d;
            }
            last_correction = Some(du);
            iterations += 1;
        }
    }

    /// `F − F_int(U)` and the slip tractions, where `F_int` is the elastic
    /// `K U` less what the slip springs cannot carry.
    fn out_of_balance(
        &self,
        model: &HpmModel,
        laws: &[MohrCoulombSpring],
        f: &[f64],
        u: &[f64],
    ) -> (Vec<f64>, Vec<SpringTraction>) {
        let ku = self.stiffness.multiply(u);
        let mut r: Vec<f64> = f.iter().zip(&ku).map(|(a, b)| a - b).collect();
        let mut tractions = Vec::with_capacity(model.slip.len());
        for (spring, law) in model.slip.iter().zip(laws) {
            let d = model.slip_displacement(spring, u);
            let response = law.evaluate_total([d[0], d[1], d[2]]);
            let (force, regime) = (response.force, response.regime);
            let elastic = Vector3::new(
                spring.normal_stiffness * d[0],
                spring.shear_stiffness * d[1],
                spring.shear_stiffness * d[2],
            );
            let excess = elastic - Vector3::new(force[0], force[1], force[2]);
            if excess.norm() > 0.0 {
                add_spring_force(model, spring, &excess, &mut r);
            }
            tractions.push(SpringTraction {
                normal: force[0],
                shear: [force[1], force[2]],
                regime,
            });
        }
        (r, tractions)
    }
}

/// The elastic result of displacements `u` under loads `f`: the slip
/// tractions of linear springs (tension kept, reported as open) and the
/// relative residual `‖f − K u‖ / ‖f‖`.
fn elastic_result(
    model: &HpmModel,
    stiffness: &BlockMatrix,
    f: &[f64],
    u: Vec<f64>,
    iterations: usize,
    converged: bool,
) -> HpmResult {
    let ku = stiffness.multiply(&u);
    let out: Vec<f64> = f.iter().zip(&ku).map(|(a, b)| a - b).collect();
    let residual = relative_to(norm(&out), norm(f));
    let tractions = model
        .slip
        .iter()
        .map(|s| {
            let d = model.slip_displacement(s, &u);
            SpringTraction {
                normal: s.normal_stiffness * d[0],
                shear: [s.shear_stiffness * d[1], s.shear_stiffness * d[2]],
                regime: if d[0] < 0.0 {
                    Regime::Open
                } else {
                    Regime::Stick
                },
            }
        })
        .collect();
    // `<=` is false for NaN: a residual that is not finite never converges.
    let convergence = if converged && residual <= EQUILIBRIUM_TOLERANCE {
        Convergence::Converged {
            iterations,
            residual,
        }
    } else {
        Convergence::NotConverged {
            iterations,
            residual,
        }
    };
    HpmResult {
        displacements: u,
        tractions,
        ill_conditioning: diagnosis(model, &convergence),
        convergence,
    }
}

/// What an observer of an HPM analysis reads at each event
/// ([`HpmSolver::nonlinear_observed`],
/// [`super::strength_reduction_observed`]): the model, the factor its
/// strength is divided by, and the displacements of the iterate (for an
/// [`Event::Trial`], those the trial's analysis returned), borrowed, not
/// copied.
#[derive(Debug, Clone, Copy)]
pub struct HpmIterate<'a> {
    /// The model analysed.
    pub model: &'a HpmModel,
    /// The strength-reduction factor of the analysis (1 for the
    /// material's own strength).
    pub reduction: f64,
    /// The displacements of the iterate, in the model's unknowns.
    pub displacements: &'a [f64],
}

/// `residual / reference`, the relative out-of-balance force; under no
/// load (`reference` zero) 0 for a zero residual and infinite otherwise.
fn relative_to(residual: f64, reference: f64) -> f64 {
    if reference == 0.0 && residual == 0.0 {
        0.0
    } else if reference == 0.0 {
        f64::INFINITY
    } else {
        residual / reference
    }
}

/// What may have spoiled a solve that did not converge.
fn diagnosis(model: &HpmModel, convergence: &Convergence) -> Vec<IllConditioning> {
    if convergence.converged() {
        Vec::new()
    } else {
        model.ill_conditioning()
    }
}

/// A solver error on an ill-conditioned model, with what makes it so.
fn name_ill_conditioning(model: &HpmModel, error: DismechError) -> DismechError {
    match error {
        DismechError::Solve(reason) => {
            let causes = model.ill_conditioning();
            if causes.is_empty() {
                DismechError::Solve(reason)
            } else {
                DismechError::Hpm(HpmError::IllConditioned { causes, reason })
            }
        }
        other => other,
    }
}
/// Add `A Nᵀ Rᵀ local` of a slip spring into `r` (the internal force of
/// local tractions `local`, eqs. 27–29).
fn add_spring_force(model: &HpmModel, spring: &SlipSpring, local: &Vector3<f64>, r: &mut [f64]) {
    let p = &spring.point;
    let global = (p.point.normal * local[0] + p.s * local[1] + p.t * local[2]) * p.point.area;
    let e = &model.elements[spring.element];
    let n = crate::kinematics::affine3::shape_matrix(&e.centre, &p.point.position);
    let contribution = n.transpose() * global;
    for (k, value) in contribution.iter().enumerate() {
        r[ELEMENT_DOF * spring.element + k] += value;
    }
}

/// The shear traction of a slip spring as a vector, `τ_s s + τ_t t`.
fn shear_vector(spring: &SlipSpring, traction: &SpringTraction) -> Vector3<f64> {
    spring.point.s * traction.shear[0] + spring.point.t * traction.shear[1]
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(v: &[f64]) -> f64 {
    dot(v, v).sqrt()
}

/// Bounds of Aitken's relaxation factor.
const MIN_RELAXATION: f64 = 0.1;
const MAX_RELAXATION: f64 = 10.0;

impl HpmResult {
    /// Global safety factor `Σ (c + σ tan φ) A / Σ |τ| A` (the stress
    /// ratio) with the material's own c and φ; σ is the springs' normal
    /// traction, the effective one where the model has a pore pressure on
    /// its slip surface ([`HpmModel::set_column_pore_pressure`]).
    ///
    /// # Errors
    /// [`HpmError::NothingDrivesSliding`] when the horizontal part of
    /// the springs' resultant shear force `Σ τ A`, the force that pushes the
    /// slide along the ground, is not above [`MIN_DRIVING_RATIO`] of the
    /// slide's weight (a level slip surface without seismic load): the
    /// springs' `|τ|` are then the squeeze of the soil on the surface, not
    /// a push that strength resists, and Hovland's Fs is infinite.
    /// [`HpmError::SlipSurfaceInTension`] when the springs' strength
    /// `Σ (c + σ tan φ) A` is not positive (springs in tension beyond
    /// `c / tan φ`, as under a large seismic coefficient), so that the
    /// ratio would be zero or negative.
    pub fn safety_factor(&self, model: &HpmModel) -> Result<f64> {
        self.driven(model, SafetyFactorKind::StressRatio)?;
        let (num, den) = self.strength_and_shear(model);
        resisting_over_driving(
            num.iter().sum(),
            den.iter().sum(),
            model.total_weight(),
            SafetyFactorTerm {
                factor: SafetyFactorKind::StressRatio,
                force: DrivingForce::SpringShear,
            },
            || self.tension(model),
        )
    }

    /// Where the slip springs' strength `c + σ tan φ` is negative: the
    /// columns and the share of the slip surface's area.
    fn tension(&self, model: &HpmModel) -> Tension {
        Tension::of(
            model,
            model.slip.iter().zip(&self.tractions).map(|(s, t)| {
                let own = s.law.strength();
                (
                    s.column,
                    s.point.point.area,
                    own.cohesion + t.normal * own.friction,
                )
            }),
        )
    }

    /// The resultant shear force `Σ (τ_s s + τ_t t) A` of the slip springs.
    fn resultant_shear(&self, model: &HpmModel) -> Vector3<f64> {
        model
            .slip
            .iter()
            .zip(&self.tractions)
            .map(|(s, t)| shear_vector(s, t) * s.point.point.area)
            .sum()
    }

    /// The plan direction of the resultant shear force, or the
    /// [`HpmError::NothingDrivesSliding`] of `what` when its horizontal
    /// part is not above [`MIN_DRIVING_RATIO`] of the weight.
    fn driven(&self, model: &HpmModel, factor: SafetyFactorKind) -> Result<(f64, f64)> {
        let resultant = self.resultant_shear(model);
        let plan = resultant.x.hypot(resultant.y);
        let weight = model.total_weight();
        // `>` is false for NaN: a NaN resultant drives nothing.
        if plan > MIN_DRIVING_RATIO * weight {
            Ok((resultant.x / plan, resultant.y / plan))
        } else {
            Err(DismechError::Hpm(HpmError::NothingDrivesSliding {
                what: SafetyFactorTerm {
                    factor,
                    force: DrivingForce::ResultantShear,
                },
                driving: plan,
                weight,
                ratio: MIN_DRIVING_RATIO,
            }))
        }
    }

    /// Plan direction `ĥ = (h_x, h_y)` (unit) of the resultant shear force
    /// `Σ (τ_s s + τ_t t) A` of the slip springs: the direction the slide
    /// pushes the ground, along which it slides. `None` when nothing drives
    /// sliding: the resultant's horizontal part is not above
    /// [`MIN_DRIVING_RATIO`] of the slide's weight.
    pub fn sliding_direction(&self, model: &HpmModel) -> Option<(f64, f64)> {
        self.driven(model, SafetyFactorKind::SlidingDirection).ok()
    }

    /// Global safety factor along the sliding direction,
    /// `Σ (c + σ tan φ) A / Σ (τ · d_i) A` with `d_i` the unit tangent of
    /// the slip surface over the plan direction
    /// [`HpmResult::sliding_direction`] (Hovland's assumption; see the
    /// module documentation).
    ///
    /// # Errors
    /// [`HpmError::NothingDrivesSliding`] when there is no sliding
    /// direction (the springs' resultant shear force has no horizontal part
    /// above [`MIN_DRIVING_RATIO`] of the weight), or the shear along it is
    /// not above that share of the weight;
    /// [`HpmError::SlipSurfaceInTension`] when the springs' strength is
    /// not positive (see [`HpmResult::safety_factor_along`]).
    pub fn sliding_safety_factor(&self, model: &HpmModel) -> Result<f64> {
        let plan = self.driven(model, SafetyFactorKind::SlidingDirection)?;
        self.safety_factor_along(model, plan)
    }

    /// `Σ (c + σ tan φ) A / Σ (τ · d_i) A` for the horizontal sliding
    /// direction `plan` (need not be unit), `d_i` the unit tangent of the
    /// slip surface at spring i whose plan projection points along `plan`.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for a `plan` that is not finite or
    /// is zero; [`HpmError::NothingDrivesSliding`] when the driving
    /// shear `Σ (τ · d_i) A` is not above [`MIN_DRIVING_RATIO`] of the
    /// slide's weight: nothing pushes the slide that way (a direction up
    /// the slope gives a negative one);
    /// [`HpmError::SlipSurfaceInTension`] when the strength
    /// `Σ (c + σ tan φ) A` is not positive (springs in tension beyond
    /// `c / tan φ`), naming the columns where it is negative.
    pub fn safety_factor_along(&self, model: &HpmModel, plan: (f64, f64)) -> Result<f64> {
        let length = plan.0.hypot(plan.1);
        if !(length.is_finite() && length > 0.0) {
            return Err(DismechError::InvalidParameter {
                name: "plan sliding direction (its length)",
                value: length,
                requirement: "must be a finite, non-zero horizontal vector",
            });
        }
        // The vertical plane through `plan` has normal m = ĥ × e_z.
        let m = Vector3::new(plan.1, -plan.0, 0.0);
        let h = Vector3::new(plan.0, plan.1, 0.0);
        let (mut num, mut den) = (0.0, 0.0);
        for (s, t) in model.slip.iter().zip(&self.tractions) {
            let a = s.point.point.area;
            let along = s.point.point.normal.cross(&m);
            let along = along.normalize() * along.dot(&h).signum();
            let own = s.law.strength();
            num += (own.cohesion + t.normal * own.friction) * a;
            den += shear_vector(s, t).dot(&along) * a;
        }
        resisting_over_driving(
            num,
            den,
            model.total_weight(),
            SafetyFactorTerm {
                factor: SafetyFactorKind::AlongDirection {
                    x: plan.0 / length,
                    y: plan.1 / length,
                },
                force: DrivingForce::ShearAlong,
            },
            || self.tension(model),
        )
    }

    /// Local safety factor of each column (same ratio over its springs);
    /// 0 where the column's strength `Σ (c + σ tan φ) A` is not positive
    /// (its base in tension beyond `c / tan φ`, as the elastic analysis'
    /// linear springs allow: nothing is left there to resist, and a
    /// negative ratio is no factor of safety), infinite where the springs
    /// carry no shear.
    pub fn local_safety_factors(&self, model: &HpmModel) -> Vec<f64> {
        let (num, den) = self.strength_and_shear(model);
        num.iter()
            .zip(&den)
            .map(|(n, d)| {
                if *n <= 0.0 {
                    0.0
                } else if *d > 0.0 {
                    n / d
                } else {
                    f64::INFINITY
                }
            })
            .collect()
    }

    /// `Σ (c + σ tan φ) A` and `Σ |τ| A` per column.
    fn strength_and_shear(&self, model: &HpmModel) -> (Vec<f64>, Vec<f64>) {
        let mut num = vec![0.0; model.columns.len()];
        let mut den = vec![0.0; model.columns.len()];
        for (s, t) in model.slip.iter().zip(&self.tractions) {
            let a = s.point.point.area;
            let own = s.law.strength();
            num[s.column] += (own.cohesion + t.normal * own.friction) * a;
            den[s.column] += t.shear_magnitude() * a;
        }
        (num, den)
    }

    /// Displacement and principal strains at the top of each column.
    pub fn surface(&self, model: &HpmModel) -> Vec<SurfacePoint> {
        model
            .columns
            .iter()
            .map(|column| {
                let e = column.elements.end - 1;
                let element = &model.elements[e];
                let dofs = ElementDofs::from_column_slice(
                    &self.displacements[ELEMENT_DOF * e..ELEMENT_DOF * (e + 1)],
                );
                let (x0, y0) = column.shape.origin();
                let half = 0.5 * column.shape.size();
                let position =
                    nalgebra::Point3::new(x0 + half, y0 + half, column.shape.top_at(0.5, 0.5));
                let strain = strain_tensor(&dofs);
                let (exx, eyy, exy) = (strain[(0, 0)], strain[(1, 1)], strain[(0, 1)]);
                let centre = 0.5 * (exx + eyy);
                let radius = (0.25 * (exx - eyy) * (exx - eyy) + exy * exy).sqrt();
                SurfacePoint {
                    position,
                    displacement: displacement_at(&element.centre, &dofs, &position),
                    principal: [centre + radius, centre - radius],
                    angle: 0.5 * (2.0 * exy).atan2(exx - eyy),
                }
            })
            .collect()
    }

    /// Share of the slip-surface area whose springs are slipping or open.
    pub fn yielded_area_fraction(&self, model: &HpmModel) -> f64 {
        let total: f64 = model.slip.iter().map(|s| s.point.point.area).sum();
        let yielded: f64 = model
            .slip
            .iter()
            .zip(&self.tractions)
            .filter(|(_, t)| t.regime != Regime::Stick)
            .map(|(s, _)| s.point.point.area)
            .sum();
        yielded / total
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::Raster;
    use crate::hpm::{HpmMaterial, HpmSettings, NamedRaster, SlopeGrids};

    /// A 2 × 2-cell slab 5 m thick on a plane dipping 20°.
    fn slab() -> HpmModel {
        let slope = 20f64.to_radians().tan();
        let plane = |offset: f64| {
            Raster::from_fn(2, 2, 0.0, 0.0, 10.0, move |_, y| Some(slope * y + offset)).unwrap()
        };
        let grids = SlopeGrids::new(
            NamedRaster::new("ground", plane(5.0)),
            NamedRaster::new("slip", plane(0.0)),
            None,
        )
        .unwrap();
        HpmModel::new(&grids, &HpmMaterial::paper(), &HpmSettings::default()).unwrap()
    }

    #[test]
    fn elastic_nan_residual_is_not_converged() {
        // A linear solver that returns NaN displacements while reporting
        // success: the recomputed residual is NaN, which is not equilibrium.
        let model = slab();
        let f = model.loads(&Seismic::none());
        let nan = vec![f64::NAN; model.dof()];
        let r = elastic_result(&model, &model.stiffness(), &f, nan, 0, true);
        match r.convergence {
            Convergence::NotConverged { residual, .. } => assert!(residual.is_nan()),
            other => panic!("NaN displacements reported {other:?}"),
        }
    }

    #[test]
    fn zero_load_has_zero_residual() {
        let model = slab();
        let f = vec![0.0; model.dof()];
        let r = elastic_result(&model, &model.stiffness(), &f, f.clone(), 0, true);
        assert_eq!(
            r.convergence,
            Convergence::Converged {
                iterations: 0,
                residual: 0.0
            }
        );
    }
}
