//! The implicit driver's model: bodies with rigid or affine kinematics, a
//! law with a consistent tangent, Newmark or quasi-static steps, sparse
//! LU, and a run of a number of steps of the driver's `dt`.

use dismech::error::DismechError;
use dismech::implicit::ImplicitError;
use dismech::implicit::{
    Body, BodyMaterial, ContactLaws, ImplicitDynamics, ImplicitSettings, PlaneState, Predictor,
    Prescribed,
};
use dismech::integrate::{
    ImplicitCoefficients, ImplicitIntegrator, Newmark, QuasiStatic, Restarting,
};
use dismech::kinematics::{Affine2, Rigid2};
use dismech::law::{PenaltyCoulomb, SpringDashpotCoulomb};
use dismech::linsolve::SparseLu;
use dismech::math::{Point, Vec2};
use dismech::shape::Segment;

use super::bodies::{BodySpec, Common, MotionSpec, PlaneSpec};
use super::check::{
    self, combination, count, finite2, named, positive, refuse_beside_driver, wall_velocity,
    Refusal,
};
use super::driver::{ImplicitSpec, PredictorSpec};
use super::explicit::{
    finite, gravity, limit_steps, stepping_law, stepping_law_at, SteppingLaw, MAX_BODIES, MAX_STEPS,
};
use super::run::RunSpec;
use super::solvers::{IntegratorSpec, KinematicsSpec};
use super::source::{KeyPath, Source};
use super::{Overrides, ScenarioSpec};

/// The time integration a scenario chose, as one integrator type: each
/// call is that of the scheme it holds.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub enum Scheme {
    /// Newmark with the scenario's β, γ.
    Newmark(Newmark),
    /// Newmark with the velocities reset after each step.
    Restarting(Restarting<Newmark>),
    /// No inertia.
    QuasiStatic(QuasiStatic),
}

impl ImplicitIntegrator for Scheme {
    fn coefficients(&self, dt: f64) -> ImplicitCoefficients {
        match self {
            Self::Newmark(s) => s.coefficients(dt),
            Self::Restarting(s) => s.coefficients(dt),
            Self::QuasiStatic(s) => s.coefficients(dt),
        }
    }

    fn finish(&self, dt: f64, increment: f64, velocity: &mut f64, acceleration: &mut f64) {
        match self {
            Self::Newmark(s) => s.finish(dt, increment, velocity, acceleration),
            Self::Restarting(s) => s.finish(dt, increment, velocity, acceleration),
            Self::QuasiStatic(s) => s.finish(dt, increment, velocity, acceleration),
        }
    }
}

/// The implicit driver of `N` unknowns per body with kinematics `K` and
/// law `L`.
pub type Implicit<const N: usize, K, L> = ImplicitDynamics<N, K, L, Scheme, SparseLu>;

/// The implicit driver with the kinematics and law the scenario chose.
pub enum ImplicitDriver {
    /// Rigid bodies, a spring–dashpot law.
    RigidSpring(Box<Implicit<3, Rigid2, SpringDashpotCoulomb>>),
    /// Rigid bodies, the penalty law.
    RigidPenalty(Box<Implicit<3, Rigid2, PenaltyCoulomb>>),
    /// Affine (DDA) bodies, a spring–dashpot law.
    AffineSpring(Box<Implicit<6, Affine2, SpringDashpotCoulomb>>),
    /// Affine (DDA) bodies, the penalty law.
    AffinePenalty(Box<Implicit<6, Affine2, PenaltyCoulomb>>),
}

/// An implicit model ready to run.
pub struct ImplicitModel {
    /// The driver.
    pub driver: ImplicitDriver,
    /// The step of each call of `advance` (s).
    pub dt: f64,
    /// Calls of `advance`.
    pub steps: u64,
    /// The hash of the bodies' sine motions and the moving walls'
    /// velocities ([`motions`]): a motion is a function, which the
    /// driver's checkpoint cannot compare.
    pub motions: u64,
}

