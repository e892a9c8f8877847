//! Scenario files: each file of `examples/scenarios/` runs (at reduced
//! size) and writes its ParaView series and summary; the three papers'
//! scenarios end in the same bits as the same compositions written in
//! Rust; refusals name the file, line, column, key and value; a few
//! thousand mutated files are refused without a panic, each naming a key.

use std::path::{Path, PathBuf};
use std::process::Command;

use dismech::dda::{
    Block, BlockMaterial, DdaModel, DdaSettings, FrictionIntegration, PenaltyCoulomb, PlaneState,
    Prescribed,
};
use dismech::dem::DemSimulation;
use dismech::explicit::{DemSettings, RestCriterion};
use dismech::integrate::ExplicitEuler;
use dismech::law::SpringDashpotCoulomb;
use dismech::math::{Point, Vec2};
use dismech::reference::Shaking;
use dismech::scene::CircleRows;
use dismech_cli::scenario::{self, fuzz, Overrides, ScenarioError};
use serde_json::Value;

fn scenarios() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/scenarios")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("dismech-scenario-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// Run the scenario `name` in-process and return its summary.
fn run(name: &str, overrides: Overrides) -> Value {
    let file = scenarios().join(name);
    let out = scratch(name);
    let prepared = scenario::load(&file, overrides).unwrap();
    let finished = scenario::execute(prepared, &file, &out, false).unwrap();
    std::fs::remove_dir_all(&out).unwrap();
    finished.summary
}

fn bits(v: &Value) -> u64 {
    v.as_f64().expect("a number").to_bits()
}

#[test]
fn every_scenario_runs_at_reduced_size_and_writes_its_series() {
    let mut names: Vec<PathBuf> = std::fs::read_dir(scenarios())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    names.sort();
    assert!(names.len() >= 3, "{names:?}");
    for file in names {
        let out = scratch(&file.file_stem().unwrap().to_string_lossy());
        let run = Command::new(env!("CARGO_BIN_EXE_dismech"))
            .arg("run")
            .arg(&file)
            .args(["--quiet", "--max-steps", "60", "--out"])
            .arg(&out)
            .output()
            .unwrap();
        assert_eq!(
            run.status.code(),
            Some(0),
            "{file:?}: {}",
            String::from_utf8_lossy(&run.stderr)
        );
        let summary: Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        let frames = summary["frames"].as_u64().unwrap();
        assert!(frames >= 1, "{file:?}: {summary}");
        if summary["driver"] != "limit" && summary["driver"] != "hpm" {
            assert_eq!(summary["steps"].as_u64(), Some(60), "{file:?}");
            assert!(frames >= 2, "{file:?}: the start and the end");
        }
        // Every index lists `frames` files, each written.
        let pvds: Vec<PathBuf> = std::fs::read_dir(&out)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "pvd"))
            .collect();
        assert!(pvds.len() >= 2, "{file:?}: {pvds:?}");
        for pvd in pvds {
            let text = std::fs::read_to_string(&pvd).unwrap();
            let listed: Vec<&str> = text
                .split("file=\"")
                .skip(1)
                .map(|s| s.split('"').next().unwrap())
                .collect();
            assert_eq!(listed.len() as u64, frames, "{pvd:?}");
            for f in listed {
                assert!(out.join(f).is_file(), "{pvd:?} lists {f}");
            }
        }
        // No staging folder is left beside the output.
        let leftovers = std::fs::read_dir(out.parent().unwrap())
            .unwrap()
            .filter(|e| {
                e.as_ref()
                    .unwrap()
                    .file_name()
                    .to_string_lossy()
                    .contains(&format!(
                        ".{}.partial",
                        out.file_name().unwrap().to_string_lossy()
                    ))
            })
            .count();
        assert_eq!(leftovers, 0);
        std::fs::remove_dir_all(&out).unwrap();
        // A scenario that saves checkpoints wrote the one of its end.
        let ckpts = out.with_file_name(format!(
            "{}.checkpoints",
            out.file_name().unwrap().to_string_lossy()
        ));
        if std::fs::read_to_string(&file)
            .unwrap()
            .contains("checkpoint_every")
        {
            assert!(ckpts.join("step-0000000060.ckpt").is_file(), "{file:?}");
            std::fs::remove_dir_all(&ckpts).unwrap();
        }
    }
}

/// Katsuki's Example 1 from its file ends at rest in the same bits as the
/// reproduction's composition (`dismech reproduce katsuki1990`: the same
/// circle rows, law, step and rest criterion).
#[test]
fn katsuki_example1_scenario_equals_the_composition_bit_for_bit() {
    let summary = run("katsuki_example1.toml", Overrides::default());
    let g = 9.80665;
    let scene = CircleRows {
        count: 179,
        radius: 0.07,
        width: 2.0,
        height: 3.0,
        per_row: 14,
        row_pitch: 0.16,
        clearance: 0.005,
        density: 2.69 * 1e-3 / 1e-6,
    }
    .scene(g)
    .unwrap();
    let law = SpringDashpotCoulomb::katsuki(750.0 * g / 1e-4, 0.3, 0.25, 0.577).unwrap();
    let settings = DemSettings {
        dt: 1e-4,
        ..DemSettings::default()
    };
    let mut dem = DemSimulation::new(scene, law, ExplicitEuler, settings).unwrap();
    let criterion = RestCriterion {
        kinetic_to_released_ratio: 1e-6,
        min_time: 0.5,
        max_time: 30.0,
        check_every: 100,
        consecutive_checks: 10,
        unbalanced_force_ratio: 1e-4,
        ..RestCriterion::default()
    };
    let outcome = dem.run_to_rest(&criterion, |_, _| {}).unwrap();
    assert_eq!(summary["outcome"]["status"], "AtRest");
    assert_eq!(summary["steps"].as_u64(), Some(outcome.steps));
    assert_eq!(bits(&summary["time"]), dem.time().to_bits());
    let bodies = summary["bodies"].as_array().unwrap();
    assert_eq!(bodies.len(), 179);
    for (b, p) in bodies.iter().zip(&dem.scene().particles) {
        assert_eq!(bits(&b["centre"][0]), p.pose.position.x.to_bits());
        assert_eq!(bits(&b["centre"][1]), p.pose.position.y.to_bits());
        assert_eq!(bits(&b["angle"]), p.pose.angle.to_bits());
        assert_eq!(bits(&b["velocity"][0]), p.velocity.x.to_bits());
        assert_eq!(bits(&b["velocity"][1]), p.velocity.y.to_bits());
        assert_eq!(bits(&b["angular_velocity"]), p.angular_velocity.to_bits());
    }
    for (k, w) in summary["walls"].as_array().unwrap().iter().enumerate() {
        let load = dem.wall_load(k);
        assert_eq!(bits(&w["load"][0]), load.x.to_bits());
        assert_eq!(bits(&w["load"][1]), load.y.to_bits());
    }
}

fn rectangle(x0: f64, y0: f64, x1: f64, y1: f64) -> [Point; 4] {
    [
        Point::new(x0, y0),
        Point::new(x1, y0),
        Point::new(x1, y1),
        Point::new(x0, y1),
    ]
}

/// The DDA sliding block from its file ends in the same bits as
/// examples/dda_sliding_block.rs (the same blocks, law, Newmark and
/// shaking, 1 500 steps of 1 ms).
#[test]
fn dda_sliding_block_scenario_equals_the_example_bit_for_bit() {
    let summary = run("dda_sliding_block.toml", Overrides::default());
    let g = 9.8;
    let rock = BlockMaterial {
        density: 21.56e3 / g,
        youngs_modulus: 14.9e9,
        poisson_ratio: 0.2,
        plane: PlaneState::Stress,
    };
    let mu = 36.4f64.to_radians().tan();
    let penalty = 2e9;
    let shaking = Shaking::with_peak_acceleration(1.5 * mu * g, 2.0, 3.0);
    let (a, w) = (shaking.amplitude, shaking.omega());
    let mut base = Block::new(&rectangle(-3.0, -0.5, 3.0, 0.0), rock, 0).unwrap();
    base.prescribed = Some(Prescribed::translation(move |t| {
        Vec2::new(a * (w * t).sin(), 0.0)
    }));
    let settle = 0.5 * rock.density * 2.0 * 0.25 * g / penalty;
    let mut block = Block::new(&rectangle(-1.0, -settle, 1.0, 0.25 - settle), rock, 1).unwrap();
    base.velocity[0] = a * w;
    block.velocity[0] = a * w;
    let law = PenaltyCoulomb::new(penalty, mu, FrictionIntegration::ReturnMapping).unwrap();
    let settings = DdaSettings {
        gravity: Vec2::new(0.0, -g),
        search_distance: 0.02,
        overlap_tolerance: 1e-3,
        ..DdaSettings::default()
    };
    let mut model = DdaModel::new(vec![base, block], law, settings).unwrap();
    let dt = 0.001;
    let steps = (shaking.duration / dt).round() as u64;
    for _ in 0..steps {
        model.advance(dt).unwrap();
    }
    assert_eq!(summary["steps"].as_u64(), Some(steps));
    assert_eq!(bits(&summary["time"]), model.time().to_bits());
    for (b, block) in summary["bodies"]
        .as_array()
        .unwrap()
        .iter()
        .zip(model.blocks())
    {
        for k in 0..6 {
            assert_eq!(
                bits(&b["displacement"][k]),
                block.displacement[k].to_bits(),
                "displacement {k}"
            );
            assert_eq!(
                bits(&b["velocity"][k]),
                block.velocity[k].to_bits(),
                "velocity {k}"
            );
        }
        assert_eq!(bits(&b["centroid"][0]), block.centroid().x.to_bits());
        assert_eq!(bits(&b["centroid"][1]), block.centroid().y.to_bits());
    }
    // The block slid relative to the base (the example prints 0.8974 mm at
    // 1.5 s beside the rigid solution's 0.8902 mm).
    let slide = summary["bodies"][1]["displacement"][0].as_f64().unwrap()
        - summary["bodies"][0]["displacement"][0].as_f64().unwrap();
    assert!((slide * 1e3 - 0.8974).abs() < 5e-5, "{slide}");
}

/// The LP bearing-capacity scenario gives the same limit load, to the
/// bit, as `dismech lattice-limit-load` for the same lattice.
#[test]
fn lp_bearing_capacity_scenario_equals_lattice_limit_load_bit_for_bit() {
    let summary = run("lp_bearing_capacity.toml", Overrides::default());
    let cli = Command::new(env!("CARGO_BIN_EXE_dismech"))
        .args([
            "lattice-limit-load",
            "--model",
            "u",
            "--m",
            "16",
            "--n",
            "16",
            "--nprime",
            "4",
        ])
        .output()
        .unwrap();
    let expected: Value = serde_json::from_slice(&cli.stdout).unwrap();
    assert_eq!(summary["outcome"]["status"], "Collapse");
    assert_eq!(bits(&summary["p_over_cp"]), bits(&expected["p_over_cp"]));
    assert_eq!(
        bits(&summary["kinematic_p_over_cp"]),
        bits(&expected["kinematic_p_over_cp"])
    );
    assert_eq!(
        bits(&summary["static_p_over_cp"]),
        bits(&expected["static_p_over_cp"])
    );
    assert_eq!(
        bits(&summary["plate_length"]),
        bits(&expected["plate_length"])
    );
    assert_eq!(summary["frames"].as_u64(), Some(1));
}

/// The polygon-LP scenarios (the rocking and the sliding block) build the
/// composition's bodies and contacts and give its limit loads to the bit.
#[test]
fn polygon_lp_scenarios_equal_the_composition_bit_for_bit() {
    use dismech_cli::compositions::polygon_lp::{
        block_limit, block_limit_model, sliding_block, tipping_block,
    };
    for (name, block) in [
        ("polygon_lp.toml", tipping_block()),
        ("polygon_lp_sliding.toml", sliding_block()),
    ] {
        let expected = block_limit_model(&block).unwrap();
        let prepared = scenario::load(&scenarios().join(name), Overrides::default()).unwrap();
        let scenario::Model::Limit(plan) = &prepared.model else {
            panic!("{name}: not a limit model");
        };
        assert_eq!(plan.model.bodies(), expected.bodies(), "{name}");
        assert_eq!(plan.model.contacts(), expected.contacts(), "{name}");
        assert_eq!(plan.model.load_driver(), expected.load_driver(), "{name}");
        assert_eq!(plan.model.supports().len(), 1, "{name}");
        let limit = block_limit(&block).unwrap();
        let summary = run(name, Overrides::default());
        assert_eq!(summary["outcome"]["status"], "Collapse", "{name}");
        assert_eq!(
            bits(&summary["load"]),
            limit.result.load.unwrap().to_bits(),
            "{name}"
        );
        assert_eq!(
            bits(&summary["kinematic_load"]),
            limit.result.kinematic_load.unwrap().to_bits(),
            "{name}"
        );
        assert_eq!(
            bits(&summary["static_load"]),
            limit.result.static_load.unwrap().to_bits(),
            "{name}"
        );
        assert_eq!(summary["contacts"].as_u64(), Some(2), "{name}");
        // Within a part in 10^7 of the closed form, rocking or sliding.
        let ratio = limit.result.load.unwrap() / limit.exact;
        assert!((ratio - 1.0).abs() < 1e-7, "{name}: {ratio}");
    }
}

