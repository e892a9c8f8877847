//! `dismech slope` as a user runs it, on the terrain shipped in
//! examples/data/terrain (SRTM heights around the Jacksboro fault,
//! Tennessee): the outputs agree with each other and with the same search
//! made through the library, bit for bit; bad input is refused with the
//! option and the value at fault and the exit status of bad input, and
//! leaves the output folder as it was.

use crate::slope_common;
use slope_common::{scratch, terrain_file};

use std::path::Path;
use std::process::{Command, Output};

use dismech::grid::{read_esri_ascii, read_raster, Raster};
use dismech::law::friction_from_degrees;
use dismech::slope::{
    search, EllipsoidRandom, SearchSettings, SlopeLoads, SlopeMaterial, SphereGrid, Steps,
    SurfaceLimits, Terrain, TrialFamily,
};

fn dismech(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_dismech"))
        .args(args)
        .output()
        .expect("the dismech binary runs")
}

/// The material of every run here.
const COHESION: &str = "20e3";
const FRICTION_DEG: &str = "30";
const UNIT_WEIGHT: &str = "20e3";

fn material() -> SlopeMaterial {
    SlopeMaterial {
        cohesion: 20e3,
        friction_coefficient: friction_from_degrees(30.0).unwrap(),
        unit_weight: 20e3,
    }
}

/// `dismech slope` on the shipped terrain with the material above and
/// `extra` options, into `out`.
fn slope(out: &Path, extra: &[&str]) -> Output {
    let dem = terrain_file();
    let mut args = vec![
        "slope",
        "--dem",
        dem.to_str().unwrap(),
        "--cohesion",
        COHESION,
        "--friction-angle",
        FRICTION_DEG,
        "--unit-weight",
        UNIT_WEIGHT,
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ];
    args.extend_from_slice(extra);
    dismech(&args)
}

/// The numbers of an ESRI ASCII grid's header, read from its text.
fn header(path: &Path) -> Vec<(String, f64)> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .take(5)
        .map(|line| {
            let mut words = line.split_whitespace();
            let key = words.next().unwrap().to_ascii_lowercase();
            (key, words.next().unwrap().parse().unwrap())
        })
        .collect()
}

/// The `fs` column of the CSV of the critical surfaces, and its trials.
fn critical_fs(path: &Path) -> Vec<(u64, f64)> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let fs = head.iter().position(|h| *h == "fs").unwrap();
    let trial = head.iter().position(|h| *h == "trial").unwrap();
    lines
        .map(|l| {
            let cells: Vec<&str> = l.split(',').collect();
            (cells[trial].parse().unwrap(), cells[fs].parse().unwrap())
        })
        .collect()
}

fn raster_min(raster: &Raster) -> f64 {
    raster
        .values()
        .iter()
        .flatten()
        .copied()
        .reduce(f64::min)
        .unwrap()
}

