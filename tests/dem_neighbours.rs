//! The explicit driver's neighbour list and parallel loops change the
//! speed, not the run: the same scene stepped with the list built at every
//! step, with a skin, and on one or two threads ends in the same state to
//! the last bit; the same scene renumbered for locality ends in the same
//! state to round-off (the sums run in another order).

use dismech::dem::DemSimulation;
use dismech::explicit::{ContactRecord, ContactTarget, DemSettings};
use dismech::integrate::ExplicitEuler;
use dismech::law::{Damping, NormalStiffness, SpringDashpotCoulomb};
use dismech::math::{Point, Vec2};
use dismech::scene::{Frame, Scene};

const DENSITY: f64 = 2690.0;

fn law(k_n: f64, gamma_n: f64) -> SpringDashpotCoulomb {
    SpringDashpotCoulomb::new(
        NormalStiffness::Constant(k_n),
        2.0 / 7.0,
        0.577,
        Damping::PerMass {
            normal: gamma_n,
            shear: 0.5 * gamma_n,
        },
    )
    .unwrap()
}

/// Circles, ellipses and polygons (a square, a triangle and an L) falling
/// into an open box, a few thrown sideways so that they roll and collide.
fn mixed_scene() -> Scene {
    mixed_rows(48, 8, false)
}

/// `count` bodies as [`mixed_scene`]'s, in rows of `columns`, numbered
/// along the rows or, `by_column`, up the columns (so that bodies of
/// distant numbers meet side by side).
fn mixed_rows(count: usize, columns: usize, by_column: bool) -> Scene {
    let rows = count.div_ceil(columns);
    let mut scene = Scene::new(
        Frame::open_box(0.2 * columns as f64, 0.2 * rows as f64 + 1.8).unwrap(),
        Vec2::new(0.0, -9.81),
    )
    .unwrap();
    for k in 0..count {
        let (col, row) = if by_column {
            (k / rows, k % rows)
        } else {
            (k % columns, k / columns)
        };
        let centre = Point::new(0.12 + 0.19 * col as f64, 0.12 + 0.2 * row as f64);
        let index = match k % 4 {
            0 => scene.add_circle(centre, 0.07 + 0.002 * (row % 6) as f64, DENSITY),
            1 => scene.add_ellipse(centre, 0.08, 0.05, 0.3 * k as f64, DENSITY),
            2 => scene.add_rectangle(centre, 0.12, 0.09, 0.2 * (row % 6) as f64, DENSITY),
            _ => {
                let shape: &[(f64, f64)] = if row % 2 == 0 {
                    &[(-0.07, -0.05), (0.07, -0.05), (0.0, 0.07)]
                } else {
                    &[
                        (-0.06, -0.06),
                        (0.06, -0.06),
                        (0.06, 0.0),
                        (0.0, 0.0),
                        (0.0, 0.06),
                        (-0.06, 0.06),
                    ]
                };
                let vertices: Vec<Point> = shape
                    .iter()
                    .map(|&(x, y)| centre + Vec2::new(x, y))
                    .collect();
                scene.add_polygon(&vertices, DENSITY)
            }
        }
        .unwrap();
        let p = &mut scene.particles[index];
        p.velocity = Vec2::new(if k % 3 == 0 { 1.5 } else { -0.7 }, 0.0);
        p.angular_velocity = 0.5 * (k % 5) as f64 - 1.0;
    }
    scene
}

/// A lattice of `nx × ny` disks in a box, as the throughput example's.
fn disk_lattice(nx: usize, ny: usize) -> Scene {
    let mut scene = Scene::new(
        Frame::open_box(nx as f64 * 0.14, ny as f64 * 0.21).unwrap(),
        Vec2::new(0.0, -9.81),
    )
    .unwrap();
    for j in 0..ny {
        for i in 0..nx {
            let k = j * nx + i;
            let r = 0.06 + 0.009 * ((k * 7919) % 101) as f64 / 100.0;
            let centre = Point::new((i as f64 + 0.5) * 0.14, (j as f64 + 0.5) * 0.14);
            let index = scene.add_circle(centre, r, DENSITY).unwrap();
            scene.particles[index].velocity =
                Vec2::new(0.2 * (((k * 104729) % 97) as f64 / 96.0 - 0.5), 0.0);
        }
    }
    scene
}

