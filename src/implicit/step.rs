//! One trial step of the implicit driver: the linearised weak form
//! assembled from the bodies and the contacts of the step, solved by an
//! open–close iteration and then Newton–Raphson with a backtracking line
//! search (paper 003, Fig. 5, written over the slots), an update stopped
//! where a contact whose slip would reverse a second time sticks.
//!
//! One step of size `Δt` solves for the increments `d` of all unknowns
//!
//! `R(d) = M a₁(d) + α M v₁(d) + K d + f_σ − f_ext + Σ_c (−t_n ∇g_n + t_s ∇g_s) + Σ_f k_f Jᵀ J d = 0`
//!
//! with `a₁ = c_a d − a_v v₀ − a_a a₀` from the integrator, the mass `M`
//! and elastic stiffness `K` from the kinematics, the internal force `f_σ`
//! of the current stress, the contact forces of the law and the fixed-point
//! springs of classic DDA. Each iteration evaluates every contact at the
//! current iterate and assembles `R` and the tangent
//!
//! `c_a M + K + Σ_c [Jᵀ C J + t_n ∇²(−g_n) + t_s ∇²g_s] + Σ_f k_f JᵀJ`
//!
//! (`J` = the rows `∇(−g_n)`, `∇g_s` from the pair query; `C` the law's
//! tangent; the Hessian terms are paper 003 eq. 12's `Δδg_n`, `Δδg_s`),
//! and solves `K_T Δd = −R` with the linear solver on a block pattern kept
//! while the pairs in contact are unchanged.

use nalgebra::{SMatrix, SVector};

use super::body::Body;
use super::detect::StepContact;
use super::laws::ContactLaws;
use super::motion;
use super::report::StepFailure;
use crate::integrate::ImplicitCoefficients;
use crate::kinematics::Kinematics;
use crate::law::{ContactInput, ContactResponse, PairProperties, Regime, Tangent, TangentLaw};
use crate::linsolve::{BlockAssembly, LinearSolver, SparseMatrix};
use crate::query::variation::{GapVariation, PairContact};

/// The largest relative residual a law without a consistent tangent may
/// leave once its contact states settled. A block resting on a base
/// (E = 1 GPa) leaves 4e-12 at a penalty of 1e9, 4e-9 at 1e12 and 3e-6 at
/// 1e15 (stresses still right), and 1.1e-5 from 1e20 on, where double
/// precision no longer resolves the gap and the stresses are wrong.
pub(super) const SETTLED_RESIDUAL_LIMIT: f64 = 5e-6;

/// How far above the estimated round-off of the residual
/// ([`Evaluation::floor`]) Newton is taken to have reached it: the solve's
/// own rounding and the sums over many terms leave the reachable residual
/// some tens of times above the estimate (40 times on a stack of five
/// blocks at penalties of 1e16 and 1e18, where Newton stalled at 1e-9 and
/// 1e-7 against the default tolerance of 1e-10).
pub(super) const FLOOR_FACTOR: f64 = 100.0;

/// Most halvings of a Newton step in the backtracking line search.
pub(super) const LINE_SEARCH: usize = 8;

/// The parts of a step's residual that do not depend on the iterate.
pub(super) struct Parts<const N: usize> {
    /// Per body: effective stiffness (elastic + inertia + fixed points).
    pub block_k: Vec<SMatrix<f64, N, N>>,
    /// Per body: force at zero increment.
    pub block_f: Vec<SVector<f64, N>>,
    /// Prescribed unknowns.
    pub mask: Vec<bool>,
    /// Consistent linearisation (Newton with the Hessian terms) or the
    /// classic open–close acceptance.
    pub consistent: bool,
    /// Scale of the loads, for the relative residual.
    pub scale: f64,
}