/// The packing-LP scenario: the composition's 120 ellipses, law, step and
/// rest criterion settle to the same bits, and the limit analysis of the
/// settled packing (`[limit_analysis]`) gives the composition's limit
/// load and bounds, bodies and contacts, to the bit.
#[test]
fn packing_lp_scenario_equals_the_composition_bit_for_bit() {
    use dismech::limit::analyse;
    use dismech::lp::LinearProgramSolver;
    use dismech_cli::compositions::packing_lp::{
        packing_limit_model, settle_ellipses, EllipsePacking,
    };
    let summary = run("packing_lp.toml", Overrides::default());
    let (dem, outcome) = settle_ellipses(&EllipsePacking::default()).unwrap();
    assert_eq!(
        summary["outcome"]["status"],
        format!("{:?}", outcome.status)
    );
    assert_eq!(summary["steps"].as_u64(), Some(outcome.steps));
    assert_eq!(bits(&summary["time"]), dem.time().to_bits());
    let bodies = summary["bodies"].as_array().unwrap();
    assert_eq!(bodies.len(), 120);
    for (b, p) in bodies.iter().zip(&dem.scene().particles) {
        assert_eq!(bits(&b["centre"][0]), p.pose.position.x.to_bits());
        assert_eq!(bits(&b["centre"][1]), p.pose.position.y.to_bits());
        assert_eq!(bits(&b["angle"]), p.pose.angle.to_bits());
    }
    let model = packing_limit_model(&dem).unwrap();
    let result = analyse(&model, &mut LinearProgramSolver::default()).unwrap();
    let limit = &summary["limit"];
    assert_eq!(limit["status"], format!("{:?}", result.status));
    assert_eq!(limit["status"], "Collapse");
    assert_eq!(bits(&limit["load"]), result.load.unwrap().to_bits());
    assert_eq!(
        bits(&limit["kinematic_load"]),
        result.kinematic_load.unwrap().to_bits()
    );
    assert_eq!(
        bits(&limit["static_load"]),
        result.static_load.unwrap().to_bits()
    );
    assert_eq!(
        limit["elements"].as_u64(),
        Some(model.bodies().len() as u64)
    );
    assert_eq!(
        limit["contacts"].as_u64(),
        Some(model.contacts().len() as u64)
    );
    assert_eq!(
        limit["supports"].as_u64(),
        Some(model.supports().len() as u64)
    );
    assert_eq!(limit["frames"].as_u64(), Some(1));
}

/// `[limit_analysis]`'s refusals name their keys; a run to rest stopped
/// short is not analysed and says so.
#[test]
fn limit_analysis_keys_are_checked() {
    let text = std::fs::read_to_string(scenarios().join("packing_lp.toml")).unwrap();
    let refused = |from: &str, to: &str| -> String {
        assert!(text.contains(from), "{from}");
        let edited = text.replacen(from, to, 1);
        match scenario::prepare(Path::new("model.toml"), &edited, Overrides::default()) {
            Err(ScenarioError::Invalid(located)) => located.to_string(),
            Err(e) => panic!("not a placed refusal: {e}"),
            Ok(_) => panic!("accepted: {to}"),
        }
    };
    let wall = refused("plate_wall = \"left\"", "plate_wall = \"top\"");
    assert!(
        wall.contains("`limit_analysis.plate_wall` = \"top\"") && wall.contains("\"left\""),
        "{wall}"
    );
    let cohesion = refused("walls = { cohesion = 2.0 }", "walls = { cohesion = -2.0 }");
    assert!(
        cohesion.contains("`limit_analysis.walls.cohesion` = -2"),
        "{cohesion}"
    );
    let both = refused(
        "plate = { cohesion = 0.0 }",
        "plate = { cohesion = 0.0, friction = 0.1, friction_angle = 5.0 }",
    );
    assert!(
        both.contains("`limit_analysis.plate.friction` and `limit_analysis.plate.friction_angle`"),
        "{both}"
    );
    let unknown = refused("rolling = true", "rolling = true\nroll = 1");
    assert!(unknown.contains("roll"), "{unknown}");
    let lp = refused("[limit_analysis]", "[limit_analysis_]");
    assert!(lp.contains("limit_analysis_"), "{lp}");
    // The LP solver serves the analysis only.
    let katsuki = std::fs::read_to_string(scenarios().join("katsuki_example1.toml")).unwrap();
    let solver = format!("{katsuki}\n[lp_solver]\nkind = \"clarabel\"\n");
    match scenario::prepare(Path::new("model.toml"), &solver, Overrides::default()) {
        Err(ScenarioError::Invalid(located)) => assert!(
            located
                .to_string()
                .contains("`driver.kind` and `lp_solver`"),
            "{located}"
        ),
        _ => panic!("an LP solver beside the explicit driver was accepted"),
    }
    // Beside the limit driver.
    let lp_file = std::fs::read_to_string(scenarios().join("lp_bearing_capacity.toml")).unwrap();
    let beside = format!(
        "{lp_file}\n[limit_analysis]\nplate_wall = \"left\"\ncontacts = {{ cohesion = 1.0 }}\n"
    );
    match scenario::prepare(Path::new("model.toml"), &beside, Overrides::default()) {
        Err(ScenarioError::Invalid(located)) => assert!(
            located
                .to_string()
                .contains("`driver.kind` and `limit_analysis`"),
            "{located}"
        ),
        _ => panic!("`[limit_analysis]` beside the limit driver was accepted"),
    }
    // Stopped short of rest: not analysed, exit status 0.
    let summary = run(
        "packing_lp.toml",
        Overrides {
            max_steps: Some(60),
            end_time: None,
        },
    );
    assert_eq!(summary["outcome"]["status"], "StepLimit");
    assert_eq!(summary["limit"]["status"], "NotAnalysed");
}

/// A moving wall drives the limit analysis: the sliding block (φ = 10°)
/// pushed over its whole left face by a wall moving at unit speed gives
/// the load of the same model built in Rust, to the bit; a moving wall
/// beside a live load, two moving walls, a wall given a zero velocity and
/// one in the implicit driver are refused by key.
#[test]
fn a_moving_wall_drives_the_limit_analysis() {
    use dismech::law::{friction_from_degrees, RigidPlastic};
    use dismech::limit::{analyse, LimitModel, Partner};
    use dismech::lp::LinearProgramSolver;
    use dismech::math::Pose2;
    use dismech::shape::Polygon;
    let text = std::fs::read_to_string(scenarios().join("polygon_lp_sliding.toml")).unwrap();
    let live = text
        .lines()
        .find(|l| l.starts_with("live = "))
        .unwrap()
        .to_string();
    let plate = "[[bodies]]\nkind = \"wall\"\nstart = [-0.2, 1.0]\nend = [-0.2, -0.1]\nvelocity = [1.0, 0.0]\n";
    let pushed = text
        .replacen("[law]", &format!("{plate}\n[law]"), 1)
        .replacen(&live, "", 1);
    let dir = scratch("moving-wall");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("pushed.toml");
    std::fs::write(&file, &pushed).unwrap();
    let prepared = scenario::load(&file, Overrides::default()).unwrap();
    let scenario::Model::Limit(plan) = &prepared.model else {
        panic!("not a limit model");
    };
    assert_eq!(plan.model.supports().len(), 2);
    assert_eq!(plan.model.supports()[1].velocity, Vec2::new(1.0, 0.0));
    assert!(plan.model.load_driver().is_none());
    let finished = scenario::execute(prepared, &file, &dir.join("out"), false).unwrap();
    let summary = finished.summary;
    assert_eq!(summary["outcome"]["status"], "Collapse", "{summary}");
    // The same model built in Rust: the block, its weight, the floor, the
    // plate at unit speed, the contacts the pair query gives.
    let law = RigidPlastic::coulomb(0.0, friction_from_degrees(10.0).unwrap(), true).unwrap();
    let mut model = LimitModel::new(8e-10).unwrap();
    let block = model
        .add_shape(
            Polygon::rectangle(0.4, 0.8).unwrap().into(),
            Pose2::new(0.0, 0.4, 0.0),
            true,
        )
        .unwrap();
    let normal = |along: Vec2| Vec2::new(-along.y, along.x);
    model
        .add_support(
            "floor",
            Point::new(-1.0, 0.0),
            normal(Vec2::new(2.0, 0.0)),
            Vec2::zeros(),
        )
        .unwrap();
    model
        .add_support(
            "plate",
            Point::new(-0.2, 1.0),
            normal(Vec2::new(0.0, -0.1 - 1.0)),
            Vec2::new(1.0, 0.0),
        )
        .unwrap();
    model.set_load(block, Vec2::new(0.0, -1000.0)).unwrap();
    model.add_contacts(block, Partner::Support(0), law).unwrap();
    model.add_contacts(block, Partner::Support(1), law).unwrap();
    let result = analyse(&model, &mut LinearProgramSolver::default()).unwrap();
    assert_eq!(
        summary["contacts"].as_u64(),
        Some(model.contacts().len() as u64)
    );
    assert_eq!(bits(&summary["load"]), result.load.unwrap().to_bits());
    assert_eq!(
        bits(&summary["static_load"]),
        result.static_load.unwrap().to_bits()
    );
    // Pushed over its whole face, with friction on the plate too (the
    // associated flow lifts a sliding block along the plate), the block
    // needs more than mu W.
    let mu_w = friction_from_degrees(10.0).unwrap() * 1000.0;
    assert!(result.load.unwrap() > mu_w, "{summary}");
    std::fs::remove_dir_all(&dir).unwrap();
    let refused = |text: &str| -> String {
        match scenario::prepare(Path::new("model.toml"), text, Overrides::default()) {
            Err(ScenarioError::Invalid(located)) => located.to_string(),
            Err(e) => panic!("not a placed refusal: {e}"),
            Ok(_) => panic!("accepted: {text}"),
        }
    };
    let both = refused(&format!("{pushed}\n{live}\n"));
    assert!(
        both.contains("`bodies[2].velocity` and `loads.live`"),
        "{both}"
    );
    let two = refused(&pushed.replacen(
        "end = [1.0, 0.0]",
        "end = [1.0, 0.0]\nvelocity = [0.0, 1.0]",
        1,
    ));
    assert!(
        two.contains("`bodies[1].velocity` and `bodies[2].velocity`"),
        "{two}"
    );
    let zero = refused(&pushed.replacen("velocity = [1.0, 0.0]", "velocity = [0.0, 0.0]", 1));
    assert!(zero.contains("`bodies[2].velocity`"), "{zero}");
    // The implicit driver translates a moving wall at its velocity (see
    // the penalty pushover's scenario); a zero velocity is refused there
    // too.
    let dda = std::fs::read_to_string(scenarios().join("dda_sliding_block.toml")).unwrap();
    let pushing = dda.replacen(
        "[law]",
        "[[bodies]]\nkind = \"wall\"\nstart = [-3.0, 1.0]\nend = [-3.0, 0.0]\nvelocity = [1.0, 0.0]\n\n[law]",
        1,
    );
    assert!(scenario::prepare(Path::new("model.toml"), &pushing, Overrides::default()).is_ok());
    let implicit = refused(&pushing.replacen("velocity = [1.0, 0.0]", "velocity = [0.0, 0.0]", 1));
    assert!(
        implicit.contains("model.toml:") && implicit.contains("`bodies[2].velocity`"),
        "{implicit}"
    );
}

