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
        if summary["driver"] != "limit" {
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
        "model.toml:38:8: `law.kind` = \"katsuk\": unknown variant `katsuk`, expected one of `katsuki`, `spring-dashpot-coulomb`, `penalty-coulomb`, `rigid-plastic`"
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
    ] {
        seeds.push((
            name.to_string(),
            std::fs::read_to_string(scenarios().join(name)).unwrap(),
        ));
    }
    let tally = fuzz::run(&seeds, 1000, 7);
    assert_eq!(tally.files, 3000);
    assert!(tally.panics.is_empty(), "{:?}", tally.panics.first());
    assert!(tally.unnamed.is_empty(), "{:?}", tally.unnamed.first());
    assert!(tally.refused > 2000, "{tally:?}");
    assert!(tally.valid > 0, "{tally:?}");
}