/// Every pose and velocity of the run's end, as bits.
fn state_bits(sim: &DemSimulation<SpringDashpotCoulomb>) -> Vec<u64> {
    sim.scene()
        .particles
        .iter()
        .flat_map(|p| {
            [
                p.pose.position.x,
                p.pose.position.y,
                p.pose.angle,
                p.velocity.x,
                p.velocity.y,
                p.angular_velocity,
            ]
        })
        .map(f64::to_bits)
        .collect()
}

fn run(
    scene: Scene,
    (k_n, gamma_n): (f64, f64),
    skin: Option<f64>,
    steps: usize,
) -> DemSimulation<SpringDashpotCoulomb> {
    let settings = DemSettings {
        dt: 1e-4,
        neighbour_skin: skin,
        ..DemSettings::default()
    };
    let mut sim = DemSimulation::new(scene, law(k_n, gamma_n), ExplicitEuler, settings).unwrap();
    for _ in 0..steps {
        sim.step().unwrap();
    }
    sim
}

#[test]
fn the_skin_changes_how_often_the_list_is_built_not_the_run() {
    let steps = 6000;
    let every_step = run(mixed_scene(), (4e6, 200.0), Some(0.0), steps);
    let automatic = run(mixed_scene(), (4e6, 200.0), None, steps);
    let wide = run(mixed_scene(), (4e6, 200.0), Some(0.05), steps);
    // Enough happened: the bodies fell into a pile of polygon contacts.
    let records = every_step.contacts();
    assert!(records.len() > 60, "{} contacts", records.len());
    assert!(records
        .iter()
        .any(|c| c.features.a != dismech::query::Feature::Whole));
    assert_eq!(every_step.neighbour_list_builds(), steps as u64);
    for sim in [&automatic, &wide] {
        assert!(
            sim.neighbour_list_builds() < steps as u64 / 4,
            "{} builds in {steps} steps",
            sim.neighbour_list_builds()
        );
        assert_eq!(state_bits(sim), state_bits(&every_step));
        assert_eq!(sim.contacts(), records);
    }
}

#[test]
fn one_and_two_threads_give_the_same_bits() {
    let run_on = |threads: usize| -> (Vec<u64>, Vec<ContactRecord>) {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            assert_eq!(rayon::current_num_threads(), threads);
            let sim = run(disk_lattice(50, 44), (1.6e7, 2000.0), None, 4000);
            (state_bits(&sim), sim.contacts().to_vec())
        })
    };
    let (one, one_contacts) = run_on(1);
    let (two, two_contacts) = run_on(2);
    assert!(one_contacts.len() > 2000, "{} contacts", one_contacts.len());
    assert_eq!(one, two);
    assert_eq!(one_contacts, two_contacts);
}

/// The step's momentum gained, `Σ m Δv`, less the impulse of the weights
/// and the walls' reactions, `Δt (Σ m g − Σ f_wall)`, over the impulse of
/// the average particle's weight (a pair's force lost or added twice
/// makes it of the order of that pair's force over a weight; the
/// round-off of the velocity differences, `ε Σ m |v| / (Δt m g)`, is
/// about 1e-10 here).
fn momentum_imbalance(sim: &DemSimulation<SpringDashpotCoulomb>, before: &[Vec2]) -> f64 {
    let dt = 1e-4;
    let particles = &sim.scene().particles;
    let gained: Vec2 = particles
        .iter()
        .zip(before)
        .map(|(p, v)| p.mass * (p.velocity - v))
        .sum();
    let weight: Vec2 = particles.iter().map(|p| p.mass * sim.scene().gravity).sum();
    let contacts = sim.contacts();
    let on_walls: Vec2 = contacts
        .iter()
        .filter(|c| matches!(c.target, ContactTarget::Wall(_)))
        .map(|c| c.force_on_target)
        .sum();
    let average_weight = weight.norm() / particles.len() as f64;
    (gained - dt * (weight - on_walls)).norm() / (dt * average_weight)
}

