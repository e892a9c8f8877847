//! Body kinematics: the affine map is DDA's displacement field, its mass
//! and stiffness are DDA's bit for bit, its geometry update is DDA's with
//! the rotation made exact (a turning body keeps its area), the rigid map's
//! mass gives a disc's exact kinetic energy, and the map derivatives are
//! the finite differences of the map parameters.

use crate::dda_common;

use dda_common::material;
use dismech::dda::Block;
use dismech::kinematics::{
    Advance, Affine2, AreaMoments, Kinematics, PlacedEllipse, PlacedPolygon, Rigid2,
};
use dismech::math::{Point, Vec2};
use dismech::shape::{Polygon, Shape};
use nalgebra::{Matrix2, SVector};
use proptest::prelude::*;

/// Classic DDA's block matrices and update (paper 003 eqs. 14–16), written
/// directly: the reference the affine kinematics must reproduce.
mod classic_dda {
    use dismech::math::Point;
    use dismech::shape::{Polygon, Shape};
    use nalgebra::{Matrix3, SMatrix, SVector};

    /// `ρ ∫ TᵀT dA` with `T = T₀ + x Tx + y Ty` about the centroid.
    pub fn mass(polygon: &Polygon, density: f64) -> SMatrix<f64, 6, 6> {
        let t0 = Polygon::dda_displacement_matrix(0.0, 0.0);
        let tx = Polygon::dda_displacement_matrix(1.0, 0.0) - t0;
        let ty = Polygon::dda_displacement_matrix(0.0, 1.0) - t0;
        let [ixx, iyy, ixy] = polygon.second_moments();
        let m = t0.transpose() * t0 * polygon.measure()
            + tx.transpose() * tx * ixx
            + ty.transpose() * ty * iyy
            + (tx.transpose() * ty + ty.transpose() * tx) * ixy;
        m * density
    }

    /// `A D` on the strain unknowns.
    pub fn stiffness(polygon: &Polygon, elastic: &Matrix3<f64>) -> SMatrix<f64, 6, 6> {
        let mut k = SMatrix::<f64, 6, 6>::zeros();
        k.fixed_view_mut::<3, 3>(3, 3)
            .copy_from(&(elastic * polygon.measure()));
        k
    }

    /// Vertices moved by `T(x − c) d` (eq. 14), the polygon rebuilt.
    pub fn apply_increment(
        polygon: &Polygon,
        centroid: Point,
        d: &SVector<f64, 6>,
    ) -> (Polygon, Point) {
        let moved: Vec<Point> = polygon
            .vertices()
            .iter()
            .map(|v| {
                let q = centroid + v.coords;
                q + Polygon::dda_displacement_matrix(q.x - centroid.x, q.y - centroid.y) * d
            })
            .collect();
        Polygon::from_world(&moved, 0).unwrap()
    }
}

/// A convex quadrilateral: a rectangle `w × h` turned by `turn`, one corner
/// pulled by `skew`, placed at `(x, y)`.
fn quad(w: f64, h: f64, turn: f64, skew: f64, x: f64, y: f64) -> Vec<Point> {
    let (s, c) = turn.sin_cos();
    [(0.0, 0.0), (w, 0.0), (w + skew, h), (0.0, h)]
        .iter()
        .map(|&(u, v)| Point::new(x + c * u - s * v, y + s * u + c * v))
        .collect()
}

fn dofs<const N: usize>(v: &[f64]) -> SVector<f64, N> {
    SVector::<f64, N>::from_column_slice(&v[..N])
}

/// Three-point Gauss–Legendre nodes and weights on [0, 1].
const GAUSS3: [(f64, f64); 3] = [
    (0.112_701_665_379_258_31, 5.0 / 18.0),
    (0.5, 8.0 / 18.0),
    (0.887_298_334_620_741_7, 5.0 / 18.0),
];

