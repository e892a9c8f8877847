//! The same model solved two ways: a limit-analysis model of circles and
//! supports (paper 002) pushed quasi-statically by the implicit driver with
//! bonded penalty contacts, whose load plateau is compared with the LP's
//! limit load.
//!
//! [`pushover_model`] turns a [`LimitModel`] of circles into an implicit
//! model, contact for contact:
//!
//! | limit model | penalty model |
//! |---|---|
//! | circular element, rolling or not | rigid disc ([`Rigid2`]), its rotation held at zero if it may not roll |
//! | support (a line, normal into the material) | a fixed wall along the line, covering its contacts' points and half a radius beyond; the support with a velocity is the plate, translated at that velocity ([`Prescribed::translation`], time = plate travel at unit speed) |
//! | contact of strength `|T| ≤ c + N tan φ` that keeps contact | [`PenaltyCoulomb::bonded_with_friction`]`(p, c, tan φ)`: bilateral, shear capped by return mapping |
//! | contact that may open | [`PenaltyCoulomb::new`]`(p, tan φ)` (no cohesion) |
//! | rigid-plastic collapse, plate at unit speed | quasi-static steps ([`QuasiStatic`]) of the plate's travel |
//!
//! The implicit driver finds its contacts by geometry (circles within the
//! search distance), so [`PushoverModel::contacts_match`] checks after a
//! step that it found exactly the pairs the limit model lists. Laws are
//! per pair of body groups: elements are group 0, support `k` is group
//! `k + 1`, so every contact between elements must have one strength, and
//! every contact on one support one strength.
//!
//! The penalty model is elastic–perfectly plastic with an associated flow
//! for cohesive contacts (`φ = 0`): by the theorems of limit analysis its
//! load under the pushing plate rises to a plateau at the rigid-plastic
//! limit load, up to the change of geometry over the plate's travel.
//! [`penalty_vs_lp`] does this for paper 002's rolling U-model.

use dismech::error::{require_positive, DismechError, PenaltyRefusal, Result};
use dismech::implicit::{
    Body, BodyMaterial, ContactLaws, ImplicitDynamics, ImplicitSettings, PlaneState, Predictor,
    Prescribed, StepReport,
};
use dismech::integrate::QuasiStatic;
use dismech::kinematics::Rigid2;
use dismech::law::{FrictionIntegration, PenaltyCoulomb};
use dismech::limit::lattice::Lattice;
use dismech::limit::{analyse, LimitModel, Partner, PlasticContact};
use dismech::linsolve::SparseLu;
use dismech::lp::LinearProgramSolver;
use dismech::math::Vec2;
use dismech::shape::{AnyShape2, Segment};

/// Fraction of a slipping contact's normal stiffness added to its shear
/// stiffness in Newton's matrix ([`ImplicitSettings::slip_regularization`]):
/// without inertia a disc whose contacts all slip turns freely. 1e-4 keeps
/// the matrix regular without slowing Newton much (1e-6 is too little: the
/// iteration wanders; 1e-2 converges too slowly).
pub const SLIP_REGULARIZATION: f64 = 1e-4;

/// The implicit model of a penalty pushover.
type Pushover = ImplicitDynamics<3, Rigid2, PenaltyCoulomb, QuasiStatic, SparseLu>;

/// A limit model turned into a penalty model, with its plate.
#[derive(Debug)]
pub struct PushoverModel {
    /// The implicit model: the elements (bodies `0..n`), then one wall per
    /// support (body `n + k` for support `k`).
    pub model: Pushover,
    /// Number of elements.
    pub elements: usize,
    /// The plate's body index.
    pub plate: usize,
    /// Unit direction of the plate's velocity.
    pub direction: Vec2,
    /// The plate's speed (m per unit of the driver's time).
    pub speed: f64,
    /// The pairs in contact the limit model lists (element, element or
    /// wall body), each as (smaller, larger) index, sorted.
    pub listed_pairs: Vec<(usize, usize)>,
}

impl PushoverModel {
    /// The plate's load: the force it exerts on the elements along its
    /// velocity (N/m).
    pub fn plate_load(&self) -> f64 {
        -self.model.contact_force_on(self.plate).dot(&self.direction)
    }

    /// The plate's travel so far (m): the driver's time times the
    /// plate's speed.
    pub fn travel(&self) -> f64 {
        self.model.time() * self.speed
    }