/// Each particle's centre and velocities before a step.
type Motion = (Point, Vec2, f64);

/// The step's angular momentum about the origin gained by the forces,
/// `Σ (m x × Δv + I Δω)` with `x` the centres before the step, less the
/// impulse of the weights' and the walls' moments about the origin,
/// `Δt (Σ x × m g + Σ p × (−f_wall))`, over the impulse of the average
/// weight's moment at 0.07 m (about a body's radius). A pair's forces and
/// their moments about the two centres have no moment about the origin
/// together, so a moment lost or added twice (a polygon point's about B's
/// centre, say) makes it of the order of that moment over a weight's
/// (10–80 when one of the three sums of polygon points' moments is left
/// out); the round-off of `m x × Δv` over the pile, about 12 m wide, made
/// at most 1.7e-8 in this test's run.
fn angular_momentum_imbalance(sim: &DemSimulation<SpringDashpotCoulomb>, before: &[Motion]) -> f64 {
    let dt = 1e-4;
    let cross = |a: Vec2, b: Vec2| a.x * b.y - a.y * b.x;
    let g = sim.scene().gravity;
    let particles = &sim.scene().particles;
    let (mut gained, mut of_weights) = (0.0, 0.0);
    for (p, &(x, v, omega)) in particles.iter().zip(before) {
        gained +=
            p.mass * cross(x.coords, p.velocity - v) + p.inertia * (p.angular_velocity - omega);
        of_weights += cross(x.coords, p.mass * g);
    }
    let of_walls: f64 = sim
        .contacts()
        .iter()
        .filter(|c| matches!(c.target, ContactTarget::Wall(_)))
        .map(|c| cross(c.point.coords, -c.force_on_target))
        .sum();
    let average_weight =
        particles.iter().map(|p| p.mass * g.norm()).sum::<f64>() / particles.len() as f64;
    (gained - dt * (of_weights + of_walls)).abs() / (dt * average_weight * 0.07)
}