/// The outputs of a run agree with each other and with the library's
/// search of the same family.
/// `gdalinfo -json` of a GeoTIFF map: its size and geotransform are the
/// DEM's (`header`: ncols, nrows, xllcorner, yllcorner, cellsize; the
/// geotransform's origin is the upper-left corner). Fails without GDAL's
/// tools (`.ci/run` installs `gdal-bin`).
fn check_geotiff_grid(tif: &Path, header: &[(String, f64)]) {
    let value = |key: &str| header.iter().find(|(k, _)| k == key).unwrap().1;
    let out = Command::new("gdalinfo")
        .arg("-json")
        .arg(tif)
        .output()
        .expect("gdalinfo runs (install GDAL's tools: apt-get install gdal-bin)");
    assert!(
        out.status.success(),
        "gdalinfo {tif:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // The DEM's coordinate system (its `.prj`), as GDAL reads it beside
    // the DEM, is the GeoTIFF's.
    let dem = Command::new("gdalinfo")
        .arg("-json")
        .arg(terrain_file())
        .output()
        .unwrap();
    let dem: serde_json::Value = serde_json::from_slice(&dem.stdout).unwrap();
    let crs = |v: &serde_json::Value| v["coordinateSystem"]["wkt"].as_str().unwrap().to_string();
    assert!(crs(&dem).contains("UTM zone 16N"), "{}", crs(&dem));
    assert_eq!(crs(&json), crs(&dem), "{tif:?}");
    let size: Vec<f64> = json["size"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(size, [value("ncols"), value("nrows")], "{tif:?}");
    let transform: Vec<f64> = json["geoTransform"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let cell = value("cellsize");
    let top = value("yllcorner") + value("nrows") * cell;
    assert_eq!(
        transform,
        [value("xllcorner"), cell, 0.0, top, 0.0, -cell],
        "{tif:?}"
    );
}

fn check_run<F: TrialFamily>(out: &Path, family: &F, keep: usize) {
    let dem_path = terrain_file();
    // The rasters lie on the DEM's grid, as their headers say.
    let dem_header = header(&dem_path);
    for name in ["fs", "volume", "area", "depth"] {
        let path = out.join(format!("slope_{name}.asc"));
        let got = header(&path);
        let keys: Vec<&str> = got.iter().map(|(k, _)| k.as_str()).collect();
        assert_eq!(
            keys,
            ["ncols", "nrows", "xllcorner", "yllcorner", "cellsize"],
            "{path:?}"
        );
        assert_eq!(got, dem_header, "{path:?}");
        // The DEM's coordinate system beside each raster.
        assert_eq!(
            std::fs::read(path.with_extension("prj")).unwrap(),
            std::fs::read(dem_path.with_extension("prj")).unwrap()
        );
        // The same map as GeoTIFF: GDAL reads the DEM's grid from it, and
        // its values are the ESRI grid's to the bit.
        let tif = path.with_extension("tif");
        check_geotiff_grid(&tif, &dem_header);
        let (from_tif, from_asc) = (read_raster(&tif).unwrap(), read_esri_ascii(&path).unwrap());
        assert!(from_tif.same_grid(&from_asc), "{tif:?}");
        let bits = |r: &Raster| -> Vec<Option<u64>> {
            r.values().iter().map(|v| v.map(f64::to_bits)).collect()
        };
        assert_eq!(bits(&from_tif), bits(&from_asc), "{tif:?}");
    }
    let fs_map = read_esri_ascii(&out.join("slope_fs.asc")).unwrap();
    let critical = critical_fs(&out.join("critical.csv"));
    assert_eq!(critical.len(), keep);
    assert!(critical.windows(2).all(|w| w[0].1 <= w[1].1));
    let lowest = critical[0].1;
    assert_eq!(lowest.to_bits(), raster_min(&fs_map).to_bits());

    // The same search through the library: the same map, bit for bit.
    let terrain = Terrain::read(&dem_path, None).unwrap();
    let settings = SearchSettings {
        limits: SurfaceLimits::default(),
        critical: keep,
        ..SearchSettings::default()
    };
    let result = search(
        &terrain,
        &material(),
        &SlopeLoads::default(),
        family,
        &settings,
        |_, _| {},
    )
    .unwrap();
    assert_eq!(
        result.lowest_safety_factor().unwrap().to_bits(),
        lowest.to_bits()
    );
    assert_eq!(result.critical[0].trial, critical[0].0);
    let library_map = result.safety_factor_raster().unwrap();
    assert_eq!(library_map.values().len(), fs_map.values().len());
    for (a, b) in library_map.values().iter().zip(fs_map.values()) {
        assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits));
    }
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["trials"], result.counts.trials);
    assert_eq!(summary["evaluated"], result.counts.evaluated);
    assert_eq!(
        summary["lowest"]["fs"].as_f64().unwrap().to_bits(),
        lowest.to_bits()
    );

    // The map: XML, the cells as an embedded PNG, the legend, the outline.
    let svg = std::fs::read_to_string(out.join("map.svg")).unwrap();
    let doc = roxmltree::Document::parse(&svg).expect("the map is well-formed XML");
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    let image = doc
        .descendants()
        .find(|n| n.has_tag_name("image"))
        .expect("the cells' picture");
    let href = image.attribute("href").unwrap();
    assert!(href.starts_with("data:image/png;base64,"));
    let texts: Vec<String> = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .map(|n| n.text().unwrap_or("").trim().to_string())
        .collect();
    for label in [
        "lowest Fs per cell",
        "Fs < 1.0",
        "1.0 ≤ Fs < 1.2",
        "Fs ≥ 3.0",
        "no trial surface",
    ] {
        assert!(texts.iter().any(|t| t == label), "{label} in {texts:?}");
    }
    let outline = format!("critical surface, Fs = {lowest:.3}");
    assert!(texts.contains(&outline), "{outline} in {texts:?}");
    assert!(doc.descendants().any(|n| n.has_tag_name("polyline")));
}

