//! The trial family a command line asks for: each option as given, or a
//! default derived from the DEM's extent (its cell size d and its shorter
//! side L), so that a DEM alone gives a search whose surfaces span a few
//! cells to a good part of the terrain.

use dismech::slope::{EllipsoidRandom, SphereGrid, Steps, Terrain};

use super::args::{SearchKind, SlopeArgs, Span};
use super::error::SlopeError;

/// Sphere centres about this many to a side of the DEM by default.
const DEFAULT_CENTRES_A_SIDE: usize = 25;
/// Radii of the default sphere grid.
const DEFAULT_RADII: usize = 10;
/// Heights of the default sphere grid.
const DEFAULT_HEIGHTS: usize = 6;

/// The DEM's cell size and shorter side, the scales of the defaults.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extent {
    /// Rows and columns.
    pub rows: usize,
    /// Columns.
    pub columns: usize,
    /// Cell size d (m).
    pub cell: f64,
}

impl Extent {
    /// The extent of `terrain`.
    pub fn of(terrain: &Terrain) -> Self {
        Self {
            rows: terrain.rows(),
            columns: terrain.columns(),
            cell: terrain.cell_size(),
        }
    }

    /// The shorter side L (m).
    pub fn shorter_side(&self) -> f64 {
        self.rows.min(self.columns) as f64 * self.cell
    }

    /// `(width, height)` (m).
    pub fn size(&self) -> (f64, f64) {
        (
            self.columns as f64 * self.cell,
            self.rows as f64 * self.cell,
        )
    }
}

/// The family a command line asks for, with its defaults filled in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Family {
    /// Scoops3D's sphere grid.
    Spheres(SphereGrid),
    /// r.slope.stability's random ellipsoids.
    Ellipsoids(EllipsoidRandom),
}

/// The default sphere grid over `extent`: a centre every L/25 (at least
/// every cell), heights from d to L/4 (6), radii from 4 d to L/3 (10).
pub fn default_sphere_grid(extent: &Extent) -> SphereGrid {
    let (d, l) = (extent.cell, extent.shorter_side());
    SphereGrid {
        stride: (extent.rows.min(extent.columns) / DEFAULT_CENTRES_A_SIDE).max(1),
        heights: Steps {
            min: d,
            max: (l / 4.0).max(d),
            count: DEFAULT_HEIGHTS,
        },
        radii: Steps {
            min: 4.0 * d,
            max: (l / 3.0).max(4.0 * d),
            count: DEFAULT_RADII,
        },
    }
}

/// The default random ellipsoids over `extent` (`count` of them, seed
/// `seed`): heights from 0 to L/40, semi-axes along from 4 d to L/4,
/// across 0.5 to 1 times that (`--across-ratio`'s default), vertical from
/// d to L/20: slides from about a tenth as deep as long to as deep as
/// wide, not the narrow shafts that Hovland's columns, with no side
/// resistance, find far weaker than the ground around them.
pub fn default_ellipsoids(extent: &Extent, count: u64, seed: u64) -> EllipsoidRandom {
    let (d, l) = (extent.cell, extent.shorter_side());
    EllipsoidRandom {
        count,
        seed,
        heights: (0.0, l / 40.0),
        along: (4.0 * d, (l / 4.0).max(4.0 * d)),
        across_ratio: (0.5, 1.0),
        vertical: (d, (l / 20.0).max(d)),
    }
}