/// A pile of 2100 circles, ellipses and polygons: above the threshold of
/// the parallel loops (2000 particles) and three blocks of the force sums
/// (1024 particles each), with polygon pairs of several points whose B is
/// in a later block than their A. One thread with the automatic skin, two
/// threads with it and two threads building the list at every step end in
/// the same bits.
#[test]
fn a_mixed_pile_of_three_blocks_gives_the_same_bits_on_two_threads_and_any_skin() {
    let steps = 1500;
    // Each run's end, its contact records, its list's builds and how many
    // polygon points joined bodies of different blocks over the steps.
    let run_on = |threads: usize, skin: Option<f64>| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let settings = DemSettings {
                dt: 1e-4,
                neighbour_skin: skin,
                ..DemSettings::default()
            };
            let scene = mixed_rows(2100, 60, true);
            let mut sim =
                DemSimulation::new(scene, law(4e6, 200.0), ExplicitEuler, settings).unwrap();
            let mut crossing_polygon_points = 0;
            let mut worst_imbalance = 0.0f64;
            let mut worst_turning_imbalance = 0.0f64;
            for _ in 0..steps {
                let before: Vec<Motion> = sim
                    .scene()
                    .particles
                    .iter()
                    .map(|p| (p.pose.position, p.velocity, p.angular_velocity))
                    .collect();
                let velocities: Vec<Vec2> = before.iter().map(|m| m.1).collect();
                sim.step().unwrap();
                worst_imbalance = worst_imbalance.max(momentum_imbalance(&sim, &velocities));
                worst_turning_imbalance =
                    worst_turning_imbalance.max(angular_momentum_imbalance(&sim, &before));
                crossing_polygon_points += sim
                    .contacts()
                    .iter()
                    .filter(|c| match c.target {
                        ContactTarget::Particle(b) => c.particle / 1024 != b / 1024,
                        ContactTarget::Wall(_) => false,
                    })
                    .filter(|c| c.features.a != dismech::query::Feature::Whole)
                    .count();
            }
            (
                state_bits(&sim),
                sim.contacts().to_vec(),
                sim.neighbour_list_builds(),
                crossing_polygon_points,
                worst_imbalance,
                worst_turning_imbalance,
            )
        })
    };
    let (one, one_contacts, one_builds, crossing, imbalance, turning_imbalance) = run_on(1, None);
    assert!(
        crossing > 1000,
        "{crossing} polygon points across blocks over the run"
    );
    // Every pair's force reached both bodies once, across blocks too: the
    // momentum gained is the impulse of the weights and the walls.
    assert!(imbalance < 1e-6, "momentum imbalance {imbalance:e}");
    // And each moment about a centre too (those of a polygon pair's points
    // are computed from the point and the force when they are summed).
    assert!(
        turning_imbalance < 1e-6,
        "angular momentum imbalance {turning_imbalance:e}"
    );
    let (two, two_contacts, two_builds, ..) = run_on(2, None);
    assert_eq!(two_builds, one_builds);
    assert_eq!(two, one);
    assert_eq!(two_contacts, one_contacts);
    let (every_step, every_step_contacts, builds, ..) = run_on(2, Some(0.0));
    assert_eq!(builds, steps as u64);
    assert!(one_builds < builds / 4, "{one_builds} builds");
    assert_eq!(every_step, one);
    assert_eq!(every_step_contacts, one_contacts);
}

/// Renumbering a scene for locality changes the order of the force sums,
/// not the physics: 2 100 disks (three blocks, numbered by rows of 100,
/// so that about one vertical pair in ten crosses blocks) and the same
/// disks renumbered in bands reach the same state after 3 000 steps
/// (0.3 s, the rows fallen onto each other), particle by particle, and the
/// same contacts with the same forces, to round-off grown over the run (measured: 4e-9 m,
/// 6e-7 m/s and 1.8e-8 of the largest force; the bounds, 1e-7 m, 1e-5 m/s
/// and 5e-7, are 17 to 28 times that, far below anything physical: 1e-6
/// of a diameter).
#[test]
fn renumbering_for_locality_changes_the_sums_order_not_the_run() {
    let scene = disk_lattice(100, 21);
    let mut renumbered = scene.clone();
    let old = renumbered.renumber_for_locality();
    assert_ne!(
        old,
        (0..old.len()).collect::<Vec<_>>(),
        "the numbering changed"
    );
    let steps = 3000;
    let a = run(scene, (1.6e7, 2000.0), None, steps);
    let b = run(renumbered, (1.6e7, 2000.0), None, steps);
    for (new, &was) in old.iter().enumerate() {
        let (p, q) = (&a.scene().particles[was], &b.scene().particles[new]);
        let moved =
            (p.pose.position - q.pose.position).norm() + (p.pose.angle - q.pose.angle).abs();
        let sped =
            (p.velocity - q.velocity).norm() + (p.angular_velocity - q.angular_velocity).abs();
        assert!(
            moved < 1e-7 && sped < 1e-5,
            "particle {was}: {moved:e} m, {sped:e} m/s"
        );
    }
    // Each contact by its particles' old indices, with the force that the
    // particle of lower old index exerts.
    let by_old = |records: &[ContactRecord], old_of: &dyn Fn(usize) -> usize| {
        let mut contacts: Vec<((usize, ContactTarget), Vec2)> = records
            .iter()
            .map(|r| match r.target {
                ContactTarget::Particle(j) => {
                    let (i, j) = (old_of(r.particle), old_of(j));
                    let sign = if i < j { 1.0 } else { -1.0 };
                    let key = (i.min(j), ContactTarget::Particle(i.max(j)));
                    (key, r.force_on_target * sign)
                }
                ContactTarget::Wall(w) => (
                    (old_of(r.particle), ContactTarget::Wall(w)),
                    r.force_on_target,
                ),
            })
            .collect();
        contacts.sort_by_key(|c| c.0);
        contacts
    };
    let (ca, cb) = (
        by_old(a.contacts(), &|i| i),
        by_old(b.contacts(), &|i| old[i]),
    );
    assert!(ca.len() > 1500, "{} contacts", ca.len());
    // The comparison meets both kinds of contact, and pairs whose order
    // the renumbering swapped (whose force changes sign in the records).
    let walls = b
        .contacts()
        .iter()
        .filter(|r| matches!(r.target, ContactTarget::Wall(_)))
        .count();
    let swapped = b
        .contacts()
        .iter()
        .filter(|r| matches!(r.target, ContactTarget::Particle(j) if old[r.particle] > old[j]))
        .count();
    assert!(
        walls > 0 && swapped > 0,
        "{walls} wall contacts, {swapped} swapped"
    );
    let pairs = |c: &[((usize, ContactTarget), Vec2)]| c.iter().map(|c| c.0).collect::<Vec<_>>();
    assert_eq!(pairs(&ca), pairs(&cb));
    let largest = ca.iter().fold(0.0f64, |m, c| m.max(c.1.norm()));
    for (x, y) in ca.iter().zip(&cb) {
        assert!(
            (x.1 - y.1).norm() < 5e-7 * largest,
            "{:?}: {} against {}",
            x.0,
            x.1,
            y.1
        );
    }
}

