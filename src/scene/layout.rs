//! Regular fillings of ellipses or circles in an open box, starting without
//! contacts so that they settle under their own weight.
//!
//! A [`Layout`] is a stack of rows of identical particles. The full rows
//! hold `per_row` particles at a horizontal pitch `width / per_row`; in a
//! staggered layout every other row holds `per_row − 1` particles shifted
//! by half a pitch (a running bond), otherwise all rows are full and the
//! particles stand in vertical stacks. Rows start `gap` apart.
//!
//! [`CircleRows`] places a given number of circles in a running bond at a
//! given row pitch, the last row partial and centred (paper 000's
//! Example 1).

use crate::error::{DismechError, Result};
use crate::math::{Point, Vec2};
use crate::scene::{Frame, Scene};

/// A regular filling: identical particles in rows (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layout {
    /// Inner width of the frame (m).
    pub width: f64,
    /// Height of the frame walls (m).
    pub height: f64,
    /// Semi-major axis a (m); equal to `semi_minor` for circles.
    pub semi_major: f64,
    /// Semi-minor axis b (m).
    pub semi_minor: f64,
    /// Angle of the major axis from the horizontal (rad).
    pub angle: f64,
    /// Particles in a full row.
    pub per_row: usize,
    /// Rows alternate `per_row` and `per_row − 1` particles (running bond)
    /// instead of all holding `per_row` (stacks).
    pub staggered: bool,
    /// Number of rows.
    pub rows: usize,
    /// Vertical gap between the rows at the start (m).
    pub gap: f64,
    /// Density (kg/m³).
    pub density: f64,
}

impl Layout {
    /// Half the horizontal and vertical extent of one particle (m).
    pub fn half_extent(&self) -> (f64, f64) {
        ellipse_half_extent(self.semi_major, self.semi_minor, self.angle)
    }

    /// Horizontal distance between neighbours in a row (m).
    pub fn pitch(&self) -> f64 {
        self.width / self.per_row as f64
    }

    /// Centres of the particles, row by row from the bottom.
    pub fn centres(&self) -> Vec<Point> {
        let (_, half_height) = self.half_extent();
        let pitch = self.pitch();
        let mut centres = Vec::new();
        for row in 0..self.rows {
            let y = half_height + self.gap + row as f64 * (2.0 * half_height + self.gap);
            let short = self.staggered && row % 2 == 1;
            let (count, x0) = if short {
                (self.per_row - 1, pitch)
            } else {
                (self.per_row, 0.5 * pitch)
            };
            centres.extend((0..count).map(|k| Point::new(x0 + k as f64 * pitch, y)));
        }
        centres
    }

    /// The scene: the particles at rest in an open box under gravity `g`
    /// (m/s²).
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming the value for fewer than
    /// two particles per row, a layout whose neighbours in a row, or whose
    /// end particles and the side walls, would overlap at the start, rows
    /// higher than the frame, or a bad frame, size or density.
    pub fn scene(&self, g: f64) -> Result<Scene> {
        let (half_width, half_height) = self.half_extent();
        if self.per_row < 2 {
            return Err(DismechError::InvalidParameter {
                name: "particles per row",
                value: self.per_row as f64,
                requirement: "at least 2",
            });
        }
        if self.pitch() < 2.0 * half_width {
            return Err(DismechError::InvalidParameter {
                name: "row pitch (frame width / particles per row)",
                value: self.pitch(),
                requirement: "at least the particle width, so that a row starts without overlaps",
            });
        }
        let top = self.rows as f64 * (2.0 * half_height + self.gap);
        if top > self.height {
            return Err(DismechError::InvalidParameter {
                name: "height of the stacked rows",
                value: top,
                requirement: "at most the frame height",
            });
        }
        let mut scene = Scene::new(
            Frame::open_box(self.width, self.height)?,
            Vec2::new(0.0, -g),
        )?;
        for centre in self.centres() {
            if self.semi_major == self.semi_minor {
                scene.add_circle(centre, self.semi_major, self.density)?;
            } else {
                scene.add_ellipse(
                    centre,
                    self.semi_major,
                    self.semi_minor,
                    self.angle,
                    self.density,
                )?;
            }
        }
        Ok(scene)
    }
}

/// A given number of circles in a running bond: rows alternately of
/// `per_row` and `per_row − 1` circles (the shorter rows shifted by half
/// the pitch `width / per_row`), `row_pitch` apart, the lowest
/// `clearance` above the floor; a partial last row is centred on the slots
/// of its row.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CircleRows {
    /// Number of circles.
    pub count: usize,
    /// Radius (m).
    pub radius: f64,
    /// Inner width of the frame (m).
    pub width: f64,
    /// Height of the frame walls (m).
    pub height: f64,
    /// Circles in a full row.
    pub per_row: usize,
    /// Vertical distance between rows at the start (m).
    pub row_pitch: f64,
    /// Gap between the lowest row and the floor (m).
    pub clearance: f64,
    /// Density (kg/m³).
    pub density: f64,
}

impl CircleRows {
    /// The scene: the circles at rest in an open box under gravity `g`
    /// (m/s²).
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] for a bad frame, radius or
    /// density (from [`Frame::open_box`] and [`Scene::add_circle`]).
    pub fn scene(&self, g: f64) -> Result<Scene> {
        let mut scene = Scene::new(
            Frame::open_box(self.width, self.height)?,
            Vec2::new(0.0, -g),
        )?;
        let pitch = self.width / self.per_row as f64;
        let mut placed = 0;
        let mut row = 0;
        while placed < self.count {
            let full = row % 2 == 0;
            let in_row = if full {
                self.per_row
            } else {
                self.per_row.saturating_sub(1).max(1)
            };
            let n = in_row.min(self.count - placed);
            let y = self.radius + self.clearance + row as f64 * self.row_pitch;
            let first_slot = (in_row - n) / 2;
            for k in 0..n {
                let slot = (first_slot + k) as f64;
                let x = if full {
                    (slot + 0.5) * pitch
                } else {
                    (slot + 1.0) * pitch
                };
                scene.add_circle(Point::new(x, y), self.radius, self.density)?;
            }
            placed += n;
            row += 1;
        }
        Ok(scene)
    }
}

/// Half the horizontal and vertical extent of an ellipse with semi-axes
/// `a`, `b` whose major axis is at `angle` (rad) from the horizontal.
pub fn ellipse_half_extent(a: f64, b: f64, angle: f64) -> (f64, f64) {
    let (s, c) = angle.sin_cos();
    (
        (a * a * c * c + b * b * s * s).sqrt(),
        (a * a * s * s + b * b * c * c).sqrt(),
    )
}
