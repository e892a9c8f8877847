//! The HPM driver's model: paper 001's columns between a ground and a slip
//! surface read from ESRI ASCII grids, the soil and slip-surface springs
//! of `[law] kind = "hpm"`, and a static or seismic elastic analysis
//! (and, with `driver.nonlinear`, the nonlinear one), written as ParaView
//! frames and per-column maps on the ground grid.

use std::path::{Path, PathBuf};

use dismech::hpm::{HpmMaterial, HpmModel, HpmSettings, NonlinearSettings, Seismic, SlopeGrids};

use super::bodies::{BodySpec, GridColumnsSpec};
use super::check::{self, combination, count, named, Refusal};
use super::driver::HpmSpec;
use super::law::LawSpec;
use super::source::{KeyPath, Source};
use super::ScenarioSpec;

/// An HPM analysis ready to run.
pub struct HpmPlan {
    /// The columns and their springs.
    pub model: HpmModel,
    /// The seismic load (none by default).
    pub seismic: Seismic,
    /// The grids the columns were built on (the maps' grid).
    pub grids: SlopeGrids,
    /// The coordinate system of the ground grid: the text of the `.prj`
    /// beside it, where there is one (copied beside every ESRI ASCII map,
    /// kept inside every GeoTIFF map).
    pub crs: Option<String>,
    /// The nonlinear analysis' settings, where `driver.nonlinear = true`.
    pub nonlinear: Option<NonlinearSettings>,
}

/// The library's names of the nonlinear settings and their keys.
const NONLINEAR_NAMES: check::Names<'static> = &[
    (
        "NonlinearSettings::tolerance (relative out-of-balance force)",
        "tolerance",
    ),
    ("NonlinearSettings::max_iterations", "max_iterations"),
];

/// The library's names of the material's and the settings' values and
/// the keys that give them.
const NAMES: check::Names<'static> = &[
    ("Young's modulus E", "youngs_modulus"),
    ("Poisson's ratio nu", "poisson_ratio"),
    ("cohesion c", "cohesion"),
    ("friction coefficient mu = tan(phi)", "friction"),
    ("cohesion c (with friction coefficient mu = 0)", "cohesion"),
    ("unit weight gamma_t", "unit_weight"),
    ("submerged unit weight gamma_sub", "submerged_unit_weight"),
    ("slip-surface modulus E_slip", "slip_modulus"),
    ("slip-surface shear stiffness k_s", "slip_shear_stiffness"),
];