/// `nx × ny` disks of radius 0.05 m on a square lattice 0.12 m apart
/// (none touching), the lowest row's centres at `bottom`, the first
/// column's at `left`, all at `velocity`, in the scene.
fn add_lattice(
    scene: &mut Scene,
    (nx, ny): (usize, usize),
    left: f64,
    bottom: f64,
    velocity: Vec2,
) {
    for j in 0..ny {
        for i in 0..nx {
            let centre = Point::new(left + 0.12 * i as f64, bottom + 0.12 * j as f64);
            let index = scene.add_circle(centre, 0.05, DENSITY).unwrap();
            scene.particles[index].velocity = velocity;
        }
    }
}

/// The falling lattices' columns and rows.
const FALLING_LATTICE: (usize, usize) = (40, 30);

/// [`FALLING_LATTICE`]'s disks (1 200, two blocks), the lowest row's
/// centres 0.6 m above the floor of a box 6 m wide, all at `velocity`,
/// under gravity.
fn falling_lattice(velocity: Vec2) -> Scene {
    let mut scene = Scene::new(Frame::open_box(6.0, 5.0).unwrap(), Vec2::new(0.0, -9.81)).unwrap();
    add_lattice(&mut scene, FALLING_LATTICE, 0.6, 0.6, velocity);
    scene
}

/// The lowest particle centre's height.
fn lowest(sim: &DemSimulation<SpringDashpotCoulomb>) -> f64 {
    sim.scene()
        .particles
        .iter()
        .map(|p| p.pose.position.y)
        .fold(f64::INFINITY, f64::min)
}