/// The block wall by the explicit polygon DEM from its file: the
/// composition's scene (its blocks, base, law and quarter of the stable
/// step), stepped as far, ends in the same bits.
#[test]
fn block_wall_dem_scenario_equals_the_composition_bit_for_bit() {
    use dismech::explicit::critical_time_step;
    use dismech::law::{Damping, NormalStiffness};
    use dismech::scene::{Frame, Scene};
    use dismech::shape::Segment;
    use dismech_cli::compositions::block_wall::{wall_by_dem, RunningBondWall};
    let wall = RunningBondWall::default();
    let blocks = wall.blocks().unwrap();
    let base = Segment::new(Point::new(-0.5, 0.0), Point::new(wall.length() + 0.5, 0.0));
    let frame = Frame::from_walls(vec![("base".into(), base)]).unwrap();
    let mut scene = Scene::new(frame, Vec2::new(0.0, -wall.gravity)).unwrap();
    for b in &blocks {
        scene.add_polygon(&b.corners, wall.density).unwrap();
    }
    let law = SpringDashpotCoulomb::new(
        NormalStiffness::Constant(wall.contact_stiffness),
        wall.dem_stiffness_ratio,
        wall.friction,
        Damping::Critical,
    )
    .unwrap();
    let dt = 0.25 * critical_time_step(&scene, &law).dt;
    let text = std::fs::read_to_string(scenarios().join("block_wall_dem.toml")).unwrap();
    assert!(text.contains(&format!("dt = {dt:?}\n")), "dt = {dt:?}");
    let steps = 3000;
    let summary = run(
        "block_wall_dem.toml",
        Overrides {
            max_steps: Some(steps),
            end_time: None,
        },
    );
    assert_eq!(summary["steps"].as_u64(), Some(steps));
    let settings = DemSettings {
        dt,
        ..DemSettings::default()
    };
    let mut sim = DemSimulation::new(scene, law, ExplicitEuler, settings).unwrap();
    for _ in 0..steps {
        sim.step().unwrap();
    }
    let bodies = summary["bodies"].as_array().unwrap();
    assert_eq!(bodies.len(), blocks.len());
    for (k, p) in sim.scene().particles.iter().enumerate() {
        assert_eq!(
            bits(&bodies[k]["centre"][0]),
            p.pose.position.x.to_bits(),
            "{k}"
        );
        assert_eq!(
            bits(&bodies[k]["centre"][1]),
            p.pose.position.y.to_bits(),
            "{k}"
        );
        assert_eq!(bits(&bodies[k]["angle"]), p.pose.angle.to_bits(), "{k}");
    }
    // Run to rest, as the composition runs it: the same steps, the same
    // unbalanced force, and the base carries the weight.
    let summary = run("block_wall_dem.toml", Overrides::default());
    let expected = wall_by_dem(&wall).unwrap();
    assert!(expected.at_rest);
    assert_eq!(summary["outcome"]["status"], "AtRest");
    assert_eq!(summary["steps"].as_u64(), Some(expected.steps as u64));
    assert_eq!(
        bits(&summary["outcome"]["unbalanced_force_ratio"]),
        expected.unbalanced.to_bits()
    );
    assert_eq!(bits(&summary["weight"]), expected.total_weight.to_bits());
    let load = &summary["walls"][0]["load"];
    assert_eq!(bits(&load[0]), (-expected.base_reaction.x).to_bits());
    assert_eq!(bits(&load[1]), (-expected.base_reaction.y).to_bits());
    assert!((expected.base_reaction_ratio() - 1.0).abs() < 1e-6);
    // Blocks must face the flat base: on its right (the base drawn the
    // other way) or beyond its ends they are refused.
    for (from, to) in [
        ("[[-0.5, 0.0], [2.95, 0.0]]", "[[2.95, 0.0], [-0.5, 0.0]]"),
        ("[[-0.5, 0.0], [2.95, 0.0]]", "[[-0.5, 0.0], [0.1, 0.0]]"),
    ] {
        let outside = refusal_of("block_wall_dem.toml", from, to);
        assert!(outside.contains("` and `boundary`:"), "{outside}");
        assert!(outside.contains("outside the frame's box"), "{outside}");
    }
}

/// The block wall by the static DDA from its file: the composition's
/// model (its blocks, fixed base, penalty law, settings and restarted
/// Newmark) advanced as many steps as the composition takes to rest ends
/// in the same bits, and its base carries the weight.
#[test]
fn block_wall_dda_scenario_equals_the_composition_bit_for_bit() {
    use dismech::integrate::{Newmark, Restarting};
    use dismech_cli::compositions::block_wall::{wall_by_dda, RunningBondWall};
    let wall = RunningBondWall::default();
    let expected = wall_by_dda(&wall).unwrap();
    assert!(expected.at_rest);
    let summary = run(
        "block_wall_dda.toml",
        Overrides {
            max_steps: Some(expected.steps as u64),
            end_time: None,
        },
    );
    assert_eq!(expected.steps, 4);
    assert_eq!(summary["steps"].as_u64(), Some(4));
    assert_eq!(summary["outcome"]["halvings"].as_u64(), Some(0));
    // The composition's model, as it builds it.
    let layout = wall.blocks().unwrap();
    let material = BlockMaterial {
        density: wall.density,
        youngs_modulus: wall.youngs_modulus,
        poisson_ratio: wall.poisson_ratio,
        plane: PlaneState::Stress,
    };
    let mut blocks: Vec<Block> = layout
        .iter()
        .enumerate()
        .map(|(i, b)| Block::new(&b.corners, material, i).unwrap())
        .collect();
    let (x0, x1, depth) = (-0.5, wall.length() + 0.5, wall.block_height);
    let corners = [(x0, -depth), (x1, -depth), (x1, 0.0), (x0, 0.0)];
    let mut base = Block::new(
        &corners.map(|(x, y)| Point::new(x, y)),
        material,
        layout.len(),
    )
    .unwrap();
    base.prescribed = Some(Prescribed::fixed());
    blocks.push(base);
    let law = PenaltyCoulomb::new(
        wall.contact_stiffness,
        wall.friction,
        FrictionIntegration::ReturnMapping,
    )
    .unwrap();
    let settings = DdaSettings {
        gravity: Vec2::new(0.0, -wall.gravity),
        search_distance: 0.5 * wall.joint,
        residual_tolerance: 1e-9,
        ..DdaSettings::default()
    };
    let mut model =
        DdaModel::with_integrator(blocks, law, Restarting(Newmark::dda()), settings).unwrap();
    for _ in 0..expected.steps {
        model.advance(0.01).unwrap();
    }
    let base_reaction = -model.contact_force_on(layout.len());
    assert_eq!(
        base_reaction.x.to_bits(),
        expected.base_reaction.x.to_bits()
    );
    assert_eq!(
        base_reaction.y.to_bits(),
        expected.base_reaction.y.to_bits()
    );
    assert!((expected.base_reaction_ratio() - 1.0).abs() < 1e-6);
    assert_eq!(bits(&summary["time"]), model.time().to_bits());
    let bodies = summary["bodies"].as_array().unwrap();
    assert_eq!(bodies.len(), layout.len() + 1);
    for (k, (b, block)) in bodies.iter().zip(model.blocks()).enumerate() {
        for d in 0..6 {
            assert_eq!(
                bits(&b["displacement"][d]),
                block.displacement[d].to_bits(),
                "body {k}, displacement {d}"
            );
        }
        assert_eq!(bits(&b["centroid"][0]), block.centroid().x.to_bits(), "{k}");
        assert_eq!(bits(&b["centroid"][1]), block.centroid().y.to_bits(), "{k}");
    }
    // The file's 200 steps keep the wall where it came to rest.
    let full = run("block_wall_dda.toml", Overrides::default());
    assert_eq!(full["steps"].as_u64(), Some(200));
    for (k, (b, block)) in full["bodies"]
        .as_array()
        .unwrap()
        .iter()
        .zip(model.blocks())
        .enumerate()
    {
        let moved = Vec2::new(
            b["centroid"][0].as_f64().unwrap() - block.centroid().x,
            b["centroid"][1].as_f64().unwrap() - block.centroid().y,
        );
        assert!(moved.norm() < 1e-8, "{k}: {moved:?}");
    }
}

/// The penalty pushover of paper 002's rolling U-model from its file: the
/// composition's model (`compositions::penalty_vs_lp::pushover_model` of
/// the default `UModelPushover`'s lattice at its stiffest penalty: its
/// elements, walls, laws per pair of groups, moving plate and settings)
/// advanced as `pushover` advances it ends in the same bits: every body's
/// displacement and centroid, the plate's contact force (the load of the
/// composition's curve at its last step), the time and the halvings.
#[test]
fn penalty_vs_lp_scenario_equals_the_composition_bit_for_bit() {
    use dismech_cli::compositions::penalty_vs_lp::{pushover, pushover_model, UModelPushover};
    let setup = UModelPushover::default();
    let penalty = *setup.penalties.last().unwrap();
    assert_eq!(penalty, 1e5);
    let limit = setup.lattice.build().unwrap();
    let travel = setup.travel_force / penalty;
    let curve = pushover(&limit, penalty, setup.search, travel, setup.steps).unwrap();
    assert!(curve.contacts_match);
    // The composition's model, advanced as `pushover` advances it.
    let mut pushed = pushover_model(&limit, penalty, setup.search).unwrap();
    let dt = travel / (setup.steps as f64 * pushed.speed);
    let mut halvings = 0;
    for _ in 0..setup.steps {
        halvings += pushed.model.advance(dt).unwrap().reductions;
    }
    assert_eq!(halvings, curve.reductions);
    assert_eq!(
        pushed.plate_load().to_bits(),
        curve.load.last().unwrap().to_bits()
    );
    let summary = run("penalty_vs_lp.toml", Overrides::default());
    assert_eq!(summary["steps"].as_u64(), Some(setup.steps as u64));
    assert_eq!(
        summary["outcome"]["halvings"].as_u64(),
        Some(halvings as u64)
    );
    assert_eq!(bits(&summary["time"]), pushed.model.time().to_bits());
    assert_eq!(
        summary["contacts"].as_u64(),
        Some(pushed.model.contacts().len() as u64)
    );
    let bodies = summary["bodies"].as_array().unwrap();
    assert_eq!(bodies.len(), pushed.model.bodies().len());
    assert_eq!(pushed.plate, 19);
    for (k, (b, body)) in bodies.iter().zip(pushed.model.bodies()).enumerate() {
        for d in 0..3 {
            assert_eq!(
                bits(&b["displacement"][d]),
                body.displacement[d].to_bits(),
                "body {k}, displacement {d}"
            );
        }
        assert_eq!(bits(&b["centroid"][0]), body.centroid().x.to_bits(), "{k}");
        assert_eq!(bits(&b["centroid"][1]), body.centroid().y.to_bits(), "{k}");
    }
    let force = pushed.model.contact_force_on(pushed.plate);
    let plate = &bodies[pushed.plate]["contact_force"];
    assert_eq!(bits(&plate[0]), force.x.to_bits());
    assert_eq!(bits(&plate[1]), force.y.to_bits());
    // The plate moves along -x: its load is the x component of the force
    // on it.
    assert_eq!(bits(&plate[0]), curve.load.last().unwrap().to_bits());
    // The plate moved by its travel.
    assert_eq!(
        bits(&bodies[pushed.plate]["displacement"][0]),
        (-pushed.model.time()).to_bits()
    );
}

/// The keys of the laws per pair of groups and of the implicit driver's
/// moving wall: bad values refused by file, line, column and key.
#[test]
fn pair_laws_and_moving_walls_are_checked() {
    let name = "penalty_vs_lp.toml";
    let unknown_group = refusal_of(name, "groups = [0, 2]", "groups = [0, 9]");
    assert!(
        unknown_group.contains("model.toml:")
            && unknown_group.contains("`pair_laws[1].groups`")
            && unknown_group.contains("no body is in group 9"),
        "{unknown_group}"
    );
    let twice = refusal_of(name, "groups = [0, 2]", "groups = [1, 0]");
    assert!(
        twice.contains("`pair_laws[0].groups` and `pair_laws[1].groups`")
            && twice.contains("(0, 1) is given two laws"),
        "{twice}"
    );
    let negative = refusal_of(
        name,
        "penalty = 1e5, friction = 0.0, cohesion = 2.0 }\n\n[[pair_laws]]\n# Elements on the far",
        "penalty = -1e5, friction = 0.0, cohesion = 2.0 }\n\n[[pair_laws]]\n# Elements on the far",
    );
    assert!(
        negative.contains("`pair_laws[0].law.penalty`") && negative.contains("-100000"),
        "{negative}"
    );
    let other_type = refusal_of(
        name,
        "law = { kind = \"penalty-coulomb\", penalty = 1e5, friction = 0.0, cohesion = 0.0 }",
        "law = { kind = \"spring-dashpot-coulomb\", normal_stiffness = 1e5, stiffness_ratio = 1.0, friction = 0.0 }",
    );
    assert!(
        other_type.contains("`law.kind` and `pair_laws[2].law.kind`"),
        "{other_type}"
    );
    let group = refusal_of(name, "group = 4", "group = -4");
    assert!(group.contains("`bodies[19].group`"), "{group}");
    let velocity = refusal_of(name, "velocity = [-1.0, 0.0]", "velocity = [-1.0, nan]");
    assert!(
        velocity.contains("model.toml:") && velocity.contains("`bodies[19].velocity`"),
        "{velocity}"
    );
    // Groups choose the implicit driver's laws; the limit driver refuses
    // them.
    let limit = refusal_of(
        "polygon_lp.toml",
        "kind = \"wall\"",
        "kind = \"wall\"\ngroup = 1",
    );
    assert!(
        limit.contains("`driver.kind` and `bodies[1].group`"),
        "{limit}"
    );
    let explicit = refusal_of(
        "katsuki_example1.toml",
        "[law]",
        "[[pair_laws]]\ngroups = [0, 0]\nlaw = { kind = \"katsuki\", youngs_modulus = 1e9, poisson_ratio = 0.2, stiffness_ratio = 0.25, friction = 0.5 }\n\n[law]",
    );
    assert!(
        explicit.contains("`driver.kind` and `pair_laws`"),
        "{explicit}"
    );
}