/// Build the HPM analysis of `spec`, read from `file` (the grids' paths
/// are relative to its folder).
pub fn build(
    source: &Source<'_>,
    spec: &ScenarioSpec,
    settings: &HpmSpec,
    file: &Path,
) -> Result<HpmPlan, Refusal> {
    let kind = KeyPath::root("driver").key("kind");
    for (present, table) in [
        (spec.kinematics.is_some(), "kinematics"),
        (spec.boundary.is_some(), "boundary"),
        (spec.integrator.is_some(), "integrator"),
        (spec.linear_solver.is_some(), "linear_solver"),
        (spec.lp_solver.is_some(), "lp_solver"),
        (spec.run.is_some(), "run"),
        (spec.loads.gravity.is_some(), "loads"),
        (!spec.loads.forces.is_empty(), "loads"),
        (!spec.loads.tractions.is_empty(), "loads"),
        (spec.loads.live.is_some(), "loads"),
    ] {
        if present {
            return Err(combination(
                source,
                &[&kind, &KeyPath::root(table)],
                "the HPM driver analyses grid columns under their weight (and `loads.seismic`) in one elastic solve (and, with `nonlinear = true`, a nonlinear one): it takes `[[bodies]]` (one `grid-columns`), `[law]` (`hpm`), `[loads] seismic` and `[output]`; remove this table",
            ));
        }
    }
    let bodies = KeyPath::root("bodies");
    count(source, &bodies, spec.bodies.len(), 1, 1).map_err(|_| {
        Box::new(source.at_key(
            &bodies,
            "the HPM driver takes exactly one `[[bodies]]` table, of kind = \"grid-columns\"",
        ))
    })?;
    let path = bodies.index(0);
    let BodySpec::GridColumns(columns) = &spec.bodies[0] else {
        return Err(combination(
            source,
            &[&kind, &path.key("kind")],
            "the HPM driver takes one `[[bodies]]` table of kind = \"grid-columns\" (ground and slip-surface grids)",
        ));
    };
    let law = KeyPath::root("law");
    let LawSpec::Hpm(soil) = &spec.law else {
        return Err(combination(
            source,
            &[&kind, &law.key("kind")],
            "the HPM driver needs the soil and its slip surface: `[law] kind = \"hpm\"`",
        ));
    };
    let grids = grids(source, columns, &path, file)?;
    let crs = crs(
        source,
        &path.key("ground"),
        &folder(file).join(&columns.ground),
    )?;
    let mu = check::friction(source, &law, soil.friction, soil.friction_angle, None)?;
    let submerged = match (soil.submerged_unit_weight, &columns.water) {
        (Some(g), _) => g,
        (None, Some(_)) => {
            return Err(combination(
                source,
                &[&path.key("water"), &law.key("submerged_unit_weight")],
                "below a water table the soil weighs its submerged unit weight: give `submerged_unit_weight`",
            ))
        }
        // Without a water table it is not used.
        (None, None) => soil.unit_weight,
    };
    let material = HpmMaterial {
        youngs_modulus: soil.youngs_modulus,
        poisson_ratio: soil.poisson_ratio,
        cohesion: soil.cohesion,
        friction_coefficient: mu,
        unit_weight: soil.unit_weight,
        submerged_unit_weight: submerged,
        slip_modulus: soil.slip_modulus.unwrap_or(soil.youngs_modulus),
        slip_shear_stiffness: soil.slip_shear_stiffness,
    };
    material
        .validate()
        .map_err(|e| named(source, &law, NAMES, e))?;
    let driver = KeyPath::root("driver");
    let defaults = HpmSettings::default();
    let hpm_settings = HpmSettings {
        layers: count(
            source,
            &driver.key("layers"),
            settings.layers.unwrap_or(defaults.layers),
            3,
            1000,
        )?,
        penalty: match settings.penalty {
            Some(p) => check::positive(source, &driver.key("penalty"), p)?,
            None => defaults.penalty,
        },
        ..defaults
    };
    let seismic = match &spec.loads.seismic {
        None => Seismic::none(),
        Some(s) => {
            let table = KeyPath::root("loads").key("seismic");
            let direction = check::finite2(source, &table.key("direction"), s.direction)?;
            let seismic = Seismic {
                coefficient: s.coefficient,
                direction: (direction[0], direction[1]),
            };
            seismic.validate().map_err(|e| {
                let key = if e.to_string().contains("direction") {
                    "direction"
                } else {
                    "coefficient"
                };
                Box::new(source.at_key(&table.key(key), e.to_string()))
            })?;
            seismic
        }
    };
    let nonlinear = nonlinear(source, settings, &driver)?;
    let model = HpmModel::new(&grids, &material, &hpm_settings)
        .map_err(|e| combination(source, &[&path, &law, &driver], &e.to_string()))?;
    Ok(HpmPlan {
        model,
        seismic,
        grids,
        crs,
        nonlinear,
    })
}

