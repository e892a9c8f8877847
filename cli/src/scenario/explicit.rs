//! The explicit driver's model: a scene in a frame, a law with a stiffness
//! bound, symplectic Euler, and a run to rest or for a number of steps.

use dismech::dem::DemSimulation;
use dismech::error::DismechError;
use dismech::explicit::ExplicitError;
use dismech::explicit::{DemSettings, RestCriterion};
use dismech::integrate::ExplicitEuler;
use dismech::law::{PenaltyCoulomb, SpringDashpotCoulomb};
use dismech::math::{Point, Pose2, Vec2};
use dismech::scene::{CircleRows, Frame, Particle, Scene, JOINT_TOLERANCE};
use dismech::shape::{AnyShape2, Circle, Ellipse, Polygon};

use super::bodies::{BodySpec, MotionSpec};
use super::boundary::BoundarySpec;
use super::check::{
    self, combination, count, finite2, named, non_negative, positive, refuse_beside_driver, Refusal,
};
use super::driver::ExplicitSpec;
use super::law::{DampingSpec, IntegrationSpec, LawSpec};
use super::run::RunSpec;
use super::solvers::IntegratorSpec;
use super::source::{KeyPath, Source};
use super::{Overrides, ScenarioSpec};

/// The most bodies a scenario may build, all its `[[bodies]]` together (a
/// generator's `count` included).
pub const MAX_BODIES: usize = 1_000_000;

/// The most outline points a ParaView frame may hold (bodies ×
/// `output.segments`): about 0.5 GB of coordinates.
pub const MAX_OUTLINE_POINTS: usize = 20_000_000;

/// The name the library gives an ellipse whose semi-axis `a` is smaller
/// than `b` (`dismech::shape::Ellipse::new`): the refusal names
/// `semi_minor`, the key that broke the order.
pub const ELLIPSE_AXES_SWAPPED: &str =
    "semi-axis a (must not be smaller than b; turn the ellipse by 90° instead)";

/// The explicit driver with the law the scenario chose.
pub enum ExplicitDem {
    /// A spring–dashpot–Coulomb law.
    Spring(Box<DemSimulation<SpringDashpotCoulomb>>),
    /// The penalty Coulomb law.
    Penalty(Box<DemSimulation<PenaltyCoulomb>>),
}

/// How an explicit run stops.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ExplicitPlan {
    /// At rest, or at a limit of the criterion.
    ToRest(RestCriterion),
    /// After this many steps.
    Steps(u64),
}

/// An explicit model ready to run.
pub struct ExplicitModel {
    /// The driver.
    pub dem: ExplicitDem,
    /// When it stops.
    pub plan: ExplicitPlan,
    /// The time step (s).
    pub dt: f64,
    /// The driver's settings.
    pub settings: DemSettings,
    /// The limit analysis of the final packing (`[limit_analysis]`).
    pub analysis: Option<Box<super::analysis::PackingAnalysis>>,
}

/// The law of `[law]` for a time-stepping driver: a spring–dashpot law
/// or the penalty law (a rigid-plastic strength has no stiffness).
pub enum SteppingLaw {
    /// A spring–dashpot–Coulomb law.
    Spring(SpringDashpotCoulomb),
    /// The penalty Coulomb law.
    Penalty(PenaltyCoulomb),
}

/// The law of `[law]` for the explicit or implicit driver.
pub fn stepping_law(source: &Source<'_>, spec: &ScenarioSpec) -> Result<SteppingLaw, Refusal> {
    stepping_law_at(source, &spec.law, &KeyPath::root("law"))
}