#[test]
fn random_ellipsoids_over_the_shipped_terrain_agree_with_the_library() {
    let out = scratch("ellipsoids").join("run");
    let run = slope(
        &out,
        &[
            "--search",
            "ellipsoids",
            "--count",
            "20000",
            "--seed",
            "7",
            "--heights",
            "0:187.5",
            "--along",
            "300:1875",
            "--across-ratio",
            "0.5:1",
            "--vertical",
            "75:375",
            "--keep",
            "5",
            "--threads",
            "2",
        ],
    );
    let stdout = String::from_utf8_lossy(&run.stdout);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(0), "{stdout}\n{stderr}");
    assert!(
        stdout.contains("lowest Fs ") && stdout.contains("trials 20000: "),
        "{stdout}"
    );
    let family = EllipsoidRandom::new(
        20_000,
        7,
        (0.0, 187.5),
        (300.0, 1875.0),
        (0.5, 1.0),
        (75.0, 375.0),
    )
    .unwrap();
    check_run(&out, &family, 5);
    std::fs::remove_dir_all(out.parent().unwrap()).unwrap();
}

/// Without family options the sphere grid comes from the DEM's extent
/// (100 × 100 cells of 75 m): a centre every 4 cells, heights 75 to
/// 1875 m, radii 300 to 2500 m.
#[test]
fn the_default_sphere_grid_over_the_shipped_terrain_agrees_with_the_library() {
    let out = scratch("spheres").join("run");
    let run = slope(&out, &["--search", "spheres"]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(0), "{stderr}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(
        summary["family"],
        "--search spheres --stride 4 --heights 75:1875:6 --radii 300:2500:10"
    );
    let family = SphereGrid::new(
        4,
        Steps::checked("heights", 75.0, 1875.0, 6, false).unwrap(),
        Steps::checked("radii", 300.0, 2500.0, 10, true).unwrap(),
    )
    .unwrap();
    check_run(&out, &family, 10);
    std::fs::remove_dir_all(out.parent().unwrap()).unwrap();
}

/// A water table and a seismic coefficient reach the search: the map
/// equals the library's with the same pore pressure and k_h, bit for bit,
/// and its lowest Fs lies below the dry, static one.
#[test]
fn a_water_table_and_k_h_are_those_of_the_library_search() {
    let dir = scratch("water");
    let dem = read_esri_ascii(&terrain_file()).unwrap();
    // The water table 20 m below the ground everywhere.
    let values = dem.values().iter().map(|v| v.map(|z| z - 20.0)).collect();
    let (x0, y0) = dem.lower_left();
    let water = Raster::new(dem.columns(), dem.rows(), x0, y0, dem.cell_size(), values).unwrap();
    let water_path = dir.join("water.asc");
    dismech::grid::write_esri_ascii(&water_path, &water).unwrap();
    let out = dir.join("run");
    let run = slope(
        &out,
        &[
            "--water",
            water_path.to_str().unwrap(),
            "--kh",
            "0.1",
            "--search",
            "ellipsoids",
            "--count",
            "5000",
            "--seed",
            "11",
        ],
    );
    assert_eq!(
        run.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let fs_map = read_esri_ascii(&out.join("slope_fs.asc")).unwrap();
    // The defaults of this DEM (100 × 100 cells of 75 m).
    let family = EllipsoidRandom::new(
        5_000,
        11,
        (0.0, 187.5),
        (300.0, 1875.0),
        (0.5, 1.0),
        (75.0, 375.0),
    )
    .unwrap();
    let wet = Terrain::new(
        dismech::hpm::NamedRaster::new("dem", dem.clone()),
        Some(dismech::hpm::NamedRaster::new("water", water)),
    )
    .unwrap();
    let loads = SlopeLoads {
        seismic_coefficient: 0.1,
        ..SlopeLoads::default()
    };
    let settings = SearchSettings::default();
    let result = search(&wet, &material(), &loads, &family, &settings, |_, _| {}).unwrap();
    let library_map = result.safety_factor_raster().unwrap();
    for (a, b) in library_map.values().iter().zip(fs_map.values()) {
        assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits));
    }
    let dry = Terrain::new(dismech::hpm::NamedRaster::new("dem", dem), None).unwrap();
    let dry = search(
        &dry,
        &material(),
        &SlopeLoads::default(),
        &family,
        &settings,
        |_, _| {},
    )
    .unwrap();
    let (wet_fs, dry_fs) = (
        result.lowest_safety_factor().unwrap(),
        dry.lowest_safety_factor().unwrap(),
    );
    assert!(wet_fs < dry_fs, "wet {wet_fs} against dry {dry_fs}");
    assert_eq!(raster_min(&fs_map).to_bits(), wet_fs.to_bits());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Bad input: the option and the value in the message, exit status 2
