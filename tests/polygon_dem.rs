//! Polygons in the explicit DEM: exact rests, refusals, the stable step and a settled pile.

use dismech::dem::DemSimulation;
use dismech::error::DismechError;
use dismech::explicit::ExplicitError;
use dismech::explicit::{
    critical_time_step, ContactTarget, DemSettings, GoverningMode, ModePartner, OscillationMode,
};
use dismech::integrate::ExplicitEuler;
use dismech::law::{Damping, NormalStiffness, SpringDashpotCoulomb};
use dismech::math::{Point, Vec2};
use dismech::query::Feature;
use dismech::scene::{Frame, Scene};
use nalgebra::{Matrix3, Vector3};

use crate::common;

use common::settle;

const G: f64 = 9.81;
const DENSITY: f64 = 2690.0;

fn law(k: f64, damping: Damping) -> SpringDashpotCoulomb {
    SpringDashpotCoulomb::new(NormalStiffness::Constant(k), 0.25, 0.5, damping).unwrap()
}

fn floor_scene() -> Scene {
    Scene::new(Frame::open_box(2.0, 1.0).unwrap(), Vec2::new(0.0, -G)).unwrap()
}

/// The wall named `bottom`'s reaction on the particles, in the last step.
fn floor_reaction<L: dismech::law::ContactLaw<2>>(sim: &DemSimulation<L>) -> Vec2 {
    -sim.wall_load(sim.scene().frame.index_of("bottom").unwrap())
}

#[test]
fn rectangle_resting_on_a_floor_carries_its_weight_on_its_two_corners() {
    let mut scene = floor_scene();
    // Given by its world vertices, 0.2 m × 0.1 m, 1e-4 m above the floor.
    let corners =
        [(0.9, 1e-4), (1.1, 1e-4), (1.1, 0.1001), (0.9, 0.1001)].map(|(x, y)| Point::new(x, y));
    scene.add_polygon(&corners, DENSITY).unwrap();
    let sim = settle(scene, law(1e7, Damping::Critical), 2e-5);
    let weight = sim.scene().total_weight();
    let reaction = floor_reaction(&sim);
    approx::assert_relative_eq!(reaction.y, weight, max_relative = 1e-6);
    assert!(reaction.x.abs() <= 1e-6 * weight, "{reaction}");
    let on_floor: Vec<_> = sim
        .contacts()
        .iter()
        .filter(|c| matches!(c.target, ContactTarget::Wall(_)))
        .collect();
    assert_eq!(on_floor.len(), 2);
    for c in &on_floor {
        approx::assert_relative_eq!(c.force_on_target.y, -0.5 * weight, max_relative = 1e-6);
    }
    // Rest overlap of two springs in parallel: m g / (2 k).
    let p = &sim.scene().particles[0];
    approx::assert_relative_eq!(0.05 - p.pose.position.y, weight / 2e7, max_relative = 1e-6);
    assert!(p.pose.angle.abs() < 1e-9);
}

#[test]
fn aligned_stacked_squares_rest_on_one_point_per_corner() {
    let mut scene = floor_scene();
    let side = 0.1;
    scene
        .add_rectangle(Point::new(1.0, 0.5 * side), side, side, 0.0, DENSITY)
        .unwrap();
    scene
        .add_rectangle(Point::new(1.0, 1.5 * side + 1e-5), side, side, 0.0, DENSITY)
        .unwrap();
    let sim = settle(scene, law(1e7, Damping::Critical), 2e-5);
    let weight = sim.scene().total_weight();
    approx::assert_relative_eq!(floor_reaction(&sim).y, weight, max_relative = 1e-6);
    let interface: Vec<_> = sim
        .contacts()
        .iter()
        .filter(|c| c.target == ContactTarget::Particle(1))
        .collect();
    assert_eq!(interface.len(), 2, "{interface:?}");
    let carried: f64 = interface.iter().map(|c| c.force_on_target.y).sum();
    approx::assert_relative_eq!(carried, 0.5 * weight, max_relative = 1e-6);
    for c in interface {
        assert!(matches!(
            (c.features.a, c.features.b),
            (Feature::Vertex(_), Feature::Vertex(_))
        ));
    }
}

