//! A fuzzer of the DEM's, the DDA's, the limit analysis' and HPM's public
//! constructors and first steps or analyses: every value drawn from a mix of ordinary, extreme (subnormal,
//! 1e±300, ±0) and invalid (negative, NaN, ±∞) numbers. Whatever is drawn,
//! nothing panics, every call returns within its bounds, an accepted model
//! steps to finite states or stops with a typed error, and an error's
//! message is not empty.
//!
//! `cargo test` runs 1 500 cases a driver; set `DISMECH_FUZZ_CASES` for
//! more (`DISMECH_FUZZ_CASES=100000 cargo test --release --test
//! integration constructor_fuzz::`, a few minutes).

use dismech::dda::{
    Block, BlockMaterial, DdaModel, DdaSettings, FrictionIntegration, PenaltyCoulomb, PlaneState,
    Prescribed,
};
use dismech::dem::DemSimulation;
use dismech::error::DismechError;
use dismech::explicit::{DemSettings, RestCriterion};
use dismech::grid::Raster;
use dismech::hpm::HpmError;
use dismech::hpm::{
    hovland, HpmMaterial, HpmModel, HpmSettings, HpmSolver, NamedRaster, Seismic, SlopeGrids,
};
use dismech::implicit::ImplicitError;
use dismech::integrate::ExplicitEuler;
use dismech::law::{Damping, NormalStiffness, RigidPlastic, SpringDashpotCoulomb};
use dismech::limit::{analyse, analyse_static, LimitModel, LimitStatus, Partner};
use dismech::lp::LinearProgramSolver;
use dismech::math::{Point, Vec2};
use dismech::scene::{Frame, Scene};
use proptest::prelude::*;

/// The horizontal unit vector at `deg` degrees counter-clockwise from +x.
fn towards_deg(deg: f64) -> (f64, f64) {
    let t = deg.to_radians();
    (t.cos(), t.sin())
}

