//! An ACADS-type benchmark (the simple slope of Donald & Giam's ACADS
//! study, 1989: 10 m high at 2 horizontal to 1 vertical, c' = 3 kPa,
//! φ' = 19.6°, γ = 20 kN/m³), extruded in 3D: Hovland's 3D Fs of an
//! ellipsoid whose cross-section through its centre is a given circle,
//! against the 2D Fs of that circle, as the ellipsoid elongates across the
//! slope. It converges to the limit the 2D sums of its cross-sections give
//! (within 1e-3 at 32 times longer than wide); that limit lies below the
//! central circle's 2D Fs for the ACADS soil, and the 3D Fs below it, but
//! above it for a purely cohesive soil (see each test for why and the
//! numbers).
//!
//! The 2D reference is computed here, independently of the library, by the
//! ordinary method of slices (Fellenius 1936), which is what Hovland's
//! method reduces to in 2D (Hovland 1977): for the circle of centre
//! `(y_c, z_c)` and radius R, slices of width δ with base
//! `z_b = z_c − √(R² − (y − y_c)²)`, base slope `s = dz_b/dy`,
//! weight `W = γ (g − z_b) δ`, `Fs = Σ (c δ √(1 + s²) + W tan φ / √(1 + s²))
//! / Σ W s / √(1 + s²)`. Taken at the DEM's cell centres it is the limit
//! of the 3D columns as the ellipsoid becomes a cylinder; taken with fine
//! slices it is the circle's own 2D Fs.

use dismech::grid::Raster;
use dismech::hpm::NamedRaster;
use dismech::slope::*;

const HEIGHT: f64 = 10.0;
const TOE: f64 = 20.0;
const COHESION: f64 = 3e3;
const PHI_DEG: f64 = 19.6;
const GAMMA: f64 = 20e3;
/// The circle: centre (y, z) and radius through the toe.
const CENTRE: (f64, f64) = (32.0, 22.0);

fn radius() -> f64 {
    (CENTRE.0 - TOE).hypot(CENTRE.1)
}

/// The ground of the simple slope, descending towards −y: level at 0
/// below the toe, rising 1 in 2 to the crest at `HEIGHT`, level beyond.
fn ground(y: f64) -> f64 {
    ((y - TOE) / 2.0).clamp(0.0, HEIGHT)
}

/// The soil with friction coefficient `mu` (ACADS: tan 19.6°).
fn soil(mu: f64) -> SlopeMaterial {
    SlopeMaterial {
        cohesion: COHESION,
        friction_coefficient: mu,
        unit_weight: GAMMA,
    }
}

fn acads_mu() -> f64 {
    PHI_DEG.to_radians().tan()
}

