//! Rolling resistance in the explicit DEM ([`RollingResistance`]): a disc
//! rolling on a floor decelerates at the exact rate of a constant rolling
//! moment `μ_r R N`, stands on a slope flatter than `tan β = μ_r` and rolls
//! down a steeper one at the exact acceleration; the law keeps its moment
//! within the rolling strength along random loading paths; without
//! rolling resistance it gives the inner law's run bit for bit; and a run
//! with rolling moments resumes from a checkpoint in the same bits.

use dismech::dem::DemSimulation;
use dismech::explicit::DemSettings;
use dismech::integrate::ExplicitEuler;
use dismech::law::conformance::{
    self,
    strategies::{history_then_input, Scales},
};
use dismech::law::{
    ContactLaw, Damping, NormalStiffness, PairProperties, RollingResistance, SpringDashpotCoulomb,
};
use dismech::math::{Point, Vec2};
use dismech::scene::{Frame, Scene};
use proptest::prelude::*;
use proptest::test_runner::TestRunner;

const G: f64 = 9.81;
const RADIUS: f64 = 0.05;
const DENSITY: f64 = 2690.0;
const K_N: f64 = 1e7;
const SHEAR_RATIO: f64 = 0.25;
const DT: f64 = 1e-4;

fn inner_law() -> SpringDashpotCoulomb {
    SpringDashpotCoulomb::new(
        NormalStiffness::Constant(K_N),
        SHEAR_RATIO,
        0.5,
        Damping::Critical,
    )
    .unwrap()
}

/// The inner law with rolling coefficient `mu_r` and the shear stiffness
/// as rolling stiffness.
fn rolling_law(mu_r: f64) -> RollingResistance<SpringDashpotCoulomb> {
    RollingResistance::new(inner_law(), mu_r, SHEAR_RATIO * K_N).unwrap()
}

/// The disc's rest overlap on a floor inclined by `beta`, `N / k_n`.
fn rest_overlap(mass: f64, beta: f64) -> f64 {
    mass * G * beta.cos() / K_N
}

/// The distance from the disc's centre to its contact point, which the
/// driver places at the middle of the overlap: `R − δ/2`.
fn lever(overlap: f64) -> f64 {
    RADIUS - 0.5 * overlap
}

/// One disc resting on the floor of a wide box under gravity `g` tilted by
/// `beta` (a floor inclined by `beta`, in the floor's frame), at its rest
/// overlap, moving at `speed` along the floor and rolling without slip.
fn disc_on_floor(beta: f64, speed: f64) -> Scene {
    let gravity = Vec2::new(G * beta.sin(), -G * beta.cos());
    let mut scene = Scene::new(Frame::open_box(20.0, 2.0).unwrap(), gravity).unwrap();
    let i = scene
        .add_circle(Point::new(2.0, RADIUS), RADIUS, DENSITY)
        .unwrap();
    let p = &mut scene.particles[i];
    let overlap = rest_overlap(p.mass, beta);
    p.pose.position.y = RADIUS - overlap;
    p.velocity = Vec2::new(speed, 0.0);
    p.angular_velocity = -speed / lever(overlap);
    scene
}

fn simulation<L>(scene: Scene, law: L) -> DemSimulation<L>
where
    L: ContactLaw<2> + dismech::law::BoundedStiffness<2>,
{
    let settings = DemSettings {
        dt: DT,
        // The discs start at their rest overlap, about 2e-5 m.
        initial_overlap_tolerance: 1e-4,
        ..DemSettings::default()
    };
    DemSimulation::new(scene, law, ExplicitEuler, settings).unwrap()
}

/// The velocity along the floor after `steps` more steps.
fn speed_after<L: ContactLaw<2>>(sim: &mut DemSimulation<L>, steps: usize) -> f64 {
    for _ in 0..steps {
        sim.step().unwrap();
    }
    sim.scene().particles[0].velocity.x
}

