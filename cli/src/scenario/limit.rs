//! The limit driver's model: paper 002's lattice of rigid circles with
//! cohesive rigid-plastic contacts, driven by its plate; or rigid bodies of
//! any shape (circles, ellipses, polygons, rectangles) on straight supports
//! (walls), their contacts found by the pair query, under dead loads and a
//! live load whose multiplier at collapse is sought. Solved by Clarabel.

use dismech::error::DismechError;
use dismech::law::RigidPlastic;
use dismech::limit::lattice::{Lattice, LatticeKind};
use dismech::limit::LimitError;
use dismech::limit::{LimitModel, Partner};
use dismech::lp::LinearProgramSolver;
use dismech::math::{Point, Pose2, Vec2};
use dismech::shape::AnyShape2;

use super::bodies::{BodySpec, LatticeModel};
use super::check::{
    self, combination, count, finite2, non_negative, positive, wall_velocity, Refusal,
};
use super::driver::LimitSpec;
use super::explicit::{gravity, MAX_BODIES};
use super::law::{LawSpec, RigidPlasticSpec};
use super::solvers::LpSolverSpec;
use super::source::{KeyPath, Source};
use super::ScenarioSpec;

/// Contact tolerance of bodies of shapes when `[driver]` does not say (m).
pub const DEFAULT_CONTACT_TOLERANCE: f64 = 1e-9;

/// A limit analysis ready to solve.
pub struct LimitPlan {
    /// The lattice as given (none for bodies of shapes).
    pub lattice: Option<Lattice>,
    /// Its model.
    pub model: LimitModel,
    /// The LP solver.
    pub solver: LinearProgramSolver,
}

/// Build the limit analysis of `spec`.
pub fn build(
    source: &Source<'_>,
    spec: &ScenarioSpec,
    settings: &LimitSpec,
) -> Result<LimitPlan, Refusal> {
    let kind = KeyPath::root("driver").key("kind");
    for (present, table) in [
        (spec.kinematics.is_some(), "kinematics"),
        (spec.boundary.is_some(), "boundary"),
        (spec.integrator.is_some(), "integrator"),
        (spec.linear_solver.is_some(), "linear_solver"),
        (spec.run.is_some(), "run"),
    ] {
        if present {
            return Err(combination(
                source,
                &[&kind, &KeyPath::root(table)],
                "the limit driver finds the collapse of rigid bodies as one LP: it takes `[[bodies]]`, `[law]` (rigid-plastic), `[loads]` (gravity, forces, live) and `[lp_solver]`; remove this table",
            ));
        }
    }
    let loads = KeyPath::root("loads");
    for (present, key) in [
        (spec.loads.seismic.is_some(), "seismic"),
        (!spec.loads.tractions.is_empty(), "tractions"),
    ] {
        if present {
            return Err(combination(
                source,
                &[&kind, &loads.key(key)],
                "the limit driver's loads are `loads.gravity` (self-weight), `loads.forces` (dead loads) and `loads.live`",
            ));
        }
    }
    let law = KeyPath::root("law");
    let LawSpec::RigidPlastic(strength) = &spec.law else {
        return Err(combination(
            source,
            &[&kind, &law.key("kind")],
            "the limit driver needs a strength: `[law] kind = \"rigid-plastic\"`",
        ));
    };
    let solver = lp_solver(source, spec)?;
    let lattice_at = spec
        .bodies
        .iter()
        .position(|b| matches!(b, BodySpec::Lattice(_)));
    match lattice_at {
        Some(k) => lattice_plan(source, spec, settings, strength, k, solver),
        None => shapes_plan(source, spec, settings, strength, solver),
    }
}

/// The LP solver of `[lp_solver]` (Clarabel's defaults when absent).
pub(super) fn lp_solver(
    source: &Source<'_>,
    spec: &ScenarioSpec,
) -> Result<LinearProgramSolver, Refusal> {
    Ok(match &spec.lp_solver {
        None => LinearProgramSolver::default(),
        Some(LpSolverSpec::Clarabel(c)) => {
            let d = LinearProgramSolver::default();
            let table = KeyPath::root("lp_solver");
            LinearProgramSolver {
                tolerance: match c.tolerance {
                    Some(t) => positive(source, &table.key("tolerance"), t)?,
                    None => d.tolerance,
                },
                max_iterations: match c.max_iterations {
                    Some(n) => {
                        count(source, &table.key("max_iterations"), n as usize, 1, 100_000)? as u32
                    }
                    None => d.max_iterations,
                },
                verbose: false,
            }
        }
    })
}

