//! The static (lower-bound) LP: maximise the plate load over contact
//! forces in equilibrium and within strength (paper 002 eq. 4 with
//! `|T| ≤ C + N tan φ`). It is the dual of the kinematic LP of
//! [`super::analyse`]: both give the same limit load; which one an
//! interior-point solver finishes faster depends on the model (see the
//! `limit_lp` benchmark).

use super::analysis::{driver, Driver, LimitResult, LimitStatus};
use super::model::{LimitModel, Partner};
use super::verdict::{certify, dead_load_scales, record_bounds, status_of_load};
use crate::error::Result;
use crate::lp::{LinearProgram, LpSolver, LpStatus};
use crate::math::{cross, Vec2};

/// Solve the static LP of `model` with any LP solver. The mechanism comes
/// from the multipliers of the equilibrium rows (element velocities);
/// slips and openings are left at zero.
///
/// The optimum is certified and classified as [`super::analyse`]'s:
/// checked against the LP's optimality conditions at
/// [`super::CERTIFICATE_TOLERANCE`], a zero load reported as
/// [`LimitStatus::ZeroLoad`], a negative live-load multiplier as
/// [`LimitStatus::Unbounded`]. An infeasible static LP (no field carries
/// the dead loads, whatever the driver's load) is
/// [`LimitStatus::Unbounded`]; an unbounded one (the dead loads are
/// carried and the load can grow without end) is [`LimitStatus::Locked`].
///
/// # Errors
/// As [`super::analyse`].
pub fn analyse_static<S: LpSolver>(model: &LimitModel, solver: &mut S) -> Result<LimitResult> {
    let driver = driver(model)?;
    let (plate, speed) = match driver {
        Driver::Plate { plate, speed } => (Some(plate), speed),
        Driver::Live(_) | Driver::DeadLoads => (None, 1.0),
    };
    let direction = plate.map_or(Vec2::zeros(), |p| model.supports()[p].velocity / speed);

    // Unknowns: P, then N (and T where the contact resists shear) per contact.
    let mut columns = Vec::with_capacity(model.contacts().len());
    let mut n = 1;
    for c in model.contacts() {
        let shear = c.law.resists_shear().then_some(n + 1);
        columns.push((n, shear));
        n += if shear.is_some() { 2 } else { 1 };
    }
    let mut lp = LinearProgram::new(n);
    lp.objective[0] = -1.0;
    // Equilibrium of each element: Σ contact forces + load = 0 (and moments
    // for rolling elements). Force on A from contact c: −N n + T t.
    let mut rows: Vec<[Vec<(usize, f64)>; 3]> = (0..model.bodies().len())
        .map(|_| [Vec::new(), Vec::new(), Vec::new()])
        .collect();
    let mut plate_row = vec![(0usize, 1.0)];
    for (c, contact) in model.contacts().iter().enumerate() {
        let (col_n, col_t) = columns[c];
        let (normal, tangent) = (contact.normal, contact.tangent());
        let add = |body: usize, sign: f64, rows: &mut Vec<[Vec<(usize, f64)>; 3]>| {
            let r = contact.point - model.bodies()[body].centre;
            // Force on this body: sign × (−N n + T t).
            rows[body][0].push((col_n, -sign * normal.x));
            rows[body][1].push((col_n, -sign * normal.y));
            rows[body][2].push((col_n, -sign * cross(&r, &normal)));
            if let Some(col_t) = col_t {
                rows[body][0].push((col_t, sign * tangent.x));
                rows[body][1].push((col_t, sign * tangent.y));
                rows[body][2].push((col_t, sign * cross(&r, &tangent)));
            }
        };
        add(contact.body, 1.0, &mut rows);
        match contact.partner {
            Partner::Body(b) => add(b, -1.0, &mut rows),
            Partner::Support(s) if Some(s) == plate => {
                // Plate equilibrium along its motion: P + (N n − T t)·d = 0.
                plate_row.push((col_n, normal.dot(&direction)));
                if let Some(col_t) = col_t {
                    plate_row.push((col_t, -tangent.dot(&direction)));
                }
            }
            Partner::Support(_) => {}
        }
        let law = &contact.law;
        if law.is_unilateral() {
            lp.add_bounds(col_n, Some(0.0), None);
        }
        if let Some(col_t) = col_t {
            let mu = law.friction();
            lp.add_inequality(&[(col_t, 1.0), (col_n, -mu)], law.cohesion());
            lp.add_inequality(&[(col_t, -1.0), (col_n, -mu)], law.cohesion());
        }
    }
    // A live load λ f at its point enters the loaded body's equilibrium.
    if let Driver::Live(live) = driver {
        let r = live.point - model.bodies()[live.body].centre;
        let rows_of = &mut rows[live.body];
        rows_of[0].push((0, live.force.x));
        rows_of[1].push((0, live.force.y));
        rows_of[2].push((0, cross(&r, &live.force)));
    }
    // Multiplied dead loads λ w enter every body's equilibrium through λ;
    // otherwise they are the right-hand side.
    let multiplied = driver == Driver::DeadLoads;
    let mut equilibrium_rows = Vec::with_capacity(model.bodies().len());
    for (i, b) in model.bodies().iter().enumerate() {
        let load: [f64; 3] = [b.load.x, b.load.y, 0.0];
        let count = if b.rotates { 3 } else { 2 };
        let mut ids = [usize::MAX; 3];
        for k in 0..count {
            if multiplied {
                if load[k] != 0.0 {
                    rows[i][k].push((0, load[k]));
                }
                ids[k] = lp.add_equality(&rows[i][k], 0.0);
            } else {
                ids[k] = lp.add_equality(&rows[i][k], -load[k]);
            }
        }
        equilibrium_rows.push(ids);
    }
    if plate.is_some() {
        lp.add_equality(&plate_row, 0.0);
    }
    let lp_size = lp.size();
    let solution = solver.solve(&lp)?;
    let status = match solution.status {
        LpStatus::Optimal | LpStatus::AlmostOptimal => LimitStatus::Collapse,
        // An unbounded static LP means no mechanism: locked.
        LpStatus::DualInfeasible => LimitStatus::Locked,
        LpStatus::PrimalInfeasible => LimitStatus::Unbounded,
        other => LimitStatus::SolverTrouble(other),
    };
    let contacts = model.contacts().len();
    let mut result = LimitResult {
        status,
        load: None,
        kinematic_load: None,
        static_load: None,
        velocities: Vec::new(),
        slip: vec![0.0; contacts],
        opening: vec![0.0; contacts],
        normal_force: vec![0.0; contacts],
        shear_force: vec![0.0; contacts],
        iterations: solution.iterations,
        solver_status: solution.solver_status.clone(),
        lp_size,
    };
    if status != LimitStatus::Collapse {
        return Ok(result);
    }
    let optimality = certify(&lp, &solution, dead_load_scales(model, &driver, true))?;
    for (c, &(col_n, col_t)) in columns.iter().enumerate() {
        result.normal_force[c] = solution.x[col_n];
        result.shear_force[c] = col_t.map_or(0.0, |k| solution.x[k]);
    }
    // Element velocities: the multipliers of the equilibrium rows, scaled
    // so that the plate moves at its speed.
    let scale = speed;
    for ids in &equilibrium_rows {
        let y = |k: usize| {
            if ids[k] == usize::MAX {
                0.0
            } else {
                solution.equality_duals[ids[k]]
            }
        };
        result
            .velocities
            .push((Vec2::new(y(0), y(1)) * scale, y(2) * scale));
    }
    let load = -solution.objective;
    result.status = status_of_load(&driver, solution.objective, load, &optimality);
    record_bounds(&mut result, -solution.dual_objective, Some(load), load);
    Ok(result)
}