/// Residual and contact states at one iterate.
pub(super) struct Evaluation<S> {
    pub r: Vec<f64>,
    pub norm: f64,
    pub contact_scale: f64,
    /// The round-off of `norm`: the norm of the vector whose entries bound
    /// the rounding of each entry of the residual (see
    /// [`StepData::assemble`]).
    pub floor: f64,
    /// The largest normal stiffness of a contact's law at this iterate.
    pub stiffness: f64,
    /// Per contact: 0 open, 1 stick, 2 / 3 slip with `t_s ≥ 0` / `< 0`.
    pub regimes: Vec<i8>,
    pub states: Vec<S>,
    pub forces: Vec<(f64, f64)>,
}

/// One contact's share at an iterate: the law's response, and where the
/// contact carries a force or has a tangent, its forces on bodies A and B,
/// the tangent blocks `[[AA, AB], [BA, BB]]` in their unknowns, and the
/// magnitudes whose `ε` multiple bounds the rounding of the forces.
#[allow(clippy::type_complexity)]
struct Share<const N: usize, S> {
    response: ContactResponse<2, S>,
    /// The law's normal stiffness.
    stiffness: f64,
    on_bodies: Option<(
        [SVector<f64, N>; 2],
        [[SMatrix<f64, N, N>; 2]; 2],
        [SVector<f64, N>; 2],
    )>,
}

/// Result of one trial step.
pub(super) struct Trial<S> {
    pub dt: f64,
    pub d: Vec<f64>,
    pub regimes: Vec<i8>,
    pub states: Vec<S>,
    pub forces: Vec<(f64, f64)>,
    pub residuals: Vec<f64>,
    pub step_lengths: Vec<f64>,
    pub open_close: usize,
}

/// What a trial needs to read: the bodies, their kinematics, the laws and
/// the contact history.
pub(super) struct StepData<'a, const N: usize, K, L: TangentLaw<2>> {
    pub bodies: &'a [Body<N>],
    pub kinematics: &'a K,
    pub laws: &'a ContactLaws<L>,
    pub contacts: &'a [StepContact],
    /// Per contact: its history from the last step, `None` for a new one
    /// (looked up once for the step, not at every evaluation).
    pub histories: Vec<Option<L::State>>,
    pub dt: f64,
    /// Fraction of the normal stiffness added to the shear stiffness of a
    /// slipping contact in the tangent ([`super::ImplicitSettings::slip_regularization`]).
    pub slip_regularization: f64,
    /// The quantile of the stick points at which an update is stopped
    /// ([`super::ImplicitSettings::slip_reversal_quantile`]).
    pub slip_reversal_quantile: f64,
    /// The step's search distance: the largest motion of a boundary point
    /// in one Newton update.
    pub search: f64,
}

/// A contact's regime as the iteration compares it: 0 open, 1 stick, 2 / 3
/// slip with `t_s ≥ 0` / `< 0`.
fn regime_code<S>(response: &ContactResponse<2, S>) -> i8 {
    match response.regime {
        Regime::Open => 0,
        Regime::Stick => 1,
        Regime::Slip if response.force[1] >= 0.0 => 2,
        Regime::Slip => 3,
    }
}

/// Halvings of the search for where a contact whose slip reverses sticks.
const STICK_SEARCH: usize = 60;

/// The unknowns of body `i` in the global vector `d`.
pub(super) fn body_dofs<const N: usize>(d: &[f64], i: usize) -> SVector<f64, N> {
    SVector::<f64, N>::from_column_slice(&d[N * i..N * i + N])
}

