//! The earth pressure that regular fillings ([`dismech::scene::Layout`]) put
//! on a wall, and the back-pressure stage: paper 000's Examples 2 and 3.
//!
//! The earth-pressure coefficient is eq. (23) of the paper,
//! `K = (P_h / d) / (σ_v,max · z / H)`, for every contact of a side wall:
//! `P_h` its normal force, `d` the mean distance between the wall's
//! contacts, `σ_v,max = W / width` the vertical pressure of the whole
//! filling on the bottom (W its weight), `H` the filling height and `z` the
//! depth of the contact below the top of the filling. The paper calls `h`
//! "the height from the bottom plate" but the ratio `h / H` must vanish at
//! the top for `σ_v,max · h / H` to be a vertical stress, so it is read here
//! as the depth.

use dismech::dem::DemSimulation;
use dismech::error::{DismechError, Result};
use dismech::explicit::ContactTarget;
use dismech::integrate::ExplicitEuler;
use dismech::law::SpringDashpotCoulomb;
use dismech::math::{Point, Vec2};
use dismech::scene::layout::ellipse_half_extent;
use dismech::scene::{Frame, Scene};
use dismech::shape::{AnyShape2, Shape2};
use statrs::distribution::{ContinuousCDF, StudentsT};

/// One contact of a side wall with its eq. (23) earth-pressure coefficient.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallPressure {
    /// Height of the contact above the floor (m).
    pub height: f64,
    /// Depth below the top of the filling (m).
    pub depth: f64,
    /// `P_h / d`, the normal pressure at the contact (Pa).
    pub pressure: f64,
    /// Eq. (23): `(P_h / d) / (σ_v,max · depth / H)`.
    pub k: f64,
    /// Contact angle ω of the wall particle (degrees from the horizontal):
    /// the normal-force-weighted mean of `|angle|` of the normals of its
    /// contacts with other particles, folded into [0°, 90°].
    pub omega_deg: f64,
}

/// The eq. (23) coefficient at every contact of the wall `wall_name`, sorted
/// by height. `fill_height` is H (m); `default_spacing` is `d` when the wall
/// has fewer than two contacts.
pub fn wall_pressures(
    sim: &DemSimulation<SpringDashpotCoulomb, ExplicitEuler>,
    wall_name: &str,
    fill_height: f64,
    default_spacing: f64,
) -> Vec<WallPressure> {
    let scene = sim.scene();
    let Some(w) = scene.frame.index_of(wall_name) else {
        return Vec::new();
    };
    let width = scene
        .frame
        .bounding_box()
        .map_or(f64::NAN, |b| b.max.x - b.min.x);
    let sigma_v_max = scene.total_weight() / width;
    let (contacts, spacing) = wall_normal_forces(sim, w, default_spacing);
    contacts
        .iter()
        .map(|&(height, force, particle)| {
            let depth = fill_height - height;
            let pressure = force / spacing;
            WallPressure {
                height,
                depth,
                pressure,
                k: pressure / (sigma_v_max * depth / fill_height),
                omega_deg: contact_angle(sim, particle),
            }
        })
        .collect()
}

/// The contacts of wall `w` as `(height, normal force pushing the wall
/// outward, particle)`, sorted by height, and the mean distance `d` between
/// them (`default_spacing` when there are fewer than two).
pub fn wall_normal_forces(
    sim: &DemSimulation<SpringDashpotCoulomb, ExplicitEuler>,
    w: usize,
    default_spacing: f64,
) -> (Vec<(f64, f64, usize)>, f64) {
    let Some(wall) = sim.scene().frame.walls().get(w) else {
        return (Vec::new(), default_spacing);
    };
    let outward = -wall.inner_normal();
    let mut contacts: Vec<(f64, f64, usize)> = sim
        .contacts()
        .iter()
        .filter(|c| c.target == ContactTarget::Wall(w))
        .map(|c| (c.point.y, c.force_on_target.dot(&outward), c.particle))
        .collect();
    contacts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let spacing = match (contacts.first(), contacts.last()) {
        (Some(lo), Some(hi)) if contacts.len() > 1 && hi.0 > lo.0 => {
            (hi.0 - lo.0) / (contacts.len() - 1) as f64
        }
        _ => default_spacing,
    };
    (contacts, spacing)
}

