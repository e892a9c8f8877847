//! Polygon pair queries (manifolds with features) and polygons in the
//! explicit DEM.

use dismech::error::DismechError;
use dismech::math::{rotate, Point, Pose2, Vec2};
use dismech::query::manifold::dispatch::{contact_2d, contact_manifold_2d};
use dismech::query::{ContactFeatures, ContactGeometry, Feature};
use dismech::shape::{AnyShape2, Circle, Ellipse, Polygon, Segment};
use proptest::prelude::*;

fn manifold(a: &AnyShape2, pa: &Pose2, b: &AnyShape2, pb: &Pose2) -> Vec<ContactGeometry> {
    let mut out = Vec::new();
    contact_manifold_2d(a, pa, b, pb, &mut out).unwrap();
    out.sort_by_key(|g| g.features);
    out
}

fn polygon(vertices: &[(f64, f64)]) -> AnyShape2 {
    let v: Vec<Point> = vertices.iter().map(|&(x, y)| Point::new(x, y)).collect();
    AnyShape2::Polygon(Polygon::from_world(&v, 0).unwrap().0)
}

fn square(side: f64) -> AnyShape2 {
    AnyShape2::Polygon(Polygon::rectangle(side, side).unwrap())
}

/// The L `[0,2]×[0,1] ∪ [0,1]×[1,2]` in its centroid frame, and the
/// centroid (the notch's reflex corner is at world (1, 1)).
fn l_shape() -> (AnyShape2, Pose2) {
    let v = [
        (0.0, 0.0),
        (2.0, 0.0),
        (2.0, 1.0),
        (1.0, 1.0),
        (1.0, 2.0),
        (0.0, 2.0),
    ]
    .map(|(x, y)| Point::new(x, y));
    let (p, c) = Polygon::from_world(&v, 0).unwrap();
    (AnyShape2::Polygon(p), Pose2::new(c.x, c.y, 0.0))
}

fn vertex_edge(i: usize, e: usize) -> ContactFeatures {
    ContactFeatures {
        a: Feature::Vertex(i),
        b: Feature::Edge(e),
    }
}

fn edge_vertex(e: usize, k: usize) -> ContactFeatures {
    vertex_edge(k, e).swapped()
}

#[test]
fn square_face_on_square_face_gives_two_points_at_the_corners_with_exact_overlap() {
    let (a, b) = (square(1.0), square(1.0));
    let depth = 1e-3;
    let (pa, pb) = (Pose2::new(0.0, 0.0, 0.0), Pose2::new(0.3, 1.0 - depth, 0.0));
    let points = manifold(&a, &pa, &b, &pb);
    assert_eq!(points.len(), 2, "{points:?}");
    // A's upper-right corner (vertex 2) in B's bottom (edge 0); B's
    // lower-left corner (vertex 0) in A's top (edge 2).
    let expected = [
        (vertex_edge(2, 0), Point::new(0.5, 0.5 - 0.5 * depth)),
        (edge_vertex(2, 0), Point::new(-0.2, 0.5 - 0.5 * depth)),
    ];
    for (features, point) in expected {
        let g = points.iter().find(|g| g.features == features).unwrap();
        approx::assert_relative_eq!(g.overlap, depth, epsilon = 1e-12);
        assert!((g.point - point).norm() < 1e-12, "{:?}", g.point);
        assert!((g.normal - Vec2::y()).norm() < 1e-12);
    }
}

