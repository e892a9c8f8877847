//! The ground, the material, the loads and the limits of a command line,
//! read and checked, each error naming its option.

use dismech::error::DismechError;
use dismech::grid::{GridError, GridFormatProblem};
use dismech::hpm::NamedRaster;
use dismech::law::friction_from_degrees;
use dismech::slope::{Ground, Layer, PoreRatio, SlopeLoads, SlopeMaterial, SurfaceLimits, Terrain};

use super::args::{RuArg, SlopeArgs, Span};
use super::error::SlopeError;

/// The DEM, the water table and the bedrock of `args`, read and checked.
///
/// # Errors
/// [`SlopeError::Argument`] naming `--dem`, `--water` or `--bedrock` and
/// the file: a file that cannot be read or is not an ESRI ASCII grid, a
/// DEM too small or without data, a water table or bedrock on another
/// grid.
pub fn terrain(args: &SlopeArgs) -> Result<Terrain, SlopeError> {
    let dem_value = args.dem.display().to_string();
    let dem =
        NamedRaster::read(&args.dem).map_err(|e| SlopeError::argument("--dem", &dem_value, e))?;
    let water = match &args.water {
        Some(path) => Some(
            NamedRaster::read(path)
                .map_err(|e| SlopeError::argument("--water", &path.display().to_string(), e))?,
        ),
        None => None,
    };
    let terrain = Terrain::new(dem, water).map_err(|e| match (&e, &args.water) {
        (DismechError::Grid(GridError::Mismatch { .. }), Some(path)) => {
            SlopeError::argument("--water", &path.display().to_string(), e)
        }
        _ => SlopeError::argument("--dem", &dem_value, e),
    })?;
    match &args.bedrock {
        None => Ok(terrain),
        Some(path) => {
            let value = path.display().to_string();
            NamedRaster::read(path)
                .and_then(|rock| terrain.with_bedrock(rock))
                .map_err(|e| SlopeError::argument("--bedrock", &value, e))
        }
    }
}

/// The DEM's coordinate system: the text of the `.prj` beside `--dem`
/// where there is one, read and checked before the search (it is copied
/// beside every ESRI ASCII map and kept inside every GeoTIFF map).
///
/// # Errors
/// [`SlopeError::Argument`] naming `--dem` and the DEM with
/// [`GridError::Format`] naming the `.prj` when it cannot be read
/// as text or a GeoTIFF cannot keep it (a character outside printable
/// ASCII or `|`, or a text too long for GDAL:
/// [`dismech::grid::check_crs_wkt`]).
pub fn crs(args: &SlopeArgs) -> Result<Option<String>, SlopeError> {
    let prj = args.dem.with_extension("prj");
    if !prj.is_file() {
        return Ok(None);
    }
    let refuse = |problem: GridFormatProblem| {
        SlopeError::argument(
            "--dem",
            &args.dem.display().to_string(),
            DismechError::Grid(GridError::Format {
                file: prj.display().to_string(),
                line: 0,
                column: 0,
                problem,
            }),
        )
    };
    let text = std::fs::read_to_string(&prj).map_err(|e| {
        refuse(GridFormatProblem::CrsUnreadable {
            kind: e.kind(),
            message: e.to_string(),
        })
    })?;
    dismech::grid::check_crs_wkt(&text)
        .map_err(|problem| refuse(GridFormatProblem::CrsNotKept { problem }))?;
    Ok(Some(text))
}

/// The material of `args`.
///
/// # Errors
/// [`SlopeError::Argument`] naming `--cohesion` where both c' and φ' are
/// zero (no strength); the values alone are checked as they are parsed.
pub fn material(args: &SlopeArgs) -> Result<SlopeMaterial, SlopeError> {
    let friction_coefficient = friction_from_degrees(args.friction_angle).map_err(|e| {
        SlopeError::argument("--friction-angle", &args.friction_angle.to_string(), e)
    })?;
    let material = SlopeMaterial {
        cohesion: args.cohesion,
        friction_coefficient,
        unit_weight: args.unit_weight,
    };
    material
        .validate()
        .map_err(|e| SlopeError::argument("--cohesion", &args.cohesion.to_string(), e))?;
    Ok(material)
}