/// With `relative_travel`, the list is kept while the particles move
/// together: what decides a build is how far they may have come closer to
/// each other (or to a wall they are not listed with), not how far they
/// moved. A lattice of 1 200 disks (two blocks) falls 0.44 m in 3 000
/// steps, untouched, in a box wide enough that no disk comes near the side
/// walls, then lands on the floor and bounces there for 2 000 steps. With
/// a skin of 0.01 m, the test of each disk's own travel (half the skin)
/// builds the list more than 80 times in the fall; the relative travel
/// keeps the list built at the start, and the run ends in the same bits as
/// one that builds the list at every step.
#[test]
fn a_packing_falling_as_a_whole_keeps_its_list_until_it_meets_the_floor() {
    let lattice = FALLING_LATTICE;
    let scene = || falling_lattice(Vec2::zeros());
    let skin = 0.01;
    let (fall, landing) = (3000, 2000);
    let settings = |relative_travel| DemSettings {
        dt: 1e-4,
        neighbour_skin: Some(skin),
        relative_travel,
        ..DemSettings::default()
    };
    let mut kept =
        DemSimulation::new(scene(), law(1.6e7, 2000.0), ExplicitEuler, settings(true)).unwrap();
    let mut own =
        DemSimulation::new(scene(), law(1.6e7, 2000.0), ExplicitEuler, settings(false)).unwrap();
    for _ in 0..fall {
        kept.step().unwrap();
        own.step().unwrap();
    }
    let fallen = 0.6 - lowest(&kept);
    assert!(fallen > 0.4 && lowest(&kept) > 0.05, "fell {fallen} m");
    assert!(kept.contacts().is_empty());
    let (own_builds, kept_builds) = (own.neighbour_list_builds(), kept.neighbour_list_builds());
    println!(
        "builds in the fall: {own_builds} by each disk's travel, {kept_builds} by the relative"
    );
    assert!(own_builds > 80, "{own_builds}");
    assert_eq!(kept.neighbour_list_builds(), 1);
    for _ in 0..landing {
        kept.step().unwrap();
        own.step().unwrap();
    }
    let every_step = run(scene(), (1.6e7, 2000.0), Some(0.0), fall + landing);
    assert_eq!(every_step.neighbour_list_builds(), (fall + landing) as u64);
    // It landed: the lowest row rests on the floor, and the rows on it.
    let on_floor = every_step
        .contacts()
        .iter()
        .filter(|c| matches!(c.target, ContactTarget::Wall(_)))
        .count();
    assert!(on_floor >= lattice.0, "{on_floor} disks on the floor");
    println!("{} contacts at the end", every_step.contacts().len());
    assert!(every_step.contacts().len() > lattice.0 * 20);
    assert!(
        kept.neighbour_list_builds() < (fall + landing) as u64 / 10,
        "{} builds",
        kept.neighbour_list_builds()
    );
    for sim in [&kept, &own] {
        assert_eq!(state_bits(sim), state_bits(&every_step));
        assert_eq!(sim.contacts(), every_step.contacts());
    }
}