    /// Whether the driver's contacts of the last step are exactly the pairs
    /// the limit model lists.
    pub fn contacts_match(&self) -> bool {
        let mut found: Vec<(usize, usize)> = self
            .model
            .contacts()
            .iter()
            .map(|c| (c.bodies.0.min(c.bodies.1), c.bodies.0.max(c.bodies.1)))
            .collect();
        found.sort_unstable();
        found == self.listed_pairs
    }
}

fn refuse(reason: PenaltyRefusal) -> DismechError {
    DismechError::PenaltyModel(reason)
}

/// The penalty law of a limit-analysis contact with penalty `penalty`.
fn penalty_law(law: &PlasticContact, penalty: f64) -> Result<PenaltyCoulomb> {
    if law.is_unilateral() {
        if law.cohesion() > 0.0 {
            return Err(refuse(PenaltyRefusal::CohesiveOpening {
                cohesion: law.cohesion(),
            }));
        }
        PenaltyCoulomb::new(penalty, law.friction(), FrictionIntegration::ReturnMapping)
    } else {
        PenaltyCoulomb::bonded_with_friction(penalty, law.cohesion(), law.friction())
    }
}

/// The wall along support `k`: a segment of its line, material on its
/// normal's side, covering the points of the support's contacts and half
/// the largest element radius beyond them.
fn support_wall(limit: &LimitModel, k: usize, index: usize) -> Result<Body<3>> {
    let support = &limit.supports()[k];
    // Direction along the line with the normal on its left.
    let along = Vec2::new(support.normal.y, -support.normal.x);
    let margin = 0.5
        * limit
            .bodies()
            .iter()
            .map(|b| b.radius())
            .fold(0.0, f64::max);
    let (lo, hi) = limit
        .contacts()
        .iter()
        .filter(|c| c.partner == Partner::Support(k))
        .map(|c| (c.point - support.point).dot(&along))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), t| {
            (lo.min(t), hi.max(t))
        });
    if !lo.is_finite() {
        return Err(refuse(PenaltyRefusal::SupportWithoutContact {
            support: k,
            name: support.name.clone(),
        }));
    }
    let at = |t: f64| support.point + along * t;
    Body::wall(Segment::new(at(lo - margin), at(hi + margin)), index)
}

/// Turn `limit` (circular elements, straight supports, one support with a
/// velocity: the plate) into a quasi-static penalty model with contact
/// penalty `penalty` (N/m per m) and search distance `search` (m). See the
/// module documentation for the correspondence.
///
/// # Errors
/// [`DismechError::PenaltyModel`] for an element that is not a circle, no
/// plate or more than one, a support without contacts, a cohesive contact
/// that may open, or two contacts of one pair of groups with different
/// strengths; invalid penalty or search distance.
pub fn pushover_model(limit: &LimitModel, penalty: f64, search: f64) -> Result<PushoverModel> {
    require_positive("contact penalty", penalty)?;
    let material = BodyMaterial {
        density: 1.0,
        youngs_modulus: 1.0,
        poisson_ratio: 0.0,
        plane: PlaneState::Stress,
    };
    let n = limit.bodies().len();
    let mut bodies = Vec::with_capacity(n + limit.supports().len());
    for (i, b) in limit.bodies().iter().enumerate() {
        let AnyShape2::Circle(circle) = &b.shape else {
            return Err(refuse(PenaltyRefusal::NotACircle { element: i }));
        };
        let mut body = Body::circle(b.centre, circle.radius(), material, i)?;
        if !b.rotates {
            body.prescribed = Some(Prescribed {
                mask: [false, false, true],
                motion: std::sync::Arc::new(|_| [0.0; 3]),
            });
        }
        bodies.push(body);
    }
    let moving: Vec<usize> = (0..limit.supports().len())
        .filter(|&k| limit.supports()[k].velocity.norm() > 0.0)
        .collect();
    let [plate_support] = moving[..] else {
        return Err(refuse(PenaltyRefusal::MovingSupports {
            count: moving.len(),
        }));
    };
    for k in 0..limit.supports().len() {
        let mut wall = support_wall(limit, k, n + k)?;
        if k == plate_support {
            let velocity = limit.supports()[k].velocity;
            wall.prescribed = Some(Prescribed::translation(move |t| velocity * t));
        }
        bodies.push(wall);
    }
    let laws = group_laws(limit, penalty, &mut bodies)?;
    let mut listed_pairs: Vec<(usize, usize)> = limit
        .contacts()
        .iter()
        .map(|c| {
            let b = match c.partner {
                Partner::Body(j) => j,
                Partner::Support(k) => n + k,
            };
            (c.body.min(b), c.body.max(b))
        })
        .collect();
    listed_pairs.sort_unstable();
    let settings = ImplicitSettings {
        gravity: Vec2::zeros(),
        search_distance: search,
        predictor: Predictor::StartOfStep,
        slip_regularization: SLIP_REGULARIZATION,
        max_newton: 60,
        residual_tolerance: 1e-9,
        ..ImplicitSettings::default()
    };
    let model = ImplicitDynamics::compose(
        bodies,
        Rigid2,
        laws,
        QuasiStatic,
        SparseLu::default(),
        settings,
    )?;
    let velocity = limit.supports()[plate_support].velocity;
    Ok(PushoverModel {
        model,
        elements: n,
        plate: n + plate_support,
        direction: velocity / velocity.norm(),
        speed: velocity.norm(),
        listed_pairs,
    })
}