impl ImplicitModel {
    /// The driver's settings, as the scenario gave them.
    pub fn settings(&self) -> &ImplicitSettings {
        match &self.driver {
            ImplicitDriver::RigidSpring(d) => d.settings(),
            ImplicitDriver::RigidPenalty(d) => d.settings(),
            ImplicitDriver::AffineSpring(d) => d.settings(),
            ImplicitDriver::AffinePenalty(d) => d.settings(),
        }
    }
}

/// The FNV-1a hash of each body's sine motion as given (body index,
/// amplitude, frequency and direction bits) and of each moving wall's
/// velocity (`wall`, the body index and the velocity's bits); 0 without
/// either.
pub fn motions(spec: &ScenarioSpec) -> u64 {
    let mut bytes = Vec::new();
    for (k, entry) in spec.bodies.iter().enumerate() {
        if let BodySpec::Wall(w) = entry {
            if let Some(v) = w.velocity {
                bytes.extend_from_slice(b"wall");
                bytes.extend_from_slice(&(k as u64).to_le_bytes());
                for c in v {
                    bytes.extend_from_slice(&c.to_bits().to_le_bytes());
                }
            }
        }
        if let Some(common) = entry.common() {
            if let Some(MotionSpec::Sine(s)) = common.motion {
                let d = s.direction.unwrap_or([1.0, 0.0]);
                bytes.extend_from_slice(&(k as u64).to_le_bytes());
                for v in [s.amplitude, s.frequency, d[0], d[1]] {
                    bytes.extend_from_slice(&v.to_bits().to_le_bytes());
                }
            }
        }
    }
    if bytes.is_empty() {
        0
    } else {
        super::checkpoint::fnv(&[&bytes])
    }
}

/// Build the implicit model of `spec`.
pub fn build(
    source: &Source<'_>,
    spec: &ScenarioSpec,
    settings: &ImplicitSpec,
    overrides: Overrides,
) -> Result<ImplicitModel, Refusal> {
    refuse_other_slots(source, spec)?;
    let law = contact_laws(source, spec)?;
    let scheme = scheme(source, spec)?;
    let driver_path = KeyPath::root("driver");
    let dt = positive(source, &driver_path.key("dt"), settings.dt)?;
    let implicit_settings = implicit_settings(source, spec, settings)?;
    let steps = steps(source, spec, dt, overrides)?;
    let affine = matches!(spec.kinematics, Some(KinematicsSpec::Affine(_)));
    let driver = if affine {
        let bodies = bodies::<6>(source, spec, true)?;
        match law {
            SteppingLaws::Spring(l) => ImplicitDriver::AffineSpring(Box::new(compose(
                source,
                spec,
                bodies,
                Affine2,
                l,
                scheme,
                implicit_settings,
            )?)),
            SteppingLaws::Penalty(l) => ImplicitDriver::AffinePenalty(Box::new(compose(
                source,
                spec,
                bodies,
                Affine2,
                l,
                scheme,
                implicit_settings,
            )?)),
        }
    } else {
        let bodies = bodies::<3>(source, spec, false)?;
        match law {
            SteppingLaws::Spring(l) => ImplicitDriver::RigidSpring(Box::new(compose(
                source,
                spec,
                bodies,
                Rigid2,
                l,
                scheme,
                implicit_settings,
            )?)),
            SteppingLaws::Penalty(l) => ImplicitDriver::RigidPenalty(Box::new(compose(
                source,
                spec,
                bodies,
                Rigid2,
                l,
                scheme,
                implicit_settings,
            )?)),
        }
    };
    Ok(ImplicitModel {
        driver,
        dt,
        steps,
        motions: motions(spec),
    })
}

/// The contact laws of the implicit driver, all of one type.
enum SteppingLaws {
    /// Spring–dashpot laws.
    Spring(ContactLaws<SpringDashpotCoulomb>),
    /// Penalty laws.
    Penalty(ContactLaws<PenaltyCoulomb>),
}

