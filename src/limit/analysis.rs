//! Assembly of the kinematic LP and its solution.

use super::model::{LimitModel, LiveLoad, LoadDriver, Partner};
use super::verdict::{certify, dead_load_scales, record_bounds, status_of_load};
use super::LimitError;
use crate::error::{DismechError, Result};
use crate::lp::{LinearProgram, LpSolver, LpStatus};
use crate::math::{cross, Vec2};

/// How a limit analysis ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LimitStatus {
    /// A collapse mechanism was found at a load that is not zero; the
    /// limit load is certified: the LP's solution meets its optimality
    /// conditions (primal and dual feasibility, zero gap) at
    /// [`super::CERTIFICATE_TOLERANCE`].
    Collapse,
    /// No kinematically admissible mechanism exists: the assembly is locked
    /// and no finite load moves the plate (the LP is infeasible), while
    /// the dead loads alone are carried.
    Locked,
    /// The assembly collapses under its own (dead) loads, before any plate
    /// load or live load: a mechanism dissipates less than the dead loads
    /// supply (the kinematic LP is unbounded, the static LP infeasible),
    /// or a live load's multiplier at collapse is negative (the live load
    /// would have to act backwards to hold the dead loads). A body under a
    /// load that touches nothing is the simplest case.
    Unbounded,
    /// The driver moves the assembly with nothing to overcome: the limit
    /// load is zero to the resolution of the data (a certified optimum
    /// below [`super::CERTIFICATE_TOLERANCE`] times the objective's scale),
    /// e.g. an element that rolls away along its neighbour, or contacts
    /// without strength. There is no positive limit load; `load` is
    /// `Some(0.0)` and the two bounds are kept as solved.
    ZeroLoad,
    /// The LP solver stopped without a certified optimum.
    SolverTrouble(LpStatus),
}

/// The result of a limit analysis.
#[derive(Debug, Clone, PartialEq)]
pub struct LimitResult {
    /// Outcome.
    pub status: LimitStatus,
    /// Limit load on the plate, along its velocity (N per m), or the
    /// multiplier λ of the live load; `Some(0.0)` for
    /// [`LimitStatus::ZeroLoad`], `None` unless the status is
    /// [`LimitStatus::Collapse`] or [`LimitStatus::ZeroLoad`].
    pub load: Option<f64>,
    /// Upper bound: the minimum of the kinematic LP (dissipation minus the
    /// power of known loads, divided by the plate speed); `None` unless the
    /// status is [`LimitStatus::Collapse`] or [`LimitStatus::ZeroLoad`] (a
    /// solve that stopped without an optimum has no bound to report).
    pub kinematic_load: Option<f64>,
    /// Lower bound: the load in equilibrium with the dual contact forces;
    /// `None` unless the status is [`LimitStatus::Collapse`] or
    /// [`LimitStatus::ZeroLoad`].
    pub static_load: Option<f64>,
    /// Velocity of each element `(velocity, angular velocity)` in the
    /// mechanism (plate at unit speed).
    pub velocities: Vec<(Vec2, f64)>,
    /// Slip rate at each contact (relative tangential velocity of B w.r.t. A).
    pub slip: Vec<f64>,
    /// Opening rate at each contact (zero for a contact that keeps contact).
    pub opening: Vec<f64>,
    /// Normal force at each contact (compression positive).
    pub normal_force: Vec<f64>,
    /// Shear force at each contact (the sign of the slip it resists).
    pub shear_force: Vec<f64>,
    /// Interior-point iterations.
    pub iterations: u32,
    /// Clarabel's own termination status.
    pub solver_status: String,
    /// Number of LP variables, equality rows and non-zeros.
    pub lp_size: (usize, usize, usize),
}

/// Column indices of one contact's extra LP variables.
#[derive(Debug, Clone, Copy, Default)]
struct ContactColumns {
    slip: Option<(usize, usize)>,
    opening: Option<usize>,
    normal_row: usize,
    shear_row: Option<usize>,
}

/// What drives a collapse: a support moving at `speed`, or a live load
/// whose multiplier is sought.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Driver {
    /// Support `plate` moves at `speed` along its velocity.
    Plate {
        /// The support.
        plate: usize,
        /// Its speed.
        speed: f64,
    },
    /// The live load's power is normalised to 1.
    Live(LiveLoad),
    /// The dead loads' power is normalised to 1; they leave the objective.
    DeadLoads,
}

impl Driver {
    /// The speed the kinematic optimum is divided by (1 for a live load).
    fn speed(&self) -> f64 {
        match self {
            Driver::Plate { speed, .. } => *speed,
            Driver::Live(_) | Driver::DeadLoads => 1.0,
        }
    }
}

