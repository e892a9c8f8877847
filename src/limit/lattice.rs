//! The regular lattices of paper 002: the U-model (half a footing, with a
//! smooth symmetry wall) and the L-model.
//!
//! Radius R, contact angle α = 45°, lattice step s = 2R cos α. Column
//! i = 0 … m−1 (i = 0 touches the loading plate) at x = −i·s; element
//! j = 0 … n−1 of column i at y = s·(2j + (i mod 2)); m even. Every pair of
//! elements at centre distance 2R is in contact with strength C_p. Walls
//! touch the elements whose centres lie at distance R:
//! * base wall x = −(m−1)s − R (column m−1), strength `c_wall` (2C_p);
//! * far wall y = (2n−1)s + R (j = n−1 of the odd columns), strength `c_wall`;
//! * symmetry wall y = −R (j = 0 of the even columns), smooth — U-model only;
//! * loading plate x = R, smooth, moving in −x at unit speed: in the U-model
//!   it touches column-0 elements j = 0 … n'−1, in the L-model all of them.
//!
//! A lattice has at most [`MAX_LATTICE_ELEMENTS`] elements (m × n).

use super::model::{LimitModel, Partner};
use super::LimitError;
use crate::error::{DismechError, Result};
use crate::law::RigidPlastic;
use crate::math::{Point, Vec2};

/// The largest lattice [`Lattice::build`] accepts, in elements (m × n).
///
/// The model, its kinematic LP and Clarabel's factor take about 8 kB per
/// element for a narrow lattice and 13 kB for a square one (peak resident
/// memory of `lattice-limit-load`: 1.5 GB for the L-model at m = 2,
/// n = 10⁵; 1.1 GB at m = n = 300, solved in 86 s), so the cap keeps a
/// solve near 1.5 GB and a few minutes, some 50 times the paper's largest
/// lattice (m = 8, n = 256).
pub const MAX_LATTICE_ELEMENTS: usize = 100_000;

/// Which lattice.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LatticeKind {
    /// Half footing with a smooth symmetry wall; the plate touches `n'`
    /// elements.
    U {
        /// Elements under the plate, n'.
        loaded: usize,
    },
    /// No symmetry wall; the plate touches the whole first column.
    L,
}

/// Parameters of a lattice model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lattice {
    /// U or L.
    pub kind: LatticeKind,
    /// Columns (even).
    pub m: usize,
    /// Elements per column.
    pub n: usize,
    /// Whether elements may rotate.
    pub rolling: bool,
    /// Element–element strength C_p.
    pub cohesion: f64,
    /// Strength of the base and far walls (2C_p in the paper).
    pub wall_cohesion: f64,
    /// Element radius R.
    pub radius: f64,
}

impl Lattice {
    /// The paper's U-model: R = 1, C_p = 1, walls 2C_p.
    pub fn u_model(m: usize, n: usize, loaded: usize, rolling: bool) -> Self {
        Self {
            kind: LatticeKind::U { loaded },
            m,
            n,
            rolling,
            cohesion: 1.0,
            wall_cohesion: 2.0,
            radius: 1.0,
        }
    }

    /// The paper's L-model: R = 1, C_p = 1, walls 2C_p.
    pub fn l_model(m: usize, n: usize, rolling: bool) -> Self {
        Self {
            kind: LatticeKind::L,
            ..Self::u_model(m, n, 0, rolling)
        }
    }

    /// Lattice step s = 2R cos 45°.
    pub fn step(&self) -> f64 {
        2.0 * self.radius * std::f64::consts::FRAC_PI_4.cos()
    }

    /// Length of the loading plate, eqs. (16) and (22):
    /// `4(n_p − 1)R sin α + R` with n_p = n' (U) or n (L).
    pub fn plate_length(&self) -> f64 {
        let loaded = match self.kind {
            LatticeKind::U { loaded } => loaded,
            LatticeKind::L => self.n,
        };
        4.0 * (loaded as f64 - 1.0) * self.radius * std::f64::consts::FRAC_PI_4.sin() + self.radius
    }

    /// Index of element (i, j).
    pub fn element(&self, i: usize, j: usize) -> usize {
        i * self.n + j
    }