/// Paper 002's lattice, the `[[bodies]]` entry `at`, the only one.
fn lattice_plan(
    source: &Source<'_>,
    spec: &ScenarioSpec,
    settings: &LimitSpec,
    strength: &RigidPlasticSpec,
    at: usize,
    solver: LinearProgramSolver,
) -> Result<LimitPlan, Refusal> {
    let bodies = KeyPath::root("bodies");
    let path = bodies.index(at);
    let lattice_kind_key = path.key("kind");
    if spec.bodies.len() != 1 {
        let other = if at == 0 { 1 } else { 0 };
        return Err(combination(
            source,
            &[&lattice_kind_key, &bodies.index(other).key("kind")],
            "a lattice is the limit driver's whole model: it takes exactly one `[[bodies]]` table, of kind = \"lattice\"",
        ));
    }
    let driver = KeyPath::root("driver");
    let loads = KeyPath::root("loads");
    for (present, key) in [
        (
            settings.contact_tolerance.is_some(),
            driver.key("contact_tolerance"),
        ),
        (
            settings.multiply_dead_loads.is_some(),
            driver.key("multiply_dead_loads"),
        ),
        (spec.loads.gravity.is_some(), loads.key("gravity")),
        (!spec.loads.forces.is_empty(), loads.key("forces")),
        (spec.loads.live.is_some(), loads.key("live")),
    ] {
        if present {
            return Err(combination(
                source,
                &[&lattice_kind_key, &key],
                "paper 002's lattice is driven by its plate, without weight, its contacts given: this key serves bodies of shapes",
            ));
        }
    }
    let BodySpec::Lattice(spec_lattice) = &spec.bodies[at] else {
        return Err(Box::new(source.at_key(&lattice_kind_key, "not a lattice")));
    };
    let law = KeyPath::root("law");
    let frictional = strength.friction.is_some_and(|f| f != 0.0)
        || strength.friction_angle.is_some_and(|f| f != 0.0)
        || strength.unilateral == Some(true);
    if frictional {
        return Err(combination(
            source,
            &[&path.key("kind"), &law.key("friction")],
            "paper 002's lattice has cohesive, bilateral contacts: `law.cohesion` only (no friction, unilateral = false)",
        ));
    }
    let cohesion = dismech::error::require_non_negative("contact cohesion C", strength.cohesion)
        .map_err(|e| Box::new(source.at_key(&law.key("cohesion"), e.to_string())))?;
    let lattice_kind = match spec_lattice.model {
        LatticeModel::U => LatticeKind::U {
            loaded: spec_lattice.loaded.unwrap_or(1),
        },
        LatticeModel::L => {
            if spec_lattice.loaded.is_some() {
                return Err(combination(
                    source,
                    &[&path.key("model"), &path.key("loaded")],
                    "the L-model's plate loads the whole first column: `loaded` is the U-model's",
                ));
            }
            LatticeKind::L
        }
    };
    let lattice = Lattice {
        kind: lattice_kind,
        m: spec_lattice.m,
        n: spec_lattice.n,
        rolling: spec_lattice.rolling.unwrap_or(true),
        cohesion,
        wall_cohesion: spec_lattice.wall_cohesion.unwrap_or(2.0 * cohesion),
        radius: match spec_lattice.radius {
            Some(r) => positive(source, &path.key("radius"), r)?,
            None => 1.0,
        },
    };
    let model = lattice
        .build()
        .map_err(|e| lattice_error(source, &path, e))?;
    Ok(LimitPlan {
        lattice: Some(lattice),
        model,
        solver,
    })
}

