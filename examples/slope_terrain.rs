//! The slope search over a real terrain at full size: the DEM shipped in
//! examples/data/terrain (SRTM heights around the Jacksboro fault,
//! Tennessee, resampled to 100 × 100 cells of 75 m in UTM zone 16N; see
//! its README), a soil of c' = 15 kPa, φ' = 28°, γ = 20 kN/m³, dry.
//!
//! Two searches by Hovland's method: Scoops3D's grid of spheres (a centre
//! every 2nd cell, 8 heights of 75 to 1875 m above the ground, 12 radii of
//! 300 to 2500 m: 240 000 trials) and r.slope.stability's random
//! ellipsoids (10⁶ trials: semi-axes along the fall line 300 to 1875 m,
//! across 0.5 to 1 times that, vertical 75 to 375 m, centres 0 to 187.5 m
//! above the ground). Each writes its maps of the lowest Fs per cell (with
//! the volume, area and depth of the surface that gave it) and its 20 most
//! critical surfaces into the folder given; the time per trial is printed.
//! `dismech slope` runs the same searches from the command line, with the
//! map as SVG.
//!
//! `cargo run --release --example slope_terrain -- OUT_DIR`

use std::path::{Path, PathBuf};
use std::time::Instant;

use dismech::law::friction_from_degrees;
use dismech::slope::{
    search, EllipsoidRandom, SearchResult, SearchSettings, SlopeLoads, SlopeMaterial, SphereGrid,
    Steps, Terrain, TrialFamily, TrialSurface,
};

fn run<F: TrialFamily>(
    name: &str,
    terrain: &Terrain,
    material: &SlopeMaterial,
    family: &F,
    out: &Path,
) -> dismech::error::Result<SearchResult<F::Surface>> {
    let settings = SearchSettings {
        critical: 20,
        ..SearchSettings::default()
    };
    let start = Instant::now();
    let result = search(
        terrain,
        material,
        &SlopeLoads::default(),
        family,
        &settings,
        |done, total| eprint!("\r  {name}: {done}/{total}"),
    )?;
    let seconds = start.elapsed().as_secs_f64();
    eprintln!();
    let c = &result.counts;
    println!(
        "{name}: {} trials in {seconds:.2} s on {} threads ({:.2} µs a trial), {} gave an Fs",
        c.trials,
        rayon::current_num_threads(),
        1e6 * seconds / c.trials as f64,
        c.evaluated
    );
    if let Some(best) = result.lowest() {
        let r = &best.result;
        println!(
            "  lowest Fs {:.4}: trial {}, {:?} = {:.1?}, {} columns, volume {:.3e} m³, area {:.3e} m², depth {:.1} m",
            r.safety_factor,
            best.trial,
            F::Surface::PARAMETERS,
            best.surface.parameters(),
            r.columns,
            r.volume,
            r.area,
            r.depth
        );
    }
    result.write_maps(out, name)?;
    result.write_critical_csv(&out.join(format!("{name}_critical.csv")))?;
    Ok(result)
}

fn main() -> dismech::error::Result<()> {
    let out = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "slope_terrain_out".into()),
    );
    let dem =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/data/terrain/jacksboro_fault.asc");
    let terrain = Terrain::read(&dem, None)?;
    let material = SlopeMaterial {
        cohesion: 15e3,
        friction_coefficient: friction_from_degrees(28.0)?,
        unit_weight: 20e3,
    };
    let spheres = SphereGrid::new(
        2,
        Steps::checked("heights above the ground", 75.0, 1875.0, 8, false)?,
        Steps::checked("radii", 300.0, 2500.0, 12, true)?,
    )?;
    run("spheres", &terrain, &material, &spheres, &out)?;
    let ellipsoids = EllipsoidRandom::new(
        1_000_000,
        1,
        (0.0, 187.5),
        (300.0, 1875.0),
        (0.5, 1.0),
        (75.0, 375.0),
    )?;
    run("ellipsoids", &terrain, &material, &ellipsoids, &out)?;
    println!("maps and critical surfaces written to {}", out.display());
    Ok(())
}
