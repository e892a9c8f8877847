//! `dismech slope --method bishop`: the search by Bishop's simplified
//! method in 3D (Hungr 1987) over the shipped terrain gives the maps and
//! the critical surfaces of the library's search by the same method, bit
//! for bit; summary.json names the method; the lowest Fs lies above
//! Hovland's.

use crate::slope_common;
use slope_common::{scratch, terrain_file};

use std::path::Path;
use std::process::{Command, Output};

use dismech::grid::read_esri_ascii;
use dismech::law::friction_from_degrees;
use dismech::slope::{
    search, BishopSettings, Method, Refusal, SearchResult, SearchSettings, SlopeLoads,
    SlopeMaterial, Sphere, SphereGrid, Steps, Terrain,
};

/// The sphere grid of the runs below.
const FAMILY: [&str; 8] = [
    "--search",
    "spheres",
    "--stride",
    "12",
    "--heights",
    "75:1875:6",
    "--radii",
    "300:2500:10",
];

fn slope(out: &Path, method: &str) -> Output {
    slope_with(out, method, &[])
}

fn slope_with(out: &Path, method: &str, extra: &[&str]) -> Output {
    let dem = terrain_file();
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
        "--out",
        out.to_str().unwrap(),
        "--quiet",
        "--method",
        method,
    ];
    args.extend_from_slice(&FAMILY);
    args.extend_from_slice(extra);
    Command::new(env!("CARGO_BIN_EXE_dismech"))
        .args(&args)
        .output()
        .expect("the dismech binary runs")
}

#[test]
fn method_bishop_is_the_library_search_by_bishop() {
    let dir = scratch("bishop-run");
    let (bishop_out, hovland_out) = (dir.join("bishop"), dir.join("hovland"));
    for (out, method) in [(&bishop_out, "bishop"), (&hovland_out, "hovland")] {
        let run = slope(out, method);
        assert_eq!(
            run.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
    }
    let dem = read_esri_ascii(&terrain_file()).unwrap();
    let terrain = Terrain::new(dismech::hpm::NamedRaster::new("dem", dem), None).unwrap();
    let material = SlopeMaterial {
        cohesion: 20e3,
        friction_coefficient: friction_from_degrees(30.0).unwrap(),
        unit_weight: 20e3,
    };
    let family = SphereGrid::new(
        12,
        Steps::checked("heights", 75.0, 1875.0, 6, false).unwrap(),
        Steps::checked("radii", 300.0, 2500.0, 10, true).unwrap(),
    )
    .unwrap();
    let settings = SearchSettings {
        method: Method::Bishop,
        ..SearchSettings::default()
    };
    let lib = search(
        &terrain,
        &material,
        &SlopeLoads::default(),
        &family,
        &settings,
        |_, _| {},
    )
    .unwrap();
    let bits = |r: &dismech::grid::Raster| -> Vec<Option<u64>> {
        r.values().iter().map(|v| v.map(f64::to_bits)).collect()
    };
    let map = read_esri_ascii(&bishop_out.join("slope_fs.asc")).unwrap();
    assert_eq!(bits(&map), bits(&lib.safety_factor_raster().unwrap()));
    let summary = |out: &Path| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
    };
    let (b, h) = (summary(&bishop_out), summary(&hovland_out));
    assert_eq!(b["method"], "bishop");
    assert_eq!(h["method"], "hovland");
    assert_eq!(b["m_alpha_floor"], 0.2);
    assert!(h["m_alpha_floor"].is_null());
    let csv = std::fs::read_to_string(bishop_out.join("critical.csv")).unwrap();
    let first: Vec<&str> = csv.lines().nth(1).unwrap().split(',').collect();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let fs_at = header.iter().position(|c| *c == "fs").unwrap();
    let lowest = lib.lowest().unwrap();
    assert_eq!(first[1].parse::<u64>().unwrap(), lowest.trial);
    assert_eq!(
        first[fs_at].parse::<f64>().unwrap().to_bits(),
        lowest.result.safety_factor.to_bits()
    );
    let hovland_map = read_esri_ascii(&hovland_out.join("slope_fs.asc")).unwrap();
    let min = |r: &dismech::grid::Raster| {
        r.values()
            .iter()
            .flatten()
            .copied()
            .fold(f64::INFINITY, f64::min)
    };
    println!(
        "lowest Fs over the shipped terrain: Bishop {}, Hovland {}",
        min(&map),
        min(&hovland_map)
    );
    assert!(min(&map) > min(&hovland_map));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--m-alpha-floor 0.05`: the library's search by Bishop's method with
/// that floor, bit for bit (the map); no more trials refused for m_alpha
/// than at the default 0.2, no fewer evaluated, and a lowest Fs no higher; the floor
/// in summary.json. `--m-alpha-floor 0.2` gives the default run's map bit
/// for bit.
#[test]
fn m_alpha_floor_is_the_library_setting() {
    let dir = scratch("bishop-floor");
    let (low, given, default) = (dir.join("low"), dir.join("given"), dir.join("default"));
    for (out, extra) in [
        (&low, &["--m-alpha-floor", "0.05"][..]),
        (&given, &["--m-alpha-floor", "0.2"][..]),
        (&default, &[][..]),
    ] {
        let run = slope_with(out, "bishop", extra);
        assert_eq!(
            run.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
    }
    let dem = read_esri_ascii(&terrain_file()).unwrap();
    let terrain = Terrain::new(dismech::hpm::NamedRaster::new("dem", dem), None).unwrap();
    let material = SlopeMaterial {
        cohesion: 20e3,
        friction_coefficient: friction_from_degrees(30.0).unwrap(),
        unit_weight: 20e3,
    };
    let family = SphereGrid::new(
        12,
        Steps::checked("heights", 75.0, 1875.0, 6, false).unwrap(),
        Steps::checked("radii", 300.0, 2500.0, 10, true).unwrap(),
    )
    .unwrap();
    let run = |bishop: BishopSettings| {
        let settings = SearchSettings {
            method: Method::Bishop,
            bishop,
            ..SearchSettings::default()
        };
        search(
            &terrain,
            &material,
            &SlopeLoads::default(),
            &family,
            &settings,
            |_, _| {},
        )
        .unwrap()
    };
    let lib_low = run(BishopSettings::default().with_m_alpha_floor(0.05).unwrap());
    let lib_default = run(BishopSettings::default());
    let bits = |r: &dismech::grid::Raster| -> Vec<Option<u64>> {
        r.values().iter().map(|v| v.map(f64::to_bits)).collect()
    };
    let map = |out: &Path| read_esri_ascii(&out.join("slope_fs.asc")).unwrap();
    assert_eq!(
        bits(&map(&low)),
        bits(&lib_low.safety_factor_raster().unwrap())
    );
    assert_eq!(bits(&map(&given)), bits(&map(&default)));
    let small = |r: &SearchResult<Sphere>| r.counts.refused_for(Refusal::SmallMAlpha);
    println!(
        "m_alpha refusals: {} at 0.2, {} at 0.05; lowest Fs {} and {}",
        small(&lib_default),
        small(&lib_low),
        lib_default.lowest().unwrap().result.safety_factor,
        lib_low.lowest().unwrap().result.safety_factor
    );
    assert!(small(&lib_low) <= small(&lib_default));
    assert!(lib_low.counts.evaluated >= lib_default.counts.evaluated);
    assert!(
        lib_low.lowest().unwrap().result.safety_factor
            <= lib_default.lowest().unwrap().result.safety_factor
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(low.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["m_alpha_floor"], 0.05);
    std::fs::remove_dir_all(&dir).unwrap();
}