/// The acceleration of a disc (inertia `m R²/2`) rolling without slip
/// down a floor inclined by `β` (gravity's share `g sin β` along it,
/// `N = m g cos β` across) with a rolling moment at its strength
/// `M = μ_r R N` against the rolling. With `ℓ` the distance from the
/// centre to the contact point, `m a = m g sin β − F`,
/// `(m R²/2) α = −F ℓ + M` and `a = −α ℓ` give
/// `a = g (sin β − μ_r (R/ℓ) cos β) / (1 + R²/(2ℓ²))`: `(2/3) g (sin β −
/// μ_r cos β)` for `ℓ = R`; here `ℓ = R − δ/2` with the rest overlap δ.
fn rolling_acceleration(beta: f64, mu_r: f64, mass: f64) -> f64 {
    let l = lever(rest_overlap(mass, beta));
    G * (beta.sin() - mu_r * RADIUS / l * beta.cos()) / (1.0 + RADIUS * RADIUS / (2.0 * l * l))
}

#[test]
fn a_disc_rolling_on_a_floor_decelerates_at_two_thirds_mu_r_g_and_stops() {
    let mu_r = 0.1;
    let v0 = 0.5;
    let mut sim = simulation(disc_on_floor(0.0, v0), rolling_law(mu_r));
    // The shear spring takes up the friction the moment needs in the
    // first milliseconds; from 0.1 s to 0.5 s the rolling is steady.
    let v1 = speed_after(&mut sim, 1000);
    let v2 = speed_after(&mut sim, 4000);
    let measured = (v2 - v1) / (4000.0 * DT);
    let mass = sim.scene().particles[0].mass;
    let exact = rolling_acceleration(0.0, mu_r, mass);
    approx::assert_relative_eq!(exact, -2.0 / 3.0 * mu_r * G, max_relative = 1e-3);
    approx::assert_relative_eq!(measured, exact, max_relative = 1e-6);
    // It stops where the constant deceleration says, v0²/(2|a|), and stays.
    let x0 = 2.0;
    let stop_time = v0 / exact.abs();
    speed_after(&mut sim, (stop_time / DT) as usize - 5000 + 2000);
    let p = &sim.scene().particles[0];
    let travelled = p.pose.position.x - x0;
    let expected = v0 * v0 / (2.0 * exact.abs());
    approx::assert_relative_eq!(travelled, expected, max_relative = 1e-3);
    assert!(
        p.velocity.x.abs() < 1e-3 * v0,
        "still moving at {} m/s",
        p.velocity.x
    );
    // Without rolling resistance the same disc keeps rolling at v0.
    let mut free = simulation(disc_on_floor(0.0, v0), inner_law());
    let v_free = speed_after(&mut free, 5000);
    approx::assert_relative_eq!(v_free, v0, max_relative = 1e-6);
}

#[test]
fn a_disc_stands_on_a_slope_flatter_than_mu_r_and_rolls_down_a_steeper_one() {
    let mu_r = 0.1;
    // tan β = 0.09: the rolling strength holds the disc.
    let gentle = 0.09f64.atan();
    let mut sim = simulation(disc_on_floor(gentle, 0.0), rolling_law(mu_r));
    let mut largest = 0.0f64;
    for _ in 0..10_000 {
        sim.step().unwrap();
        let p = &sim.scene().particles[0];
        largest = largest.max((p.pose.position.x - 2.0).abs());
    }
    // The elastic share: the rolling spring's and the shear spring's
    // deflections under m g sin β, m g sin β / k_s each.
    let p = &sim.scene().particles[0];
    let mass = p.mass;
    let elastic = p.mass * G * gentle.sin() / (SHEAR_RATIO * K_N);
    assert!(
        largest < 10.0 * elastic,
        "the disc moved {largest} m on a slope its rolling strength holds (elastic scale {elastic} m)"
    );
    // The same slope without rolling resistance: it rolls down at
    // (2/3) g sin β.
    let mut free = simulation(disc_on_floor(gentle, 0.0), inner_law());
    let (w1, w2) = (speed_after(&mut free, 1000), speed_after(&mut free, 4000));
    approx::assert_relative_eq!(
        (w2 - w1) / (4000.0 * DT),
        rolling_acceleration(gentle, 0.0, mass),
        max_relative = 1e-6
    );
    // tan β = 0.12: it rolls down, at (2/3) g (sin β − μ_r cos β).
    let steep = 0.12f64.atan();
    let mut sim = simulation(disc_on_floor(steep, 0.0), rolling_law(mu_r));
    let (v1, v2) = (speed_after(&mut sim, 1000), speed_after(&mut sim, 4000));
    approx::assert_relative_eq!(
        (v2 - v1) / (4000.0 * DT),
        rolling_acceleration(steep, mu_r, mass),
        max_relative = 1e-6
    );
}

