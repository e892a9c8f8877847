//! Gap and shear variations of the implicit pair queries: every gradient
//! and Hessian against central finite differences, in the map parameters
//! and in the unknowns of rigid, affine and fixed bodies; exact gaps of
//! circles; DDA's vertex–edge contact to round-off, and its gap on a
//! long edge to round-off of the gap itself.

use crate::dda_common;

use crate::variation_common;

use dda_common::material;
use dismech::dda::Block;
use dismech::kinematics::{
    Affine2, Fixed, Kinematics, MapVector, PlacedEllipse, PlacedPolygon, Rigid2,
};
use dismech::math::{Point, Vec2};
use dismech::query::variation::{
    entrance_edges, local_geometry, DofVariation, GapVariation, MapVariation, PolygonCorner,
    SmoothEdgeContact, SmoothSide, SmoothSmoothContact, VertexEdgeContact,
};
use nalgebra::{DMatrix, DVector, SVector};
use proptest::prelude::*;
use variation_common::{ellipse, point, smooth_edge, vertex_edge};

// ---------------------------------------------------------------- helpers

/// Gap, shear and their variations flattened over `n` variables.
struct Flat {
    gap: f64,
    shear: f64,
    grad: [DVector<f64>; 2],
    hess: [DMatrix<f64>; 2],
}

fn flat_map(v: &MapVariation) -> Flat {
    let d = |g: &SVector<f64, 12>| DVector::from_column_slice(g.as_slice());
    let m = |h: &nalgebra::SMatrix<f64, 12, 12>| DMatrix::from_column_slice(12, 12, h.as_slice());
    Flat {
        gap: v.gap,
        shear: v.shear,
        grad: [d(&v.grad_gap), d(&v.grad_shear)],
        hess: [m(&v.hess_gap), m(&v.hess_shear)],
    }
}

fn flat_dofs<const NA: usize, const NB: usize>(v: &DofVariation<NA, NB>) -> Flat {
    let n = NA + NB;
    let grad = |g: &dismech::query::variation::PairVector<NA, NB>| {
        DVector::from_iterator(n, g.a.iter().chain(g.b.iter()).copied())
    };
    let hess = |h: &dismech::query::variation::PairMatrix<NA, NB>| {
        let mut m = DMatrix::zeros(n, n);
        m.view_mut((0, 0), (NA, NA)).copy_from(&h.aa);
        m.view_mut((0, NA), (NA, NB)).copy_from(&h.ab);
        m.view_mut((NA, 0), (NB, NA)).copy_from(&h.ba);
        m.view_mut((NA, NA), (NB, NB)).copy_from(&h.bb);
        m
    };
    Flat {
        gap: v.gap,
        shear: v.shear,
        grad: [grad(&v.grad_gap), grad(&v.grad_shear)],
        hess: [hess(&v.hess_gap), hess(&v.hess_shear)],
    }
}

/// Central differences of `f` at `x` against its gradients and Hessians.
fn check_fd(
    f: impl Fn(&DVector<f64>) -> Flat,
    x: DVector<f64>,
    tol: f64,
) -> Result<(), TestCaseError> {
    let h = 1e-6;
    let at = f(&x);
    for i in 0..x.len() {
        let mut e = DVector::zeros(x.len());
        e[i] = h;
        let (p, m) = (f(&(&x + &e)), f(&(&x - &e)));
        for (k, (vp, vm)) in [(p.gap, m.gap), (p.shear, m.shear)].into_iter().enumerate() {
            let fd = (vp - vm) / (2.0 * h);
            let g = at.grad[k][i];
            prop_assert!(
                (fd - g).abs() <= tol * (1.0 + g.abs()),
                "grad {} [{}]: fd {} vs {}",
                k,
                i,
                fd,
                g
            );
            for j in 0..x.len() {
                let fd = (p.grad[k][j] - m.grad[k][j]) / (2.0 * h);
                let hh = at.hess[k][(j, i)];
                prop_assert!(
                    (fd - hh).abs() <= 10.0 * tol * (1.0 + hh.abs()),
                    "hess {} [{},{}]: fd {} vs {}",
                    k,
                    j,
                    i,
                    fd,
                    hh
                );
            }
        }
    }
    Ok(())
}