#[test]
fn aligned_squares_with_coincident_corners_give_one_point_per_corner() {
    let depth = 1e-3;
    let points = manifold(
        &square(1.0),
        &Pose2::new(0.0, 0.0, 0.0),
        &square(1.0),
        &Pose2::new(0.0, 1.0 - depth, 0.0),
    );
    assert_eq!(points.len(), 2, "{points:?}");
    for (i, k, x) in [(2, 1, 0.5), (3, 0, -0.5)] {
        let g = points
            .iter()
            .find(|g| {
                g.features
                    == ContactFeatures {
                        a: Feature::Vertex(i),
                        b: Feature::Vertex(k),
                    }
            })
            .unwrap();
        approx::assert_relative_eq!(g.overlap, depth, epsilon = 1e-12);
        assert!((g.point - Point::new(x, 0.5 - 0.5 * depth)).norm() < 1e-12);
        assert!((g.normal - Vec2::y()).norm() < 1e-12);
    }
}

#[test]
fn corner_on_a_face_gives_one_point_with_the_face_normal() {
    // A diamond whose lowest corner dips 1e-3 into the top of a square.
    let diamond = polygon(&[(0.0, -1.0), (1.0, 0.0), (0.0, 1.0), (-1.0, 0.0)]);
    let pb = Pose2::new(0.1, 1.5 - 1e-3, 0.0);
    let points = manifold(&square(1.0), &Pose2::default(), &diamond, &pb);
    assert_eq!(points.len(), 1, "{points:?}");
    assert_eq!(points[0].features, edge_vertex(2, 0));
    approx::assert_relative_eq!(points[0].overlap, 1e-3, epsilon = 1e-12);
    assert!((points[0].normal - Vec2::y()).norm() < 1e-12);
}

#[test]
fn polygon_features_stay_while_the_bodies_slide_a_little() {
    let (a, b) = (square(1.0), square(1.0));
    let features = |shift: f64, turn: f64| -> Vec<ContactFeatures> {
        manifold(
            &a,
            &Pose2::default(),
            &b,
            &Pose2::new(0.3 + shift, 1.0 - 1e-3, turn),
        )
        .iter()
        .map(|g| g.features)
        .collect()
    };
    let reference = features(0.0, 0.0);
    for (shift, turn) in [(1e-4, 0.0), (-2e-3, 1e-4), (5e-3, -2e-4)] {
        assert_eq!(features(shift, turn), reference);
    }
}

#[test]
fn disc_in_the_notch_of_an_l_touches_both_notch_edges() {
    let (l, pose) = l_shape();
    let r = 0.25;
    let disc = AnyShape2::Circle(Circle::new(r).unwrap());
    // Centre 0.24 from both notch faces (x = 1 and y = 1).
    let centre = Pose2::new(1.24, 1.24, 0.0);
    let points = manifold(&disc, &centre, &l, &pose);
    assert_eq!(points.len(), 2, "{points:?}");
    let normals: Vec<Vec2> = points.iter().map(|g| g.normal).collect();
    assert!(normals
        .iter()
        .any(|n| (n - Vec2::new(-1.0, 0.0)).norm() < 1e-12));
    assert!(normals
        .iter()
        .any(|n| (n - Vec2::new(0.0, -1.0)).norm() < 1e-12));
    for g in &points {
        approx::assert_relative_eq!(g.overlap, 0.01, epsilon = 1e-12);
        assert!(matches!(g.features.b, Feature::Edge(2) | Feature::Edge(3)));
    }
}

#[test]
fn square_pressed_into_the_notch_of_an_l_bears_on_both_faces_at_both_ends() {
    let (l, pose) = l_shape();
    let d = 1e-3;
    // A 0.8 square pressed 1e-3 into both notch faces.
    let sq = square(0.8);
    let ps = Pose2::new(1.4 - d, 1.4 - d, 0.0);
    let points = manifold(&sq, &ps, &l, &pose);
    let on = |n: Vec2| points.iter().filter(move |g| (g.normal - n).norm() < 1e-9);
    // Into the notch's bottom face: normal −y; into its left face: −x.
    for n in [Vec2::new(0.0, -1.0), Vec2::new(-1.0, 0.0)] {
        assert_eq!(on(n).count(), 2, "{points:?}");
        for g in on(n) {
            approx::assert_relative_eq!(g.overlap, d, epsilon = 1e-12);
        }
    }
    assert_eq!(points.len(), 4);
}

