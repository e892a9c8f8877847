//! Ellipses settled in a box by the implicit driver at a time step far
//! beyond the explicit stability limit: rigid ellipses ([`Rigid2`]) with
//! the penalty Coulomb law (return mapping), Newmark, sparse LU — the
//! composition paper 000's ellipses never had, since its DEM is explicit.
//!
//! The packing: ellipses of aspect ratio 2, semi-major axes and
//! orientations spread by low-discrepancy sequences (as in
//! [`super::packing_lp`]), stacked in columns with small gaps and released
//! in an open box (a floor and two side walls, all bodies of the driver).
//! The step is `step_ratio` times the explicit limit `2 √(m/k)` of the
//! lightest ellipse on one penalty spring (its translation against a
//! wall: the softest contact mode, so the largest explicit step; rotation
//! and several contacts only lower it, so the ratio is a lower bound).
//!
//! The integrator is Newmark with `γ = 1` and `β = (γ + ½)²/4 = 0.5625`:
//! classic DDA's `β = ½, γ = 1` damps the stiff contact modes well only
//! near `ω Δt ≈ 4`; at 20 times the explicit limit (`ω Δt = 40` for the
//! softest mode) its spectral radius is 0.995, so the contact modes keep
//! ringing and a packing does not come to rest. With `β = 0.5625` the
//! spectral radius at high frequency is 1/3 (computed by
//! [`Newmark::spectral_radius`]).
//!
//! The driver halves a step whose open–close or Newton iteration does not
//! converge and doubles it again after a success. While the columns
//! collapse the ellipses spin fast ([`SettledBox::peak_spin`]; tens of
//! rad/s) and boundary points move several centimetres in a step of 20
//! limits, more than the search distance (30 mm, the smallest semi-minor
//! axis): such a step would miss contacts, so it is detected again at a
//! search distance that covers its motion, up to
//! [`EllipseBox::max_search_distance`] (the smallest ellipse's length),
//! and repeated at its size ([`ImplicitSettings::max_search_distance`]).
//! The collapse — impacts, contacts opening and closing, slip reversing —
//! is where Newton and the open–close iteration fail within 40 iterations
//! and a step is halved; once the packing is dense the steps are taken
//! whole, and it settles at the requested step.
//! [`SettledBox::accepted_step_ratio`] reports the mean accepted sub-step
//! against the explicit limit beside the requested
//! [`SettledBox::step_ratio`], [`SettledBox::halvings`] the causes,
//! [`SettledBox::last_halved_at`] when the last halving was and
//! [`SettledBox::whole_steps`] how many steps were taken whole.
//!
//! Ellipses balanced on one contact rock slowly (ω ≈ 5 rad/s), and
//! Newmark's damping of so low a frequency at this step is small, so
//! without more a packing reaches the rest criterion after anywhere from 1
//! to more than 10 s. Mass-proportional damping `α = 2` /s
//! ([`EllipseBox::mass_damping`]) takes a rocking amplitude down by `e`
//! each second; it vanishes at rest, so the static state it leads to is a
//! static state of the undamped packing.
//!
//! At rest the walls carry the weight: the sum of their vertical forces on
//! the ellipses over the total weight is 1, to the precision of the rest.

use dismech::error::{require_positive, DismechError, Result};
use dismech::implicit::{
    Body, BodyMaterial, Halvings, ImplicitDynamics, ImplicitSettings, PlaneState, Predictor,
};
use dismech::integrate::Newmark;
use dismech::kinematics::Rigid2;
use dismech::law::{FrictionIntegration, PenaltyCoulomb};
use dismech::linsolve::SparseLu;
use dismech::math::{Point, Vec2};
use dismech::shape::Segment;

/// The box of ellipses and how it is settled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EllipseBox {
    /// Number of ellipses.
    pub count: usize,
    /// Columns of the initial stack.
    pub columns: usize,
    /// Smallest and largest semi-major axis (m); `b = a / aspect`.
    pub semi_major: (f64, f64),
    /// Aspect ratio a/b.
    pub aspect: f64,
    /// Vertical gap between stacked ellipses at the start (m).
    pub gap: f64,
    /// Density (kg/m³).
    pub density: f64,
    /// Contact penalty (N/m per m), normal and shear.
    pub penalty: f64,
    /// Friction coefficient of every contact.
    pub friction: f64,
    /// Time step over the explicit limit `2 √(m_min/k)`.
    pub step_ratio: f64,
    /// Newmark's β and γ.
    pub newmark: (f64, f64),
    /// At rest when no boundary point moves faster than this (m/s).
    pub rest_speed: f64,
    /// Give up after this time (s).
    pub max_time: f64,
    /// Gravity (m/s²).
    pub gravity: f64,
    /// Search distance of the implicit driver (m): pairs nearer than this
    /// are contacts of a step.
    pub search_distance: f64,
    /// Largest search distance a step may use when the bodies move fast
    /// (m; [`ImplicitSettings::max_search_distance`]).
    pub max_search_distance: f64,
    /// Mass-proportional damping (1/s; [`ImplicitSettings::mass_damping`]).
    pub mass_damping: f64,
    /// Most open–close and most Newton iterations of a step (each).
    pub max_iterations: usize,
}