/// The kinematic LP of a model and where its unknowns sit.
struct KinematicLp {
    lp: LinearProgram,
    dof: Vec<usize>,
    columns: Vec<ContactColumns>,
    driver: Driver,
    /// Row of the live load's power normalisation.
    live_row: Option<usize>,
}

/// Assemble the kinematic LP of `model`.
fn build_kinematic_lp(model: &LimitModel) -> Result<KinematicLp> {
    let driver = driver(model)?;

    // Velocity unknowns: u, v (and θ̇ for rolling elements) per element.
    let mut dof = Vec::with_capacity(model.bodies().len());
    let mut n = 0;
    for b in model.bodies() {
        dof.push(n);
        n += if b.rotates { 3 } else { 2 };
    }
    // Extra unknowns per contact.
    let mut columns = vec![ContactColumns::default(); model.contacts().len()];
    for (c, contact) in model.contacts().iter().enumerate() {
        if contact.law.resists_shear() {
            columns[c].slip = Some((n, n + 1));
            n += 2;
        }
        if contact.law.is_unilateral() || contact.law.friction() > 0.0 {
            columns[c].opening = Some(n);
            n += 1;
        }
    }
    let mut lp = LinearProgram::new(n);
    if driver != Driver::DeadLoads {
        for (i, b) in model.bodies().iter().enumerate() {
            lp.objective[dof[i]] = -b.load.x;
            lp.objective[dof[i] + 1] = -b.load.y;
        }
    }

    let mut row = Vec::with_capacity(8);
    for (c, contact) in model.contacts().iter().enumerate() {
        let law = &contact.law;
        let mu = law.friction();
        // Normal: opening rate = Δv·n.
        let constant = jump_row(model, &dof, c, &contact.normal, &mut row);
        if let Some(opening) = columns[c].opening {
            row.push((opening, -1.0));
            columns[c].normal_row = lp.add_equality(&row, -constant);
            lp.add_bounds(opening, Some(0.0), None);
            if mu > 0.0 && !law.is_unilateral() {
                // Bilateral frictional contact: dissipation C cot φ × opening.
                lp.objective[opening] = law.cohesion() / mu;
            }
        } else {
            columns[c].normal_row = lp.add_equality(&row, -constant);
        }
        // Shear: slip rate = Δv·t = S⁺ − S⁻.
        if let Some((plus, minus)) = columns[c].slip {
            let constant = jump_row(model, &dof, c, &contact.tangent(), &mut row);
            row.push((plus, -1.0));
            row.push((minus, 1.0));
            columns[c].shear_row = Some(lp.add_equality(&row, -constant));
            lp.add_bounds(plus, Some(0.0), None);
            lp.add_bounds(minus, Some(0.0), None);
            let bilateral_frictional = mu > 0.0 && !law.is_unilateral();
            let cost = if bilateral_frictional {
                0.0
            } else {
                law.cohesion()
            };
            lp.objective[plus] = cost;
            lp.objective[minus] = cost;
            if let (Some(opening), true) = (columns[c].opening, mu > 0.0) {
                // Associated flow: opening ≥ |S| tan φ.
                lp.add_inequality(&[(plus, mu), (minus, mu), (opening, -1.0)], 0.0);
            }
        }
    }
    // A live load: its power on the mechanism is normalised to one.
    let live_row = match driver {
        Driver::Live(live) => {
            let b = &model.bodies()[live.body];
            let k = dof[live.body];
            let mut row = vec![(k, live.force.x), (k + 1, live.force.y)];
            if b.rotates {
                row.push((k + 2, cross(&(live.point - b.centre), &live.force)));
            }
            Some(lp.add_equality(&row, 1.0))
        }
        // The dead loads act at the reference points: no moment.
        Driver::DeadLoads => {
            let row: Vec<(usize, f64)> = model
                .bodies()
                .iter()
                .enumerate()
                .flat_map(|(i, b)| [(dof[i], b.load.x), (dof[i] + 1, b.load.y)])
                .filter(|&(_, f)| f != 0.0)
                .collect();
            Some(lp.add_equality(&row, 1.0))
        }
        Driver::Plate { .. } => None,
    };
    Ok(KinematicLp {
        lp,
        dof,
        columns,
        driver,
        live_row,
    })
}

