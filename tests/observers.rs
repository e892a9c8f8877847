//! Observers of a run: what they are told, that watching changes nothing,
//! that an observer's error stops the run, and ParaView frames written by
//! one.

use dismech::dem::DemSimulation;
use dismech::error::DismechError;
use dismech::explicit::{DemSettings, RestCriterion, RunStatus};
use dismech::integrate::ExplicitEuler;
use dismech::law::SpringDashpotCoulomb;
use dismech::math::{Point, Vec2};
use dismech::observe::{every, Event};
use dismech::scene::{Frame, Scene};
use dismech::vtk::DemFrames;

type Dem = DemSimulation<SpringDashpotCoulomb>;

/// A few discs and an ellipse dropped into a box.
fn dem() -> Dem {
    let mut scene = Scene::new(Frame::open_box(1.0, 1.0).unwrap(), Vec2::new(0.0, -9.81)).unwrap();
    for k in 0..4 {
        scene
            .add_circle(
                Point::new(0.2 + 0.2 * k as f64, 0.1 + 0.05 * k as f64),
                0.05,
                2600.0,
            )
            .unwrap();
    }
    scene
        .add_ellipse(Point::new(0.5, 0.4), 0.08, 0.04, 0.3, 2600.0)
        .unwrap();
    let law = SpringDashpotCoulomb::katsuki(73.55e6, 0.3, 0.25, 0.577).unwrap();
    DemSimulation::new(scene, law, ExplicitEuler, DemSettings::default()).unwrap()
}

fn criterion() -> RestCriterion {
    RestCriterion {
        max_time: 0.5,
        check_every: 50,
        ..RestCriterion::default()
    }
}

/// Every step is told once, in order, then each check, then the end; the
/// run observed ends in the same bits as the run not observed, and the
/// old callback sees the checks' ratios.
#[test]
fn an_observer_sees_every_step_and_check_and_changes_nothing() {
    let mut plain = dem();
    let mut ratios = Vec::new();
    let outcome = plain
        .run_to_rest(&criterion(), |_, ratio| ratios.push(ratio))
        .unwrap();

    let mut observed = dem();
    let (mut steps, mut checks, mut finished) = (Vec::new(), Vec::new(), Vec::new());
    let mut last = 'n';
    let seen = observed
        .run_to_rest_observed(&criterion(), &mut |d: &Dem, e: &Event<'_>| {
            assert_ne!(last, 'f', "an event after the end");
            match *e {
                Event::Step { step, time } => {
                    assert_eq!((step, time), (d.steps(), d.time()));
                    steps.push(step);
                    last = 's';
                }
                Event::Check { rest_ratio, .. } => {
                    assert_eq!(last, 's', "a check follows a step");
                    checks.push(rest_ratio);
                    last = 'c';
                }
                Event::Finished { step, time } => {
                    finished.push((step, time));
                    last = 'f';
                }
                other => panic!("the explicit driver sent {other:?}"),
            }
            Ok(())
        })
        .unwrap();
    assert_eq!(seen, outcome);
    assert_eq!(steps, (1..=outcome.steps).collect::<Vec<_>>());
    assert_eq!(checks, ratios);
    assert_eq!(finished, [(outcome.steps, observed.time())]);
    for (a, b) in plain
        .scene()
        .particles
        .iter()
        .zip(&observed.scene().particles)
    {
        assert_eq!(a.pose.position.x.to_bits(), b.pose.position.x.to_bits());
        assert_eq!(a.pose.position.y.to_bits(), b.pose.position.y.to_bits());
        assert_eq!(a.velocity.x.to_bits(), b.velocity.x.to_bits());
        assert_eq!(a.angular_velocity.to_bits(), b.angular_velocity.to_bits());
    }
}

/// An observer that fails stops the run at that step with its error.
#[test]
fn an_observer_error_stops_the_run() {
    let mut sim = dem();
    let result = sim.run_to_rest_observed(&criterion(), &mut |d: &Dem, _: &Event<'_>| {
        if d.steps() == 10 {
            return Err(DismechError::InvalidParameter {
                name: "observer",
                value: 10.0,
                requirement: "stops at step 10",
            });
        }
        Ok(())
    });
    assert!(matches!(
        result,
        Err(DismechError::InvalidParameter {
            name: "observer",
            ..
        })
    ));
    assert_eq!(sim.steps(), 10);
}