/// The law `law`, read from the table `table` (`[law]`, or a pair's law
/// of `[[pair_laws]]`), for the explicit or implicit driver.
pub fn stepping_law_at(
    source: &Source<'_>,
    law: &LawSpec,
    table: &KeyPath,
) -> Result<SteppingLaw, Refusal> {
    let table = table.clone();
    let with = |e| named(source, &table, LAW_NAMES, e);
    Ok(match law {
        LawSpec::Katsuki(p) => {
            let mu = check::friction(source, &table, p.friction, p.friction_angle, None)?;
            SteppingLaw::Spring(
                SpringDashpotCoulomb::katsuki(p.youngs_modulus, p.poisson_ratio, p.stiffness_ratio, mu)
                    .map_err(with)?,
            )
        }
        LawSpec::SpringDashpotCoulomb(p) => {
            let mu = check::friction(source, &table, p.friction, p.friction_angle, None)?;
            let damping = match p.damping.unwrap_or(DampingSpec::Critical) {
                DampingSpec::Critical => dismech::law::Damping::Critical,
                DampingSpec::None => dismech::law::Damping::None,
            };
            SteppingLaw::Spring(
                SpringDashpotCoulomb::new(
                    dismech::law::NormalStiffness::Constant(p.normal_stiffness),
                    p.stiffness_ratio,
                    mu,
                    damping,
                )
                .map_err(with)?,
            )
        }
        LawSpec::PenaltyCoulomb(p) => {
            let mu = check::friction(source, &table, p.friction, p.friction_angle, None)?;
            let law = match (p.cohesion, p.integration) {
                (Some(_), Some(IntegrationSpec::Conventional)) => {
                    return Err(combination(
                        source,
                        &[&table.key("cohesion"), &table.key("integration")],
                        "a bonded contact (cohesion) is integrated by return mapping only",
                    ))
                }
                (Some(c), _) => PenaltyCoulomb::bonded_with_friction(p.penalty, c, mu),
                (None, integration) => {
                    let integration = match integration.unwrap_or(IntegrationSpec::ReturnMapping) {
                        IntegrationSpec::ReturnMapping => {
                            dismech::law::FrictionIntegration::ReturnMapping
                        }
                        IntegrationSpec::Conventional => dismech::law::FrictionIntegration::Conventional,
                    };
                    PenaltyCoulomb::new(p.penalty, mu, integration)
                }
            };
            SteppingLaw::Penalty(law.map_err(with)?)
        }
        LawSpec::RigidPlastic(_) | LawSpec::Hpm(_) => {
            return Err(combination(
                source,
                &[&KeyPath::root("driver").key("kind"), &table.key("kind")],
                "a rigid-plastic strength serves the limit driver, the `hpm` soil the HPM driver; a time-stepping driver takes `katsuki`, `spring-dashpot-coulomb` or `penalty-coulomb`",
            ))
        }
    })
}

/// The library's names of the laws' values and the keys that give them.
const LAW_NAMES: check::Names<'static> = &[
    ("Young's modulus E", "youngs_modulus"),
    ("Poisson's ratio", "poisson_ratio"),
    ("stiffness ratio s", "stiffness_ratio"),
    ("friction coefficient mu", "friction"),
    ("normal stiffness k_n", "normal_stiffness"),
    ("contact penalty p_c", "penalty"),
    ("contact cohesion c", "cohesion"),
];

/// Refuse the tables that the explicit driver has no slot for.
fn refuse_other_slots(source: &Source<'_>, spec: &ScenarioSpec) -> Result<(), Refusal> {
    refuse_beside_driver(
        source,
        spec.kinematics
            .as_ref()
            .is_some_and(|k| k.kind() != "rigid"),
        KeyPath::root("kinematics").key("kind"),
        "the explicit driver moves rigid bodies only",
    )?;
    refuse_beside_driver(
        source,
        spec.integrator
            .as_ref()
            .is_some_and(|i| !matches!(i, IntegratorSpec::ExplicitEuler(_))),
        KeyPath::root("integrator").key("kind"),
        "the explicit driver takes an explicit integrator (`explicit-euler`); `newmark` and `quasi-static` are implicit",
    )?;
    refuse_beside_driver(
        source,
        spec.lp_solver.is_some() && spec.limit_analysis.is_none(),
        KeyPath::root("lp_solver"),
        "the explicit driver solves no LP but that of `[limit_analysis]`: remove this table or add that one",
    )?;
    refuse_beside_driver(
        source,
        spec.linear_solver.is_some(),
        KeyPath::root("linear_solver"),
        "the explicit driver solves no system: remove this table",
    )?;
    refuse_beside_driver(
        source,
        spec.loads.seismic.is_some(),
        KeyPath::root("loads").key("seismic"),
        "a seismic coefficient loads the HPM driver's columns",
    )?;
    refuse_beside_driver(
        source,
        !spec.loads.tractions.is_empty(),
        KeyPath::root("loads").key("tractions"),
        "edge tractions load the implicit driver's polygons; the explicit driver takes `loads.forces`",
    )?;
    refuse_beside_driver(
        source,
        spec.loads.live.is_some(),
        KeyPath::root("loads").key("live"),
        "a live load is the limit driver's; the explicit driver takes `loads.forces`",
    )
}