/// A point, a vector or a pair of groups is an array of exactly two
/// numbers: one with a third (or only one) is refused at its key, not read
/// as its first two.
#[test]
fn arrays_of_another_length_are_refused_by_key() {
    let cases = [
        (
            "penalty_vs_lp.toml",
            "groups = [0, 2]",
            "groups = [0, 2, 1]",
            "pair_laws[1].groups",
            3,
        ),
        (
            "penalty_vs_lp.toml",
            "velocity = [-1.0, 0.0]",
            "velocity = [-1.0, 0.0, 7.0]",
            "velocity",
            3,
        ),
        (
            "affine_disc.toml",
            "gravity = [0.0, -9.81]",
            "gravity = [0.0, -9.81, 0.0]",
            "loads.gravity",
            3,
        ),
        (
            "affine_disc.toml",
            "gravity = [0.0, -9.81]",
            "gravity = [-9.81]",
            "loads.gravity",
            1,
        ),
        (
            "block_wall_dda.toml",
            "vertices = [[0.0, 0.0], [0.4, 0.0],",
            "vertices = [[0.0, 0.0, 0.0], [0.4, 0.0],",
            "vertices",
            3,
        ),
    ];
    for (name, from, to, key, length) in cases {
        let refused = refusal_of(name, from, to);
        assert!(
            refused.contains("model.toml:")
                && refused.contains(key)
                && refused.contains(&format!(
                    "invalid length {length}, expected an array of length 2"
                )),
            "{to}: {refused}"
        );
    }
}

