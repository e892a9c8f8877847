//! The DDA model and its time step: contact detection, global assembly of
//! the linearised weak form (paper 003 eq. 11) into a sparse system, the
//! open–close iteration then Newton–Raphson (Fig. 5), Newmark β = ½, γ = 1
//! (§2.(5)), and automatic reduction of the time step.
//!
//! One step of size `Δt` solves for the increments `d` of all unknowns
//!
//! `R(d) = M a₁(d) + K d + f_σ − f_ext + Σ_c (−t_n ∇g_n + t_s ∇g_s) + Σ_f k_f Tᵀ T d = 0`
//!
//! with `a₁ = c_a d − a_v v₀ − a_a a₀` (Newmark), the elastic stiffness `K`,
//! the internal force `f_σ` of the current stress, the contact forces of the
//! [`PenaltyCoulomb`] law and the fixed-point springs of classic DDA. Each
//! iteration evaluates every contact at the current iterate, assembles
//! `R` and the tangent
//!
//! `c_a M + K + Σ_c [Jᵀ C J + t_n ∇²(−g_n) + t_s ∇²g_s] + Σ_f k_f TᵀT`
//!
//! (`J` = the rows `∇(−g_n)`, `∇g_s`; `C` the law's tangent; the Hessian
//! terms are eq. 12's `Δδg_n`, `Δδg_s`), and solves `K_T Δd = −R` with a
//! [`LinearSolver`] ([`SparseLu`]). The tangent is assembled into 6 × 6
//! blocks on a pattern built from the pairs of blocks in contact
//! ([`BlockAssembly`]; blocks whose six unknowns are all prescribed keep
//! only their diagonal), so an iteration only refills values; the pattern,
//! and the solver's analysis of it, are kept while those pairs are
//! unchanged (open contacts keep their zero entries so the pattern holds).
//!
//! * **Open–close**: while the set of open contacts changes from one
//!   iterate to the next, the iteration is an open–close iteration
//!   (at most `max_open_close`).
//! * **Newton**: once the set is stable, return mapping iterates to
//!   `‖R‖ ≤ tol · scale` with the consistent tangent (at most `max_newton`
//!   iterations), with the LOCK/CLOSE states and slip directions unchanged
//!   between the last two iterates. A backtracking line search on `‖R‖`
//!   halves a step that does not lower the residual (at most 8 times); it
//!   stops Newton from cycling between the two slip directions of a contact
//!   that should stick, which at high penalties would otherwise cost Δt
//!   reductions. Full steps are recorded in [`StepReport::step_lengths`]. The conventional law has no Newton phase: as in classic
//!   DDA the step is accepted when the open/closed states no longer change,
//!   and its tangent has no Hessian terms (the paper's remark after eq. 13).
//! * **Δt reduction**: a step whose iteration fails, whose solve is
//!   singular, or which moves a vertex further than the search distance
//!   relative to a neighbouring block is retried with half the step, down to
//!   `min_dt_ratio` times the requested step; after a successful sub-step the
//!   step doubles again up to the requested one. Past that bound
//!   [`DdaModel::advance`] returns a [`StepStatus::Failed`] saying what
//!   failed.

use std::collections::HashMap;

use nalgebra::SVector;

use super::block::{Block, Dof6, Mat6};
use super::contact::{closest_edge, penetration_depth, Grad12, Kinematics, VertexEdge};
use super::friction::{FrictionIntegration, PenaltyCoulomb, PenaltyState};
use crate::broad_phase::CellGrid;
use crate::contact::{ContactInput, ContactLaw, PairProperties, Regime};
use crate::error::{require_positive, DismechError, Result};
use crate::integrate::{Integrator, Newmark};
use crate::linsolve::{BlockAssembly, LinearSolver, LinearSolverInfo, SparseLu};
use crate::math::{Aabb2, Point, Vec2};
use crate::shape::Shape2;