/// Finite-difference check in the 12 map parameters.
fn check_map<const M: usize>(
    q: &impl GapVariation<M>,
    p: &[f64],
    tol: f64,
) -> Result<(), TestCaseError> {
    let split = |x: &DVector<f64>| {
        (
            MapVector::from_column_slice(&x.as_slice()[0..6]),
            MapVector::from_column_slice(&x.as_slice()[6..12]),
        )
    };
    check_fd(
        |x| {
            let (a, b) = split(x);
            flat_map(&q.map_variation(&a, &b).unwrap())
        },
        DVector::from_column_slice(p),
        tol,
    )
}

/// Finite-difference check in the unknowns of two bodies.
fn check_dofs<const M: usize, KA, KB, const NA: usize, const NB: usize>(
    q: &impl GapVariation<M>,
    ka: &KA,
    kb: &KB,
    d: &[f64],
    tol: f64,
) -> Result<(), TestCaseError>
where
    KA: Kinematics<NA>,
    KB: Kinematics<NB>,
{
    check_fd(
        |x| {
            let a = SVector::<f64, NA>::from_column_slice(&x.as_slice()[..NA]);
            let b = SVector::<f64, NB>::from_column_slice(&x.as_slice()[NA..NA + NB]);
            flat_dofs(&q.dof_variation(ka, &a, kb, &b).unwrap())
        },
        DVector::from_column_slice(&d[..NA + NB]),
        tol,
    )
}

/// The derivative checks of one contact in the map parameters and in the
/// unknowns of every pairing of kinematics.
fn check_all<const M: usize>(
    q: &impl GapVariation<M>,
    p: &[f64],
    tol: f64,
) -> Result<(), TestCaseError> {
    check_map(q, p, tol)?;
    // Rotations up to ~0.6 rad for rigid bodies, small strains for affine ones.
    let rigid: Vec<f64> = p.iter().map(|v| 10.0 * v).collect();
    check_dofs(q, &Rigid2, &Rigid2, &rigid, tol)?;
    check_dofs(q, &Affine2, &Affine2, p, tol)?;
    let mixed: Vec<f64> = rigid[..3].iter().chain(&p[3..9]).copied().collect();
    check_dofs(q, &Rigid2, &Affine2, &mixed, tol)?;
    check_dofs(q, &Affine2, &Fixed, p, tol)?;
    Ok(())
}