/// `½ ρ ∫ |∂x/∂d ḋ|² dA` over a disc of radius `r` centred on the reference
/// point, exact for the quadratic integrand (Gauss in r, 8 angles).
fn disc_kinetic_energy<K: Kinematics<N>, const N: usize>(
    k: &K,
    r: f64,
    rho: f64,
    d: &SVector<f64, N>,
    rate: &SVector<f64, N>,
) -> f64 {
    let mut sum = 0.0;
    for &(s, w) in &GAUSS3 {
        for j in 0..8 {
            let phi = j as f64 * std::f64::consts::TAU / 8.0;
            let offset = Vec2::new(phi.cos(), phi.sin()) * (s * r);
            let v = k.point_jacobian(d, &offset) * rate;
            // dA = ρ' dρ' dφ with ρ' = s r.
            sum += w * r * (s * r) * (std::f64::consts::TAU / 8.0) * v.norm_squared();
        }
    }
    0.5 * rho * sum
}

proptest! {
    /// `c + t + F (X − c)` is DDA's `X + T(X − c) d` (eq. 14), and `∂x/∂d`
    /// is `T(X − c)` (eq. 15) exactly.
    #[test]
    fn affine_map_is_the_dda_displacement_field(
        d in proptest::collection::vec(-0.1f64..0.1, 6),
        c in proptest::collection::vec(-5.0f64..5.0, 2),
        x in proptest::collection::vec(-5.0f64..5.0, 2),
    ) {
        let d = dofs::<6>(&d);
        let (c, x) = (Point::new(c[0], c[1]), Point::new(x[0], x[1]));
        let t = Polygon::dda_displacement_matrix(x.x - c.x, x.y - c.y);
        let dda = x + t * d;
        let moved = Affine2.map(&d).apply(&c, &x);
        prop_assert!((moved - dda).norm() <= 1e-14 * (1.0 + x.coords.norm()));
        prop_assert_eq!(Affine2.point_jacobian(&d, &(x - c)), t);
    }

    /// Mass and stiffness of an affine polygon are those of classic DDA's
    /// block (eqs. 14–16 written directly), bit for bit; its committed
    /// update is classic DDA's vertex update with the rotation made exact:
    /// `c + t + R(r₀)(I + E)(X − c)`, which differs from `X + T(X − c) d`
    /// by second-order terms only (`|R(r₀) − I − r₀ J| ≤ r₀²/2`, and `r₀ E`).
    #[test]
    fn affine_polygon_is_a_dda_block_with_an_exact_rotation(
        w in 0.5f64..3.0, h in 0.5f64..3.0, turn in -1.0f64..1.0, skew in -0.3f64..0.3,
        x in -10.0f64..10.0, y in -10.0f64..10.0,
        d in proptest::collection::vec(-0.01f64..0.01, 6),
    ) {
        let vertices = quad(w, h, turn, skew, x, y);
        let block = Block::new(&vertices, material(), 0).unwrap();
        let placed = PlacedPolygon::from_world(&vertices, 0).unwrap();
        prop_assert_eq!(placed.centroid(), block.centroid());
        let moments = placed.moments();
        let (polygon, centroid) = Polygon::from_world(&vertices, 0).unwrap();
        prop_assert_eq!(Affine2.mass(&moments, material().density), classic_dda::mass(&polygon, material().density));
        let elastic = material().elastic_matrix();
        prop_assert_eq!(Affine2.stiffness(&moments, &elastic), classic_dda::stiffness(&polygon, &elastic));
        let d = dofs::<6>(&d);
        let moved = Affine2.advance(&placed, &d, 0).unwrap();
        let (moved_polygon, moved_centroid) = classic_dda::apply_increment(&polygon, centroid, &d);
        let (r0, strain) = (d[2].abs(), d[3].abs().max(d[4].abs()).max(0.5 * d[5].abs()));
        let map = Affine2.committed_map(&d);
        for k in 0..4 {
            let start = placed.vertex(k);
            let arm = (start - centroid).norm();
            prop_assert!((moved.vertex(k) - map.apply(&centroid, &start)).norm() <= 1e-13 * (1.0 + start.coords.norm()));
            let classic = moved_centroid + moved_polygon.vertices()[k].coords;
            let second_order = (0.5 * r0 * r0 + 2.0 * r0 * strain) * arm;
            prop_assert!((moved.vertex(k) - classic).norm() <= second_order * 1.01 + 1e-13 * (1.0 + start.coords.norm()));
        }
    }

    /// A pure rotation of an affine polygon keeps its shape and area to
    /// round-off, where classic DDA's first-order update grows the area by
    /// `r₀²`.
    #[test]
    fn a_turning_affine_polygon_keeps_its_area(
        w in 0.5f64..3.0, h in 0.5f64..3.0, turn in -1.0f64..1.0, skew in -0.3f64..0.3,
        r0 in -0.05f64..0.05, t in proptest::collection::vec(-0.1f64..0.1, 2),
    ) {
        let vertices = quad(w, h, turn, skew, 0.5, -0.3);
        let placed = PlacedPolygon::from_world(&vertices, 0).unwrap();
        let d = SVector::<f64, 6>::from_column_slice(&[t[0], t[1], r0, 0.0, 0.0, 0.0]);
        let area = placed.moments().area;
        let moved = Affine2.advance(&placed, &d, 0).unwrap().moments().area;
        prop_assert!((moved / area - 1.0).abs() <= 1e-13, "{}", moved / area - 1.0);
        let (polygon, centroid) = Polygon::from_world(&vertices, 0).unwrap();
        let (classic, _) = classic_dda::apply_increment(&polygon, centroid, &d);
        let grown = classic.measure() / area - 1.0;
        prop_assert!((grown - r0 * r0).abs() <= 1e-12 + 1e-9 * r0 * r0, "{} vs {}", grown, r0 * r0);
    }

    /// Under the affine map a circle becomes the ellipse with matrix
    /// `F M Fᵀ`: the mapped boundary points lie on it.
    #[test]
    fn affine_map_turns_a_circle_into_the_ellipse_f_m_ft(
        r in 0.1f64..2.0, d in proptest::collection::vec(-0.2f64..0.2, 6),
    ) {
        let centre = Point::new(1.0, -2.0);
        let circle = PlacedEllipse::circle(centre, r).unwrap();
        let d = dofs::<6>(&d);
        let moved = Affine2.advance(&circle, &d, 0).unwrap();
        let map = Affine2.committed_map(&d);
        let expected = map.gradient * circle.matrix() * map.gradient.transpose();
        prop_assert!((moved.matrix() - expected).norm() <= 1e-14 * r * r);
        let inverse = moved.matrix().try_inverse().unwrap();
        for k in 0..16 {
            let t = k as f64 * std::f64::consts::TAU / 16.0;
            let x = map.apply(&centre, &(centre + Vec2::new(t.cos(), t.sin()) * r));
            let q = x - moved.centre();
            prop_assert!(((q.transpose() * inverse * q)[0] - 1.0).abs() < 1e-12);
        }
    }

    /// `½ ḋᵀ M ḋ` is the kinetic energy `½ ρ ∫ |ẋ|² dA` of a disc, for the
    /// rigid map at any angle and for the affine map.
    #[test]
    fn mass_gives_the_kinetic_energy_of_a_disc(
        r in 0.1f64..2.0, rho in 100.0f64..5000.0,
        d in proptest::collection::vec(-3.0f64..3.0, 6),
        rate in proptest::collection::vec(-1.0f64..1.0, 6),
    ) {
        let moments = PlacedEllipse::circle(Point::origin(), r).unwrap().moments();
        let (d3, v3) = (dofs::<3>(&d), dofs::<3>(&rate));
        let m3 = Rigid2.mass(&moments, rho);
        let exact = disc_kinetic_energy(&Rigid2, r, rho, &d3, &v3);
        prop_assert!((0.5 * (v3.transpose() * m3 * v3)[0] - exact).abs() <= 1e-12 * exact.max(1e-300));
        let (d6, v6) = (dofs::<6>(&d) * 0.01, dofs::<6>(&rate));
        let m6 = Affine2.mass(&moments, rho);
        let exact = disc_kinetic_energy(&Affine2, r, rho, &d6, &v6);
        prop_assert!((0.5 * (v6.transpose() * m6 * v6)[0] - exact).abs() <= 1e-12 * exact.max(1e-300));
    }

    /// `P = ∂Δp/∂d` and `Σ w_k ∂²Δp_k/∂d²` are the finite differences of
    /// the map parameters.
    #[test]
    fn map_derivatives_match_finite_differences(
        d in proptest::collection::vec(-3.0f64..3.0, 6),
        w in proptest::collection::vec(-1.0f64..1.0, 6),
    ) {
        let w = dofs::<6>(&w);
        fn check<K: Kinematics<N>, const N: usize>(k: &K, d: SVector<f64, N>, w: &SVector<f64, 6>) -> Result<(), TestCaseError> {
            let h = 1e-6;
            let p = k.map_jacobian(&d);
            let curvature = k.map_curvature(&d, w);
            for i in 0..N {
                let mut e = SVector::<f64, N>::zeros();
                e[i] = h;
                let fd = (k.map_parameters(&(d + e)) - k.map_parameters(&(d - e))) / (2.0 * h);
                prop_assert!((fd - p.column(i)).norm() < 1e-9);
                let fd = (k.map_jacobian(&(d + e)) - k.map_jacobian(&(d - e))).transpose() * w / (2.0 * h);
                prop_assert!((fd - curvature.column(i)).norm() < 1e-9);
            }
            Ok(())
        }
        check(&Rigid2, dofs::<3>(d.as_slice()), &w)?;
        check(&Affine2, dofs::<6>(d.as_slice()), &w)?;
    }
}

