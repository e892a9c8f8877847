//! The files of a slope search, written into the staged folder, and the
//! report printed after them.

use std::path::{Path, PathBuf};

use dismech::error::DismechError;
use dismech::grid::{write_rasters_with_crs, Raster, RasterFormat};
use dismech::slope::{surface_columns, SearchCounts, SearchResult, Terrain, TrialSurface};

use super::args::SlopeArgs;
use super::error::{refusals, SlopeError};
use super::footprint::{centroid, outline};
use super::hpm::HpmRuns;
use super::map::{write_slope_map, SlopeMap};

/// The prefix of the rasters: `slope_fs.asc`, …
pub const MAP_PREFIX: &str = "slope";
/// The most critical surfaces.
pub const CRITICAL_CSV: &str = "critical.csv";
/// The map.
pub const MAP_SVG: &str = "map.svg";
/// The summary.
pub const SUMMARY_JSON: &str = "summary.json";
/// The prefix of the HPM maps of the most critical surface (`--hpm`).
pub const HPM_PREFIX: &str = "hpm";
/// The prefix of its nonlinear HPM maps (`--hpm-nonlinear`).
pub const HPM_NONLINEAR_PREFIX: &str = "hpm_nonlinear";

/// `csv` (the critical surfaces) with two columns more,
/// `hpm_elastic_fs` and `hpm_nonlinear_fs`: HPM's Fs along the sliding
/// direction of each surface re-analysed, empty where there is none (not
/// re-analysed, not asked, or refused: summary.json says why).
fn with_hpm_columns(csv: &str, surfaces: &[super::hpm::HpmSurface]) -> String {
    let mut out = String::with_capacity(csv.len() + 64 * surfaces.len());
    for (k, line) in csv.lines().enumerate() {
        out.push_str(line);
        if k == 0 {
            out.push_str(",hpm_elastic_fs,hpm_nonlinear_fs\n");
            continue;
        }
        let number = |v: Option<&Result<f64, String>>| {
            v.and_then(|r| r.as_ref().ok())
                .map_or_else(String::new, |f| f.to_string())
        };
        let (elastic, nonlinear) = match surfaces.get(k - 1).map(|s| &s.outcome) {
            Some(Ok((_, e, n))) => (
                number(Some(&e.sliding_fs)),
                number(n.as_ref().map(|n| &n.sliding_fs)),
            ),
            _ => (String::new(), String::new()),
        };
        out.push(',');
        out.push_str(&elastic);
        out.push(',');
        out.push_str(&nonlinear);
        out.push('\n');
    }
    out
}

/// How the search ran.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    /// The family, as the options that give it.
    pub family: String,
    /// `spheres` or `ellipsoids`.
    pub kind: &'static str,
    /// Worker threads.
    pub threads: usize,
    /// Seconds the search took (the files not included).
    pub seconds: f64,
}

/// The most critical surface.
#[derive(Debug, Clone, PartialEq)]
pub struct Lowest {
    /// Its Fs.
    pub safety_factor: f64,
    /// Its trial index in the family.
    pub trial: u64,
    /// Its parameters, named (m; radians for an azimuth).
    pub surface: Vec<(&'static str, f64)>,
    /// The centroid of its columns (m).
    pub centroid: (f64, f64),
    /// Columns.
    pub columns: usize,
    /// Volume (m³).
    pub volume: f64,
    /// Plan area (m²).
    pub area: f64,
    /// Depth (m).
    pub depth: f64,
    /// Sliding direction (degrees counter-clockwise from east).
    pub direction_deg: f64,
}

/// What `dismech slope` found and wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// The folder written.
    pub out: PathBuf,
    /// The files in it.
    pub files: Vec<String>,
    /// The most critical surface.
    pub lowest: Lowest,
    /// Trials and refusals.
    pub counts: SearchCounts,
    /// How the search ran.
    pub run: Run,
    /// The HPM re-analyses (`--hpm K`), most critical first.
    pub hpm: Vec<super::hpm::HpmSurface>,
}