/// Settings of a DDA run; validated by [`DdaModel::new`].
#[derive(Debug, Clone, PartialEq)]
pub struct DdaSettings {
    /// Gravity (m/s²).
    pub gravity: Vec2,
    /// Search distance `d₀` of vertex–edge detection (m).
    pub search_distance: f64,
    /// Largest penetration accepted at the start (m).
    pub overlap_tolerance: f64,
    /// Most open–close iterations per step.
    pub max_open_close: usize,
    /// Most Newton iterations per step once the contact states settled.
    pub max_newton: usize,
    /// Relative residual tolerance of Newton.
    pub residual_tolerance: f64,
    /// Smallest step, as a fraction of the requested one (e.g. 1/64).
    pub min_dt_ratio: f64,
    /// Dynamic analysis, or the static analysis of classic DDA (the inertia
    /// term stays in the equations but velocities and accelerations are
    /// reset to zero after every step, so the motion stops each step).
    pub dynamic: bool,
}

impl Default for DdaSettings {
    fn default() -> Self {
        Self {
            gravity: Vec2::new(0.0, -9.8),
            search_distance: 0.01,
            overlap_tolerance: 1e-6,
            max_open_close: 20,
            max_newton: 20,
            residual_tolerance: 1e-10,
            min_dt_ratio: 1.0 / 64.0,
            dynamic: true,
        }
    }
}

/// A penalty spring tying a material point of a block to its start position
/// (the fixed point of classic DDA).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedPoint {
    /// The block.
    pub block: usize,
    /// Current position of the material point (moves with the block).
    pub point: Point,
    /// Anchor it is tied to.
    pub anchor: Point,
    /// Spring stiffness (N/m per m).
    pub stiffness: f64,
}

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
    },
    /// The linear solve failed (singular tangent).
    Solve(String),
    /// A vertex moved further than the search distance relative to a
    /// neighbouring block.
    TooFast {
        /// Block of the vertex.
        block: usize,
        /// Relative motion (m).
        motion: f64,
    },
    /// A block became an invalid polygon.
    Geometry(String),
}

impl std::fmt::Display for StepFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::OpenCloseNotSettled { iterations } => write!(f, "open-close iteration did not settle in {iterations} iterations"),
            Self::NewtonNotConverged { iterations, residual } => write!(f, "Newton-Raphson did not converge in {iterations} iterations (relative residual {residual:.3e})"),
            Self::Solve(m) => write!(f, "linear solve failed: {m}"),
            Self::TooFast { block, motion } => write!(f, "a vertex of block {block} moved {motion:.3e} m relative to a neighbour in one step, beyond the search distance"),
            Self::Geometry(m) => write!(f, "{m}"),
        }
    }
}

/// Outcome of [`DdaModel::advance`].
#[derive(Debug, Clone, PartialEq)]
pub enum StepStatus {
    /// The whole interval was integrated.
    Converged,
    /// A sub-step failed at the smallest admissible step; the model is left
    /// at the last accepted state.
    Failed {
        /// Time reached (s).
        time: f64,
        /// Step that failed (s).
        dt: f64,
        /// What failed; reduce the time step or change the penalty.
        reason: StepFailure,
    },
}

/// Record of one [`DdaModel::advance`] call.
#[derive(Debug, Clone, PartialEq)]
pub struct StepReport {
    /// Converged or failed.
    pub status: StepStatus,
    /// Sub-steps taken.
    pub substeps: usize,
    /// How many times the step was halved.
    pub reductions: usize,
    /// Smallest sub-step used (s).
    pub smallest_dt: f64,
    /// Relative residual norms of every iteration of the last sub-step.
    pub residuals: Vec<f64>,
    /// Length (1 = full Newton step) of the update after each residual of
    /// `residuals` but the last, from the backtracking line search.
    pub step_lengths: Vec<f64>,
    /// Open–close iterations of the last sub-step.
    pub open_close_iterations: usize,
}

/// A contact after the last accepted step.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactReport {
    /// Which vertex and edge.
    pub contact: VertexEdge,
    /// The history kept for the next step (after any pull-back).
    pub state: PenaltyState,
    /// `(t_n, t_s)` in the equilibrium of the step (before the pull-back of
    /// the conventional law; equal to `state` for return mapping).
    pub force: (f64, f64),
    /// Force on the vertex's block at the vertex, `t_n n − t_s τ` (N/m),
    /// from `force`.
    pub force_on_vertex: Vec2,
    /// The vertex (world).
    pub point: Point,
}

/// Most halvings of a Newton step in the backtracking line search.
const LINE_SEARCH: usize = 8;