/// The contact laws: `[law]` between groups that no entry of
/// `[[pair_laws]]` names, each entry's law between its two groups
/// ([`ContactLaws::with_pair`]). Refused: a pair given twice, a group no
/// body is in, a pair's law of another type than `[law]`'s.
fn contact_laws(source: &Source<'_>, spec: &ScenarioSpec) -> Result<SteppingLaws, Refusal> {
    let mut laws = match stepping_law(source, spec)? {
        SteppingLaw::Spring(l) => SteppingLaws::Spring(ContactLaws::uniform(l)),
        SteppingLaw::Penalty(l) => SteppingLaws::Penalty(ContactLaws::uniform(l)),
    };
    let groups: Vec<usize> = spec.bodies.iter().map(|b| b.group().unwrap_or(0)).collect();
    let mut given: Vec<((usize, usize), KeyPath)> = Vec::with_capacity(spec.pair_laws.len());
    for (i, pair) in spec.pair_laws.iter().enumerate() {
        let path = KeyPath::root("pair_laws").index(i);
        let [a, b] = pair.groups;
        for g in [a, b] {
            if !groups.contains(&g) {
                return Err(Box::new(source.at_key(
                    &path.key("groups"),
                    format!(
                        "no body is in group {g} (a body's group is its `group` key, 0 by default)"
                    ),
                )));
            }
        }
        let key = (a.min(b), a.max(b));
        if let Some((_, first)) = given.iter().find(|(k, _)| *k == key) {
            return Err(combination(
                source,
                &[&first.key("groups"), &path.key("groups")],
                &format!(
                    "the pair of groups ({}, {}) is given two laws",
                    key.0, key.1
                ),
            ));
        }
        given.push((key, path.clone()));
        let table = path.key("law");
        laws = match (laws, stepping_law_at(source, &pair.law, &table)?) {
            (SteppingLaws::Spring(l), SteppingLaw::Spring(p)) => {
                SteppingLaws::Spring(l.with_pair(a, b, p))
            }
            (SteppingLaws::Penalty(l), SteppingLaw::Penalty(p)) => {
                SteppingLaws::Penalty(l.with_pair(a, b, p))
            }
            _ => {
                return Err(combination(
                    source,
                    &[&KeyPath::root("law").key("kind"), &table.key("kind")],
                    "a pair's law is of the type of `[law]`: `penalty-coulomb` beside `penalty-coulomb`, `katsuki` or `spring-dashpot-coulomb` beside either of those",
                ))
            }
        };
    }
    Ok(laws)
}

/// [`ImplicitDynamics::compose`], its errors placed at the keys that gave
/// the values.
fn compose<const N: usize, K, L>(
    source: &Source<'_>,
    spec: &ScenarioSpec,
    bodies: Vec<Body<N>>,
    kinematics: K,
    laws: ContactLaws<L>,
    scheme: Scheme,
    settings: ImplicitSettings,
) -> Result<Implicit<N, K, L>, Refusal>
where
    K: dismech::kinematics::Kinematics<N>
        + dismech::kinematics::Advance<dismech::kinematics::PlacedPolygon, N>
        + dismech::kinematics::Advance<dismech::kinematics::PlacedEllipse, N>,
    L: dismech::law::TangentLaw<2>,
{
    ImplicitDynamics::compose(
        bodies,
        kinematics,
        laws,
        scheme,
        SparseLu::default(),
        settings,
    )
    .map_err(|e| compose_error(source, spec, e))
}