/// Rigid bodies of shapes on walls (supports), their contacts found by the
/// pair query.
fn shapes_plan(
    source: &Source<'_>,
    spec: &ScenarioSpec,
    settings: &LimitSpec,
    strength: &RigidPlasticSpec,
    solver: LinearProgramSolver,
) -> Result<LimitPlan, Refusal> {
    let driver = KeyPath::root("driver");
    let kind = driver.key("kind");
    let bodies = KeyPath::root("bodies");
    let loads = KeyPath::root("loads");
    let law_path = KeyPath::root("law");
    let cohesion = non_negative(source, &law_path.key("cohesion"), strength.cohesion)?;
    let mu = check::friction(
        source,
        &law_path,
        strength.friction,
        strength.friction_angle,
        Some(0.0),
    )?;
    let law = RigidPlastic::coulomb(cohesion, mu, strength.unilateral.unwrap_or(false))
        .map_err(|e| Box::new(source.at_key(&law_path, e.to_string())))?;
    let tolerance = match settings.contact_tolerance {
        Some(t) => positive(source, &driver.key("contact_tolerance"), t)?,
        None => DEFAULT_CONTACT_TOLERANCE,
    };
    let mut model = LimitModel::new(tolerance)
        .map_err(|e| Box::new(source.at_key(&driver.key("contact_tolerance"), e.to_string())))?;
    let g = gravity(source, spec)?;
    count(source, &bodies, spec.bodies.len(), 1, MAX_BODIES)?;
    // The `[[bodies]]` entry of each model body and of each support.
    let mut body_paths: Vec<KeyPath> = Vec::new();
    let mut support_paths: Vec<(KeyPath, f64)> = Vec::new();
    // The `velocity` key of the moving wall (the plate), if any.
    let mut moving: Option<KeyPath> = None;
    for (k, entry) in spec.bodies.iter().enumerate() {
        let path = bodies.index(k);
        if let BodySpec::Wall(wall) = entry {
            let start = finite2(source, &path.key("start"), wall.start)?;
            let end = finite2(source, &path.key("end"), wall.end)?;
            let along = Vec2::new(end[0] - start[0], end[1] - start[1]);
            let name = format!("wall {}", support_paths.len());
            let velocity = match wall.velocity {
                None => Vec2::zeros(),
                Some(v) => {
                    let key = path.key("velocity");
                    let v = wall_velocity(source, &key, v)?;
                    if let Some(first) = &moving {
                        return Err(combination(
                            source,
                            &[first, &key],
                            "one wall may move: the limit load is the force of the one moving wall (the plate) along its velocity",
                        ));
                    }
                    moving = Some(key);
                    Vec2::new(v[0], v[1])
                }
            };
            model
                .add_support(
                    &name,
                    Point::new(start[0], start[1]),
                    Vec2::new(-along.y, along.x),
                    velocity,
                )
                .map_err(|e| Box::new(source.at_key(&path.key("end"), e.to_string())))?;
            support_paths.push((path, along.norm()));
            continue;
        }
        let (shape, pose, density) = shape_of(source, entry, &path, &kind)?;
        let index = model
            .add_shape(shape, pose, true)
            .map_err(|e| Box::new(source.at_key(&path, e.to_string())))?;
        if let Some(density) = density {
            let mass = model.bodies()[index]
                .shape
                .as_shape()
                .mass_properties(density)
                .mass;
            model
                .set_load(index, g * mass)
                .map_err(|e| Box::new(source.at_key(&path.key("density"), e.to_string())))?;
        }
        body_paths.push(path);
    }
    if body_paths.is_empty() {
        return Err(Box::new(source.at_key(
            &bodies,
            "no body to analyse: the limit driver's walls hold bodies of kind circle, ellipse, polygon or rectangle",
        )));
    }
    let n = body_paths.len();
    for (k, f) in spec.loads.forces.iter().enumerate() {
        let path = loads.key("forces").index(k);
        count(source, &path.key("body"), f.body, 0, n - 1)?;
        let force = finite2(source, &path.key("force"), f.force)?;
        let load = model.bodies()[f.body].load + Vec2::new(force[0], force[1]);
        model
            .set_load(f.body, load)
            .map_err(|e| Box::new(source.at_key(&path.key("force"), e.to_string())))?;
    }
    if let Some(plate) = &moving {
        let other = if spec.loads.live.is_some() {
            Some(loads.key("live"))
        } else if settings.multiply_dead_loads == Some(true) {
            Some(driver.key("multiply_dead_loads"))
        } else {
            None
        };
        if let Some(other) = other {
            return Err(combination(
                source,
                &[plate, &other],
                "the limit load is the moving wall's force, a live load's multiplier or the dead loads' factor: give one",
            ));
        }
    }
    match (&spec.loads.live, settings.multiply_dead_loads.unwrap_or(false)) {
        (None, false) if moving.is_some() => {}
        (Some(_), true) => {
            return Err(combination(
                source,
                &[&loads.key("live"), &driver.key("multiply_dead_loads")],
                "the limit load multiplies either the live load or the dead loads: give one",
            ))
        }
        (Some(live), false) => {
            let path = loads.key("live");
            count(source, &path.key("body"), live.body, 0, n - 1)?;
            let force = finite2(source, &path.key("force"), live.force)?;
            let point = match live.point {
                Some(p) => {
                    let p = finite2(source, &path.key("point"), p)?;
                    Point::new(p[0], p[1])
                }
                None => model.bodies()[live.body].centre,
            };
            model
                .set_live_load(live.body, Vec2::new(force[0], force[1]), point)
                .map_err(|e| Box::new(source.at_key(&path.key("force"), e.to_string())))?;
        }
        (None, true) => {
            if !model.has_dead_loads() {
                return Err(Box::new(source.at_key(
                    &driver.key("multiply_dead_loads"),
                    "no dead load to multiply: give bodies a `density` (self-weight under `loads.gravity`) or `loads.forces`",
                )));
            }
            model.multiply_dead_loads();
        }
        (None, false) => {
            return Err(Box::new(source.at_key(
                &loads,
                "no load to multiply: give `loads.live` (a body, a force and its point), `driver.multiply_dead_loads = true` or a wall a `velocity` (the plate)",
            )))
        }
    }
    add_contacts(
        source,
        &mut model,
        law,
        tolerance,
        &body_paths,
        &support_paths,
    )?;
    Ok(LimitPlan {
        lattice: None,
        model,
        solver,
    })
}