/// ParaView frames every 200 steps and at the end, by an observer: the
/// series lists their times, each a step of the run, and the last is the
/// run's end.
#[test]
fn frames_are_written_by_an_observer_every_n_steps_and_at_the_end() {
    let folder =
        std::env::temp_dir().join(format!("dismech-observed-frames-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&folder);
    let mut sim = dem();
    let dt = DemSettings::default().dt;
    let mut initial = DemFrames::new(&folder, 24).unwrap();
    initial.write(&sim).unwrap();
    let mut frames = every(200, initial);
    let outcome = sim.run_to_rest_observed(&criterion(), &mut frames).unwrap();
    assert_ne!(outcome.status, RunStatus::StepLimit);
    let frames = frames.into_inner();
    let times: Vec<f64> = frames
        .series()
        .entries("particles")
        .iter()
        .map(|e| e.time)
        .collect();
    let expected: Vec<u64> = (0..=outcome.steps / 200)
        .map(|k| 200 * k)
        .chain((outcome.steps % 200 != 0).then_some(outcome.steps))
        .collect();
    assert_eq!(times.len(), expected.len());
    assert_eq!(*times.last().unwrap(), sim.time());
    for (t, step) in times.iter().zip(&expected) {
        assert!((t - *step as f64 * dt).abs() < 1e-9, "{t} for step {step}");
    }
    for name in ["particles", "contacts", "walls"] {
        let pvd = std::fs::read_to_string(frames.series().pvd_path(name)).unwrap();
        assert_eq!(pvd.matches("<DataSet").count(), expected.len(), "{name}");
    }
    std::fs::remove_dir_all(&folder).unwrap();
}

/// A DDA block of 1 × 0.5 m, `gap` m above a fixed base (E = 1 GPa,
/// penalty 1e9, μ = 0.5, return mapping).
fn block_on_base(gap: f64) -> dismech::dda::DdaModel {
    use dismech::dda::{
        Block, BlockMaterial, DdaModel, DdaSettings, FrictionIntegration, PenaltyCoulomb,
        PlaneState, Prescribed,
    };
    let rect = |x0: f64, y0: f64, x1: f64, y1: f64| {
        [
            Point::new(x0, y0),
            Point::new(x1, y0),
            Point::new(x1, y1),
            Point::new(x0, y1),
        ]
    };
    let rock = BlockMaterial {
        density: 2200.0,
        youngs_modulus: 1e9,
        poisson_ratio: 0.2,
        plane: PlaneState::Strain,
    };
    let mut base = Block::new(&rect(-1.0, -1.0, 1.0, 0.0), rock, 0).unwrap();
    base.prescribed = Some(Prescribed::fixed());
    let block = Block::new(&rect(-0.5, gap, 0.5, gap + 0.5), rock, 1).unwrap();
    let law = PenaltyCoulomb::new(1e9, 0.5, FrictionIntegration::ReturnMapping).unwrap();
    DdaModel::new(vec![base, block], law, DdaSettings::default()).unwrap()
}

/// The implicit driver tells an observer every accepted sub-step, every
/// halving with its cause, and the end of the interval: a block 2 cm above
/// a base, one call of 0.1 s, lands in halved sub-steps; the events add up
/// to the call's report, the sub-steps tile the interval, and the model
/// ends where the unobserved one does, bit for bit.
#[test]
fn the_implicit_driver_tells_its_sub_steps_and_halvings() {
    use dismech::dda::{DdaModel, Halvings};
    let model = || block_on_base(0.02);
    let mut plain = model();
    let expected = plain.advance(0.1).unwrap();
    assert!(expected.reductions > 0, "the landing needs halvings");

    let mut observed = model();
    let (mut substeps, mut halvings, mut finished) = (Vec::new(), Halvings::default(), Vec::new());
    let mut covered = 0.0;
    let report = observed
        .advance_observed(0.1, &mut |m: &DdaModel, e: &Event<'_>| {
            assert!(finished.is_empty(), "an event after the end");
            match *e {
                Event::SubStep { substep, time, dt } => {
                    assert_eq!(time, m.time());
                    covered += dt;
                    substeps.push(substep);
                }
                Event::Halved { time, reason, .. } => {
                    assert_eq!(time, m.time());
                    halvings.count(reason);
                }
                Event::Finished { step, time } => finished.push((step, time)),
                other => panic!("the implicit driver sent {other:?}"),
            }
            Ok(())
        })
        .unwrap();
    assert_eq!(report, expected);
    assert_eq!(substeps, (1..=report.substeps).collect::<Vec<_>>());
    assert_eq!(halvings, report.halvings);
    assert!((covered - 0.1).abs() < 1e-12, "{covered}");
    assert_eq!(finished, [(report.substeps as u64, observed.time())]);
    for (a, b) in plain.blocks().iter().zip(observed.blocks()) {
        for k in 0..6 {
            assert_eq!(a.displacement[k].to_bits(), b.displacement[k].to_bits());
            assert_eq!(a.velocity[k].to_bits(), b.velocity[k].to_bits());
        }
    }
}

/// `every(n, o)` counts the implicit sub-steps it is told of across calls:
/// twenty calls of one sub-step each reach it four times at n = 5.
#[test]
fn every_counts_implicit_sub_steps_across_calls() {
    use dismech::dda::DdaModel;
    let mut model = block_on_base(0.0);
    let mut seen = Vec::new();
    let mut every_fifth = every(5, |m: &DdaModel, e: &Event<'_>| {
        if let Event::SubStep { .. } = e {
            seen.push(m.time());
        }
        Ok(())
    });
    let mut substeps = 0;
    for _ in 0..20 {
        substeps += model
            .advance_observed(1e-3, &mut every_fifth)
            .unwrap()
            .substeps;
    }
    assert_eq!(substeps, 20, "one sub-step a call");
    assert_eq!(seen.len(), 4);
}