/// The normal-force-weighted mean angle from the horizontal (degrees, in
/// [0°, 90°]) of the particle–particle contact normals of `particle`.
fn contact_angle(sim: &DemSimulation<SpringDashpotCoulomb, ExplicitEuler>, particle: usize) -> f64 {
    let (mut sum, mut weight) = (0.0, 0.0);
    for c in sim.contacts() {
        let ContactTarget::Particle(other) = c.target else {
            continue;
        };
        if c.particle != particle && other != particle {
            continue;
        }
        let normal_force = c.force_on_target.dot(&c.normal).abs();
        let angle = c.normal.y.abs().atan2(c.normal.x.abs()).to_degrees();
        sum += normal_force * angle;
        weight += normal_force;
    }
    if weight > 0.0 {
        sum / weight
    } else {
        f64::NAN
    }
}

/// The per-contact K of a wall profile at depths between 20 % and 90 % of
/// H: the band of [`representative_k`].
fn band_k(profile: &[WallPressure], fill_height: f64) -> Vec<f64> {
    profile
        .iter()
        .filter(|p| p.depth >= 0.2 * fill_height && p.depth <= 0.9 * fill_height)
        .map(|p| p.k)
        .collect()
}

/// The representative K of a wall profile: the median of the per-contact
/// values at depths between 20 % and 90 % of H (the top fifth divides by a
/// vanishing σ_v, and the paper notes the bottom is disturbed by the
/// friction of the bottom plate). `None` when no contact lies in that band.
pub fn representative_k(profile: &[WallPressure], fill_height: f64) -> Option<f64> {
    let mut ks = band_k(profile, fill_height);
    if ks.is_empty() {
        return None;
    }
    ks.sort_by(f64::total_cmp);
    let n = ks.len();
    Some(if n % 2 == 1 {
        ks[n / 2]
    } else {
        0.5 * (ks[n / 2 - 1] + ks[n / 2])
    })
}

/// Whether two walls carry the same earth pressure, as a test of
/// significance: the two-sided p-value of Welch's t test of the hypothesis
/// that the per-contact K of the two profiles, in the band of
/// [`representative_k`], are samples of one mean (t with the
/// Welch–Satterthwaite degrees of freedom). A small value says the walls
/// differ by more than their contacts' scatter explains. `None` when a
/// wall has fewer than two contacts in the band; 1 (or 0) when neither
/// sample scatters and their means are equal (or not).
///
/// The test takes the contacts of a wall as independent, which neighbours
/// in one force chain are not, and with a handful of contacts on each
/// wall it finds only a large difference: it guards the study's outcome, while a
/// handedness of the contact itself is ruled out exactly by the mirror
/// tests of `tests/ellipse_contact.rs`.
pub fn same_mean_p_value(
    left: &[WallPressure],
    right: &[WallPressure],
    fill_height: f64,
) -> Option<f64> {
    let (left, right) = (band_k(left, fill_height), band_k(right, fill_height));
    if left.len() < 2 || right.len() < 2 {
        return None;
    }
    // The mean and the variance of the mean of a sample.
    let moments = |ks: &[f64]| {
        let n = ks.len() as f64;
        let mean = ks.iter().sum::<f64>() / n;
        let variance = ks.iter().map(|k| (k - mean).powi(2)).sum::<f64>() / (n - 1.0);
        (mean, variance / n, n)
    };
    let ((mean_l, var_l, n_l), (mean_r, var_r, n_r)) = (moments(&left), moments(&right));
    let variance = var_l + var_r;
    if variance <= 0.0 {
        return Some(if mean_l == mean_r { 1.0 } else { 0.0 });
    }
    let t = (mean_l - mean_r).abs() / variance.sqrt();
    let freedom = variance * variance / (var_l * var_l / (n_l - 1.0) + var_r * var_r / (n_r - 1.0));
    let student = StudentsT::new(0.0, 1.0, freedom).ok()?;
    Some(2.0 * student.sf(t))
}