/// The outline, pose and density of one body of a shape; keys of the time
/// steppers' bodies refused.
fn shape_of(
    source: &Source<'_>,
    body: &BodySpec,
    path: &KeyPath,
    kind: &KeyPath,
) -> Result<(AnyShape2, Pose2, Option<f64>), Refusal> {
    if let Some(common) = body.common() {
        for (given, key) in [
            (common.youngs_modulus.is_some(), "youngs_modulus"),
            (common.poisson_ratio.is_some(), "poisson_ratio"),
            (common.plane.is_some(), "plane"),
            (common.velocity.is_some(), "velocity"),
            (common.angular_velocity.is_some(), "angular_velocity"),
            (common.motion.is_some(), "motion"),
        ] {
            if given {
                return Err(combination(
                    source,
                    &[kind, &path.key(key)],
                    "the limit driver's bodies are rigid and at rest until collapse, held by the walls: this key serves the time-stepping drivers",
                ));
            }
        }
        if let Some(d) = common.density {
            positive(source, &path.key("density"), d)?;
        }
    }
    match super::explicit::shape_of(source, path, body, 0)? {
        Some(shaped) => Ok(shaped),
        None => Err(combination(
            source,
            &[kind, &path.key("kind")],
            "the limit driver takes bodies of kind circle, ellipse, polygon, rectangle and wall, or one lattice alone; circle rows serve the explicit driver, grid columns the HPM driver",
        )),
    }
}

/// Declare, with `law`, the contacts the pair query finds between every
/// two bodies whose bounding circles come within the tolerance and between
/// every body and every wall it reaches: bodies first, in order, each with
/// the walls and then with the bodies after it.
fn add_contacts(
    source: &Source<'_>,
    model: &mut LimitModel,
    law: RigidPlastic,
    tolerance: f64,
    body_paths: &[KeyPath],
    support_paths: &[(KeyPath, f64)],
) -> Result<(), Refusal> {
    let n = model.bodies().len();
    let walls: Vec<(Point, Vec2)> = model
        .supports()
        .iter()
        .map(|s| (s.point, s.normal))
        .collect();
    let touched = |r: dismech::error::Result<Vec<usize>>| match r {
        Ok(_) | Err(DismechError::Limit(LimitError::ContactNotTouching { .. })) => Ok(()),
        Err(e) => Err(e),
    };
    for i in 0..n {
        let (centre, radius) = (model.bodies()[i].centre, model.bodies()[i].radius());
        for (s, (point, normal)) in walls.iter().enumerate() {
            let tangent = Vec2::new(normal.y, -normal.x);
            let along = (centre - point).dot(&tangent);
            let across = (centre - point).dot(normal);
            let reach = radius + tolerance;
            if across.abs() > reach || along < -reach || along > support_paths[s].1 + reach {
                continue;
            }
            touched(model.add_contacts(i, Partner::Support(s), law)).map_err(|e| {
                combination(
                    source,
                    &[&body_paths[i], &support_paths[s].0],
                    &e.to_string(),
                )
            })?;
        }
        for j in i + 1..n {
            let other = &model.bodies()[j];
            let reach = radius + other.radius() + tolerance;
            if (other.centre - centre).norm() > reach {
                continue;
            }
            touched(model.add_contacts(i, Partner::Body(j), law)).map_err(|e| {
                combination(source, &[&body_paths[i], &body_paths[j]], &e.to_string())
            })?;
        }
    }
    Ok(())
}

/// The refusal of an error of [`Lattice::build`].
fn lattice_error(source: &Source<'_>, path: &KeyPath, error: DismechError) -> Refusal {
    let message = error.to_string();
    let key = match &error {
        DismechError::InvalidParameter { name, .. } if name.starts_with("m ") => path.key("m"),
        DismechError::InvalidParameter { name, .. } if name.starts_with("n'") => path.key("loaded"),
        DismechError::InvalidParameter { name, .. } if name.starts_with("n ") => path.key("n"),
        DismechError::InvalidParameter { name, .. } if name.contains("radius") => {
            path.key("radius")
        }
        DismechError::InvalidParameter { name, .. } if name.contains("cohesion") => {
            path.key("wall_cohesion")
        }
        DismechError::Limit(LimitError::LatticeTooLarge { .. }) => {
            return Box::new(source.at_keys(&[&path.key("m"), &path.key("n")], message))
        }
        _ => path.clone(),
    };
    Box::new(source.at_key(&key, message))
}