/// The refusal of an error of [`ImplicitDynamics::compose`].
fn compose_error(source: &Source<'_>, spec: &ScenarioSpec, error: DismechError) -> Refusal {
    let body = |k: usize| KeyPath::root("bodies").index(k);
    let message = error.to_string();
    let driver = KeyPath::root("driver");
    Box::new(match &error {
        DismechError::Implicit(ImplicitError::BlocksOverlap {
            vertex_block,
            edge_block,
            ..
        }) => source.at_keys(&[&body(*vertex_block), &body(*edge_block)], message),
        DismechError::Implicit(ImplicitError::BlocksCross { a, b, .. }) => {
            source.at_keys(&[&body(*a), &body(*b)], message)
        }
        DismechError::Implicit(ImplicitError::InvalidEdgeTraction { body: b, edge, .. }) => {
            let k = spec
                .loads
                .tractions
                .iter()
                .position(|t| t.body == *b && t.edge == *edge)
                .unwrap_or(0);
            source.at_key(&KeyPath::root("loads").key("tractions").index(k), message)
        }
        DismechError::Implicit(ImplicitError::InvalidBlock { block, .. }) => {
            source.at_key(&body(*block), message)
        }
        DismechError::InvalidParameter { name, .. } => {
            let key = match *name {
                "search distance d0" => "search_distance",
                "overlap tolerance" => "overlap_tolerance",
                "max_search_distance" => "max_search_distance",
                "residual tolerance" => "residual_tolerance",
                "slip regularization" => "slip_regularization",
                "slip_reversal_quantile" => "slip_reversal_quantile",
                "mass damping" => "mass_damping",
                "min_dt_ratio" => "min_dt_ratio",
                "gravity" => {
                    return Box::new(source.at_key(&KeyPath::root("loads").key("gravity"), message))
                }
                _ => return Box::new(source.at_key(&KeyPath::root("bodies"), message)),
            };
            source.at_key(&driver.key(key), message)
        }
        _ => source.at_key(&KeyPath::root("bodies"), message),
    })
}

/// Refuse the tables that the implicit driver has no slot for.
fn refuse_other_slots(source: &Source<'_>, spec: &ScenarioSpec) -> Result<(), Refusal> {
    refuse_beside_driver(
        source,
        spec.boundary.is_some(),
        KeyPath::root("boundary").key("kind"),
        "the implicit driver's walls are bodies: give `[[bodies]] kind = \"wall\"` instead of a `[boundary]`",
    )?;
    refuse_beside_driver(
        source,
        spec.lp_solver.is_some(),
        KeyPath::root("lp_solver"),
        "the implicit driver solves no LP: remove this table",
    )?;
    refuse_beside_driver(
        source,
        spec.loads.seismic.is_some(),
        KeyPath::root("loads").key("seismic"),
        "a seismic coefficient loads the HPM driver's columns",
    )?;
    refuse_beside_driver(
        source,
        !spec.loads.forces.is_empty(),
        KeyPath::root("loads").key("forces"),
        "the implicit driver takes loads as edge tractions (`loads.tractions`)",
    )?;
    refuse_beside_driver(
        source,
        spec.loads.live.is_some(),
        KeyPath::root("loads").key("live"),
        "a live load is the limit driver's; the implicit driver takes loads as edge tractions (`loads.tractions`)",
    )
}

/// The integrator of `[integrator]` (Newmark β = ½, γ = 1 by default).
fn scheme(source: &Source<'_>, spec: &ScenarioSpec) -> Result<Scheme, Refusal> {
    let table = KeyPath::root("integrator");
    match &spec.integrator {
        None => Ok(Scheme::Newmark(Newmark::dda())),
        Some(IntegratorSpec::Newmark(n)) => {
            let newmark = Newmark::new(n.beta.unwrap_or(0.5), n.gamma.unwrap_or(1.0)).map_err(|e| {
                named(source, &table, &[("Newmark beta", "beta"), ("Newmark gamma", "gamma")], e)
            })?;
            Ok(if n.restarting.unwrap_or(false) {
                Scheme::Restarting(Restarting(newmark))
            } else {
                Scheme::Newmark(newmark)
            })
        }
        Some(IntegratorSpec::QuasiStatic(_)) => Ok(Scheme::QuasiStatic(QuasiStatic)),
        Some(IntegratorSpec::ExplicitEuler(_)) => Err(combination(
            source,
            &[&KeyPath::root("driver").key("kind"), &table.key("kind")],
            "the implicit driver takes an implicit integrator (`newmark` or `quasi-static`); `explicit-euler` serves the explicit driver",
        )),
    }
}

