//! The explicit driver's neighbour list and parallel loops change the
//! speed, not the run: the same scene stepped with the list built at every
//! step, with a skin, and on one or two threads ends in the same state to
//! the last bit.

use dismech::dem::{ContactRecord, DemSettings, DemSimulation};
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
    let mut scene = Scene::new(Frame::open_box(1.6, 3.0).unwrap(), Vec2::new(0.0, -9.81)).unwrap();
    for k in 0..48 {
        let (col, row) = (k % 8, k / 8);
        let centre = Point::new(0.12 + 0.19 * col as f64, 0.12 + 0.2 * row as f64);
        let index = match k % 4 {
            0 => scene.add_circle(centre, 0.07 + 0.002 * row as f64, DENSITY),
            1 => scene.add_ellipse(centre, 0.08, 0.05, 0.3 * k as f64, DENSITY),
            2 => scene.add_rectangle(centre, 0.12, 0.09, 0.2 * row as f64, DENSITY),
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
