//! The ACADS simple slope (Donald & Giam 1989: 10 m high at 2:1,
//! c' = 3 kPa, φ' = 19.6°, γ = 20 kN/m³) extruded in 3D at full size:
//! cells of 0.25 m, ellipsoids through the circle of centre (y 32 m,
//! z 22 m) through the toe, 1 to 64 times longer across the slope than
//! along it. Prints Hovland's 3D Fs of each against the circle's 2D Fs by
//! the ordinary method of slices (which Hovland's method reduces to in 2D,
//! computed here with 10⁶ slices) and against the limit of the elongated
//! ellipsoid from the 2D sums of its cross-sections, concentric circles
//! of radius `R √(1 − t²)` (tests/slope_extruded.rs checks the same at
//! 1 m cells).
//!
//! Printed: 2D 1.49421; limit 1.44155; 3D 1.37108, 1.41997, 1.43577,
//! 1.44008, 1.44117, 1.44145, 1.44152 for 1 to 64 times (up to 1.1 × 10⁶
//! columns): the 3D Fs rises to the limit, below the circle's 2D Fs (why:
//! tests/slope_extruded.rs).
//!
//! `cargo run --release --example slope_extruded`

use dismech::grid::Raster;
use dismech::hpm::NamedRaster;
use dismech::slope::{
    hovland_columns, surface_columns, Ellipsoid, SlopeLoads, SlopeMaterial, SurfaceLimits, Terrain,
};

const HEIGHT: f64 = 10.0;
const TOE: f64 = 20.0;
const COHESION: f64 = 3e3;
const GAMMA: f64 = 20e3;
const CENTRE: (f64, f64) = (32.0, 22.0);
const CELL: f64 = 0.25;
const LENGTH: f64 = 70.0;

fn ground(y: f64) -> f64 {
    ((y - TOE) / 2.0).clamp(0.0, HEIGHT)
}

/// `(Σ (c l + N tan φ), Σ T)` per unit width of the circle of radius `r`
/// by the ordinary method of slices, slices of width `width` at `centres`.
fn slice_sums(r: f64, centres: impl Iterator<Item = f64>, width: f64, mu: f64) -> (f64, f64) {
    let (mut resisting, mut driving) = (0.0, 0.0);
    for y in centres {
        let q = r * r - (y - CENTRE.0).powi(2);
        if q <= 0.0 {
            continue;
        }
        let h = ground(y) - (CENTRE.1 - q.sqrt());
        if h <= 0.0 {
            continue;
        }
        let s = (y - CENTRE.0) / q.sqrt();
        let rho = (1.0 + s * s).sqrt();
        let w = GAMMA * h * width;
        resisting += COHESION * width * rho + w / rho * mu;
        driving += w * s / rho;
    }
    (resisting, driving)
}

fn main() -> dismech::error::Result<()> {
    let mu = 19.6f64.to_radians().tan();
    let r = (CENTRE.0 - TOE).hypot(CENTRE.1);
    let n = 1_000_000;
    let delta = (CENTRE.0 + r - TOE) / n as f64;
    let (a, b) = slice_sums(r, (0..n).map(|k| TOE + (k as f64 + 0.5) * delta), delta, mu);
    let rows = (LENGTH / CELL).round() as usize;
    let centres = || (0..rows).map(|j| (j as f64 + 0.5) * CELL);
    let (mut res, mut drv) = (0.0, 0.0);
    let m = 20_000;
    for k in 0..m {
        let t = -1.0 + (k as f64 + 0.5) * 2.0 / m as f64;
        let (x, y) = slice_sums(r * (1.0 - t * t).sqrt(), centres(), CELL, mu);
        res += x;
        drv += y;
    }
    println!(
        "circle: centre (y {}, z {}) m, radius {r:.4} m",
        CENTRE.0, CENTRE.1
    );
    println!(
        "2D ordinary method of slices, 10^6 slices: Fs = {:.5}",
        a / b
    );
    println!(
        "limit of the elongated ellipsoid (2D sums of its cross-sections): Fs = {:.5}",
        res / drv
    );
    let soil = SlopeMaterial {
        cohesion: COHESION,
        friction_coefficient: mu,
        unit_weight: GAMMA,
    };
    for ratio in [1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0] {
        let across = ratio * r;
        let columns = ((2.0 * across + 5.0) / CELL).round() as usize;
        let dem = Raster::from_fn(columns, rows, 0.0, 0.0, CELL, |_, y| Some(ground(y)))?;
        let terrain = Terrain::new(NamedRaster::new("extruded", dem), None)?;
        let surface = Ellipsoid::new(
            (0.5 * columns as f64 * CELL, CENTRE.0, CENTRE.1),
            r,
            across,
            r,
            -std::f64::consts::FRAC_PI_2,
        )?;
        let mut slip = Vec::new();
        let fs = surface_columns(&terrain, &surface, &mut slip).and_then(|()| {
            hovland_columns(
                &slip,
                CELL,
                &soil,
                &SlopeLoads::default(),
                &SurfaceLimits::default(),
            )
        });
        match fs {
            Ok(fs) => println!(
                "across/along {ratio:>4}: 3D Hovland Fs = {:.5} ({} columns)",
                fs.safety_factor, fs.columns
            ),
            Err(reason) => println!("across/along {ratio:>4}: refused ({reason:?})"),
        }
    }
    Ok(())
}