#[test]
fn separated_shapes_give_no_point() {
    let (l, pose) = l_shape();
    let shapes = [
        AnyShape2::Circle(Circle::new(0.3).unwrap()),
        AnyShape2::Ellipse(Ellipse::new(0.4, 0.2).unwrap()),
        square(0.5),
        l.clone(),
    ];
    let radius = |s: &AnyShape2| s.as_shape().bounding_radius();
    for a in &shapes {
        let ra = radius(a);
        for b in &shapes {
            let rb = radius(b);
            let gap = ra + rb + 1e-6;
            let pb = Pose2::new(gap * 0.6, gap * 0.8, 0.3);
            assert!(manifold(a, &Pose2::new(0.0, 0.0, -0.2), b, &pb).is_empty());
        }
        // A wall just below the body.
        let wall = AnyShape2::Segment(Segment::new(
            Point::new(-5.0, -ra - 1e-6),
            Point::new(5.0, -ra - 1e-6),
        ));
        assert!(manifold(a, &Pose2::new(0.0, 0.0, 0.7), &wall, &Pose2::default()).is_empty());
        assert!(manifold(&wall, &Pose2::default(), a, &Pose2::new(0.0, 0.0, 0.7)).is_empty());
    }
    // The notch itself is empty: a small disc in it touches nothing.
    let disc = AnyShape2::Circle(Circle::new(0.2).unwrap());
    assert!(manifold(&disc, &Pose2::new(1.5, 1.5, 0.0), &l, &pose).is_empty());
}

#[test]
fn two_segments_are_a_typed_error_naming_both_shapes() {
    let s = AnyShape2::Segment(Segment::new(Point::new(0.0, 0.0), Point::new(1.0, 0.0)));
    let t = AnyShape2::Segment(Segment::new(Point::new(0.5, -1.0), Point::new(0.5, 1.0)));
    let mut out = vec![];
    let err = contact_manifold_2d(&s, &Pose2::default(), &t, &Pose2::default(), &mut out);
    assert_eq!(
        err.unwrap_err(),
        DismechError::UnsupportedPair("segment", "segment")
    );
    assert!(out.is_empty());
    let err = contact_2d(&s, &Pose2::default(), &t, &Pose2::default()).unwrap_err();
    assert!(err.to_string().contains("segment against segment"), "{err}");
}

#[test]
fn rectangle_on_a_wall_touches_at_its_corners_and_the_wall_end_acts_as_a_corner() {
    let floor = AnyShape2::Segment(Segment::new(Point::new(0.0, 0.0), Point::new(2.0, 0.0)));
    let block = AnyShape2::Polygon(Polygon::rectangle(0.4, 0.2).unwrap());
    let d = 1e-3;
    // Fully on the floor: its two bottom corners.
    let points = manifold(
        &block,
        &Pose2::new(1.0, 0.1 - d, 0.0),
        &floor,
        &Pose2::default(),
    );
    assert_eq!(
        points.iter().map(|g| g.features).collect::<Vec<_>>(),
        vec![vertex_edge(0, 0), vertex_edge(1, 0)]
    );
    for g in &points {
        approx::assert_relative_eq!(g.overlap, d, epsilon = 1e-12);
        assert!((g.normal + Vec2::y()).norm() < 1e-12);
    }
    // Overhanging the floor's end (x = 2): the lower-left corner and the
    // floor's end against the block's bottom edge.
    let points = manifold(
        &block,
        &Pose2::new(2.1, 0.1 - d, 0.0),
        &floor,
        &Pose2::default(),
    );
    assert_eq!(
        points.iter().map(|g| g.features).collect::<Vec<_>>(),
        vec![vertex_edge(0, 0), edge_vertex(0, 1)]
    );
    let end = points
        .iter()
        .find(|g| g.features == edge_vertex(0, 1))
        .unwrap();
    assert!((end.point - Point::new(2.0, -0.5 * d)).norm() < 1e-12);
    approx::assert_relative_eq!(end.overlap, d, epsilon = 1e-12);
    assert!((end.normal + Vec2::y()).norm() < 1e-12);
    // Behind the wall within its extent it is pushed back however deep.
    let deep = manifold(
        &block,
        &Pose2::new(1.0, -0.05, 0.0),
        &floor,
        &Pose2::default(),
    );
    assert_eq!(deep.len(), 2);
    approx::assert_relative_eq!(deep[0].overlap, 0.15, epsilon = 1e-12);
}

