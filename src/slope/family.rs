//! Families of trial surfaces a search runs through, each trial given by
//! its index alone (so that any worker can make any trial, and the result
//! does not depend on which worker made it): Scoops3D's systematic grid of
//! sphere centres and radii (Reid, Christian & Brien, USGS 2015) and
//! r.slope.stability's random sampling (Mergili et al. 2014), of spheres
//! and of ellipsoids along the fall line.

use super::error::SlopeError;
use crate::error::{require_finite, require_positive, DismechError, Result};

use super::surface::{Ellipsoid, Refusal, Sphere, TrialSurface};
use super::terrain::Terrain;

/// A family of trial surfaces over a terrain, indexed `0..len`.
pub trait TrialFamily: Sync {
    /// The kind of surface.
    type Surface: TrialSurface + Copy + Send + Sync + std::fmt::Debug;

    /// Check the family's values (its fields are public: [`crate::slope::search`]
    /// checks them again before the first trial).
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] or [`SlopeError::InvalidRange`]
    /// naming the offending value, as the family's constructor.
    fn validate(&self) -> Result<()>;

    /// The number of trials over `terrain`.
    fn len(&self, terrain: &Terrain) -> u64;

    /// Whether the family has no trial over `terrain`.
    fn is_empty(&self, terrain: &Terrain) -> bool {
        self.len(terrain) == 0
    }

    /// Trial `index` (below [`Self::len`]).
    ///
    /// # Errors
    /// (A refusal, not a [`crate::error::DismechError`].)
    /// [`Refusal::CentreOffDem`] when its centre lies over no ground data.
    fn trial(&self, terrain: &Terrain, index: u64) -> std::result::Result<Self::Surface, Refusal>;
}

/// `count` values evenly spaced from `min` to `max` (both included; one
/// value is `min`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Steps {
    /// The first value.
    pub min: f64,
    /// The last value.
    pub max: f64,
    /// How many (≥ 1).
    pub count: usize,
}

impl Steps {
    /// The values `min..=max` in `count` steps, checked.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] named `name` for a bound that is
    /// not finite (or not positive, where `positive`) or no value;
    /// [`SlopeError::InvalidRange`] for `min > max`.
    pub fn checked(
        name: &'static str,
        min: f64,
        max: f64,
        count: usize,
        positive: bool,
    ) -> Result<Self> {
        let steps = Self { min, max, count };
        steps.validate(name, positive)?;
        Ok(steps)
    }

    /// Check the values, as [`Steps::checked`].
    ///
    /// # Errors
    /// As [`Steps::checked`].
    pub fn validate(&self, name: &'static str, positive: bool) -> Result<()> {
        check_interval(name, self.min, self.max, positive)?;
        require_positive(name, self.count as f64).map_err(|_| DismechError::InvalidParameter {
            name,
            value: self.count as f64,
            requirement: "the number of values must be at least 1",
        })?;
        Ok(())
    }

    /// Value `i` (below `count`).
    pub fn value(&self, i: usize) -> f64 {
        if self.count <= 1 {
            self.min
        } else {
            self.min + (self.max - self.min) * i as f64 / (self.count - 1) as f64
        }
    }
}

/// `min <= max`, both finite (and positive where `positive`).
fn check_interval(name: &'static str, min: f64, max: f64, positive: bool) -> Result<()> {
    if positive {
        require_positive(name, min)?;
        require_positive(name, max)?;
    } else {
        require_finite(name, min)?;
        require_finite(name, max)?;
    }
    if min > max {
        return Err(DismechError::Slope(SlopeError::InvalidRange {
            name,
            low: min,
            high: max,
        }));
    }
    Ok(())
}

/// Scoops3D's systematic search: sphere centres over every `stride`-th
/// cell in each direction (from cell `stride / 2`), at each of `heights`
/// above the ground of that cell, with each of `radii`. Trial index
/// `((centre × heights) + height) × radii + radius`, centres row by row
/// from the top.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphereGrid {
    /// Cells between neighbouring centres (≥ 1).
    pub stride: usize,
    /// Heights of the centre above the ground of its cell (m).
    pub heights: Steps,
    /// Radii (m, > 0).
    pub radii: Steps,
}