/// Build the explicit model of `spec`.
pub fn build(
    source: &Source<'_>,
    spec: &ScenarioSpec,
    settings: &ExplicitSpec,
    overrides: Overrides,
) -> Result<ExplicitModel, Refusal> {
    refuse_other_slots(source, spec)?;
    let law = stepping_law(source, spec)?;
    let (scene, entry_of) = scene(source, spec)?;
    let driver = KeyPath::root("driver");
    let defaults = DemSettings::default();
    let dem_settings = DemSettings {
        dt: positive(source, &driver.key("dt"), settings.dt)?,
        initial_overlap_tolerance: match settings.initial_overlap_tolerance {
            Some(t) => non_negative(source, &driver.key("initial_overlap_tolerance"), t)?,
            None => defaults.initial_overlap_tolerance,
        },
        stability_overlap: settings
            .stability_overlap
            .unwrap_or(defaults.stability_overlap),
        check_stability: settings.check_stability.unwrap_or(defaults.check_stability),
        neighbour_skin: match settings.neighbour_skin {
            Some(s) => Some(non_negative(source, &driver.key("neighbour_skin"), s)?),
            None => None,
        },
        relative_travel: settings.relative_travel.unwrap_or(defaults.relative_travel),
    };
    let analysis = super::analysis::build(source, spec, &scene, &entry_of)?;
    let plan = plan(source, spec, dem_settings.dt, overrides)?;
    let dem_settings_dt = dem_settings.dt;
    let refuse = |e: DismechError| build_error(source, &entry_of, e);
    let dem = match law {
        SteppingLaw::Spring(law) => ExplicitDem::Spring(Box::new(
            DemSimulation::new(scene, law, ExplicitEuler, dem_settings).map_err(refuse)?,
        )),
        SteppingLaw::Penalty(law) => ExplicitDem::Penalty(Box::new(
            DemSimulation::new(scene, law, ExplicitEuler, dem_settings).map_err(refuse)?,
        )),
    };
    Ok(ExplicitModel {
        dem,
        plan,
        dt: dem_settings_dt,
        settings: dem_settings,
        analysis,
    })
}

/// The refusal of an error of the driver's constructor, at the key that
/// gave the value: a body's entry, a setting, the law.
fn build_error(source: &Source<'_>, entry_of: &[usize], error: DismechError) -> Refusal {
    let body = |k: usize| KeyPath::root("bodies").index(entry_of.get(k).copied().unwrap_or(0));
    let driver = KeyPath::root("driver");
    let message = error.to_string();
    Box::new(match &error {
        DismechError::Explicit(ExplicitError::StartsInsideWall { body: b, .. })
        | DismechError::Explicit(ExplicitError::InvalidParticle { particle: b, .. }) => {
            source.at_keys(&[&body(*b), &KeyPath::root("boundary")], message)
        }
        DismechError::Explicit(ExplicitError::InitialOverlap { a, b, .. }) => {
            source.at_keys(&[&body(*a), &body(*b)], message)
        }
        DismechError::Explicit(ExplicitError::LawUndefinedForShape { body: b, .. }) => source
            .at_keys(
                &[&body(*b).key("kind"), &KeyPath::root("law").key("kind")],
                message,
            ),
        DismechError::Explicit(ExplicitError::UnstableTimeStep { .. }) => {
            source.at_key(&driver.key("dt"), message)
        }
        DismechError::InvalidParameter { name, .. } => {
            let key = match *name {
                "time step dt" => "dt",
                "stability_overlap" => "stability_overlap",
                "initial_overlap_tolerance" => "initial_overlap_tolerance",
                "neighbour_skin" => "neighbour_skin",
                _ => return Box::new(source.at_key(&KeyPath::root("bodies"), message)),
            };
            source.at_key(&driver.key(key), message)
        }
        DismechError::Explicit(ExplicitError::OutOfMemory { .. }) => {
            source.at_key(&KeyPath::root("bodies"), message)
        }
        _ => source.at_key(&driver, message),
    })
}

