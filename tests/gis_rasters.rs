//! Maps for a GIS read back by GDAL: the GeoTIFF and ESRI ASCII rasters
//! the library writes (a raster, an HPM and a Hovland analysis' maps, a
//! slope search's maps) are opened with `gdalinfo -json`, which must
//! report the size, origin, cell size, data type and no-data value
//! written, and converted back to text by `gdal_translate -of AAIGrid`
//! (20 significant digits), whose values must equal the raster's bit for
//! bit.
//!
//! The other way, GeoTIFF DEMs written by GDAL (64- and 32-bit floats,
//! 16-bit integers; uncompressed, LZW, Deflate; strips and tiles; pixels
//! as areas and as points) are read by the library with the grid and the
//! values GDAL reads.
//!
//! GDAL's tools come from the Debian package `gdal-bin`, which `.ci/run`
//! installs; the tests fail, not skip, where `gdalinfo` cannot be run.

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::Command;

use dismech::grid::{
    read_esri_ascii, read_geotiff, read_raster, write_esri_ascii, write_geotiff, Raster,
    RasterFormat, GEOTIFF_NODATA,
};
use dismech::hpm::{
    hovland, HpmMaterial, HpmModel, HpmSettings, HpmSolver, NamedRaster, Seismic, SlopeGrids,
    HOVLAND_MAP_NAMES, HPM_MAP_NAMES,
};
use dismech::slope::{
    search, SearchSettings, SlopeLoads, SlopeMaterial, SphereGrid, Steps, Terrain, MAP_NAMES,
};
use serde_json::Value;

