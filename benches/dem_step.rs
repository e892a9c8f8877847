//! Speed of one explicit DEM step on a settled filling (paper 000's
//! Example 1: 179 circles in a 2.0 m frame), of the broad phase alone, and
//! of the ellipse–ellipse contact from scratch and about the last step's
//! contact point. A run of 100 steps with an observer at every step is
//! timed beside 100 plain steps: what an observer costs.

use criterion::{criterion_group, criterion_main, Criterion};
use dismech::broad_phase::CellGrid;
use dismech::dem::DemSimulation;
use dismech::error::DismechError;
use dismech::explicit::{DemSettings, RestCriterion};
use dismech::integrate::ExplicitEuler;
use dismech::law::SpringDashpotCoulomb;
use dismech::math::{Aabb2, Point, Pose2, Vec2};
use dismech::observe::Event;
use dismech::query::manifold::ellipse::{
    contact_ellipse_ellipse, contact_ellipse_ellipse_near, contact_ellipse_ellipse_oriented,
    OrientedEllipse,
};
use dismech::query::ContactShape;
use dismech::reference::ellipse_contact::touching_distance;
use dismech::scene::CircleRows;
use dismech::shape::Ellipse;
use nalgebra::UnitComplex;

/// Example 1 settled: ρ = 2.69 gf/cm³, E = 750 kgf/cm², ν = 0.3,
/// k_s/k_n = 0.25, μ = 0.577, Δt = 1e-4 s, g = 9.80665 m/s², and the
/// study's rest criterion.
fn settled_example1() -> Result<DemSimulation<SpringDashpotCoulomb, ExplicitEuler>, DismechError> {
    let g = 9.80665;
    let rows = CircleRows {
        count: 179,
        radius: 0.07,
        width: 2.0,
        height: 3.0,
        per_row: 14,
        row_pitch: 0.16,
        clearance: 0.005,
        density: 2.69 * 1e-3 / 1e-6,
    };
    let law = SpringDashpotCoulomb::katsuki(750.0 * g / 1e-4, 0.3, 0.25, 0.577)?;
    let settings = DemSettings {
        dt: 1e-4,
        ..DemSettings::default()
    };
    let mut sim = DemSimulation::new(rows.scene(g)?, law, ExplicitEuler, settings)?;
    let rest = RestCriterion {
        kinetic_to_released_ratio: 1e-6,
        min_time: 0.5,
        max_time: 30.0,
        check_every: 100,
        consecutive_checks: 10,
        unbalanced_force_ratio: 1e-4,
        ..RestCriterion::default()
    };
    sim.run_to_rest(&rest, |_, _| {})?;
    Ok(sim)
}

fn bench_dem(c: &mut Criterion) {
    let mut sim = match settled_example1() {
        Ok(s) => s,
        Err(e) => panic!("settling the benchmark filling failed: {e}"),
    };
    c.bench_function("dem step, 179 settled circles", |b| {
        b.iter(|| sim.step().map_err(|e| e.to_string()))
    });
    // The same step with an observer attached: a closure reading the
    // driver's time at each step, as a progress bar or an output does (a
    // run of 100 steps and its end, per iteration, against 100 plain
    // steps).
    let mut latest = 0.0;
    let mut observer = |sim: &DemSimulation<SpringDashpotCoulomb, ExplicitEuler>,
                        _: &Event<'_>|
     -> dismech::error::Result<()> {
        latest = sim.time();
        Ok(())
    };
    c.bench_function("dem 100 steps, 179 settled circles", |b| {
        b.iter(|| {
            for _ in 0..100 {
                sim.step().map_err(|e| e.to_string())?;
            }
            Ok::<(), String>(())
        })
    });
    c.bench_function(
        "dem 100 steps, 179 settled circles, observed at every step",
        |b| {
            b.iter(|| {
                sim.run_steps_observed(100, &mut observer)
                    .map_err(|e| e.to_string())
            })
        },
    );
    let boxes: Vec<Aabb2> = sim
        .scene()
        .particles
        .iter()
        .map(|p| p.shape.as_shape().aabb(&p.pose))
        .collect();
    let mut grid = CellGrid::new();
    let mut pairs = Vec::new();
    c.bench_function("cell grid pairs, 179 circles", |b| {
        b.iter(|| grid.candidate_pairs(&boxes, 0.0, &mut pairs))
    });
}

