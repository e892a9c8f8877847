//! The particle patterns of Examples 2 and 3 (paper Figs. 6(a) and 8(a),
//! both missing from the text), as chosen here.
//!
//! Every particle has the area of Example 1's circle (r = 0.07 m); the
//! ellipses have aspect ratio a/b = 2 (a = 0.099 m, b = 0.0495 m). The frame
//! is 2.0 m wide, as in Example 1. Each pattern is a regular [`Layout`]:
//!
//! | pattern | particles | major axis | rows | full row | pitch / particle width |
//! |---|---|---|---|---|---|
//! | A | flat ellipses | horizontal | running bond | 10 | 1.01 |
//! | B | flat ellipses | horizontal | loose running bond | 8 | 1.26 |
//! | C | circles | – | running bond | 14 | 1.02 |
//! | D | upright ellipses | vertical | running bond | 20 | 1.01 |
//! | E (Example 3) | flat ellipses | horizontal | stacks | 10 | 1.01 |
//!
//! A, C and D are the tight running bond of Example 1 drawn with the three
//! shapes (each is the affine image of the hexagonal packing of circles);
//! B keeps A's flat ellipses but widens the pitch, so that the upper
//! particles sit deeper in the grooves of the row below and the contact
//! angle ω is smaller. E stacks A's flat ellipses straight above each
//! other, so that every row is a horizontal column of particles.

use super::DENSITY;
use dismech::scene::Layout;

/// Radius of the circle with the area of every particle (m).
pub const EQUIVALENT_RADIUS: f64 = 0.07;
/// Aspect ratio a/b of the ellipses.
pub const ASPECT_RATIO: f64 = 2.0;
/// Inner width of the frame (m).
pub const FRAME_WIDTH: f64 = 2.0;
/// Vertical gap between the rows at the start (m).
pub const ROW_GAP: f64 = 0.01;

/// One pattern of particles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pattern {
    /// The paper's letter.
    pub name: &'static str,
    /// What the particles and their arrangement are.
    pub description: &'static str,
    /// Ellipses (a/b = [`ASPECT_RATIO`]) or circles.
    pub ellipse: bool,
    /// Angle of the major axis from the horizontal (degrees).
    pub angle_deg: f64,
    /// Particles in a full row.
    pub per_row: usize,
    /// Running bond (rows alternate `per_row` and `per_row − 1`, shifted by
    /// half a pitch) or stacks (every row full, particles above each other).
    pub staggered: bool,
    /// Number of rows.
    pub rows: usize,
}

impl Pattern {
    /// The layout of this pattern in a frame `FRAME_WIDTH · scale` wide
    /// (`scale` = 1 is the size used for the reproduction; 0.5 is a quick
    /// version with a quarter of the particles).
    pub fn layout(&self, scale: f64) -> Layout {
        let (a, b) = if self.ellipse {
            (
                EQUIVALENT_RADIUS * ASPECT_RATIO.sqrt(),
                EQUIVALENT_RADIUS / ASPECT_RATIO.sqrt(),
            )
        } else {
            (EQUIVALENT_RADIUS, EQUIVALENT_RADIUS)
        };
        let per_row = ((self.per_row as f64 * scale).round() as usize).max(2);
        let rows = ((self.rows as f64 * scale).round() as usize).max(2);
        let mut layout = Layout {
            width: FRAME_WIDTH * per_row as f64 / self.per_row as f64,
            height: 0.0,
            semi_major: a,
            semi_minor: b,
            angle: self.angle_deg.to_radians(),
            per_row,
            staggered: self.staggered,
            rows,
            gap: ROW_GAP,
            density: DENSITY,
        };
        let (_, half_height) = layout.half_extent();
        layout.height = rows as f64 * (2.0 * half_height + ROW_GAP) + 0.1;
        layout
    }
}

/// Patterns A–D of Example 2 (Fig. 6(a)).
pub const EXAMPLE2: [Pattern; 4] = [
    Pattern {
        name: "A",
        description: "flat ellipses (a/b = 2, major axis horizontal), running bond",
        ellipse: true,
        angle_deg: 0.0,
        per_row: 10,
        staggered: true,
        rows: 18,
    },
    Pattern {
        name: "B",
        description: "flat ellipses (a/b = 2, major axis horizontal), loose running bond",
        ellipse: true,
        angle_deg: 0.0,
        per_row: 8,
        staggered: true,
        rows: 22,
    },
    Pattern {
        name: "C",
        description: "circles (r = 0.07 m), running bond",
        ellipse: false,
        angle_deg: 0.0,
        per_row: 14,
        staggered: true,
        rows: 13,
    },
    Pattern {
        name: "D",
        description: "upright ellipses (a/b = 2, major axis vertical), running bond",
        ellipse: true,
        angle_deg: 90.0,
        per_row: 20,
        staggered: true,
        rows: 9,
    },
];

/// Pattern E of Example 3 (Fig. 8(a)); A–D are those of Example 2.
pub const PATTERN_E: Pattern = Pattern {
    name: "E",
    description: "flat ellipses (a/b = 2, major axis horizontal), stacks",
    ellipse: true,
    angle_deg: 0.0,
    per_row: 10,
    staggered: false,
    rows: 17,
};