// ---------------------------------------------------- finite differences

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Vertex–edge: gradients and Hessians in p and in d (rigid, affine,
    /// mixed, against a fixed body) are the finite differences.
    #[test]
    fn vertex_edge_variations_match_finite_differences(
        geometry in proptest::collection::vec(-1.0f64..1.0, 11),
        p in proptest::collection::vec(-0.05f64..0.05, 12),
    ) {
        check_all(&vertex_edge(&geometry), &p, 1e-6)?;
    }

    /// Smooth–edge (ellipse, circle and point sides).
    #[test]
    fn smooth_edge_variations_match_finite_differences(
        geometry in proptest::collection::vec(-1.0f64..1.0, 11),
        centre in proptest::collection::vec(-1.0f64..1.0, 2),
        reference in proptest::collection::vec(-0.3f64..0.3, 2),
        a in 0.2f64..1.0, ratio in 0.25f64..1.0, phi in -3.0f64..3.0,
        p in proptest::collection::vec(-0.05f64..0.05, 12),
    ) {
        let mut side = ellipse(point(&centre) + Vec2::new(0.0, 2.0), a, a * ratio, phi);
        check_all(&smooth_edge(&geometry, side), &p, 1e-6)?;
        side.reference += Vec2::new(reference[0], reference[1]);
        check_all(&smooth_edge(&geometry, side), &p, 1e-6)?;
        let point_side = SmoothSide::vertex(side.centre, side.reference);
        check_all(&smooth_edge(&geometry, point_side), &p, 1e-6)?;
    }

    /// Smooth–smooth: ellipse pairs, apart or overlapping, and a vertex
    /// against an ellipse.
    #[test]
    fn smooth_smooth_variations_match_finite_differences(
        a in (0.2f64..1.0, 0.25f64..1.0, -3.0f64..3.0),
        b in (0.2f64..1.0, 0.25f64..1.0, -3.0f64..3.0),
        distance in 0.5f64..2.5, direction in -3.2f64..3.2,
        reference in proptest::collection::vec(-0.3f64..0.3, 2),
        p in proptest::collection::vec(-0.05f64..0.05, 12),
    ) {
        let side_a = ellipse(Point::origin(), a.0, a.0 * a.1, a.2);
        let mut side_b = ellipse(Point::new(direction.cos(), direction.sin()) * (distance * (a.0 + b.0)), b.0, b.0 * b.1, b.2);
        side_b.reference += Vec2::new(reference[0], reference[1]);
        let contact = SmoothSmoothContact::detect(&side_a, &side_b, f64::INFINITY, None).unwrap().unwrap();
        check_all(&contact, &p, 1e-6)?;
        let vertex = SmoothSide::vertex(side_b.centre, side_b.reference);
        let contact = SmoothSmoothContact::detect(&side_a, &vertex, f64::INFINITY, None).unwrap().unwrap();
        check_all(&contact, &p, 1e-6)?;
    }
}

// --------------------------------------------------------------- DDA

/// The two blocks of the DDA derivative test: a slab and a tilted block
/// above it, with the upper block's lowest vertex.
fn dda_pair(dx: f64, gap: f64, tilt: f64) -> (Vec<Block>, usize) {
    let slab = [(-1.0, -0.5), (1.0, -0.5), (1.0, 0.0), (-1.0, 0.0)].map(|(x, y)| Point::new(x, y));
    let lower = Block::new(&slab, material(), 0).unwrap();
    let (c, s) = (tilt.cos(), tilt.sin());
    let corners: Vec<Point> = [(-0.3, 0.0), (0.3, 0.0), (0.3, 0.4), (-0.3, 0.4)]
        .iter()
        .map(|&(x, y)| Point::new(dx + c * x - s * y, gap + s * x + c * y + 0.3 * tilt.abs()))
        .collect();
    let upper = Block::new(&corners, material(), 1).unwrap();
    let vertex = (0..4).fold(0, |b, v| {
        if upper.vertex(v).y < upper.vertex(b).y {
            v
        } else {
            b
        }
    });
    (vec![lower, upper], vertex)
}

fn placed(block: &Block) -> PlacedPolygon {
    block.polygon().unwrap().clone()
}

/// Classic DDA's vertex–edge contact written directly (paper 003 eqs.
/// 17–35): detection over the edges of block k, and `g_n`, `g_s` with their
/// variations in the twelve unknowns through the chain of the displacement
/// matrices `T` (eq. 15) at the three points. The reference the generic
/// query must reproduce to round-off.
mod classic_dda {
    use super::*;
    use dismech::query::variation::local_geometry;
    use dismech::shape::Polygon;
    use nalgebra::{SMatrix, Vector2};

    pub type Grad12 = SVector<f64, 12>;
    pub type Hess12 = SMatrix<f64, 12, 12>;

    /// `T(p − c)` of a block.
    fn t(block: &Block, p: &Point) -> SMatrix<f64, 2, 6> {
        let c = block.centroid();
        Polygon::dda_displacement_matrix(p.x - c.x, p.y - c.y)
    }