/// The run plan of `[run]` (to rest with the library's defaults when
/// absent), limited by `overrides`.
fn plan(
    source: &Source<'_>,
    spec: &ScenarioSpec,
    dt: f64,
    overrides: Overrides,
) -> Result<ExplicitPlan, Refusal> {
    let run = KeyPath::root("run");
    let steps_of_time = |t: f64| (t / dt).round();
    match &spec.run {
        None | Some(RunSpec::ToRest(_)) => {
            let d = RestCriterion::default();
            let mut c = d;
            if let Some(RunSpec::ToRest(r)) = &spec.run {
                c.kinetic_to_released_ratio = match r.kinetic_to_released_ratio {
                    Some(v) => positive(source, &run.key("kinetic_to_released_ratio"), v)?,
                    None => d.kinetic_to_released_ratio,
                };
                c.min_time = match r.min_time {
                    Some(v) => non_negative(source, &run.key("min_time"), v)?,
                    None => d.min_time,
                };
                c.max_time = match r.max_time {
                    Some(v) => positive(source, &run.key("max_time"), v)?,
                    None => d.max_time,
                };
                c.check_every = match r.check_every {
                    Some(v) => {
                        count(source, &run.key("check_every"), v as usize, 1, usize::MAX)? as u64
                    }
                    None => d.check_every,
                };
                c.consecutive_checks = match r.consecutive_checks {
                    Some(v) => count(
                        source,
                        &run.key("consecutive_checks"),
                        v as usize,
                        1,
                        u32::MAX as usize,
                    )? as u32,
                    None => d.consecutive_checks,
                };
                c.unbalanced_force_ratio = match r.unbalanced_force_ratio {
                    Some(v) => non_negative(source, &run.key("unbalanced_force_ratio"), v)?,
                    None => d.unbalanced_force_ratio,
                };
                c.max_steps = match r.max_steps {
                    Some(v) => {
                        count(source, &run.key("max_steps"), v as usize, 1, usize::MAX)? as u64
                    }
                    None => d.max_steps,
                };
            }
            if let Some(n) = overrides.max_steps {
                c.max_steps = c.max_steps.min(n);
            }
            if let Some(t) = overrides.end_time {
                c.max_time = c.max_time.min(t);
                c.min_time = c.min_time.min(t);
            }
            Ok(ExplicitPlan::ToRest(c))
        }
        Some(RunSpec::Steps(s)) => {
            let mut steps =
                count(source, &run.key("steps"), s.steps as usize, 1, usize::MAX)? as u64;
            steps = limit_steps(steps, overrides, steps_of_time);
            Ok(ExplicitPlan::Steps(steps))
        }
        Some(RunSpec::Time(t)) => {
            let end = positive(source, &run.key("end_time"), t.end_time)?;
            let steps = steps_of_time(end);
            let steps = check::require(
                source,
                &run.key("end_time"),
                end,
                (1.0..=MAX_STEPS).contains(&steps),
                &format!("must hold between 1 and {MAX_STEPS:e} steps of the driver's dt = {dt} s"),
            )
            .map(|_| steps as u64)?;
            Ok(ExplicitPlan::Steps(limit_steps(
                steps,
                overrides,
                steps_of_time,
            )))
        }
    }
}