/// The parts of a step's residual that do not depend on the iterate.
struct Parts {
    /// Per block: effective stiffness (elastic + Newmark mass + fixed points).
    block_k: Vec<Mat6>,
    /// Per block: force at zero increment.
    block_f: Vec<Dof6>,
    /// Prescribed unknowns.
    mask: Vec<bool>,
    /// Consistent linearisation (return mapping) or classic.
    consistent: bool,
}

/// Residual and contact states at one iterate.
struct Evaluation {
    r: Vec<f64>,
    norm: f64,
    contact_scale: f64,
    /// Per contact: 0 open, 1 LOCK, 2 / 3 CLOSE sliding with `t_s ≥ 0` / `< 0`.
    regimes: Vec<i8>,
    states: Vec<PenaltyState>,
    forces: Vec<(f64, f64)>,
}

/// Result of one trial sub-step.
struct Trial {
    dt: f64,
    d: Vec<f64>,
    states: Vec<PenaltyState>,
    forces: Vec<(f64, f64)>,
    residuals: Vec<f64>,
    step_lengths: Vec<f64>,
    open_close: usize,
}

/// A DDA model: blocks, one contact law, fixed points, and the solver's
/// workspaces.
#[derive(Debug)]
pub struct DdaModel {
    blocks: Vec<Block>,
    law: PenaltyCoulomb,
    settings: DdaSettings,
    integrator: Newmark,
    fixed_points: Vec<FixedPoint>,
    time: f64,
    history: HashMap<(usize, usize, usize, usize), PenaltyState>,
    contacts: Vec<ContactReport>,
    solver: SparseLu,
    grid: CellGrid,
    pairs: Vec<(usize, usize)>,
    assembly: BlockAssembly,
    requested_dt: Option<f64>,
    current_dt: f64,
}

impl DdaModel {
    /// A model of `blocks` with contact law `law`. Refuses invalid settings
    /// and blocks that overlap at the start by more than
    /// `settings.overlap_tolerance` (the error names both blocks).
    pub fn new(blocks: Vec<Block>, law: PenaltyCoulomb, settings: DdaSettings) -> Result<Self> {
        require_positive("search distance d0", settings.search_distance)?;
        require_positive("overlap tolerance", settings.overlap_tolerance)?;
        require_positive("residual tolerance", settings.residual_tolerance)?;
        if !(settings.min_dt_ratio > 0.0 && settings.min_dt_ratio <= 1.0) {
            return Err(DismechError::InvalidParameter {
                name: "min_dt_ratio",
                value: settings.min_dt_ratio,
                requirement: "must lie in (0, 1]",
            });
        }
        if !(settings.gravity.x.is_finite() && settings.gravity.y.is_finite()) {
            return Err(DismechError::InvalidParameter {
                name: "gravity",
                value: settings.gravity.norm(),
                requirement: "must be finite",
            });
        }
        let assembly = BlockAssembly::new(blocks.len(), 6, &[])?;
        let mut model = Self {
            blocks,
            law,
            settings,
            integrator: Newmark::dda(),
            fixed_points: Vec::new(),
            time: 0.0,
            history: HashMap::new(),
            contacts: Vec::new(),
            solver: SparseLu::default(),
            grid: CellGrid::new(),
            pairs: Vec::new(),
            assembly,
            requested_dt: None,
            current_dt: 0.0,
        };
        model.find_pairs();
        for &(i, j) in &model.pairs {
            for (a, b) in [(i, j), (j, i)] {
                for v in 0..model.blocks[a].vertex_count() {
                    let p = model.blocks[a].vertex(v);
                    if let Some(depth) = penetration_depth(&p, &model.blocks[b]) {
                        if depth > model.settings.overlap_tolerance {
                            return Err(DismechError::BlocksOverlap {
                                vertex_block: a,
                                vertex: v,
                                edge_block: b,
                                depth,
                                tolerance: model.settings.overlap_tolerance,
                            });
                        }
                    }
                }
            }
        }
        Ok(model)
    }

    /// Add a fixed point: the material point `point` of `block` is tied to
    /// its present position by a spring of `stiffness`.
    pub fn add_fixed_point(&mut self, block: usize, point: Point, stiffness: f64) -> Result<()> {
        require_positive("fixed-point stiffness", stiffness)?;
        if block >= self.blocks.len() {
            return Err(DismechError::NoSuchBody {
                index: block,
                count: self.blocks.len(),
            });
        }
        self.fixed_points.push(FixedPoint {
            block,
            point,
            anchor: point,
            stiffness,
        });
        Ok(())
    }

