//! A slope search over a synthetic terrain: a valley side descending
//! towards the south at about 27° with a bump on it, 150 × 120 cells of
//! 2 m. Scoops3D's systematic grid of spheres (every 3rd cell, 6 heights,
//! 10 radii) and r.slope.stability's random ellipsoids are evaluated by
//! Hovland's method; the map of the lowest Fs per cell (with the volume,
//! area and depth of the surface that gave it) and the 20 most critical
//! surfaces are written into the folder given.
//!
//! `cargo run --release --example slope_search -- OUT_DIR`

use std::path::PathBuf;
use std::time::Instant;

use dismech::grid::Raster;
use dismech::hpm::NamedRaster;
use dismech::slope::{
    search, EllipsoidRandom, SearchResult, SearchSettings, SlopeLoads, SlopeMaterial, SphereGrid,
    Steps, Terrain, TrialSurface,
};

fn report<S: TrialSurface>(name: &str, result: &SearchResult<S>, seconds: f64) {
    let c = &result.counts;
    println!(
        "{name}: {} trials in {seconds:.2} s ({:.1} µs a trial), {} gave an Fs",
        c.trials,
        1e6 * seconds / c.trials as f64,
        c.evaluated
    );
    if let Some(best) = result.lowest() {
        let r = &best.result;
        println!(
            "  lowest Fs {:.4}: trial {}, {:?} = {:?}, {} columns, volume {:.0} m³, area {:.0} m², depth {:.1} m",
            r.safety_factor,
            best.trial,
            S::PARAMETERS,
            best.surface.parameters(),
            r.columns,
            r.volume,
            r.area,
            r.depth
        );
    }
}

fn main() -> dismech::error::Result<()> {
    let out = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "slope_search_out".into()),
    );
    let dem = Raster::from_fn(150, 120, 500_000.0, 4_100_000.0, 2.0, |x, y| {
        let (u, v) = (x - 500_000.0, y - 4_100_000.0);
        // The valley floor along y = 0, the side rising northwards, a
        // bump of 6 m on the side.
        let side = 0.5 * v + 0.0012 * (u - 150.0).powi(2);
        let bump = 6.0 * (-((u - 170.0).powi(2) + (v - 130.0).powi(2)) / 600.0).exp();
        Some(100.0 + side + bump)
    })?;
    let terrain = Terrain::new(NamedRaster::new("valley side", dem), None)?;
    let material = SlopeMaterial {
        cohesion: 10e3,
        friction_coefficient: 30f64.to_radians().tan(),
        unit_weight: 19e3,
    };
    let settings = SearchSettings {
        critical: 20,
        ..SearchSettings::default()
    };

    let family = SphereGrid::new(
        3,
        Steps::checked("heights above the ground", 5.0, 40.0, 6, false)?,
        Steps::checked("radii", 15.0, 90.0, 10, true)?,
    )?;
    let start = Instant::now();
    let spheres = search(
        &terrain,
        &material,
        &SlopeLoads::default(),
        &family,
        &settings,
        |done, total| eprint!("\r  spheres {done}/{total}"),
    )?;
    eprintln!();
    report("spheres (grid)", &spheres, start.elapsed().as_secs_f64());
    spheres.write_maps(&out, "spheres")?;
    spheres.write_critical_csv(&out.join("spheres_critical.csv"))?;

    let family = EllipsoidRandom::new(
        100_000,
        2024,
        (0.0, 10.0),
        (15.0, 60.0),
        (0.3, 0.9),
        (4.0, 20.0),
    )?;
    let start = Instant::now();
    let ellipsoids = search(
        &terrain,
        &material,
        &SlopeLoads::default(),
        &family,
        &settings,
        |done, total| eprint!("\r  ellipsoids {done}/{total}"),
    )?;
    eprintln!();
    report(
        "ellipsoids (random)",
        &ellipsoids,
        start.elapsed().as_secs_f64(),
    );
    ellipsoids.write_maps(&out, "ellipsoids")?;
    ellipsoids.write_critical_csv(&out.join("ellipsoids_critical.csv"))?;
    println!("maps and critical surfaces written to {}", out.display());
    Ok(())
}