/// The contact laws by group (elements 0, support `k` group `k + 1`, set
/// on `bodies`), from the limit model's contacts.
fn group_laws(
    limit: &LimitModel,
    penalty: f64,
    bodies: &mut [Body<3>],
) -> Result<ContactLaws<PenaltyCoulomb>> {
    let n = limit.bodies().len();
    for (k, body) in bodies[n..].iter_mut().enumerate() {
        body.group = k + 1;
    }
    let mut table: Vec<((usize, usize), PlasticContact)> = Vec::new();
    for (index, c) in limit.contacts().iter().enumerate() {
        let groups = match c.partner {
            Partner::Body(_) => (0, 0),
            Partner::Support(k) => (0, k + 1),
        };
        match table.iter().find(|(g, _)| *g == groups) {
            Some((_, law)) if *law != c.law => {
                return Err(refuse(PenaltyRefusal::UnlikeStrengths {
                    contact: index,
                    cohesion: c.law.cohesion(),
                    friction: c.law.friction(),
                    other_cohesion: law.cohesion(),
                    other_friction: law.friction(),
                }))
            }
            Some(_) => {}
            None => table.push((groups, c.law)),
        }
    }
    let Some(((_, _), first)) = table.first() else {
        return Err(refuse(PenaltyRefusal::NoContact));
    };
    let mut laws = ContactLaws::uniform(penalty_law(first, penalty)?);
    for ((a, b), law) in &table {
        laws = laws.with_pair(*a, *b, penalty_law(law, penalty)?);
    }
    Ok(laws)
}

/// A pushover run: the plate's travel and load after each step.
#[derive(Debug, Clone, PartialEq)]
pub struct PushoverCurve {
    /// The contact penalty (N/m per m).
    pub penalty: f64,
    /// Plate travel after each step (m).
    pub travel: Vec<f64>,
    /// Plate load after each step (N/m).
    pub load: Vec<f64>,
    /// Newton iterations of each step (its last sub-step).
    pub iterations: Vec<usize>,
    /// Step reductions over the run.
    pub reductions: usize,
    /// Whether the driver found exactly the limit model's contacts (after
    /// the first step).
    pub contacts_match: bool,
}

impl PushoverCurve {
    /// The plateau: the mean load over the last `fraction` of the steps.
    pub fn plateau(&self, fraction: f64) -> f64 {
        let count = ((self.load.len() as f64 * fraction).ceil() as usize).clamp(1, self.load.len());
        let tail = &self.load[self.load.len() - count..];
        tail.iter().sum::<f64>() / count as f64
    }

    /// Largest relative departure of the loads of the last `fraction` of
    /// the steps from their mean: how flat the plateau is.
    pub fn plateau_spread(&self, fraction: f64) -> f64 {
        let mean = self.plateau(fraction);
        let count = ((self.load.len() as f64 * fraction).ceil() as usize).clamp(1, self.load.len());
        self.load[self.load.len() - count..]
            .iter()
            .map(|l| (l / mean - 1.0).abs())
            .fold(0.0, f64::max)
    }
}