/// The tuned skin (the default, `neighbour_skin: None`) widens while the
/// particles move fast and the list is built often, and narrows again once
/// the builds are rare; only how often the list is built changes. The
/// lattice of 1 200 disks above, thrown down at 4 m/s, falls 0.45 m in
/// 1 000 steps: with the least skin held fixed (0.15 of the radius,
/// 0.0075 m) the list is built more than 100 times, with the tuned skin
/// at most half as often, its skin by then wider than the least. After
/// 3 000 steps of landing and bouncing (1 200 contacts at the most) the
/// skin is back to the least, and both runs end in the bits of one that
/// builds the list at every step.
#[test]
fn the_tuned_skin_widens_in_a_fall_and_keeps_the_bits() {
    let lattice = FALLING_LATTICE;
    let scene = || falling_lattice(Vec2::new(0.0, -4.0));
    let least = 0.15 * 0.05;
    let (fall, landing) = (1000, 3000);
    let start = |skin| {
        let settings = DemSettings {
            dt: 1e-4,
            neighbour_skin: skin,
            ..DemSettings::default()
        };
        DemSimulation::new(scene(), law(1.6e7, 2000.0), ExplicitEuler, settings).unwrap()
    };
    let (mut tuned, mut fixed) = (start(None), start(Some(least)));
    assert_eq!(tuned.neighbour_skin(), least);
    for _ in 0..fall {
        tuned.step().unwrap();
        fixed.step().unwrap();
    }
    assert!(tuned.contacts().is_empty());
    let bottom = lowest(&tuned);
    assert!(
        bottom < 0.2 && bottom > 0.05,
        "the lowest centre at {bottom} m"
    );
    let (tuned_builds, fixed_builds) =
        (tuned.neighbour_list_builds(), fixed.neighbour_list_builds());
    let falling_skin = tuned.neighbour_skin();
    println!(
        "in the fall: {fixed_builds} builds with the least skin, {tuned_builds} tuned (skin {falling_skin} m)"
    );
    assert!(fixed_builds > 100, "{fixed_builds}");
    assert!(
        2 * tuned_builds <= fixed_builds,
        "{tuned_builds} against {fixed_builds}"
    );
    assert!(
        falling_skin > 1.5 * least && falling_skin <= 4.0 * least,
        "{falling_skin}"
    );
    assert_eq!(fixed.neighbour_skin(), least);
    // The most contacts at a step of the landing.
    let mut most_contacts = 0;
    for _ in 0..landing {
        tuned.step().unwrap();
        fixed.step().unwrap();
        most_contacts = most_contacts.max(tuned.contacts().len());
    }
    println!(
        "{most_contacts} contacts at most in the landing, {} at the end",
        tuned.contacts().len()
    );
    assert!(most_contacts > lattice.0 * 20, "{most_contacts} contacts");
    let settled_skin = tuned.neighbour_skin();
    println!("after landing: skin {settled_skin} m");
    assert_eq!(settled_skin, least);
    let every_step = run(scene(), (1.6e7, 2000.0), Some(0.0), fall + landing);
    for sim in [&tuned, &fixed] {
        assert_eq!(state_bits(sim), state_bits(&every_step));
        assert_eq!(sim.contacts(), every_step.contacts());
    }
}

/// With `relative_travel`, two blocks of particles moving towards each
/// other keep the list until they may have met: two lattices of 1 024 disks (one block each),
/// 0.3 m apart and closing at 2 m/s without gravity, need no build in
/// the 1 400 steps before they meet (a test of each disk's own travel,
/// with a skin of 0.01 m, would build 28 times); then they collide, and
/// the run ends in the same bits as one that builds the list at every
/// step.
#[test]
fn two_blocks_closing_on_each_other_keep_the_list_until_they_meet() {
    let scene = || {
        let mut scene = Scene::new(Frame::open_box(12.0, 6.0).unwrap(), Vec2::zeros()).unwrap();
        // 32 × 32 disks each: 3.82 m wide, the second 0.3 m (between
        // boxes) to the right of the first.
        add_lattice(&mut scene, (32, 32), 1.0, 1.0, Vec2::new(1.0, 0.0));
        add_lattice(
            &mut scene,
            (32, 32),
            1.0 + 31.0 * 0.12 + 0.05 + 0.3 + 0.05,
            1.0,
            Vec2::new(-1.0, 0.0),
        );
        scene
    };
    let settings = DemSettings {
        dt: 1e-4,
        neighbour_skin: Some(0.01),
        relative_travel: true,
        ..DemSettings::default()
    };
    let mut kept =
        DemSimulation::new(scene(), law(1.6e7, 2000.0), ExplicitEuler, settings).unwrap();
    for _ in 0..1400 {
        kept.step().unwrap();
    }
    assert!(kept.contacts().is_empty());
    assert_eq!(kept.neighbour_list_builds(), 1);
    let steps = 2500;
    // The most contacts between the lattices at one step.
    let mut across = 0;
    for _ in 1400..steps {
        kept.step().unwrap();
        let now = kept
            .contacts()
            .iter()
            .filter(|c| {
                matches!(c.target, ContactTarget::Particle(b) if c.particle < 1024 && b >= 1024)
            })
            .count();
        across = across.max(now);
    }
    assert!(across >= 32, "{across} contacts between the lattices");
    let every_step = run(scene(), (1.6e7, 2000.0), Some(0.0), steps);
    assert_eq!(state_bits(&kept), state_bits(&every_step));
    assert_eq!(kept.contacts(), every_step.contacts());
}