/// Timing the phases counts every step and every build of the list, takes
/// time in each phase, and changes no bit of the run.
#[test]
fn phase_times_count_the_steps_and_builds_and_change_nothing() {
    let (mut timed, mut plain) = (dem(), dem());
    assert!(timed.phase_times().is_none());
    for _ in 0..100 {
        timed.step().unwrap();
        plain.step().unwrap();
    }
    timed.time_phases();
    let builds = timed.neighbour_list_builds();
    for _ in 0..2000 {
        timed.step().unwrap();
        plain.step().unwrap();
    }
    let times = *timed.phase_times().unwrap();
    assert_eq!(times.steps, 2000);
    assert_eq!(times.builds, timed.neighbour_list_builds() - builds);
    assert!(times.builds > 0, "the discs fell through the skin");
    for (name, time) in times.phases() {
        assert!(!time.is_zero(), "no time in {name}");
    }
    assert_eq!(times.total(), times.phases().iter().map(|(_, t)| *t).sum());
    let table = times.to_string();
    assert!(
        table.contains("2000 steps") && table.contains("forces"),
        "{table}"
    );
    let bits = |s: &Dem| -> Vec<u64> {
        s.scene()
            .particles
            .iter()
            .flat_map(|p| [p.pose.position.x, p.pose.position.y, p.pose.angle])
            .map(f64::to_bits)
            .collect()
    };
    assert_eq!(bits(&timed), bits(&plain));
    // Asked again, the times start from zero.
    timed.time_phases();
    assert_eq!(timed.phase_times().unwrap().steps, 0);
}

/// A 4 × 5-column slab 6 m thick on a slip plane dipping 20° (c = 5 kPa),
/// for HPM's nonlinear analysis and strength reduction.
fn cohesive_slab() -> dismech::hpm::HpmModel {
    use dismech::grid::Raster;
    use dismech::hpm::{HpmMaterial, HpmModel, HpmSettings, NamedRaster, SlopeGrids};
    let slope = 20f64.to_radians().tan();
    let plane = |offset: f64| {
        Raster::from_fn(5, 4, 0.0, 0.0, 10.0, move |x, _| {
            Some(500.0 + slope * x + offset)
        })
        .unwrap()
    };
    let grids = SlopeGrids::new(
        NamedRaster::new("ground", plane(6.0)),
        NamedRaster::new("slip", plane(0.0)),
        None,
    )
    .unwrap();
    let material = HpmMaterial {
        cohesion: 5.0e3,
        ..HpmMaterial::paper()
    };
    HpmModel::new(&grids, &material, &HpmSettings::default()).unwrap()
}