#[test]
fn smooth_pairs_give_the_single_point_bit_for_bit() {
    let c = AnyShape2::Circle(Circle::new(0.3).unwrap());
    let e = AnyShape2::Ellipse(Ellipse::new(0.5, 0.2).unwrap());
    let wall = AnyShape2::Segment(Segment::new(
        Point::new(-2.0, -0.25),
        Point::new(2.0, -0.28),
    ));
    let (pa, pb) = (Pose2::new(0.01, 0.02, 0.3), Pose2::new(0.45, 0.3, 1.1));
    let on_wall = Pose2::new(0.2, -0.1, 0.3);
    for (a, pa, b, pb) in [
        (&c, pa, &c, pb),
        (&c, pa, &e, pb),
        (&e, pa, &c, pb),
        (&e, pa, &e, pb),
        (&c, pa, &wall, pb),
        (&wall, pb, &e, on_wall),
        (&e, on_wall, &wall, pb),
    ] {
        let single = contact_2d(a, &pa, b, &pb).unwrap().unwrap();
        let mut out = Vec::new();
        contact_manifold_2d(a, &pa, b, &pb, &mut out).unwrap();
        assert_eq!(out, vec![single]);
        assert_eq!(single.features, ContactFeatures::WHOLE);
    }
}

#[test]
fn the_manifold_buffer_is_reused_without_allocating() {
    let (a, b) = (square(1.0), square(1.0));
    let pb = Pose2::new(0.3, 1.0 - 1e-3, 0.0);
    let mut out = Vec::with_capacity(8);
    let (capacity, address) = (out.capacity(), out.as_ptr());
    for _ in 0..100 {
        out.clear();
        contact_manifold_2d(&a, &Pose2::default(), &b, &pb, &mut out).unwrap();
    }
    assert_eq!(out.len(), 2);
    assert_eq!((out.capacity(), out.as_ptr()), (capacity, address));
}

prop_compose! {
    /// A simple polygon, star-shaped about its centre, often concave: 3–8
    /// vertices at increasing angles and radii in [0.3, 1] × `size`.
    fn star_polygon(size: f64)(n in 3usize..9, jitter in prop::collection::vec(-0.4f64..0.4, 8),
                               radii in prop::collection::vec(0.3f64..1.0, 8)) -> Polygon {
        let v: Vec<Point> = (0..n).map(|k| {
            let t = (k as f64 + jitter[k]) * std::f64::consts::TAU / n as f64;
            Point::new(size * radii[k] * t.cos(), size * radii[k] * t.sin())
        }).collect();
        Polygon::from_world(&v, 0).unwrap().0
    }
}

prop_compose! {
    /// A regular polygon (3–8 sides) of circumradius `size`, turned.
    fn regular_polygon(size: f64)(n in 3usize..9, turn in 0.0f64..6.3) -> Polygon {
        let v: Vec<Point> = (0..n).map(|k| {
            let t = turn + k as f64 * std::f64::consts::TAU / n as f64;
            Point::new(size * t.cos(), size * t.sin())
        }).collect();
        Polygon::from_world(&v, 0).unwrap().0
    }
}