/// Push `limit`'s plate by `travel` (m) in `steps` equal quasi-static
/// steps with contact penalty `penalty` and search distance `search`.
///
/// # Errors
/// As [`pushover_model`], and
/// [`ImplicitError::StepFailed`](dismech::implicit::ImplicitError::StepFailed)
/// when a step fails at its smallest size.
pub fn pushover(
    limit: &LimitModel,
    penalty: f64,
    search: f64,
    travel: f64,
    steps: usize,
) -> Result<PushoverCurve> {
    if steps == 0 {
        return Err(DismechError::InvalidParameter {
            name: "pushover steps",
            value: 0.0,
            requirement: "must be at least 1",
        });
    }
    let mut run = pushover_model(limit, penalty, search)?;
    // The driver's time step that moves the plate by travel / steps.
    let step = require_positive("plate travel", travel)? / (steps as f64 * run.speed);
    let mut curve = PushoverCurve {
        penalty,
        travel: Vec::with_capacity(steps),
        load: Vec::with_capacity(steps),
        iterations: Vec::with_capacity(steps),
        reductions: 0,
        contacts_match: false,
    };
    for k in 0..steps {
        let report: StepReport = run.model.advance(step)?;
        if k == 0 {
            curve.contacts_match = run.contacts_match();
        }
        curve.reductions += report.reductions;
        curve.iterations.push(report.residuals.len());
        curve.travel.push(run.travel());
        curve.load.push(run.plate_load());
    }
    Ok(curve)
}

/// Paper 002's U-model pushed by penalty models of three stiffnesses.
///
/// Each run pushes the plate by `travel_force / penalty`: the elastic
/// travel to the plateau scales with the compliance `1/p`, so every run
/// reaches its plateau in the same share of its steps. What separates the
/// plateau from the LP's load is the change of geometry over that travel
/// (the LP is of the undeformed lattice): the gap falls as the penalty
/// rises.
#[derive(Debug, Clone, PartialEq)]
pub struct UModelPushover {
    /// The lattice ([`Lattice::u_model`]: R = 1, C_p = 1).
    pub lattice: Lattice,
    /// Contact penalties (N/m per m, with C_p = 1 N/m and R = 1 m), softest
    /// first; the check takes the last.
    pub penalties: Vec<f64>,
    /// Plate travel of a run times its penalty (N/m).
    pub travel_force: f64,
    /// Quasi-static steps of every run.
    pub steps: usize,
    /// Search distance (m).
    pub search: f64,
    /// Fraction of the steps (the last ones) over which the plateau is
    /// averaged.
    pub plateau_fraction: f64,
}

impl Default for UModelPushover {
    /// k = 4, n' = 1, rolling; penalties 1e4, 3e4, 1e5; travel 300 / p
    /// (0.03 R at 1e4) in 80 steps; plateau over the last quarter.
    fn default() -> Self {
        Self {
            lattice: Lattice::u_model(4, 4, 1, true),
            penalties: vec![1e4, 3e4, 1e5],
            travel_force: 300.0,
            steps: 80,
            search: 0.1,
            plateau_fraction: 0.25,
        }
    }
}

/// The LP limit load and the pushover curves of a U-model.
#[derive(Debug, Clone, PartialEq)]
pub struct PenaltyVsLp {
    /// The set-up.
    pub setup: UModelPushover,
    /// The LP's limit load (N/m, in units of C_p with R = 1).
    pub lp_load: f64,
    /// One curve per penalty, in the order of `setup.penalties`.
    pub curves: Vec<PushoverCurve>,
}

impl PenaltyVsLp {
    /// Plateau of curve `k` over the LP limit load.
    pub fn plateau_ratio(&self, k: usize) -> f64 {
        self.curves[k].plateau(self.setup.plateau_fraction) / self.lp_load
    }

    /// The checked ratio: the plateau of the stiffest run (the last) over
    /// the LP limit load.
    pub fn checked_ratio(&self) -> f64 {
        self.plateau_ratio(self.curves.len().saturating_sub(1))
    }
}

/// Solve `setup`'s lattice by the LP (Clarabel) and push it with each
/// penalty.
///
/// # Errors
/// [`DismechError::InvalidParameter`] for no penalties or a travel force
/// that is not positive; as [`Lattice::build`], [`analyse`] and
/// [`pushover`]; a collapse the LP
/// does not find is [`DismechError::PenaltyModel`].
pub fn penalty_vs_lp(setup: &UModelPushover) -> Result<PenaltyVsLp> {
    if setup.penalties.is_empty() {
        return Err(DismechError::InvalidParameter {
            name: "penalties",
            value: 0.0,
            requirement: "needs at least one penalty",
        });
    }
    let limit = setup.lattice.build()?;
    let result = analyse(&limit, &mut LinearProgramSolver::default())?;
    let lp_load = result.load.ok_or_else(|| {
        refuse(PenaltyRefusal::NoCollapse {
            status: result.status,
        })
    })?;
    let curves = setup
        .penalties
        .iter()
        .map(|&p| {
            let travel = require_positive("travel force", setup.travel_force)? / p;
            pushover(&limit, p, setup.search, travel, setup.steps)
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(PenaltyVsLp {
        setup: setup.clone(),
        lp_load,
        curves,
    })
}