/// The ordinary method of slices for the circle of radius `r` about
/// [`CENTRE`] over slices of width `width` centred at `centres`: the sums
/// `(Σ (c l + N tan φ), Σ T)` per unit width.
fn slice_sums(r: f64, centres: impl Iterator<Item = f64>, width: f64, mu: f64) -> (f64, f64) {
    let (mut resisting, mut driving) = (0.0, 0.0);
    for y in centres {
        let q = r * r - (y - CENTRE.0).powi(2);
        if q <= 0.0 {
            continue;
        }
        let base = CENTRE.1 - q.sqrt();
        let h = ground(y) - base;
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

/// The cell centres y = 0.5, 1.5, … m of the DEM's rows.
fn cell_centres() -> impl Iterator<Item = f64> {
    (0..70).map(|j| j as f64 + 0.5)
}

/// The 3D Fs of the ellipsoid of semi-axis `across` over the slope
/// extruded on cells of `cell` m, wide enough for it.
fn fs_3d(across: f64, cell: f64, mu: f64) -> (f64, usize) {
    let length = 70.0;
    let width = 2.0 * across + 20.0 * cell;
    let (columns, rows) = (
        (width / cell).round() as usize,
        (length / cell).round() as usize,
    );
    let dem = Raster::from_fn(columns, rows, 0.0, 0.0, cell, |_, y| Some(ground(y))).unwrap();
    let terrain = Terrain::new(NamedRaster::new("extruded", dem), None).unwrap();
    let r = radius();
    let surface = Ellipsoid::new(
        (0.5 * columns as f64 * cell, CENTRE.0, CENTRE.1),
        r,
        across,
        r,
        -std::f64::consts::FRAC_PI_2,
    )
    .unwrap();
    let mut slip = Vec::new();
    surface_columns(&terrain, &surface, &mut slip).unwrap();
    let fs = hovland_columns(
        &slip,
        cell,
        &soil(mu),
        &SlopeLoads::default(),
        &SurfaceLimits::default(),
    )
    .unwrap();
    assert!(fs.direction.1 < -1.0 + 1e-12, "{:?}", fs.direction);
    (fs.safety_factor, slip.len())
}

/// The 2D Fs of the circle by the ordinary method of slices: at the 1 m
/// cell centres and with 10⁶ slices.
fn reference_2d(mu: f64) -> (f64, f64) {
    let r = radius();
    let (res, drv) = slice_sums(r, cell_centres(), 1.0, mu);
    let span = (TOE, CENTRE.0 + r);
    let n = 1_000_000;
    let delta = (span.1 - span.0) / n as f64;
    let (fine_res, fine_drv) = slice_sums(
        r,
        (0..n).map(|k| span.0 + (k as f64 + 0.5) * delta),
        delta,
        mu,
    );
    (res / drv, fine_res / fine_drv)
}

/// The limit of the 3D Fs as the ellipsoid elongates, from 2D sums alone:
/// the cross-section of the ellipsoid at `v = t b` across is the circle
/// about the same centre of radius `R √(1 − t²)`, and as b grows the
/// columns' sideways slope vanishes, so that Hovland's sums become the
/// integrals over t of the 2D sums of these circles (midpoint rule, 20 000
/// points, 2D slices at the cell centres).
fn elongated_limit(mu: f64) -> f64 {
    let n = 20_000;
    let (mut res, mut drv) = (0.0, 0.0);
    for k in 0..n {
        let t = -1.0 + (k as f64 + 0.5) * 2.0 / n as f64;
        let (a, b) = slice_sums(radius() * (1.0 - t * t).sqrt(), cell_centres(), 1.0, mu);
        res += a;
        drv += b;
    }
    res / drv
}

/// Across/along ratios of the ellipsoids.
const ELONGATIONS: [f64; 6] = [1.0, 2.0, 4.0, 8.0, 16.0, 32.0];

fn fs_by_elongation(mu: f64) -> Vec<f64> {
    let r = radius();
    ELONGATIONS
        .iter()
        .map(|&k| fs_3d(k * r, 1.0, mu).0)
        .collect()
}

/// The ACADS soil (c' = 3 kPa, φ' = 19.6°). Measured: the circle's 2D
/// Fs 1.49421 (10⁶ slices), 1.49351 (1 m slices at the cell centres); 3D
/// 1.37201, 1.42031, 1.43578, 1.44026, 1.44142, 1.44167 for across/along
/// = 1, 2, 4, 8, 16, 32, rising to the limit of the elongated ellipsoid,
/// computed from 2D sums alone ([`elongated_limit`]), below the central
/// circle's 2D Fs: an ellipsoid's cross-sections are concentric circles
/// of every smaller radius whatever its elongation, so it never becomes a
/// cylinder, and for this soil the smaller circles have the lower Fs.
/// The 3D Fs also lies below the 2D one at every elongation: Hovland's
/// method takes each column's normal force as its weight's component on
/// the base normal, `N = W / ρ` with `ρ = √(1 + z_x² + z_y²)`, so the
/// sideways tilt of the bases towards the ends lowers their friction, and
/// with no forces between columns nothing gives it back (Duncan, J.
/// Geotech. Eng. 122(7), 1996, reviews this of Hovland's method). The
/// purely cohesive case below lies above.
#[test]
fn extruded_acads_slope_3d_fs_approaches_the_2d_limit_as_the_ellipsoid_elongates() {
    let (at_centres, fine) = reference_2d(acads_mu());
    let limit = elongated_limit(acads_mu());
    let fs = fs_by_elongation(acads_mu());
    println!(
        "2D ordinary method of slices: {fine:.5} (10^6 slices), {at_centres:.5} (1 m slices at the cell centres); elongated limit {limit:.5}; 3D Hovland, across/along = {ELONGATIONS:?}: {fs:?}"
    );
    for w in fs.windows(2) {
        assert!(w[0] < w[1] && w[1] < limit, "{fs:?} against {limit}");
    }
    assert!(limit < at_centres);
    let last = fs[fs.len() - 1];
    assert!((limit - last) < 1e-3 * limit, "{last} against {limit}");
    // The cells' sampling of the circle moves the 2D Fs by under 1 %.
    assert!(
        (at_centres - fine).abs() < 0.01 * fine,
        "{at_centres} {fine}"
    );
}

/// A purely cohesive soil (φ = 0, c = 3 kPa): the 3D Fs lies above the
/// circle's 2D one at every elongation (the ends add base area, and so
/// cohesion) and falls towards the elongated limit, itself above the 2D
/// Fs. Measured: 2D 0.10089 (10⁶ slices), 0.10078 (cell centres); 3D
/// 0.13338, 0.12326, 0.12016, 0.11964, 0.11951, 0.11945.
#[test]
fn extruded_cohesive_slope_3d_fs_lies_above_the_2d_and_falls_to_the_limit() {
    let (at_centres, fine) = reference_2d(0.0);
    let limit = elongated_limit(0.0);
    let fs = fs_by_elongation(0.0);
    println!(
        "φ = 0: 2D {fine:.5} (10^6 slices), {at_centres:.5} (cell centres); elongated limit {limit:.5}; 3D, across/along = {ELONGATIONS:?}: {fs:?}"
    );
    for w in fs.windows(2) {
        assert!(w[0] > w[1] && w[1] > limit, "{fs:?} against {limit}");
    }
    assert!(limit > at_centres);
    let last = fs[fs.len() - 1];
    assert!((last - limit) < 1e-3 * limit, "{last} against {limit}");
    assert!(
        (at_centres - fine).abs() < 0.01 * fine,
        "{at_centres} {fine}"
    );
}
