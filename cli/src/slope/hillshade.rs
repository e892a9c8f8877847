//! Shaded relief of a DEM: how brightly a distant sun lights each cell's
//! ground, the backdrop of the slope map.
//!
//! The ground's gradient at a cell is Horn's weighted difference over the
//! 3 × 3 cells around it (Horn, Proc. IEEE 69(1), 1981, eq. 7-8; the
//! gradient GDAL's `gdaldem hillshade` uses), with the cell's own height
//! in place of a neighbour off the grid or without data; the shade is the
//! cosine of the angle between the ground's normal and the sun, 0 where
//! the sun is behind the ground (Burrough & McDonnell, Principles of GIS,
//! 1998, ch. 8).

use dismech::grid::Raster;

/// Where the sun stands.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sun {
    /// Azimuth (degrees clockwise from north).
    pub azimuth_deg: f64,
    /// Altitude above the horizon (degrees).
    pub altitude_deg: f64,
}

impl Default for Sun {
    /// The cartographers' sun: from the north-west (315°), 45° high.
    fn default() -> Self {
        Self {
            azimuth_deg: 315.0,
            altitude_deg: 45.0,
        }
    }
}

/// The gradient `(∂z/∂x, ∂z/∂y)` of the ground at cell (row, column), x
/// east and y north, by Horn's 3 × 3 weights; `None` without data there.
pub fn gradient(dem: &Raster, row: usize, column: usize) -> Option<(f64, f64)> {
    let centre = dem.get(row, column)?;
    let z = |dr: isize, dc: isize| -> f64 {
        let (r, c) = (row as isize + dr, column as isize + dc);
        if r < 0 || c < 0 {
            return centre;
        }
        dem.get(r as usize, c as usize).unwrap_or(centre)
    };
    let d = dem.cell_size();
    // Row 0 is the north: row − 1 lies north of the cell.
    let east = z(-1, 1) + 2.0 * z(0, 1) + z(1, 1);
    let west = z(-1, -1) + 2.0 * z(0, -1) + z(1, -1);
    let north = z(-1, -1) + 2.0 * z(-1, 0) + z(-1, 1);
    let south = z(1, -1) + 2.0 * z(1, 0) + z(1, 1);
    Some(((east - west) / (8.0 * d), (north - south) / (8.0 * d)))
}

/// The shade of every cell of `dem` in `[0, 1]` (row by row from the top),
/// `None` without data.
pub fn hillshade(dem: &Raster, sun: Sun) -> Vec<Option<f64>> {
    let (azimuth, altitude) = (sun.azimuth_deg.to_radians(), sun.altitude_deg.to_radians());
    let light = (
        altitude.cos() * azimuth.sin(),
        altitude.cos() * azimuth.cos(),
        altitude.sin(),
    );
    (0..dem.rows() * dem.columns())
        .map(|k| {
            let (zx, zy) = gradient(dem, k / dem.columns(), k % dem.columns())?;
            let norm = (zx * zx + zy * zy + 1.0).sqrt();
            Some(((-zx * light.0 - zy * light.1 + light.2) / norm).max(0.0))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plane_is_shaded_by_the_cosine_of_its_angle_to_the_sun() {
        // Rising 30° towards the east, with a no-data cell in its middle.
        let tan = 30f64.to_radians().tan();
        let (columns, rows) = (8, 6);
        let dem = Raster::from_fn(columns, rows, 10.0, 20.0, 2.0, |x, y| {
            ((x - 15.0).abs() > 1.5 || (y - 25.0).abs() > 1.5).then_some(x * tan)
        })
        .unwrap();
        assert!(dem.values().iter().any(Option::is_none));
        let sun = Sun::default();
        let shade = hillshade(&dem, sun);
        // Normal (−sin 30°, 0, cos 30°); sun (cos 45° sin 315°, cos 45° cos 315°, sin 45°).
        let (a, h) = (315f64.to_radians(), 45f64.to_radians());
        let expected =
            -30f64.to_radians().sin() * h.cos() * a.sin() + 30f64.to_radians().cos() * h.sin();
        let mut inner = 0;
        for r in 1..rows - 1 {
            for c in 1..columns - 1 {
                let near_hole = (0..rows * columns).any(|k| {
                    dem.values()[k].is_none()
                        && (k / columns).abs_diff(r) <= 1
                        && (k % columns).abs_diff(c) <= 1
                });
                if let (Some(s), false) = (shade[r * columns + c], near_hole) {
                    assert!((s - expected).abs() < 1e-12, "{s} against {expected}");
                    inner += 1;
                }
            }
        }
        assert_eq!(inner, 4 * 6 - 9);
        let holes = shade.iter().filter(|s| s.is_none()).count();
        assert_eq!(holes, dem.values().iter().filter(|v| v.is_none()).count());
    }

    #[test]
    fn level_ground_has_the_sun_s_altitude_and_a_face_away_from_it_is_dark() {
        let level = Raster::from_fn(4, 4, 0.0, 0.0, 1.0, |_, _| Some(3.0)).unwrap();
        for s in hillshade(&level, Sun::default()) {
            assert!((s.unwrap() - 45f64.to_radians().sin()).abs() < 1e-15);
        }
        // Falling 60° towards the south-east, away from a sun 10° high in the
        // north-west: in shadow.
        let steep = Raster::from_fn(4, 4, 0.0, 0.0, 1.0, |x, y| Some(2.0 * (y - x))).unwrap();
        let sun = Sun {
            azimuth_deg: 315.0,
            altitude_deg: 10.0,
        };
        assert_eq!(hillshade(&steep, sun)[5], Some(0.0));
        // A gradient of +2 northwards and −2 eastwards.
        let (zx, zy) = gradient(&steep, 1, 1).unwrap();
        assert!((zx + 2.0).abs() < 1e-12 && (zy - 2.0).abs() < 1e-12);
    }
}