    /// The blocks.
    pub fn blocks(&self) -> &[Block] {
        &self.blocks
    }

    /// Simulated time (s).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The contact law.
    pub fn law(&self) -> &PenaltyCoulomb {
        &self.law
    }

    /// Contacts of the last accepted step.
    pub fn contacts(&self) -> &[ContactReport] {
        &self.contacts
    }

    /// The linear solver of the Newton iterations (its analyses, fill and
    /// fallbacks).
    pub fn linear_solver(&self) -> &SparseLu {
        &self.solver
    }

    /// How many symbolic analyses the sparse solver made so far.
    pub fn symbolic_analyses(&self) -> usize {
        self.solver.symbolic_analyses()
    }

    fn find_pairs(&mut self) {
        let boxes: Vec<Aabb2> = self
            .blocks
            .iter()
            .map(|b| b.polygon().aabb(&b.pose()))
            .collect();
        self.grid
            .candidate_pairs(&boxes, self.settings.search_distance, &mut self.pairs);
    }

    /// Vertex–edge contacts at the start of a step (rule in [`super::contact`]).
    fn detect(&mut self) -> Vec<VertexEdge> {
        self.find_pairs();
        let mut previous: HashMap<(usize, usize, usize), usize> = HashMap::new();
        for &(j, v, k, e) in self.history.keys() {
            previous.insert((j, v, k), e);
        }
        let mut out = Vec::new();
        for &(i, j) in &self.pairs {
            for (a, b) in [(i, j), (j, i)] {
                for v in 0..self.blocks[a].vertex_count() {
                    let p = self.blocks[a].vertex(v);
                    let prev = previous.get(&(a, v, b)).copied();
                    if let Some((edge, xi, gap)) =
                        closest_edge(&p, &self.blocks[b], self.settings.search_distance, prev)
                    {
                        out.push(VertexEdge {
                            vertex_block: a,
                            vertex: v,
                            edge_block: b,
                            edge,
                            xi,
                            initial_gap: gap,
                        });
                    }
                }
            }
        }
        out
    }

    fn block_dofs(d: &[f64], block: usize) -> Dof6 {
        Dof6::from_column_slice(&d[6 * block..6 * block + 6])
    }

    fn prescribed_mask(&self) -> Vec<bool> {
        let mut mask = vec![false; 6 * self.blocks.len()];
        for (i, b) in self.blocks.iter().enumerate() {
            if let Some(p) = &b.prescribed {
                mask[6 * i..6 * i + 6].copy_from_slice(&p.mask);
            }
        }
        mask
    }

    /// Evaluate one contact at the iterate `d`.
    fn evaluate(
        &self,
        c: &VertexEdge,
        d: &[f64],
        dt: f64,
    ) -> (Kinematics, crate::contact::ContactResponse<2, PenaltyState>) {
        let kin = c.kinematics(
            &self.blocks,
            &Self::block_dofs(d, c.vertex_block),
            &Self::block_dofs(d, c.edge_block),
        );
        let old = self.history.get(&c.key()).copied().unwrap_or_default();
        let input = ContactInput {
            overlap: -kin.gap,
            increment: SVector::<f64, 2>::new(c.initial_gap - kin.gap, kin.shear),
            dt,
            is_new: !self.history.contains_key(&c.key()),
            pair: PairProperties {
                curvature_radius_a: f64::INFINITY,
                curvature_radius_b: f64::INFINITY,
                width: 0.0,
                mass_a: self.blocks[c.vertex_block].area()
                    * self.blocks[c.vertex_block].material().density,
                mass_b: self.blocks[c.edge_block].area()
                    * self.blocks[c.edge_block].material().density,
            },
        };
        let response = self.law.evaluate(&input, &old);
        (kin, response)
    }