/// Any shape but a segment, placed near the origin (ellipse aspect 1–3).
fn any_body() -> impl Strategy<Value = AnyShape2> {
    prop_oneof![
        (0.2f64..1.0).prop_map(|r| AnyShape2::Circle(Circle::new(r).unwrap())),
        (0.2f64..0.6, 1.0f64..3.0)
            .prop_map(|(b, k)| AnyShape2::Ellipse(Ellipse::new(b * k, b).unwrap())),
        star_polygon(1.0).prop_map(AnyShape2::Polygon),
    ]
}

/// A pair with at least one polygon: B placed along a random direction at
/// a random fraction of the sum of bounding radii (so often overlapping).
fn polygon_pair() -> impl Strategy<Value = (AnyShape2, Pose2, AnyShape2, Pose2)> {
    (
        any_body(),
        star_polygon(1.0),
        any::<bool>(),
        0.0f64..6.3,
        0.0f64..6.3,
        0.0f64..6.3,
        0.5f64..1.05,
    )
        .prop_map(|(other, p, first, phi_a, phi_b, dir, frac)| {
            let p = AnyShape2::Polygon(p);
            let (a, b) = if first { (p, other) } else { (other, p) };
            let d = frac * (a.as_shape().bounding_radius() + b.as_shape().bounding_radius());
            let pb = Pose2::new(d * dir.cos(), d * dir.sin(), phi_b);
            (a, Pose2::new(0.0, 0.0, phi_a), b, pb)
        })
}