/// The smallest half-size of a particle: semi-minor axis or radius (m).
fn smallest_half_size(p: &dismech::scene::Particle) -> f64 {
    match &p.shape {
        AnyShape2::Circle(c) => c.radius(),
        AnyShape2::Ellipse(e) => e.b(),
        AnyShape2::Polygon(polygon) => {
            let (hx, hy) = half_extent(p);
            hx.min(hy).min(polygon.bounding_radius())
        }
        AnyShape2::Segment(_) => f64::INFINITY,
    }
}

/// Half the horizontal and vertical extent of a particle (m).
fn half_extent(p: &dismech::scene::Particle) -> (f64, f64) {
    match &p.shape {
        AnyShape2::Circle(c) => (c.radius(), c.radius()),
        AnyShape2::Ellipse(e) => ellipse_half_extent(e.a(), e.b(), p.pose.angle),
        AnyShape2::Segment(seg) => {
            let d = seg.end - seg.start;
            (0.5 * d.x.abs(), 0.5 * d.y.abs())
        }
        AnyShape2::Polygon(polygon) => {
            let bb = polygon.aabb(&p.pose);
            (0.5 * (bb.max.x - bb.min.x), 0.5 * (bb.max.y - bb.min.y))
        }
    }
}

/// Outlines of the particles of `scene` (closed polylines, for pictures).
pub fn particle_outlines(scene: &Scene) -> Vec<Vec<Point>> {
    const POINTS: usize = 48;
    scene
        .particles
        .iter()
        .filter_map(|p| {
            if let AnyShape2::Polygon(polygon) = &p.shape {
                let mut outline: Vec<Point> = polygon.world_vertices(&p.pose).collect();
                outline.push(outline[0]);
                return Some(outline);
            }
            let point = |k: usize| {
                let t = k as f64 / POINTS as f64 * std::f64::consts::TAU;
                match &p.shape {
                    AnyShape2::Circle(c) => Some(Point::new(
                        p.pose.position.x + c.radius() * t.cos(),
                        p.pose.position.y + c.radius() * t.sin(),
                    )),
                    AnyShape2::Ellipse(e) => Some(e.world_point(&p.pose, t)),
                    AnyShape2::Segment(_) | AnyShape2::Polygon(_) => None,
                }
            };
            (0..=POINTS).map(point).collect()
        })
        .collect()
}