/// Cases a driver: 1 500, or `DISMECH_FUZZ_CASES`.
fn cases() -> u32 {
    std::env::var("DISMECH_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1500)
}

/// A number around `typical`: mostly ordinary (a factor of 1e±1 of it),
/// one in 21 extreme or invalid (so that about half the cases draw only
/// ordinary values and reach the stepping).
fn wild(typical: f64) -> impl Strategy<Value = f64> {
    prop_oneof![
        20 => (-1.0f64..1.0).prop_map(move |e| typical * 10f64.powf(e)),
        1 => prop::sample::select(vec![
            0.0,
            -0.0,
            5e-324,
            1e-300,
            1e300,
            f64::MAX,
            f64::MIN_POSITIVE,
            -typical,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ]),
    ]
}

/// A message says something.
fn said(e: &DismechError) -> bool {
    !e.to_string().trim().is_empty()
}

#[derive(Debug, Clone)]
enum Grain {
    Circle {
        x: f64,
        y: f64,
        r: f64,
    },
    Ellipse {
        x: f64,
        y: f64,
        a: f64,
        b: f64,
        angle: f64,
    },
    Rectangle {
        x: f64,
        y: f64,
        w: f64,
        h: f64,
        angle: f64,
    },
}

fn grain() -> impl Strategy<Value = Grain> {
    prop_oneof![
        (wild(0.5), wild(0.5), wild(0.05)).prop_map(|(x, y, r)| Grain::Circle { x, y, r }),
        (wild(0.5), wild(0.5), wild(0.05), wild(0.03), wild(0.5))
            .prop_map(|(x, y, a, b, angle)| Grain::Ellipse { x, y, a, b, angle }),
        (wild(0.5), wild(0.5), wild(0.08), wild(0.04), wild(0.5))
            .prop_map(|(x, y, w, h, angle)| Grain::Rectangle { x, y, w, h, angle }),
    ]
}

#[derive(Debug, Clone)]
struct DemCase {
    box_size: (f64, f64),
    gravity: f64,
    grains: Vec<Grain>,
    density: f64,
    stiffness: (f64, f64, f64),
    damping: (f64, f64),
    dt: f64,
    skin: Option<f64>,
    overlap_tolerance: f64,
}

fn dem_case() -> impl Strategy<Value = DemCase> {
    (
        (wild(1.0), wild(1.0)),
        wild(9.8),
        prop::collection::vec(grain(), 1..6),
        wild(2650.0),
        (wild(1e6), wild(0.3), wild(0.5)),
        (wild(100.0), wild(50.0)),
        wild(1e-5),
        prop::option::of(wild(0.01)),
        wild(1e-6),
    )
        .prop_map(
            |(box_size, gravity, grains, density, stiffness, damping, dt, skin, overlap)| DemCase {
                box_size,
                gravity,
                grains,
                density,
                stiffness,
                damping,
                dt,
                skin,
                overlap_tolerance: overlap,
            },
        )
}

/// Build and run a DEM case: `Err` is a typed refusal or a stop.
fn run_dem(case: &DemCase) -> Result<bool, DismechError> {
    let frame = Frame::open_box(case.box_size.0, case.box_size.1)?;
    let mut scene = Scene::new(frame, Vec2::new(0.0, -case.gravity))?;
    for g in &case.grains {
        match *g {
            Grain::Circle { x, y, r } => scene.add_circle(Point::new(x, y), r, case.density),
            Grain::Ellipse { x, y, a, b, angle } => {
                scene.add_ellipse(Point::new(x, y), a, b, angle, case.density)
            }
            Grain::Rectangle { x, y, w, h, angle } => {
                scene.add_rectangle(Point::new(x, y), w, h, angle, case.density)
            }
        }?;
    }
    let (k, ratio, mu) = case.stiffness;
    let law = SpringDashpotCoulomb::new(
        NormalStiffness::Constant(k),
        ratio,
        mu,
        Damping::PerMass {
            normal: case.damping.0,
            shear: case.damping.1,
        },
    )?;
    let settings = DemSettings {
        dt: case.dt,
        neighbour_skin: case.skin,
        initial_overlap_tolerance: case.overlap_tolerance,
        ..DemSettings::default()
    };
    let mut sim = DemSimulation::new(scene, law, ExplicitEuler, settings)?;
    for _ in 0..20 {
        if let Err(e) = sim.step() {
            // A stop after the start is a run, not a refusal.
            assert!(said(&e), "{e:?}");
            return Ok(true);
        }
        for p in &sim.scene().particles {
            let state = [
                p.pose.position.x,
                p.pose.position.y,
                p.pose.angle,
                p.velocity.x,
                p.velocity.y,
                p.angular_velocity,
            ];
            assert!(
                state.iter().all(|v| v.is_finite()),
                "a step returned Ok with a non-finite state: {p:?}"
            );
        }
    }
    let criterion = RestCriterion {
        max_steps: 50,
        ..RestCriterion::default()
    };
    let outcome = sim.run_to_rest(&criterion, |_, _| {})?;
    assert!(outcome.steps <= 50, "{outcome:?}");
    Ok(true)
}

#[derive(Debug, Clone)]
struct Brick {
    x0: f64,
    y0: f64,
    w: f64,
    h: f64,
}

#[derive(Debug, Clone)]
struct DdaCase {
    bricks: Vec<Brick>,
    material: (f64, f64, f64),
    penalty: f64,
    friction: f64,
    return_mapping: bool,
    search: f64,
    min_dt_ratio: f64,
    tolerance: f64,
    dt: f64,
    traction: Option<(usize, f64)>,
}

fn dda_case() -> impl Strategy<Value = DdaCase> {
    (
        prop::collection::vec(
            (wild(0.5), wild(0.1), wild(0.4), wild(0.2)).prop_map(|(x0, y0, w, h)| Brick {
                x0,
                y0,
                w,
                h,
            }),
            1..4,
        ),
        (wild(2200.0), wild(1e9), wild(0.25)),
        wild(1e9),
        wild(0.5),
        any::<bool>(),
        wild(0.01),
        wild(1.0 / 64.0),
        wild(1e-10),
        wild(1e-3),
        prop::option::of((0usize..8, wild(1e3))),
    )
        .prop_map(
            |(bricks, material, penalty, friction, rm, search, ratio, tolerance, dt, traction)| {
                DdaCase {
                    bricks,
                    material,
                    penalty,
                    friction,
                    return_mapping: rm,
                    search,
                    min_dt_ratio: ratio,
                    tolerance,
                    dt,
                    traction,
                }
            },
        )
}

fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<Point> {
    vec![
        Point::new(x0, y0),
        Point::new(x1, y0),
        Point::new(x1, y1),
        Point::new(x0, y1),
    ]
}

/// Build and advance a DDA case: `Err` is a typed refusal.
fn run_dda(case: &DdaCase) -> Result<bool, DismechError> {
    let material = BlockMaterial {
        density: case.material.0,
        youngs_modulus: case.material.1,
        poisson_ratio: case.material.2,
        plane: PlaneState::Strain,
    };
    let mut base = Block::new(&rect(-2.0, -1.0, 2.0, 0.0), material, 0)?;
    base.prescribed = Some(Prescribed::fixed());
    let mut blocks = vec![base];
    for (i, b) in case.bricks.iter().enumerate() {
        let mut block = Block::new(&rect(b.x0, b.y0, b.x0 + b.w, b.y0 + b.h), material, i + 1)?;
        if let Some((edge, t)) = case.traction {
            block.edge_tractions.push((edge, Vec2::new(0.0, -t)));
        }
        blocks.push(block);
    }
    let integration = if case.return_mapping {
        FrictionIntegration::ReturnMapping
    } else {
        FrictionIntegration::Conventional
    };
    let law = PenaltyCoulomb::new(case.penalty, case.friction, integration)?;
    let settings = DdaSettings {
        search_distance: case.search,
        min_dt_ratio: case.min_dt_ratio,
        residual_tolerance: case.tolerance,
        ..DdaSettings::default()
    };
    let mut model = DdaModel::new(blocks, law, settings)?;
    for _ in 0..3 {
        match model.advance(case.dt) {
            Err(DismechError::Implicit(ImplicitError::StepFailed { reason, .. })) => {
                assert!(!reason.to_string().is_empty());
                break;
            }
            other => {
                other?;
            }
        }
        for block in model.blocks() {
            for v in 0..block.vertex_count() {
                let p = block.vertex(v);
                assert!(
                    p.x.is_finite() && p.y.is_finite(),
                    "a converged step left a non-finite vertex"
                );
            }
        }
    }
    Ok(true)
}

#[derive(Debug, Clone)]
struct LimitCase {
    tolerance: f64,
    radius: f64,
    /// Per element above the first: its offset from touching the one below.
    offsets: Vec<f64>,
    weight: f64,
    cohesion: f64,
    friction: f64,
    unilateral: bool,
    plate_speed: f64,
    solver_tolerance: f64,
}

fn limit_case() -> impl Strategy<Value = LimitCase> {
    (
        wild(1e-9),
        wild(0.5),
        prop::collection::vec(prop_oneof![4 => Just(0.0), 1 => wild(1e-10)], 0..4),
        wild(10.0),
        wild(1.0),
        wild(0.5),
        any::<bool>(),
        wild(1.0),
        prop_oneof![4 => Just(1e-9), 1 => wild(1e-6)],
    )
        .prop_map(
            |(tolerance, radius, offsets, weight, cohesion, phi, unilateral, speed, solver)| {
                LimitCase {
                    tolerance,
                    radius,
                    offsets,
                    weight,
                    cohesion,
                    friction: phi,
                    unilateral,
                    plate_speed: speed,
                    solver_tolerance: solver,
                }
            },
        )
}

/// Build and analyse a column of circular elements on a floor under a
/// plate, both ways: `Err` is a typed refusal. Where both analyses report a
/// collapse, the kinematic (upper) and static (lower) loads agree: the
/// certificate the library checks.
fn run_limit(case: &LimitCase) -> Result<bool, DismechError> {
    let mut m = LimitModel::new(case.tolerance)?;
    let r = case.radius;
    let law = RigidPlastic::coulomb(case.cohesion, case.friction, case.unilateral)?;
    let floor = m.add_support("floor", Point::origin(), Vec2::new(0.0, 1.0), Vec2::zeros())?;
    let mut y = r;
    let first = m.add_body(Point::new(0.0, y), r, true)?;
    m.set_load(first, Vec2::new(0.0, -case.weight))?;
    m.add_contact(first, Partner::Support(floor), law)?;
    let mut below = first;
    for offset in &case.offsets {
        y += 2.0 * r + offset;
        let e = m.add_body(Point::new(0.0, y), r, true)?;
        m.set_load(e, Vec2::new(0.0, -case.weight))?;
        m.add_contact(e, Partner::Body(below), law)?;
        below = e;
    }
    let plate = m.add_support(
        "plate",
        Point::new(0.0, y + r),
        Vec2::new(0.0, -1.0),
        Vec2::new(0.0, -case.plate_speed),
    )?;
    m.add_contact(below, Partner::Support(plate), law)?;
    let mut solver = LinearProgramSolver {
        tolerance: case.solver_tolerance,
        ..Default::default()
    };
    let upper = analyse(&m, &mut solver)?;
    let lower = analyse_static(&m, &mut solver)?;
    if let (LimitStatus::Collapse, LimitStatus::Collapse, Some(p), Some(q)) =
        (&upper.status, &lower.status, upper.load, lower.load)
    {
        assert!(p.is_finite() && q.is_finite(), "{p} {q}");
        assert!(
            (p - q).abs() <= 1e-6 * p.abs().max(q.abs()).max(1.0),
            "a certified collapse whose bounds differ: kinematic {p}, static {q}"
        );
    }
    Ok(true)
}

#[derive(Debug, Clone)]
struct SlopeCase {
    rows: usize,
    columns: usize,
    cell: f64,
    dip_deg: f64,
    thickness: f64,
    material: HpmMaterial,
    layers: usize,
    penalty: f64,
    memory_budget: Option<u64>,
    seismic: f64,
    direction_deg: f64,
}

/// An HPM memory budget: mostly 4 GiB, sometimes one too small for any
/// model. Never `None` (the system asked): on a machine with hundreds of
/// GB the system would give a model of 10^6 layers, and the cases are to
/// be the same on every machine.
fn budget() -> impl Strategy<Value = Option<u64>> {
    prop_oneof![
        9 => Just(Some(4u64 << 30)),
        1 => prop::sample::select(vec![Some(0u64), Some(1 << 12), Some(1 << 20)]),
    ]
}

fn slope_case() -> impl Strategy<Value = SlopeCase> {
    (
        (1usize..6, 1usize..6, wild(10.0)),
        (wild(20.0), wild(5.0)),
        (wild(1e7), wild(0.3), wild(1e4), wild(0.5), wild(2e4)),
        prop::sample::select(vec![0usize, 2, 3, 3, 3, 4, 6, 1_000_000]),
        (wild(100.0), budget()),
        prop_oneof![3 => Just(0.0), 1 => wild(0.1)],
        wild(270.0),
    )
        .prop_map(
            |(
                (rows, columns, cell),
                (dip, thickness),
                (e, nu, c, phi, gamma),
                layers,
                (penalty, memory_budget),
                kh,
                dir,
            )| {
                let mut material = HpmMaterial::paper();
                material.youngs_modulus = e;
                material.poisson_ratio = nu;
                material.cohesion = c;
                material.friction_coefficient = phi;
                material.unit_weight = gamma;
                SlopeCase {
                    rows,
                    columns,
                    cell,
                    dip_deg: dip,
                    thickness,
                    material,
                    layers,
                    penalty,
                    memory_budget,
                    seismic: kh,
                    direction_deg: dir,
                }
            },
        )
}

/// Build a slab on a dipping plane and analyse it (elastic HPM and
/// Hovland): `Err` is a typed refusal; a safety factor returned is finite
/// and positive, and one that is not given is refused because nothing
/// drives the slide ([`HpmError::NothingDrivesSliding`]) or because
/// the slip surface has no strength left
/// ([`HpmError::SlipSurfaceInTension`]: a seismic load that puts it in
/// tension beyond `c / tan φ`, where the ratio used to come out negative).
fn run_slope(case: &SlopeCase) -> Result<bool, DismechError> {
    let slope = case.dip_deg.to_radians().tan();
    let raster = |offset: f64| {
        Raster::from_fn(case.columns, case.rows, 0.0, 0.0, case.cell, move |_, y| {
            Some(100.0 + slope * y + offset)
        })
    };
    let grids = SlopeGrids::new(
        NamedRaster::new("ground.asc", raster(case.thickness)?),
        NamedRaster::new("slip.asc", raster(0.0)?),
        None,
    )?;
    let settings = HpmSettings {
        layers: case.layers,
        penalty: case.penalty,
        memory_budget: case.memory_budget,
    };
    let model = HpmModel::new(&grids, &case.material, &settings)?;
    let seismic = Seismic {
        coefficient: case.seismic,
        direction: towards_deg(case.direction_deg),
    };
    let elastic = HpmSolver::new(&model)?.elastic(&model, &seismic)?;
    for (name, fs) in [
        ("HPM stress ratio", elastic.safety_factor(&model)),
        (
            "HPM along the sliding direction",
            elastic.sliding_safety_factor(&model),
        ),
        (
            "Hovland",
            hovland(&model, &seismic, towards_deg(case.direction_deg)).map(|h| h.safety_factor),
        ),
    ] {
        match fs {
            Ok(fs) => assert!(fs.is_finite() && fs > 0.0, "{name} Fs {fs}"),
            Err(
                DismechError::Hpm(HpmError::NothingDrivesSliding { .. })
                | DismechError::Hpm(HpmError::SlipSurfaceInTension { .. }),
            ) => {}
            Err(other) => panic!("{name}: {other:?}"),
        }
    }
    let local = elastic.local_safety_factors(&model);
    assert!(
        local.iter().all(|f| *f >= 0.0),
        "a negative local Fs: {local:?}"
    );
    Ok(true)
}

/// Counts of how far the cases went.
#[derive(Debug, Default)]
struct Reach {
    cases: u64,
    stepped: u64,
    errors: std::collections::BTreeMap<String, u64>,
}

impl Reach {
    fn note(&mut self, outcome: &Result<bool, DismechError>) {
        self.cases += 1;
        match outcome {
            Ok(true) => self.stepped += 1,
            Ok(false) => {}
            Err(e) => {
                // The implicit and explicit drivers' and the limit
                // analysis' errors under their own names, as `StepFailed`,
                // `EnergyBlowUp`, `NoLimitLoad`, ...
                let kind = match e {
                    DismechError::Implicit(implicit) => format!("{implicit:?}"),
                    DismechError::Explicit(explicit) => format!("{explicit:?}"),
                    DismechError::Limit(limit) => format!("{limit:?}"),
                    other => format!("{other:?}"),
                };
                let kind = kind.split([' ', '(', '{']).next().unwrap_or("").to_string();
                *self.errors.entry(kind).or_default() += 1;
            }
        }
    }
}

/// Run `check` on `cases()` cases of `strategy` (seeded, so that a run
/// is repeatable), asserting each; return how far they went.
fn fuzz<T: std::fmt::Debug>(
    strategy: impl Strategy<Value = T>,
    check: impl Fn(&T) -> Result<bool, DismechError>,
) -> Reach {
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let config = Config {
        cases: cases(),
        failure_persistence: None,
        ..Config::default()
    };
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[7; 32]);
    let mut runner = TestRunner::new_with_rng(config, rng);
    let reach = std::cell::RefCell::new(Reach::default());
    let result = runner.run(&strategy, |case| {
        let outcome = check(&case);
        if let Err(e) = &outcome {
            prop_assert!(said(e), "{e:?}");
        }
        reach.borrow_mut().note(&outcome);
        Ok(())
    });
    if let Err(e) = result {
        panic!("{e}");
    }
    reach.into_inner()
}