#[test]
fn hpm_analyses_tell_every_iterate_and_trial_and_change_nothing() {
    use dismech::hpm::{
        strength_reduction, strength_reduction_observed, HpmIterate, HpmSolver, NonlinearSettings,
        Seismic,
    };
    let model = cohesive_slab();
    let settings = NonlinearSettings::default();
    let none = Seismic::none();
    let mut solver = HpmSolver::new(&model).unwrap();
    let plain = solver.nonlinear(&model, &none, 1.3, &settings).unwrap();

    // Every iterate of the nonlinear solve, the start and the one returned
    // included, with the displacements of the iterate.
    let mut seen: Vec<(usize, f64, f64, Vec<f64>)> = Vec::new();
    let mut lasts = Vec::new();
    let mut record = |it: &HpmIterate<'_>, event: &Event<'_>| {
        if let Event::Iteration {
            iteration,
            residual,
            last,
        } = *event
        {
            seen.push((iteration, residual, it.reduction, it.displacements.to_vec()));
            lasts.push(last);
        }
        Ok(())
    };
    let observed = solver
        .nonlinear_observed(&model, &none, 1.3, &settings, &mut record)
        .unwrap();
    assert_eq!(observed, plain);
    assert!(
        plain.convergence.iterations() > 1,
        "{:?}",
        plain.convergence
    );
    assert_eq!(seen.len(), plain.convergence.iterations() + 1);
    for (k, (iteration, _, reduction, u)) in seen.iter().enumerate() {
        assert_eq!(*iteration, k);
        assert_eq!(*reduction, 1.3);
        assert_eq!(u.len(), plain.displacements.len());
    }
    assert!(seen[0].3.iter().all(|u| *u == 0.0), "the start is U = 0");
    // Only the iterate returned is the last.
    assert_eq!(lasts.iter().filter(|l| **l).count(), 1);
    assert_eq!(lasts.last(), Some(&true));
    let last = seen.last().unwrap();
    assert_eq!(last.1, plain.convergence.residual());
    assert_eq!(last.3, plain.displacements);

    // The strength reduction: one `Trial` per factor tried, in order, each
    // after the iterates of its analysis; the same search.
    let srf = strength_reduction(&mut solver, &model, &none, &settings, 0.01).unwrap();
    let mut events: Vec<String> = Vec::new();
    let mut trials: Vec<(f64, bool)> = Vec::new();
    let mut watch = |it: &HpmIterate<'_>, event: &Event<'_>| {
        match *event {
            Event::Iteration { iteration, .. } => {
                events.push(format!("i{iteration}@{}", it.reduction))
            }
            Event::Trial { factor, converged } => {
                assert_eq!(factor, it.reduction);
                trials.push((factor, converged));
                events.push(format!("t@{factor}"));
            }
            _ => panic!("an HPM analysis sends iterations and trials only: {event:?}"),
        }
        Ok(())
    };
    let observed =
        strength_reduction_observed(&mut solver, &model, &none, &settings, 0.01, &mut watch)
            .unwrap();
    assert_eq!(observed, srf);
    let expected: Vec<(f64, bool)> = srf
        .trials
        .iter()
        .map(|(f, c)| (*f, c.converged()))
        .collect();
    assert_eq!(trials, expected);
    let iterates: usize = srf.trials.iter().map(|(_, c)| c.iterations() + 1).sum();
    assert_eq!(events.len(), iterates + srf.trials.len());
    // Each trial's events: its iterates 0, 1, … at its factor, then the trial.
    let mut k = 0;
    for (factor, convergence) in &srf.trials {
        for i in 0..=convergence.iterations() {
            assert_eq!(events[k], format!("i{i}@{factor}"));
            k += 1;
        }
        assert_eq!(events[k], format!("t@{factor}"));
        k += 1;
    }

    // An observer's error stops the analysis at that iterate.
    let mut stop_at_two = |_: &HpmIterate<'_>, event: &Event<'_>| match event {
        Event::Iteration { iteration: 2, .. } => Err(DismechError::InvalidParameter {
            name: "test stop",
            value: 2.0,
            requirement: "stops the analysis",
        }),
        _ => Ok(()),
    };
    let stopped = solver.nonlinear_observed(&model, &none, 1.3, &settings, &mut stop_at_two);
    assert!(
        matches!(
            stopped,
            Err(DismechError::InvalidParameter {
                name: "test stop",
                ..
            })
        ),
        "{stopped:?}"
    );
}