#[test]
fn disc_and_ellipse_resting_on_a_rectangle_load_the_floor_with_both_weights() {
    for smooth in 0..2 {
        let mut scene = floor_scene();
        scene
            .add_rectangle(Point::new(1.0, 0.05), 0.3, 0.1, 0.0, DENSITY)
            .unwrap();
        if smooth == 0 {
            scene
                .add_circle(Point::new(1.0, 0.1 + 0.05 + 1e-5), 0.05, DENSITY)
                .unwrap();
        } else {
            scene
                .add_ellipse(Point::new(1.0, 0.1 + 0.03 + 1e-5), 0.06, 0.03, 0.0, DENSITY)
                .unwrap();
        }
        let sim = settle(scene, law(1e7, Damping::Critical), 1e-5);
        let weight = sim.scene().total_weight();
        approx::assert_relative_eq!(floor_reaction(&sim).y, weight, max_relative = 1e-6);
        // The block (particle 0) carries the top body (particle 1).
        let carried: f64 = sim
            .contacts()
            .iter()
            .filter(|c| c.target == ContactTarget::Particle(1))
            .map(|c| c.force_on_target.y)
            .sum();
        let top = &sim.scene().particles[1];
        approx::assert_relative_eq!(carried, top.mass * G, max_relative = 1e-6);
    }
}

#[test]
fn eq19_stiffness_is_refused_for_polygons() {
    let mut scene = floor_scene();
    scene
        .add_rectangle(Point::new(1.0, 0.06), 0.2, 0.1, 0.0, DENSITY)
        .unwrap();
    let eq19 = SpringDashpotCoulomb::katsuki(5e9, 0.3, 0.25, 0.5).unwrap();
    let err = DemSimulation::new(scene, eq19, ExplicitEuler, DemSettings::default()).unwrap_err();
    assert!(
        matches!(
            err,
            DismechError::Explicit(ExplicitError::LawUndefinedForShape {
                body: 0,
                shape: "polygon",
                ..
            })
        ),
        "{err}"
    );
    assert_eq!(
        critical_time_step(
            &{
                let mut s = floor_scene();
                s.add_rectangle(Point::new(1.0, 0.06), 0.2, 0.1, 0.0, DENSITY)
                    .unwrap();
                s
            },
            &eq19
        )
        .dt,
        0.0
    );
}

/// The stable step of an undamped rectangle resting on its face: `2/ω`
/// with `ω²` the largest eigenvalue of `M⁻¹ K` for its two corner springs.
fn face_on_floor_limit(w: f64, h: f64, k: f64, ks: f64) -> f64 {
    let m = DENSITY * w * h;
    let inertia = m * (w * w + h * h) / 12.0;
    let mut stiffness = Matrix3::zeros();
    for x in [-0.5 * w, 0.5 * w] {
        let (r, normal, tangent) = (Vec2::new(x, -0.5 * h), Vec2::y(), Vec2::x());
        let g_n = Vector3::new(normal.x, normal.y, r.x * normal.y - r.y * normal.x);
        let g_t = Vector3::new(tangent.x, tangent.y, r.x * tangent.y - r.y * tangent.x);
        stiffness += g_n * g_n.transpose() * k + g_t * g_t.transpose() * ks;
    }
    let scale = Matrix3::from_diagonal(&Vector3::new(m, m, inertia).map(|v| 1.0 / v.sqrt()));
    let omega2 = (scale * stiffness * scale)
        .symmetric_eigen()
        .eigenvalues
        .max();
    2.0 / omega2.sqrt()
}

#[test]
fn polygon_stable_step_is_a_safe_bound_for_a_face_on_a_wall() {
    let (w, h, k) = (0.2, 0.1, 1e7);
    let mut scene = floor_scene();
    scene
        .add_rectangle(Point::new(1.0, 0.05 + 1e-4), w, h, 0.0, DENSITY)
        .unwrap();
    let elastic = law(k, Damping::None);
    let estimate = critical_time_step(&scene, &elastic).dt;
    let exact = face_on_floor_limit(w, h, k, 0.25 * k);
    eprintln!("stable step: estimate {estimate:.4e} s, exact face-on-wall {exact:.4e} s");
    assert!(estimate <= exact && estimate >= 0.5 * exact);
    // At the estimated limit (dashpots included) a dropped block settles
    // without blowing up.
    let damped = law(k, Damping::Critical);
    let dt = critical_time_step(&scene, &damped).dt;
    let sim = settle(scene, damped, dt);
    approx::assert_relative_eq!(
        floor_reaction(&sim).y,
        sim.scene().total_weight(),
        max_relative = 1e-6
    );
}