/// Any DEM set-up is accepted and steps to finite states, or is refused
/// (or stopped) with a message.
#[test]
fn dem_constructors_and_steps_never_panic() {
    let reach = fuzz(dem_case(), run_dem);
    eprintln!("{reach:?}");
    // The cases reach the stepping, not only the refusals.
    assert!(reach.stepped * 10 >= reach.cases, "{reach:?}");
}

/// Any limit model of a column of elements is analysed both ways, or
/// refused with a message; where both collapse, their loads agree.
#[test]
fn limit_constructors_and_analyses_never_panic() {
    let reach = fuzz(limit_case(), run_limit);
    eprintln!("{reach:?}");
    assert!(reach.stepped * 10 >= reach.cases, "{reach:?}");
}

/// Any slab over a dipping plane is analysed (HPM, Hovland) or refused
/// with a message; every safety factor returned is finite and positive.
#[test]
fn slope_constructors_and_analyses_never_panic() {
    let reach = fuzz(slope_case(), run_slope);
    eprintln!("{reach:?}");
    assert!(reach.stepped * 10 >= reach.cases, "{reach:?}");
}

/// Any DDA set-up is accepted and advances to finite blocks or a failed
/// status, or is refused with a message.
#[test]
fn dda_constructors_and_steps_never_panic() {
    let reach = fuzz(dda_case(), run_dda);
    eprintln!("{reach:?}");
    assert!(reach.stepped * 10 >= reach.cases, "{reach:?}");
}