/// The settings of `[driver]`, each defaulting to the library's.
fn implicit_settings(
    source: &Source<'_>,
    spec: &ScenarioSpec,
    s: &ImplicitSpec,
) -> Result<ImplicitSettings, Refusal> {
    let d = ImplicitSettings::default();
    let driver = KeyPath::root("driver");
    let iterations = |v: Option<usize>, key: &str, default: usize| match v {
        Some(v) => count(source, &driver.key(key), v, 1, 1_000_000),
        None => Ok(default),
    };
    Ok(ImplicitSettings {
        gravity: gravity(source, spec)?,
        search_distance: s.search_distance.unwrap_or(d.search_distance),
        max_search_distance: s.max_search_distance.or(d.max_search_distance),
        overlap_tolerance: s.overlap_tolerance.unwrap_or(d.overlap_tolerance),
        max_open_close: iterations(s.max_open_close, "max_open_close", d.max_open_close)?,
        max_newton: iterations(s.max_newton, "max_newton", d.max_newton)?,
        residual_tolerance: s.residual_tolerance.unwrap_or(d.residual_tolerance),
        min_dt_ratio: s.min_dt_ratio.unwrap_or(d.min_dt_ratio),
        predictor: match s.predictor {
            None => d.predictor,
            Some(PredictorSpec::FreeFlight) => Predictor::FreeFlight,
            Some(PredictorSpec::ConstantAcceleration) => Predictor::ConstantAcceleration,
            Some(PredictorSpec::StartOfStep) => Predictor::StartOfStep,
        },
        slip_regularization: s.slip_regularization.unwrap_or(d.slip_regularization),
        slip_reversal_quantile: s.slip_reversal_quantile.unwrap_or(d.slip_reversal_quantile),
        mass_damping: s.mass_damping.unwrap_or(d.mass_damping),
    })
}

/// The calls of `advance` of `[run]` (`steps` or `time`; required).
fn steps(
    source: &Source<'_>,
    spec: &ScenarioSpec,
    dt: f64,
    overrides: Overrides,
) -> Result<u64, Refusal> {
    let run = KeyPath::root("run");
    let steps_of_time = |t: f64| (t / dt).round();
    let steps = match &spec.run {
        Some(RunSpec::Steps(s)) => {
            count(source, &run.key("steps"), s.steps as usize, 1, usize::MAX)? as u64
        }
        Some(RunSpec::Time(t)) => {
            let end = positive(source, &run.key("end_time"), t.end_time)?;
            let steps = steps_of_time(end);
            check::require(
                source,
                &run.key("end_time"),
                end,
                (1.0..=MAX_STEPS).contains(&steps),
                &format!("must hold between 1 and {MAX_STEPS:e} steps of the driver's dt = {dt} s"),
            )?;
            steps as u64
        }
        Some(RunSpec::ToRest(_)) => return Err(combination(
            source,
            &[&KeyPath::root("driver").key("kind"), &run.key("kind")],
            "a run to rest is the explicit driver's; the implicit driver runs `steps` or `time`",
        )),
        None => {
            return Err(Box::new(source.at_key(
                &run,
                "the implicit driver needs a `[run]` (kind = \"steps\" or \"time\")",
            )))
        }
    };
    Ok(limit_steps(steps, overrides, steps_of_time))
}