/// The ground of `args`: the layers of `--layer` above the material of
/// `--cohesion`, `--friction-angle` and `--unit-weight` (one layer without
/// `--layer`: the single material), with the r_u of `--ru`.
///
/// # Errors
/// [`SlopeError::Argument`] naming `--layer` and its value for a bottom
/// file that cannot be read, lies on another grid than the DEM or a layer
/// without strength; naming `--ru` for a file that cannot be read, a value
/// outside [0, 1) or a grid other than the DEM's; those of [`material`].
pub fn ground(args: &SlopeArgs, terrain: &Terrain) -> Result<Ground, SlopeError> {
    let last = material(args)?;
    let layer_value = |l: &super::args::LayerArg| {
        format!(
            "{}:{}:{}:{}:{}",
            l.name,
            l.bottom.display(),
            l.cohesion,
            l.friction_angle,
            l.unit_weight
        )
    };
    let mut ground = if args.layers.is_empty() {
        Ground::from(last)
    } else {
        let mut layers = Vec::with_capacity(args.layers.len() + 1);
        for l in &args.layers {
            let fail = |e| SlopeError::argument("--layer", &layer_value(l), e);
            let bottom = NamedRaster::read(&l.bottom).map_err(fail)?;
            let material = SlopeMaterial {
                cohesion: l.cohesion,
                friction_coefficient: friction_from_degrees(l.friction_angle).map_err(fail)?,
                unit_weight: l.unit_weight,
            };
            layers.push(Layer {
                name: l.name.clone(),
                bottom: Some(bottom),
                material,
            });
        }
        layers.push(Layer {
            name: "base (--cohesion, --friction-angle, --unit-weight)".to_string(),
            bottom: None,
            material: last,
        });
        let ground = Ground::layered(layers).map_err(|e| {
            let l = match &e {
                DismechError::Slope(dismech::slope::SlopeError::InvalidLayer { layer, .. }) => {
                    args.layers.iter().find(|l| &l.name == layer)
                }
                _ => None,
            };
            match l {
                Some(l) => SlopeError::argument("--layer", &layer_value(l), e),
                None => SlopeError::argument("--cohesion", &args.cohesion.to_string(), e),
            }
        })?;
        for (l, layer) in args.layers.iter().zip(ground.layers()) {
            if let Some(b) = &layer.bottom {
                b.require_grid_of(terrain.dem())
                    .map_err(|e| SlopeError::argument("--layer", &layer_value(l), e))?;
            }
        }
        ground
    };
    if let Some(ru) = &args.ru {
        let (value, ratio) = match ru {
            RuArg::Constant(v) => (v.to_string(), PoreRatio::Constant(*v)),
            RuArg::File(path) => {
                let value = path.display().to_string();
                let raster =
                    NamedRaster::read(path).map_err(|e| SlopeError::argument("--ru", &value, e))?;
                raster
                    .require_grid_of(terrain.dem())
                    .map_err(|e| SlopeError::argument("--ru", &value, e))?;
                (value, PoreRatio::Raster(raster))
            }
        };
        ground = ground
            .with_pore_ratio(ratio)
            .map_err(|e| SlopeError::argument("--ru", &value, e))?;
    }
    Ok(ground)
}

/// The loads of `args` (k_h; γ_w = 9810 N/m³).
///
/// # Errors
/// [`SlopeError::Argument`] naming `--kh` (checked as it is parsed).
pub fn loads(args: &SlopeArgs) -> Result<SlopeLoads, SlopeError> {
    let loads = SlopeLoads {
        seismic_coefficient: args.kh,
        ..SlopeLoads::default()
    };
    loads
        .validate()
        .map_err(|e| SlopeError::argument("--kh", &args.kh.to_string(), e))?;
    Ok(loads)
}

/// The limits of `args` (no limit where an option is not given).
///
/// # Errors
/// [`SlopeError::Run`] with the library's error naming the limit (the
/// options are checked as they are parsed).
pub fn limits(args: &SlopeArgs) -> Result<SurfaceLimits, SlopeError> {
    let open = SurfaceLimits::default();
    let pick = |s: Option<Span>, default| s.map_or(default, |s| s.pair());
    let limits = SurfaceLimits {
        min_columns: args.min_columns,
        volume: pick(args.volume, open.volume),
        area: pick(args.area, open.area),
        depth: pick(args.depth, open.depth),
    };
    // The options were checked as they were parsed; the library checks
    // the whole again and names the limit.
    limits.validate()?;
    Ok(limits)
}