/// Options given that the chosen family does not use (refused rather than
/// silently ignored).
fn refuse_unused(args: &SlopeArgs) -> Result<(), SlopeError> {
    let (family, unused): (&str, Vec<(&'static str, Option<String>)>) = match args.search {
        SearchKind::Spheres => (
            "spheres",
            vec![
                ("--along", args.along.map(|s| s.to_string())),
                ("--vertical", args.vertical.map(|s| s.to_string())),
            ],
        ),
        SearchKind::Ellipsoids => (
            "ellipsoids",
            vec![
                ("--stride", args.stride.map(|s| s.to_string())),
                ("--radii", args.radii.map(|s| s.to_string())),
                (
                    "--heights",
                    args.heights
                        .filter(|h| h.count.is_some())
                        .map(|s| s.to_string()),
                ),
            ],
        ),
    };
    for (flag, value) in unused {
        if let Some(value) = value {
            return Err(SlopeError::Unused {
                flag,
                value,
                family,
            });
        }
    }
    Ok(())
}

/// The family of `args` over `terrain`, defaults filled in from its
/// extent, checked by the library.
///
/// # Errors
/// [`SlopeError::Unused`] for an option of the other family (or a COUNT in
/// `--heights` for ellipsoids); [`SlopeError::Argument`] for a stride that
/// leaves no sphere centre on the DEM; [`SlopeError::Run`] for a family
/// the library refuses (the options are checked as they are parsed).
pub fn family(args: &SlopeArgs, terrain: &Terrain) -> Result<Family, SlopeError> {
    refuse_unused(args)?;
    let extent = Extent::of(terrain);
    match args.search {
        SearchKind::Spheres => {
            let mut grid = default_sphere_grid(&extent);
            if let Some(stride) = args.stride {
                grid.stride = stride;
            }
            if let Some(h) = args.heights {
                grid.heights = h.steps(DEFAULT_HEIGHTS);
            }
            if let Some(r) = args.radii {
                grid.radii = r.steps(DEFAULT_RADII);
            }
            // Each option was checked as it was parsed; the library checks
            // the defaults with them.
            let grid = SphereGrid::new(grid.stride, grid.heights, grid.radii)?;
            let first = grid.stride / 2;
            if first >= extent.rows || first >= extent.columns {
                return Err(SlopeError::argument(
                    "--stride",
                    &grid.stride.to_string(),
                    dismech::error::DismechError::InvalidParameter {
                        name: "sphere grid stride (cells)",
                        value: grid.stride as f64,
                        requirement:
                            "leaves no sphere centre on the DEM: the first centre is at cell stride/2, which must lie inside its rows and columns",
                    },
                ));
            }
            Ok(Family::Spheres(grid))
        }
        SearchKind::Ellipsoids => {
            let mut e = default_ellipsoids(&extent, args.count, args.seed);
            if let Some(h) = args.heights {
                e.heights = h.pair();
            }
            if let Some(a) = args.along {
                e.along = a.pair();
            }
            e.across_ratio = args.across_ratio.pair();
            if let Some(v) = args.vertical {
                e.vertical = v.pair();
            }
            let e = EllipsoidRandom::new(
                e.count,
                e.seed,
                e.heights,
                e.along,
                e.across_ratio,
                e.vertical,
            )?;
            Ok(Family::Ellipsoids(e))
        }
    }
}

/// The family's values as the options that give it, for the summary.
pub fn describe(family: &Family) -> String {
    let range = |(a, b): (f64, f64)| Span {
        min: a,
        max: b,
        count: None,
    };
    let steps = |s: &Steps| Span {
        min: s.min,
        max: s.max,
        count: Some(s.count),
    };
    match family {
        Family::Spheres(g) => format!(
            "--search spheres --stride {} --heights {} --radii {}",
            g.stride,
            steps(&g.heights),
            steps(&g.radii)
        ),
        Family::Ellipsoids(e) => format!(
            "--search ellipsoids --count {} --seed {} --heights {} --along {} --across-ratio {} --vertical {}",
            e.count,
            e.seed,
            range(e.heights),
            range(e.along),
            range(e.across_ratio),
            range(e.vertical)
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_scale_with_the_dem() {
        let extent = Extent {
            rows: 100,
            columns: 120,
            cell: 75.0,
        };
        assert_eq!(extent.shorter_side(), 7500.0);
        let g = default_sphere_grid(&extent);
        assert_eq!(g.stride, 4);
        assert_eq!((g.heights.min, g.heights.max), (75.0, 1875.0));
        assert_eq!(
            (g.radii.min, g.radii.max, g.radii.count),
            (300.0, 2500.0, 10)
        );
        let e = default_ellipsoids(&extent, 10, 3);
        assert_eq!(e.along, (300.0, 1875.0));
        assert_eq!(e.vertical, (75.0, 375.0));
        assert_eq!(e.heights, (0.0, 187.5));
        // A small DEM: a centre at every cell, ranges that stay ranges.
        let small = Extent {
            rows: 5,
            columns: 5,
            cell: 1.0,
        };
        let g = default_sphere_grid(&small);
        assert_eq!(g.stride, 1);
        assert!(g.radii.min <= g.radii.max && g.heights.min <= g.heights.max);
        assert!(SphereGrid::new(g.stride, g.heights, g.radii).is_ok());
    }
}