    /// One trial sub-step of size `dt` from the current state.
    fn trial(
        &mut self,
        dt: f64,
        contacts: &[VertexEdge],
    ) -> std::result::Result<Trial, StepFailure> {
        let nb = self.blocks.len();
        let n = 6 * nb;
        let mask = self.prescribed_mask();
        let mut d = vec![0.0; n];
        for (i, b) in self.blocks.iter().enumerate() {
            if let Some(p) = &b.prescribed {
                let (u0, u1) = ((p.motion)(self.time), (p.motion)(self.time + dt));
                for k in 0..6 {
                    if p.mask[k] {
                        d[6 * i + k] = u1[k] - u0[k];
                    }
                }
            }
        }
        let coeffs = self.integrator.implicit_coefficients(dt);
        // Predictor for the free unknowns: the motion at constant
        // acceleration, Δd = Δt v₀ + ½ Δt² a₀.
        for (i, b) in self.blocks.iter().enumerate() {
            for k in 0..6 {
                if !mask[6 * i + k] {
                    d[6 * i + k] = dt * b.velocity[k] + 0.5 * dt * dt * b.acceleration[k];
                }
            }
        }
        let consistent = self.law.integration() == FrictionIntegration::ReturnMapping;
        // Per-block constant parts: effective stiffness and the force at d = 0.
        let mut block_k: Vec<Mat6> = Vec::with_capacity(nb);
        let mut block_f: Vec<Dof6> = Vec::with_capacity(nb);
        let mut scale = 0.0f64;
        for b in &self.blocks {
            let mut k = b.stiffness();
            let ext = b.external_force(&self.settings.gravity);
            let mut f = b.stress_force() - ext;
            scale = scale.max(ext.norm()).max(b.stress_force().norm());
            if let Some(c) = &coeffs {
                let m = b.mass();
                k += m * c.acceleration_per_increment;
                let hist = m
                    * (b.velocity * c.acceleration_from_velocity
                        + b.acceleration * c.acceleration_from_acceleration);
                f -= hist;
                scale = scale.max(hist.norm());
            }
            block_k.push(k);
            block_f.push(f);
        }
        for fp in &self.fixed_points {
            let t = self.blocks[fp.block].displacement_matrix(&fp.point);
            block_k[fp.block] += t.transpose() * t * fp.stiffness;
            block_f[fp.block] += t.transpose() * (fp.point - fp.anchor) * fp.stiffness;
        }

        self.update_pattern(contacts, &mask)?;
        let parts = Parts {
            block_k,
            block_f,
            mask,
            consistent,
        };
        let max_iter = self.settings.max_open_close + self.settings.max_newton;
        let mut residuals = Vec::new();
        let mut step_lengths = Vec::new();
        let mut open_close = 0;
        let mut newton = 0;
        let mut last_open: Option<Vec<bool>> = None;
        let mut last_regimes: Option<Vec<i8>> = None;
        let mut eval = self.assemble(&d, dt, contacts, &parts, true);
        for _ in 0..=max_iter {
            let rel = eval.norm / scale.max(eval.contact_scale).max(f64::MIN_POSITIVE);
            residuals.push(rel);
            if !rel.is_finite() {
                return Err(StepFailure::Solve("non-finite residual".into()));
            }
            let open: Vec<bool> = eval.regimes.iter().map(|&r| r == 0).collect();
            let settled = last_open.as_ref() == Some(&open);
            if settled {
                let done = if consistent {
                    last_regimes.as_ref() == Some(&eval.regimes)
                        && rel <= self.settings.residual_tolerance
                } else {
                    true
                };
                if done {
                    return Ok(Trial {
                        dt,
                        d,
                        states: eval.states,
                        forces: eval.forces,
                        residuals,
                        step_lengths,
                        open_close,
                    });
                }
                newton += 1;
                if newton > self.settings.max_newton {
                    return Err(StepFailure::NewtonNotConverged {
                        iterations: newton - 1,
                        residual: rel,
                    });
                }
            } else if last_open.is_some() {
                open_close += 1;
                if open_close > self.settings.max_open_close {
                    return Err(StepFailure::OpenCloseNotSettled {
                        iterations: open_close - 1,
                    });
                }
            }
            last_open = Some(open);
            last_regimes = Some(eval.regimes.clone());
            let mut delta: Vec<f64> = eval.r.iter().map(|x| -x).collect();
            let matrix = self.assembly.matrix();
            self.solver
                .factor(matrix)
                .and_then(|()| self.solver.solve_in_place(matrix, &mut delta))
                .map_err(|e| StepFailure::Solve(e.to_string()))?;
            // Backtracking on ‖R‖ (return mapping only): a full step that does
            // not lower the residual is halved, up to `LINE_SEARCH` times, so
            // that Newton does not cycle between the two slip directions of
            // a contact that should stick.
            let mut alpha = 1.0;
            let mut next = Vec::with_capacity(n);
            for attempt in 0..=LINE_SEARCH {
                next.clear();
                next.extend(d.iter().zip(&delta).map(|(x, dx)| x + alpha * dx));
                if !consistent || attempt == LINE_SEARCH {
                    break;
                }
                let probe = self.assemble(&next, dt, contacts, &parts, false);
                if probe.norm < (1.0 - 1e-4 * alpha) * eval.norm || eval.norm == 0.0 {
                    break;
                }
                alpha *= 0.5;
            }
            // The step reached (accepted, or the last halving) is taken.
            step_lengths.push(alpha);
            std::mem::swap(&mut d, &mut next);
            eval = self.assemble(&d, dt, contacts, &parts, true);
        }
        Err(StepFailure::NewtonNotConverged {
            iterations: newton,
            residual: residuals.last().copied().unwrap_or(f64::NAN),
        })
    }