    /// The candidate edge of block `k` for vertex `p`: `(edge, ξ, g_n)`.
    pub fn closest_edge(
        p: &Point,
        k: &Block,
        search: f64,
        previous: Option<usize>,
    ) -> Option<(usize, f64, f64)> {
        let mut best: Option<(usize, f64, f64)> = None;
        for e in 0..k.vertex_count() {
            let (x2, x3) = (k.vertex(e), k.vertex(e + 1));
            let (a, b) = (p - x2, x3 - x2);
            let l2 = b.norm_squared();
            let xi = a.dot(&b) / l2;
            let gap = dismech::math::cross(&a, &b) / l2.sqrt();
            if !(0.0..=1.0).contains(&xi) || gap.abs() > search {
                continue;
            }
            if previous == Some(e) {
                return Some((e, xi, gap));
            }
            if best.is_none_or(|(_, _, g)| gap > g) {
                best = Some((e, xi, gap));
            }
        }
        best
    }

    /// `(g_n, g_s, ∇g_n, ∇g_s, ∇²g_n, ∇²g_s)` in `(d_j, d_k)` for vertex
    /// `vertex` of block j = 1 against edge `edge` of block k = 0.
    #[allow(clippy::type_complexity)]
    pub fn kinematics(
        blocks: &[Block],
        vertex: usize,
        edge: usize,
        xi: f64,
        d_j: &SVector<f64, 6>,
        d_k: &SVector<f64, 6>,
    ) -> (f64, f64, Grad12, Grad12, Hess12, Hess12) {
        let (bj, bk) = (&blocks[1], &blocks[0]);
        let (x1, x2, x3) = (bj.vertex(vertex), bk.vertex(edge), bk.vertex(edge + 1));
        let (t1, t2, t3) = (t(bj, &x1), t(bk, &x2), t(bk, &x3));
        let mut c = SMatrix::<f64, 4, 12>::zeros();
        c.fixed_view_mut::<2, 6>(0, 0).copy_from(&t1);
        c.fixed_view_mut::<2, 6>(0, 6).copy_from(&(-t2));
        c.fixed_view_mut::<2, 6>(2, 6).copy_from(&(t3 - t2));
        let mut d = Grad12::zeros();
        d.fixed_rows_mut::<6>(0).copy_from(d_j);
        d.fixed_rows_mut::<6>(6).copy_from(d_k);
        let delta = c * d;
        let a = (x1 - x2) + Vector2::new(delta[0], delta[1]);
        let b = (x3 - x2) + Vector2::new(delta[2], delta[3]);
        let g = local_geometry(&a, &b, xi);
        let ct = c.transpose();
        (
            g.gap,
            g.shear,
            ct * g.grad_gap,
            ct * g.grad_shear,
            ct * g.hess_gap * c,
            ct * g.hess_shear * c,
        )
    }
}

/// `|x − y| ≤ tol (1 + |y|)`, entry by entry.
fn close<const R: usize, const C: usize>(
    x: &nalgebra::SMatrix<f64, R, C>,
    y: &nalgebra::SMatrix<f64, R, C>,
    tol: f64,
) -> bool {
    x.iter()
        .zip(y.iter())
        .all(|(a, b)| (a - b).abs() <= tol * (1.0 + b.abs()))
}

