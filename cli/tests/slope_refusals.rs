//! `dismech slope` refuses, before the search and with exit status 2, what
//! it used to find late or ignore: a `.prj` beside the DEM that the maps
//! cannot carry, `--hpm K` above `--keep`, the HPM options without
//! `--hpm`, and a `--m-alpha-floor` outside (0, 1] or without `--method
//! bishop`; and where no surface gives an Fs over a `--bedrock`, the
//! message names the bedrock as a cause.

use crate::slope_common;
use slope_common::{scratch, terrain_file};

use std::path::Path;
use std::process::{Command, Output};

/// `dismech slope` over `dem` with a small sphere grid and `extra`.
fn slope(dem: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "slope",
        "--dem",
        dem.to_str().unwrap(),
        "--cohesion",
        "20e3",
        "--friction-angle",
        "30",
        "--unit-weight",
        "20e3",
        "--search",
        "spheres",
        "--stride",
        "25",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ];
    args.extend_from_slice(extra);
    Command::new(env!("CARGO_BIN_EXE_dismech"))
        .args(&args)
        .output()
        .expect("the dismech binary runs")
}

fn refused(run: &Output, needles: &[&str]) -> String {
    let stderr = String::from_utf8_lossy(&run.stderr).into_owned();
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    for needle in needles {
        assert!(stderr.contains(needle), "`{needle}` in {stderr}");
    }
    assert!(!stderr.contains("panicked"), "{stderr}");
    stderr
}