impl Default for EllipseBox {
    /// 64 ellipses, a ∈ [0.06, 0.09] m, a/b = 2, in 8 columns; ρ = 2650
    /// kg/m³, penalty 1e8 N/m per m, μ = 0.5; Δt = 20 explicit limits;
    /// Newmark β = 0.5625, γ = 1; mass damping 2 /s; at rest below 1e-4
    /// m/s; search distance 30 mm (the smallest semi-minor axis), up to
    /// 120 mm (the smallest ellipse's length) for a fast step; at most 40
    /// open–close and 40 Newton iterations a step.
    fn default() -> Self {
        Self {
            count: 64,
            columns: 8,
            semi_major: (0.06, 0.09),
            aspect: 2.0,
            gap: 0.005,
            density: 2650.0,
            penalty: 1e8,
            friction: 0.5,
            step_ratio: 20.0,
            newmark: (0.5625, 1.0),
            rest_speed: 1e-4,
            max_time: 10.0,
            gravity: 9.81,
            search_distance: 0.03,
            max_search_distance: 0.12,
            mass_damping: 2.0,
            max_iterations: 40,
        }
    }
}

/// One ellipse of the initial stack: centre, semi-axes, angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlacedEllipse2 {
    /// Centre (m).
    pub centre: Point,
    /// Semi-major axis (m).
    pub a: f64,
    /// Semi-minor axis (m).
    pub b: f64,
    /// Angle of the major axis (rad).
    pub angle: f64,
}

/// The fractional parts of `k φ` (golden ratio) and `k ψ` (plastic number):
/// two independent low-discrepancy sequences.
fn spread(k: usize) -> (f64, f64) {
    let golden = 0.618_033_988_749_894_9;
    let plastic = 0.754_877_666_246_692_8;
    ((k as f64 * golden).fract(), (k as f64 * plastic).fract())
}

impl EllipseBox {
    fn validate(&self) -> Result<()> {
        for (name, value) in [
            ("smallest semi-major axis", self.semi_major.0),
            ("aspect ratio", self.aspect),
            ("density", self.density),
            ("penalty", self.penalty),
            ("step ratio", self.step_ratio),
            ("rest speed", self.rest_speed),
            ("maximum time", self.max_time),
            ("gravity", self.gravity),
            ("search distance", self.search_distance),
        ] {
            require_positive(name, value)?;
        }
        if self.semi_major.1 < self.semi_major.0 || self.count == 0 || self.columns == 0 {
            return Err(DismechError::InvalidParameter {
                name: "ellipse box",
                value: self.count as f64,
                requirement: "needs ellipses, columns, and a_max >= a_min",
            });
        }
        Ok(())
    }

    /// Width of the box (m): one largest ellipse per column and a gap.
    pub fn width(&self) -> f64 {
        self.columns as f64 * (2.0 * self.semi_major.1 + self.gap)
    }

    /// The ellipses of the initial stack: column by column, each resting a
    /// gap above the one below (their vertical half-extents from their
    /// semi-axes and angle).
    pub fn ellipses(&self) -> Vec<PlacedEllipse2> {
        let pitch = 2.0 * self.semi_major.1 + self.gap;
        let mut top = vec![0.0; self.columns];
        (0..self.count)
            .map(|k| {
                let (size, turn) = spread(k + 1);
                let a = self.semi_major.0 + (self.semi_major.1 - self.semi_major.0) * size;
                let b = a / self.aspect;
                let angle = std::f64::consts::PI * turn;
                let half = ((a * angle.sin()).powi(2) + (b * angle.cos()).powi(2)).sqrt();
                let column = k % self.columns;
                let y = top[column] + self.gap + half;
                top[column] = y + half;
                PlacedEllipse2 {
                    centre: Point::new(pitch * (column as f64 + 0.5), y),
                    a,
                    b,
                    angle,
                }
            })
            .collect()
    }

