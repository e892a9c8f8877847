//! The numbering of a scene's particles, for the speed of the explicit
//! step: the physics does not depend on it, the memory traffic does.
//!
//! The explicit driver sums the contact forces by blocks of 1024
//! consecutive particle indices and adds a pair whose two particles lie in
//! different blocks in a pass of its own; and it goes down the list of
//! pairs in the order of their first particle, reading the second from
//! wherever its index puts it. A lattice numbered row by row, with rows
//! longer than a block, puts every pair of vertical neighbours across
//! blocks and a row apart in memory. Numbered column by column, a settled
//! packing's columns of particles resting on each other are consecutive
//! indices, and 10⁵ disks in 32 rows ran about 1.13 times as fast as
//! numbered row by row (medians of a few runs on one machine; see the
//! README's throughput section).

use super::{Particle, Scene};

/// Bands are this many mean particle widths high, so that a block of 1024
/// particles is a patch of about 32 × 32 however wide the scene.
const BAND_WIDTHS: f64 = 32.0;

impl Scene {
    /// Renumber the particles so that neighbours have near indices: the
    /// scene is cut into horizontal bands 32 mean particle widths high
    /// (the width of a particle is twice its bounding radius; the bands
    /// start at the lowest centre, the columns at the leftmost), numbered
    /// from the bottom; each band is numbered by columns one mean width
    /// wide, from the left, and each column from the bottom (ties by the
    /// old index). Returns, for each new index, the particle's old index.
    ///
    /// A run of the renumbered scene is the same physics: only the order
    /// of the force sums, and so the last bits, change (and, as in any
    /// granular run, round-off grows over many steps). A scene with a
    /// position that is not finite, or whose mean width is not positive
    /// and finite, is left as it is (the identity is returned).
    pub fn renumber_for_locality(&mut self) -> Vec<usize> {
        let n = self.particles.len();
        let identity = || (0..n).collect::<Vec<_>>();
        let finite = |p: &Particle| p.pose.position.x.is_finite() && p.pose.position.y.is_finite();
        if n == 0 || !self.particles.iter().all(finite) {
            return identity();
        }
        let widths = || {
            self.particles
                .iter()
                .map(|p| 2.0 * p.shape.as_shape().bounding_radius())
        };
        let mut width = widths().sum::<f64>() / n as f64;
        if width.is_infinite() {
            // The sum overflowed: as fractions of the mean instead.
            width = widths().map(|w| w / n as f64).sum();
        }
        if !(width.is_finite() && width > 0.0) {
            return identity();
        }
        let (x0, y0) = self
            .particles
            .iter()
            .fold((f64::INFINITY, f64::INFINITY), |(x, y), p: &Particle| {
                (x.min(p.pose.position.x), y.min(p.pose.position.y))
            });
        let band = BAND_WIDTHS * width;
        // (Band, column, height) of each particle; the casts saturate.
        let keys: Vec<(i64, i64, f64)> = self
            .particles
            .iter()
            .map(|p| {
                let (x, y) = (p.pose.position.x - x0, p.pose.position.y - y0);
                ((y / band).floor() as i64, (x / width).floor() as i64, y)
            })
            .collect();
        let mut old = identity();
        // (The old index breaks ties: the keys are distinct.)
        old.sort_unstable_by(|&i, &j| {
            let (a, b) = (&keys[i], &keys[j]);
            (a.0, a.1)
                .cmp(&(b.0, b.1))
                .then(a.2.total_cmp(&b.2))
                .then(i.cmp(&j))
        });
        let mut before: Vec<Option<Particle>> = std::mem::take(&mut self.particles)
            .into_iter()
            .map(Some)
            .collect();
        self.particles = old.iter().filter_map(|&i| before[i].take()).collect();
        old
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{Point, Vec2};
    use crate::scene::Frame;

    /// A `columns × rows` lattice of disks of diameter 1 at pitch 1,
    /// numbered row by row.
    fn lattice(columns: usize, rows: usize) -> Scene {
        let mut scene = Scene::new(
            Frame::open_box(columns as f64 + 2.0, rows as f64 + 2.0).unwrap(),
            Vec2::new(0.0, -9.81),
        )
        .unwrap();
        for j in 0..rows {
            for i in 0..columns {
                scene
                    .add_circle(Point::new(1.5 + i as f64, 1.5 + j as f64), 0.5, 1000.0)
                    .unwrap();
            }
        }
        scene
    }

    /// A lattice 5 wide and 70 high is numbered in bands of 32 rows (the
    /// last one 6), each column by column: the particle at lattice column
    /// i, row j has the index the bands predict, and the returned indices
    /// are where each particle was.
    #[test]
    fn a_lattice_is_numbered_band_by_band_and_column_by_column() {
        let (columns, rows) = (5, 70);
        let mut scene = lattice(columns, rows);
        let before = scene.particles.clone();
        let old = scene.renumber_for_locality();
        assert_eq!(old.len(), before.len());
        for (new, &was) in old.iter().enumerate() {
            assert_eq!(scene.particles[new], before[was]);
            let (i, j) = (was % columns, was / columns);
            let band = j / 32;
            let band_height = (rows - 32 * band).min(32);
            let expected = band * 32 * columns + i * band_height + (j - 32 * band);
            assert_eq!(new, expected, "column {i}, row {j}");
        }
    }

    /// Lattice neighbours end up near in index: one apart up a column,
    /// at most a band's height across, save the pairs across the bands'
    /// edges.
    #[test]
    fn neighbours_are_near_in_index() {
        let (columns, rows) = (40, 200);
        let mut scene = lattice(columns, rows);
        let old = scene.renumber_for_locality();
        let mut new_of = vec![0; old.len()];
        for (new, &was) in old.iter().enumerate() {
            new_of[was] = new;
        }
        let index = |i: usize, j: usize| new_of[j * columns + i];
        let mut far = 0;
        for j in 0..rows {
            for i in 0..columns {
                if j + 1 < rows && index(i, j).abs_diff(index(i, j + 1)) > 1 {
                    far += 1;
                }
                if i + 1 < columns {
                    assert!(index(i, j).abs_diff(index(i + 1, j)) <= 32);
                }
            }
        }
        // Only the vertical pairs across the 6 inner band edges.
        assert_eq!(far, 6 * columns);
    }

    /// A position that is not a finite number leaves the numbering as it
    /// is.
    #[test]
    fn a_scene_with_a_position_not_finite_is_left_as_it_is() {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let mut scene = lattice(40, 3);
            scene.particles[7].pose.position.y = bad;
            let before = scene.particles.clone();
            assert_eq!(scene.renumber_for_locality(), (0..120).collect::<Vec<_>>());
            assert_eq!(format!("{:?}", scene.particles), format!("{before:?}"));
        }
    }

    #[test]
    fn an_empty_scene_stays_empty() {
        let mut scene = lattice(0, 0);
        assert!(scene.renumber_for_locality().is_empty());
        assert!(scene.particles.is_empty());
    }
}