impl<const N: usize, K: Kinematics<N>, L: TangentLaw<2>> StepData<'_, N, K, L> {
    /// The law for contact `c` at the gap `gap` and shear `shear` of an
    /// iterate. Where it answers no force and no tangent (an open contact
    /// of a penalty law) the iterate needs no variations of the contact,
    /// which are most of its cost.
    fn respond(
        &self,
        k: usize,
        c: &StepContact,
        gap: f64,
        shear: f64,
    ) -> (ContactResponse<2, L::State>, Tangent<2>) {
        let history = &self.histories[k];
        let (ba, bb) = (&self.bodies[c.a], &self.bodies[c.b]);
        let input = ContactInput {
            overlap: -gap,
            increment: SVector::<f64, 2>::new(c.geometry.initial_gap() - gap, shear),
            dt: self.dt,
            is_new: history.is_none(),
            pair: PairProperties {
                curvature_radius_a: f64::INFINITY,
                curvature_radius_b: f64::INFINITY,
                width: 0.0,
                mass_a: ba.area() * ba.material().density,
                mass_b: bb.area() * bb.material().density,
            },
            rotation: 0.0,
        };
        let law = self.laws.law(ba.group, bb.group);
        let answer = match history {
            Some(old) => law.evaluate_with_tangent(&input, old),
            None => law.evaluate_with_tangent(&input, &L::State::default()),
        };
        debug_assert!(
            law.moment(&answer.0.state) == 0.0,
            "a tangent law answered a rolling moment, which the implicit driver does not apply"
        );
        answer
    }

    /// Contact `c`'s share of the residual and (with `matrix`) of the
    /// tangent at the iterate `d`, from its geometry `g`, written in the
    /// contact's local variables `z = z₀ + C_A d_A + C_B d_B` and mapped to
    /// the bodies' unknowns once: the forces `C_Aᵀ f`, `C_Bᵀ f` with `f =
    /// −t_n ∇g_n + t_s ∇g_s`, and the tangent blocks `C_pᵀ K C_q` with `K =
    /// Σ_ij c_ij r_i r_jᵀ − t_n ∇²g_n + t_s ∇²g_s` (`r = (−∇g_n, ∇g_s)`,
    /// `c` the law's tangent; the second variations only for a consistent
    /// law at a closed contact), plus the curvature of a nonlinear
    /// kinematics' map weighted by `Lᵀ f`. Nothing is mapped where the law
    /// answers no force and no tangent (an open contact of a penalty law),
    /// and then the variations are not computed.
    fn share<const M: usize, G: GapVariation<M>>(
        &self,
        g: &G,
        k: usize,
        c: &StepContact,
        d: &[f64],
        consistent: bool,
        matrix: bool,
    ) -> Result<Share<N, L::State>, StepFailure> {
        let (d_a, d_b) = (body_dofs::<N>(d, c.a), body_dofs::<N>(d, c.b));
        let kin = self.kinematics;
        let (z, ca, cb) = g.dof_local_variables(kin, &d_a, kin, &d_b);
        // A kind whose values cost as much as its variations computes them
        // once.
        let mut known = None;
        let (gap, shear) = if G::VALUES_ALONE {
            g.values(&z).map_err(StepFailure::Variation)?
        } else {
            let local = g.local(&z).map_err(StepFailure::Variation)?;
            let values = (local.gap, local.shear);
            known = Some(local);
            values
        };
        let (response, mut tangent) = self.respond(k, c, gap, shear);
        if response.force.iter().all(|f| *f == 0.0) && tangent.iter().all(|t| *t == 0.0) {
            return Ok(Share {
                response,
                stiffness: 0.0,
                on_bodies: None,
            });
        }
        if response.regime == Regime::Slip {
            tangent[(1, 1)] += self.slip_regularization * tangent[(0, 0)].abs();
        }
        let local = match known {
            Some(local) => local,
            None => g.local(&z).map_err(StepFailure::Variation)?,
        };
        let (t_n, t_s) = (response.force[0], response.force[1]);
        let f = local.grad_shear * t_s - local.grad_gap * t_n;
        let (ta, tb) = (ca.transpose(), cb.transpose());
        let forces = [ta * f, tb * f];
        // The size of the terms of the forces, and the force the rounding
        // of the gap and shear makes through the law's stiffnesses.
        let motion = (ca * d_a).norm() + (cb * d_b).norm() + gap.abs() + shear.abs();
        let stiffness = tangent.abs().column_sum();
        let spread = local.grad_gap.abs() + local.grad_shear.abs();
        let size = spread * (t_n.abs() + t_s.abs() + (stiffness[0] + stiffness[1]) * motion);
        let magnitudes = [ta.abs() * size, tb.abs() * size];
        let mut blocks = [[SMatrix::<f64, N, N>::zeros(); 2]; 2];
        if matrix {
            let rows = [-local.grad_gap, local.grad_shear];
            let mut kz = SMatrix::<f64, M, M>::zeros();
            for (i, ri) in rows.iter().enumerate() {
                for (j, rj) in rows.iter().enumerate() {
                    let cij = tangent[(i, j)];
                    if cij != 0.0 {
                        kz += ri * rj.transpose() * cij;
                    }
                }
            }
            let curved = consistent && response.regime != Regime::Open;
            if curved {
                kz += local.hess_shear * t_s - local.hess_gap * t_n;
            }
            let (wa, wb) = (ta * kz, tb * kz);
            blocks = [[wa * ca, wa * cb], [wb * ca, wb * cb]];
            if curved && !(K::LINEAR) {
                let (la, lb) = g.chain();
                blocks[0][0] += kin.map_curvature(&d_a, &(la.transpose() * f));
                blocks[1][1] += kin.map_curvature(&d_b, &(lb.transpose() * f));
            }
        }
        Ok(Share {
            response,
            stiffness: tangent[(0, 0)].abs(),
            on_bodies: Some((forces, blocks, magnitudes)),
        })
    }

    /// The regime code of contact `c` at the iterate `d` (the law alone,
    /// without the variations).
    fn regime_at(&self, k: usize, c: &StepContact, d: &[f64]) -> Result<i8, StepFailure> {
        let (d_a, d_b) = (body_dofs::<N>(d, c.a), body_dofs::<N>(d, c.b));
        let (gap, shear) = c
            .geometry
            .dof_values(self.kinematics, &d_a, self.kinematics, &d_b)
            .map_err(StepFailure::Variation)?;
        Ok(regime_code(&self.respond(k, c, gap, shear).0))
    }

    /// The parts of the residual that do not depend on the iterate, for
    /// the integrator's coefficients `coeffs`, gravity `gravity` and the
    /// fixed points `(body, point, anchor, stiffness)`.
    pub fn parts(
        &self,
        coeffs: &ImplicitCoefficients,
        gravity: &crate::math::Vec2,
        mass_damping: f64,
        fixed_points: &[super::FixedPoint],
        mask: Vec<bool>,
    ) -> Parts<N> {
        let zero = SVector::<f64, N>::zeros();
        let mut block_k = Vec::with_capacity(self.bodies.len());
        let mut block_f = Vec::with_capacity(self.bodies.len());
        let mut scale = 0.0f64;
        for b in self.bodies {
            let moments = b.geometry().moments();
            let elastic = b.material().elastic_matrix();
            let mut k = self.kinematics.stiffness(&moments, &elastic);
            let ext = external_force(self.kinematics, b, gravity);
            let stress_force = self.kinematics.stress_force(&moments, &b.stress);
            let mut f = stress_force - ext;
            scale = scale.max(ext.norm()).max(stress_force.norm());
            let m = self.kinematics.mass(&moments, b.material().density);
            // Inertia `M a₁` and damping `α M v₁`, with `a₁`, `v₁` linear
            // in the increment by the integrator's coefficients.
            k += m
                * (coeffs.acceleration_per_increment
                    + mass_damping * coeffs.velocity_per_increment);
            let hist = m
                * (b.velocity
                    * (coeffs.acceleration_from_velocity
                        + mass_damping * coeffs.velocity_from_velocity)
                    + b.acceleration
                        * (coeffs.acceleration_from_acceleration
                            + mass_damping * coeffs.velocity_from_acceleration));
            f -= hist;
            scale = scale.max(hist.norm());
            block_k.push(k);
            block_f.push(f);
        }
        for fp in fixed_points {
            let body = &self.bodies[fp.body];
            let t = self
                .kinematics
                .point_jacobian(&zero, &(fp.point - body.centroid()));
            block_k[fp.body] += t.transpose() * t * fp.stiffness;
            block_f[fp.body] += t.transpose() * (fp.point - fp.anchor) * fp.stiffness;
        }
        let consistent = self.laws.default_law().is_consistent();
        Parts {
            block_k,
            block_f,
            mask,
            consistent,
            scale,
        }
    }

    /// Residual (and, with `matrix`, the tangent in `assembly`) at the
    /// iterate `d`, with the round-off of its norm.
    ///
    /// The round-off is that of the sums and products that make each entry
    /// (`ε` times the sum of the magnitudes of their terms: the bodies'
    /// `|f| + |K||d|`, each contact's forces), and that of each contact's
    /// gap and shear, which its law multiplies by its stiffnesses: the
    /// contact's local variables `z = z₀ + C_A d_A + C_B d_B` sum the two
    /// bodies' motions over the step, which nearly cancel where they move
    /// together, so a gap is known to `ε (|C_A d_A| + |C_B d_B|)` and a
    /// penalty `p` makes a force of `p` times that. Below that Newton cannot
    /// take the residual; the test of convergence accepts it there.
    pub fn assemble(
        &self,
        d: &[f64],
        parts: &Parts<N>,
        assembly: &mut BlockAssembly,
        matrix: bool,
    ) -> Result<Evaluation<L::State>, StepFailure> {
        let nb = self.bodies.len();
        let mask = &parts.mask;
        let mut r = vec![0.0; N * nb];
        let mut rounding = vec![0.0; N * nb];
        if matrix {
            assembly.clear();
        }
        for i in 0..nb {
            let k = &parts.block_k[i];
            let di = body_dofs::<N>(d, i);
            let fi = parts.block_f[i] + k * di;
            let magnitude = parts.block_f[i].abs() + k.abs() * di.abs();
            let slot = assembly.slot(i, i);
            for a in 0..N {
                r[N * i + a] += fi[a];
                rounding[N * i + a] += magnitude[a];
                let Some(slot) = slot.filter(|_| matrix) else {
                    continue;
                };
                for b in 0..N {
                    let (ra, cb) = (N * i + a, N * i + b);
                    if !mask[ra] && !mask[cb] {
                        assembly.add(slot, a, b, k[(a, b)]);
                    }
                }
                if mask[N * i + a] {
                    assembly.add(slot, a, a, 1.0);
                }
            }
        }
        let mut eval = Evaluation {
            r: Vec::new(),
            norm: 0.0,
            contact_scale: 0.0,
            floor: 0.0,
            stiffness: 0.0,
            regimes: Vec::with_capacity(self.contacts.len()),
            states: Vec::with_capacity(self.contacts.len()),
            forces: Vec::with_capacity(self.contacts.len()),
        };
        for (k, c) in self.contacts.iter().enumerate() {
            let share = match &c.geometry {
                PairContact::VertexEdge(g) => self.share(g, k, c, d, parts.consistent, matrix)?,
                PairContact::SmoothEdge(g) => self.share(g, k, c, d, parts.consistent, matrix)?,
                PairContact::SmoothSmooth(g) => self.share(g, k, c, d, parts.consistent, matrix)?,
            };
            let (t_n, t_s) = (share.response.force[0], share.response.force[1]);
            eval.contact_scale = eval.contact_scale.max(t_n.abs() + t_s.abs());
            eval.regimes.push(regime_code(&share.response));
            eval.states.push(share.response.state);
            eval.forces.push((t_n, t_s));
            eval.stiffness = eval.stiffness.max(share.stiffness);
            let Some((forces, blocks, magnitudes)) = share.on_bodies else {
                continue;
            };
            let bodies = [c.a, c.b];
            for (side, force) in forces.iter().enumerate() {
                for a in 0..N {
                    r[N * bodies[side] + a] += force[a];
                    rounding[N * bodies[side] + a] += magnitudes[side][a];
                }
            }
            if !matrix {
                continue;
            }
            for (q, &column) in bodies.iter().enumerate() {
                for (p, &row) in bodies.iter().enumerate() {
                    // A block missing from the pattern has only prescribed
                    // entries.
                    let Some(slot) = assembly.slot(row, column) else {
                        continue;
                    };
                    let kt = &blocks[p][q];
                    for b in 0..N {
                        for a in 0..N {
                            let (ra, cb) = (N * row + a, N * column + b);
                            if !mask[ra] && !mask[cb] {
                                assembly.add(slot, a, b, kt[(a, b)]);
                            }
                        }
                    }
                }
            }
        }
        for (k, m) in mask.iter().enumerate() {
            if *m {
                r[k] = 0.0;
                rounding[k] = 0.0;
            }
        }
        eval.norm = r.iter().map(|x| x * x).sum::<f64>().sqrt();
        eval.floor = f64::EPSILON * rounding.iter().map(|x| x * x).sum::<f64>().sqrt();
        eval.r = r;
        Ok(eval)
    }

    /// Open–close, then Newton–Raphson with the line search, from the
    /// predictor `d` (see the module documentation); `solves` counts the
    /// linear solves.
    #[allow(clippy::too_many_arguments)]
    pub fn iterate<S: LinearSolver<SparseMatrix>>(
        &self,
        mut d: Vec<f64>,
        parts: &Parts<N>,
        assembly: &mut BlockAssembly,
        solver: &mut S,
        settings: &super::ImplicitSettings,
        solves: &mut usize,
    ) -> Result<Trial<L::State>, StepFailure> {
        let consistent = parts.consistent;
        let max_iter = settings.max_open_close + settings.max_newton;
        let mut residuals = Vec::new();
        let mut step_lengths = Vec::new();
        let mut open_close = 0;
        let mut newton = 0;
        let mut last_open: Option<Vec<bool>> = None;
        let mut last_regimes: Option<Vec<i8>> = None;
        // Per contact: whether its slip has reversed between two iterates.
        let mut reversed = vec![false; self.contacts.len()];
        let mut last_tolerance = settings.residual_tolerance;
        let mut eval = self.assemble(&d, parts, assembly, true)?;
        for _ in 0..=max_iter {
            let scale = parts.scale.max(eval.contact_scale).max(f64::MIN_POSITIVE);
            let (rel, floor) = (eval.norm / scale, eval.floor / scale);
            residuals.push(rel);
            if !rel.is_finite() {
                return Err(StepFailure::NonFiniteResidual);
            }
            if floor > SETTLED_RESIDUAL_LIMIT {
                // The round-off of the residual alone is above what a step
                // may leave: the answer would be noise.
                return Err(StepFailure::RoundOff {
                    floor,
                    limit: SETTLED_RESIDUAL_LIMIT,
                    stiffness: eval.stiffness,
                });
            }
            // The tolerance, or the residual's round-off where the penalty
            // makes that larger, up to what a step may leave.
            let tolerance = settings
                .residual_tolerance
                .max((FLOOR_FACTOR * floor).min(SETTLED_RESIDUAL_LIMIT));
            last_tolerance = tolerance;
            let open: Vec<bool> = eval.regimes.iter().map(|&r| r == 0).collect();
            let settled = last_open.as_ref() == Some(&open);
            if settled {
                let done = if consistent {
                    last_regimes.as_ref() == Some(&eval.regimes) && rel <= tolerance
                } else {
                    // Classic DDA accepts settled states; a residual far
                    // above the tolerance there is lost precision, not an
                    // iteration to continue.
                    if rel > SETTLED_RESIDUAL_LIMIT {
                        return Err(StepFailure::Imprecise {
                            residual: rel,
                            limit: SETTLED_RESIDUAL_LIMIT,
                        });
                    }
                    true
                };
                if done {
                    return Ok(Trial {
                        dt: self.dt,
                        d,
                        regimes: eval.regimes,
                        states: eval.states,
                        forces: eval.forces,
                        residuals,
                        step_lengths,
                        open_close,
                    });
                }
                newton += 1;
                if newton > settings.max_newton {
                    return Err(StepFailure::NewtonNotConverged {
                        iterations: newton - 1,
                        residual: rel,
                        tolerance,
                    });
                }
            } else if last_open.is_some() {
                open_close += 1;
                if open_close > settings.max_open_close {
                    return Err(StepFailure::OpenCloseNotSettled {
                        iterations: open_close - 1,
                    });
                }
            }
            last_open = Some(open);
            if let Some(last) = &last_regimes {
                for ((r, &was), &now) in reversed.iter_mut().zip(last).zip(&eval.regimes) {
                    *r |= was >= 2 && now >= 2 && was != now;
                }
            }
            last_regimes = Some(eval.regimes.clone());
            let mut delta: Vec<f64> = eval.r.iter().map(|x| -x).collect();
            let matrix = assembly.matrix();
            *solves += 1;
            solver
                .factor(matrix)
                .and_then(|()| solver.solve_in_place(matrix, &mut delta))
                .map_err(StepFailure::Solve)?;
            self.limit_update(&d, &mut delta, self.search);
            // A contact whose slip would reverse stops the update where it
            // sticks; then backtracking on ‖R‖ (consistent laws only): a
            // step that does not lower the residual is halved, up to
            // `LINE_SEARCH` times.
            let mut alpha = if consistent {
                self.slip_reversal_bound(&d, &delta, &eval.regimes, &reversed)?
            } else {
                1.0
            };
            // Each step tried is evaluated with its tangent, so that the
            // one taken needs no second evaluation.
            let mut next = Vec::with_capacity(d.len());
            let mut attempt = 0;
            let taken = loop {
                next.clear();
                next.extend(d.iter().zip(&delta).map(|(x, dx)| x + alpha * dx));
                let probe = self.assemble(&next, parts, assembly, true)?;
                if !consistent
                    || attempt == LINE_SEARCH
                    || probe.norm < (1.0 - 1e-4 * alpha) * eval.norm
                    || eval.norm == 0.0
                {
                    break probe;
                }
                alpha *= 0.5;
                attempt += 1;
            };
            // The step reached (accepted, or the last halving) is taken.
            step_lengths.push(alpha);
            std::mem::swap(&mut d, &mut next);
            eval = taken;
        }
        Err(StepFailure::NewtonNotConverged {
            iterations: newton,
            residual: residuals.last().copied().unwrap_or(f64::NAN),
            tolerance: last_tolerance,
        })
    }
}