    /// The explicit limit `2 √(m/k)` of the lightest ellipse on one
    /// penalty spring (s).
    pub fn explicit_limit(&self) -> f64 {
        let lightest = self
            .ellipses()
            .iter()
            .map(|e| self.density * std::f64::consts::PI * e.a * e.b)
            .fold(f64::INFINITY, f64::min);
        2.0 * (lightest / self.penalty).sqrt()
    }

    /// The time step (s).
    pub fn time_step(&self) -> f64 {
        self.step_ratio * self.explicit_limit()
    }

    /// The walls: floor, left, right (material on the inner side), each
    /// reaching a little beyond the box.
    pub fn walls(&self) -> [Segment; 3] {
        let (w, h) = (self.width(), 4.0 * self.width());
        let e = 0.1 * w;
        [
            Segment::new(Point::new(-e, 0.0), Point::new(w + e, 0.0)),
            Segment::new(Point::new(0.0, h), Point::new(0.0, -e)),
            Segment::new(Point::new(w, -e), Point::new(w, h)),
        ]
    }
}

/// The packing at the end of the run.
#[derive(Debug, Clone, PartialEq)]
pub struct SettledBox {
    /// The set-up.
    pub setup: EllipseBox,
    /// Time step requested (s).
    pub dt: f64,
    /// The explicit limit it is compared with (s).
    pub dt_explicit: f64,
    /// Steps of `dt` taken.
    pub steps: usize,
    /// Sub-steps taken (a step reduced in size takes several).
    pub substeps: usize,
    /// Times a step was halved.
    pub reductions: usize,
    /// Why, by kind of failure.
    pub halvings: Halvings,
    /// Steps of `dt` taken whole (one sub-step, no halving).
    pub whole_steps: usize,
    /// Time at the end of the last step that was not taken whole (s; 0
    /// when every step was).
    pub last_halved_at: f64,
    /// Sub-steps repeated at the same size with the contacts detected at a
    /// larger search distance.
    pub redetections: usize,
    /// Newton and open–close iterations (linear solves), failed sub-steps
    /// included.
    pub iterations: usize,
    /// Simulated time (s).
    pub time: f64,
    /// Whether the rest criterion was met.
    pub at_rest: bool,
    /// Largest speed of a boundary point at the end (m/s).
    pub max_speed: f64,
    /// Largest angular speed of an ellipse at the end of any step (rad/s).
    pub peak_spin: f64,
    /// Total weight of the ellipses (N/m).
    pub weight: f64,
    /// Vertical force of the walls on the ellipses (N/m).
    pub vertical_reaction: f64,
    /// The ellipses at the end: centre, axes matrix columns.
    pub ellipses: Vec<(Point, Vec2, Vec2)>,
    /// Contact forces at the end: point, force on one of the two bodies.
    pub contacts: Vec<(Point, Vec2)>,
}

impl SettledBox {
    /// Σ vertical wall reactions / total weight.
    pub fn reaction_ratio(&self) -> f64 {
        self.vertical_reaction / self.weight
    }

    /// Time step over the explicit limit.
    pub fn step_ratio(&self) -> f64 {
        self.dt / self.dt_explicit
    }

    /// The mean accepted sub-step over the explicit limit: the simulated
    /// time over the sub-steps that made it.
    pub fn accepted_step_ratio(&self) -> f64 {
        self.time / self.substeps.max(1) as f64 / self.dt_explicit
    }

    /// Steps from the last one not taken whole to the end, each taken
    /// whole.
    pub fn final_whole_steps(&self) -> usize {
        ((self.time - self.last_halved_at) / self.dt).round() as usize
    }

    /// Mean iterations (linear solves) per step of `dt`.
    pub fn iterations_per_step(&self) -> f64 {
        self.iterations as f64 / self.steps.max(1) as f64
    }
}

/// The implicit model of the box.
type BoxModel = ImplicitDynamics<3, Rigid2, PenaltyCoulomb, Newmark, SparseLu>;