/// The bodies of `[[bodies]]` with `N` unknowns each (`affine`: elastic
/// material required), and the tractions of `[loads]`.
fn bodies<const N: usize>(
    source: &Source<'_>,
    spec: &ScenarioSpec,
    affine: bool,
) -> Result<Vec<Body<N>>, Refusal> {
    let driver_kind = KeyPath::root("driver").key("kind");
    count(
        source,
        &KeyPath::root("bodies"),
        spec.bodies.len(),
        1,
        MAX_BODIES,
    )?;
    let mut bodies = Vec::with_capacity(spec.bodies.len());
    for (k, entry) in spec.bodies.iter().enumerate() {
        let path = KeyPath::root("bodies").index(k);
        let mut body = match entry {
            BodySpec::Wall(w) => {
                let start = finite2(source, &path.key("start"), w.start)?;
                let end = finite2(source, &path.key("end"), w.end)?;
                let segment = Segment::new(Point::new(start[0], start[1]), Point::new(end[0], end[1]));
                let mut wall = Body::wall(segment, k)
                    .map_err(|e| Box::new(source.at_key(&path, e.to_string())))?;
                if let Some(v) = w.velocity {
                    let v = wall_velocity(source, &path.key("velocity"), v)?;
                    let velocity = Vec2::new(v[0], v[1]);
                    wall.prescribed = Some(Prescribed::translation(move |t| velocity * t));
                }
                wall
            }
            BodySpec::CircleRows(_) | BodySpec::Lattice(_) | BodySpec::GridColumns(_) => {
                return Err(combination(
                    source,
                    &[&driver_kind, &path.key("kind")],
                    "the implicit driver takes single bodies: `circle`, `ellipse`, `polygon`, `rectangle` or `wall`",
                ))
            }
            _ => single(source, entry, &path, k, affine)?,
        };
        body.group = entry.group().unwrap_or(0);
        bodies.push(body);
    }
    for (i, t) in spec.loads.tractions.iter().enumerate() {
        let path = KeyPath::root("loads").key("tractions").index(i);
        count(source, &path.key("body"), t.body, 0, bodies.len() - 1)?;
        let traction = finite2(source, &path.key("traction"), t.traction)?;
        bodies[t.body]
            .edge_tractions
            .push((t.edge, Vec2::new(traction[0], traction[1])));
    }
    Ok(bodies)
}

/// A single body (not a wall) of `N` unknowns.
fn single<const N: usize>(
    source: &Source<'_>,
    entry: &BodySpec,
    path: &KeyPath,
    k: usize,
    affine: bool,
) -> Result<Body<N>, Refusal> {
    let Some(common) = entry.common() else {
        return Err(Box::new(source.at_key(path, "not a single body")));
    };
    let material = material(source, &common, path, affine)?;
    let centre = |c: [f64; 2]| -> Result<Point, Refusal> {
        let c = finite2(source, &path.key("centre"), c)?;
        Ok(Point::new(c[0], c[1]))
    };
    let names: check::Names<'_> = &[
        ("density", "density"),
        ("Young's modulus", "youngs_modulus"),
        ("Poisson's ratio", "poisson_ratio"),
        ("semi-axis a", "semi_major"),
        ("semi-axis b", "semi_minor"),
        (super::explicit::ELLIPSE_AXES_SWAPPED, "semi_minor"),
        ("ellipse angle", "angle"),
    ];
    let refuse = |e: DismechError| named(source, path, names, e);
    let mut body = match entry {
        BodySpec::Circle(b) => {
            positive(source, &path.key("radius"), b.radius)?;
            Body::circle(centre(b.centre)?, b.radius, material, k).map_err(refuse)?
        }
        BodySpec::Ellipse(b) => {
            let angle = finite(source, &path.key("angle"), b.angle.unwrap_or(0.0))?;
            Body::ellipse(
                centre(b.centre)?,
                b.semi_major,
                b.semi_minor,
                angle,
                material,
                k,
            )
            .map_err(refuse)?
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
            Body::new(&vertices, material, k).map_err(|e| match e {
                DismechError::InvalidPolygon { .. } => {
                    Box::new(source.at_key(&path.key("vertices"), e.to_string()))
                }
                e => refuse(e),
            })?
        }
        BodySpec::Rectangle(b) => {
            let c = centre(b.centre)?;
            let (w, h) = (
                positive(source, &path.key("width"), b.width)?,
                positive(source, &path.key("height"), b.height)?,
            );
            let angle = finite(source, &path.key("angle"), b.angle.unwrap_or(0.0))?;
            let (s, co) = angle.sin_cos();
            let corners: Vec<Point> = [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]
                .iter()
                .map(|(x, y)| {
                    let (dx, dy) = (x * w, y * h);
                    Point::new(c.x + co * dx - s * dy, c.y + s * dx + co * dy)
                })
                .collect();
            Body::new(&corners, material, k)
                .map_err(|e| Box::new(source.at_key(path, e.to_string())))?
        }
        _ => return Err(Box::new(source.at_key(path, "not a single body"))),
    };
    if let Some(v) = common.velocity {
        let v = finite2(source, &path.key("velocity"), v)?;
        body.velocity[0] = v[0];
        body.velocity[1] = v[1];
    }
    if let Some(w) = common.angular_velocity {
        body.velocity[2] = finite(source, &path.key("angular_velocity"), w)?;
    }
    body.prescribed = match common.motion {
        None => None,
        Some(MotionSpec::Fixed(_)) => Some(Prescribed::fixed()),
        Some(MotionSpec::Sine(s)) => Some(sine(source, &path.key("motion"), s)?),
        Some(MotionSpec::ConstantVelocity(_)) => {
            return Err(combination(
                source,
                &[
                    &KeyPath::root("driver").key("kind"),
                    &path.key("motion").key("kind"),
                ],
                "a constant velocity drives the explicit driver's bodies; the implicit driver's are `fixed` or `sine`",
            ))
        }
    };
    Ok(body)
}