/// (bad input) or 6 (an output that cannot be written), no panic, and the
/// previous output folder untouched.
#[test]
fn bad_input_names_the_option_and_leaves_the_folder_as_it_was() {
    let dir = scratch("refusals");
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    // A folder of the user's own files is not an earlier run's: refused
    // whole (exit 6), not replaced.
    std::fs::write(out.join("previous.txt"), "kept").unwrap();
    let foreign = slope(&out, &["--search", "spheres", "--stride", "25"]);
    assert_eq!(foreign.status.code(), Some(6));
    assert!(
        String::from_utf8_lossy(&foreign.stderr).contains("no summary.json"),
        "{}",
        String::from_utf8_lossy(&foreign.stderr)
    );
    assert_eq!(
        std::fs::read_to_string(out.join("previous.txt")).unwrap(),
        "kept"
    );
    // An earlier run's folder (it has its summary) is kept by every
    // refusal below and replaced by the run that succeeds.
    std::fs::write(out.join("summary.json"), "{}").unwrap();
    let malformed = dir.join("malformed.asc");
    std::fs::write(
        &malformed,
        "ncols 3\nnrows two\nxllcorner 0\nyllcorner 0\ncellsize 75\n1 2 3\n",
    )
    .unwrap();
    let small = dir.join("small.asc");
    std::fs::write(
        &small,
        "ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 75\n1 2 3\n4 5 6\n7 8 9\n",
    )
    .unwrap();
    let missing = dir.join("missing.asc");
    let a_file = dir.join("a_file");
    std::fs::write(&a_file, "mine").unwrap();
    let dem = terrain_file();
    let dem = dem.to_str().unwrap();
    let material = [
        "--cohesion",
        COHESION,
        "--friction-angle",
        FRICTION_DEG,
        "--unit-weight",
        UNIT_WEIGHT,
    ];
    let o = out.to_str().unwrap();
    let cases: Vec<(Vec<&str>, i32, Vec<String>)> = vec![
        (
            vec!["--dem", missing.to_str().unwrap(), "--search", "spheres"],
            2,
            vec![format!("--dem {}", missing.display())],
        ),
        (
            vec!["--dem", malformed.to_str().unwrap(), "--search", "spheres"],
            2,
            vec![
                format!("--dem {}", malformed.display()),
                "nrows".into(),
                "two".into(),
            ],
        ),
        (
            vec![
                "--dem",
                dem,
                "--water",
                small.to_str().unwrap(),
                "--search",
                "spheres",
            ],
            2,
            vec![format!("--water {}", small.display())],
        ),
        (
            vec!["--dem", dem, "--search", "spheres", "--stride", "1000"],
            2,
            vec!["--stride 1000".into(), "no sphere centre".into()],
        ),
        (
            vec!["--dem", dem, "--search", "ellipsoids", "--radii", "10:20"],
            2,
            vec!["--radii 10:20: not an option of --search ellipsoids".into()],
        ),
        // Every sphere of this grid is wider than the DEM.
        (
            vec![
                "--dem",
                dem,
                "--search",
                "spheres",
                "--radii",
                "20000:30000:2",
                "--heights",
                "0:10:2",
            ],
            2,
            vec![
                "no trial surface gave a factor of safety".into(),
                "leave the DEM".into(),
                "--radii 20000:30000:2".into(),
            ],
        ),
        (
            vec!["--dem", dem, "--search", "spheres", "--radii", "500:100"],
            2,
            vec![
                "--radii <MIN:MAX[:COUNT]>".into(),
                "MIN 500 lies above MAX 100".into(),
            ],
        ),
        (
            vec!["--dem", dem, "--search", "cubes"],
            2,
            vec!["--search <SEARCH>".into(), "cubes".into()],
        ),
    ];
    for (extra, code, needles) in cases {
        let mut args = vec!["slope", "--out", o, "--quiet"];
        args.extend_from_slice(&material);
        args.extend_from_slice(&extra);
        let run = dismech(&args);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(code), "{extra:?}: {stderr}");
        for needle in &needles {
            assert!(
                stderr.contains(needle.as_str()),
                "{extra:?}: `{needle}` in {stderr}"
            );
        }
        assert!(!stderr.contains("panicked"), "{stderr}");
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        assert!(!names.iter().any(|n| n.starts_with(".out.")), "{names:?}");
        assert_eq!(
            std::fs::read_dir(&out).unwrap().count(),
            2,
            "{extra:?} touched the folder"
        );
        assert_eq!(
            std::fs::read_to_string(out.join("previous.txt")).unwrap(),
            "kept"
        );
    }

    // Material values out of range, refused by the parser.
    for (flag, value, needle) in [
        ("--cohesion", "-5", "invalid cohesion c' (Pa) = -5"),
        ("--friction-angle", "95", "must lie in [0, 90)"),
        ("--unit-weight", "0", "invalid unit weight gamma (N/m3) = 0"),
        ("--kh", "-0.1", "invalid seismic coefficient k_h = -0.1"),
    ] {
        let mut args = vec![
            "slope", "--out", o, "--quiet", "--dem", dem, "--search", "spheres",
        ];
        let mut given = material.to_vec();
        match given.iter().position(|a| *a == flag) {
            Some(i) => given[i + 1] = value,
            None => given.extend([flag, value]),
        }
        args.extend_from_slice(&given);
        let run = dismech(&args);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{flag} {value}: {stderr}");
        assert!(
            stderr.contains(&format!("'{value}' for '{flag} ")),
            "{stderr}"
        );
        assert!(stderr.contains(needle), "{stderr}");
    }
    // No strength at all: c' = 0 and φ' = 0 together.
    let run = dismech(&[
        "slope",
        "--out",
        o,
        "--quiet",
        "--dem",
        dem,
        "--search",
        "spheres",
        "--cohesion",
        "0",
        "--friction-angle",
        "0",
        "--unit-weight",
        "2e4",
    ]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("--cohesion 0: ") && stderr.contains("no strength"),
        "{stderr}"
    );

    // An output folder that is a file: refused before the search (exit 6),
    // the file kept.
    let mut args = vec!["slope", "--out", a_file.to_str().unwrap(), "--quiet"];
    args.extend_from_slice(&material);
    args.extend_from_slice(&["--dem", dem, "--search", "spheres"]);
    let run = dismech(&args);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(6), "{stderr}");
    assert!(stderr.contains("is not a folder"), "{stderr}");
    assert_eq!(std::fs::read_to_string(&a_file).unwrap(), "mine");

    // A run that succeeds replaces the folder whole.
    let run = slope(&out, &["--search", "spheres", "--stride", "25"]);
    assert_eq!(
        run.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(!out.join("previous.txt").exists());
    assert!(out.join("map.svg").is_file());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The defaults of the shipped DEM's random ellipsoids (100 × 100 cells of
/// 75 m), 5000 trials, seed 11.
fn ellipsoids_5000() -> EllipsoidRandom {
    EllipsoidRandom::new(
        5_000,
        11,
        (0.0, 187.5),
        (300.0, 1875.0),
        (0.5, 1.0),
        (75.0, 375.0),
    )
    .unwrap()
}

/// `dismech slope` with `extra`, then the Fs map it wrote.
fn fs_map_of(out: &Path, extra: &[&str]) -> Raster {
    let mut args = vec!["--search", "ellipsoids", "--count", "5000", "--seed", "11"];
    args.extend_from_slice(extra);
    let run = slope(out, &args);
    assert_eq!(
        run.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    read_esri_ascii(&out.join("slope_fs.asc")).unwrap()
}

fn bits(r: &Raster) -> Vec<Option<u64>> {
    r.values().iter().map(|v| v.map(f64::to_bits)).collect()
}

/// Two layers (`--layer`) and r_u (`--ru`): the maps of the library's
/// search on the same ground bit for bit; a weak upper layer 40 m thick
/// changes the map and the lowest Fs; an upper layer whose bottom lies
/// below every trial surface gives the one-layer run of its own material
/// bit for bit (every base lies in it: σ_v = γ₁ (g − z_b), the same
/// operations); --ru 0 is dry; --ru with --water, and bad layers, are
/// refused naming the option and the value.
#[test]
fn layers_and_ru_are_those_of_the_library_search() {
    use dismech::hpm::NamedRaster;
    use dismech::slope::{Ground, Layer, PoreRatio};
    let dir = scratch("layers");
    let dem = read_esri_ascii(&terrain_file()).unwrap();
    let (x0, y0) = dem.lower_left();
    let shifted = |dz: f64, name: &str| {
        let values = dem.values().iter().map(|v| v.map(|z| z - dz)).collect();
        let r = Raster::new(dem.columns(), dem.rows(), x0, y0, dem.cell_size(), values).unwrap();
        let path = dir.join(name);
        dismech::grid::write_esri_ascii(&path, &r).unwrap();
        (path, r)
    };
    let (shallow_path, shallow) = shifted(40.0, "colluvium.asc");
    let (deep_path, _) = shifted(5000.0, "deep.asc");
    let weak = SlopeMaterial {
        cohesion: 5e3,
        friction_coefficient: friction_from_degrees(22.0).unwrap(),
        unit_weight: 18e3,
    };
    let terrain = Terrain::new(NamedRaster::new("dem", dem.clone()), None).unwrap();
    let family = ellipsoids_5000();
    let settings = SearchSettings::default();
    let lib = |ground: &Ground| {
        search(
            &terrain,
            ground,
            &SlopeLoads::default(),
            &family,
            &settings,
            |_, _| {},
        )
        .unwrap()
    };

    let one = fs_map_of(&dir.join("one"), &[]);
    let layer_arg = format!("colluvium:{}:5e3:22:18e3", shallow_path.display());
    let two = fs_map_of(&dir.join("two"), &["--layer", &layer_arg]);
    let ground = Ground::layered(vec![
        Layer {
            name: "colluvium".into(),
            bottom: Some(NamedRaster::new("colluvium.asc", shallow)),
            material: weak,
        },
        Layer {
            name: "base".into(),
            bottom: None,
            material: material(),
        },
    ])
    .unwrap();
    let layered = lib(&ground);
    assert_eq!(bits(&two), bits(&layered.safety_factor_raster().unwrap()));
    let differing = one
        .values()
        .iter()
        .zip(two.values())
        .filter(|(a, b)| a.map(f64::to_bits) != b.map(f64::to_bits))
        .count();
    assert!(differing > 1000, "{differing} cells differ");
    let (fs_one, fs_two) = (raster_min(&one), raster_min(&two));
    assert!(fs_two < fs_one - 0.05, "two layers {fs_two}, one {fs_one}");
    println!("lowest Fs: one layer {fs_one}, two layers {fs_two}; {differing} cells differ");

    // An upper layer below every surface: its material alone.
    let deep_arg = format!("all:{}:5e3:22:18e3", deep_path.display());
    let deep = fs_map_of(&dir.join("deep"), &["--layer", &deep_arg]);
    let alone = search(
        &terrain,
        &weak,
        &SlopeLoads::default(),
        &family,
        &settings,
        |_, _| {},
    )
    .unwrap();
    assert_eq!(bits(&deep), bits(&alone.safety_factor_raster().unwrap()));

    // r_u: 0 is dry, 0.25 is the library's.
    assert_eq!(
        bits(&fs_map_of(&dir.join("ru0"), &["--ru", "0"])),
        bits(&one)
    );
    let ru = fs_map_of(&dir.join("ru"), &["--ru", "0.25", "--layer", &layer_arg]);
    let wet = lib(&ground
        .clone()
        .with_pore_ratio(PoreRatio::Constant(0.25))
        .unwrap());
    assert_eq!(bits(&ru), bits(&wet.safety_factor_raster().unwrap()));
    assert!(raster_min(&ru) < fs_two);

    // Refusals: exit status 2, the option and the value named.
    let (water_path, _) = shifted(20.0, "water.asc");
    let out = dir.join("refused");
    for (extra, words) in [
        (
            vec!["--ru", "0.2", "--water", water_path.to_str().unwrap()],
            vec!["--ru", "--water"],
        ),
        (vec!["--ru", "1"], vec!["--ru", "r_u = 1"]),
        (
            vec!["--layer", "sand:x.asc:5e3:95:18e3"],
            vec!["--layer", "sand", "95"],
        ),
        (
            vec!["--layer", "sand:5e3:18e3"],
            vec!["--layer", "NAME:BOTTOM"],
        ),
        (
            vec!["--layer", "sand:missing.asc:5e3:30:18e3"],
            vec!["--layer", "missing.asc"],
        ),
    ] {
        let mut args = vec!["--search", "spheres"];
        args.extend_from_slice(&extra);
        let run = slope(&out, &args);
        let err = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{extra:?}: {err}");
        for w in words {
            assert!(err.contains(w), "{extra:?}: `{w}` not in {err}");
        }
        assert!(!err.contains("panicked"), "{err}");
        assert!(!out.exists());
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--hpm 2 --hpm-nonlinear`: the two most critical surfaces re-analysed by
/// HPM. The slip surface written (`hpm_slip.asc`) is the library's raster
/// of the library search's most critical surface bit for bit; HPM run
/// directly on it and the DEM, read from their files, gives the Fs of
/// summary.json and critical.csv and the maps `hpm_*.asc` bit for bit;
/// the third surface, not re-analysed, has empty HPM columns.
#[test]
fn hpm_reanalysis_of_the_worst_surfaces_is_a_direct_hpm_run() {
    use dismech::hpm::{
        HpmMaterial, HpmModel, HpmSettings, HpmSolver, NonlinearSettings, Seismic, SlopeGrids,
    };
    let dir = scratch("hpm");
    let out = dir.join("run");
    let mut args = vec!["--search", "ellipsoids", "--count", "5000", "--seed", "11"];
    args.extend_from_slice(&["--keep", "3", "--hpm", "2", "--hpm-nonlinear"]);
    let run = slope(&out, &args);
    assert_eq!(
        run.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let dem = read_esri_ascii(&terrain_file()).unwrap();
    let terrain = Terrain::new(dismech::hpm::NamedRaster::new("dem", dem), None).unwrap();
    let lib = search(
        &terrain,
        &material(),
        &SlopeLoads::default(),
        &ellipsoids_5000(),
        &SearchSettings::default(),
        |_, _| {},
    )
    .unwrap();
    let worst = lib.lowest().unwrap();
    let slip = read_esri_ascii(&out.join("hpm_slip.asc")).unwrap();
    let expected = dismech::slope::surface_raster(&terrain, &worst.surface).unwrap();
    assert_eq!(bits(&slip), bits(&expected));

    let grids = SlopeGrids::read(&terrain_file(), &out.join("hpm_slip.asc"), None).unwrap();
    let hpm_material = HpmMaterial {
        cohesion: 20e3,
        friction_coefficient: friction_from_degrees(30.0).unwrap(),
        unit_weight: 20e3,
        submerged_unit_weight: 20e3 - 9810.0,
        ..HpmMaterial::paper()
    };
    let model = HpmModel::new(&grids, &hpm_material, &HpmSettings::default()).unwrap();
    let mut solver = HpmSolver::new(&model).unwrap();
    let seismic = Seismic {
        coefficient: 0.0,
        direction: worst.result.direction,
    };
    let elastic = solver.elastic(&model, &seismic).unwrap();
    let plastic = solver
        .nonlinear(&model, &seismic, 1.0, &NonlinearSettings::default())
        .unwrap();
    let elastic_fs = elastic.sliding_safety_factor(&model).unwrap();
    let plastic_fs = plastic.sliding_safety_factor(&model).unwrap();

    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let first = &summary["hpm"]["results"][0];
    assert_eq!(first["trial"], worst.trial);
    assert_eq!(first["columns"], model.columns.len());
    assert_eq!(
        first["elastic"]["fs"].as_f64().unwrap().to_bits(),
        elastic_fs.to_bits()
    );
    assert_eq!(
        first["nonlinear"]["fs"].as_f64().unwrap().to_bits(),
        plastic_fs.to_bits()
    );
    assert_eq!(
        first["hovland_fs"].as_f64().unwrap().to_bits(),
        worst.result.safety_factor.to_bits()
    );
    assert_eq!(summary["hpm"]["results"].as_array().unwrap().len(), 2);

    let csv = std::fs::read_to_string(out.join("critical.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
    let column = |name: &str| rows[0].iter().position(|h| *h == name).unwrap();
    let (e, n) = (column("hpm_elastic_fs"), column("hpm_nonlinear_fs"));
    assert_eq!(rows.len(), 4);
    assert_eq!(
        rows[1][e].parse::<f64>().unwrap().to_bits(),
        elastic_fs.to_bits()
    );
    assert_eq!(
        rows[1][n].parse::<f64>().unwrap().to_bits(),
        plastic_fs.to_bits()
    );
    assert!(!rows[2][e].is_empty() && !rows[2][n].is_empty());
    assert_eq!((rows[3][e], rows[3][n]), ("", ""));

    for (prefix, result) in [("hpm", &elastic), ("hpm_nonlinear", &plastic)] {
        for (name, raster) in result.maps(&model, &grids).unwrap().maps {
            let written = read_esri_ascii(&out.join(format!("{prefix}_{name}.asc"))).unwrap();
            assert_eq!(bits(&written), bits(&raster), "{prefix}_{name}");
        }
    }

    // A layer of the same unit weight: taken, each column's springs the
    // strength of the layer they cross; a weak colluvium 40 m thick
    // lowers HPM's Fs of the worst surface.
    let dem = read_esri_ascii(&terrain_file()).unwrap();
    let (x0, y0) = dem.lower_left();
    let values = dem.values().iter().map(|v| v.map(|z| z - 40.0)).collect();
    let bottom = Raster::new(dem.columns(), dem.rows(), x0, y0, dem.cell_size(), values).unwrap();
    let bottom_path = dir.join("colluvium.asc");
    dismech::grid::write_esri_ascii(&bottom_path, &bottom).unwrap();
    let layer = format!("colluvium:{}:5e3:22:20e3", bottom_path.display());
    let mut layered_args = args.clone();
    layered_args.extend_from_slice(&["--layer", &layer]);
    let taken = slope(&dir.join("layered_same"), &layered_args);
    assert_eq!(
        taken.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&taken.stderr)
    );
    let layered_summary: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join("layered_same").join("summary.json")).unwrap(),
    )
    .unwrap();
    let layered_fs = layered_summary["hpm"]["results"][0]["elastic"]["fs"]
        .as_f64()
        .unwrap();
    assert!(layered_fs < elastic_fs, "{layered_fs} {elastic_fs}");
    // A layer of another unit weight (it used to be refused): taken, its
    // elements weighing the layers over their height, an HPM Fs given.
    let light = format!("colluvium:{}:5e3:22:18e3", bottom_path.display());
    let mut light_args = args.clone();
    light_args.extend_from_slice(&["--layer", &light]);
    let taken = slope(&dir.join("layered_light"), &light_args);
    assert_eq!(
        taken.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&taken.stderr)
    );
    let light_summary: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join("layered_light").join("summary.json")).unwrap(),
    )
    .unwrap();
    let light_fs = light_summary["hpm"]["results"][0]["elastic"]["fs"]
        .as_f64()
        .unwrap();
    assert!(light_fs.is_finite() && light_fs > 0.0, "{light_fs}");
    // The lighter colluvium (same strength) gives another Fs: the
    // elements weigh the layer they hold.
    assert_ne!(light_fs.to_bits(), layered_fs.to_bits(), "{light_fs}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--bedrock`: the map equals the library's search over the terrain with
/// the same bedrock bit for bit, and differs from the run without it; a
/// bedrock on another grid is refused naming `--bedrock` and the file.
#[test]
fn a_bedrock_is_that_of_the_library_search() {
    let dir = scratch("bedrock");
    let dem = read_esri_ascii(&terrain_file()).unwrap();
    let (x0, y0) = dem.lower_left();
    let values = dem.values().iter().map(|v| v.map(|z| z - 30.0)).collect();
    let rock = Raster::new(dem.columns(), dem.rows(), x0, y0, dem.cell_size(), values).unwrap();
    let rock_path = dir.join("rock.asc");
    dismech::grid::write_esri_ascii(&rock_path, &rock).unwrap();
    let with = fs_map_of(
        &dir.join("with"),
        &["--bedrock", rock_path.to_str().unwrap()],
    );
    let without = fs_map_of(&dir.join("without"), &[]);
    let terrain = Terrain::new(dismech::hpm::NamedRaster::new("dem", dem.clone()), None)
        .unwrap()
        .with_bedrock(dismech::hpm::NamedRaster::new("rock", rock))
        .unwrap();
    let lib = search(
        &terrain,
        &material(),
        &SlopeLoads::default(),
        &ellipsoids_5000(),
        &SearchSettings::default(),
        |_, _| {},
    )
    .unwrap();
    assert_eq!(bits(&with), bits(&lib.safety_factor_raster().unwrap()));
    assert_ne!(bits(&with), bits(&without));
    let summary: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join("with").join("summary.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(summary["bedrock"], rock_path.display().to_string());

    let small = dir.join("small.asc");
    std::fs::write(
        &small,
        "ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 75\n1 2 3\n4 5 6\n7 8 9\n",
    )
    .unwrap();
    let refused = slope(
        &dir.join("refused"),
        &["--search", "spheres", "--bedrock", small.to_str().unwrap()],
    );
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert_eq!(refused.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains(&format!("--bedrock {}", small.display())),
        "{stderr}"
    );
    assert!(!dir.join("refused").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