/// Build and solve the kinematic LP of `model` with any LP solver.
///
/// An optimum is certified before it is reported: the solution must meet
/// the LP's optimality conditions at [`super::CERTIFICATE_TOLERANCE`],
/// whatever tolerance the solver was given. A zero optimum is reported as
/// [`LimitStatus::ZeroLoad`], a negative live-load multiplier as
/// [`LimitStatus::Unbounded`], and an infeasible LP as
/// [`LimitStatus::Locked`] only when the dead loads alone are carried
/// (else [`LimitStatus::Unbounded`], as the static LP says); see the
/// module documentation of `verdict`.
///
/// With the dead loads as the driver ([`LimitModel::multiply_dead_loads`])
/// the load is their multiplier λ at collapse; an infeasible LP (no
/// mechanism on which they do work) is [`LimitStatus::Locked`].
///
/// # Errors
/// [`LimitError::DrivingSupportCount`] for a model without exactly one
/// driver (one moving support, or a live load or the dead loads' multiplier
/// and no moving support); [`LimitError::NoDeadLoads`] for the dead
/// loads' multiplier where every dead load is zero;
/// [`LimitError::PlateTouchesNothing`] for a plate touching nothing;
/// [`DismechError::Solve`] for a solver that refuses the LP;
/// [`LimitError::UncertifiedOptimum`] when the solver reports an
/// optimum that fails the LP's optimality conditions (e.g. a loose
/// `LinearProgramSolver.tolerance`).
pub fn analyse<S: LpSolver>(model: &LimitModel, solver: &mut S) -> Result<LimitResult> {
    let KinematicLp {
        lp,
        dof,
        columns,
        driver,
        live_row,
    } = build_kinematic_lp(model)?;
    let speed = driver.speed();
    let lp_size = lp.size();
    let solution = solver.solve(&lp)?;

    let status = match solution.status {
        LpStatus::Optimal | LpStatus::AlmostOptimal => LimitStatus::Collapse,
        LpStatus::PrimalInfeasible => {
            dead_load_status(model, &driver, lp.clone(), live_row, solver)?
        }
        LpStatus::DualInfeasible => LimitStatus::Unbounded,
        other => LimitStatus::SolverTrouble(other),
    };
    let contacts = model.contacts();
    let mut result = LimitResult {
        status,
        load: None,
        kinematic_load: None,
        static_load: None,
        velocities: Vec::with_capacity(model.bodies().len()),
        slip: vec![0.0; contacts.len()],
        opening: vec![0.0; contacts.len()],
        normal_force: vec![0.0; contacts.len()],
        shear_force: vec![0.0; contacts.len()],
        iterations: solution.iterations,
        solver_status: solution.solver_status.clone(),
        lp_size,
    };
    if status != LimitStatus::Collapse {
        return Ok(result);
    }
    let optimality = certify(&lp, &solution, dead_load_scales(model, &driver, false))?;
    read_mechanism(model, &dof, &columns, &solution.x, &mut result);
    let mut plate_force = Vec2::zeros();
    for (c, contact) in contacts.iter().enumerate() {
        let cols = columns[c];
        // Dual multipliers → contact forces (see the module docs of
        // `crate::lp` for the sign convention).
        result.normal_force[c] = -solution.equality_duals[cols.normal_row];
        if let Some(r) = cols.shear_row {
            result.shear_force[c] = solution.equality_duals[r];
        }
        if let Driver::Plate { plate, .. } = driver {
            if contact.partner == Partner::Support(plate) {
                plate_force += contact.normal * result.normal_force[c]
                    - contact.tangent() * result.shear_force[c];
            }
        }
    }
    let static_load = match (driver, live_row) {
        // The load that drives the plate balances the elements' push on it.
        (Driver::Plate { plate, speed }, _) => {
            Some(-plate_force.dot(&(model.supports()[plate].velocity / speed)))
        }
        // The multiplier of the normalisation row (dual objective −y·1).
        (Driver::Live(_) | Driver::DeadLoads, Some(row)) => Some(-solution.equality_duals[row]),
        (Driver::Live(_) | Driver::DeadLoads, None) => None,
    };
    let kinematic = solution.objective / speed;
    result.status = status_of_load(&driver, solution.objective, kinematic, &optimality);
    record_bounds(&mut result, kinematic, static_load, kinematic);
    Ok(result)
}