impl SphereGrid {
    /// A grid search, checked.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming the value for a stride of
    /// 0, heights that are not finite, radii that are not finite and
    /// positive, or no height or radius; [`SlopeError::InvalidRange`] for
    /// a range whose minimum lies above its maximum.
    pub fn new(stride: usize, heights: Steps, radii: Steps) -> Result<Self> {
        require_positive("sphere grid stride (cells)", stride as f64)?;
        heights.validate("sphere grid heights above the ground", false)?;
        radii.validate("sphere grid radius range", true)?;
        Ok(Self {
            stride,
            heights,
            radii,
        })
    }

    fn centres(&self, n: usize) -> usize {
        let first = self.stride / 2;
        if first >= n {
            0
        } else {
            (n - 1 - first) / self.stride + 1
        }
    }
}

impl TrialFamily for SphereGrid {
    type Surface = Sphere;

    fn validate(&self) -> Result<()> {
        Self::new(self.stride, self.heights, self.radii).map(|_| ())
    }

    fn len(&self, terrain: &Terrain) -> u64 {
        (self.centres(terrain.rows()) as u64)
            .saturating_mul(self.centres(terrain.columns()) as u64)
            .saturating_mul(self.heights.count as u64)
            .saturating_mul(self.radii.count as u64)
    }

    fn trial(&self, terrain: &Terrain, index: u64) -> std::result::Result<Sphere, Refusal> {
        let radii = self.radii.count as u64;
        let heights = self.heights.count as u64;
        let radius = self.radii.value((index % radii) as usize);
        let rest = index / radii;
        let height = self.heights.value((rest % heights) as usize);
        let centre = rest / heights;
        let across = self.centres(terrain.columns()) as u64;
        let first = self.stride / 2;
        let row = first + (centre / across) as usize * self.stride;
        let column = first + (centre % across) as usize * self.stride;
        let ground = terrain.ground(row, column).ok_or(Refusal::CentreOffDem)?;
        let (x, y) = terrain.dem().raster.cell_centre(row, column);
        Ok(Sphere {
            x,
            y,
            z: ground + height,
            radius,
        })
    }
}

/// SplitMix64 (Steele, Lea & Flood 2014): a small, fast generator whose
/// stream for a trial depends on the seed and the trial's index alone.
#[derive(Debug, Clone, Copy)]
struct SplitMix64(u64);

impl SplitMix64 {
    fn for_trial(seed: u64, index: u64) -> Self {
        let mut s = Self(seed ^ index.wrapping_mul(0xD1B5_4A32_D192_ED03));
        s.next();
        s
    }

    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in [lo, hi].
    fn between(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

/// A random point of the grid's plan extent, and its cell's ground.
fn random_centre(
    terrain: &Terrain,
    rng: &mut SplitMix64,
) -> std::result::Result<(f64, f64, f64, (usize, usize)), Refusal> {
    let (x0, y0) = terrain.dem().raster.lower_left();
    let d = terrain.cell_size();
    let x = x0 + rng.unit() * terrain.columns() as f64 * d;
    let y = y0 + rng.unit() * terrain.rows() as f64 * d;
    let cell = terrain.cell_at(x, y).ok_or(Refusal::CentreOffDem)?;
    let ground = terrain
        .ground(cell.0, cell.1)
        .ok_or(Refusal::CentreOffDem)?;
    Ok((x, y, ground, cell))
}

/// r.slope.stability's random sampling, with spheres: `count` trials,
/// each with its centre uniform over the grid's plan extent, its height
/// uniform in `heights` above the ground of the cell under it, and its
/// radius uniform in `radii`; trial `i` draws from a generator seeded with
/// `seed` and `i` alone.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphereRandom {
    /// Number of trials.
    pub count: u64,
    /// Seed of the generator.
    pub seed: u64,
    /// Range of the centre's height above the ground (m), `(min, max)`.
    pub heights: (f64, f64),
    /// Range of the radius (m), `(min, max)`.
    pub radii: (f64, f64),
}

impl SphereRandom {
    /// A random search, checked.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming the value for no trial,
    /// heights that are not finite or radii that are not finite and
    /// positive; [`SlopeError::InvalidRange`] for a range whose minimum
    /// lies above its maximum.
    pub fn new(count: u64, seed: u64, heights: (f64, f64), radii: (f64, f64)) -> Result<Self> {
        require_positive("random search: number of trials", count as f64)?;
        check_interval(
            "random search: height range above the ground",
            heights.0,
            heights.1,
            false,
        )?;
        check_interval("random search: radius range", radii.0, radii.1, true)?;
        Ok(Self {
            count,
            seed,
            heights,
            radii,
        })
    }
}

impl TrialFamily for SphereRandom {
    type Surface = Sphere;

