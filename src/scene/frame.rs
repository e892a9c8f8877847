//! A rigid frame: a chain of wall segments.

use crate::error::{require_positive, DismechError, Result};
use crate::math::{Aabb2, Point};
use crate::shape::Segment;

/// Walls joined end to end, material on their left (a frame is drawn
/// counter-clockwise around what it holds). A frame may be open (a box
/// without a lid) but must not leave gaps between consecutive walls.
///
/// Serialized as its named walls; read back through [`Frame::from_walls`],
/// which checks them.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "FrameRecord", into = "FrameRecord")]
pub struct Frame {
    walls: Vec<Segment>,
    names: Vec<String>,
}

/// A frame as serialized: its walls with their names.
#[derive(serde::Serialize, serde::Deserialize)]
struct FrameRecord {
    walls: Vec<(String, Segment)>,
}

impl From<Frame> for FrameRecord {
    fn from(frame: Frame) -> Self {
        Self {
            walls: frame.names.into_iter().zip(frame.walls).collect(),
        }
    }
}

impl TryFrom<FrameRecord> for Frame {
    type Error = DismechError;
    fn try_from(record: FrameRecord) -> Result<Self> {
        Self::from_walls(record.walls)
    }
}

/// Largest gap (m) accepted between the end of one wall and the start of the
/// next.
pub const JOINT_TOLERANCE: f64 = 1e-9;

impl Frame {
    /// A frame from named walls; each wall must start where the previous one
    /// ends (within [`JOINT_TOLERANCE`]), have finite end points and a
    /// positive length.
    ///
    /// # Errors
    /// [`DismechError::DegenerateWall`] naming the wall for an end point
    /// that is not finite or a length of at most [`JOINT_TOLERANCE`];
    /// [`DismechError::FrameNotClosed`] naming both walls and the gap when
    /// a wall does not start within [`JOINT_TOLERANCE`] of where the
    /// previous one ends.
    pub fn from_walls(walls: Vec<(String, Segment)>) -> Result<Self> {
        for (i, (_, w)) in walls.iter().enumerate() {
            let finite = [w.start.x, w.start.y, w.end.x, w.end.y]
                .iter()
                .all(|v| v.is_finite());
            if !finite {
                return Err(DismechError::DegenerateWall {
                    wall: i,
                    reason: "an end point is not finite",
                });
            }
            if w.length() <= JOINT_TOLERANCE {
                return Err(DismechError::DegenerateWall {
                    wall: i,
                    reason: "its length is zero",
                });
            }
        }
        for i in 1..walls.len() {
            let (end, start) = (walls[i - 1].1.end, walls[i].1.start);
            let gap = (end - start).norm();
            if gap > JOINT_TOLERANCE {
                return Err(DismechError::FrameNotClosed {
                    wall: i - 1,
                    next: i,
                    end_x: end.x,
                    end_y: end.y,
                    start_x: start.x,
                    start_y: start.y,
                    gap,
                });
            }
        }
        let (names, walls) = walls.into_iter().unzip();
        Ok(Self { walls, names })
    }

    /// An open box `width × height` with its bottom-left corner at the
    /// origin: walls `left` (top to bottom), `bottom`, `right` (bottom to
    /// top).
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming `frame width` or
    /// `frame height` when either is not finite and positive;
    /// [`DismechError::DegenerateWall`] when one is no longer than
    /// [`JOINT_TOLERANCE`].
    pub fn open_box(width: f64, height: f64) -> Result<Self> {
        require_positive("frame width", width)?;
        require_positive("frame height", height)?;
        let (a, b, c, d) = (
            Point::new(0.0, height),
            Point::new(0.0, 0.0),
            Point::new(width, 0.0),
            Point::new(width, height),
        );
        Self::from_walls(vec![
            ("left".into(), Segment::new(a, b)),
            ("bottom".into(), Segment::new(b, c)),
            ("right".into(), Segment::new(c, d)),
        ])
    }

    /// Whether the walls run clockwise: the polygon they close (the last
    /// wall's end joined to the first wall's start) has a negative signed
    /// area, so the material on their left lies outside. A frame around an
    /// obstacle in a flow is drawn so; one meant to hold particles is not.
    pub fn runs_clockwise(&self) -> bool {
        let area2: f64 = self
            .walls
            .iter()
            .map(|w| w.start.x * w.end.y - w.end.x * w.start.y)
            .sum::<f64>()
            + self
                .walls
                .last()
                .zip(self.walls.first())
                .map_or(0.0, |(last, first)| {
                    last.end.x * first.start.y - first.start.x * last.end.y
                });
        area2 < 0.0
    }

    /// The walls.
    pub fn walls(&self) -> &[Segment] {
        &self.walls
    }

    /// The box spanned by the walls, `None` for a frame without walls.
    pub fn bounding_box(&self) -> Option<Aabb2> {
        let boxes = self
            .walls
            .iter()
            .map(|w| Aabb2::from_corners(w.start, w.end));
        boxes.reduce(|a, b| a.merged(&b))
    }

    /// The name of wall `i` (`None` if there is no such wall).
    pub fn name(&self, i: usize) -> Option<&str> {
        self.names.get(i).map(String::as_str)
    }

    /// Index of the wall named `name`.
    pub fn index_of(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n == name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_with_a_gap_is_refused_with_the_gap() {
        let err = Frame::from_walls(vec![
            (
                "a".into(),
                Segment::new(Point::new(0.0, 1.0), Point::new(0.0, 0.0)),
            ),
            (
                "b".into(),
                Segment::new(Point::new(0.01, 0.0), Point::new(1.0, 0.0)),
            ),
        ])
        .unwrap_err();
        match err {
            DismechError::FrameNotClosed {
                wall: 0,
                next: 1,
                gap,
                ..
            } => {
                approx::assert_relative_eq!(gap, 0.01)
            }
            other => panic!("unexpected {other}"),
        }
    }

    #[test]
    fn open_box_walls_face_inwards() {
        let f = Frame::open_box(2.0, 1.0).unwrap();
        let bottom = f.walls()[f.index_of("bottom").unwrap()];
        approx::assert_relative_eq!(bottom.inner_normal().y, 1.0);
        let left = f.walls()[f.index_of("left").unwrap()];
        approx::assert_relative_eq!(left.inner_normal().x, 1.0);
    }
}