/// The status of a model whose kinematic LP is infeasible: no mechanism
/// moves the driver, so it is [`LimitStatus::Locked`], unless the dead
/// loads alone make it collapse ([`LimitStatus::Unbounded`]): the
/// kinematic LP with the driver at rest (every right-hand side zero, no
/// live load's normalisation) is homogeneous, so its optimum is zero
/// unless a mechanism dissipates less than the dead loads supply.
///
/// # Errors
/// A solver that refuses the LP.
fn dead_load_status<S: LpSolver>(
    model: &LimitModel,
    driver: &Driver,
    mut lp: LinearProgram,
    live_row: Option<usize>,
    solver: &mut S,
) -> Result<LimitStatus> {
    // Multiplied dead loads that do no work on any mechanism are carried
    // at every multiple.
    if !model.has_dead_loads() || *driver == Driver::DeadLoads {
        return Ok(LimitStatus::Locked);
    }
    if let Some(row) = live_row {
        lp.equalities.retain(|t| t.0 != row);
        for t in &mut lp.equalities {
            if t.0 > row {
                t.0 -= 1;
            }
        }
        lp.equality_rhs.remove(row);
    }
    lp.equality_rhs.iter_mut().for_each(|b| *b = 0.0);
    Ok(match solver.solve(&lp)?.status {
        LpStatus::DualInfeasible => LimitStatus::Unbounded,
        LpStatus::Optimal | LpStatus::AlmostOptimal | LpStatus::PrimalInfeasible => {
            LimitStatus::Locked
        }
        other => LimitStatus::SolverTrouble(other),
    })
}

/// What drives the collapse of `model`: its live load or its dead loads
/// (then no support may move; dead loads must not all be zero), or its
/// one moving support (which must touch something).
pub(super) fn driver(model: &LimitModel) -> Result<Driver> {
    let drivers: Vec<usize> = model
        .supports()
        .iter()
        .enumerate()
        .filter(|(_, s)| s.velocity.norm() > 0.0)
        .map(|(i, _)| i)
        .collect();
    if let Some(load) = model.load_driver() {
        if !drivers.is_empty() {
            return Err(LimitError::DrivingSupportCount(drivers.len()).into());
        }
        return match load {
            LoadDriver::Live(live) => Ok(Driver::Live(*live)),
            LoadDriver::DeadLoads => {
                if model.has_dead_loads() {
                    Ok(Driver::DeadLoads)
                } else {
                    Err(LimitError::NoDeadLoads.into())
                }
            }
        };
    }
    if drivers.len() != 1 {
        return Err(LimitError::DrivingSupportCount(drivers.len()).into());
    }
    let plate = drivers[0];
    if !model
        .contacts()
        .iter()
        .any(|c| c.partner == Partner::Support(plate))
    {
        return Err(LimitError::PlateTouchesNothing {
            support: plate,
            name: model.supports()[plate].name.clone(),
        }
        .into());
    }
    Ok(Driver::Plate {
        plate,
        speed: model.supports()[plate].velocity.norm(),
    })
}

/// Element velocities, slips and openings of an LP solution `x`.
fn read_mechanism(
    model: &LimitModel,
    dof: &[usize],
    columns: &[ContactColumns],
    x: &[f64],
    result: &mut LimitResult,
) {
    result.velocities.clear();
    for (i, b) in model.bodies().iter().enumerate() {
        let k = dof[i];
        let omega = if b.rotates { x[k + 2] } else { 0.0 };
        result.velocities.push((Vec2::new(x[k], x[k + 1]), omega));
    }
    for (c, cols) in columns.iter().enumerate() {
        result.slip[c] = cols.slip.map_or(0.0, |(plus, minus)| x[plus] - x[minus]);
        result.opening[c] = cols.opening.map_or(0.0, |opening| x[opening]);
    }
}

/// Coefficients of `Δv · direction` at contact `c` in terms of the element
/// velocities (into `row`), and the constant part from moving supports.
fn jump_row(
    model: &LimitModel,
    dof: &[usize],
    c: usize,
    direction: &Vec2,
    row: &mut Vec<(usize, f64)>,
) -> f64 {
    row.clear();
    let contact = &model.contacts()[c];
    let add_body = |i: usize, sign: f64, row: &mut Vec<(usize, f64)>| {
        let b = &model.bodies()[i];
        let k = dof[i];
        row.push((k, sign * direction.x));
        row.push((k + 1, sign * direction.y));
        if b.rotates {
            // ω × r = ω perp(r), so its component along d is ω (r × d).
            let r = contact.point - b.centre;
            row.push((k + 2, sign * cross(&r, direction)));
        }
    };
    add_body(contact.body, -1.0, row);
    match contact.partner {
        Partner::Body(j) => {
            add_body(j, 1.0, row);
            0.0
        }
        Partner::Support(s) => model.supports()[s].velocity.dot(direction),
    }
}

