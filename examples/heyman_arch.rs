//! Heyman's arch: the least thickness of a semicircular masonry arch that
//! stands under its own weight, found by the rigid-plastic limit analysis
//! of polygon voussoirs with self-weight only.
//!
//! Each voussoir is a quadrilateral cut by radial joints from a ring of
//! centre-line radius `R` and thickness `t`; the contacts are whatever the
//! pair query finds between touching outlines
//! ([`LimitModel::add_contacts`]): the two ends of every joint, and the
//! two ends of each springing on the ground. Joints are unilateral and
//! frictional without cohesion (no tension, ample friction), so the
//! analysis of the dead loads' multiplier
//! ([`LimitModel::multiply_dead_loads`]) says either `Locked` (no mechanism
//! on which the weight does work: the arch stands) or `ZeroLoad` (it falls
//! under any weight). Bisection on `t` gives the least thickness, a
//! geometric factor of safety `t / t_min` for a given arch.
//!
//! Heyman (1969) found `t/R ≈ 0.106` with an approximate weight
//! distribution; the exact value for a continuous semicircular arch is
//! `t/R = 0.1075` (Ochsendorf 2002), with hinges at the crown, at about
//! 54.5° from the crown at the intrados, and at the springings.
//!
//! `cargo run --release --example heyman_arch -- [voussoirs]` (default 180).

use dismech::law::RigidPlastic;
use dismech::limit::{analyse, analyse_static, LimitModel, LimitStatus, Partner};
use dismech::lp::LinearProgramSolver;
use dismech::math::{Point, Pose2, Vec2};
use dismech::shape::{Polygon, Shape};

/// The arch of `voussoirs` blocks of centre-line radius 1 and thickness `t`,
/// standing on the ground line y = 0, each loaded by its weight (unit
/// weight per area).
fn arch(voussoirs: usize, t: f64) -> dismech::error::Result<LimitModel> {
    let mut model = LimitModel::new(1e-9)?;
    let ground = model.add_support("ground", Point::origin(), Vec2::y(), Vec2::zeros())?;
    let (inner, outer) = (1.0 - 0.5 * t, 1.0 + 0.5 * t);
    let at = |r: f64, k: usize| {
        let angle = std::f64::consts::PI * k as f64 / voussoirs as f64;
        Point::new(r * angle.cos(), r * angle.sin())
    };
    for k in 0..voussoirs {
        let corners = [
            at(outer, k),
            at(outer, k + 1),
            at(inner, k + 1),
            at(inner, k),
        ];
        let (polygon, centroid) = Polygon::from_world(&corners, k)?;
        let area = polygon.measure();
        let body = model.add_shape(
            polygon.into(),
            Pose2::new(centroid.x, centroid.y, 0.0),
            true,
        )?;
        model.set_load(body, Vec2::new(0.0, -area))?;
    }
    // No tension, no cohesion, ample friction (φ = 40°).
    let joint = RigidPlastic::from_friction_angle_deg(0.0, 40.0, true)?;
    for k in 0..voussoirs - 1 {
        model.add_contacts(k, Partner::Body(k + 1), joint)?;
    }
    model.add_contacts(0, Partner::Support(ground), joint)?;
    model.add_contacts(voussoirs - 1, Partner::Support(ground), joint)?;
    model.multiply_dead_loads();
    Ok(model)
}

/// Whether the arch of thickness `t` stands: `Some(true)` when both the
/// kinematic and the static analyses find it locked, `Some(false)` when both
/// find that it falls under any weight, `None` when they disagree (within
/// the LPs' resolution of the critical thickness).
pub fn stands(voussoirs: usize, t: f64) -> dismech::error::Result<Option<bool>> {
    let model = arch(voussoirs, t)?;
    let mut solver = LinearProgramSolver::default();
    let kinematic = analyse(&model, &mut solver)?.status;
    let statical = analyse_static(&model, &mut solver)?.status;
    let verdict = |s: LimitStatus| match s {
        LimitStatus::Locked => Some(true),
        LimitStatus::ZeroLoad => Some(false),
        _ => None,
    };
    Ok(match (verdict(kinematic), verdict(statical)) {
        (Some(a), Some(b)) if a == b => Some(a),
        _ => None,
    })
}

/// The least thickness over the centre-line radius, bracketed by bisection
/// from `[0.05, 0.2]` to `1e-6`, or as far as both analyses agree.
pub fn least_thickness(voussoirs: usize) -> dismech::error::Result<(f64, f64)> {
    let (mut thin, mut thick) = (0.05, 0.2);
    while thick - thin > 1e-6 {
        let mid = 0.5 * (thin + thick);
        match stands(voussoirs, mid)? {
            Some(true) => thick = mid,
            Some(false) => thin = mid,
            None => break,
        }
    }
    Ok((thin, thick))
}

/// The relative rotation rates at the joints (ground, joint 1, …, ground)
/// of the mechanism of the arch of thickness `t`, which must fall.
pub fn hinges(voussoirs: usize, t: f64) -> dismech::error::Result<Vec<f64>> {
    let model = arch(voussoirs, t)?;
    let result = analyse(&model, &mut LinearProgramSolver::default())?;
    let spin: Vec<f64> = result.velocities.iter().map(|v| v.1).collect();
    let mut jumps = vec![spin[0]];
    jumps.extend(spin.windows(2).map(|w| w[1] - w[0]));
    jumps.push(-spin[voussoirs - 1]);
    Ok(jumps)
}

/// The hinges of a mechanism as the mean angle from the crown (deg,
/// positive on the side of the first voussoir) of each run of joints
/// that turn, weighted by how fast they turn.
pub fn hinge_zones(jumps: &[f64], voussoirs: usize) -> Vec<f64> {
    let largest = jumps.iter().fold(0.0f64, |m, j| m.max(j.abs()));
    let mut zones = Vec::new();
    let mut run: Option<(f64, f64)> = None;
    for (k, j) in jumps.iter().enumerate() {
        let angle = 90.0 - 180.0 * k as f64 / voussoirs as f64;
        if j.abs() > 1e-3 * largest {
            let (sum, weight) = run.unwrap_or((0.0, 0.0));
            run = Some((sum + angle * j.abs(), weight + j.abs()));
        } else if let Some((sum, weight)) = run.take() {
            zones.push(sum / weight);
        }
    }
    if let Some((sum, weight)) = run {
        zones.push(sum / weight);
    }
    zones
}

fn main() -> dismech::error::Result<()> {
    let voussoirs: usize = std::env::args()
        .nth(1)
        .map_or(180, |s| s.parse().expect("a number of voussoirs"));
    let (thin, thick) = least_thickness(voussoirs)?;
    let t = 0.5 * (thin + thick);
    println!("{voussoirs} voussoirs: least thickness t/R = {t:.5} (bracket {thin:.6}..{thick:.6}; continuous arch: 0.1075)");
    let zones = hinge_zones(&hinges(voussoirs, thin * (1.0 - 1e-4))?, voussoirs);
    print!("hinges of the mechanism just below t_min (angle from the crown, deg):");
    for angle in zones {
        print!(" {angle:.1}");
    }
    println!();
    Ok(())
}