    /// The block pattern of the tangent for `contacts`: a block for every
    /// pair of blocks in contact, unless all six unknowns of one of them are
    /// prescribed (its rows and columns then hold only its diagonal). Kept,
    /// with the solver's analysis, while the pairs are unchanged.
    fn update_pattern(
        &mut self,
        contacts: &[VertexEdge],
        mask: &[bool],
    ) -> std::result::Result<(), StepFailure> {
        let held = |b: usize| mask[6 * b..6 * b + 6].iter().all(|m| *m);
        let pairs: Vec<(usize, usize)> = contacts
            .iter()
            .map(|c| (c.vertex_block, c.edge_block))
            .filter(|&(a, b)| !held(a) && !held(b))
            .collect();
        let pairs = BlockAssembly::normalised(&pairs);
        if !self.assembly.has_layout(self.blocks.len(), 6, &pairs) {
            self.assembly = BlockAssembly::new(self.blocks.len(), 6, &pairs)
                .map_err(|e| StepFailure::Solve(e.to_string()))?;
        }
        Ok(())
    }

    /// Residual (and, with `matrix`, the tangent in `self.assembly`) at the
    /// iterate `d`.
    fn assemble(
        &mut self,
        d: &[f64],
        dt: f64,
        contacts: &[VertexEdge],
        parts: &Parts,
        matrix: bool,
    ) -> Evaluation {
        let nb = self.blocks.len();
        let n = 6 * nb;
        let mask = &parts.mask;
        let mut r = vec![0.0; n];
        if matrix {
            self.assembly.clear();
        }
        for i in 0..nb {
            let k = &parts.block_k[i];
            let fi = parts.block_f[i] + k * Self::block_dofs(d, i);
            let slot = self.assembly.slot(i, i);
            for a in 0..6 {
                r[6 * i + a] += fi[a];
                let Some(slot) = slot.filter(|_| matrix) else {
                    continue;
                };
                for b in 0..6 {
                    let (ra, cb) = (6 * i + a, 6 * i + b);
                    if !mask[ra] && !mask[cb] {
                        self.assembly.add(slot, a, b, k[(a, b)]);
                    }
                }
                if mask[6 * i + a] {
                    self.assembly.add(slot, a, a, 1.0);
                }
            }
        }
        let mut eval = Evaluation {
            r: Vec::new(),
            norm: 0.0,
            contact_scale: 0.0,
            regimes: Vec::with_capacity(contacts.len()),
            states: Vec::with_capacity(contacts.len()),
            forces: Vec::with_capacity(contacts.len()),
        };
        for c in contacts {
            let (kin, resp) = self.evaluate(c, d, dt);
            let (t_n, t_s) = (resp.force[0], resp.force[1]);
            eval.contact_scale = eval.contact_scale.max(t_n.abs() + t_s.abs());
            let g_ov: Grad12 = -kin.grad_gap;
            let force: Grad12 = g_ov * t_n + kin.grad_shear * t_s;
            let dofs = |a: usize| {
                if a < 6 {
                    6 * c.vertex_block + a
                } else {
                    6 * c.edge_block + a - 6
                }
            };
            for a in 0..12 {
                r[dofs(a)] += force[a];
            }
            eval.regimes.push(match resp.regime {
                Regime::Open => 0,
                Regime::Stick => 1,
                Regime::Slip if t_s >= 0.0 => 2,
                Regime::Slip => 3,
            });
            eval.states.push(resp.state);
            eval.forces.push((t_n, t_s));
            if !matrix {
                continue;
            }
            let rows = [g_ov, kin.grad_shear];
            let mut kt = nalgebra::SMatrix::<f64, 12, 12>::zeros();
            for (p, rp) in rows.iter().enumerate() {
                for (q, rq) in rows.iter().enumerate() {
                    let cpq = resp.tangent[(p, q)];
                    if cpq != 0.0 {
                        kt += rp * rq.transpose() * cpq;
                    }
                }
            }
            if parts.consistent && resp.regime != Regime::Open {
                kt -= kin.hess_gap * t_n;
                kt += kin.hess_shear * t_s;
            }
            // Blocks (vertex, vertex), (edge, vertex), (vertex, edge), (edge, edge);
            // a block missing from the pattern has only prescribed entries.
            let bodies = [c.vertex_block, c.edge_block];
            for (q, &column) in bodies.iter().enumerate() {
                for (p, &row) in bodies.iter().enumerate() {
                    let Some(slot) = self.assembly.slot(row, column) else {
                        continue;
                    };
                    for b in 0..6 {
                        for a in 0..6 {
                            let (ra, cb) = (6 * row + a, 6 * column + b);
                            if !mask[ra] && !mask[cb] {
                                self.assembly.add(slot, a, b, kt[(6 * p + a, 6 * q + b)]);
                            }
                        }
                    }
                }
            }
        }
        for (k, m) in mask.iter().enumerate() {
            if *m {
                r[k] = 0.0;
            }
        }
        eval.norm = r.iter().map(|x| x * x).sum::<f64>().sqrt();
        eval.r = r;
        eval
    }