proptest! {
    /// The affine vertex–edge contact is classic DDA's contact (eqs. 17–35
    /// through the T matrices of eq. 15) to round-off (values, gradients,
    /// Hessians: it measures the vertex from the foot of the perpendicular
    /// rather than from the edge's start, so the last bits differ), and
    /// its detection is DDA's rule away from the corners (the slab's
    /// corners are 0.5 m or more from the vertex here).
    #[test]
    fn affine_vertex_edge_is_the_dda_contact_to_round_off(
        dx in -0.2f64..0.2, gap in -0.01f64..0.01, tilt in -0.3f64..0.3,
        d in proptest::collection::vec(-0.01f64..0.01, 12),
        previous in proptest::option::of(0usize..4),
    ) {
        let (blocks, vertex) = dda_pair(dx, gap, tilt);
        let p1 = blocks[1].vertex(vertex);
        let dda = classic_dda::closest_edge(&p1, &blocks[0], 0.05, previous);
        let corner = PolygonCorner::of(&placed(&blocks[1]), vertex);
        let met = entrance_edges(&corner, blocks[1].centroid(), &placed(&blocks[0]), 0.05, previous);
        prop_assert!(met.len() <= 1);
        let ours = met.first().copied();
        prop_assert_eq!(dda, ours.map(|(e, c)| (e, c.xi, c.initial_gap)));
        let Some((edge, contact)) = ours else { return Ok(()) };
        let (dj, dk) = (SVector::<f64, 6>::from_column_slice(&d[0..6]), SVector::<f64, 6>::from_column_slice(&d[6..12]));
        let (gap, shear, grad_gap, grad_shear, hess_gap, hess_shear) =
            classic_dda::kinematics(&blocks, vertex, edge, contact.xi, &dj, &dk);
        let v = contact.dof_variation(&Affine2, &dj, &Affine2, &dk).unwrap();
        let tol = 1e-12;
        prop_assert!((gap - v.gap).abs() <= 1e-15 && (shear - v.shear).abs() <= 1e-15, "{} {} vs {} {}", gap, shear, v.gap, v.shear);
        for (g12, g) in [(&grad_gap, &v.grad_gap), (&grad_shear, &v.grad_shear)] {
            prop_assert!(close(&g12.fixed_rows::<6>(0).into_owned(), &g.a, tol));
            prop_assert!(close(&g12.fixed_rows::<6>(6).into_owned(), &g.b, tol));
        }
        for (h12, h) in [(&hess_gap, &v.hess_gap), (&hess_shear, &v.hess_shear)] {
            prop_assert!(close(&h12.fixed_view::<6, 6>(0, 0).into_owned(), &h.aa, tol));
            prop_assert!(close(&h12.fixed_view::<6, 6>(0, 6).into_owned(), &h.ab, tol));
            prop_assert!(close(&h12.fixed_view::<6, 6>(6, 0).into_owned(), &h.ba, tol));
            prop_assert!(close(&h12.fixed_view::<6, 6>(6, 6).into_owned(), &h.bb, tol));
        }
    }

    /// On a long edge the gap is resolved to the round-off of its own size,
    /// not of the edge's: a vertex 1 mm above a 60 m incline, near its far
    /// end, moved 1 nm along the normal, changes its gap by 1 nm to 1e-9
    /// (measured from the edge's start, the round-off of `a × b / l` is
    /// about 1e-14 m, a hundredth of a percent of the nanometre).
    #[test]
    fn the_gap_on_a_long_edge_is_resolved_to_round_off(
        slope in 0.05f64..0.6, along in 0.8f64..0.99, height in 1e-4f64..1e-2,
    ) {
        let (c, s) = (1.0 / (1.0 + slope * slope).sqrt(), slope / (1.0 + slope * slope).sqrt());
        let (tau, n) = (Vec2::new(c, s), Vec2::new(-s, c));
        // B below the incline: its top edge runs right to left.
        let (start, end) = (Point::new(60.0 * c, 60.0 * s), Point::origin());
        let vertex = Point::origin() + tau * (60.0 * along) + n * height;
        let contact = VertexEdgeContact::detect(vertex, vertex, [start, end], Point::new(30.0 * c, 30.0 * s - 1.0), 0.05).unwrap();
        let step = 1e-9;
        let d_a = SVector::<f64, 3>::new(n.x * step, n.y * step, 0.0);
        let moved = contact.dof_variation(&Rigid2, &d_a, &Rigid2, &SVector::<f64, 3>::zeros()).unwrap();
        let rest = contact.dof_variation(&Rigid2, &SVector::<f64, 3>::zeros(), &Rigid2, &SVector::<f64, 3>::zeros()).unwrap();
        let change = moved.gap - rest.gap;
        // The same from the edge's start, for the record.
        let from_start = |p: Point| local_geometry(&(p - start), &(end - start), 0.0).gap;
        let classic = from_start(vertex + n * step) - from_start(vertex);
        println!("slope {slope:.3}: from the foot {:.2e}, from the start {:.2e}", (change - step).abs() / step, (classic - step).abs() / step);
        prop_assert!((change - step).abs() <= 1e-8 * step, "gap change {change:e} for a move of {step:e}");
    }
}