fn moved(p: &Pose2, turn: f64, shift: Vec2) -> Pose2 {
    Pose2 {
        position: Point::from(rotate(&p.position.coords, turn) + shift),
        angle: p.angle + turn,
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    #[test]
    fn polygon_manifold_is_invariant_under_rigid_motion(
        (a, pa, b, pb) in polygon_pair(), turn in 0.0f64..6.3, tx in -10.0f64..10.0, ty in -10.0f64..10.0
    ) {
        let shift = Vec2::new(tx, ty);
        let here = manifold(&a, &pa, &b, &pb);
        let there = manifold(&a, &moved(&pa, turn, shift), &b, &moved(&pb, turn, shift));
        // Points at the threshold of existing may come and go by rounding.
        let real = |m: &[ContactGeometry]| m.iter().filter(|g| g.overlap > 1e-9).copied().collect::<Vec<_>>();
        let (here, there) = (real(&here), real(&there));
        prop_assert_eq!(here.len(), there.len());
        for (g, h) in here.iter().zip(&there) {
            prop_assert_eq!(g.features, h.features);
            let expected = Point::from(rotate(&g.point.coords, turn) + shift);
            prop_assert!((h.point - expected).norm() < 1e-8, "{:?} vs {:?}", h.point, expected);
            prop_assert!((h.normal - rotate(&g.normal, turn)).norm() < 1e-8);
            prop_assert!((g.overlap - h.overlap).abs() < 1e-8 && (g.width - h.width).abs() < 1e-7);
        }
    }

    #[test]
    fn swapping_the_pair_flips_normals_and_keeps_points((a, pa, b, pb) in polygon_pair()) {
        let ab = manifold(&a, &pa, &b, &pb);
        let mut ba: Vec<ContactGeometry> = manifold(&b, &pb, &a, &pa).iter().map(|g| g.flipped()).collect();
        ba.sort_by_key(|g| g.features);
        prop_assert_eq!(ab, ba);
    }

    #[test]
    fn wall_manifold_is_invariant_under_rigid_motion_and_swap(
        p in star_polygon(1.0), phi in 0.0f64..6.3, dir in 0.0f64..6.3, depth in -0.2f64..0.5,
        half in 0.5f64..3.0, offset in -1.5f64..1.5, turn in 0.0f64..6.3, tx in -10.0f64..10.0, ty in -10.0f64..10.0
    ) {
        let p = AnyShape2::Polygon(p);
        let r = p.as_shape().bounding_radius();
        // A wall whose inner normal is (cos dir, sin dir), reaching into the
        // polygon by up to half its radius.
        let inner = Vec2::new(dir.cos(), dir.sin());
        let along = Vec2::new(inner.y, -inner.x);
        let foot = Point::from(-inner * (r - depth)) + along * offset;
        let wall = |turn: f64, shift: Vec2| {
            let m = |q: Point| Point::from(rotate(&q.coords, turn) + shift);
            AnyShape2::Segment(Segment::new(m(foot - along * half), m(foot + along * half)))
        };
        let pose = Pose2::new(0.0, 0.0, phi);
        let shift = Vec2::new(tx, ty);
        let here = manifold(&p, &pose, &wall(0.0, Vec2::zeros()), &Pose2::default());
        let there = manifold(&p, &moved(&pose, turn, shift), &wall(turn, shift), &Pose2::default());
        let real = |m: &[ContactGeometry]| m.iter().filter(|g| g.overlap > 1e-9).copied().collect::<Vec<_>>();
        let (here_r, there_r) = (real(&here), real(&there));
        prop_assert_eq!(here_r.len(), there_r.len());
        for (g, h) in here_r.iter().zip(&there_r) {
            prop_assert_eq!(g.features, h.features);
            prop_assert!((h.point - Point::from(rotate(&g.point.coords, turn) + shift)).norm() < 1e-8);
            prop_assert!((h.normal - rotate(&g.normal, turn)).norm() < 1e-8);
            prop_assert!((g.overlap - h.overlap).abs() < 1e-8);
        }
        let mut swapped: Vec<ContactGeometry> = manifold(&wall(0.0, Vec2::zeros()), &Pose2::default(), &p, &pose)
            .iter().map(|g| g.flipped()).collect();
        swapped.sort_by_key(|g| g.features);
        prop_assert_eq!(here, swapped);
    }

    #[test]
    fn circle_on_a_polygon_edge_is_the_circle_on_that_edge_as_a_wall(
        p in regular_polygon(1.0), x in -3.0f64..3.0, y in -3.0f64..3.0, phi in 0.0f64..6.3,
        edge in 0usize..8, t in 0.1f64..0.9, size in 0.05f64..0.3, depth in 1e-4f64..0.1
    ) {
        let n = p.vertices().len();
        let k = edge % n;
        let pose = Pose2::new(x, y, phi);
        let (v0, v1) = (pose.transform_point(&p.vertices()[k]), pose.transform_point(&p.vertices()[(k + 1) % n]));
        let r = size * (v1 - v0).norm();
        let m = pose.transform_vector(&p.edge_normal(k));
        let centre = v0 + (v1 - v0) * t + m * (r * (1.0 - depth));
        let disc = AnyShape2::Circle(Circle::new(r).unwrap());
        let pc = Pose2 { position: centre, angle: 0.4 };
        let points = manifold(&disc, &pc, &AnyShape2::Polygon(p), &pose);
        prop_assert_eq!(points.len(), 1);
        let on_wall = contact_2d(&disc, &pc, &AnyShape2::Segment(Segment::new(v1, v0)), &Pose2::default()).unwrap().unwrap();
        let g = points[0];
        prop_assert_eq!(g.features, ContactFeatures { a: Feature::Whole, b: Feature::Edge(k) });
        prop_assert!((g.point - on_wall.point).norm() < 1e-12 && (g.normal - on_wall.normal).norm() < 1e-12);
        prop_assert!((g.overlap - on_wall.overlap).abs() < 1e-12 && (g.width - on_wall.width).abs() < 1e-9);
        prop_assert!(g.curvature_radius_a == on_wall.curvature_radius_a && g.curvature_radius_b == on_wall.curvature_radius_b);
    }

    #[test]
    fn ellipse_on_a_polygon_edge_is_the_ellipse_on_that_edge_as_a_wall(
        p in regular_polygon(1.0), x in -3.0f64..3.0, y in -3.0f64..3.0, phi in 0.0f64..6.3,
        edge in 0usize..8, t in 0.35f64..0.65, size in 0.05f64..0.15, aspect in 1.0f64..3.0,
        turn in 0.0f64..6.3, depth in 1e-4f64..0.05
    ) {
        let n = p.vertices().len();
        let k = edge % n;
        let pose = Pose2::new(x, y, phi);
        let (v0, v1) = (pose.transform_point(&p.vertices()[k]), pose.transform_point(&p.vertices()[(k + 1) % n]));
        let a_axis = size * (v1 - v0).norm();
        let e = Ellipse::new(a_axis, a_axis / aspect).unwrap();
        let m = pose.transform_vector(&p.edge_normal(k));
        // Reach of the ellipse (angle `turn`) towards the polygon.
        let out = rotate(&(-m), -turn);
        let reach = ((e.a() * out.x).powi(2) + (e.b() * out.y).powi(2)).sqrt();
        let pe = Pose2 { position: v0 + (v1 - v0) * t + m * (reach - depth * e.b()), angle: turn };
        let body = AnyShape2::Ellipse(e);
        let points = manifold(&body, &pe, &AnyShape2::Polygon(p), &pose);
        prop_assert_eq!(points.len(), 1);
        let on_wall = contact_2d(&body, &pe, &AnyShape2::Segment(Segment::new(v1, v0)), &Pose2::default()).unwrap().unwrap();
        let g = points[0];
        prop_assert_eq!(g.features, ContactFeatures { a: Feature::Whole, b: Feature::Edge(k) });
        prop_assert!((g.point - on_wall.point).norm() < 1e-12 && (g.normal - on_wall.normal).norm() < 1e-12);
        prop_assert!((g.overlap - on_wall.overlap).abs() < 1e-12 && (g.width - on_wall.width).abs() < 1e-12);
        prop_assert!((g.curvature_radius_a - on_wall.curvature_radius_a).abs() < 1e-12);
    }

    #[test]
    fn polygon_corner_in_an_ellipse_meets_its_nearest_boundary_point(
        b in 0.2f64..0.6, aspect in 1.0f64..3.0, phi in 0.0f64..6.3, t in 0.0f64..6.3, depth in 1e-4f64..0.05
    ) {
        // A diamond's lowest corner pushed into the ellipse along the
        // ellipse's normal at parameter t: the corner point's overlap is
        // the push and its normal the ellipse's.
        let e = Ellipse::new(b * aspect, b).unwrap();
        let pe = Pose2::new(0.0, 0.0, phi);
        let on = e.world_point(&pe, t);
        let normal = pe.transform_vector(&e.outward_normal(&e.local_point(t)));
        let push = depth * b * b / e.a();
        let corner = on - normal * push;
        // A small sharp diamond pointing along −normal, so only its tip enters.
        let s = 0.3 * b;
        let axis_angle = normal.y.atan2(normal.x);
        let diamond = [(0.0, 0.0), (s, -0.3 * s), (2.0 * s, 0.0), (s, 0.3 * s)]
            .map(|(u, w)| corner + rotate(&Vec2::new(u, w), axis_angle));
        let (poly, centroid) = Polygon::from_world(&diamond, 0).unwrap();
        let points = manifold(&AnyShape2::Ellipse(e), &pe, &AnyShape2::Polygon(poly), &Pose2::new(centroid.x, centroid.y, 0.0));
        prop_assert_eq!(points.len(), 1, "{:?}", points);
        let g = points[0];
        prop_assert_eq!(g.features, ContactFeatures { a: Feature::Whole, b: Feature::Vertex(0) });
        prop_assert!((g.overlap - push).abs() < 1e-9 * b, "{} vs {}", g.overlap, push);
        prop_assert!((g.normal - normal).norm() < 1e-6);
    }
}