/// A time step above a polygon's stable limit is refused before the run,
/// naming the face mode that governs: the normal mode of a face on a face
/// of an identical polygon (half the wall's mass, and the normal spring is
/// the stiffer one).
#[test]
fn a_time_step_above_a_polygon_face_limit_names_the_face_mode() {
    let mut scene = floor_scene();
    scene
        .add_rectangle(Point::new(1.0, 0.05 + 1e-4), 0.2, 0.1, 0.0, DENSITY)
        .unwrap();
    let damped = law(1e7, Damping::Critical);
    let limit = critical_time_step(&scene, &damped);
    let settings = DemSettings {
        dt: 2.0 * limit.dt,
        ..DemSettings::default()
    };
    let err = DemSimulation::new(scene, damped, ExplicitEuler, settings).unwrap_err();
    match err {
        DismechError::Explicit(ExplicitError::UnstableTimeStep {
            dt,
            limit: l,
            governing,
            overlap: None,
        }) => {
            assert_eq!(dt, 2.0 * limit.dt);
            assert_eq!(l, limit.dt);
            assert_eq!(governing, limit.governing);
            match governing {
                GoverningMode::PolygonFace {
                    polygon: 0,
                    mode: OscillationMode::NormalRotation,
                    partner: ModePartner::Identical,
                    stiffness_per_point,
                    mass,
                } => {
                    assert_eq!(stiffness_per_point, 1e7);
                    assert!(mass > 0.0 && mass.is_finite(), "{mass}");
                }
                other => panic!("{other:?}"),
            }
        }
        ref other => panic!("{other:?}"),
    }
    let message = err.to_string();
    assert!(
        message.contains(
            "normal-rotation mode of a face of polygon 0 (two points) against an identical polygon"
        ),
        "{message}"
    );
}

/// A pile of 34 random simple polygons (3–8 vertices, often concave) and 8
/// discs dropped into a box settles with the walls carrying the weight, and
/// its overlaps stay small (the range the manifold rules assume).
#[test]
fn pile_of_random_polygons_and_discs_settles_with_the_walls_carrying_its_weight() {
    let mut seed = 777u64;
    let mut uniform = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut scene = Scene::new(Frame::open_box(1.0, 2.0).unwrap(), Vec2::new(0.0, -G)).unwrap();
    let size = 0.05;
    for row in 0..6 {
        for col in 0..7 {
            let c = Point::new(0.1 + col as f64 * 0.13, 0.1 + row as f64 * 0.13);
            if (row + col) % 5 == 0 {
                scene.add_circle(c, 0.8 * size, DENSITY).unwrap();
                continue;
            }
            let n = 3 + (uniform() * 6.0) as usize;
            let vertices: Vec<Point> = (0..n)
                .map(|k| {
                    let t = (k as f64 + 0.6 * (uniform() - 0.5)) * std::f64::consts::TAU / n as f64;
                    let r = size * (0.5 + 0.5 * uniform());
                    c + Vec2::new(r * t.cos(), r * t.sin())
                })
                .collect();
            scene.add_polygon(&vertices, DENSITY).unwrap();
        }
    }
    let law = law(1e7, Damping::Critical);
    let dt = 0.5 * critical_time_step(&scene, &law).dt;
    let mut sim = DemSimulation::new(
        scene,
        law,
        ExplicitEuler,
        DemSettings {
            dt,
            ..DemSettings::default()
        },
    )
    .unwrap();
    let outcome = sim
        .run_to_rest(&dismech::explicit::RestCriterion::default(), |_, _| {})
        .unwrap();
    assert_eq!(outcome.status, dismech::explicit::RunStatus::AtRest);
    let weight = sim.scene().total_weight();
    let walls: Vec2 = (0..3).map(|w| sim.wall_load(w)).sum();
    approx::assert_relative_eq!(-walls.y, weight, max_relative = 1e-3);
    // The deepest overlap at rest, from the contact forces: f_n / k_n.
    let deepest = sim
        .contacts()
        .iter()
        .map(|c| c.force_on_target.dot(&c.normal) / 1e7)
        .fold(0.0, f64::max);
    assert!(deepest < 0.01 * size, "deepest overlap {deepest}");
}

/// Two rectangles crossed as a plus sign (no corner of either inside the
/// other) are refused at the start of a DEM run, like any overlap.
#[test]
fn crossing_rectangles_are_refused_at_the_start() {
    let mut scene = floor_scene();
    scene
        .add_rectangle(Point::new(1.0, 1.0), 0.6, 0.1, 0.0, DENSITY)
        .unwrap();
    scene
        .add_rectangle(Point::new(1.0, 1.0), 0.1, 0.6, 0.0, DENSITY)
        .unwrap();
    let settings = DemSettings {
        dt: 1e-5,
        ..DemSettings::default()
    };
    match DemSimulation::new(scene, law(1e7, Damping::Critical), ExplicitEuler, settings) {
        Err(DismechError::Explicit(ExplicitError::InitialOverlap {
            a: 0,
            b: 1,
            overlap,
            ..
        })) => {
            assert!((overlap - 0.1).abs() < 1e-12, "overlap {overlap}")
        }
        other => panic!("expected an overlap, got {other:?}"),
    }
}