    /// Largest motion over the increment `d` of a vertex near a neighbouring
    /// block (inside its box grown by the search distance) relative to that
    /// block's material.
    fn fastest_vertex(&self, d: &[f64]) -> (usize, f64) {
        let mut worst = (0, 0.0f64);
        for &(i, j) in &self.pairs {
            for (a, b) in [(i, j), (j, i)] {
                let (da, db) = (Self::block_dofs(d, a), Self::block_dofs(d, b));
                let near = self.blocks[b]
                    .polygon()
                    .aabb(&self.blocks[b].pose())
                    .inflated(self.settings.search_distance);
                for v in 0..self.blocks[a].vertex_count() {
                    let p = self.blocks[a].vertex(v);
                    if p.x < near.min.x || p.x > near.max.x || p.y < near.min.y || p.y > near.max.y
                    {
                        continue;
                    }
                    let rel = self.blocks[a].displacement_matrix(&p) * da
                        - self.blocks[b].displacement_matrix(&p) * db;
                    if rel.norm() > worst.1 {
                        worst = (a, rel.norm());
                    }
                }
            }
        }
        worst
    }

    /// Accept a trial: move the blocks, update velocities and accelerations
    /// (Newmark), keep the contact states.
    fn commit(
        &mut self,
        contacts: &[VertexEdge],
        trial: &Trial,
    ) -> std::result::Result<(), StepFailure> {
        let mut moved = self.blocks.clone();
        for (i, b) in moved.iter_mut().enumerate() {
            let di = Self::block_dofs(&trial.d, i);
            b.apply_increment(&di, i)
                .map_err(|e| StepFailure::Geometry(e.to_string()))?;
            for k in 0..6 {
                if self.settings.dynamic {
                    let (mut v, mut a) = (b.velocity[k], b.acceleration[k]);
                    self.integrator
                        .finish_implicit(trial.dt, di[k], &mut v, &mut a);
                    b.velocity[k] = v;
                    b.acceleration[k] = a;
                } else {
                    b.velocity[k] = 0.0;
                    b.acceleration[k] = 0.0;
                }
            }
        }
        for fp in &mut self.fixed_points {
            let t = self.blocks[fp.block].displacement_matrix(&fp.point);
            fp.point += t * Self::block_dofs(&trial.d, fp.block);
        }
        // Contact reports in the accepted configuration.
        self.history.clear();
        self.contacts.clear();
        for ((c, s), &(t_n, t_s)) in contacts.iter().zip(&trial.states).zip(&trial.forces) {
            let bk = &self.blocks[c.edge_block];
            let (x2, x3) = (bk.vertex(c.edge), bk.vertex(c.edge + 1));
            let t2 = bk.displacement_matrix(&x2) * Self::block_dofs(&trial.d, c.edge_block);
            let t3 = bk.displacement_matrix(&x3) * Self::block_dofs(&trial.d, c.edge_block);
            let b = (x3 + t3) - (x2 + t2);
            let tau = b / b.norm();
            let normal = Vec2::new(tau.y, -tau.x);
            let bj = &self.blocks[c.vertex_block];
            let x1 = bj.vertex(c.vertex);
            let point =
                x1 + bj.displacement_matrix(&x1) * Self::block_dofs(&trial.d, c.vertex_block);
            if s.regime != Some(Regime::Open) {
                self.history.insert(c.key(), *s);
            }
            self.contacts.push(ContactReport {
                contact: *c,
                state: *s,
                force: (t_n, t_s),
                force_on_vertex: normal * t_n - tau * t_s,
                point,
            });
        }
        self.blocks = moved;
        self.time += trial.dt;
        Ok(())
    }

