//! A rigid rectangle on an incline in the explicit DEM: the polygon DEM
//! against the exact motion of a block with Coulomb friction.
//!
//! The incline is a frame of one wall (material on its upper side), the
//! block a [`Polygon`](dismech::shape::Polygon) rectangle laid on it at rest,
//! touching at its two bottom corners (a face on a face: two contact points
//! that keep their features while it slides). The law is the
//! spring–dashpot–Coulomb law with a constant normal stiffness per point
//! and critical dashpots. A rigid block on a slope of angle β with friction
//! μ = tan φ slides with `a = g (sin β − cos β tan φ)` when `β > φ` and stays
//! at rest otherwise; the DEM should reproduce both up to the elastic
//! compliance of its contacts.

use dismech::dem::DemSimulation;
use dismech::error::{require_positive, Result};
use dismech::explicit::DemSettings;
use dismech::integrate::ExplicitEuler;
use dismech::law::{Damping, NormalStiffness, SpringDashpotCoulomb};
use dismech::math::{perp, Point, Vec2};
pub use dismech::reference::incline::sliding_acceleration;
use dismech::scene::{Frame, Scene};
use dismech::shape::Segment;

/// The set-up of a block on an incline; [`Default`] is a 0.2 m × 0.1 m
/// granite block on a 40° slope with μ = tan 30°.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockOnIncline {
    /// Slope angle β (rad).
    pub slope: f64,
    /// Friction coefficient μ = tan φ between block and incline.
    pub friction: f64,
    /// Block length along the slope (m).
    pub width: f64,
    /// Block height (m).
    pub height: f64,
    /// Density (kg/m³).
    pub density: f64,
    /// Normal stiffness per contact point (N/m per m of thickness).
    pub normal_stiffness: f64,
    /// `k_s / k_n`.
    pub stiffness_ratio: f64,
    /// Magnitude of gravity (m/s²).
    pub gravity: f64,
    /// Time step (s).
    pub dt: f64,
    /// Simulated time (s).
    pub duration: f64,
    /// The acceleration is measured from this time on (s), once the block
    /// has settled onto its contacts.
    pub settling_time: f64,
}

impl Default for BlockOnIncline {
    fn default() -> Self {
        Self {
            slope: 40f64.to_radians(),
            friction: 30f64.to_radians().tan(),
            width: 0.2,
            height: 0.1,
            density: 2690.0,
            normal_stiffness: 1e8,
            stiffness_ratio: 0.25,
            gravity: 9.81,
            dt: 2e-5,
            duration: 1.0,
            settling_time: 0.1,
        }
    }
}

/// What a run of [`BlockOnIncline`] measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InclineRun {
    /// Displacement of the centroid along the slope, downhill positive,
    /// from the start to the end of the run (m).
    pub displacement: f64,
    /// Mean acceleration along the slope from the settling time to the end
    /// (m/s²).
    pub acceleration: f64,
    /// The rigid block's acceleration, [`sliding_acceleration`] (m/s²).
    pub exact_acceleration: f64,
    /// Rotation of the block at the end (rad).
    pub rotation: f64,
}

/// Run the block on the incline.
///
/// # Errors
/// [`DismechError::InvalidParameter`](dismech::error::DismechError::InvalidParameter) for a slope outside (0, 90°), a
/// duration not above the settling time, or any value the scene, the law or
/// the DEM refuses; the DEM's own errors if the run fails.
pub fn run_block_on_incline(setup: &BlockOnIncline) -> Result<InclineRun> {
    let beta = setup.slope;
    super::require_incline_run(beta, setup.settling_time, setup.duration)?;
    // A wall 15 block lengths long, descending to the right; the block
    // starts 3 lengths below its top.
    let length = 15.0 * require_positive("block width", setup.width)?;
    let downhill = Vec2::new(beta.cos(), -beta.sin());
    let top = Point::new(0.0, length * beta.sin());
    let frame = Frame::from_walls(vec![(
        "incline".into(),
        Segment::new(top, top + downhill * length),
    )])?;
    let mut scene = Scene::new(frame, Vec2::new(0.0, -setup.gravity))?;
    let centre = top + downhill * (3.0 * setup.width) + perp(&downhill) * (0.5 * setup.height);
    scene.add_rectangle(centre, setup.width, setup.height, -beta, setup.density)?;
    let law = SpringDashpotCoulomb::new(
        NormalStiffness::Constant(setup.normal_stiffness),
        setup.stiffness_ratio,
        setup.friction,
        Damping::Critical,
    )?;
    let settings = DemSettings {
        dt: setup.dt,
        ..DemSettings::default()
    };
    let mut sim = DemSimulation::new(scene, law, ExplicitEuler, settings)?;
    let steps = (setup.duration / setup.dt).round() as u64;
    let settle_steps = (setup.settling_time / setup.dt).round() as u64;
    let mut settled_velocity = 0.0;
    for step in 1..=steps {
        sim.step()?;
        if step == settle_steps {
            settled_velocity = sim.scene().particles[0].velocity.dot(&downhill);
        }
    }
    let block = &sim.scene().particles[0];
    let elapsed = (steps - settle_steps) as f64 * setup.dt;
    Ok(InclineRun {
        displacement: (block.pose.position - centre).dot(&downhill),
        acceleration: (block.velocity.dot(&downhill) - settled_velocity) / elapsed,
        exact_acceleration: sliding_acceleration(setup.gravity, beta, setup.friction),
        rotation: block.pose.angle + beta,
    })
}

/// The measured over the exact sliding acceleration of the default block:
/// a 40° slope, μ = tan 30°, 1 s (the check `polygon_dem.incline_slide_ratio`).
///
/// # Errors
/// As [`run_block_on_incline`].
pub fn incline_slide_ratio() -> Result<f64> {
    let run = run_block_on_incline(&BlockOnIncline::default())?;
    Ok(run.acceleration / run.exact_acceleration)
}

/// How far the default block moves on a 20° slope (μ = tan 30°, it should
/// stick) in 1 s, from its placing at rest, as a fraction of its length
/// (the check `polygon_dem.incline_stick_displacement`); what it moves is
/// the elastic settling of its contact springs.
///
/// # Errors
/// As [`run_block_on_incline`].
pub fn incline_stick_displacement() -> Result<f64> {
    let setup = BlockOnIncline {
        slope: 20f64.to_radians(),
        ..BlockOnIncline::default()
    };
    let run = run_block_on_incline(&setup)?;
    Ok(run.displacement.abs() / setup.width)
}