#[test]
fn rigid_mass_is_diagonal_with_the_polar_moment() {
    let moments = AreaMoments::new(2.0, [0.5, 0.25, 0.1]);
    let m = Rigid2.mass(&moments, 3.0);
    assert_eq!(
        m,
        nalgebra::Matrix3::from_diagonal(&nalgebra::Vector3::new(6.0, 6.0, 2.25))
    );
    assert_eq!(
        Rigid2.stiffness(&moments, &nalgebra::Matrix3::identity()),
        nalgebra::Matrix3::zeros()
    );
}

#[test]
fn rigid_advance_keeps_an_ellipse_and_a_polygon_congruent() {
    let e = PlacedEllipse::new(Point::new(1.0, 2.0), Matrix2::new(2.0, 0.0, 0.0, 0.5)).unwrap();
    let d = SVector::<f64, 3>::new(0.3, -0.2, 0.9);
    let moved = Rigid2.advance(&e, &d, 0).unwrap();
    approx::assert_relative_eq!(moved.centre(), Point::new(1.3, 1.8), epsilon = 1e-15);
    let (m0, m1) = (e.matrix(), moved.matrix());
    approx::assert_relative_eq!(m0.trace(), m1.trace(), max_relative = 1e-14);
    approx::assert_relative_eq!(m0.determinant(), m1.determinant(), max_relative = 1e-14);
    let p = PlacedPolygon::from_world(&quad(2.0, 1.0, 0.3, 0.2, 4.0, -1.0), 0).unwrap();
    let q = Rigid2.advance(&p, &d, 0).unwrap();
    approx::assert_relative_eq!(
        q.centroid(),
        p.centroid() + Vec2::new(0.3, -0.2),
        epsilon = 1e-13
    );
    for k in 0..4 {
        let (a, b) = (p.vertex(k + 1) - p.vertex(k), q.vertex(k + 1) - q.vertex(k));
        approx::assert_relative_eq!(b, Rigid2::rotation(0.9) * a, epsilon = 1e-13);
    }
}