    /// Like [`DdaModel::advance`], for drivers that cannot go on after a
    /// failed step: a [`StepStatus::Failed`] becomes
    /// [`DismechError::StepFailed`], which says what failed.
    pub fn advance_or_stop(&mut self, dt: f64) -> Result<StepReport> {
        let report = self.advance(dt)?;
        match report.status {
            StepStatus::Failed {
                time,
                dt,
                ref reason,
            } => Err(DismechError::StepFailed {
                time,
                dt,
                reason: reason.to_string(),
            }),
            StepStatus::Converged => Ok(report),
        }
    }

    /// Total contact force on `block` from the contacts of the last
    /// accepted step (N/m).
    pub fn contact_force_on(&self, block: usize) -> Vec2 {
        self.contacts.iter().fold(Vec2::zeros(), |f, c| {
            if c.contact.vertex_block == block {
                f + c.force_on_vertex
            } else if c.contact.edge_block == block {
                f - c.force_on_vertex
            } else {
                f
            }
        })
    }

    /// Advance the model by `dt` (s), in sub-steps if a step has to be
    /// reduced. Misuse (`dt ≤ 0`) is an error; a step that cannot be
    /// completed within the reduction bound is a [`StepStatus::Failed`].
    pub fn advance(&mut self, dt: f64) -> Result<StepReport> {
        require_positive("time step dt", dt)?;
        if self.requested_dt != Some(dt) {
            self.requested_dt = Some(dt);
            self.current_dt = dt;
        }
        let end = self.time + dt;
        let mut report = StepReport {
            status: StepStatus::Converged,
            substeps: 0,
            reductions: 0,
            smallest_dt: dt,
            residuals: Vec::new(),
            step_lengths: Vec::new(),
            open_close_iterations: 0,
        };
        while end - self.time > 1e-12 * dt {
            let h = self.current_dt.min(end - self.time);
            let contacts = self.detect();
            let outcome = self.trial(h, &contacts).and_then(|trial| {
                let (block, motion) = self.fastest_vertex(&trial.d);
                if motion > self.settings.search_distance {
                    Err(StepFailure::TooFast { block, motion })
                } else {
                    Ok(trial)
                }
            });
            let outcome = outcome.and_then(|trial| {
                self.commit(&contacts, &trial)?;
                Ok(trial)
            });
            match outcome {
                Ok(trial) => {
                    report.substeps += 1;
                    report.smallest_dt = report.smallest_dt.min(h);
                    report.residuals = trial.residuals;
                    report.step_lengths = trial.step_lengths;
                    report.open_close_iterations = trial.open_close;
                    self.current_dt = (2.0 * self.current_dt).min(dt);
                }
                Err(reason) => {
                    if h / 2.0 >= dt * self.settings.min_dt_ratio * (1.0 - 1e-12) {
                        self.current_dt = h / 2.0;
                        report.reductions += 1;
                    } else {
                        report.status = StepStatus::Failed {
                            time: self.time,
                            dt: h,
                            reason,
                        };
                        return Ok(report);
                    }
                }
            }
        }
        Ok(report)
    }
}
