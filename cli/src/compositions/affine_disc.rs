//! A disc as a DDA body: six affine degrees of freedom ([`Affine2`],
//! paper 003 eq. 16) on a smooth boundary, rolling down a frictional
//! incline in the implicit driver (Newmark β = ½, γ = 1 as in DDA, the
//! penalty Coulomb law with return mapping, sparse LU). Classic DDA has
//! polygons only; here the affine body takes the ellipse's pair queries.
//!
//! A uniform disc on a slope of angle β with `μ ≥ tan β / 3` rolls without
//! slipping with the centre acceleration `(2/3) g sin β`
//! ([`disc_acceleration`]); 30° and μ = 0.5 roll. The acceleration is
//! measured by a least-squares parabola through the centre's travel along
//! the slope after a settling time.
//!
//! What remains is the time step's, first order in `Δt`: Newmark with
//! `γ = 1` is first-order accurate, and the error halves with the step.
//! DDA's first-order rotation `I + [[0, −r₀], [r₀, 0]]` would stretch the
//! body by `1 + r₀²` in area each step; [`Affine2`] moves the geometry with
//! the rotation made exact at the end of each step, so the disc keeps its
//! area but for its elastic strain ([`RollingRun::area_change`] reports
//! it: −1.4e-7 at every step size, over ten revolutions too).

use dismech::error::{require_positive, DismechError, Result};
use dismech::implicit::{Body, BodyMaterial, ImplicitDynamics, ImplicitSettings, PlaneState};
use dismech::integrate::Newmark;
use dismech::kinematics::Affine2;
use dismech::law::{FrictionIntegration, PenaltyCoulomb};
use dismech::linsolve::SparseLu;
use dismech::math::{Point, Vec2};
use dismech::reference::incline::disc_acceleration;
use dismech::shape::Segment;

/// A disc on an incline; [`Default`] is the check's set-up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollingDisc {
    /// Slope angle β (rad).
    pub slope: f64,
    /// Friction coefficient between disc and incline.
    pub friction: f64,
    /// Disc radius (m).
    pub radius: f64,
    /// Density (kg/m³).
    pub density: f64,
    /// Young's modulus of the disc (Pa).
    pub youngs_modulus: f64,
    /// Poisson's ratio of the disc.
    pub poisson_ratio: f64,
    /// Contact penalty (N/m per m).
    pub penalty: f64,
    /// Gravity (m/s²).
    pub gravity: f64,
    /// Time step (s).
    pub dt: f64,
    /// Simulated time (s).
    pub duration: f64,
    /// The parabola is fitted from this time on (s).
    pub settling_time: f64,
}

impl Default for RollingDisc {
    /// A 0.1 m disc (ρ = 2000 kg/m³, E = 10 GPa, ν = 0.2) on a 30° slope,
    /// μ = 0.5, penalty 1e8 N/m per m; Δt = 2.5e-4 s for 0.5 s, fitted
    /// from 0.1 s.
    fn default() -> Self {
        Self {
            slope: 30f64.to_radians(),
            friction: 0.5,
            radius: 0.1,
            density: 2000.0,
            youngs_modulus: 1e10,
            poisson_ratio: 0.2,
            penalty: 1e8,
            gravity: 9.81,
            dt: 2.5e-4,
            duration: 0.5,
            settling_time: 0.1,
        }
    }
}

/// What a run of [`RollingDisc`] measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollingRun {
    /// Centre acceleration along the slope, from the fitted parabola
    /// (m/s²).
    pub acceleration: f64,
    /// The rigid disc's, [`disc_acceleration`] (m/s²).
    pub exact_acceleration: f64,
    /// Area at the end over area at the start, minus one.
    pub area_change: f64,
    /// Turn of the disc over the run (rad): the travel over the radius.
    pub turn: f64,
    /// Mean linear solves per step.
    pub iterations_per_step: f64,
    /// Step reductions over the run.
    pub reductions: usize,
}

impl RollingRun {
    /// Measured over exact acceleration.
    pub fn ratio(&self) -> f64 {
        self.acceleration / self.exact_acceleration
    }
}

/// Least-squares parabola `x = c₀ + c₁ t + c₂ t²` through `(t, x)`:
/// returns `2 c₂`, the acceleration.
fn fitted_acceleration(samples: &[(f64, f64)]) -> Option<f64> {
    let mut normal = dismech::nalgebra::Matrix3::<f64>::zeros();
    let mut rhs = dismech::nalgebra::Vector3::<f64>::zeros();
    for &(t, x) in samples {
        let basis = dismech::nalgebra::Vector3::new(1.0, t, t * t);
        normal += basis * basis.transpose();
        rhs += basis * x;
    }
    normal.lu().solve(&rhs).map(|c| 2.0 * c[2])
}