/// A heap of discs dropped into a box.
fn heap() -> Scene {
    let mut scene = Scene::new(Frame::open_box(1.2, 2.0).unwrap(), Vec2::new(0.0, -G)).unwrap();
    for row in 0..6 {
        for col in 0..8 {
            let shift = if row % 2 == 0 { 0.0 } else { 0.06 };
            let r = 0.045 + 0.004 * ((row * 8 + col) % 3) as f64;
            scene
                .add_circle(
                    Point::new(0.1 + shift + 0.13 * col as f64, 0.1 + 0.12 * row as f64),
                    r,
                    DENSITY,
                )
                .unwrap();
        }
    }
    scene
}

#[test]
fn without_rolling_resistance_the_run_is_the_inner_laws_bit_for_bit() {
    let mut plain = simulation(heap(), inner_law());
    let mut wrapped = simulation(
        heap(),
        RollingResistance::new(inner_law(), 0.0, SHEAR_RATIO * K_N).unwrap(),
    );
    for _ in 0..3000 {
        plain.step().unwrap();
        wrapped.step().unwrap();
    }
    let bits = |s: &Scene| -> Vec<u64> {
        s.particles
            .iter()
            .flat_map(|p| {
                [
                    p.pose.position.x,
                    p.pose.position.y,
                    p.pose.angle,
                    p.angular_velocity,
                ]
            })
            .map(f64::to_bits)
            .collect()
    };
    assert_eq!(bits(plain.scene()), bits(wrapped.scene()));
    assert!(!plain.contacts().is_empty(), "the heap has contacts");
    // With rolling resistance the same heap takes rolling moments.
    let mut rolling = simulation(heap(), rolling_law(0.3));
    for _ in 0..3000 {
        rolling.step().unwrap();
    }
    assert!(rolling.contacts().iter().any(|c| c.rolling_moment != 0.0));
    assert!(plain.contacts().iter().all(|c| c.rolling_moment == 0.0));
}

#[test]
fn a_run_with_rolling_moments_resumes_from_a_checkpoint_in_the_same_bits() {
    let law = rolling_law(0.3);
    let mut sim = simulation(heap(), law);
    for _ in 0..2000 {
        sim.step().unwrap();
    }
    assert!(sim.contacts().iter().any(|c| c.rolling_moment != 0.0));
    let saved = sim.checkpoint().unwrap();
    let mut resumed = DemSimulation::restore(law, ExplicitEuler, &saved).unwrap();
    for _ in 0..1000 {
        sim.step().unwrap();
        resumed.step().unwrap();
    }
    let state = |s: &DemSimulation<RollingResistance<SpringDashpotCoulomb>>| -> Vec<u64> {
        s.scene()
            .particles
            .iter()
            .flat_map(|p| [p.pose.position.x, p.pose.position.y, p.angular_velocity])
            .chain(s.contacts().iter().map(|c| c.rolling_moment))
            .map(f64::to_bits)
            .collect()
    };
    assert_eq!(state(&sim), state(&resumed));
}