    /// Build the model.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for m odd or below 2, n below 1,
    /// n below 2 in the rolling L-model (its one loaded element rolls away
    /// at no load), n' outside `1..=n`, a radius that is not positive or a
    /// negative strength; [`LimitError::LatticeTooLarge`] for more than
    /// [`MAX_LATTICE_ELEMENTS`] elements.
    pub fn build(&self) -> Result<LimitModel> {
        if self.m < 2 || self.m % 2 != 0 {
            return Err(DismechError::InvalidParameter {
                name: "m (columns)",
                value: self.m as f64,
                requirement: "must be even and >= 2",
            });
        }
        if self.n < 1 {
            return Err(DismechError::InvalidParameter {
                name: "n (elements per column)",
                value: self.n as f64,
                requirement: "must be >= 1",
            });
        }
        if self.kind == LatticeKind::L && self.rolling && self.n < 2 {
            // Element (0, 0) touches only the smooth plate and element
            // (1, 0), at 45°: it rolls down along it without slip or
            // opening, and nothing dissipates (limit load zero).
            return Err(DismechError::InvalidParameter {
                name: "n (elements per column) of the rolling L-model",
                value: self.n as f64,
                requirement: "must be >= 2: a column of one element rolls off its neighbour at no load, so the limit load is zero; use n >= 2, fix the rotations (no rolling) or take the U-model",
            });
        }
        if self
            .m
            .checked_mul(self.n)
            .is_none_or(|elements| elements > MAX_LATTICE_ELEMENTS)
        {
            return Err(LimitError::LatticeTooLarge {
                m: self.m,
                n: self.n,
                limit: MAX_LATTICE_ELEMENTS,
            }
            .into());
        }
        if let LatticeKind::U { loaded } = self.kind {
            if loaded < 1 || loaded > self.n {
                return Err(DismechError::InvalidParameter {
                    name: "n' (elements under the plate)",
                    value: loaded as f64,
                    requirement: "must lie in 1..=n",
                });
            }
        }
        let (r, s) = (self.radius, self.step());
        let mut model = LimitModel::new(1e-9 * r.max(1.0))?;
        for i in 0..self.m {
            for j in 0..self.n {
                let y = s * (2 * j + i % 2) as f64;
                model.add_body(Point::new(-(i as f64) * s, y), r, self.rolling)?;
            }
        }
        crate::error::require_positive("element radius R", self.radius)?;
        let inner = RigidPlastic::cohesive(self.cohesion)?;
        let wall = RigidPlastic::cohesive(self.wall_cohesion)?;
        let smooth = RigidPlastic::cohesive(0.0)?;
        // Element–element contacts: column i with column i+1, |Δy| = s.
        for i in 0..self.m - 1 {
            for j in 0..self.n {
                let y = s * (2 * j + i % 2) as f64;
                for jn in j.saturating_sub(1)..(j + 2).min(self.n) {
                    let yn = s * (2 * jn + (i + 1) % 2) as f64;
                    if ((yn - y).abs() - s).abs() < 1e-9 * s {
                        model.add_contact(
                            self.element(i, j),
                            Partner::Body(self.element(i + 1, jn)),
                            inner,
                        )?;
                    }
                }
            }
        }
        let m = self.m as f64;
        let base = model.add_support(
            "base wall",
            Point::new(-(m - 1.0) * s - r, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::zeros(),
        )?;
        for j in 0..self.n {
            model.add_contact(self.element(self.m - 1, j), Partner::Support(base), wall)?;
        }
        let far = model.add_support(
            "far wall",
            Point::new(0.0, (2.0 * self.n as f64 - 1.0) * s + r),
            Vec2::new(0.0, -1.0),
            Vec2::zeros(),
        )?;
        for i in (1..self.m).step_by(2) {
            model.add_contact(self.element(i, self.n - 1), Partner::Support(far), wall)?;
        }
        let loaded = match self.kind {
            LatticeKind::U { loaded } => {
                let symmetry = model.add_support(
                    "symmetry wall",
                    Point::new(0.0, -r),
                    Vec2::new(0.0, 1.0),
                    Vec2::zeros(),
                )?;
                for i in (0..self.m).step_by(2) {
                    model.add_contact(self.element(i, 0), Partner::Support(symmetry), smooth)?;
                }
                loaded
            }
            LatticeKind::L => self.n,
        };
        let plate = model.add_support(
            "loading plate",
            Point::new(r, 0.0),
            Vec2::new(-1.0, 0.0),
            Vec2::new(-1.0, 0.0),
        )?;
        for j in 0..loaded {
            model.add_contact(self.element(0, j), Partner::Support(plate), smooth)?;
        }
        Ok(model)
    }
}
