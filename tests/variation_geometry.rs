//! Geometry of the implicit pair queries: ellipse gaps against brute
//! force, invariance under rigid motion and under a change of frame, the
//! normal search, and the contacts of smooth bodies at polygon corners.

use crate::variation_common;

use dismech::kinematics::{MapVector, PlacedEllipse, PlacedPolygon, Rigid2};
use dismech::math::{Point, Vec2};
use dismech::query::variation::{
    smooth_polygon_contacts, GapVariation, PairContact, SmoothEdgeContact, SmoothSide,
    SmoothSmoothContact, VariationError, VertexEdgeContact,
};
use nalgebra::Matrix2;
use proptest::prelude::*;
use variation_common::{boundary, ellipse, point, smooth_edge, vertex_edge};

// ------------------------------------------------------- brute force

/// `max over the boundary of (x − e)·m`, from 2048 boundary points.
fn sampled_support(side: &SmoothSide, m: &Vec2) -> f64 {
    (0..2048)
        .map(|k| k as f64 * std::f64::consts::TAU / 2048.0)
        .map(|t| (side.axes * Vec2::new(t.cos(), t.sin())).dot(m))
        .fold(f64::NEG_INFINITY, f64::max)
}

/// The smallest value of `f` over a period: on 512 angles, then, around
/// each of the eight best of them (the global minimum may lie in a basin
/// whose coarse sample is not the best), three times on 64 angles.
fn minimise_on_circle(f: impl Fn(f64) -> f64) -> f64 {
    let coarse = 512;
    let coarse_step = std::f64::consts::TAU / coarse as f64;
    let mut samples: Vec<(f64, f64)> = (0..coarse)
        .map(|k| k as f64 * coarse_step)
        .map(|t| (f(t), t))
        .collect();
    samples.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut value = f64::INFINITY;
    for &(start_value, start) in samples.iter().take(8) {
        let (mut best, mut best_value) = (start, start_value);
        let (mut width, count) = (4.0 * coarse_step, 64);
        for _ in 0..3 {
            let step = width / count as f64;
            for k in 0..=count {
                let t = best - 0.5 * width + k as f64 * step;
                let v = f(t);
                if v < best_value {
                    (best_value, best) = (v, t);
                }
            }
            width = 4.0 * step;
        }
        value = value.min(best_value);
    }
    value
}

