//! An independent reference for the ellipse–ellipse contact routine
//! ([`crate::query::manifold::ellipse::contact_ellipse_ellipse`]), and its
//! comparison with the routine over random pairs (paper 000's ellipse
//! model).
//!
//! The reference samples the boundary of ellipse i densely (4096 points),
//! evaluates the implicit function of ellipse j there, refines every sign
//! change by bisection and the lowest sample by golden-section search, so
//! that a shallow contact whose two crossings fall between two samples is
//! still found. It shares nothing with the routine under test (which
//! isolates the real roots of a quartic).
//!
//! Pairs: aspect ratios 1–5, size ratio (of the minor axes) 1–10, random
//! orientations and direction; the touching distance along the direction
//! is found by bisection on the reference, then the pair is moved closer by
//! an overlap uniform in [−5 %, 20 %] of the smaller b (negative: apart).

use crate::math::{Pose2, SplitMix64, Vec2};
use crate::query::manifold::ellipse::contact_ellipse_ellipse;
use crate::shape::Ellipse;

/// Results of a random-pair comparison.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairStatistics {
    /// Pairs tested.
    pub count: usize,
    /// Pairs in contact by the reference.
    pub in_contact: usize,
    /// Contacts the routine missed (reference overlap deeper than 1e-9 b).
    pub missed: usize,
    /// Contacts the routine reported where the reference finds a gap
    /// larger than 1e-9 b.
    pub false_contacts: usize,
    /// Largest distance between the routine's and the reference's P1, P2,
    /// divided by the smaller b.
    pub max_point_error: f64,
}

/// Value of j's implicit function at i's boundary point `t`.
fn g(i: &Ellipse, pi: &Pose2, j: &Ellipse, pj: &Pose2, t: f64) -> f64 {
    j.implicit(pj, &i.world_point(pi, t))
}

/// Minimum of g over the boundary of i: best of `samples` points, refined
/// by golden-section search within one sample spacing.
fn reference_minimum(
    i: &Ellipse,
    pi: &Pose2,
    j: &Ellipse,
    pj: &Pose2,
    samples: usize,
) -> (f64, f64) {
    let h = std::f64::consts::TAU / samples as f64;
    let (mut best_t, mut best) = (0.0, f64::INFINITY);
    for k in 0..samples {
        let t = k as f64 * h;
        let v = g(i, pi, j, pj, t);
        if v < best {
            best = v;
            best_t = t;
        }
    }
    let (mut lo, mut hi) = (best_t - h, best_t + h);
    let ratio = 0.618_033_988_749_895;
    for _ in 0..80 {
        let x1 = hi - ratio * (hi - lo);
        let x2 = lo + ratio * (hi - lo);
        if g(i, pi, j, pj, x1) < g(i, pi, j, pj, x2) {
            hi = x2;
        } else {
            lo = x1;
        }
    }
    let t = 0.5 * (lo + hi);
    (t, g(i, pi, j, pj, t))
}