// ------------------------------------------------------ exact values

/// Rigid increments of two bodies from six numbers.
fn rigid(v: &[f64]) -> (SVector<f64, 3>, SVector<f64, 3>) {
    (
        SVector::<f64, 3>::from_column_slice(&v[0..3]),
        SVector::<f64, 3>::from_column_slice(&v[3..6]),
    )
}

proptest! {
    /// Two circles under rigid motion: `g = |c_B − c_A| − r_A − r_B`.
    #[test]
    fn circle_circle_gap_is_the_centre_distance_minus_the_radii(
        ra in 0.1f64..1.0, rb in 0.1f64..1.0, distance in 0.3f64..2.0, direction in -3.2f64..3.2,
        d in proptest::collection::vec(-0.5f64..0.5, 6),
    ) {
        let (ca, cb) = (Point::new(0.3, -0.2), Point::new(0.3, -0.2) + Vec2::new(direction.cos(), direction.sin()) * (distance * (ra + rb)));
        let a = SmoothSide::ellipse(&PlacedEllipse::circle(ca, ra).unwrap());
        let b = SmoothSide::ellipse(&PlacedEllipse::circle(cb, rb).unwrap());
        let contact = SmoothSmoothContact::detect(&a, &b, f64::INFINITY, None).unwrap().unwrap();
        let (da, db) = rigid(&d);
        let v = contact.dof_variation(&Rigid2, &da, &Rigid2, &db).unwrap();
        let (xa, xb) = (ca + Vec2::new(da[0], da[1]), cb + Vec2::new(db[0], db[1]));
        let exact = (xb - xa).norm() - ra - rb;
        prop_assert!((v.gap - exact).abs() <= 1e-14 * (1.0 + (xb - xa).norm()), "{} vs {}", v.gap, exact);
    }

    /// A circle against an edge is the vertex–edge contact of its centre
    /// minus r, in value and gradient, under any rigid motion; with pure
    /// translations the shear is the centre's too.
    #[test]
    fn smooth_edge_of_a_circle_is_the_vertex_edge_of_its_centre_minus_r(
        r in 0.1f64..1.0, x in -0.9f64..0.9, height in -0.2f64..0.5, slope in -0.5f64..0.5,
        d in proptest::collection::vec(-0.3f64..0.3, 6),
    ) {
        // B lies below the line y = slope x: its edge runs right to left,
        // so that the outward normal (right of the direction) points up.
        let edge = [Point::new(3.0, 3.0 * slope), Point::new(-3.0, -3.0 * slope)];
        let reference_b = Point::new(0.1, -0.7);
        let centre = Point::new(x, slope * x + r + height);
        let side = SmoothSide::ellipse(&PlacedEllipse::circle(centre, r).unwrap());
        let smooth = SmoothEdgeContact::detect(&side, edge, reference_b, f64::INFINITY).unwrap();
        let vertex = VertexEdgeContact::detect(centre, centre, edge, reference_b, f64::INFINITY).unwrap();
        prop_assert!((smooth.initial_gap - (vertex.initial_gap - r)).abs() < 1e-14);
        let (da, db) = rigid(&d);
        let (s, v) = (
            smooth.dof_variation(&Rigid2, &da, &Rigid2, &db).unwrap(),
            vertex.dof_variation(&Rigid2, &da, &Rigid2, &db).unwrap(),
        );
        prop_assert!((s.gap - (v.gap - r)).abs() < 1e-13);
        prop_assert!((s.grad_gap.a - v.grad_gap.a).norm() < 1e-13 && (s.grad_gap.b - v.grad_gap.b).norm() < 1e-13);
        let (ta, tb) = (SVector::<f64, 3>::new(d[0], d[1], 0.0), SVector::<f64, 3>::new(d[3], d[4], 0.0));
        let (s, v) = (
            smooth.dof_variation(&Rigid2, &ta, &Rigid2, &tb).unwrap(),
            vertex.dof_variation(&Rigid2, &ta, &Rigid2, &tb).unwrap(),
        );
        prop_assert!((s.shear - v.shear).abs() < 1e-13, "{} vs {}", s.shear, v.shear);
    }

    /// A point side against an edge is the vertex–edge contact, and a
    /// vertex against a circle is at `|x − c| − r`.
    #[test]
    fn point_sides_reduce_to_vertex_edge_and_to_point_distance(
        geometry in proptest::collection::vec(-1.0f64..1.0, 11),
        p in proptest::collection::vec(-0.05f64..0.05, 12),
        r in 0.1f64..1.0, distance in 0.2f64..2.0, direction in -3.2f64..3.2,
    ) {
        let ve = vertex_edge(&geometry);
        let mut se = smooth_edge(&geometry, SmoothSide::vertex(ve.vertex, ve.reference_a));
        se.material = ve.vertex;
        let (a, b) = (MapVector::from_column_slice(&p[0..6]), MapVector::from_column_slice(&p[6..12]));
        let (x, y) = (flat_map(&ve.map_variation(&a, &b).unwrap()), flat_map(&se.map_variation(&a, &b).unwrap()));
        prop_assert!((x.gap - y.gap).abs() < 1e-13 && (x.shear - y.shear).abs() < 1e-13);
        for k in 0..2 {
            prop_assert!((&x.grad[k] - &y.grad[k]).norm() < 1e-12 && (&x.hess[k] - &y.hess[k]).norm() < 1e-10);
        }
        let c = Point::new(0.2, 0.1);
        let circle = SmoothSide::ellipse(&PlacedEllipse::circle(c, r).unwrap());
        let v = c + Vec2::new(direction.cos(), direction.sin()) * (distance * r);
        let contact = SmoothSmoothContact::detect(&circle, &SmoothSide::vertex(v, Point::new(-1.0, 3.0)), f64::INFINITY, None).unwrap().unwrap();
        prop_assert!((contact.initial_gap - ((v - c).norm() - r)).abs() < 1e-14);
    }
}