/// Run one of GDAL's tools; its standard output. Panics (the test fails)
/// where the tool cannot be run or fails.
fn gdal<S: AsRef<OsStr>>(tool: &str, args: &[S]) -> Vec<u8> {
    let out = Command::new(tool).args(args).output().unwrap_or_else(|e| {
        panic!(
            "cannot run `{tool}` ({e}): install GDAL's tools, the Debian package gdal-bin \
             (`apt-get install gdal-bin`, as .ci/run does)"
        )
    });
    assert!(
        out.status.success(),
        "`{tool}` failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

/// GDAL's open options for `path`: an ESRI ASCII grid read as 64-bit
/// floats (GDAL's AAIGrid driver reads 32-bit floats unless told).
fn open_options(path: &Path) -> Vec<&'static OsStr> {
    if path.extension() == Some(OsStr::new("asc")) {
        vec![OsStr::new("-oo"), OsStr::new("DATATYPE=Float64")]
    } else {
        vec![]
    }
}

/// What `gdalinfo -json` reports of `path`.
fn gdalinfo(path: &Path) -> Value {
    let mut args = open_options(path);
    args.extend([OsStr::new("-json"), path.as_os_str()]);
    let json = gdal("gdalinfo", &args);
    serde_json::from_slice(&json).expect("gdalinfo -json prints JSON")
}

/// The raster GDAL reads from `path`, as GDAL writes it in ESRI ASCII
/// (`gdal_translate -of AAIGrid`, 20 significant digits: every `f64`
/// reads back to its bits) and the library parses it.
fn gdal_values(path: &Path, scratch: &Path) -> Raster {
    let asc = scratch.join(format!(
        "{}.gdal.asc",
        path.file_name().unwrap().to_string_lossy()
    ));
    let mut args = open_options(path);
    args.extend([
        OsStr::new("-q"),
        OsStr::new("-of"),
        OsStr::new("AAIGrid"),
        path.as_os_str(),
        asc.as_os_str(),
    ]);
    gdal("gdal_translate", &args);
    read_esri_ascii(&asc).unwrap()
}

/// Check what GDAL reports of `path` against `raster`'s grid: size,
/// geotransform (the upper-left corner, `cellsize` across and
/// `−cellsize` down), one band of `band_type`, pixels as areas, and the
/// no-data value `nodata` (`None`: NaN).
fn assert_georeferenced(info: &Value, raster: &Raster, band_type: &str, nodata: Option<f64>) {
    let (x0, y0) = raster.lower_left();
    let d = raster.cell_size();
    assert_eq!(
        info["size"],
        serde_json::json!([raster.columns(), raster.rows()]),
        "{info}"
    );
    let transform: Vec<f64> = info["geoTransform"]
        .as_array()
        .expect("a geotransform")
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(
        transform,
        [x0, d, 0.0, y0 + raster.rows() as f64 * d, 0.0, -d]
    );
    let lower_left: Vec<f64> = info["cornerCoordinates"]["lowerLeft"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(lower_left, [x0, y0]);
    let bands = info["bands"].as_array().unwrap();
    assert_eq!(bands.len(), 1);
    assert_eq!(bands[0]["type"], band_type);
    match nodata {
        Some(v) => assert_eq!(bands[0]["noDataValue"].as_f64(), Some(v), "{info}"),
        None => assert_eq!(bands[0]["noDataValue"], "NaN", "{info}"),
    }
}

/// A folder for a test's files, emptied.
fn folder(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("gis_rasters_{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Projected coordinates of the size of a UTM zone's, a cell size that is
/// no power of two, values of every kind (negative, fractions with all 17
/// digits) and cells without data.
fn utm_raster() -> Raster {
    Raster::from_fn(7, 5, 512_345.25, 4_102_030.5, 2.5, |x, y| {
        if x > 512_360.0 && y < 4_102_035.0 {
            None
        } else {
            Some((x - 512_345.0) * (y - 4_102_030.0) / 7.0 - 3.0)
        }
    })
    .unwrap()
}

#[test]
fn a_geotiff_reads_back_in_gdal_with_its_origin_cell_size_nodata_and_values() {
    let dir = folder("raster");
    let raster = utm_raster();
    assert_eq!(raster.values().iter().filter(|v| v.is_none()).count(), 2);
    let tif = dir.join("values.tif");
    write_geotiff(&tif, &raster).unwrap();
    let info = gdalinfo(&tif);
    assert_eq!(info["driverShortName"], "GTiff");
    assert_georeferenced(&info, &raster, "Float64", Some(GEOTIFF_NODATA));
    assert_eq!(info["metadata"][""]["AREA_OR_POINT"], "Area");
    // The plane coordinates in metres, the projection left to the user.
    let wkt = info["coordinateSystem"]["wkt"].as_str().unwrap();
    assert!(wkt.contains("LENGTHUNIT[\"metre\",1"), "{wkt}");
    assert_eq!(gdal_values(&tif, &dir), raster);

    // The ESRI ASCII grid of the same raster, read by GDAL: the same grid.
    let asc = dir.join("values.asc");
    write_esri_ascii(&asc, &raster).unwrap();
    assert_georeferenced(&gdalinfo(&asc), &raster, "Float64", Some(-9999.0));
    assert_eq!(gdal_values(&asc, &dir), raster);
}

#[test]
fn a_cell_holding_the_nodata_value_makes_it_nan_in_gdal() {
    let dir = folder("nan");
    let raster = Raster::new(
        3,
        2,
        -100.0,
        50.0,
        0.5,
        vec![
            Some(-9999.0),
            None,
            Some(1.5),
            Some(0.0),
            Some(-0.0),
            Some(2.0),
        ],
    )
    .unwrap();
    let tif = dir.join("nan.tif");
    write_geotiff(&tif, &raster).unwrap();
    assert_georeferenced(&gdalinfo(&tif), &raster, "Float64", None);
    // GDAL writes the NaN no-data value as `nan`, which the reader takes.
    let back = gdal_values(&tif, &dir);
    assert_eq!(back.get(0, 0), Some(-9999.0));
    assert_eq!(back.get(0, 1), None);
    assert_eq!(back, raster);
}

/// A slope on a georeferenced grid: ground dipping towards −y, a slip
/// surface 6 m below it under the middle of the grid only (so that some
/// cells have no column).
fn slope() -> SlopeGrids {
    let (x0, y0, d) = (351_210.0, 4_500_120.0, 10.0);
    let ground = Raster::from_fn(5, 4, x0, y0, d, |x, y| {
        Some(0.36 * (y - y0) + 0.01 * (x - x0))
    })
    .unwrap();
    let slip = Raster::from_fn(5, 4, x0, y0, d, |x, y| {
        let z = 0.36 * (y - y0) + 0.01 * (x - x0);
        Some(if x < x0 + 40.0 { z - 6.0 } else { z + 1.0 })
    })
    .unwrap();
    SlopeGrids::new(
        NamedRaster::new("ground", ground),
        NamedRaster::new("slip", slip),
        None,
    )
    .unwrap()
}

#[test]
fn hpm_and_hovland_maps_read_back_in_gdal_on_the_input_grid() {
    let dir = folder("hpm");
    let grids = slope();
    let grid = &grids.ground().raster;
    let model = HpmModel::new(&grids, &HpmMaterial::paper(), &HpmSettings::default()).unwrap();
    assert_eq!(model.columns.len(), 16);
    let mut solver = HpmSolver::new(&model).unwrap();
    let result = solver.elastic(&model, &Seismic::none()).unwrap();
    let maps = result.maps(&model, &grids).unwrap();
    let hov = hovland(&model, &Seismic::none(), (0.0, -1.0)).unwrap();
    let hov_maps = hov.maps(&model, &grids).unwrap();

    // The maps hold each column's values at its cell, no data elsewhere.
    let local = result.local_safety_factors(&model);
    let surface = result.surface(&model);
    let (c, mu) = (model.material.cohesion, model.material.friction());
    for (k, column) in model.columns.iter().enumerate() {
        let (r, col) = column.cell;
        let at = |name: &str| maps.get(name).unwrap().get(r, col);
        assert_eq!(at("local_fs"), Some(local[k]));
        assert_eq!(at("displacement_y"), Some(surface[k].displacement.y));
        assert_eq!(at("displacement"), Some(surface[k].displacement.norm()));
        assert_eq!(at("strain_minor"), Some(surface[k].principal[1]));
        let t = hov.columns[k];
        assert_eq!(
            hov_maps.get("local_fs").unwrap().get(r, col),
            Some((c * t.area + t.normal * mu) / t.driving)
        );
        assert_eq!(
            hov_maps.get("driving_force").unwrap().get(r, col),
            Some(t.driving)
        );
    }
    for name in HPM_MAP_NAMES {
        let map = maps.get(name).unwrap();
        assert!(map.same_grid(grid));
        assert_eq!(map.values().iter().filter(|v| v.is_none()).count(), 4);
    }
    // The slide moves down the dip (−y) and shears its columns.
    assert!(surface.iter().all(|p| p.displacement.y < 0.0));

    let paths = maps.write(&dir, "elastic", &RasterFormat::ALL).unwrap();
    let hov_paths = hov_maps.write(&dir, "hovland", &RasterFormat::ALL).unwrap();
    assert_eq!(paths.len(), 2 * HPM_MAP_NAMES.len());
    assert_eq!(hov_paths.len(), 2 * HOVLAND_MAP_NAMES.len());
    for ((name, raster), files) in maps
        .maps
        .iter()
        .chain(&hov_maps.maps)
        .zip(paths.chunks(2).chain(hov_paths.chunks(2)))
    {
        let (asc, tif) = (&files[0], &files[1]);
        assert!(tif.to_string_lossy().ends_with(&format!("_{name}.tif")));
        assert_georeferenced(&gdalinfo(tif), grid, "Float64", Some(GEOTIFF_NODATA));
        assert_eq!(&gdal_values(tif, &dir), raster, "{name}");
        assert_eq!(&read_esri_ascii(asc).unwrap(), raster, "{name}");
    }
}

#[test]
fn a_slope_search_writes_its_maps_as_geotiff_beside_the_ascii_grids() {
    let dir = folder("search");
    let (x0, y0) = (612_000.0, 5_100_000.0);
    let dem = Raster::from_fn(24, 20, x0, y0, 2.0, |x, y| {
        Some(0.47 * (y - y0) + 0.002 * (x - x0 - 24.0).powi(2))
    })
    .unwrap();
    let terrain = Terrain::new(NamedRaster::new("dem", dem.clone()), None).unwrap();
    let soil = SlopeMaterial {
        cohesion: 8e3,
        friction_coefficient: 30f64.to_radians().tan(),
        unit_weight: 19e3,
    };
    let family = SphereGrid::new(
        3,
        Steps::checked("heights", 4.0, 12.0, 3, false).unwrap(),
        Steps::checked("radii", 6.0, 16.0, 4, true).unwrap(),
    )
    .unwrap();
    let result = search(
        &terrain,
        &soil,
        &SlopeLoads::default(),
        &family,
        &SearchSettings::default(),
        |_, _| {},
    )
    .unwrap();
    let paths = result
        .write_maps_as(&dir, "search", &RasterFormat::ALL)
        .unwrap();
    assert_eq!(paths.len(), 2 * MAP_NAMES.len());
    let fs = result.safety_factor_raster().unwrap();
    assert!(fs.values().iter().any(|v| v.is_some()));
    assert!(fs.values().iter().any(|v| v.is_none()));
    let rasters = [
        fs,
        result.volume_raster().unwrap(),
        result.area_raster().unwrap(),
        result.depth_raster().unwrap(),
    ];
    for (raster, files) in rasters.iter().zip(paths.chunks(2)) {
        assert_georeferenced(&gdalinfo(&files[1]), &dem, "Float64", Some(GEOTIFF_NODATA));
        assert_eq!(&gdal_values(&files[1], &dir), raster);
        assert_eq!(&read_esri_ascii(&files[0]).unwrap(), raster);
    }
    // The ASCII grids are those of `write_maps`, byte for byte.
    let ascii = result.write_maps(&dir.join("ascii"), "search").unwrap();
    for (a, both) in ascii.iter().zip(paths.chunks(2)) {
        assert_eq!(std::fs::read(a).unwrap(), std::fs::read(&both[0]).unwrap());
    }
}

/// `gdal_translate` `source` into the GeoTIFF `target` with `options`.
fn translate(source: &Path, target: &Path, options: &[&str]) {
    let mut args: Vec<&OsStr> = open_options(source);
    args.push(OsStr::new("-q"));
    args.extend(options.iter().map(OsStr::new));
    args.extend([source.as_os_str(), target.as_os_str()]);
    gdal("gdal_translate", &args);
}

#[test]
fn geotiff_dems_written_by_gdal_are_read_with_their_grid_and_values() {
    let dir = folder("gdal_written");
    let raster = utm_raster();
    let asc = dir.join("dem.asc");
    write_esri_ascii(&asc, &raster).unwrap();
    let same_values = |read: &Raster, expected: &dyn Fn(f64) -> f64| {
        assert!(read.same_grid(&raster));
        assert_eq!(read.lower_left(), raster.lower_left());
        assert_eq!(read.cell_size(), raster.cell_size());
        let want: Vec<Option<f64>> = raster.values().iter().map(|v| v.map(expected)).collect();
        assert_eq!(read.values(), &want[..]);
    };
    let exact = |v: f64| v;
    for (name, options) in [
        ("plain", &["-ot", "Float64"][..]),
        ("lzw", &["-ot", "Float64", "-co", "COMPRESS=LZW"][..]),
        (
            "deflate_tiled",
            &[
                "-ot",
                "Float64",
                "-co",
                "COMPRESS=DEFLATE",
                "-co",
                "TILED=YES",
                "-co",
                "BLOCKXSIZE=16",
                "-co",
                "BLOCKYSIZE=16",
            ][..],
        ),
        (
            "lzw_predictor",
            &[
                "-ot",
                "Float64",
                "-co",
                "COMPRESS=LZW",
                "-co",
                "PREDICTOR=1",
            ][..],
        ),
        // Pixels as points: GDAL moves the tie point to the first cell's
        // centre, and the reader moves it back by half a cell.
        (
            "point",
            &["-ot", "Float64", "-mo", "AREA_OR_POINT=Point"][..],
        ),
    ] {
        let tif = dir.join(format!("{name}.tif"));
        translate(&asc, &tif, options);
        let read = read_geotiff(&tif).unwrap_or_else(|e| panic!("{name}: {e}"));
        same_values(&read, &exact);
        assert_eq!(read, gdal_values(&tif, &dir), "{name}");
    }
    let info = gdalinfo(&dir.join("point.tif"));
    assert_eq!(info["metadata"][""]["AREA_OR_POINT"], "Point");

    // 32-bit floats: the values rounded to f32 (and the no-data value
    // compared as f32); 16-bit integers: as GDAL reads them.
    let tif = dir.join("float32.tif");
    translate(&asc, &tif, &["-ot", "Float32", "-co", "COMPRESS=DEFLATE"]);
    same_values(&read_geotiff(&tif).unwrap(), &|v| v as f32 as f64);
    let tif = dir.join("int16.tif");
    translate(&asc, &tif, &["-ot", "Int16", "-co", "COMPRESS=LZW"]);
    let read = read_geotiff(&tif).unwrap();
    assert!(read.same_grid(&raster));
    assert_eq!(read, gdal_values(&tif, &dir));
    assert_eq!(read.values().iter().filter(|v| v.is_none()).count(), 2);
    assert!(read.values().iter().flatten().all(|v| v.fract() == 0.0));

    // A DEM given as GeoTIFF where an ESRI ASCII grid was: by extension.
    let lzw = dir.join("lzw.tif");
    assert_eq!(read_raster(&lzw).unwrap(), raster);
    assert_eq!(NamedRaster::read(&lzw).unwrap().raster, raster);
    assert_eq!(read_raster(&asc).unwrap(), raster);
}

#[test]
fn gdal_files_a_raster_cannot_hold_are_refused_naming_the_tag() {
    let dir = folder("gdal_refused");
    let asc = dir.join("dem.asc");
    write_esri_ascii(&asc, &utm_raster()).unwrap();
    let refusal = |name: &str, options: &[&str]| {
        let tif = dir.join(format!("{name}.tif"));
        translate(&asc, &tif, options);
        let e = read_geotiff(&tif).unwrap_err().to_string();
        assert!(e.contains(&format!("{name}.tif")), "{e}");
        e
    };
    // Cells of 2.5 m × 6.25 m (5 rows squeezed into 2).
    let e = refusal("rectangular", &["-outsize", "100%", "50%"]);
    assert!(e.contains("ModelPixelScale (33550) = (2.5, 6.25)"), "{e}");
    // Two bands.
    let e = refusal("two_bands", &["-b", "1", "-b", "1"]);
    assert!(e.contains("one band"), "{e}");
    // A baseline TIFF: no GeoTIFF tags (GDAL keeps the georeferencing in a
    // side file the reader does not read).
    let e = refusal("bare", &["-co", "PROFILE=BASELINE"]);
    assert!(
        e.contains("has no ModelPixelScale (33550) and ModelTiepoint (33922)"),
        "{e}"
    );
}

/// A GeoTIFF written with the coordinate system of a `.prj` (the shipped
/// terrain's, an ESRI WKT of UTM zone 16N) has, as `gdalinfo -json`
/// reports it, the coordinate system GDAL reads from the ESRI ASCII grid
/// with that `.prj` beside it, and its grid and values unchanged; a WKT a
/// GeoTIFF's key cannot hold is refused naming the file, which is then not
/// there.
#[test]
fn a_geotiff_carries_the_coordinate_system_of_a_prj() {
    let dir = folder("crs");
    let dem =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/data/terrain/jacksboro_fault.asc");
    let wkt = std::fs::read_to_string(dem.with_extension("prj")).unwrap();
    let raster = read_esri_ascii(&dem).unwrap();
    let tif = dir.join("dem.tif");
    dismech::grid::write_geotiff_with_crs(&tif, &raster, Some(&wkt)).unwrap();
    let info = gdalinfo(&tif);
    let expected = gdalinfo(&dem);
    let crs = |v: &Value| v["coordinateSystem"]["wkt"].as_str().unwrap().to_string();
    assert!(
        crs(&expected).starts_with("PROJCRS[\"WGS 84 / UTM zone 16N\""),
        "{}",
        crs(&expected)
    );
    assert_eq!(crs(&info), crs(&expected));
    assert_georeferenced(&info, &raster, "Float64", Some(GEOTIFF_NODATA));
    assert_eq!(read_geotiff(&tif).unwrap(), raster);
    assert_eq!(gdal_values(&tif, &dir), raster);
    // Without one, the CRS stays user-defined, not UTM.
    let plain = dir.join("plain.tif");
    write_geotiff(&plain, &raster).unwrap();
    assert!(!crs(&gdalinfo(&plain)).contains("UTM"));

    for bad in [
        "PROJCS[\"a|b\"]".to_string(),
        "PROJCS[\"é\"]".to_string(),
        "P".repeat(2400),
    ] {
        let path = dir.join("bad.tif");
        let e = dismech::grid::write_geotiff_with_crs(&path, &raster, Some(&bad)).unwrap_err();
        assert!(
            matches!(&e, dismech::error::DismechError::Output { path: p, .. } if p.ends_with("bad.tif")),
            "{e}"
        );
        assert!(!path.exists());
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