    fn validate(&self) -> Result<()> {
        Self::new(self.count, self.seed, self.heights, self.radii).map(|_| ())
    }

    fn len(&self, _terrain: &Terrain) -> u64 {
        self.count
    }

    fn trial(&self, terrain: &Terrain, index: u64) -> std::result::Result<Sphere, Refusal> {
        let mut rng = SplitMix64::for_trial(self.seed, index);
        let (x, y, ground, _) = random_centre(terrain, &mut rng)?;
        let height = rng.between(self.heights.0, self.heights.1);
        let radius = rng.between(self.radii.0, self.radii.1);
        Ok(Sphere {
            x,
            y,
            z: ground + height,
            radius,
        })
    }
}

/// r.slope.stability's random ellipsoids (Mergili et al. 2014), not
/// tilted: `count` trials, each with its centre uniform over the grid's
/// plan extent and its height uniform in `heights` above the ground of the
/// cell under it; semi-axes uniform in `along`, `across_ratio × along` and
/// `vertical`; the long axis along the ground's fall line at the centre
/// cell ([`Terrain::fall_line`]; +x where the ground is level there).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EllipsoidRandom {
    /// Number of trials.
    pub count: u64,
    /// Seed of the generator.
    pub seed: u64,
    /// Range of the centre's height above the ground (m).
    pub heights: (f64, f64),
    /// Range of the semi-axis along the fall line (m).
    pub along: (f64, f64),
    /// Range of the ratio of the semi-axis across to the one along.
    pub across_ratio: (f64, f64),
    /// Range of the vertical semi-axis (m).
    pub vertical: (f64, f64),
}

impl EllipsoidRandom {
    /// A random search of ellipsoids, checked.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming the value for no trial,
    /// heights that are not finite or semi-axes or ratios that are not
    /// finite and positive; [`SlopeError::InvalidRange`] for a range
    /// whose minimum lies above its maximum.
    pub fn new(
        count: u64,
        seed: u64,
        heights: (f64, f64),
        along: (f64, f64),
        across_ratio: (f64, f64),
        vertical: (f64, f64),
    ) -> Result<Self> {
        require_positive("random ellipsoids: number of trials", count as f64)?;
        check_interval(
            "random ellipsoids: height range",
            heights.0,
            heights.1,
            false,
        )?;
        check_interval("random ellipsoids: semi-axis along", along.0, along.1, true)?;
        check_interval(
            "random ellipsoids: ratio across/along",
            across_ratio.0,
            across_ratio.1,
            true,
        )?;
        check_interval(
            "random ellipsoids: vertical semi-axis",
            vertical.0,
            vertical.1,
            true,
        )?;
        Ok(Self {
            count,
            seed,
            heights,
            along,
            across_ratio,
            vertical,
        })
    }
}

impl TrialFamily for EllipsoidRandom {
    type Surface = Ellipsoid;

    fn validate(&self) -> Result<()> {
        Self::new(
            self.count,
            self.seed,
            self.heights,
            self.along,
            self.across_ratio,
            self.vertical,
        )
        .map(|_| ())
    }

    fn len(&self, _terrain: &Terrain) -> u64 {
        self.count
    }

    fn trial(&self, terrain: &Terrain, index: u64) -> std::result::Result<Ellipsoid, Refusal> {
        let mut rng = SplitMix64::for_trial(self.seed, index);
        let (x, y, ground, (row, column)) = random_centre(terrain, &mut rng)?;
        let height = rng.between(self.heights.0, self.heights.1);
        let along = rng.between(self.along.0, self.along.1);
        let across = along * rng.between(self.across_ratio.0, self.across_ratio.1);
        let vertical = rng.between(self.vertical.0, self.vertical.1);
        let (fx, fy) = terrain.fall_line(row, column).unwrap_or((1.0, 0.0));
        Ok(Ellipsoid {
            x,
            y,
            z: ground + height,
            along,
            across,
            vertical,
            azimuth: fy.atan2(fx),
        })
    }
}