/// A sinusoidal translation `u(t) = A d sin(2π f t)`.
fn sine<const N: usize>(
    source: &Source<'_>,
    path: &KeyPath,
    s: &super::bodies::SineSpec,
) -> Result<Prescribed<N>, Refusal> {
    let a = finite(source, &path.key("amplitude"), s.amplitude)?;
    let f = check::non_negative(source, &path.key("frequency"), s.frequency)?;
    let d = finite2(
        source,
        &path.key("direction"),
        s.direction.unwrap_or([1.0, 0.0]),
    )?;
    let norm = d[0].hypot(d[1]);
    check::require(
        source,
        &path.key("direction"),
        norm,
        (norm - 1.0).abs() <= 1e-12,
        "must be a unit vector (its length is given)",
    )?;
    let w = std::f64::consts::TAU * f;
    // A zero component stays an exact zero (not −0 · sin).
    let along = move |c: f64, u: f64| if c == 0.0 { 0.0 } else { c * u };
    Ok(Prescribed::translation(move |t| {
        let u = a * (w * t).sin();
        Vec2::new(along(d[0], u), along(d[1], u))
    }))
}

/// The material of a single body: the density, and for affine bodies the
/// elastic constants (for rigid ones, which do not deform, E and ν are
/// not used and may be left out).
fn material(
    source: &Source<'_>,
    common: &Common<'_>,
    path: &KeyPath,
    affine: bool,
) -> Result<BodyMaterial, Refusal> {
    let density = match common.density {
        Some(d) => positive(source, &path.key("density"), d)?,
        None => return Err(Box::new(source.at_key(path, "no `density` (kg/m^3)"))),
    };
    let elastic = |v: Option<f64>, key: &str, rigid: f64| {
        match (v, affine) {
        (Some(v), _) => Ok(v),
        (None, false) => Ok(rigid),
        (None, true) => Err(combination(
            source,
            &[&path.key(key), &KeyPath::root("kinematics").key("kind")],
            "an affine (deformable) body needs its elastic constants `youngs_modulus` and `poisson_ratio`",
        )),
    }
    };
    let material = BodyMaterial {
        density,
        youngs_modulus: elastic(common.youngs_modulus, "youngs_modulus", 1.0)?,
        poisson_ratio: elastic(common.poisson_ratio, "poisson_ratio", 0.0)?,
        plane: match common.plane {
            None | Some(PlaneSpec::Stress) => PlaneState::Stress,
            Some(PlaneSpec::Strain) => PlaneState::Strain,
        },
    };
    material.validate(0).map_err(|e| {
        named(
            source,
            path,
            &[
                ("density", "density"),
                ("Young's modulus", "youngs_modulus"),
                ("Poisson's ratio", "poisson_ratio"),
            ],
            e,
        )
    })?;
    Ok(material)
}