#[test]
fn the_rolling_moment_stays_within_mu_r_r_star_f_n_along_random_paths() {
    let law = RollingResistance::new(inner_law(), 0.2, SHEAR_RATIO * K_N).unwrap();
    let pair = PairProperties {
        curvature_radius_a: 0.05,
        curvature_radius_b: 0.08,
        width: 0.01,
        mass_a: 20.0,
        mass_b: 50.0,
    };
    let r_star = 0.05 * 0.08 / 0.13;
    let mut scales = Scales::new(1e-4, 2e-5, pair);
    scales.rotation = 1e-3;
    TestRunner::default()
        .run(
            &history_then_input::<_, 2>(law, scales, 1..12),
            |(state, input)| {
                let violations = conformance::check_force_law(&law, &input, &state);
                prop_assert!(violations.is_empty(), "{:?}", violations);
                let r = law.evaluate(&input, &state);
                let moment = law.moment(&r.state);
                let strength = 0.2 * r_star * r.force[0].max(0.0);
                prop_assert!(
                    moment.abs() <= strength * (1.0 + 1e-12),
                    "moment {} above the rolling strength {}",
                    moment,
                    strength
                );
                // Elastic below the strength: the moment moved by k_r Δθ_r.
                let trial = state.moment - SHEAR_RATIO * K_N * r_star * r_star * input.rotation;
                if r.force[0] > 0.0 && trial.abs() < strength {
                    prop_assert!((moment - trial).abs() <= 1e-9 * strength.max(trial.abs()));
                }
                Ok(())
            },
        )
        .unwrap();
}

#[test]
fn a_negative_or_non_finite_rolling_parameter_is_refused_by_name() {
    for (mu_r, k, name) in [
        (-0.1, 1.0, "rolling coefficient"),
        (f64::NAN, 1.0, "rolling coefficient"),
        (0.1, -1.0, "rolling stiffness"),
        (0.1, f64::INFINITY, "rolling stiffness"),
    ] {
        let err = RollingResistance::new(inner_law(), mu_r, k).unwrap_err();
        assert!(err.to_string().contains(name), "{err}");
    }
}

/// A law with a tangent that exerts a moment, which the implicit driver
/// would not apply: the conformance check says so.
#[derive(Debug, Clone, Copy)]
struct TurningPenalty(dismech::law::PenaltyCoulomb);

impl ContactLaw<2> for TurningPenalty {
    type State = dismech::law::PenaltyState;

    fn evaluate(
        &self,
        input: &dismech::law::ContactInput<2>,
        state: &Self::State,
    ) -> dismech::law::ContactResponse<2, Self::State> {
        self.0.evaluate(input, state)
    }

    fn moment(&self, state: &Self::State) -> f64 {
        1e-3 * state.normal
    }
}

impl dismech::law::TangentLaw<2> for TurningPenalty {
    fn evaluate_with_tangent(
        &self,
        input: &dismech::law::ContactInput<2>,
        state: &Self::State,
    ) -> (
        dismech::law::ContactResponse<2, Self::State>,
        dismech::law::Tangent<2>,
    ) {
        self.0.evaluate_with_tangent(input, state)
    }
}

#[test]
fn the_conformance_checks_refuse_a_moment_from_a_law_with_a_tangent() {
    use dismech::law::{FrictionIntegration, PenaltyCoulomb, PenaltyState};
    let penalty = PenaltyCoulomb::new(1e8, 0.5, FrictionIntegration::ReturnMapping).unwrap();
    let input = dismech::law::ContactInput {
        overlap: 1e-4,
        increment: dismech::nalgebra::Vector2::new(1e-5, 2e-5),
        dt: 1e-3,
        is_new: false,
        pair: PairProperties::rigid(),
        rotation: 0.0,
    };
    let state = PenaltyState::default();
    assert!(conformance::check_tangent_law(&penalty, &input, &state).is_empty());
    let violations = conformance::check_tangent_law(&TurningPenalty(penalty), &input, &state);
    assert!(
        violations
            .iter()
            .any(|v| v.check == "no_moment_with_tangent"),
        "{violations:?}"
    );
}

/// The angular momentum `I ω + m x × v` of particles `ids` about the origin.
fn angular_momentum(scene: &Scene, ids: &[usize]) -> f64 {
    ids.iter()
        .map(|&i| {
            let p = &scene.particles[i];
            let (x, v) = (p.pose.position, p.velocity);
            p.inertia * p.angular_velocity + p.mass * (x.x * v.y - x.y * v.x)
        })
        .sum()
}