/// The most steps a run of `kind = "time"` may hold.
pub const MAX_STEPS: f64 = 1e12;

/// `steps` limited by the command line's `--max-steps` and `--end-time`
/// (at least one step).
pub fn limit_steps(steps: u64, overrides: Overrides, steps_of_time: impl Fn(f64) -> f64) -> u64 {
    let mut steps = steps;
    if let Some(n) = overrides.max_steps {
        steps = steps.min(n);
    }
    if let Some(t) = overrides.end_time {
        steps = steps.min(steps_of_time(t).clamp(1.0, MAX_STEPS) as u64);
    }
    steps.max(1)
}

/// The frame of `[boundary]`.
fn frame(source: &Source<'_>, spec: &ScenarioSpec) -> Result<Frame, Refusal> {
    let table = KeyPath::root("boundary");
    let Some(boundary) = &spec.boundary else {
        return Err(Box::new(source.at_key(
            &table,
            "the explicit driver needs a `[boundary]` (kind = \"open-box\" or \"walls\")",
        )));
    };
    match boundary {
        BoundarySpec::OpenBox(b) => Frame::open_box(b.width, b.height).map_err(|e| {
            named(
                source,
                &table,
                &[("frame width", "width"), ("frame height", "height")],
                e,
            )
        }),
        BoundarySpec::Walls(w) => {
            count(source, &table.key("points"), w.points.len(), 2, MAX_BODIES)?;
            if let Some(names) = &w.names {
                if names.len() != w.points.len() - 1 {
                    return Err(combination(
                        source,
                        &[&table.key("names"), &table.key("points")],
                        "give one name per wall: one fewer than the points",
                    ));
                }
            }
            let walls = w
                .points
                .windows(2)
                .enumerate()
                .map(|(k, p)| {
                    let name = w
                        .names
                        .as_ref()
                        .map_or_else(|| format!("wall{k}"), |n| n[k].clone());
                    let segment = dismech::shape::Segment::new(
                        Point::new(p[0][0], p[0][1]),
                        Point::new(p[1][0], p[1][1]),
                    );
                    (name, segment)
                })
                .collect();
            Frame::from_walls(walls).map_err(|e| {
                let wall = match &e {
                    DismechError::DegenerateWall { wall, .. } => *wall,
                    DismechError::FrameNotClosed { wall, .. } => *wall,
                    _ => 0,
                };
                Box::new(source.at_key(&table.key("points").index(wall), e.to_string()))
            })
        }
    }
}

/// The scene of `[boundary]`, `[[bodies]]` and `[loads]`, and the entry of
/// `[[bodies]]` each particle comes from.
fn scene(source: &Source<'_>, spec: &ScenarioSpec) -> Result<(Scene, Vec<usize>), Refusal> {
    let frame = frame(source, spec)?;
    let gravity = gravity(source, spec)?;
    let mut scene = Scene::new(frame, gravity).map_err(|e| {
        Box::new(source.at_key(&KeyPath::root("loads").key("gravity"), e.to_string()))
    })?;
    let mut entry_of = Vec::new();
    let kind = KeyPath::root("driver").key("kind");
    for (k, body) in spec.bodies.iter().enumerate() {
        let path = KeyPath::root("bodies").index(k);
        let before = scene.particles.len();
        add_body(source, &mut scene, body, &path, &kind)?;
        entry_of.resize(scene.particles.len(), k);
        inside_frame(source, &scene, before, &path)?;
    }
    let segments = spec
        .output
        .segments
        .unwrap_or(super::execute::DEFAULT_SEGMENTS);
    let points = scene.particles.len().saturating_mul(segments);
    if points > MAX_OUTLINE_POINTS {
        return Err(Box::new(source.at_key(
            &KeyPath::root("output").key("segments"),
            format!(
                "{segments} segments for each of {} bodies make {points} outline points a frame, above {MAX_OUTLINE_POINTS}: give fewer segments",
                scene.particles.len()
            ),
        )));
    }
    if scene.particles.is_empty() {
        return Err(Box::new(source.at_key(
            &KeyPath::root("bodies"),
            "no bodies: add at least one `[[bodies]]` table",
        )));
    }
    for (i, force) in spec.loads.forces.iter().enumerate() {
        let path = KeyPath::root("loads").key("forces").index(i);
        count(
            source,
            &path.key("body"),
            force.body,
            0,
            scene.particles.len() - 1,
        )?;
        if scene.particles[force.body].is_prescribed() {
            let entry = KeyPath::root("bodies").index(entry_of[force.body]);
            return Err(combination(
                source,
                &[&path.key("body"), &entry.key("motion").key("kind")],
                &format!(
                    "body {} is fixed or moves at a constant velocity: forces do not act on it",
                    force.body
                ),
            ));
        }
        let f = finite2(source, &path.key("force"), force.force)?;
        scene
            .set_external_force(force.body, Vec2::new(f[0], f[1]))
            .map_err(|e| Box::new(source.at_key(&path, e.to_string())))?;
    }
    Ok((scene, entry_of))
}

