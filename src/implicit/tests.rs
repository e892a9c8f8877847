//! The driver's linearisation: the tangent it assembles is the derivative
//! of the residual it assembles, for every kind of contact (vertex–wall,
//! smooth–wall, smooth–smooth, smooth–corner), both kinematics, and the
//! law in stick and in slip.

use super::{Body, BodyMaterial, ImplicitDynamics, ImplicitSettings, PlaneState, Prescribed};
use crate::integrate::Newmark;
use crate::kinematics::{Advance, Affine2, Kinematics, PlacedEllipse, PlacedPolygon, Rigid2};
use crate::law::{FrictionIntegration, PenaltyCoulomb};
use crate::linsolve::SparseLu;
use crate::math::Point;
use crate::shape::Segment;

fn material() -> BodyMaterial {
    BodyMaterial {
        density: 2000.0,
        youngs_modulus: 1e8,
        poisson_ratio: 0.25,
        plane: PlaneState::Stress,
    }
}

/// A deterministic sequence in (−1, 1).
fn noise(k: usize) -> f64 {
    2.0 * ((k as f64 * 0.618_033_988_749_894_9 + 0.1).fract()) - 1.0
}

/// Largest relative difference between the tangent's product with four
/// directions and central differences of the residual, at an iterate of
/// size `size` (translations; rotations and strains a tenth), with the
/// regimes of the contacts there (1 stick, 2 and 3 slip).
fn tangent_error<const N: usize, K>(
    bodies: Vec<Body<N>>,
    kinematics: K,
    size: f64,
    friction: f64,
) -> (f64, Vec<i8>)
where
    K: Kinematics<N> + Advance<PlacedPolygon, N> + Advance<PlacedEllipse, N>,
{
    let law = PenaltyCoulomb::new(1e7, friction, FrictionIntegration::ReturnMapping).unwrap();
    let settings = ImplicitSettings {
        search_distance: 0.02,
        overlap_tolerance: 1.0,
        ..ImplicitSettings::default()
    };
    let mut model = ImplicitDynamics::compose(
        bodies,
        kinematics,
        law,
        Newmark::dda(),
        SparseLu::default(),
        settings,
    )
    .unwrap();
    let mask: Vec<bool> = model
        .bodies()
        .iter()
        .flat_map(|b| std::iter::repeat_n(b.is_fixed(), N))
        .collect();
    let n = mask.len();
    let scale = |k: usize| if k % N >= 2 { 0.1 } else { 1.0 };
    let free = |k: usize, v: f64| if mask[k] { 0.0 } else { scale(k) * v };
    let d: Vec<f64> = (0..n).map(|k| free(k, size * noise(k))).collect();
    let (_, _, regimes) = model.residual_and_product(1e-3, &d, &d);
    assert!(
        regimes.iter().any(|r| *r != 0),
        "no closed contact: {regimes:?}"
    );
    let mut worst = 0.0f64;
    for trial in 0..4 {
        let v: Vec<f64> = (0..n)
            .map(|k| free(k, noise(7 * k + 31 * trial + 3)))
            .collect();
        let h = 1e-7;
        let at = |t: f64| -> Vec<f64> { d.iter().zip(&v).map(|(x, y)| x + t * y).collect() };
        let (_, product, _) = model.residual_and_product(1e-3, &d, &v);
        let (rp, _, plus) = model.residual_and_product(1e-3, &at(h), &v);
        let (rm, _, minus) = model.residual_and_product(1e-3, &at(-h), &v);
        assert!(plus == regimes && minus == regimes, "a regime changes");
        let fd: Vec<f64> = rp
            .iter()
            .zip(&rm)
            .map(|(a, b)| (a - b) / (2.0 * h))
            .collect();
        let norm = fd
            .iter()
            .chain(&product)
            .fold(0.0f64, |m, x| m.max(x.abs()));
        let diff = fd
            .iter()
            .zip(&product)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        worst = worst.max(diff / norm);
    }
    (worst, regimes)
}

fn floor<const N: usize>(index: usize) -> Body<N> {
    Body::wall(
        Segment::new(Point::new(-1.0, 0.0), Point::new(1.0, 0.0)),
        index,
    )
    .unwrap()
}

/// The height of the centre of an ellipse (a, b) at `angle` touching the
/// floor, less `sink`.
fn resting(a: f64, b: f64, angle: f64, sink: f64) -> f64 {
    ((a * angle.sin()).powi(2) + (b * angle.cos()).powi(2)).sqrt() - sink
}

/// The scenes: a tilted ellipse sunk 1 mm into a floor, two overlapping
/// ellipses, a disc on the corner of a fixed square, a tilted square on a
/// floor (vertex–wall).
fn scenes<const N: usize>() -> Vec<(&'static str, Vec<Body<N>>)> {
    let ellipse = |c: Point, angle: f64, i: usize| {
        Body::<N>::ellipse(c, 0.2, 0.1, angle, material(), i).unwrap()
    };
    let on_floor = ellipse(Point::new(0.0, resting(0.2, 0.1, 0.4, 1e-3)), 0.4, 0);
    let below = ellipse(Point::new(0.0, 0.5), 0.4, 0);
    let above = ellipse(Point::new(0.05, 0.73), -0.7, 1);
    let mut corner = Body::<N>::new(
        &[(-0.3, -0.3), (0.0, -0.3), (0.0, 0.0), (-0.3, 0.0)].map(|(x, y)| Point::new(x, y)),
        material(),
        1,
    )
    .unwrap();
    corner.prescribed = Some(Prescribed::fixed());
    let disc = Body::<N>::circle(Point::new(0.06, 0.0799), 0.1, material(), 0).unwrap();
    let (s, c) = 0.3f64.sin_cos();
    let square: Vec<Point> = [(-0.1, -0.1), (0.1, -0.1), (0.1, 0.1), (-0.1, 0.1)]
        .iter()
        .map(|&(x, y)| Point::new(c * x - s * y, s * x + c * y + 0.1 * (c + s) - 1e-3))
        .collect();
    let block = Body::<N>::new(&square, material(), 0).unwrap();
    vec![
        ("ellipse on a floor", vec![on_floor, floor(1)]),
        ("two ellipses", vec![below, above]),
        ("disc on a corner", vec![disc, corner]),
        ("square on a floor", vec![block, floor(1)]),
    ]
}

#[test]
fn assembled_tangent_is_the_derivative_of_the_assembled_residual() {
    let mut seen = Vec::new();
    for (size, mu) in [
        (1e-5, 0.5),
        (3e-4, 0.5),
        (3e-4, 0.05),
        (-3e-4, 0.05),
        (3e-4, 0.0),
    ] {
        for (name, bodies) in scenes::<3>() {
            let (err, regimes) = tangent_error(bodies, Rigid2, size, mu);
            assert!(
                err < 1e-6,
                "rigid, {name}, size {size}, mu {mu}: {err:e} {regimes:?}"
            );
            seen.extend(regimes);
        }
        for (name, bodies) in scenes::<6>() {
            let (err, regimes) = tangent_error(bodies, Affine2, size, mu);
            assert!(
                err < 1e-6,
                "affine, {name}, size {size}, mu {mu}: {err:e} {regimes:?}"
            );
            seen.extend(regimes);
        }
    }
    // Stick and both slip directions were checked.
    for regime in [1, 2, 3] {
        assert!(
            seen.contains(&regime),
            "regime {regime} not reached: {seen:?}"
        );
    }
}