impl std::fmt::Display for Report {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let l = &self.lowest;
        let surface: Vec<String> = l
            .surface
            .iter()
            .map(|(n, v)| format!("{n} {v:.1}"))
            .collect();
        writeln!(
            f,
            "lowest Fs {:.4} (trial {}: {}), {} columns around ({:.0}, {:.0}) m, volume {:.3e} m³, area {:.3e} m², depth {:.1} m, sliding towards {:.0}° (counter-clockwise from east)",
            l.safety_factor,
            l.trial,
            surface.join(", "),
            l.columns,
            l.centroid.0,
            l.centroid.1,
            l.volume,
            l.area,
            l.depth,
            l.direction_deg
        )?;
        let refused = self.counts.trials - self.counts.evaluated;
        write!(
            f,
            "trials {}: {} evaluated, {} refused",
            self.counts.trials, self.counts.evaluated, refused
        )?;
        if refused > 0 {
            write!(f, " ({})", refusals(&self.counts).join(", "))?;
        }
        writeln!(
            f,
            "; {:.2} s on {} thread{} ({:.2} µs a trial)",
            self.run.seconds,
            self.run.threads,
            if self.run.threads == 1 { "" } else { "s" },
            1e6 * self.run.seconds / self.counts.trials as f64
        )?;
        write!(f, "wrote {}: {}", self.out.display(), self.files.join(", "))
    }
}

fn output_error(path: &Path, e: impl std::fmt::Display) -> DismechError {
    DismechError::Output {
        path: path.display().to_string(),
        message: e.to_string(),
    }
}