/// Whether the optimal mechanism is unique, tested on the element
/// velocities.
#[derive(Debug, Clone, PartialEq)]
pub struct Uniqueness {
    /// `true` when every optimal mechanism has the same element velocities
    /// (within the tolerance).
    pub unique: bool,
    /// Spread `max f − min f` of a fixed generic linear functional `f` of
    /// the velocities over the optimal face.
    pub spread: f64,
    /// A vertex of the optimal face: the optimal mechanism that minimises
    /// `f` (the result with its velocities, slips and openings replaced).
    /// When the optimum is not unique this is one pure mechanism, where
    /// the interior-point optimum may be a blend of several. When the face
    /// is unbounded (`spread` infinite: an element moves freely at no cost)
    /// there is no vertex and this is the interior-point optimum itself.
    pub vertex: LimitResult,
}

/// Test whether the optimum of a solved model is unique: fix the
/// dissipation at its optimum (within a relative `1e-7`) and minimise and
/// maximise a generic linear functional of the element velocities over
/// that optimal face. An interior-point solver returns a point inside the
/// face, which may blend several optimal vertex mechanisms; a spread above
/// `1e-4` (relative to the velocity scale) says the face is not a point.
///
/// Each of the two optima is certified as [`analyse`] certifies its own:
/// checked against the optimality conditions of its LP at
/// [`super::CERTIFICATE_TOLERANCE`], whatever tolerance the solver was
/// given, before its extreme or its vertex is used (a loosely solved
/// extreme could make a unique mechanism look blended, or the reverse).
///
/// # Errors
/// [`LimitError::NoLimitLoad`] when `result` has no kinematic load (it
/// is not a collapse); [`LimitError::UncertifiedOptimum`] when the
/// solver reports an optimum of either LP that fails its optimality
/// conditions (e.g. a loose `LinearProgramSolver.tolerance`);
/// [`DismechError::Solve`] when either LP ends without an optimum (other
/// than an unbounded face, which is reported as not unique) or the solver
/// refuses it; as [`analyse`] for the model's own checks.
pub fn mechanism_uniqueness<S: LpSolver>(
    model: &LimitModel,
    solver: &mut S,
    result: &LimitResult,
) -> Result<Uniqueness> {
    let kinematic = result.kinematic_load.ok_or(LimitError::NoLimitLoad {
        status: result.status,
        what: "the uniqueness test of the mechanism",
    })?;
    let KinematicLp {
        mut lp,
        dof,
        columns,
        driver,
        ..
    } = build_kinematic_lp(model)?;
    let speed = driver.speed();
    let optimum = kinematic * speed;
    let row: Vec<(usize, f64)> = lp
        .objective
        .iter()
        .enumerate()
        .filter(|(_, c)| **c != 0.0)
        .map(|(j, c)| (j, *c))
        .collect();
    lp.add_inequality(&row, optimum + 1e-7 * (1.0 + optimum.abs()));
    // A generic functional: weights from a fixed irrational sequence.
    let mut weights = vec![0.0; lp.num_variables];
    for (i, &k) in dof.iter().enumerate() {
        let columns = if model.bodies()[i].rotates { 3 } else { 2 };
        for d in 0..columns {
            weights[k + d] = ((k + d + 1) as f64 * 0.618_033_988_749_895).fract() - 0.5;
        }
    }
    let mut extreme = [0.0; 2];
    let mut vertex = result.clone();
    for (slot, sign) in [1.0, -1.0].into_iter().enumerate() {
        lp.objective = weights.iter().map(|w| sign * w).collect();
        let solution = solver.solve(&lp)?;
        if solution.status == LpStatus::DualInfeasible {
            // The optimal face is unbounded: some element can move freely
            // at no cost (a rattler, or a rolling element between smooth
            // contacts), so the mechanism is not unique and has no vertex.
            return Ok(Uniqueness {
                unique: false,
                spread: f64::INFINITY,
                vertex: result.clone(),
            });
        }
        if !matches!(solution.status, LpStatus::Optimal | LpStatus::AlmostOptimal) {
            return Err(DismechError::Solve(
                crate::error::SolveError::LinearProgram(crate::error::LpFailure::UniquenessTest {
                    status: solution.status,
                }),
            ));
        }
        certify(&lp, &solution, dead_load_scales(model, &driver, false))?;
        extreme[slot] = sign * solution.objective;
        if slot == 0 && solution.x.len() == lp.num_variables {
            read_mechanism(model, &dof, &columns, &solution.x, &mut vertex);
        }
    }
    let scale = result
        .velocities
        .iter()
        .map(|(v, w)| v.norm().max(w.abs()))
        .fold(1.0, f64::max);
    let spread = (extreme[1] - extreme[0]).abs();
    Ok(Uniqueness {
        unique: spread <= 1e-4 * scale,
        spread,
        vertex,
    })
}