/// The nonlinear analysis' settings of `[driver]` at `driver`: none
/// unless `nonlinear = true`; `tolerance` and `max_iterations` (the
/// library's defaults where not given) checked by
/// [`NonlinearSettings::validate`], and refused without `nonlinear = true`.
fn nonlinear(
    source: &Source<'_>,
    settings: &HpmSpec,
    driver: &KeyPath,
) -> Result<Option<NonlinearSettings>, Refusal> {
    if settings.nonlinear != Some(true) {
        for (given, key) in [
            (settings.tolerance.is_some(), "tolerance"),
            (settings.max_iterations.is_some(), "max_iterations"),
        ] {
            if given {
                let mut keys = vec![driver.key(key)];
                if settings.nonlinear.is_some() {
                    keys.push(driver.key("nonlinear"));
                }
                let keys: Vec<&KeyPath> = keys.iter().collect();
                return Err(combination(
                    source,
                    &keys,
                    "the tolerance and iteration limit are the nonlinear analysis': give `nonlinear = true` or remove this key",
                ));
            }
        }
        return Ok(None);
    }
    let defaults = NonlinearSettings::default();
    let nonlinear = NonlinearSettings {
        tolerance: settings.tolerance.unwrap_or(defaults.tolerance),
        max_iterations: match settings.max_iterations {
            // As the other drivers' step counts, at most 10⁶.
            Some(n) => count(source, &driver.key("max_iterations"), n, 1, 1_000_000)?,
            None => defaults.max_iterations,
        },
    };
    nonlinear
        .validate()
        .map_err(|e| named(source, driver, NONLINEAR_NAMES, e))?;
    Ok(Some(nonlinear))
}

/// The folder of the scenario `file`, against which its paths are read.
fn folder(file: &Path) -> &Path {
    file.parent().unwrap_or(Path::new(""))
}

/// The coordinate system of the ground grid `ground` (given at `key`):
/// the text of the `.prj` beside it where there is one, checked to be one
/// a GeoTIFF keeps ([`dismech::grid::check_crs_wkt`]).
fn crs(source: &Source<'_>, key: &KeyPath, ground: &Path) -> Result<Option<String>, Refusal> {
    let prj: PathBuf = ground.with_extension("prj");
    if prj == ground || !prj.is_file() {
        return Ok(None);
    }
    let text = std::fs::read_to_string(&prj).map_err(|e| {
        Box::new(source.at_key(
            key,
            format!(
                "{}: the coordinate system beside the ground grid cannot be read: {e}",
                prj.display()
            ),
        ))
    })?;
    dismech::grid::check_crs_wkt(&text).map_err(|problem| {
        Box::new(source.at_key(
            key,
            format!(
                "{}: the coordinate system beside the ground grid cannot be kept in the GeoTIFF maps: {problem}",
                prj.display()
            ),
        ))
    })?;
    Ok(Some(text))
}

/// The grids of a `grid-columns` entry, read from their files.
fn grids(
    source: &Source<'_>,
    columns: &GridColumnsSpec,
    path: &KeyPath,
    file: &Path,
) -> Result<SlopeGrids, Refusal> {
    let folder = folder(file);
    let mut paths = Vec::new();
    for (key, given) in [
        ("ground", Some(&columns.ground)),
        ("slip", Some(&columns.slip)),
        ("water", columns.water.as_ref()),
    ] {
        let Some(given) = given else {
            paths.push(None);
            continue;
        };
        if given.is_empty() || given.contains('\0') {
            return Err(Box::new(source.at_key(
                &path.key(key),
                "give the path of an ESRI ASCII grid (relative to the scenario file's folder)",
            )));
        }
        let at = folder.join(given);
        if !at.is_file() {
            return Err(Box::new(source.at_key(
                &path.key(key),
                format!("{} is not a readable file", at.display()),
            )));
        }
        paths.push(Some(at));
    }
    let (Some(ground), Some(slip)) = (&paths[0], &paths[1]) else {
        return Err(Box::new(source.at_key(path, "no ground or slip grid")));
    };
    SlopeGrids::read(ground, slip, paths[2].as_deref()).map_err(|e| {
        let message = e.to_string();
        let key = if paths[2]
            .as_ref()
            .is_some_and(|w| message.contains(&w.display().to_string()))
        {
            "water"
        } else if message.contains(&slip.display().to_string()) {
            "slip"
        } else {
            "ground"
        };
        Box::new(source.at_key(&path.key(key), message))
    })
}