#[test]
fn a_fixed_wall_carries_no_unknowns() {
    let wall = dismech::shape::Segment::new(Point::new(-2.0, 0.0), Point::new(2.0, 0.0));
    let edge = dismech::query::variation::wall_edge(&wall);
    let side = ellipse(Point::new(0.2, 0.31), 0.5, 0.3, 0.4);
    let contact = SmoothEdgeContact::detect(&side, edge, Point::origin(), 0.05).unwrap();
    assert!((contact.initial_gap - (0.31 - side.support(&Vec2::new(0.0, 1.0)))).abs() < 1e-15);
    let d = SVector::<f64, 3>::new(0.01, -0.02, 0.1);
    let v = contact
        .dof_variation(&Rigid2, &d, &Fixed, &SVector::<f64, 0>::zeros())
        .unwrap();
    let p = contact
        .map_variation(&Rigid2.map_parameters(&d), &MapVector::zeros())
        .unwrap();
    assert!((v.gap - p.gap).abs() < 1e-15 && (v.shear - p.shear).abs() < 1e-15);
    let jac = Rigid2.map_jacobian(&d);
    let grad = jac.transpose() * p.grad_gap.fixed_rows::<6>(0);
    assert!((v.grad_gap.a - grad).norm() < 1e-14);
}