impl<const N: usize, K: Kinematics<N>, L: TangentLaw<2>> StepData<'_, N, K, L> {
    /// The largest fraction of the Newton update `delta` from `d` that takes
    /// no slipping contact (`regimes`) whose slip has reversed before in
    /// this step's iteration (`reversed`) across its stick band to slip the
    /// other way again: the fraction at which the first such contact
    /// sticks (with [`super::ImplicitSettings::slip_reversal_quantile`] `q
    /// > 0`, the `q`-quantile of the fractions at which they stick).
    ///
    /// The stick band of a contact is narrow — the shear travel `2 μ t_n /
    /// k_s` between the two slip limits, micrometres for a stiff penalty —
    /// and the tangent of a slipping contact has no shear stiffness, so a
    /// full update jumps from one slip direction to the other and the next
    /// one jumps back: Newton cycles, and backtracking on ‖R‖ only shortens
    /// the jumps. Stopped inside the band, the contact sticks and the next
    /// update sees its shear stiffness. A first reversal is taken whole: a
    /// contact whose slip truly reverses within the step (and there are
    /// many as a packing or a wall takes its load) would otherwise cost an
    /// iteration each. The fraction is found by bisection
    /// on the contact's regime along the update (only the law's regimes are
    /// read, so this holds for any [`TangentLaw`]).
    fn slip_reversal_bound(
        &self,
        d: &[f64],
        delta: &[f64],
        regimes: &[i8],
        reversed: &[bool],
    ) -> Result<f64, StepFailure> {
        if !reversed.contains(&true) {
            return Ok(1.0);
        }
        // The iterate `d + α delta`, written only for the two bodies of
        // the contact evaluated (the pair query reads no other).
        let mut x = d.to_vec();
        let mut regime_along = |k: usize, alpha: f64| -> Result<i8, StepFailure> {
            let c = &self.contacts[k];
            for body in [c.a, c.b] {
                for i in N * body..N * body + N {
                    x[i] = d[i] + alpha * delta[i];
                }
            }
            self.regime_at(k, c, &x)
        };
        let mut bound = 1.0f64;
        let mut sticks = Vec::new();
        for ((k, &now), _) in regimes
            .iter()
            .enumerate()
            .zip(reversed)
            .filter(|(_, &cycled)| cycled)
        {
            if now < 2 {
                continue;
            }
            let end = regime_along(k, 1.0)?;
            if end < 2 || end == now {
                continue;
            }
            // `low` still slips as now, `high` does not.
            let (mut low, mut high) = (0.0f64, 1.0f64);
            for _ in 0..STICK_SEARCH {
                let mid = 0.5 * (low + high);
                match regime_along(k, mid)? {
                    r if r == now => low = mid,
                    0 | 1 => {
                        high = mid;
                        break;
                    }
                    _ => high = mid,
                }
            }
            bound = bound.min(high);
            sticks.push(high);
        }
        if self.slip_reversal_quantile > 0.0 && !sticks.is_empty() {
            sticks.sort_by(f64::total_cmp);
            let k = (sticks.len() as f64 * self.slip_reversal_quantile) as usize;
            return Ok(sticks[k.min(sticks.len() - 1)]);
        }
        Ok(bound)
    }

    /// Scale the Newton update `delta` at the iterate `d` so that it moves
    /// no boundary point further than `limit` (to first order): a step
    /// beyond the search distance is rejected anyway, and a tangent that
    /// is (nearly) singular — a disc whose every contact slips turns
    /// freely — would otherwise throw the iterate to a far spurious
    /// equilibrium.
    fn limit_update(&self, d: &[f64], delta: &mut [f64], limit: f64) {
        let largest = self.bodies.iter().enumerate().fold(0.0f64, |m, (i, b)| {
            m.max(motion::update_motion(
                self.kinematics,
                b,
                &body_dofs::<N>(d, i),
                &body_dofs::<N>(delta, i),
            ))
        });
        if largest > limit {
            let scale = limit / largest;
            delta.iter_mut().for_each(|x| *x *= scale);
        }
    }
}

/// External load of a body: its weight `ρ A g` at the reference point and
/// its edge tractions, `∫ Jᵀ t dΓ = L J(midpoint)ᵀ t` (J is linear along an
/// edge), at the start of the step.
pub(super) fn external_force<const N: usize, K: Kinematics<N>>(
    kinematics: &K,
    body: &Body<N>,
    gravity: &crate::math::Vec2,
) -> SVector<f64, N> {
    let zero = SVector::<f64, N>::zeros();
    let w = body.material().density * body.area();
    let mut f = kinematics
        .point_jacobian(&zero, &crate::math::Vec2::zeros())
        .transpose()
        * (gravity * w);
    let c = body.centroid();
    for &(edge, traction) in &body.edge_tractions {
        let (a, b) = (body.vertex(edge), body.vertex(edge + 1));
        let mid = crate::math::Point::from((a.coords + b.coords) * 0.5);
        f += kinematics.point_jacobian(&zero, &(mid - c)).transpose() * traction * (b - a).norm();
    }
    f
}