/// Gravity of `[loads]`: (0, −9.81) m/s² by default.
pub fn gravity(source: &Source<'_>, spec: &ScenarioSpec) -> Result<Vec2, Refusal> {
    let g = spec.loads.gravity.unwrap_or([0.0, -9.81]);
    let g = finite2(source, &KeyPath::root("loads").key("gravity"), g)?;
    Ok(Vec2::new(g[0], g[1]))
}

/// Refuse a particle added from `path` whose centre lies outside the
/// frame's bounding box; where the walls lie on one straight line (a flat
/// or inclined base, whose box holds nothing), one that faces no wall
/// either (lies on no wall's left, the side of the material, within its
/// length).
fn inside_frame(
    source: &Source<'_>,
    scene: &Scene,
    from: usize,
    path: &KeyPath,
) -> Result<(), Refusal> {
    let Some(bounds) = scene.frame.bounding_box() else {
        return Ok(());
    };
    let walls = scene.frame.walls();
    let straight = walls.first().is_some_and(|first| {
        let along = first.end - first.start;
        let off = |p: Point| {
            let d = p - first.start;
            (along.x * d.y - along.y * d.x).abs() <= JOINT_TOLERANCE * along.norm()
        };
        walls.iter().all(|w| off(w.start) && off(w.end))
    });
    let faces_a_wall = |c: Point| {
        straight
            && walls.iter().any(|w| {
                let along = w.end - w.start;
                let length2 = along.norm_squared();
                let t = (c - w.start).dot(&along);
                let left = along.x * (c.y - w.start.y) - along.y * (c.x - w.start.x);
                left > 0.0 && (0.0..=length2).contains(&t)
            })
    };
    for (k, p) in scene.particles.iter().enumerate().skip(from) {
        let c = p.pose.position;
        let inside = c.x >= bounds.min.x
            && c.x <= bounds.max.x
            && c.y >= bounds.min.y
            && c.y <= bounds.max.y;
        if !inside && !faces_a_wall(c) {
            return Err(combination(
                source,
                &[path, &KeyPath::root("boundary")],
                &format!(
                    "body {k} is centred at ({}, {}) m, outside the frame's box [{}, {}] x [{}, {}] m (walls on one line: and on the left of none)",
                    c.x, c.y, bounds.min.x, bounds.max.x, bounds.min.y, bounds.max.y
                ),
            ));
        }
    }
    Ok(())
}