/// Bisection for a zero of g between `a` (g < 0) and `b` (g > 0).
fn bisect(i: &Ellipse, pi: &Pose2, j: &Ellipse, pj: &Pose2, mut a: f64, mut b: f64) -> f64 {
    for _ in 0..100 {
        let m = 0.5 * (a + b);
        if g(i, pi, j, pj, m) < 0.0 {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

/// The reference crossings P1, P2 bounding the deepest part of i inside j,
/// from the minimum `(t_min, v_min)` of g.
fn reference_crossings(
    i: &Ellipse,
    pi: &Pose2,
    j: &Ellipse,
    pj: &Pose2,
    (t_min, v_min): (f64, f64),
) -> Option<[Vec2; 2]> {
    if v_min >= 0.0 {
        return None;
    }
    // Walk away from the minimum on both sides until g > 0, then bisect.
    let h = std::f64::consts::TAU / 4096.0;
    let mut out = [Vec2::zeros(); 2];
    for (slot, dir) in [-1.0, 1.0].into_iter().enumerate() {
        let mut inside = t_min;
        let mut step = h * 1e-6;
        let mut outside = t_min + dir * step;
        let mut guard = 0;
        while g(i, pi, j, pj, outside) < 0.0 && guard < 8192 {
            inside = outside;
            step = (step * 2.0).min(h);
            outside += dir * step;
            guard += 1;
        }
        let t = bisect(i, pi, j, pj, inside, outside);
        out[slot] = i.world_point(pi, t).coords;
    }
    Some(out)
}

/// The distance along `direction` from i's centre at which j (at angle
/// `angle_j`) just touches i, approached from outside (a small j can sit
/// wholly inside i, where no boundary crosses), by bisection on the
/// reference.
pub fn touching_distance(
    ei: &Ellipse,
    pi: &Pose2,
    ej: &Ellipse,
    angle_j: f64,
    direction: &Vec2,
) -> f64 {
    let at = |d: f64| Pose2 {
        position: pi.position + direction * d,
        angle: angle_j,
    };
    let overlapping = |pj: &Pose2| {
        reference_minimum(ei, pi, ej, pj, 128).1 < 0.0
            || ei.implicit(pi, &pj.position) < 0.0
            || ej.implicit(pj, &pi.position) < 0.0
    };
    let (mut lo, mut hi) = (0.0, ei.a() + ej.a());
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if overlapping(&at(mid)) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Compare the contact routine with the reference over `count` random
/// pairs drawn from `seed`.
pub fn random_pair_statistics(count: usize, seed: u64) -> PairStatistics {
    let mut rng = SplitMix64(seed);
    let mut stats = PairStatistics {
        count,
        in_contact: 0,
        missed: 0,
        false_contacts: 0,
        max_point_error: 0.0,
    };
    for _ in 0..count {
        let b_i = 1.0;
        let b_j = if rng.next_uniform() < 0.5 {
            1.0 + 9.0 * rng.next_uniform()
        } else {
            1.0 / (1.0 + 9.0 * rng.next_uniform())
        };
        let (Ok(ei), Ok(ej)) = (
            Ellipse::new(b_i * (1.0 + 4.0 * rng.next_uniform()), b_i),
            Ellipse::new(b_j * (1.0 + 4.0 * rng.next_uniform()), b_j),
        ) else {
            continue;
        };
        let tau = std::f64::consts::TAU;
        let pi = Pose2::new(0.0, 0.0, tau * rng.next_uniform());
        let angle_j = tau * rng.next_uniform();
        let direction = Vec2::new(
            (tau * rng.next_uniform()).cos(),
            (tau * rng.next_uniform()).sin(),
        )
        .normalize();
        let b_min = b_i.min(b_j);
        let at = |d: f64| Pose2 {
            position: pi.position + direction * d,
            angle: angle_j,
        };
        let overlap = (-0.05 + 0.25 * rng.next_uniform()) * b_min;
        let touching = touching_distance(&ei, &pi, &ej, angle_j, &direction);
        let pj = at(touching - overlap);
        let minimum = reference_minimum(&ei, &pi, &ej, &pj, 4096);
        let depth = minimum.1;
        let reference = reference_crossings(&ei, &pi, &ej, &pj, minimum);
        let ours = contact_ellipse_ellipse(&ei, &pi, &ej, &pj);
        if reference.is_some() {
            stats.in_contact += 1;
        }
        match (&ours, &reference) {
            (None, Some(_)) if depth < -1e-9 => stats.missed += 1,
            (Some(_), None) if depth > 1e-9 => stats.false_contacts += 1,
            (Some(c), Some(r)) => {
                let half = c.tangent() * (0.5 * c.width);
                let p = [c.point.coords - half, c.point.coords + half];
                let direct = (p[0] - r[0]).norm().max((p[1] - r[1]).norm());
                let swapped = (p[0] - r[1]).norm().max((p[1] - r[0]).norm());
                stats.max_point_error = stats.max_point_error.max(direct.min(swapped) / b_min);
            }
            _ => {}
        }
    }
    stats
}

/// [`random_pair_statistics`] over `count` pairs split across the
/// machine's cores (each share with its own seed derived from `seed`).
pub fn random_pair_statistics_parallel(count: usize, seed: u64) -> PairStatistics {
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .max(1);
    let share = count.div_ceil(threads);
    let parts: Vec<PairStatistics> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|k| {
                let n = share.min(count.saturating_sub(k * share));
                scope.spawn(move || {
                    random_pair_statistics(n, seed.wrapping_add(k as u64 * 0x1000_0000))
                })
            })
            .collect();
        handles.into_iter().filter_map(|h| h.join().ok()).collect()
    });
    parts.into_iter().fold(
        PairStatistics {
            count: 0,
            in_contact: 0,
            missed: 0,
            false_contacts: 0,
            max_point_error: 0.0,
        },
        |a, b| PairStatistics {
            count: a.count + b.count,
            in_contact: a.in_contact + b.in_contact,
            missed: a.missed + b.missed,
            false_contacts: a.false_contacts + b.false_contacts,
            max_point_error: a.max_point_error.max(b.max_point_error),
        },
    )
}