/// The particles of a settled filling in an open box, with the back
/// (`left`) wall replaced by a uniform horizontal `pressure` (Pa, acting
/// towards +x) on the back particles, and the box closed by a lid just above
/// the filling: Example 3's rigid rectangular frame under back storage sand
/// pressure.
///
/// The back particles are those whose back edge lies within the smallest
/// half-size of any particle (its semi-minor axis or radius) of the back,
/// and the first particles seen from the back: those with no particle
/// further back whose height range overlaps the middle half of theirs (in a
/// running bond, the end particle of every row). Each
/// takes the pressure over its share of the height: from half-way to the
/// back particle below (the floor for the lowest) to half-way to the one
/// above (the top of the filling, `fill_height`, for the highest), so that
/// the forces add up to `pressure · fill_height`. The walls of the new
/// frame are `bottom`, `front` and `lid`. The particles start at their
/// settled poses, at rest and without contact history.
pub fn back_pressure_scene(
    settled: &DemSimulation<SpringDashpotCoulomb, ExplicitEuler>,
    pressure: f64,
    fill_height: f64,
    lid_gap: f64,
) -> Result<Scene> {
    dismech::error::require_finite("back pressure", pressure)?;
    dismech::error::require_non_negative("lid gap", lid_gap)?;
    let old = settled.scene();
    let left = old
        .frame
        .index_of("left")
        .ok_or(DismechError::InvalidParameter {
            name: "walls of the settled frame",
            value: old.frame.walls().len() as f64,
            requirement: "a wall named `left` (an open box)",
        })?;
    let back_x = old.frame.walls()[left]
        .start
        .x
        .max(old.frame.walls()[left].end.x);
    let right_x = old.frame.bounding_box().map_or(back_x, |b| b.max.x);
    let top = fill_height + lid_gap;
    let frame = Frame::from_walls(vec![
        (
            "bottom".into(),
            dismech::shape::Segment::new(Point::new(back_x, 0.0), Point::new(right_x, 0.0)),
        ),
        (
            "front".into(),
            dismech::shape::Segment::new(Point::new(right_x, 0.0), Point::new(right_x, top)),
        ),
        (
            "lid".into(),
            dismech::shape::Segment::new(Point::new(right_x, top), Point::new(back_x, top)),
        ),
    ])?;
    let extents: Vec<(f64, f64)> = old.particles.iter().map(half_extent).collect();
    let reach = old
        .particles
        .iter()
        .map(smallest_half_size)
        .fold(f64::INFINITY, f64::min);
    let mut back: Vec<(f64, usize)> = (0..old.particles.len())
        .filter(|&i| {
            let (x, y) = (
                old.particles[i].pose.position.x,
                old.particles[i].pose.position.y,
            );
            let (half_width, band) = (extents[i].0, 0.5 * extents[i].1);
            let near_the_back = x - half_width - back_x < reach;
            let first_seen = !old.particles.iter().enumerate().any(|(j, q)| {
                let (qy, qh) = (q.pose.position.y, extents[j].1);
                q.pose.position.x < x && qy + qh > y - band && qy - qh < y + band
            });
            near_the_back || first_seen
        })
        .map(|i| (old.particles[i].pose.position.y, i))
        .collect();
    back.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut scene = Scene::new(frame, old.gravity)?;
    for p in &old.particles {
        let mut particle = p.clone();
        particle.velocity = Vec2::zeros();
        particle.angular_velocity = 0.0;
        particle.external_force = Vec2::zeros();
        scene.particles.push(particle);
    }
    for (k, &(y, particle)) in back.iter().enumerate() {
        let below = if k == 0 {
            0.0
        } else {
            0.5 * (y + back[k - 1].0)
        };
        let above = if k + 1 == back.len() {
            fill_height
        } else {
            0.5 * (y + back[k + 1].0)
        };
        scene.set_external_force(particle, Vec2::new(pressure * (above - below), 0.0))?;
    }
    Ok(scene)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Contacts with the given K, all in the band of a filling 1 m high.
    fn profile(ks: &[f64]) -> Vec<WallPressure> {
        ks.iter()
            .map(|&k| WallPressure {
                height: 0.5,
                depth: 0.5,
                pressure: 1.0,
                k,
                omega_deg: 45.0,
            })
            .collect()
    }

    #[test]
    fn welch_p_value_matches_an_independent_computation() {
        // scipy.stats.ttest_ind(a, b, equal_var=False).pvalue =
        // 0.04357052647926788 (t = -2.40, 7.89 degrees of freedom).
        let a = profile(&[1.0, 2.0, 3.0, 4.0]);
        let b = profile(&[2.5, 3.5, 4.5, 5.5, 6.5, 9.0]);
        let p = same_mean_p_value(&a, &b, 1.0).unwrap();
        approx::assert_relative_eq!(p, 0.04357052647926788, max_relative = 1e-9);
        // The walls' order does not matter.
        assert_eq!(p, same_mean_p_value(&b, &a, 1.0).unwrap());
    }

    #[test]
    fn welch_p_value_in_the_degenerate_cases() {
        let one = profile(&[0.3]);
        let two = profile(&[0.3, 0.4]);
        assert_eq!(same_mean_p_value(&one, &two, 1.0), None);
        assert_eq!(same_mean_p_value(&two, &two, 1.0), Some(1.0));
        let flat = profile(&[0.3, 0.3]);
        assert_eq!(same_mean_p_value(&flat, &flat, 1.0), Some(1.0));
        assert_eq!(
            same_mean_p_value(&flat, &profile(&[0.5, 0.5]), 1.0),
            Some(0.0)
        );
        // Contacts outside the band (depth 0.2-0.9 H) do not count.
        let mut shallow = profile(&[0.3, 0.4]);
        shallow[0].depth = 0.1;
        assert_eq!(same_mean_p_value(&shallow, &two, 1.0), None);
    }
}