/// The moving wall's velocity is a function the implicit driver's
/// checkpoint cannot compare: the scenario's checkpoint refuses a run
/// whose plate moves at another velocity; the unchanged file resumes.
#[test]
fn a_checkpoint_of_another_wall_velocity_is_refused() {
    let dir = scratch("resume-wall");
    let file = variant("penalty_vs_lp.toml", "checkpoint_every = 10", &dir);
    let text = std::fs::read_to_string(&file).unwrap();
    run_file(&file, "a", Some(20), None);
    let ckpt = dir.join("a.checkpoints/step-0000000020.ckpt");
    for to in ["velocity = [-2.0, 0.0]", "velocity = [-1.0, 1e-9]"] {
        let edited = dir.join("edited.toml");
        std::fs::write(&edited, text.replacen("velocity = [-1.0, 0.0]", to, 1)).unwrap();
        let refused = resume_refusal(&edited, &ckpt, Some(30));
        assert!(
            refused.contains("moving walls' velocities"),
            "{to}: {refused}"
        );
    }
    let straight = run_file(&file, "c", Some(30), None);
    let resumed = run_file(&file, "b", Some(30), Some(&ckpt));
    assert_eq!(straight, resumed);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The limit driver finds the contacts of circles and ellipses by the
/// pair query: a circle on the floor, a circle on it, an ellipse on the
/// floor beside them, and a circle apart from all, which touches nothing.
#[test]
fn limit_shapes_contacts_come_from_the_pair_query() {
    let text = r#"
[driver]
kind = "limit"
multiply_dead_loads = true

[[bodies]]
kind = "wall"
start = [-10.0, 0.0]
end = [10.0, 0.0]

[[bodies]]
kind = "circle"
centre = [0.0, 1.0]
radius = 1.0
density = 1000.0

[[bodies]]
kind = "circle"
centre = [0.0, 3.0]
radius = 1.0
density = 1000.0

[[bodies]]
kind = "ellipse"
centre = [5.0, 0.5]
semi_major = 2.0
semi_minor = 0.5
density = 1000.0

[[bodies]]
kind = "circle"
centre = [-5.0, 4.0]
radius = 1.0
density = 1000.0

[law]
kind = "rigid-plastic"
cohesion = 10.0
"#;
    let prepared = scenario::prepare(Path::new("model.toml"), text, Overrides::default()).unwrap();
    let scenario::Model::Limit(plan) = &prepared.model else {
        panic!("not a limit model");
    };
    let model = &plan.model;
    assert_eq!(model.bodies().len(), 4);
    assert_eq!(model.supports().len(), 1);
    let pairs: Vec<(usize, dismech::limit::Partner)> = model
        .contacts()
        .iter()
        .map(|c| (c.body, c.partner))
        .collect();
    use dismech::limit::Partner;
    assert_eq!(
        pairs,
        [
            (0, Partner::Support(0)),
            (0, Partner::Body(1)),
            (2, Partner::Support(0)),
        ]
    );
    // Self-weight m g under the default gravity.
    let weight = 1000.0 * std::f64::consts::PI * 9.81;
    assert!((model.bodies()[0].load.y + weight).abs() < 1e-9 * weight);
    assert_eq!(
        model.load_driver(),
        Some(&dismech::limit::LoadDriver::DeadLoads)
    );
}

/// The refusal of `name` (a scenario of `examples/scenarios/`) with `from`
/// replaced by `to`.
fn refusal_of(name: &str, from: &str, to: &str) -> String {
    let text = std::fs::read_to_string(scenarios().join(name)).unwrap();
    assert!(text.contains(from), "{name}: {from}");
    let text = text.replacen(from, to, 1);
    match scenario::prepare(Path::new("model.toml"), &text, Overrides::default()) {
        Err(ScenarioError::Invalid(located)) => located.to_string(),
        Err(e) => panic!("not a placed refusal: {e}"),
        Ok(_) => panic!("accepted: {to}"),
    }
}

/// The limit driver's bodies of shapes: values refused by key, and
/// combinations that cannot compose by both keys.
#[test]
fn limit_shapes_refusals_name_their_keys() {
    let bad = [
        (
            "contact_tolerance = 8e-10",
            "contact_tolerance = -1.0",
            "`driver.contact_tolerance` = -1.0",
        ),
        ("width = 0.4", "width = 0.0", "`bodies[0].width` = 0.0"),
        (
            "end = [1.0, 0.0]",
            "end = [-1.0, 0.0]",
            "`bodies[1].end` = [-1.0, 0.0]",
        ),
        (
            "body = 0, force = [1.0",
            "body = 3, force = [1.0",
            "`loads.live.body` = 3",
        ),
        (
            "force = [1.0, 0.0]",
            "force = [0.0, 0.0]",
            "`loads.live.force`",
        ),
        (
            "point = [0.0, 0.8]",
            "point = [0.0, nan]",
            "`loads.live.point`",
        ),
        (
            "body = 0, force = [0.0, -1000.0]",
            "body = 1, force = [0.0, -1000.0]",
            "`loads.forces[0].body` = 1",
        ),
        (
            "friction_angle = 30.0",
            "friction_angle = 95.0",
            "`law.friction_angle` = 95.0",
        ),
        (
            "height = 0.8",
            "height = 0.8\nvelocity = [1.0, 0.0]",
            "`driver.kind` and `bodies[0].velocity`",
        ),
        (
            "contact_tolerance = 8e-10",
            "multiply_dead_loads = true",
            "`loads.live` and `driver.multiply_dead_loads`",
        ),
        (
            "live = { body = 0, force = [1.0, 0.0], point = [0.0, 0.8] }",
            "",
            "`loads`",
        ),
        (
            "live = { body = 0,",
            "tractions = [{ body = 0, edge = 0, traction = [1.0, 0.0] }]\nlive = { body = 0,",
            "`driver.kind` and `loads.tractions`",
        ),
        (
            "kind = \"rectangle\"",
            "kind = \"circle-rows\"",
            "`bodies[0]",
        ),
        (
            "height = 0.8\n",
            "height = 0.8\nbogus = 1\n",
            "`bodies[0].bogus`",
        ),
    ];
    for (from, to, key) in bad {
        let message = refusal_of("polygon_lp.toml", from, to);
        assert!(message.starts_with("model.toml:"), "{message}");
        assert!(message.contains(key), "{to}: {message}");
    }
    // Beside a lattice, the keys of bodies of shapes are refused by both.
    let lattice = refusal_of(
        "lp_bearing_capacity.toml",
        "kind = \"limit\"",
        "kind = \"limit\"\ncontact_tolerance = 1e-9",
    );
    assert!(
        lattice.contains("`bodies[0].kind` and `driver.contact_tolerance`"),
        "{lattice}"
    );
    let mixed = refusal_of(
        "lp_bearing_capacity.toml",
        "[law]",
        "[[bodies]]\nkind = \"circle\"\ncentre = [0.0, 0.0]\nradius = 1.0\n\n[law]",
    );
    assert!(
        mixed.contains("`bodies[0].kind` and `bodies[1].kind`"),
        "{mixed}"
    );
    // A live load is the limit driver's.
    let explicit = refusal(
        "[loads]",
        "[loads]\nlive = { body = 0, force = [1.0, 0.0] }",
    );
    assert!(explicit.contains("`loads.live`"), "{explicit}");
}

/// The refusal of the Katsuki scenario with `from` replaced by `to`.
fn refusal(from: &str, to: &str) -> String {
    let file = scenarios().join("katsuki_example1.toml");
    let text = std::fs::read_to_string(&file)
        .unwrap()
        .replacen(from, to, 1);
    assert!(!text.contains(from) || from == to || text.matches(from).count() < 2);
    match scenario::prepare(Path::new("model.toml"), &text, Overrides::default()) {
        Err(ScenarioError::Invalid(located)) => located.to_string(),
        Err(e) => panic!("not a placed refusal: {e}"),
        Ok(_) => panic!("accepted: {to}"),
    }
}

#[test]
fn refusals_name_the_file_line_column_key_and_value() {
    assert_eq!(
        refusal("friction = 0.577", "friction = 0.577\nfrction = 3"),
        "model.toml:43:1: `law.frction` = 3: unknown field `frction`, expected one of `youngs_modulus`, `poisson_ratio`, `stiffness_ratio`, `friction`, `friction_angle`"
    );
    assert_eq!(
        refusal("friction = 0.577", "friction = \"NaN\""),
        "model.toml:42:12: `law.friction` = \"NaN\": invalid type: string \"NaN\", expected f64"
    );
    assert_eq!(
        refusal("radius = 0.07", "radius = -0.07"),
        "model.toml:30:10: `bodies[0].radius` = -0.07: -0.07 is refused: must be finite and > 0"
    );
    assert_eq!(
        refusal("poisson_ratio = 0.3", "poisson_ratio = 0.7"),
        "model.toml:40:17: `law.poisson_ratio` = 0.7: invalid Poisson's ratio = 0.7: must lie in [-1, 0.5)"
    );
    assert_eq!(
        refusal("kind = \"katsuki\"", "kind = \"katsuk\""),
        "model.toml:38:8: `law.kind` = \"katsuk\": unknown variant `katsuk`, expected one of `katsuki`, `spring-dashpot-coulomb`, `penalty-coulomb`, `rigid-plastic`, `hpm`"
    );
    assert_eq!(
        refusal("count = 179", ""),
        "model.toml:25:1: `bodies[0].count`: missing field `count`"
    );
    // A combination the library cannot compose names both keys.
    assert_eq!(
        refusal("kind = \"explicit-euler\"", "kind = \"newmark\""),
        "model.toml:17:8: `driver.kind` and `integrator.kind`: the explicit driver takes an explicit integrator (`explicit-euler`); `newmark` and `quasi-static` are implicit (driver.kind = \"explicit\", integrator.kind = \"newmark\")"
    );
    // A body outside the box.
    let outside = refusal("clearance = 0.005", "clearance = 5.0");
    assert!(
        outside.starts_with("model.toml:25:1: `bodies[0]` and `boundary`:"),
        "{outside}"
    );
    assert!(outside.contains("outside the frame's box"), "{outside}");
    // A shape's own refusal names the key that gave the value: an
    // ellipse's semi-axes (and their order), a rectangle's sides.
    let body = |table: &str| {
        refusal(
            "density = 2690.0000000000005\n",
            &format!("density = 2690.0000000000005\n\n[[bodies]]\n{table}\n"),
        )
    };
    let ellipse = body("kind = \"ellipse\"\ncentre = [1.0, 2.5]\nsemi_major = -0.1\nsemi_minor = 0.05\ndensity = 2690.0");
    assert!(ellipse.contains("`bodies[1].semi_major`"), "{ellipse}");
    let swapped = body("kind = \"ellipse\"\ncentre = [1.0, 2.5]\nsemi_major = 0.05\nsemi_minor = 0.1\ndensity = 2690.0");
    assert!(swapped.contains("`bodies[1].semi_minor`"), "{swapped}");
    let rectangle = body(
        "kind = \"rectangle\"\ncentre = [1.0, 2.5]\nwidth = 0.2\nheight = 0.0\ndensity = 2690.0",
    );
    assert!(rectangle.contains("`bodies[1].height`"), "{rectangle}");
    // A syntax error names its line and column.
    assert_eq!(
        refusal("per_row = 14", "per_row = = 14"),
        "model.toml:31:11: `(syntax)`: not valid TOML: extra `=`, expected nothing"
    );
}

#[test]
fn a_refused_file_exits_with_the_bad_input_code_and_writes_nothing() {
    let dir = scratch("refused");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("bad.toml");
    std::fs::write(&file, "[driver]\nkind = \"explicit\"\ndt = -1\n").unwrap();
    let run = Command::new(env!("CARGO_BIN_EXE_dismech"))
        .arg("run")
        .arg(&file)
        .arg("--quiet")
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains("bad.toml:1:1: `law`: missing field `law`"),
        "{stderr}"
    );
    assert!(!scenario::default_output(&file).exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A few thousand mutants of the scenarios (the example
/// `fuzz_scenarios` runs 10⁵ and more): no panic, every refusal names a
/// key and a line.
#[test]
fn mutated_scenarios_are_refused_by_key_without_a_panic() {
    let mut seeds = Vec::new();
    for name in [
        "katsuki_example1.toml",
        "dda_sliding_block.toml",
        "lp_bearing_capacity.toml",
        "dem_incline_and_plate.toml",
    ] {
        seeds.push((
            name.to_string(),
            std::fs::read_to_string(scenarios().join(name)).unwrap(),
        ));
    }
    let tally = fuzz::run(&seeds, 1000, 7);
    assert_eq!(tally.files, 4000);
    assert!(tally.panics.is_empty(), "{:?}", tally.panics.first());
    assert!(tally.unnamed.is_empty(), "{:?}", tally.unnamed.first());
    assert!(tally.refused > 3000, "{tally:?}");
    assert!(tally.valid > 0, "{tally:?}");
}

/// The scenario `name` with `extra` appended (to its last table,
/// `[output]`), written as `model.toml` into the folder `dir`.
fn variant(name: &str, extra: &str, dir: &Path) -> PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    let text = std::fs::read_to_string(scenarios().join(name)).unwrap();
    assert!(text
        .trim_end()
        .ends_with(&text[text.rfind("[output]").unwrap()..].trim_end()));
    let file = dir.join("model.toml");
    std::fs::write(&file, format!("{text}\n{extra}\n")).unwrap();
    file
}

/// Run `file` into `dir/out`, from the start or from `resume`; the text
/// of its summary without the keys a resumed run writes otherwise (its
/// frames, and where it resumed from).
fn run_file(file: &Path, out: &str, max_steps: Option<u64>, resume: Option<&Path>) -> String {
    let overrides = Overrides {
        max_steps,
        end_time: None,
    };
    let prepared = scenario::load(file, overrides).unwrap();
    let out = file.with_file_name(out);
    let finished = match resume {
        Some(c) => scenario::resume(prepared, file, &out, false, c),
        None => scenario::execute(prepared, file, &out, false),
    }
    .unwrap();
    let mut summary = finished.summary;
    let map = summary.as_object_mut().unwrap();
    assert_eq!(map.remove("resumed_from").is_some(), resume.is_some());
    map.remove("frames");
    serde_json::to_string(&summary).unwrap()
}

/// The checkpoints in `dir`, by name (a file being written is hidden).
fn checkpoints(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| !n.starts_with('.'))
        .collect();
    names.sort();
    names
}

/// Every checkpoint the resumed run wrote is, byte for byte, the one the
/// run that never stopped wrote at that step.
fn same_checkpoints(straight: &Path, resumed: &Path) -> usize {
    let names = checkpoints(resumed);
    for name in &names {
        assert_eq!(
            std::fs::read(straight.join(name)).unwrap(),
            std::fs::read(resumed.join(name)).unwrap(),
            "{name}"
        );
    }
    names.len()
}

/// Katsuki's Example 1 run to rest in one go, and stopped at step 3 000
/// (particles still falling and sliding) then resumed from its
/// checkpoint in a new run: the same summary, to the last digit of every
/// number, and the same checkpoints.
#[test]
fn an_explicit_run_stopped_and_resumed_ends_in_the_same_bits() {
    let dir = scratch("resume-explicit");
    let file = variant("katsuki_example1.toml", "checkpoint_every = 500", &dir);
    let straight = run_file(&file, "straight", None, None);
    assert!(straight.contains("\"AtRest\""), "{straight}");
    let stopped = run_file(&file, "stopped", Some(3000), None);
    assert!(stopped.contains("\"StepLimit\""), "{stopped}");
    assert_eq!(
        checkpoints(&dir.join("stopped.checkpoints")),
        (1..=6)
            .map(|k| format!("step-{:010}.ckpt", 500 * k))
            .collect::<Vec<_>>()
    );
    let from = dir.join("stopped.checkpoints/step-0000003000.ckpt");
    let resumed = run_file(&file, "resumed", None, Some(&from));
    assert_eq!(resumed, straight);
    assert!(
        same_checkpoints(
            &dir.join("straight.checkpoints"),
            &dir.join("resumed.checkpoints")
        ) >= 10
    );
    // A run stopped at step 3 000 by `--max-steps` and resumed with
    // `--max-steps 4000` ends as the run stopped at 4 000.
    let to_4000 = run_file(&file, "to4000", Some(4000), None);
    let resumed_4000 = run_file(&file, "resumed4000", Some(4000), Some(&from));
    assert_eq!(resumed_4000, to_4000);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The DDA sliding block run in one go, and stopped at step 700 (the
/// block sliding on the shaken base) then resumed: the same summary and
/// checkpoints.
#[test]
fn an_implicit_run_stopped_and_resumed_ends_in_the_same_bits() {
    let dir = scratch("resume-implicit");
    let file = variant("dda_sliding_block.toml", "checkpoint_every = 100", &dir);
    let straight = run_file(&file, "straight", None, None);
    run_file(&file, "stopped", Some(700), None);
    let from = dir.join("stopped.checkpoints/step-0000000700.ckpt");
    let resumed = run_file(&file, "resumed", None, Some(&from));
    assert_eq!(resumed, straight);
    assert_eq!(
        same_checkpoints(
            &dir.join("straight.checkpoints"),
            &dir.join("resumed.checkpoints")
        ),
        8
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `dismech run` killed while it runs, then resumed from the last
/// checkpoint it wrote, ends as the run never killed.
#[test]
fn a_killed_run_resumes_from_its_last_checkpoint() {
    let dir = scratch("resume-killed");
    let file = variant("dda_sliding_block.toml", "checkpoint_every = 20", &dir);
    let straight = run_file(&file, "straight", None, None);
    let ckpts = dir.join("killed.checkpoints");
    let mut child = Command::new(env!("CARGO_BIN_EXE_dismech"))
        .arg("run")
        .arg(&file)
        .args(["--quiet", "--out"])
        .arg(dir.join("killed"))
        .spawn()
        .unwrap();
    // Kill it once it has written a checkpoint, at a step the scheduler
    // chooses.
    while !ckpts.is_dir() || checkpoints(&ckpts).is_empty() {
        if let Some(status) = child.try_wait().unwrap() {
            assert!(
                ckpts.is_dir(),
                "the run ended ({status}) without a checkpoint"
            );
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    std::thread::sleep(std::time::Duration::from_millis(50));
    let _ = child.kill();
    child.wait().unwrap();
    // The last checkpoint before the end (a killed run may have finished).
    let last = checkpoints(&ckpts)
        .into_iter()
        .rfind(|n| n != "step-0000001500.ckpt")
        .unwrap();
    let resumed = Command::new(env!("CARGO_BIN_EXE_dismech"))
        .arg("run")
        .arg(&file)
        .args(["--quiet", "--out"])
        .arg(dir.join("resumed"))
        .arg("--resume")
        .arg(ckpts.join(&last))
        .output()
        .unwrap();
    assert_eq!(
        resumed.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&resumed.stderr)
    );
    let mut summary: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("resumed/summary.json")).unwrap())
            .unwrap();
    let map = summary.as_object_mut().unwrap();
    assert!(map.remove("resumed_from").is_some());
    map.remove("frames");
    assert_eq!(serde_json::to_string(&summary).unwrap(), straight);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The error of resuming `file` from `checkpoint`.
fn resume_refusal(file: &Path, checkpoint: &Path, max_steps: Option<u64>) -> String {
    let overrides = Overrides {
        max_steps,
        end_time: None,
    };
    let prepared = scenario::load(file, overrides).unwrap();
    let out = file.with_file_name("refused");
    match scenario::resume(prepared, file, &out, false, checkpoint) {
        Ok(_) => panic!("resumed from {checkpoint:?}"),
        Err(e) => {
            assert!(!out.exists());
            e.to_string()
        }
    }
}

#[test]
fn a_checkpoint_of_another_run_or_damaged_is_refused_by_name() {
    let dir = scratch("resume-refused");
    let dem = variant(
        "katsuki_example1.toml",
        "checkpoint_every = 100",
        &dir.join("dem"),
    );
    let dda = variant(
        "dda_sliding_block.toml",
        "checkpoint_every = 10",
        &dir.join("dda"),
    );
    run_file(&dem, "a", Some(200), None);
    run_file(&dda, "a", Some(20), None);
    let dem_ckpt = dir.join("dem/a.checkpoints/step-0000000200.ckpt");
    let dda_ckpt = dir.join("dda/a.checkpoints/step-0000000020.ckpt");
    let refused = resume_refusal(&dem, &dda_ckpt, None);
    assert!(
        refused.contains("a checkpoint of the implicit driver, restored into the explicit driver"),
        "{refused}"
    );
    let refused = resume_refusal(&dda, &dem_ckpt, None);
    assert!(
        refused.contains("a checkpoint of the explicit driver"),
        "{refused}"
    );
    // Past the run's end.
    let refused = resume_refusal(&dda, &dda_ckpt, Some(20));
    assert!(
        refused.contains("at or past the run's end at step 20"),
        "{refused}"
    );
    // Another model: the bodies' density, the law's penalty, the step.
    let edit = |file: &Path, from: &str, to: &str| {
        let text = std::fs::read_to_string(file).unwrap();
        assert!(text.contains(from));
        let edited = file.with_file_name("edited.toml");
        std::fs::write(&edited, text.replacen(from, to, 1)).unwrap();
        edited
    };
    let refused = resume_refusal(
        &edit(&dem, "density = 2690.0000000000005", "density = 2691"),
        &dem_ckpt,
        None,
    );
    assert!(refused.contains("body 0's mass"), "{refused}");
    let refused = resume_refusal(&edit(&dem, "\ndt = 1e-4", "\ndt = 0.5e-4"), &dem_ckpt, None);
    assert!(refused.contains("driver.dt"), "{refused}");
    let refused = resume_refusal(
        &edit(&dda, "penalty = 2e9", "penalty = 3e9"),
        &dda_ckpt,
        None,
    );
    assert!(refused.contains("contact laws parameters"), "{refused}");
    // Damaged: cut short, a byte changed, not a checkpoint, missing.
    let bytes = std::fs::read(&dem_ckpt).unwrap();
    let damaged = dir.join("damaged.ckpt");
    std::fs::write(&damaged, &bytes[..bytes.len() / 2]).unwrap();
    let refused = resume_refusal(&dem, &damaged, None);
    assert!(refused.contains("damaged.ckpt: truncated"), "{refused}");
    let mut flipped = bytes.clone();
    flipped[bytes.len() / 2] ^= 1;
    std::fs::write(&damaged, &flipped).unwrap();
    let refused = resume_refusal(&dem, &damaged, None);
    assert!(refused.contains("damaged.ckpt: corrupt"), "{refused}");
    let refused = resume_refusal(&dem, &dem, None);
    assert!(refused.contains("not a dismech checkpoint"), "{refused}");
    let refused = resume_refusal(&dem, &dir.join("none.ckpt"), None);
    assert!(refused.contains("none.ckpt: cannot be read"), "{refused}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The implicit driver's summary gives each body's contact force: the
/// base and the sliding block, in contact only with each other, carry
/// opposite forces, the block's pointing up.
#[test]
fn implicit_summary_gives_each_bodys_contact_force() {
    let summary = run(
        "dda_sliding_block.toml",
        Overrides {
            max_steps: Some(5),
            end_time: None,
        },
    );
    let bodies = summary["bodies"].as_array().unwrap();
    let force = |k: usize, i: usize| bodies[k]["contact_force"][i].as_f64().unwrap();
    for i in 0..2 {
        assert_eq!(force(0, i).to_bits(), (-force(1, i)).to_bits(), "{summary}");
    }
    assert!(force(1, 1) > 0.0, "{summary}");
}

/// `dismech run FILE --check --resume CHECKPOINT` checks the resumed
/// run: a checkpoint that resumes the file passes, naming its step; one
/// of another model, damaged or past the run's end is refused as `--resume`
/// refuses it (exit status 2); nothing is run or written either way.
#[test]
fn check_with_resume_checks_the_checkpoint_and_writes_nothing() {
    let dir = scratch("check-resume");
    let dda = variant("dda_sliding_block.toml", "checkpoint_every = 10", &dir);
    run_file(&dda, "a", Some(20), None);
    let good = dir.join("a.checkpoints/step-0000000020.ckpt");
    let check = |checkpoint: &Path, max_steps: Option<&str>| {
        let mut command = Command::new(env!("CARGO_BIN_EXE_dismech"));
        command
            .arg("run")
            .arg(&dda)
            .args(["--quiet", "--check", "--out"])
            .arg(dir.join("checked"))
            .arg("--resume")
            .arg(checkpoint);
        if let Some(n) = max_steps {
            command.args(["--max-steps", n]);
        }
        let output = command.output().unwrap();
        assert!(!dir.join("checked").exists());
        assert!(!dir.join("checked.checkpoints").exists());
        (
            output.status.code(),
            String::from_utf8_lossy(&output.stdout).into_owned(),
            String::from_utf8_lossy(&output.stderr).into_owned(),
        )
    };
    let (code, stdout, stderr) = check(&good, None);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        stdout.contains("the scenario is valid and resumes from") && stdout.contains("(step 20)"),
        "{stdout}"
    );
    let (code, _, stderr) = check(&good, Some("20"));
    assert_eq!(code, Some(2), "{stderr}");
    assert!(
        stderr.contains("at or past the run's end at step 20"),
        "{stderr}"
    );
    let bytes = std::fs::read(&good).unwrap();
    let damaged = dir.join("damaged.ckpt");
    std::fs::write(&damaged, &bytes[..bytes.len() / 2]).unwrap();
    let (code, _, stderr) = check(&damaged, None);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("damaged.ckpt: truncated"), "{stderr}");
    let (code, _, stderr) = check(&dir.join("none.ckpt"), None);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("none.ckpt: cannot be read"), "{stderr}");
    // A limit analysis has no checkpoints, whatever the file.
    let lp = Command::new(env!("CARGO_BIN_EXE_dismech"))
        .arg("run")
        .arg(scenarios().join("lp_bearing_capacity.toml"))
        .args(["--quiet", "--check", "--resume"])
        .arg(dir.join("none.ckpt"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&lp.stderr);
    assert_eq!(lp.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("a limit or HPM analysis takes no steps and has no checkpoints"),
        "{stderr}"
    );
    // Another model: the law's penalty changed.
    let text = std::fs::read_to_string(&dda).unwrap();
    std::fs::write(&dda, text.replacen("penalty = 2e9", "penalty = 3e9", 1)).unwrap();
    let (code, _, stderr) = check(&good, None);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("contact laws parameters"), "{stderr}");
    // The library's check, in-process.
    let prepared = scenario::load(&dda, Overrides::default()).unwrap();
    assert!(scenario::check_resume(prepared, &dda, &good).is_err());
    std::fs::write(&dda, &text).unwrap();
    let prepared = scenario::load(&dda, Overrides::default()).unwrap();
    assert_eq!(scenario::check_resume(prepared, &dda, &good).unwrap(), 20);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `keep_checkpoints = 3`: a run leaves its newest three checkpoints; a
/// run resumed into the same folder removes the older ones as it writes
/// newer ones, and its result is the run's that never stopped.
#[test]
fn keep_checkpoints_leaves_the_newest() {
    let dir = scratch("keep-checkpoints");
    let file = variant(
        "dda_sliding_block.toml",
        "checkpoint_every = 100\ncheckpoint_dir = \"ck\"\nkeep_checkpoints = 3",
        &dir,
    );
    let names = |steps: &[u64]| -> Vec<String> {
        steps.iter().map(|k| format!("step-{k:010}.ckpt")).collect()
    };
    run_file(&file, "a", Some(700), None);
    assert_eq!(checkpoints(&dir.join("ck")), names(&[500, 600, 700]));
    let from = dir.join("resume-from.ckpt");
    std::fs::copy(dir.join("ck/step-0000000500.ckpt"), &from).unwrap();
    let resumed = run_file(&file, "b", Some(900), Some(&from));
    assert_eq!(checkpoints(&dir.join("ck")), names(&[700, 800, 900]));
    std::fs::remove_dir_all(dir.join("ck")).unwrap();
    let straight = run_file(&file, "c", Some(900), None);
    assert_eq!(resumed, straight);
    assert_eq!(checkpoints(&dir.join("ck")), names(&[700, 800, 900]));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn checkpoint_keys_are_checked() {
    let refused = |name: &str, extra: &str| -> String {
        let text = std::fs::read_to_string(scenarios().join(name)).unwrap();
        let text = if text.contains("[output]") {
            format!("{text}\n{extra}\n")
        } else {
            format!("{text}\n[output]\n{extra}\n")
        };
        match scenario::prepare(Path::new("model.toml"), &text, Overrides::default()) {
            Err(ScenarioError::Invalid(located)) => located.to_string(),
            Err(e) => panic!("not a placed refusal: {e}"),
            Ok(_) => panic!("accepted: {extra}"),
        }
    };
    let zero = refused("dda_sliding_block.toml", "checkpoint_every = 0");
    assert!(
        zero.contains("`output.checkpoint_every` = 0: 0 is refused"),
        "{zero}"
    );
    let alone = refused("dda_sliding_block.toml", "checkpoint_dir = \"ck\"");
    assert!(
        alone.contains("`output.checkpoint_dir` and `output.checkpoint_every`"),
        "{alone}"
    );
    let empty = refused(
        "dda_sliding_block.toml",
        "checkpoint_every = 5\ncheckpoint_dir = \"\"",
    );
    assert!(empty.contains("`output.checkpoint_dir` = \"\""), "{empty}");
    let rest = refused("katsuki_example1.toml", "checkpoint_every = 150");
    assert!(
        rest.contains("`output.checkpoint_every` and `run.check_every`"),
        "{rest}"
    );
    let limit = refused("lp_bearing_capacity.toml", "checkpoint_every = 1");
    assert!(
        limit.contains("`driver.kind` and `output.checkpoint_every`"),
        "{limit}"
    );
    let keep = refused(
        "dda_sliding_block.toml",
        "checkpoint_every = 5\nkeep_checkpoints = 0",
    );
    assert!(
        keep.contains("`output.keep_checkpoints` = 0: 0 is refused: must be at least 1"),
        "{keep}"
    );
    let keep_alone = refused("dda_sliding_block.toml", "keep_checkpoints = 2");
    assert!(
        keep_alone.contains("`output.keep_checkpoints` and `output.checkpoint_every`"),
        "{keep_alone}"
    );
    let negative = refused("dda_sliding_block.toml", "checkpoint_every = -1");
    assert!(
        negative.contains("`output.checkpoint_every` = -1"),
        "{negative}"
    );
}

/// Fixed and driven bodies of any shape in the explicit driver: the
/// scenario of a fixed wedge, a fixed disc and a plate at a constant
/// velocity ends in the same bits as the scene built in Rust with
/// `Particle::fixed` and `Particle::prescribed`.
#[test]
fn fixed_and_driven_bodies_scenario_equals_the_composition_bit_for_bit() {
    use dismech::law::{Damping, NormalStiffness};
    use dismech::math::Pose2;
    use dismech::scene::{Frame, Particle, Scene};
    use dismech::shape::{Circle, Polygon};
    let summary = run("dem_incline_and_plate.toml", Overrides::default());
    let mut scene = Scene::new(Frame::open_box(2.0, 1.0).unwrap(), Vec2::new(0.0, -9.81)).unwrap();
    let wedge = [
        Point::new(0.0, 0.0),
        Point::new(1.0, 0.0),
        Point::new(0.0, 0.5),
    ];
    let (wedge, centroid) = Polygon::from_world(&wedge, 0).unwrap();
    scene.particles.push(Particle::fixed(
        wedge.into(),
        Pose2::new(centroid.x, centroid.y, 0.0),
    ));
    for (x, y) in [(0.2, 0.48), (0.35, 0.405), (0.5, 0.33)] {
        scene.add_circle(Point::new(x, y), 0.05, 2600.0).unwrap();
    }
    scene.particles.push(Particle::fixed(
        Circle::new(0.03).unwrap().into(),
        Pose2::new(1.15, 0.0, 0.0),
    ));
    scene
        .add_rectangle(Point::new(1.4, 0.0505), 0.1, 0.1, 0.0, 2000.0)
        .unwrap();
    scene.particles.push(Particle::prescribed(
        Polygon::rectangle(0.04, 0.3).unwrap().into(),
        Pose2::new(1.6, 0.16, 0.0),
        Vec2::new(-0.4, 0.0),
        0.0,
    ));
    let law =
        SpringDashpotCoulomb::new(NormalStiffness::Constant(1e6), 0.25, 0.5, Damping::Critical)
            .unwrap();
    let settings = DemSettings {
        dt: 1e-4,
        ..DemSettings::default()
    };
    let mut dem = DemSimulation::new(scene, law, ExplicitEuler, settings).unwrap();
    for _ in 0..8000 {
        dem.step().unwrap();
    }
    assert_eq!(summary["steps"].as_u64(), Some(8000));
    assert_eq!(bits(&summary["time"]), dem.time().to_bits());
    let bodies = summary["bodies"].as_array().unwrap();
    assert_eq!(bodies.len(), 7);
    for (b, p) in bodies.iter().zip(&dem.scene().particles) {
        assert_eq!(bits(&b["centre"][0]), p.pose.position.x.to_bits());
        assert_eq!(bits(&b["centre"][1]), p.pose.position.y.to_bits());
        assert_eq!(bits(&b["angle"]), p.pose.angle.to_bits());
        assert_eq!(bits(&b["velocity"][0]), p.velocity.x.to_bits());
        assert_eq!(bits(&b["velocity"][1]), p.velocity.y.to_bits());
        assert_eq!(bits(&b["angular_velocity"]), p.angular_velocity.to_bits());
    }
    // The wedge and the bump did not move; the plate kept its velocity
    // and pushed the block; the discs came down the wedge.
    assert_eq!(
        bodies[0]["centre"],
        serde_json::json!([1.0 / 3.0, 0.5 / 3.0])
    );
    assert_eq!(bodies[4]["velocity"], serde_json::json!([0.0, 0.0]));
    assert_eq!(bodies[6]["velocity"], serde_json::json!([-0.4, 0.0]));
    assert!(bodies[5]["velocity"][0].as_f64().unwrap() < -0.1);
    assert!(bodies[1]["centre"][0].as_f64().unwrap() > 0.9);
    assert_eq!(
        bits(&summary["weight"]),
        dem.scene().total_weight().to_bits()
    );
}

#[test]
fn motions_of_the_explicit_driver_are_checked() {
    let refused = |from: &str, to: &str| -> String {
        let text = std::fs::read_to_string(scenarios().join("dem_incline_and_plate.toml"))
            .unwrap()
            .replacen(from, to, 1);
        match scenario::prepare(Path::new("model.toml"), &text, Overrides::default()) {
            Err(ScenarioError::Invalid(located)) => located.to_string(),
            Err(e) => panic!("not a placed refusal: {e}"),
            Ok(_) => panic!("accepted: {to}"),
        }
    };
    let sine = refused(
        "motion = { kind = \"fixed\" }",
        "motion = { kind = \"sine\", amplitude = 0.1, frequency = 1.0 }",
    );
    assert!(
        sine.contains("`driver.kind` and `bodies[0].motion.kind`"),
        "{sine}"
    );
    let density = refused(
        "motion = { kind = \"fixed\" }",
        "motion = { kind = \"fixed\" }\ndensity = 2000.0",
    );
    assert!(
        density.contains("`bodies[0].density` and `bodies[0].motion.kind`"),
        "{density}"
    );
    assert!(density.contains("infinite mass"), "{density}");
    let moving = refused(
        "motion = { kind = \"fixed\" }",
        "motion = { kind = \"fixed\" }\nvelocity = [1.0, 0.0]",
    );
    assert!(
        moving.contains("`bodies[0].velocity` and `bodies[0].motion.kind`"),
        "{moving}"
    );
    let force = refused(
        "gravity = [0.0, -9.81]",
        "gravity = [0.0, -9.81]\nforces = [{ body = 6, force = [1.0, 0.0] }]",
    );
    assert!(
        force.contains("`loads.forces[0].body` and `bodies[6].motion.kind`"),
        "{force}"
    );
    let unknown = refused("kind = \"constant-velocity\"", "kind = \"constant-speed\"");
    assert!(
        unknown.contains("unknown variant `constant-speed`"),
        "{unknown}"
    );
    // The implicit driver refuses a constant velocity, naming both keys.
    let text = std::fs::read_to_string(scenarios().join("dda_sliding_block.toml"))
        .unwrap()
        .replacen(
            "kind = \"sine\", amplitude = 0.06863101004005262, frequency = 2.0",
            "kind = \"constant-velocity\"",
            1,
        );
    match scenario::prepare(Path::new("model.toml"), &text, Overrides::default()) {
        Err(ScenarioError::Invalid(located)) => {
            let m = located.to_string();
            assert!(
                m.contains("`driver.kind` and `bodies[0].motion.kind`"),
                "{m}"
            );
        }
        other => panic!("{:?}", other.err()),
    }
}

/// The cross-composition of a rectangle sliding on an incline from its
/// file: the same displacement down the slope and rotation, to the bit,
/// as `compositions::polygon_incline::run_block_on_incline` for the
/// default block.
#[test]
fn polygon_incline_scenario_equals_the_composition_bit_for_bit() {
    use dismech::math::perp;
    use dismech_cli::compositions::polygon_incline::{run_block_on_incline, BlockOnIncline};
    let summary = run("polygon_incline.toml", Overrides::default());
    let setup = BlockOnIncline::default();
    let expected = run_block_on_incline(&setup).unwrap();
    // The composition's start, as it computes it.
    let beta = setup.slope;
    let downhill = Vec2::new(beta.cos(), -beta.sin());
    let top = Point::new(0.0, 15.0 * setup.width * beta.sin());
    let centre = top + downhill * (3.0 * setup.width) + perp(&downhill) * (0.5 * setup.height);
    let block = &summary["bodies"][0];
    let at = Point::new(
        block["centre"][0].as_f64().unwrap(),
        block["centre"][1].as_f64().unwrap(),
    );
    assert_eq!(summary["steps"].as_u64(), Some(50_000));
    let displacement = (at - centre).dot(&downhill);
    assert_eq!(displacement.to_bits(), expected.displacement.to_bits());
    let rotation = block["angle"].as_f64().unwrap() + beta;
    assert_eq!(rotation.to_bits(), expected.rotation.to_bits());
    // It slid: about half of g (sin b - cos b tan phi) t^2 in 1 s.
    let exact = 0.5 * expected.exact_acceleration;
    assert!(
        (displacement / exact - 1.0).abs() < 0.05,
        "{displacement} vs {exact}"
    );
}

/// The cross-composition of a DDA disc rolling down an incline from its
/// file: the same turn (travel over radius), to the bit, as
/// `compositions::affine_disc::run_rolling_disc` for the default disc.
#[test]
fn affine_disc_scenario_equals_the_composition_bit_for_bit() {
    use dismech_cli::compositions::affine_disc::{run_rolling_disc, RollingDisc};
    let summary = run("affine_disc.toml", Overrides::default());
    let setup = RollingDisc::default();
    let expected = run_rolling_disc(&setup).unwrap();
    let (s, c) = setup.slope.sin_cos();
    let downhill = Vec2::new(c, -s);
    let normal = Vec2::new(s, c);
    let mass = setup.density * std::f64::consts::PI * setup.radius.powi(2);
    let sink = mass * setup.gravity * c / setup.penalty;
    let start = Point::origin() + normal * (setup.radius - sink);
    let disc = &summary["bodies"][0];
    let at = Point::new(
        disc["centroid"][0].as_f64().unwrap(),
        disc["centroid"][1].as_f64().unwrap(),
    );
    assert_eq!(summary["steps"].as_u64(), Some(2000));
    let turn = (at - start).dot(&downhill) / setup.radius;
    assert_eq!(turn.to_bits(), expected.turn.to_bits());
    assert_eq!(
        summary["outcome"]["halvings"].as_u64(),
        Some(expected.reductions as u64)
    );
    // It rolled: about half of (2/3) g sin b t^2 in 0.5 s.
    let exact = 0.5 * expected.exact_acceleration * 0.25 / setup.radius;
    assert!((turn / exact - 1.0).abs() < 0.1, "{turn} vs {exact}");
}

/// Paper 001's HPM example from its files: the representative slope's
/// elastic Fs, static and seismic, are the numbers `dismech reproduce
/// yamaguchi-hpm` reports (`slope.fs.elastic.*` and
/// `slope.fs_sliding.elastic.*`, written here as the f64s it printed), and
/// those the library gives for the reproduction's material and settings
/// on the same grids.
#[test]
fn yamaguchi_hpm_scenarios_equal_the_reproduction_bit_for_bit() {
    use dismech::hpm::{HpmMaterial, HpmModel, HpmSettings, HpmSolver, Seismic, SlopeGrids};
    let grids = SlopeGrids::read(
        &scenarios().join("yamaguchi_hpm/ground.asc"),
        &scenarios().join("yamaguchi_hpm/slip.asc"),
        None,
    )
    .unwrap();
    let model = HpmModel::new(&grids, &HpmMaterial::paper(), &HpmSettings::default()).unwrap();
    let toe = 270f64.to_radians();
    for (name, seismic, fs, sliding) in [
        (
            "yamaguchi_hpm.toml",
            Seismic::none(),
            1.2757176078478898,
            1.8106037943834912,
        ),
        (
            "yamaguchi_hpm_seismic.toml",
            Seismic {
                coefficient: 0.15,
                direction: (toe.cos(), toe.sin()),
            },
            0.9218122874622943,
            1.0715385969964661,
        ),
    ] {
        let summary = run(name, Overrides::default());
        let result = HpmSolver::new(&model)
            .unwrap()
            .elastic(&model, &seismic)
            .unwrap();
        let expected = result.safety_factor(&model).unwrap();
        let expected_sliding = result.sliding_safety_factor(&model).unwrap();
        assert_eq!(
            bits(&summary["safety_factor"]),
            expected.to_bits(),
            "{name}"
        );
        assert_eq!(
            bits(&summary["sliding_safety_factor"]),
            expected_sliding.to_bits(),
            "{name}"
        );
        assert_eq!(expected.to_bits(), f64::to_bits(fs), "{name}");
        assert_eq!(expected_sliding.to_bits(), f64::to_bits(sliding), "{name}");
        assert_eq!(
            summary["columns"].as_u64(),
            Some(model.columns.len() as u64)
        );
        assert_eq!(summary["frames"].as_u64(), Some(1));
    }
}

#[test]
fn hpm_keys_are_checked() {
    let refused = |from: &str, to: &str| -> String {
        let file = scenarios().join("yamaguchi_hpm.toml");
        let text = std::fs::read_to_string(&file)
            .unwrap()
            .replacen(from, to, 1);
        match scenario::prepare(&file, &text, Overrides::default()) {
            Err(ScenarioError::Invalid(located)) => located.to_string(),
            Err(e) => panic!("not a placed refusal: {e}"),
            Ok(_) => panic!("accepted: {to}"),
        }
    };
    let nu = refused("poisson_ratio = 0.2", "poisson_ratio = 0.5");
    assert!(nu.contains("`law.poisson_ratio` = 0.5"), "{nu}");
    let layers = refused("layers = 3", "layers = 2");
    assert!(layers.contains("`driver.layers` = 2"), "{layers}");
    let missing = refused(
        "slip = \"yamaguchi_hpm/slip.asc\"",
        "slip = \"nowhere.asc\"",
    );
    assert!(
        missing.contains("`bodies[0].slip` = \"nowhere.asc\""),
        "{missing}"
    );
    assert!(missing.contains("not a readable file"), "{missing}");
    let swapped = refused(
        "slip = \"yamaguchi_hpm/slip.asc\"",
        "slip = \"../katsuki_example1.toml\"",
    );
    assert!(swapped.contains("`bodies[0].slip`"), "{swapped}");
    let run = refused("[law]", "[run]\nkind = \"steps\"\nsteps = 3\n\n[law]");
    assert!(run.contains("`driver.kind` and `run`"), "{run}");
    let seismic = refused(
        "[law]",
        "[loads]\nseismic = { coefficient = -0.1, direction = [0.0, -1.0] }\n\n[law]",
    );
    assert!(seismic.contains("`loads.seismic.coefficient`"), "{seismic}");
    let law = refused("kind = \"hpm\"\nyoungs", "kind = \"katsuki\"\nyoungs");
    assert!(law.contains("`law"), "{law}");
    // The other drivers refuse the HPM's pieces by both keys.
    let text = std::fs::read_to_string(scenarios().join("dda_sliding_block.toml")).unwrap()
        + "\n[loads.seismic]\ncoefficient = 0.1\ndirection = [1.0, 0.0]\n";
    match scenario::prepare(Path::new("model.toml"), &text, Overrides::default()) {
        Err(e) => {
            let m = e.to_string();
            assert!(m.contains("loads"), "{m}");
        }
        Ok(_) => panic!("a seismic load beside the implicit driver"),
    }
}

/// The representative slope of paper 001 on the grids of the HPM
/// scenarios, with the reproduction's material and settings (those the
/// files give), and the load of `yamaguchi_hpm_seismic.toml` where
/// `seismic`.
fn yamaguchi_hpm_model(
    seismic: bool,
) -> (
    dismech::hpm::SlopeGrids,
    dismech::hpm::HpmModel,
    dismech::hpm::Seismic,
) {
    use dismech::hpm::{HpmMaterial, HpmModel, HpmSettings, Seismic, SlopeGrids};
    let grids = SlopeGrids::read(
        &scenarios().join("yamaguchi_hpm/ground.asc"),
        &scenarios().join("yamaguchi_hpm/slip.asc"),
        None,
    )
    .unwrap();
    let model = HpmModel::new(&grids, &HpmMaterial::paper(), &HpmSettings::default()).unwrap();
    let toe = 270f64.to_radians();
    let load = if seismic {
        Seismic {
            coefficient: 0.15,
            direction: (toe.cos(), toe.sin()),
        }
    } else {
        Seismic::none()
    };
    (grids, model, load)
}

/// Run the scenario `name` with `from` replaced by `to` (read as if from
/// its own file) into a scratch folder named `tag`, which is kept: its
/// summary and the folder.
fn run_hpm_variant(name: &str, from: &str, to: &str, tag: &str) -> (Value, PathBuf) {
    let file = scenarios().join(name);
    let text = std::fs::read_to_string(&file)
        .unwrap()
        .replacen(from, to, 1);
    let out = scratch(tag);
    let prepared = scenario::prepare(&file, &text, Overrides::default()).unwrap();
    let finished = scenario::execute(prepared, &file, &out, false).unwrap();
    (finished.summary, out)
}

/// Each map of `maps` was written into `out` as `{prefix}_{name}.asc` and
/// `.tif`, each read back by the library's readers equal to the map to
/// the bit, on the grid of `ground` (its corner, cell size and size).
fn assert_maps_written(
    out: &Path,
    prefix: &str,
    maps: &dismech::hpm::ColumnMaps,
    ground: &dismech::grid::Raster,
) {
    use dismech::grid::{read_esri_ascii, read_geotiff};
    use dismech::hpm::HPM_MAP_NAMES;
    assert_eq!(maps.maps.len(), HPM_MAP_NAMES.len());
    for name in HPM_MAP_NAMES {
        let expected = maps.get(name).unwrap();
        let asc = read_esri_ascii(&out.join(format!("{prefix}_{name}.asc"))).unwrap();
        let tif = read_geotiff(&out.join(format!("{prefix}_{name}.tif"))).unwrap();
        for read in [&asc, &tif] {
            assert!(read.same_grid(ground), "{prefix}_{name}");
            assert_eq!(read.cell_size().to_bits(), ground.cell_size().to_bits());
            let (x, y) = read.lower_left();
            let (gx, gy) = ground.lower_left();
            assert_eq!((x.to_bits(), y.to_bits()), (gx.to_bits(), gy.to_bits()));
            assert_eq!(
                (read.rows(), read.columns()),
                (ground.rows(), ground.columns())
            );
            assert_eq!(read.values().len(), expected.values().len());
            for (a, b) in read.values().iter().zip(expected.values()) {
                assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits), "{prefix}_{name}");
            }
        }
        assert!(
            expected.values().iter().any(Option::is_some),
            "{prefix}_{name}: no data at all"
        );
    }
}

/// The HPM scenario writes the elastic analysis' maps on the ground grid
/// (ESRI ASCII and GeoTIFF), equal to the bit to the library's
/// `HpmResult::maps` for the same model, and no nonlinear maps unless
/// asked.
#[test]
fn hpm_scenario_maps_equal_the_librarys_bit_for_bit() {
    use dismech::hpm::HpmSolver;
    let (summary, out) = run_hpm_variant("yamaguchi_hpm.toml", "", "", "hpm-maps");
    let (grids, model, seismic) = yamaguchi_hpm_model(false);
    let result = HpmSolver::new(&model)
        .unwrap()
        .elastic(&model, &seismic)
        .unwrap();
    let maps = result.maps(&model, &grids).unwrap();
    assert_maps_written(&out, "elastic", &maps, &grids.ground().raster);
    let listed: Vec<&str> = summary["maps"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    assert_eq!(listed.len(), 14, "{listed:?}");
    for name in &listed {
        assert!(out.join(name).is_file(), "{name}");
    }
    // No nonlinear analysis, no `.prj` (the ground grid has none).
    assert!(summary.get("nonlinear").is_none(), "{summary}");
    for entry in std::fs::read_dir(&out).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        assert!(!name.starts_with("nonlinear_"), "{name}");
        assert!(!name.ends_with(".prj"), "{name}");
    }
    std::fs::remove_dir_all(&out).unwrap();
}

/// `driver.nonlinear = true` (yamaguchi_hpm_seismic.toml): the nonlinear
/// analysis' Fs, convergence and maps equal to the bit the library's
/// `HpmSolver::nonlinear` with the default settings on the same model,
/// beside the elastic ones; `tolerance` and `max_iterations` are its
/// settings.
#[test]
fn hpm_nonlinear_scenario_equals_the_library_bit_for_bit() {
    use dismech::hpm::{HpmSolver, NonlinearSettings};
    let (grids, model, seismic) = yamaguchi_hpm_model(true);
    let mut solver = HpmSolver::new(&model).unwrap();
    let elastic = solver.elastic(&model, &seismic).unwrap();
    for (settings, from, to) in [
        (NonlinearSettings::default(), "", ""),
        (
            NonlinearSettings {
                tolerance: 1e-3,
                max_iterations: 4,
            },
            "nonlinear = true",
            "nonlinear = true\ntolerance = 1e-3\nmax_iterations = 4",
        ),
    ] {
        let (summary, out) =
            run_hpm_variant("yamaguchi_hpm_seismic.toml", from, to, "hpm-nonlinear");
        let nl = solver.nonlinear(&model, &seismic, 1.0, &settings).unwrap();
        let got = &summary["nonlinear"];
        assert_eq!(
            bits(&got["safety_factor"]),
            nl.safety_factor(&model).unwrap().to_bits(),
            "{got}"
        );
        assert_eq!(
            bits(&got["sliding_safety_factor"]),
            nl.sliding_safety_factor(&model).unwrap().to_bits(),
            "{got}"
        );
        let status = if nl.convergence.converged() {
            "Converged"
        } else {
            "NotConverged"
        };
        let (iterations, residual) = (nl.convergence.iterations(), nl.convergence.residual());
        assert_eq!(got["status"], status, "{got}");
        assert_eq!(got["iterations"].as_u64(), Some(iterations as u64));
        assert_eq!(bits(&got["residual"]), residual.to_bits());
        assert_eq!(bits(&got["tolerance"]), settings.tolerance.to_bits());
        assert_eq!(
            got["max_iterations"].as_u64(),
            Some(settings.max_iterations as u64)
        );
        // The elastic keys stay those of the elastic analysis.
        assert_eq!(
            bits(&summary["safety_factor"]),
            elastic.safety_factor(&model).unwrap().to_bits()
        );
        assert_eq!(
            bits(&summary["sliding_safety_factor"]),
            elastic.sliding_safety_factor(&model).unwrap().to_bits()
        );
        let ground = &grids.ground().raster;
        assert_maps_written(
            &out,
            "elastic",
            &elastic.maps(&model, &grids).unwrap(),
            ground,
        );
        assert_maps_written(&out, "nonlinear", &nl.maps(&model, &grids).unwrap(), ground);
        assert_eq!(summary["maps"].as_array().unwrap().len(), 28);
        std::fs::remove_dir_all(&out).unwrap();
    }
    // The default run converged; four iterations do not reach 1e-3.
    let default = solver
        .nonlinear(&model, &seismic, 1.0, &NonlinearSettings::default())
        .unwrap();
    assert!(default.convergence.converged());
}

/// A coordinate system beside the ground grid (its `.prj`) is copied
/// beside every ESRI ASCII map and kept inside every GeoTIFF; one a
/// GeoTIFF cannot keep is refused at `bodies[0].ground`.
#[test]
fn hpm_maps_carry_the_ground_grids_coordinate_system() {
    let dir = scratch("hpm-prj");
    std::fs::create_dir_all(&dir).unwrap();
    for name in ["ground.asc", "slip.asc"] {
        std::fs::copy(scenarios().join("yamaguchi_hpm").join(name), dir.join(name)).unwrap();
    }
    let wkt = "PROJCS[\"WGS_1984_UTM_Zone_16N\",GEOGCS[\"GCS_WGS_1984\"]]\n";
    std::fs::write(dir.join("ground.prj"), wkt).unwrap();
    let text = std::fs::read_to_string(scenarios().join("yamaguchi_hpm.toml"))
        .unwrap()
        .replace("yamaguchi_hpm/", "");
    let file = dir.join("model.toml");
    std::fs::write(&file, &text).unwrap();
    let out = dir.join("out");
    let prepared = scenario::load(&file, Overrides::default()).unwrap();
    let finished = scenario::execute(prepared, &file, &out, false).unwrap();
    for name in dismech::hpm::HPM_MAP_NAMES {
        let prj = out.join(format!("elastic_{name}.prj"));
        assert_eq!(std::fs::read_to_string(&prj).unwrap(), wkt, "{prj:?}");
        let tif = std::fs::read(out.join(format!("elastic_{name}.tif"))).unwrap();
        let needle = b"ESRI PE String = PROJCS";
        assert!(tif.windows(needle.len()).any(|w| w == needle), "{name}");
    }
    assert_eq!(finished.summary["maps"].as_array().unwrap().len(), 21);
    std::fs::write(dir.join("ground.prj"), "PROJCS[\"a|b\"]").unwrap();
    match scenario::load(&file, Overrides::default()) {
        Err(ScenarioError::Invalid(located)) => {
            let m = located.to_string();
            assert!(m.contains("`bodies[0].ground`"), "{m}");
            assert!(m.contains("ground.prj"), "{m}");
        }
        Err(e) => panic!("not a placed refusal: {e}"),
        Ok(_) => panic!("a coordinate system a GeoTIFF cannot keep was accepted"),
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The nonlinear analysis' keys: a value of the wrong type or one
/// `NonlinearSettings::validate` refuses, or a setting without
/// `nonlinear = true`, is refused naming the key.
#[test]
fn hpm_nonlinear_keys_are_checked() {
    let refused = |to: &str| -> String {
        let file = scenarios().join("yamaguchi_hpm.toml");
        let text = std::fs::read_to_string(&file).unwrap().replacen(
            "penalty = 100.0",
            &format!("penalty = 100.0\n{to}"),
            1,
        );
        match scenario::prepare(&file, &text, Overrides::default()) {
            Err(ScenarioError::Invalid(located)) => located.to_string(),
            Err(e) => panic!("not a placed refusal: {e}"),
            Ok(_) => panic!("accepted: {to}"),
        }
    };
    let kind = refused("nonlinear = \"yes\"");
    assert!(kind.contains("`driver.nonlinear`"), "{kind}");
    assert!(kind.contains("yamaguchi_hpm.toml:23:13"), "{kind}");
    for (to, key) in [
        (
            "nonlinear = true\ntolerance = 1.5",
            "`driver.tolerance` = 1.5",
        ),
        (
            "nonlinear = true\ntolerance = 0.0",
            "`driver.tolerance` = 0.0",
        ),
        ("nonlinear = true\ntolerance = nan", "`driver.tolerance`"),
        (
            "nonlinear = true\nmax_iterations = 0",
            "`driver.max_iterations` = 0",
        ),
        (
            "nonlinear = true\nmax_iterations = -3",
            "`driver.max_iterations`",
        ),
        (
            "nonlinear = true\nmax_iterations = 1000001",
            "`driver.max_iterations` = 1000001",
        ),
        ("tolerance = 1e-3", "`driver.tolerance`"),
        (
            "nonlinear = false\nmax_iterations = 10",
            "`driver.max_iterations`",
        ),
    ] {
        let m = refused(to);
        assert!(m.contains(key), "{to}: {m}");
        assert!(m.contains("yamaguchi_hpm.toml:"), "{to}: {m}");
    }
    let without = refused("nonlinear = false\nmax_iterations = 10");
    assert!(without.contains("`driver.nonlinear`"), "{without}");
}

/// The cross-composition of ellipses settled by the implicit driver from
/// its file: run for the steps the composition took to rest, the same
/// time, sub-steps, halvings and centres, to the bit, as
/// `compositions::implicit_ellipses::settle` for the default box.
#[test]
fn implicit_ellipses_scenario_equals_the_composition_bit_for_bit() {
    use dismech_cli::compositions::implicit_ellipses::{settle, EllipseBox};
    let summary = run("implicit_ellipses.toml", Overrides::default());
    let settled = settle(&EllipseBox::default()).unwrap();
    assert!(settled.at_rest);
    assert_eq!(summary["steps"].as_u64(), Some(settled.steps as u64));
    assert_eq!(bits(&summary["time"]), settled.time.to_bits());
    assert_eq!(
        summary["outcome"]["substeps"].as_u64(),
        Some(settled.substeps as u64)
    );
    assert_eq!(
        summary["outcome"]["halvings"].as_u64(),
        Some(settled.reductions as u64)
    );
    let bodies = summary["bodies"].as_array().unwrap();
    assert_eq!(bodies.len(), settled.ellipses.len() + 3);
    for (b, (centre, _, _)) in bodies.iter().zip(&settled.ellipses) {
        assert_eq!(bits(&b["centroid"][0]), centre.x.to_bits());
        assert_eq!(bits(&b["centroid"][1]), centre.y.to_bits());
    }
}

/// A prescribed body's motion is the model's: a checkpoint of a run whose
/// plate was driven at another velocity, or whose bump stood elsewhere, is
/// refused, naming the body; the unchanged file resumes.
#[test]
fn a_checkpoint_of_another_prescribed_motion_is_refused() {
    let dir = scratch("resume-prescribed");
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(scenarios().join("dem_incline_and_plate.toml")).unwrap();
    let file = dir.join("model.toml");
    std::fs::write(&file, &text).unwrap();
    run_file(&file, "a", Some(1000), None);
    let ckpt = dir.join("a.checkpoints/step-0000001000.ckpt");
    let edit = |from: &str, to: &str| {
        assert!(text.contains(from), "{from}");
        let edited = dir.join("edited.toml");
        std::fs::write(&edited, text.replacen(from, to, 1)).unwrap();
        edited
    };
    let refused = resume_refusal(
        &edit("velocity = [-0.4, 0.0]", "velocity = [0.4, 0.0]"),
        &ckpt,
        None,
    );
    assert!(
        refused.contains("body 6's prescribed velocity"),
        "{refused}"
    );
    let refused = resume_refusal(
        &edit("centre = [1.15, 0.0]", "centre = [1.2, 0.0]"),
        &ckpt,
        None,
    );
    assert!(refused.contains("body 4's fixed pose"), "{refused}");
    run_file(&file, "b", Some(2000), Some(&ckpt));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The implicit driver's `sine` motion is a function its checkpoint
/// cannot compare: the scenario's checkpoint refuses another amplitude,
/// frequency or direction.
#[test]
fn a_checkpoint_of_another_sine_motion_is_refused() {
    let dir = scratch("resume-sine");
    let file = variant("dda_sliding_block.toml", "checkpoint_every = 10", &dir);
    let text = std::fs::read_to_string(&file).unwrap();
    run_file(&file, "a", Some(20), None);
    let ckpt = dir.join("a.checkpoints/step-0000000020.ckpt");
    for (from, to) in [
        ("frequency = 2.0", "frequency = 3.0"),
        ("amplitude = 0.06863101004005262", "amplitude = 0.07"),
        ("frequency = 2.0", "frequency = 2.0, direction = [0.0, 1.0]"),
    ] {
        assert!(text.contains(from), "{from}");
        let edited = dir.join("edited.toml");
        std::fs::write(&edited, text.replacen(from, to, 1)).unwrap();
        let refused = resume_refusal(&edited, &ckpt, Some(40));
        assert!(refused.contains("bodies' sine motions"), "{to}: {refused}");
    }
    run_file(&file, "b", Some(40), Some(&ckpt));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `driver.slip_reversal_quantile` reaches the implicit driver's settings
/// and is refused outside [0, 1) naming its key.
#[test]
fn the_slip_reversal_quantile_is_read_and_checked() {
    let from = "search_distance = 0.02";
    for bad in ["1.0", "-0.1", "nan"] {
        let message = refusal_of(
            "dda_sliding_block.toml",
            from,
            &format!("{from}\nslip_reversal_quantile = {bad}"),
        );
        assert!(
            message.contains("model.toml:22:") && message.contains("driver.slip_reversal_quantile"),
            "{message}"
        );
    }
    let text = std::fs::read_to_string(scenarios().join("dda_sliding_block.toml")).unwrap();
    let text = text.replacen(from, &format!("{from}\nslip_reversal_quantile = 0.5"), 1);
    let prepared = scenario::prepare(Path::new("model.toml"), &text, Overrides::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let scenario::Model::Implicit(model) = prepared.model else {
        panic!("the sliding block is an implicit model")
    };
    // Not the default (0.2): the file's value.
    assert_eq!(model.settings().slip_reversal_quantile, 0.5);
}