/// Two spinning discs of unequal radii pressed together, without gravity:
/// each pair's angular momentum is kept (to round-off) while its rolling
/// moment acts, so the moment on B is the opposite of A's. One pair lies
/// in one block of particles, the other across blocks (its B's moment
/// added in the motion pass), among 2 100 resting discs that touch
/// nothing (the driver's threaded path).
#[test]
fn the_rolling_moment_on_b_is_the_opposite_of_as_within_and_across_blocks() {
    let mut scene = Scene::new(Frame::open_box(200.0, 200.0).unwrap(), Vec2::zeros()).unwrap();
    for k in 0..2100 {
        let (col, row) = ((k % 60) as f64, (k / 60) as f64);
        scene
            .add_circle(Point::new(20.0 + col, 20.0 + row), 0.1, DENSITY)
            .unwrap();
    }
    // The pairs replace discs 100 & 101 (one block) and 500 & 1900
    // (blocks 0 and 1), placed apart from the rest.
    let pairs = [(100usize, 101usize, 150.0), (500, 1900, 170.0)];
    for &(a, b, x) in &pairs {
        let (ra, rb) = (0.05, 0.08);
        let overlap = 5e-5;
        for (i, r, centre, spin) in [
            (a, ra, Point::new(x, 150.0), 12.0),
            (b, rb, Point::new(x + ra + rb - overlap, 150.0), -3.0),
        ] {
            let mass = DENSITY * std::f64::consts::PI * r * r;
            let p = &mut scene.particles[i];
            p.shape = dismech::shape::Circle::new(r).unwrap().into();
            p.pose.position = centre;
            p.mass = mass;
            p.inertia = 0.5 * mass * r * r;
            p.angular_velocity = spin;
        }
    }
    let law = rolling_law(0.3);
    let mut sim = simulation(scene, law);
    let ids = |&(a, b, _): &(usize, usize, f64)| [a, b];
    let before: Vec<f64> = pairs
        .iter()
        .map(|pair| angular_momentum(sim.scene(), &ids(pair)))
        .collect();
    let mut rolled = [false; 2];
    for _ in 0..400 {
        sim.step().unwrap();
        for (k, &(a, b, _)) in pairs.iter().enumerate() {
            rolled[k] |= sim.contacts().iter().any(|c| {
                c.particle == a
                    && c.target == dismech::explicit::ContactTarget::Particle(b)
                    && c.rolling_moment != 0.0
            });
        }
    }
    assert_eq!(rolled, [true, true], "each pair took a rolling moment");
    for (k, pair) in pairs.iter().enumerate() {
        let after = angular_momentum(sim.scene(), &ids(pair));
        let spin_scale: f64 = ids(pair)
            .iter()
            .map(|&i| {
                let p = &sim.scene().particles[i];
                p.inertia * 12.0
            })
            .sum();
        assert!(
            (after - before[k]).abs() <= 1e-9 * spin_scale,
            "pair {k}: angular momentum {} -> {after}",
            before[k]
        );
    }
}

/// An ellipse's flat side rolls on the stiffest rolling spring
/// (`k_roll (a²/b)²` against a wall): the stable step the driver estimates
/// lies below that rolling mode's, `2 √(I / k_r)`.
#[test]
fn the_stable_step_bounds_an_ellipses_rolling_mode() {
    let mut scene = Scene::new(Frame::open_box(2.0, 2.0).unwrap(), Vec2::new(0.0, -G)).unwrap();
    let (a, b) = (0.09, 0.03);
    scene
        .add_ellipse(Point::new(1.0, 0.5), a, b, 0.0, DENSITY)
        .unwrap();
    let p = &scene.particles[0];
    let k_roll = 50.0 * K_N;
    let law = RollingResistance::new(inner_law(), 0.3, k_roll).unwrap();
    let limit = dismech::explicit::critical_time_step(&scene, &law);
    let flat = a * a / b;
    let rolling_mode = 2.0 * (p.inertia / (k_roll * flat * flat)).sqrt();
    assert!(
        limit.dt <= rolling_mode,
        "stable step {} above the rolling mode's {rolling_mode}",
        limit.dt
    );
    // Without the rolling spring the estimate is the inner law's, above it.
    let inner = dismech::explicit::critical_time_step(&scene, &inner_law());
    assert!(inner.dt > rolling_mode, "{} <= {rolling_mode}", inner.dt);
}