/// The smallest distance between the boundaries of two ellipses: over A's
/// boundary, the distance of each point to B's boundary.
fn nearest_boundary_distance(a: &SmoothSide, b: &SmoothSide) -> f64 {
    let at = |side: &SmoothSide, t: f64| side.centre + side.axes * Vec2::new(t.cos(), t.sin());
    minimise_on_circle(|ta| {
        let x = at(a, ta);
        minimise_on_circle(|tb| (at(b, tb) - x).norm())
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// The ellipse gap equals a brute-force one: the largest sampled
    /// separation `Δe·n − h_A(n) − h_B(−n)` with supports from boundary
    /// points (apart or overlapping), and, apart, the smallest distance
    /// between sampled boundary points.
    #[test]
    fn ellipse_gap_matches_brute_force(
        a in (0.2f64..1.0, 0.25f64..1.0, -3.0f64..3.0),
        b in (0.2f64..1.0, 0.25f64..1.0, -3.0f64..3.0),
        distance in 0.6f64..1.6, direction in -3.2f64..3.2,
    ) {
        let side_a = ellipse(Point::new(0.1, 0.2), a.0, a.0 * a.1, a.2);
        let centre_b = side_a.centre + Vec2::new(direction.cos(), direction.sin()) * (distance * (a.0 + b.0));
        let side_b = ellipse(centre_b, b.0, b.0 * b.1, b.2);
        let gap = SmoothSmoothContact::detect(&side_a, &side_b, f64::INFINITY, None).unwrap().unwrap().initial_gap;
        let de = side_b.centre - side_a.centre;
        let separation = (0..2048)
            .map(|k| k as f64 * std::f64::consts::TAU / 2048.0)
            .map(|t| { let n = Vec2::new(t.cos(), t.sin()); de.dot(&n) - sampled_support(&side_a, &n) - sampled_support(&side_b, &(-n)) })
            .fold(f64::NEG_INFINITY, f64::max);
        prop_assert!((gap - separation).abs() < 2e-5, "gap {} vs sampled separation {}", gap, separation);
        if gap > 1e-3 {
            let nearest = nearest_boundary_distance(&side_a, &side_b);
            prop_assert!((gap - nearest).abs() < 1e-9, "gap {} vs sampled distance {}", gap, nearest);
        }
    }
}

// ------------------------------------------------------- invariance

/// Map parameters after a rigid motion `x ↦ Q(α)(x − o) + o + s` is
/// superposed on the map `Δp` of a body with reference point `c`.
fn superpose(dp: &MapVector, c: &Point, alpha: f64, o: &Point, s: &Vec2) -> MapVector {
    let q = Rigid2::rotation(alpha);
    let f = q * Matrix2::new(1.0 + dp[2], dp[3], dp[4], 1.0 + dp[5]);
    let t = q * (c + Vec2::new(dp[0], dp[1]) - o) + o.coords + s - c.coords;
    MapVector::new(
        t.x,
        t.y,
        f[(0, 0)] - 1.0,
        f[(0, 1)],
        f[(1, 0)],
        f[(1, 1)] - 1.0,
    )
}

/// `(g_n, g_s)` of a contact with the rigid motion superposed on both maps.
fn superposed<const M: usize>(
    q: &impl GapVariation<M>,
    c: [Point; 2],
    p: &[f64],
    motion: (f64, Point, Vec2),
) -> (f64, f64) {
    let (a, b) = (
        MapVector::from_column_slice(&p[0..6]),
        MapVector::from_column_slice(&p[6..12]),
    );
    let (alpha, o, s) = motion;
    let v = q
        .map_variation(
            &superpose(&a, &c[0], alpha, &o, &s),
            &superpose(&b, &c[1], alpha, &o, &s),
        )
        .unwrap();
    (v.gap, v.shear)
}

proptest! {
    /// A rigid motion of both bodies superposed within the step leaves
    /// every gap unchanged, and the shear of the edge contacts (measured
    /// along the current edge); the smooth–smooth shear, measured along the
    /// frozen start tangent, gains exactly `g₀ sin α` under a pure rotation.
    #[test]
    fn gaps_are_invariant_under_a_rigid_motion_of_both_bodies(
        geometry in proptest::collection::vec(-1.0f64..1.0, 11),
        p in proptest::collection::vec(-0.05f64..0.05, 12),
        alpha in -1.5f64..1.5, o in proptest::collection::vec(-2.0f64..2.0, 2), s in proptest::collection::vec(-2.0f64..2.0, 2),
        shape in (0.2f64..1.0, 0.25f64..1.0, -3.0f64..3.0),
    ) {
        let motion = (alpha, point(&o), Vec2::new(s[0], s[1]));
        let still = (0.0, Point::origin(), Vec2::zeros());
        let ve = vertex_edge(&geometry);
        let c = [ve.reference_a, ve.reference_b];
        let (x, y) = (superposed(&ve, c, &p, still), superposed(&ve, c, &p, motion));
        prop_assert!((x.0 - y.0).abs() < 1e-12 && (x.1 - y.1).abs() < 1e-12, "{:?} vs {:?}", x, y);
        let side = ellipse(point(&geometry[0..2]) + Vec2::new(0.0, 2.0), shape.0, shape.0 * shape.1, shape.2);
        let se = smooth_edge(&geometry, side);
        let c = [side.reference, se.reference_b];
        let (x, y) = (superposed(&se, c, &p, still), superposed(&se, c, &p, motion));
        prop_assert!((x.0 - y.0).abs() < 1e-12 && (x.1 - y.1).abs() < 1e-12, "{:?} vs {:?}", x, y);
        let other = ellipse(side.centre + Vec2::new(1.5, 0.3), 0.4, 0.3, 0.2);
        let ss = SmoothSmoothContact::detect(&side, &other, f64::INFINITY, None).unwrap().unwrap();
        let c = [side.reference, other.reference];
        let (x, y) = (superposed(&ss, c, &p, still), superposed(&ss, c, &p, motion));
        prop_assert!((x.0 - y.0).abs() < 1e-12, "{} vs {}", x.0, y.0);
        let (_, turned) = superposed(&ss, c, &[0.0; 12], (alpha, point(&o), Vec2::zeros()));
        prop_assert!((turned - ss.initial_gap * alpha.sin()).abs() < 1e-12, "{} vs {}", turned, ss.initial_gap * alpha.sin());
    }

    /// Turning and shifting the whole start configuration (and the step's
    /// maps with it) changes neither gaps nor shears, for every kind.
    #[test]
    fn contacts_do_not_depend_on_the_frame(
        geometry in proptest::collection::vec(-1.0f64..1.0, 11),
        p in proptest::collection::vec(-0.05f64..0.05, 12),
        alpha in -3.2f64..3.2, s in proptest::collection::vec(-5.0f64..5.0, 2),
    ) {
        let q = Rigid2::rotation(alpha);
        let shift = Vec2::new(s[0], s[1]);
        let place = |x: Point| Point::from(q * x.coords + shift);
        let turn_map = |dp: &[f64]| {
            let t = q * Vec2::new(dp[0], dp[1]);
            let f = q * Matrix2::new(dp[2], dp[3], dp[4], dp[5]) * q.transpose();
            MapVector::new(t.x, t.y, f[(0, 0)], f[(0, 1)], f[(1, 0)], f[(1, 1)])
        };
        let (a, b) = (MapVector::from_column_slice(&p[0..6]), MapVector::from_column_slice(&p[6..12]));
        let (ta, tb) = (turn_map(&p[0..6]), turn_map(&p[6..12]));
        let turn_side = |side: &SmoothSide| SmoothSide { centre: place(side.centre), axes: q * side.axes, reference: place(side.reference) };
        let side = ellipse(point(&geometry[0..2]) + Vec2::new(0.0, 2.0), 0.7, 0.3, geometry[2]);
        let other = ellipse(side.centre + Vec2::new(1.2, 0.3), 0.4, 0.3, 0.2);
        let edge = [point(&geometry[4..6]), point(&geometry[6..8]) + Vec2::new(2.0, 0.5)];
        let pairs: Vec<(PairContact, PairContact)> = vec![
            (
                PairContact::VertexEdge(VertexEdgeContact::detect(side.centre, side.reference, edge, point(&geometry[8..10]), f64::INFINITY).unwrap_or(vertex_edge(&geometry))),
                PairContact::VertexEdge(VertexEdgeContact::detect(place(side.centre), place(side.reference), edge.map(place), place(point(&geometry[8..10])), f64::INFINITY).unwrap_or({
                    let v = vertex_edge(&geometry);
                    VertexEdgeContact { vertex: place(v.vertex), reference_a: place(v.reference_a), edge: v.edge.map(place), reference_b: place(v.reference_b), ..v }
                })),
            ),
            (
                PairContact::SmoothSmooth(SmoothSmoothContact::detect(&side, &other, f64::INFINITY, None).unwrap().unwrap()),
                PairContact::SmoothSmooth(SmoothSmoothContact::detect(&turn_side(&side), &turn_side(&other), f64::INFINITY, None).unwrap().unwrap()),
            ),
        ];
        for (x, y) in pairs {
            let (u, v) = (x.map_variation(&a, &b).unwrap(), y.map_variation(&ta, &tb).unwrap());
            prop_assert!((u.gap - v.gap).abs() < 1e-12 && (u.shear - v.shear).abs() < 1e-12, "{} {} vs {} {}", u.gap, u.shear, v.gap, v.shear);
        }
        let se = smooth_edge(&geometry, side);
        let turned = SmoothEdgeContact { side: turn_side(&side), edge: se.edge.map(place), reference_b: place(se.reference_b), material: place(se.material), ..se };
        let (u, v) = (se.map_variation(&a, &b).unwrap(), turned.map_variation(&ta, &tb).unwrap());
        prop_assert!((u.gap - v.gap).abs() < 1e-12 && (u.shear - v.shear).abs() < 1e-12);
    }
}

// ------------------------------------------------ normal search, corners

#[test]
fn normal_search_finds_the_same_normal_from_a_perturbed_start() {
    let a = ellipse(Point::origin(), 1.0, 0.3, 0.4);
    let b = ellipse(Point::new(1.1, 0.6), 0.6, 0.2, -0.7);
    let c = SmoothSmoothContact::detect(&a, &b, f64::INFINITY, None)
        .unwrap()
        .unwrap();
    for delta in [-0.4, -0.1, 0.05, 0.3] {
        let d = SmoothSmoothContact::detect(&a, &b, f64::INFINITY, Some(c.angle + delta))
            .unwrap()
            .unwrap();
        assert!(
            (d.angle - c.angle).abs() < 1e-12,
            "{} vs {}",
            d.angle,
            c.angle
        );
        assert!((d.initial_gap - c.initial_gap).abs() < 1e-15);
    }
    assert!(
        SmoothSmoothContact::detect(&a, &b, c.initial_gap - 1e-3, None)
            .unwrap()
            .is_none()
    );
}

#[test]
fn concentric_circles_have_no_contact_normal() {
    let a = SmoothSide::ellipse(&PlacedEllipse::circle(Point::new(1.0, 1.0), 0.5).unwrap());
    let b = SmoothSide::ellipse(&PlacedEllipse::circle(Point::new(1.0, 1.0), 0.3).unwrap());
    match SmoothSmoothContact::detect(&a, &b, 1.0, None) {
        Err(VariationError::NotAMaximum { curvature, .. }) => assert!(curvature.abs() < 1e-12),
        other => panic!("{other:?}"),
    }
}

/// A circle moved around a square's corner at a fixed clearance meets it
/// once: on an edge, or on the corner when its normal is in the corner's
/// cone, never both; its gap is the clearance on the corner.
#[test]
fn a_circle_meets_a_polygon_corner_once() {
    let square =
        [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| Point::new(x, y));
    let square = PlacedPolygon::from_world(&square, 0).unwrap();
    let (r, clearance) = (0.5, 1e-3);
    for k in 0..=44 {
        let angle = (-10.0 + 2.5 * k as f64).to_radians();
        let centre = Point::new(1.0, 1.0) + Vec2::new(angle.cos(), angle.sin()) * (r + clearance);
        let side = SmoothSide::ellipse(&PlacedEllipse::circle(centre, r).unwrap());
        let contacts = smooth_polygon_contacts(&side, &square, 0.01).unwrap();
        assert_eq!(contacts.len(), 1, "at {angle} rad: {contacts:?}");
        let (feature, contact) = &contacts[0];
        let inside_cone = angle > 0.0 && angle < std::f64::consts::FRAC_PI_2;
        match contact {
            PairContact::SmoothSmooth(c) => {
                assert!(inside_cone && *feature == 2, "corner contact at {angle}");
                assert!((c.initial_gap - clearance).abs() < 1e-14);
            }
            PairContact::SmoothEdge(c) => {
                assert!(!inside_cone, "edge contact at {angle}");
                assert!(*feature == if angle <= 0.0 { 1 } else { 2 });
                assert!(c.initial_gap <= clearance + 1e-14);
            }
            PairContact::VertexEdge(_) => panic!("no vertex–edge contact expected"),
        }
    }
}

/// A body against a fixed wall: the unknowns of the fixed side are none,
/// and the variations are those in the map parameters with the wall still.
fn segment_distance(p: &Point, a: &Point, b: &Point) -> f64 {
    let ab = b - a;
    let s = ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
    (p - (a + ab * s)).norm()
}

proptest! {
    /// An ellipse outside a square near its corner has exactly one contact
    /// when it is within the search distance of the square, none when it is
    /// beyond, and the contact's gap is the brute-force distance.
    #[test]
    fn an_ellipse_near_a_corner_has_one_contact_at_the_true_distance(
        turn in -3.2f64..3.2, angle in -0.4f64..2.0, reach in 0.25f64..0.75, ratio in 0.3f64..1.0,
    ) {
        let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| Point::new(x, y));
        let square = PlacedPolygon::from_world(&corners, 0).unwrap();
        let side = ellipse(Point::new(1.0, 1.0) + Vec2::new(angle.cos(), angle.sin()) * reach, 0.5, 0.5 * ratio, turn);
        let outline = boundary(&side, 4000);
        prop_assume!(outline.iter().all(|p| p.x.abs() > 1.0 || p.y.abs() > 1.0));
        // Distance of the boundary point at parameter t to the square,
        // minimised on 4000 parameters, then twice more around the best.
        let to_square = |t: f64| {
            let p = side.centre + side.axes * Vec2::new(t.cos(), t.sin());
            (0..4).map(|k| segment_distance(&p, &corners[k], &corners[(k + 1) % 4])).fold(f64::INFINITY, f64::min)
        };
        let (mut best, mut width) = (0.0, std::f64::consts::TAU);
        for _ in 0..3 {
            let step = width / 4000.0;
            best = (0..=4000)
                .map(|k| best - 0.5 * width + k as f64 * step)
                .map(|t| (t, to_square(t)))
                .fold((best, f64::INFINITY), |b, x| if x.1 < b.1 { x } else { b })
                .0;
            width = 4.0 * step;
        }
        let distance = to_square(best);
        // Apart: a boundary point on the square would be at distance ~0.
        prop_assume!(distance > 1e-6);
        let search = 0.05;
        let contacts = smooth_polygon_contacts(&side, &square, search).unwrap();
        prop_assert!(contacts.len() <= 1, "{:?}", contacts);
        if distance < search - 1e-4 {
            prop_assert_eq!(contacts.len(), 1);
            let gap = contacts[0].1.initial_gap();
            prop_assert!((gap - distance).abs() < 1e-9, "gap {} vs distance {}", gap, distance);
        } else if distance > search + 1e-4 {
            prop_assert!(contacts.is_empty());
        }
    }
}

/// After a rigid turn of both bodies the normal found from the start normal
/// is the start normal turned by the same angle.
#[test]
fn the_normal_turns_with_the_pair() {
    let a = ellipse(Point::origin(), 1.0, 0.3, 0.4);
    let b = ellipse(Point::new(1.1, 0.6), 0.6, 0.2, -0.7);
    let c = SmoothSmoothContact::detect(&a, &b, f64::INFINITY, None)
        .unwrap()
        .unwrap();
    let alpha = 0.3;
    let o = Point::new(0.5, 0.2);
    let turn = |side: &SmoothSide| {
        superpose(
            &MapVector::zeros(),
            &side.reference,
            alpha,
            &o,
            &Vec2::zeros(),
        )
    };
    let angle = c.normal_angle(&turn(&a), &turn(&b)).unwrap();
    assert!(
        (angle - (c.angle + alpha)).abs() < 1e-12,
        "{angle} vs {}",
        c.angle + alpha
    );
}