/// Write the rasters, the `.prj` copies, the CSV, the map and the summary
/// of `result` into `dir`; the report names them. `wkt` is the DEM's
/// coordinate system, the text of its `.prj` ([`super::inputs::crs`]).
///
/// # Errors
/// [`SlopeError::Run`] with [`DismechError::Output`] naming a file that
/// cannot be written.
pub fn write<S: TrialSurface + Copy>(
    args: &SlopeArgs,
    terrain: &Terrain,
    result: &SearchResult<S>,
    hpm: &HpmRuns,
    dir: &Path,
    wkt: Option<&str>,
    run: Run,
) -> Result<Report, SlopeError> {
    let mut files = Vec::new();
    let name = |p: &Path| p.file_name().map(|n| n.to_string_lossy().into_owned());
    // ESRI ASCII grids and GeoTIFF beside them, on the DEM's grid.
    // A GIS reads an ESRI ASCII grid's coordinate system from a `.prj`
    // beside it, copied from the DEM's; a GeoTIFF carries it inside (GDAL
    // ignores a `.prj` beside a GeoTIFF).
    // (read and checked before the search: [`super::inputs::crs`]).
    let prj = args.dem.with_extension("prj");
    let all = &RasterFormat::ALL;
    let mut rasters = result.write_maps_with_crs(dir, MAP_PREFIX, all, wkt)?;
    if let Some(worst) = &hpm.worst {
        let slip = [("slip", &worst.grids.slip().raster)];
        rasters.extend(write_rasters_with_crs(dir, HPM_PREFIX, &slip, all, wkt)?);
        let maps = [
            (HPM_PREFIX, Some(worst.elastic_maps()?)),
            (HPM_NONLINEAR_PREFIX, worst.nonlinear_maps()?),
        ];
        for (prefix, maps) in maps {
            let Some(maps) = maps else { continue };
            let list: Vec<(&str, &Raster)> = maps.maps.iter().map(|(n, r)| (*n, r)).collect();
            rasters.extend(write_rasters_with_crs(dir, prefix, &list, all, wkt)?);
        }
    }
    for raster in &rasters {
        files.extend(name(raster));
        if prj.is_file() && RasterFormat::of_path(raster) == RasterFormat::EsriAscii {
            let copy = raster.with_extension("prj");
            std::fs::copy(&prj, &copy).map_err(|e| output_error(&copy, e))?;
            files.extend(name(&copy));
        }
    }
    let keep = args.keep.min(result.critical.len());
    let csv = dir.join(CRITICAL_CSV);
    let mut kept = result.clone();
    kept.critical.truncate(keep);
    let text = kept.critical_csv();
    let text = if args.hpm.is_none() {
        text
    } else {
        with_hpm_columns(&text, &hpm.surfaces)
    };
    dismech::io::write_atomically(&csv, text.as_bytes())?;
    files.push(CRITICAL_CSV.into());

    let best = result.lowest().ok_or_else(|| {
        output_error(dir, "the search kept no critical surface (none gave an Fs)")
    })?;
    let mut columns = Vec::new();
    surface_columns(terrain, &best.surface, &mut columns).map_err(|reason| {
        output_error(
            dir,
            format!("the critical surface's columns could not be found again ({reason:?})"),
        )
    })?;
    let dem = &terrain.dem().raster;
    let centre = centroid(dem, &columns).unwrap_or(dem.lower_left());
    let r = &best.result;
    let reach = (r.area / std::f64::consts::PI).sqrt();
    let lowest = Lowest {
        safety_factor: r.safety_factor,
        trial: best.trial,
        surface: S::PARAMETERS
            .iter()
            .copied()
            .zip(best.surface.parameters())
            .collect(),
        centroid: centre,
        columns: r.columns,
        volume: r.volume,
        area: r.area,
        depth: r.depth,
        direction_deg: r.direction.1.atan2(r.direction.0).to_degrees(),
    };
    let safety = result.safety_factor_raster()?;
    let dem_name = args.dem.file_name().map_or_else(
        || args.dem.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let map = SlopeMap {
        dem,
        safety: &safety,
        title: format!("{dem_name}: lowest Fs per cell ({})", run.kind),
        outline: outline(dem, &columns),
        arrow: Some((
            centre,
            (
                centre.0 + reach * r.direction.0,
                centre.1 + reach * r.direction.1,
            ),
        )),
        outline_label: format!("critical surface, Fs = {:.3}", r.safety_factor),
    };
    write_slope_map(&dir.join(MAP_SVG), &map)?;
    files.push(MAP_SVG.into());
    files.push(SUMMARY_JSON.into());
    let report = Report {
        out: args.out.clone(),
        files,
        lowest,
        counts: result.counts,
        run,
        hpm: hpm.surfaces.clone(),
    };
    let summary = summary_json(args, terrain, &report);
    let text = serde_json::to_string_pretty(&summary)
        .map_err(|e| output_error(&dir.join(SUMMARY_JSON), e))?;
    dismech::io::write_atomically(&dir.join(SUMMARY_JSON), text.as_bytes())?;
    Ok(report)
}

/// `summary.json`: the inputs, the family, the counts, the most critical
/// surface, the run and the files.
fn summary_json(args: &SlopeArgs, terrain: &Terrain, report: &Report) -> serde_json::Value {
    let dem = &terrain.dem().raster;
    let l = &report.lowest;
    let c = &report.counts;
    let mut refused = serde_json::Map::new();
    for reason in dismech::slope::Refusal::ALL {
        refused.insert(format!("{reason:?}"), c.refused_for(reason).into());
    }
    let mut surface = serde_json::Map::new();
    for (name, value) in &l.surface {
        surface.insert((*name).to_string(), (*value).into());
    }
    serde_json::json!({
        "dem": args.dem.display().to_string(),
        "water": args.water.as_ref().map(|w| w.display().to_string()),
        "bedrock": args.bedrock.as_ref().map(|b| b.display().to_string()),
        "grid": {
            "rows": dem.rows(),
            "columns": dem.columns(),
            "cell_size_m": dem.cell_size(),
            "lower_left": [dem.lower_left().0, dem.lower_left().1],
        },
        "material": {
            "cohesion_pa": args.cohesion,
            "friction_angle_deg": args.friction_angle,
            "unit_weight_n_per_m3": args.unit_weight,
        },
        "layers": args.layers.iter().map(|l| serde_json::json!({
            "name": l.name,
            "bottom": l.bottom.display().to_string(),
            "cohesion_pa": l.cohesion,
            "friction_angle_deg": l.friction_angle,
            "unit_weight_n_per_m3": l.unit_weight,
        })).collect::<Vec<_>>(),
        "ru": args.ru.as_ref().map(|r| match r {
            super::args::RuArg::Constant(v) => serde_json::json!(v),
            super::args::RuArg::File(p) => serde_json::json!(p.display().to_string()),
        }),
        "kh": args.kh,
        "method": args.method.name(),
        "m_alpha_floor": match args.method {
            super::args::MethodArg::Bishop => serde_json::json!(args.bishop().map(|b| b.m_alpha_floor()).ok()),
            super::args::MethodArg::Hovland => serde_json::Value::Null,
        },
        "family": report.run.family,
        "limits": {
            "min_columns": args.min_columns,
            "depth_m": args.depth.map(|s| s.to_string()),
            "volume_m3": args.volume.map(|s| s.to_string()),
            "area_m2": args.area.map(|s| s.to_string()),
        },
        "trials": c.trials,
        "evaluated": c.evaluated,
        "refused": refused,
        "lowest": {
            "fs": l.safety_factor,
            "trial": l.trial,
            "surface": surface,
            "centroid_m": [l.centroid.0, l.centroid.1],
            "columns": l.columns,
            "volume_m3": l.volume,
            "area_m2": l.area,
            "depth_m": l.depth,
            "direction_deg": l.direction_deg,
        },
        "hpm": if args.hpm.is_none() {
            serde_json::Value::Null
        } else {
            serde_json::json!({
                "surfaces": args.hpm,
                "nonlinear": args.hpm_nonlinear,
                "youngs_modulus_pa": args.youngs_modulus,
                "poisson_ratio": args.poisson_ratio,
                "results": report.hpm.iter().map(super::hpm::HpmSurface::json).collect::<Vec<_>>(),
            })
        },
        "threads": report.run.threads,
        "seconds": report.run.seconds,
        "files": report.files,
    })
}