/// Roll the disc.
///
/// # Errors
/// [`DismechError::InvalidParameter`] for a slope outside (0, 90°), a
/// duration not above the settling time, or any value the bodies, the law
/// or the driver refuses;
/// [`ImplicitError::StepFailed`](dismech::implicit::ImplicitError::StepFailed)
/// when a step fails.
pub fn run_rolling_disc(setup: &RollingDisc) -> Result<RollingRun> {
    let beta = setup.slope;
    super::require_incline_run(beta, setup.settling_time, setup.duration)?;
    for (name, value) in [
        ("radius", setup.radius),
        ("density", setup.density),
        ("gravity", setup.gravity),
        ("time step", setup.dt),
    ] {
        require_positive(name, value)?;
    }
    let (s, c) = beta.sin_cos();
    let downhill = Vec2::new(c, -s);
    let normal = Vec2::new(s, c);
    // The incline through the origin, long enough for the run.
    let reach = 2.0 * setup.gravity * setup.duration.powi(2) + 10.0 * setup.radius;
    let incline = Body::<6>::wall(
        Segment::new(
            Point::origin() - downhill * (5.0 * setup.radius),
            Point::origin() + downhill * reach,
        ),
        1,
    )?;
    let material = BodyMaterial {
        density: setup.density,
        youngs_modulus: setup.youngs_modulus,
        poisson_ratio: setup.poisson_ratio,
        plane: PlaneState::Stress,
    };
    // Placed on its static sink `m g cos β / k`, so that it starts in
    // contact without a drop.
    let mass = setup.density * std::f64::consts::PI * setup.radius.powi(2);
    let sink = mass * setup.gravity * c / setup.penalty;
    let start = Point::origin() + normal * (setup.radius - sink);
    let disc = Body::<6>::circle(start, setup.radius, material, 0)?;
    let law = PenaltyCoulomb::new(
        setup.penalty,
        setup.friction,
        FrictionIntegration::ReturnMapping,
    )?;
    let settings = ImplicitSettings {
        gravity: Vec2::new(0.0, -setup.gravity),
        search_distance: 0.1 * setup.radius,
        overlap_tolerance: 0.01 * setup.radius,
        ..ImplicitSettings::default()
    };
    let mut model = ImplicitDynamics::compose(
        vec![disc, incline],
        Affine2,
        law,
        Newmark::dda(),
        SparseLu::default(),
        settings,
    )?;
    let area = model.bodies()[0].area();
    let steps = (setup.duration / setup.dt).round() as usize;
    let (mut iterations, mut reductions) = (0, 0);
    let mut samples = Vec::with_capacity(steps);
    for _ in 0..steps {
        let report = model.advance(setup.dt)?;
        iterations += report.iterations;
        reductions += report.reductions;
        let travel = (model.bodies()[0].centroid() - start).dot(&downhill);
        if model.time() >= setup.settling_time * (1.0 - 1e-12) {
            samples.push((model.time(), travel));
        }
    }
    if samples.len() < 3 {
        return Err(DismechError::InvalidParameter {
            name: "duration",
            value: setup.duration,
            requirement: "must leave at least three steps after the settling time",
        });
    }
    let acceleration = fitted_acceleration(&samples).ok_or(DismechError::InvalidParameter {
        name: "time step",
        value: setup.dt,
        requirement: "must leave distinct sample times after the settling time",
    })?;
    let travel = (model.bodies()[0].centroid() - start).dot(&downhill);
    Ok(RollingRun {
        acceleration,
        exact_acceleration: disc_acceleration(setup.gravity, beta, setup.friction),
        area_change: model.bodies()[0].area() / area - 1.0,
        turn: travel / setup.radius,
        iterations_per_step: iterations as f64 / steps.max(1) as f64,
        reductions,
    })
}

/// The default disc rolled at `Δt` and at twice and four times `Δt`
/// (the check `affine_disc.rolling_ratio` takes the first): the error
/// falls with the step.
///
/// # Errors
/// As [`run_rolling_disc`].
pub fn rolling_convergence(setup: &RollingDisc) -> Result<[RollingRun; 3]> {
    let at = |factor: f64| {
        run_rolling_disc(&RollingDisc {
            dt: setup.dt * factor,
            ..*setup
        })
    };
    Ok([at(1.0)?, at(2.0)?, at(4.0)?])
}