fn build(setup: &EllipseBox) -> Result<BoxModel> {
    setup.validate()?;
    let material = BodyMaterial {
        density: setup.density,
        youngs_modulus: 1.0,
        poisson_ratio: 0.0,
        plane: PlaneState::Stress,
    };
    let mut bodies = Vec::with_capacity(setup.count + 3);
    for (i, e) in setup.ellipses().iter().enumerate() {
        bodies.push(Body::ellipse(e.centre, e.a, e.b, e.angle, material, i)?);
    }
    for (k, wall) in setup.walls().into_iter().enumerate() {
        bodies.push(Body::wall(wall, setup.count + k)?);
    }
    let law = PenaltyCoulomb::new(
        setup.penalty,
        setup.friction,
        FrictionIntegration::ReturnMapping,
    )?;
    let settings = ImplicitSettings {
        gravity: Vec2::new(0.0, -setup.gravity),
        search_distance: setup.search_distance,
        max_search_distance: Some(setup.max_search_distance),
        mass_damping: setup.mass_damping,
        predictor: Predictor::StartOfStep,
        max_open_close: setup.max_iterations,
        max_newton: setup.max_iterations,
        ..ImplicitSettings::default()
    };
    let (beta, gamma) = setup.newmark;
    ImplicitDynamics::compose(
        bodies,
        Rigid2,
        law,
        Newmark::new(beta, gamma)?,
        SparseLu::default(),
        settings,
    )
}

/// A bound on the largest speed of a boundary point: `|v| + |ω| D` over
/// the ellipses, with `D` the diagonal of the ellipse's bounding box (more
/// than any distance of a boundary point from the centre).
fn max_speed(model: &BoxModel, count: usize) -> f64 {
    model.bodies()[..count]
        .iter()
        .map(|b| {
            let reach = b.geometry().aabb();
            let size = (reach.max - reach.min).norm();
            b.velocity.fixed_rows::<2>(0).norm() + b.velocity[2].abs() * size
        })
        .fold(0.0, f64::max)
}

/// Settle `setup` until at rest (or `max_time`).
///
/// # Errors
/// Invalid set-up values, and
/// [`ImplicitError::StepFailed`](dismech::implicit::ImplicitError::StepFailed)
/// when a step fails at its smallest size.
pub fn settle(setup: &EllipseBox) -> Result<SettledBox> {
    let mut model = build(setup)?;
    let (dt, dt_explicit) = (setup.time_step(), setup.explicit_limit());
    let n = setup.count;
    let weight: f64 = model.bodies()[..n]
        .iter()
        .map(|b| b.area() * b.material().density * setup.gravity)
        .sum();
    let (mut steps, mut substeps, mut reductions, mut iterations) = (0, 0, 0, 0);
    let mut redetections = 0;
    let (mut whole_steps, mut last_halved_at) = (0, 0.0);
    let mut halvings = Halvings::default();
    let mut peak_spin = 0.0f64;
    let mut at_rest = false;
    while model.time() < setup.max_time {
        let report = model.advance(dt)?;
        steps += 1;
        substeps += report.substeps;
        reductions += report.reductions;
        halvings.add(&report.halvings);
        redetections += report.redetections;
        // Whole: one sub-step of the requested size (a step after a
        // halving may take several sub-steps without halving again).
        if report.reductions == 0 && report.substeps == 1 {
            whole_steps += 1;
        } else {
            last_halved_at = model.time();
        }
        peak_spin = model.bodies()[..n]
            .iter()
            .fold(peak_spin, |m, b| m.max(b.velocity[2].abs()));
        iterations += report.iterations;
        if max_speed(&model, n) <= setup.rest_speed {
            at_rest = true;
            break;
        }
    }
    let vertical_reaction = -(n..n + setup.walls().len())
        .map(|w| model.contact_force_on(w).y)
        .sum::<f64>();
    let ellipses = model.bodies()[..n]
        .iter()
        .filter_map(|b| match b.geometry() {
            dismech::implicit::BodyGeometry::Ellipse(e) => {
                let a = e.axes();
                Some((
                    e.centre(),
                    a.column(0).into_owned(),
                    a.column(1).into_owned(),
                ))
            }
            _ => None,
        })
        .collect();
    let contacts = model
        .contacts()
        .iter()
        .filter(|c| c.force.0 > 0.0)
        .map(|c| (c.point, c.force_on_a))
        .collect();
    Ok(SettledBox {
        setup: *setup,
        dt,
        dt_explicit,
        steps,
        substeps,
        reductions,
        halvings,
        whole_steps,
        last_halved_at,
        redetections,
        iterations,
        time: model.time(),
        at_rest,
        max_speed: max_speed(&model, n),
        peak_spin,
        weight,
        vertical_reaction,
        ellipses,
        contacts,
    })
}