/// A `.prj` that a GeoTIFF map cannot keep (a `|`, or bytes that are not
/// text) is refused naming `--dem` and the `.prj`, before the search: with
/// spheres that all leave the DEM, the search would end in "no trial
/// surface gave a factor of safety", and that message does not come.
#[test]
fn a_bad_prj_is_refused_before_the_search() {
    let dir = scratch("refusals-prj");
    let dem = dir.join("dem.asc");
    std::fs::copy(terrain_file(), &dem).unwrap();
    let prj = dir.join("dem.prj");
    let every_sphere_leaves = ["--radii", "20000:30000:2", "--heights", "0:10:2"];
    for (bytes, needle) in [
        (&b"PROJCS[\"a|b\"]"[..], "'|'"),
        (&b"PROJCS[\"\xff\xfe\"]"[..], "cannot be read as text"),
    ] {
        std::fs::write(&prj, bytes).unwrap();
        let out = dir.join("out");
        let run = slope(&dem, &out, &every_sphere_leaves);
        let stderr = refused(
            &run,
            &[&format!("--dem {}", dem.display()), "dem.prj", needle],
        );
        assert!(!stderr.contains("no trial surface"), "{stderr}");
        assert!(!out.exists());
    }
    // A good one passes, and the search then runs.
    std::fs::write(&prj, "PROJCS[\"ok\"]").unwrap();
    let run = slope(&dem, &dir.join("out"), &every_sphere_leaves);
    refused(&run, &["no trial surface gave a factor of safety"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// With a bedrock at the ground no surface has a column: the message names
/// `--bedrock` and its file as the cause; without `--bedrock` it does not
/// mention one.
#[test]
fn no_surface_over_a_bedrock_names_the_bedrock() {
    let dir = scratch("refusals-bedrock");
    let rock = dir.join("rock.asc");
    std::fs::copy(terrain_file(), &rock).unwrap();
    let run = slope(
        &terrain_file(),
        &dir.join("out"),
        &["--bedrock", rock.to_str().unwrap()],
    );
    refused(
        &run,
        &[
            "no trial surface gave a factor of safety",
            &format!("the bedrock --bedrock {}", rock.display()),
        ],
    );
    let run = slope(
        &terrain_file(),
        &dir.join("out"),
        &["--radii", "20000:30000:2", "--heights", "0:10:2"],
    );
    let stderr = refused(&run, &["no trial surface gave a factor of safety"]);
    assert!(!stderr.contains("bedrock"), "{stderr}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--hpm K` above `--keep` is refused naming both values (it used to be
/// cut to --keep silently); `--hpm` equal to `--keep` is not refused by
/// this check.
#[test]
fn hpm_above_keep_is_refused_naming_both() {
    let dir = scratch("refusals-keep");
    let run = slope(
        &terrain_file(),
        &dir.join("out"),
        &["--hpm", "3", "--keep", "2"],
    );
    refused(&run, &["--hpm 3", "--keep 2", "critical.csv"]);
    let run = slope(&terrain_file(), &dir.join("out"), &["--hpm", "12"]);
    refused(&run, &["--hpm 12", "--keep 10"]);
    assert!(!dir.join("out").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--youngs-modulus` and `--poisson-ratio` without `--hpm` are refused by
/// the parser naming the flag and `--hpm` (they used to be ignored).
#[test]
fn hpm_moduli_without_hpm_are_refused() {
    let dir = scratch("refusals-moduli");
    for (flag, value) in [("--youngs-modulus", "5e8"), ("--poisson-ratio", "0.3")] {
        let run = slope(&terrain_file(), &dir.join("out"), &[flag, value]);
        refused(&run, &[flag, "--hpm <K>"]);
    }
    assert!(!dir.join("out").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--hpm 0` re-analyses nothing, so the HPM options beside it would be
/// ignored as they are without `--hpm`: it is refused by the parser,
/// naming the value, the HPM options it would leave unused and saying to
/// leave `--hpm` out; alone, with the moduli given explicitly, or with
/// `--hpm-nonlinear`.
#[test]
fn hpm_zero_is_refused_and_does_not_let_the_hpm_options_through() {
    let dir = scratch("refusals-zero");
    for extra in [
        &["--hpm", "0"][..],
        &["--hpm", "0", "--youngs-modulus", "5e8"][..],
        &["--hpm", "0", "--poisson-ratio", "0.3"][..],
        &[
            "--hpm",
            "0",
            "--youngs-modulus",
            "5e8",
            "--poisson-ratio",
            "0.3",
        ][..],
        &["--hpm", "0", "--hpm-nonlinear"][..],
    ] {
        let run = slope(&terrain_file(), &dir.join("out"), extra);
        refused(
            &run,
            &[
                "--hpm",
                "`0`",
                "leave --hpm out",
                "--youngs-modulus",
                "--poisson-ratio",
                "--hpm-nonlinear",
            ],
        );
    }
    assert!(!dir.join("out").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--m-alpha-floor` outside (0, 1], or not a number, is refused by the
/// parser naming the flag, the value and the range; a valid floor with
/// Hovland's method (the default, or given) is refused naming the flag
/// and `--method bishop`, as it would be ignored.
#[test]
fn m_alpha_floor_out_of_range_or_without_bishop_is_refused() {
    let dir = scratch("refusals-m-alpha");
    for bad in ["0", "-0.1", "1.5", "inf"] {
        let run = slope(
            &terrain_file(),
            &dir.join("out"),
            &["--method", "bishop", "--m-alpha-floor", bad],
        );
        refused(&run, &["--m-alpha-floor", bad, "m_alpha floor", "(0, 1]"]);
    }
    for bad in ["nan", "x"] {
        let run = slope(
            &terrain_file(),
            &dir.join("out"),
            &["--method", "bishop", "--m-alpha-floor", bad],
        );
        refused(&run, &["--m-alpha-floor", bad]);
    }
    for extra in [
        &["--m-alpha-floor", "0.1"][..],
        &["--method", "hovland", "--m-alpha-floor", "0.1"][..],
    ] {
        let run = slope(&terrain_file(), &dir.join("out"), extra);
        refused(&run, &["--m-alpha-floor 0.1", "--method bishop"]);
    }
    assert!(!dir.join("out").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