/// 1000 pairs of ellipses (a/b = 1.5 and 2, all orientations and
/// directions) overlapping by 0.1–20 % of the smaller b, the range of a
/// DEM, each with its contact point.
fn overlapping_ellipses() -> Vec<(Ellipse, Pose2, Ellipse, Pose2, Point)> {
    let (ei, ej) = match (Ellipse::new(0.75, 0.5), Ellipse::new(0.8, 0.4)) {
        (Ok(i), Ok(j)) => (i, j),
        _ => panic!("the benchmark's ellipses are valid"),
    };
    (0..1000)
        .filter_map(|k| {
            let k = k as f64;
            let (phi_i, phi_j, dir) = (0.37 * k, 1.1 - 0.29 * k, 0.26 * k);
            let overlap = 0.001 + 0.199 * (0.5 + 0.5 * (1.3 * k).sin());
            let pose_i = Pose2::new(0.0, 0.0, phi_i);
            let direction = Vec2::new(dir.cos(), dir.sin());
            let d = touching_distance(&ei, &pose_i, &ej, phi_j, &direction) - overlap * 0.4;
            let pose_j = Pose2::new(d * direction.x, d * direction.y, phi_j);
            let contact = contact_ellipse_ellipse(&ei, &pose_i, &ej, &pose_j)?;
            Some((ei, pose_i, ej, pose_j, contact.point))
        })
        .collect()
}

fn bench_ellipse_contact(c: &mut Criterion) {
    let pairs = overlapping_ellipses();
    c.bench_function("ellipse contact from scratch, 1000 pairs", |b| {
        b.iter(|| {
            pairs
                .iter()
                .filter_map(|(i, pi, j, pj, _)| contact_ellipse_ellipse(i, pi, j, pj))
                .map(|g| g.overlap)
                .sum::<f64>()
        })
    });
    c.bench_function(
        "ellipse contact about the last contact point, 1000 pairs",
        |b| {
            b.iter(|| {
                pairs
                    .iter()
                    .filter_map(|(i, pi, j, pj, near)| {
                        contact_ellipse_ellipse_near(i, pi, j, pj, Some(near))
                    })
                    .map(|g| g.overlap)
                    .sum::<f64>()
            })
        },
    );
    let oriented: Vec<_> = pairs
        .iter()
        .map(|(i, pi, j, pj, near)| {
            (
                *i,
                *pi,
                UnitComplex::new(pi.angle),
                *j,
                *pj,
                UnitComplex::new(pj.angle),
                *near,
            )
        })
        .collect();
    c.bench_function(
        "ellipse contact about the last contact point, kept rotations, without radii, 1000 pairs",
        |b| {
            b.iter(|| {
                oriented
                    .iter()
                    .filter_map(|pair| {
                        let (i, j) = one(pair);
                        contact_ellipse_ellipse_oriented(i, j, Some(&pair.6), ContactShape::Skipped)
                    })
                    .map(|g| g.overlap)
                    .sum::<f64>()
            })
        },
    );
}

/// An ellipse pair with the rotations of its poses and its last contact
/// point.
type Oriented = (
    Ellipse,
    Pose2,
    UnitComplex<f64>,
    Ellipse,
    Pose2,
    UnitComplex<f64>,
    Point,
);

/// The pair's two ellipses, oriented.
fn one((i, pi, ri, j, pj, rj, _): &Oriented) -> (OrientedEllipse<'_>, OrientedEllipse<'_>) {
    (
        OrientedEllipse {
            shape: i,
            pose: pi,
            rotation: ri,
        },
        OrientedEllipse {
            shape: j,
            pose: pj,
            rotation: rj,
        },
    )
}

criterion_group!(benches, bench_dem, bench_ellipse_contact);
criterion_main!(benches);
