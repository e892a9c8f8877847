//! Ellipse contact: geometry properties, robustness against an
//! independent reference, and exact resting states in the DEM.

use dismech::dem::DemSimulation;
use dismech::explicit::{DemSettings, RestCriterion, RunStatus};
use dismech::integrate::ExplicitEuler;
use dismech::law::{Damping, NormalStiffness, SpringDashpotCoulomb};
use dismech::math::{rotate, Point, Pose2, Vec2};
use dismech::query::manifold::circle_circle::contact_circle_circle;
use dismech::query::manifold::ellipse::{
    contact_ellipse_ellipse, contact_ellipse_ellipse_near, contact_ellipse_ellipse_oriented,
    contact_ellipse_segment, OrientedEllipse,
};
use dismech::query::{ContactGeometry, ContactShape};
use dismech::reference::ellipse_contact::{random_pair_statistics, touching_distance};
use dismech::scene::{Frame, Scene};
use dismech::shape::{Circle, Ellipse, Segment, Shape2};
use nalgebra::UnitComplex;
use proptest::prelude::*;

prop_compose! {
    /// Two ellipses (aspect 1–4) overlapping by up to 20 % of the smaller b,
    /// the range a DEM meets.
    fn overlapping_pair()(bi in 0.2f64..1.0, ri in 1.0f64..4.0, bj in 0.2f64..1.0, rj in 1.0f64..4.0,
                          phi_i in 0.0f64..6.3, phi_j in 0.0f64..6.3, dir in 0.0f64..6.3, frac in 0.001f64..0.2)
        -> (Ellipse, Pose2, Ellipse, Pose2) {
        let ei = Ellipse::new(bi * ri, bi).unwrap();
        let ej = Ellipse::new(bj * rj, bj).unwrap();
        let pi = Pose2::new(0.0, 0.0, phi_i);
        let direction = Vec2::new(dir.cos(), dir.sin());
        let d = touching_distance(&ei, &pi, &ej, phi_j, &direction) - frac * bi.min(bj);
        (ei, pi, ej, Pose2::new(d * dir.cos(), d * dir.sin(), phi_j))
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn ellipse_contact_is_symmetric_in_the_order_of_the_pair((ei, pi, ej, pj) in overlapping_pair()) {
        let ab = contact_ellipse_ellipse(&ei, &pi, &ej, &pj);
        let ba = contact_ellipse_ellipse(&ej, &pj, &ei, &pi);
        prop_assert!(ab.is_some() && ba.is_some());
        if let (Some(ab), Some(ba)) = (ab, ba) {
            prop_assert!((ab.point - ba.point).norm() < 1e-9, "{:?} vs {:?}", ab.point, ba.point);
            prop_assert!((ab.normal + ba.normal).norm() < 1e-9);
            prop_assert!((ab.overlap - ba.overlap).abs() < 1e-9);
            prop_assert!((ab.width - ba.width).abs() < 1e-9);
            prop_assert!((ab.curvature_radius_a - ba.curvature_radius_b).abs() < 1e-7 * (1.0 + ab.curvature_radius_a));
        }
    }

    #[test]
    fn ellipse_contact_is_invariant_under_rigid_motion(
        (ei, pi, ej, pj) in overlapping_pair(), turn in 0.0f64..6.3, tx in -10.0f64..10.0, ty in -10.0f64..10.0
    ) {
        let shift = Vec2::new(tx, ty);
        let moved = |p: &Pose2| Pose2 { position: Point::from(rotate(&p.position.coords, turn) + shift), angle: p.angle + turn };
        let a = contact_ellipse_ellipse(&ei, &pi, &ej, &pj);
        let b = contact_ellipse_ellipse(&ei, &moved(&pi), &ej, &moved(&pj));
        prop_assert_eq!(a.is_some(), b.is_some());
        if let (Some(a), Some(b)) = (a, b) {
            let expected = Point::from(rotate(&a.point.coords, turn) + shift);
            prop_assert!((b.point - expected).norm() < 1e-8);
            prop_assert!((b.normal - rotate(&a.normal, turn)).norm() < 1e-8);
            prop_assert!((a.overlap - b.overlap).abs() < 1e-9 && (a.width - b.width).abs() < 1e-8);
        }
    }

    /// Given where the pair touched (the last step's contact point, here
    /// the contact point moved by up to `shift` of the smaller b, or any
    /// point at all), the contact is the same as found from scratch: the
    /// fast search about that point answers only where it shows the
    /// overlap is one lens.
    #[test]
    fn ellipse_contact_near_a_previous_point_is_the_contact(
        (ei, pi, ej, pj) in overlapping_pair(), shift in 0.0f64..0.5, dir in 0.0f64..6.3,
        anywhere in prop::array::uniform2(-10.0f64..10.0)
    ) {
        let plain = contact_ellipse_ellipse(&ei, &pi, &ej, &pj).unwrap();
        let moved = plain.point + Vec2::new(dir.cos(), dir.sin()) * (shift * ei.b().min(ej.b()));
        for near in [plain.point, moved, Point::new(anywhere[0], anywhere[1])] {
            let hinted = contact_ellipse_ellipse_near(&ei, &pi, &ej, &pj, Some(&near)).unwrap();
            prop_assert!((hinted.point - plain.point).norm() < 1e-9, "{:?} vs {:?}", hinted.point, plain.point);
            prop_assert!((hinted.normal - plain.normal).norm() < 1e-9);
            prop_assert!((hinted.overlap - plain.overlap).abs() < 1e-9 * (1.0 + plain.overlap));
            prop_assert!((hinted.width - plain.width).abs() < 1e-9);
            prop_assert!((hinted.curvature_radius_a - plain.curvature_radius_a).abs() < 1e-7 * (1.0 + plain.curvature_radius_a));
            prop_assert!((hinted.curvature_radius_b - plain.curvature_radius_b).abs() < 1e-7 * (1.0 + plain.curvature_radius_b));
            // Given the rotations of the poses' angles, the very same.
            let (ri, rj) = (UnitComplex::new(pi.angle), UnitComplex::new(pj.angle));
            let oriented = |radii| contact_ellipse_ellipse_oriented(
                OrientedEllipse { shape: &ei, pose: &pi, rotation: &ri },
                OrientedEllipse { shape: &ej, pose: &pj, rotation: &rj },
                Some(&near),
                radii,
            );
            prop_assert_eq!(oriented(ContactShape::Computed), Some(hinted));
            // Without the radii of curvature, the rest the very same.
            let without = oriented(ContactShape::Skipped).unwrap();
            prop_assert!(without.curvature_radius_a.is_nan() && without.curvature_radius_b.is_nan());
            prop_assert_eq!(
                ContactGeometry { curvature_radius_a: hinted.curvature_radius_a, curvature_radius_b: hinted.curvature_radius_b, ..without },
                hinted
            );
        }
    }

    /// Left and right are alike: the mirror image (x → −x) of a pair has
    /// the mirror image of its contact. A scene laid out mirror-symmetric
    /// meets the same contacts on both sides, to round-off.
    #[test]
    fn ellipse_contact_of_the_mirror_image_is_the_mirror_image_of_the_contact(
        (ei, pi, ej, pj) in overlapping_pair(), tx in -10.0f64..10.0
    ) {
        let a = contact_ellipse_ellipse(&ei, &pi, &ej, &pj);
        let b = contact_ellipse_ellipse(&ei, &mirrored_pose(&pi, tx), &ej, &mirrored_pose(&pj, tx));
        prop_assert!(a.is_some() && b.is_some());
        if let (Some(a), Some(b)) = (a, b) {
            prop_assert!((b.point - mirrored(&a.point, tx)).norm() < 1e-9, "{:?} vs {:?}", a.point, b.point);
            prop_assert!((b.normal - Vec2::new(-a.normal.x, a.normal.y)).norm() < 1e-9);
            prop_assert!((a.overlap - b.overlap).abs() < 1e-9 * (1.0 + a.overlap));
            prop_assert!((a.width - b.width).abs() < 1e-9);
            prop_assert!((a.curvature_radius_a - b.curvature_radius_a).abs() < 1e-7 * (1.0 + a.curvature_radius_a));
            prop_assert!((a.curvature_radius_b - b.curvature_radius_b).abs() < 1e-7 * (1.0 + a.curvature_radius_b));
            // And so for the search about the last contact point, the
            // path a DEM pair takes, given the mirror image of that point.
            let ah = contact_ellipse_ellipse_near(&ei, &pi, &ej, &pj, Some(&a.point)).unwrap();
            let mirror_hint = mirrored(&a.point, tx);
            let bh = contact_ellipse_ellipse_near(&ei, &mirrored_pose(&pi, tx), &ej, &mirrored_pose(&pj, tx), Some(&mirror_hint)).unwrap();
            prop_assert!((bh.point - mirrored(&ah.point, tx)).norm() < 1e-9);
            prop_assert!((bh.normal - Vec2::new(-ah.normal.x, ah.normal.y)).norm() < 1e-9);
            prop_assert!((ah.overlap - bh.overlap).abs() < 1e-9 * (1.0 + ah.overlap));
            prop_assert!((ah.width - bh.width).abs() < 1e-9);
        }
    }

    /// The same for a wall: the mirror image of a wall (its ends swapped, so
    /// that its material stays on its left) takes the mirror image of the
    /// contact.
    #[test]
    fn ellipse_wall_contact_of_the_mirror_image_is_the_mirror_image_of_the_contact(
        b in 0.2f64..1.0, aspect in 1.0f64..4.0, phi in 0.0f64..6.3, wall_angle in 0.0f64..6.3,
        depth in 0.001f64..0.2, along in -0.4f64..0.4, tx in -10.0f64..10.0
    ) {
        let e = Ellipse::new(aspect * b, b).unwrap();
        let pose = Pose2::new(0.0, 0.0, phi);
        // A wall of length 4a through the point at which the ellipse reaches
        // furthest along the wall's inward normal, moved in by `depth`.
        let direction = Vec2::new(wall_angle.cos(), wall_angle.sin());
        // The wall's material is on its left, the ellipse on its right.
        let inward = Vec2::new(-direction.y, direction.x);
        let local = rotate(&inward, -phi);
        let reach = (e.a() * e.a() * local.x * local.x + e.b() * e.b() * local.y * local.y).sqrt();
        let centre = Point::from(inward * (reach - depth * b) + direction * (along * e.a()));
        let half = direction * (2.0 * e.a());
        let wall = Segment::new(centre - half, centre + half);
        let mirror_wall = Segment::new(mirrored(&wall.end, tx), mirrored(&wall.start, tx));
        let a = contact_ellipse_segment(&e, &pose, &wall);
        let m = contact_ellipse_segment(&e, &mirrored_pose(&pose, tx), &mirror_wall);
        prop_assert!(a.is_some() && m.is_some());
        if let (Some(a), Some(m)) = (a, m) {
            prop_assert!((m.point - mirrored(&a.point, tx)).norm() < 1e-9, "{:?} vs {:?}", a.point, m.point);
            prop_assert!((m.normal - Vec2::new(-a.normal.x, a.normal.y)).norm() < 1e-9);
            prop_assert!((a.overlap - m.overlap).abs() < 1e-9 * (1.0 + a.overlap));
            prop_assert!((a.width - m.width).abs() < 1e-9);
            prop_assert!((a.curvature_radius_a - m.curvature_radius_a).abs() < 1e-7 * (1.0 + a.curvature_radius_a));
        }
    }

    #[test]
    fn ellipse_contact_equals_the_circle_contact_when_a_equals_b(
        ri in 0.1f64..2.0, rj in 0.1f64..2.0, dir in 0.0f64..6.3, frac in 0.01f64..0.999, phi in 0.0f64..6.3
    ) {
        // Crossing circles (neither inside the other).
        let lo = (ri - rj).abs() + 1e-3;
        let d = lo + frac * (ri + rj - lo);
        let (pi, pj) = (Pose2::new(1.0, 2.0, phi), Pose2::new(1.0 + d * dir.cos(), 2.0 + d * dir.sin(), -phi));
        let e = contact_ellipse_ellipse(&Ellipse::new(ri, ri).unwrap(), &pi, &Ellipse::new(rj, rj).unwrap(), &pj).unwrap();
        let c = contact_circle_circle(&Circle::new(ri).unwrap(), &pi, &Circle::new(rj).unwrap(), &pj).unwrap();
        prop_assert!((e.point - c.point).norm() < 1e-8);
        prop_assert!((e.normal - c.normal).norm() < 1e-8);
        prop_assert!((e.overlap - c.overlap).abs() < 1e-8 && (e.width - c.width).abs() < 1e-7);
        prop_assert!((e.curvature_radius_a - ri).abs() < 1e-9 && (e.curvature_radius_b - rj).abs() < 1e-9);
    }

    #[test]
    fn no_ellipse_contact_when_bounding_boxes_are_apart(
        (ei, pi, ej, pj) in overlapping_pair(), push in 1.001f64..3.0
    ) {
        let (bi, bj) = (ei.aabb(&pi), ej.aabb(&pj));
        // Move j right until the boxes are apart.
        let gap = bi.max.x - bj.min.x;
        let pj = Pose2 { position: pj.position + Vec2::new(gap.max(0.0) * push + 1e-9, 0.0), ..pj };
        prop_assert!(!ei.aabb(&pi).intersects(&ej.aabb(&pj)));
        prop_assert!(contact_ellipse_ellipse(&ei, &pi, &ej, &pj).is_none());
    }
}

/// 2 000 random pairs (aspect 1–5, size ratio 1–10, overlap −5 … 20 % of
/// the smaller b) against the dense-sampling reference: nothing missed,
/// nothing invented, crossings exact to round-off. The reproduction runs
/// 100 000.
#[test]
fn ellipse_contact_agrees_with_the_reference_on_random_pairs() {
    let s = random_pair_statistics(2000, 11);
    assert!(
        s.in_contact > 1000,
        "too few contacts to mean anything: {s:?}"
    );
    assert_eq!(s.missed, 0, "{s:?}");
    assert_eq!(s.false_contacts, 0, "{s:?}");
    assert!(s.max_point_error < 1e-8, "{s:?}");
}

/// The mirror image of a point in the vertical line x = tx / 2.
fn mirrored(p: &Point, tx: f64) -> Point {
    Point::new(tx - p.x, p.y)
}

/// The mirror image of a pose in the vertical line x = tx / 2: an ellipse's
/// axis at angle φ goes to π − φ.
fn mirrored_pose(p: &Pose2, tx: f64) -> Pose2 {
    Pose2::new(
        tx - p.position.x,
        p.position.y,
        std::f64::consts::PI - p.angle,
    )
}

/// The points where i's boundary crosses j's, by sampling and bisection
/// (independent of the routine's quartic), in increasing parametric angle.
fn sampled_crossings(ei: &Ellipse, pi: &Pose2, ej: &Ellipse, pj: &Pose2) -> Vec<Point> {
    let g = |t: f64| ej.implicit(pj, &ei.world_point(pi, t));
    let h = std::f64::consts::TAU / 8192.0;
    let mut found = Vec::new();
    for k in 0..8192 {
        let (mut a, mut b) = (k as f64 * h, (k + 1) as f64 * h);
        if (g(a) < 0.0) != (g(b) < 0.0) {
            for _ in 0..80 {
                let m = 0.5 * (a + b);
                if (g(m) < 0.0) == (g(a) < 0.0) {
                    a = m;
                } else {
                    b = m;
                }
            }
            found.push(ei.world_point(pi, 0.5 * (a + b)));
        }
    }
    found
}

/// An elongated ellipse deep in a long one, its centre outside it, whose
/// point farthest from the long one's centre lies inside the long one:
/// its boundary still crosses the other's twice, and the contact is that
/// lens (its chord's midpoint and length), not the containment of one
/// ellipse in the other.
#[test]
fn an_elongated_ellipse_deep_in_a_long_one_touches_it_by_its_lens() {
    let ei = Ellipse::new(2.331, 0.366).unwrap();
    let pi = Pose2::new(-3.676, -1.311, 2.834);
    let ej = Ellipse::new(9.84, 1.0).unwrap();
    let pj = Pose2::new(0.0, 0.0, 0.0);
    assert!(
        ej.implicit(&pj, &pi.position) > 0.0,
        "i's centre is outside j"
    );
    let crossings = sampled_crossings(&ei, &pi, &ej, &pj);
    assert_eq!(crossings.len(), 2, "{crossings:?}");
    let midpoint = Point::from(0.5 * (crossings[0].coords + crossings[1].coords));
    for contact in [
        contact_ellipse_ellipse(&ei, &pi, &ej, &pj).unwrap(),
        contact_ellipse_ellipse(&ej, &pj, &ei, &pi).unwrap(),
    ] {
        assert!(
            (contact.point - midpoint).norm() < 1e-9,
            "{:?} vs {midpoint:?}",
            contact.point
        );
        approx::assert_relative_eq!(
            contact.width,
            (crossings[1] - crossings[0]).norm(),
            max_relative = 1e-9
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Deep overlaps beyond a DEM's range: an elongated ellipse whose
    /// centre lies just outside another, at any angle. Wherever the
    /// boundaries cross twice, the contact is that lens, from either side.
    #[test]
    fn a_deep_elongated_overlap_is_its_lens(
        ai in 3.0f64..10.0, aj in 1.0f64..10.0, bj in 0.3f64..3.0, s in 0.0f64..6.3,
        out in 0.01f64..0.3, phi_i in 0.0f64..6.3, phi_j in 0.0f64..6.3
    ) {
        let (ei, ej) = (Ellipse::new(ai * 0.4, 0.4).unwrap(), Ellipse::new(aj * bj, bj).unwrap());
        let pj = Pose2::new(0.0, 0.0, phi_j);
        let on_j = ej.world_point(&pj, s);
        let pi = Pose2::new((1.0 + out) * on_j.x, (1.0 + out) * on_j.y, phi_i);
        let crossings = sampled_crossings(&ei, &pi, &ej, &pj);
        prop_assume!(crossings.len() == 2);
        let midpoint = Point::from(0.5 * (crossings[0].coords + crossings[1].coords));
        for contact in [
            contact_ellipse_ellipse(&ei, &pi, &ej, &pj).unwrap(),
            contact_ellipse_ellipse(&ej, &pj, &ei, &pi).unwrap(),
        ] {
            prop_assert!((contact.point - midpoint).norm() < 1e-8, "{:?} vs {:?}", contact.point, midpoint);
            prop_assert!((contact.width - (crossings[1] - crossings[0]).norm()).abs() < 1e-8);
        }
    }
}

fn constant_law(k: f64) -> SpringDashpotCoulomb {
    SpringDashpotCoulomb::new(NormalStiffness::Constant(k), 0.25, 0.5, Damping::Critical).unwrap()
}

fn settle_ellipse(
    a: f64,
    b: f64,
    angle: f64,
    height: f64,
    k: f64,
    time: f64,
) -> DemSimulation<SpringDashpotCoulomb> {
    let mut scene = Scene::new(Frame::open_box(4.0, 2.0).unwrap(), Vec2::new(0.0, -9.81)).unwrap();
    scene
        .add_ellipse(Point::new(2.0, height), a, b, angle, 2690.0)
        .unwrap();
    let mut sim = DemSimulation::new(
        scene,
        constant_law(k),
        ExplicitEuler,
        DemSettings {
            dt: 2e-5,
            ..DemSettings::default()
        },
    )
    .unwrap();
    let criterion = RestCriterion {
        kinetic_to_released_ratio: 1e-12,
        unbalanced_force_ratio: 1e-9,
        min_time: time,
        max_time: 30.0,
        ..RestCriterion::default()
    };
    let outcome = sim.run_to_rest(&criterion, |_, _| {}).unwrap();
    assert_eq!(outcome.status, RunStatus::AtRest);
    sim
}

/// On its flat side the lowest point is b below the centre, on its end a.
#[test]
fn ellipse_rests_on_a_wall_at_overlap_mg_over_kn_on_its_side_and_on_its_end() {
    let (a, b, k) = (0.12, 0.06, 1e7);
    for (angle, reach) in [(0.0, b), (std::f64::consts::FRAC_PI_2, a)] {
        let sim = settle_ellipse(a, b, angle, reach + 1e-4, k, 0.2);
        let p = &sim.scene().particles[0];
        let overlap = reach - p.pose.position.y;
        approx::assert_relative_eq!(overlap, p.mass * 9.81 / k, max_relative = 1e-6);
        approx::assert_relative_eq!(p.pose.angle, angle, epsilon = 1e-9);
    }
}

/// Released at rest with its major axis tilted 30°, an ellipse on a wall
/// turns towards lying flat: the normal force alone, acting off the
/// centre, makes the torque (paper 000, §2(6)). Flat is the stable state: it
/// rolls through it and rocks about it with amplitudes that shrink at every
/// swing. (A rigid ellipse rolling without slip on a rigid wall dissipates
/// only through the normal dashpot, so with this law the rocking takes tens
/// of seconds to die out; the test follows the first seconds.)
#[test]
fn tilted_ellipse_turns_towards_flat_and_rocks_about_it_with_shrinking_amplitude() {
    let (a, b) = (0.12, 0.06);
    let tilt = 30f64.to_radians();
    let reach = ((a * tilt.sin()).powi(2) + (b * tilt.cos()).powi(2)).sqrt();
    let mut scene = Scene::new(Frame::open_box(4.0, 2.0).unwrap(), Vec2::new(0.0, -9.81)).unwrap();
    scene
        .add_ellipse(Point::new(2.0, reach + 1e-5), a, b, tilt, 2690.0)
        .unwrap();
    let mut sim = DemSimulation::new(
        scene,
        constant_law(1e7),
        ExplicitEuler,
        DemSettings {
            dt: 2e-5,
            ..DemSettings::default()
        },
    )
    .unwrap();
    let mut first_flat = None;
    let mut turning = Vec::new();
    let mut previous_omega = 0.0;
    for _ in 0..150_000 {
        sim.step().unwrap();
        let p = &sim.scene().particles[0];
        if first_flat.is_none() && p.pose.angle <= 0.0 {
            first_flat = Some(sim.time());
        }
        if previous_omega != 0.0 && p.angular_velocity * previous_omega < 0.0 {
            turning.push(p.pose.angle.abs());
        }
        previous_omega = p.angular_velocity;
        if sim.time() < 0.01 {
            assert!(
                p.angular_velocity <= 1e-12,
                "first turned away from flat: ω = {}",
                p.angular_velocity
            );
        }
    }
    let t_flat = first_flat.expect("never reached flat");
    assert!(t_flat < 0.2, "reached flat only at {t_flat} s");
    assert!(turning.len() >= 6, "rocked {} times", turning.len());
    for w in turning.windows(2) {
        assert!(w[1] < w[0], "rocking amplitude grew: {turning:?}");
    }
    assert!(turning[0] < tilt);
}