/// Add the particles of one `[[bodies]]` entry.
fn add_body(
    source: &Source<'_>,
    scene: &mut Scene,
    body: &BodySpec,
    path: &KeyPath,
    kind: &KeyPath,
) -> Result<(), Refusal> {
    if let Some(common) = body.common() {
        for (given, key) in [
            (common.youngs_modulus.is_some(), "youngs_modulus"),
            (common.poisson_ratio.is_some(), "poisson_ratio"),
            (common.plane.is_some(), "plane"),
        ] {
            if given {
                return Err(combination(
                    source,
                    &[kind, &path.key(key)],
                    "the explicit driver's bodies are rigid: this key serves the implicit driver",
                ));
            }
        }
    }
    let motion = body.common().and_then(|c| c.motion);
    let motion_kind = path.key("motion").key("kind");
    match motion {
        Some(MotionSpec::Sine(_)) => {
            return Err(combination(
                source,
                &[kind, &motion_kind],
                "the explicit driver's bodies are `fixed` or move at a `constant-velocity`; a `sine` motion serves the implicit driver",
            ))
        }
        Some(m) => {
            if body.common().and_then(|c| c.density).is_some() {
                return Err(combination(
                    source,
                    &[&path.key("density"), &motion_kind],
                    &format!(
                        "a {} body has an infinite mass: leave out its density",
                        m.kind()
                    ),
                ));
            }
            if let MotionSpec::Fixed(_) = m {
                for (given, key) in [
                    (body.common().and_then(|c| c.velocity).is_some(), "velocity"),
                    (
                        body.common().and_then(|c| c.angular_velocity).is_some(),
                        "angular_velocity",
                    ),
                ] {
                    if given {
                        return Err(combination(
                            source,
                            &[&path.key(key), &motion_kind],
                            "a fixed body is at rest: give `constant-velocity` to move it",
                        ));
                    }
                }
            }
        }
        None => {}
    }
    // A free body's density; a prescribed one's shape and pose are pushed
    // as a prescribed particle.
    let density = |d: Option<f64>| -> Result<f64, Refusal> {
        match d {
            Some(d) => positive(source, &path.key("density"), d),
            None => Err(Box::new(source.at_key(path, "no `density` (kg/m^3)"))),
        }
    };
    let shaped = shape_of(source, path, body, scene.particles.len())?;
    let (shape, pose, given_density): (AnyShape2, Pose2, Option<f64>) = match (shaped, body) {
        (Some(shaped), _) => shaped,
        (None, BodySpec::CircleRows(rows)) => return add_rows(source, scene, rows, path),
        (None, _) => return Err(combination(
            source,
            &[kind, &path.key("kind")],
            "the explicit driver's walls are the `[boundary]`; a lattice serves the limit driver, grid columns the HPM driver",
        )),
    };
    let index = if motion.is_some() {
        // Infinite mass and moment of inertia: its velocities, set below,
        // are kept for the whole run.
        scene.particles.push(Particle::fixed(shape, pose));
        scene.particles.len() - 1
    } else {
        scene
            .add_shape(shape, pose, density(given_density)?)
            .map_err(|e| Box::new(source.at_key(path, e.to_string())))?
    };
    let Some(common) = body.common() else {
        return Ok(());
    };
    let particle = &mut scene.particles[index];
    if let Some(v) = common.velocity {
        let v = finite2(source, &path.key("velocity"), v)?;
        particle.velocity = Vec2::new(v[0], v[1]);
    }
    if let Some(w) = common.angular_velocity {
        particle.angular_velocity = finite(source, &path.key("angular_velocity"), w)?;
    }
    Ok(())
}

