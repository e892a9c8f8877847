//! `dismech slope`: the slope search of [`dismech::slope`] over a DEM from
//! one command, with a progress bar, and its results written into one
//! folder, whole or not at all.
//!
//! | concept | items | file |
//! |---|---|---|
//! | the options, checked as parsed | [`SlopeArgs`], [`SearchKind`], [`MethodArg`] (`--method hovland\|bishop`), [`Span`] | `args.rs` |
//! | ground, layers, r_u, loads, limits | [`inputs::terrain`], [`inputs::ground`], [`inputs::material`], … | `inputs.rs` |
//! | the family, defaults from the DEM | [`family::family`], [`family::Family`] | `family.rs` |
//! | errors naming the option | [`SlopeError`] | `error.rs` |
//! | the run and its files | [`run`], [`Report`] | `mod.rs`, `outputs.rs` |
//! | HPM re-analysis of the worst surfaces (`--hpm K`) | [`hpm::reanalyse`], [`hpm::HpmSurface`] | `hpm.rs` |
//! | the map | [`map::write_slope_map`], [`hillshade::hillshade`], [`footprint`] | `map.rs`, `hillshade.rs`, `footprint.rs` |
//!
//! The folder `--out` holds the rasters of the lowest Fs per cell and of
//! the volume, area and depth of the surface that gave it (`slope_fs.asc`,
//! `slope_volume.asc`, `slope_area.asc`, `slope_depth.asc`, on the DEM's
//! grid; with a copy of the DEM's `.prj` beside each where it has one),
//! the most critical surfaces (`critical.csv`), the map (`map.svg`) and
//! `summary.json`; with `--hpm K`, the HPM maps of the most critical
//! surface (`hpm_local_fs.asc`, `hpm_displacement.asc`, …, with
//! `hpm_nonlinear_*` for `--hpm-nonlinear`) and its slip surface
//! (`hpm_slip.asc`), and the HPM Fs of the K worst in `critical.csv` and
//! `summary.json`.

mod args;
mod error;
pub mod family;
pub mod footprint;
pub mod hillshade;
pub mod hpm;
pub mod inputs;
pub mod map;
mod outputs;

use std::time::Instant;

use dismech::slope::{
    search, Ground, SearchResult, SearchSettings, SlopeLoads, SurfaceLimits, Terrain, TrialFamily,
    TrialSurface,
};

use crate::output::StagedFolder;

pub use args::{LayerArg, MethodArg, RuArg, SearchKind, SlopeArgs, Span};
pub use error::{refusal_words, refusals, SlopeError};
pub use outputs::{Lowest, Report};

use family::Family;

/// What a search needs besides its family.
pub struct Problem {
    terrain: Terrain,
    ground: Ground,
    loads: SlopeLoads,
    limits: SurfaceLimits,
    /// The DEM's coordinate system (its `.prj`), checked.
    crs: Option<String>,
}

/// A progress bar over the trials, hidden when `quiet`.
fn progress_bar(total: u64, quiet: bool) -> indicatif::ProgressBar {
    if quiet {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(total);
    if let Ok(style) = indicatif::ProgressStyle::with_template(
        "slope search [{elapsed_precise}] {bar:30} {human_pos}/{human_len} trials ({eta} left)",
    ) {
        bar.set_style(style);
    }
    bar
}

/// Run the search of `family` and keep the `keep` most critical surfaces
/// (at least one, for the map).
fn run_family<F: TrialFamily>(
    problem: &Problem,
    family: &F,
    keep: usize,
    method: dismech::slope::Method,
    bishop: dismech::slope::BishopSettings,
    bar: &indicatif::ProgressBar,
) -> dismech::error::Result<SearchResult<F::Surface>> {
    let settings = SearchSettings {
        limits: problem.limits,
        critical: keep.max(1),
        method,
        bishop,
        ..SearchSettings::default()
    };
    bar.set_length(family.len(&problem.terrain));
    search(
        &problem.terrain,
        &problem.ground,
        &problem.loads,
        family,
        &settings,
        |done, _| bar.set_position(done),
    )
}

/// Search, then write every output into the staged folder and put it in
/// place.
fn search_and_write<F: TrialFamily>(
    args: &SlopeArgs,
    problem: &Problem,
    family: &F,
    description: String,
) -> Result<Report, SlopeError>
where
    F::Surface: TrialSurface,
{
    // A target that cannot become the folder is refused before the search.
    let folder = StagedFolder::new_replacing_runs(&args.out, "summary.json")?;
    let bishop = args.bishop()?;
    let bar = progress_bar(family.len(&problem.terrain), args.quiet);
    let search = || {
        run_family(
            problem,
            family,
            args.keep,
            args.method.method(),
            bishop,
            &bar,
        )
    };
    let threads;
    let start = Instant::now();
    let result = match args.threads {
        Some(n) => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|_| {
                    SlopeError::argument(
                        "--threads",
                        &n.to_string(),
                        dismech::error::DismechError::InvalidParameter {
                            name: "worker threads",
                            value: n as f64,
                            requirement: "no thread pool of that many threads could be started",
                        },
                    )
                })?;
            threads = n;
            pool.install(search)?
        }
        None => {
            threads = rayon::current_num_threads();
            search()?
        }
    };
    let seconds = start.elapsed().as_secs_f64();
    bar.finish_and_clear();
    if result.counts.evaluated == 0 {
        let extent = family::Extent::of(&problem.terrain);
        let (width, height) = extent.size();
        return Err(SlopeError::NoSurface {
            family: description,
            dem: (width, height, extent.cell),
            counts: Box::new(result.counts),
            bedrock: args.bedrock.as_ref().map(|b| b.display().to_string()),
        });
    }
    let hpm_runs = hpm::reanalyse(args, problem, &result);
    let report = outputs::write(
        args,
        &problem.terrain,
        &result,
        &hpm_runs,
        folder.path(),
        problem.crs.as_deref(),
        outputs::Run {
            family: description,
            kind: match args.search {
                SearchKind::Spheres => "spheres",
                SearchKind::Ellipsoids => "ellipsoids",
            },
            threads,
            seconds,
        },
    )?;
    folder.commit()?;
    Ok(report)
}

/// Run `dismech slope` with `args`: read and check the inputs, search,
/// write the folder `--out` whole, and report what was found.
///
/// # Errors
/// A [`SlopeError`] naming the option or file at fault; the folder
/// `--out` is then left as it was.
pub fn run(args: &SlopeArgs) -> Result<Report, SlopeError> {
    hpm::check(args)?;
    args.bishop()?;
    let terrain = inputs::terrain(args)?;
    let crs = inputs::crs(args)?;
    let problem = Problem {
        crs,
        ground: inputs::ground(args, &terrain)?,
        loads: inputs::loads(args)?,
        limits: inputs::limits(args)?,
        terrain,
    };
    let family = family::family(args, &problem.terrain)?;
    let description = family::describe(&family);
    match family {
        Family::Spheres(grid) => search_and_write(args, &problem, &grid, description),
        Family::Ellipsoids(random) => search_and_write(args, &problem, &random, description),
    }
}