/// The shape, pose and given density of a body of one shape (circle,
/// ellipse, polygon or rectangle) at `path`, the polygon numbered `index`;
/// `None` for the other kinds, which each driver refuses or takes in its
/// own way.
pub fn shape_of(
    source: &Source<'_>,
    path: &KeyPath,
    body: &BodySpec,
    index: usize,
) -> Result<Option<(AnyShape2, Pose2, Option<f64>)>, Refusal> {
    let centre = |c: [f64; 2]| -> Result<Point, Refusal> {
        let c = finite2(source, &path.key("centre"), c)?;
        Ok(Point::new(c[0], c[1]))
    };
    let shape_error =
        |names: check::Names<'static>| move |e: DismechError| named(source, path, names, e);
    Ok(Some(match body {
        BodySpec::Circle(b) => {
            let shape = Circle::new(b.radius).map_err(shape_error(&[("radius", "radius")]))?;
            let c = centre(b.centre)?;
            (shape.into(), Pose2::new(c.x, c.y, 0.0), b.density)
        }
        BodySpec::Ellipse(b) => {
            let shape = Ellipse::new(b.semi_major, b.semi_minor).map_err(shape_error(&[
                ("semi-axis a", "semi_major"),
                ("semi-axis b", "semi_minor"),
                (ELLIPSE_AXES_SWAPPED, "semi_minor"),
            ]))?;
            let c = centre(b.centre)?;
            let angle = finite(source, &path.key("angle"), b.angle.unwrap_or(0.0))?;
            (shape.into(), Pose2::new(c.x, c.y, angle), b.density)
        }
        BodySpec::Polygon(b) => {
            count(
                source,
                &path.key("vertices"),
                b.vertices.len(),
                3,
                MAX_BODIES,
            )?;
            let vertices: Vec<Point> = b.vertices.iter().map(|v| Point::new(v[0], v[1])).collect();
            let (polygon, centroid) = Polygon::from_world(&vertices, index)
                .map_err(|e| Box::new(source.at_key(&path.key("vertices"), e.to_string())))?;
            (
                polygon.into(),
                Pose2::new(centroid.x, centroid.y, 0.0),
                b.density,
            )
        }
        BodySpec::Rectangle(b) => {
            let shape = Polygon::rectangle(b.width, b.height).map_err(shape_error(&[
                ("rectangle width", "width"),
                ("rectangle height", "height"),
            ]))?;
            let c = centre(b.centre)?;
            let angle = finite(source, &path.key("angle"), b.angle.unwrap_or(0.0))?;
            (shape.into(), Pose2::new(c.x, c.y, angle), b.density)
        }
        BodySpec::CircleRows(_)
        | BodySpec::Wall(_)
        | BodySpec::Lattice(_)
        | BodySpec::GridColumns(_) => return Ok(None),
    }))
}

/// A finite value at `path`.
pub fn finite(source: &Source<'_>, path: &KeyPath, value: f64) -> Result<f64, Refusal> {
    check::require(source, path, value, value.is_finite(), "must be finite")
}

/// Add the circles of a `circle-rows` entry (the frame must be an open
/// box: its width and height place the rows).
fn add_rows(
    source: &Source<'_>,
    scene: &mut Scene,
    rows: &super::bodies::CircleRowsSpec,
    path: &KeyPath,
) -> Result<(), Refusal> {
    let (width, height) = match (scene.frame.index_of("bottom"), scene.frame.bounding_box()) {
        (Some(_), Some(b)) if scene.frame.walls().len() == 3 => {
            (b.max.x - b.min.x, b.max.y - b.min.y)
        }
        _ => {
            return Err(combination(
                source,
                &[&path.key("kind"), &KeyPath::root("boundary").key("kind")],
                "circle rows fill an open box: give `[boundary] kind = \"open-box\"`",
            ))
        }
    };
    // The bodies of the entries before count towards the same limit.
    let room = MAX_BODIES.saturating_sub(scene.particles.len());
    count(source, &path.key("count"), rows.count, 1, room)?;
    count(source, &path.key("per_row"), rows.per_row, 1, MAX_BODIES)?;
    positive(source, &path.key("radius"), rows.radius)?;
    positive(source, &path.key("row_pitch"), rows.row_pitch)?;
    non_negative(source, &path.key("clearance"), rows.clearance)?;
    positive(source, &path.key("density"), rows.density)?;
    let filled = CircleRows {
        count: rows.count,
        radius: rows.radius,
        width,
        height,
        per_row: rows.per_row,
        row_pitch: rows.row_pitch,
        clearance: rows.clearance,
        density: rows.density,
    }
    .scene(1.0)
    .map_err(|e| Box::new(source.at_key(path, e.to_string())))?;
    scene.particles.extend(filled.particles);
    Ok(())
}
