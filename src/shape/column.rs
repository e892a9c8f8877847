//! The grid column of HPM slope analysis (paper 001): a hexahedron over one
//! square grid cell with vertical sides and bilinear bottom and top faces
//! (eq. 23).

use super::{MassProperties, Shape, ShapeKind};
use crate::error::{require_finite, require_positive, DismechError, Result};
use nalgebra::Point3;

/// A column element over the cell `[x0, x0 + size] × [y0, y0 + size]`; the
/// bottom and top faces are bilinear through their corner heights, given
/// in the order (x0, y0), (x0 + size, y0), (x0 + size, y0 + size),
/// (x0, y0 + size).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Column {
    x0: f64,
    y0: f64,
    size: f64,
    bottom: [f64; 4],
    top: [f64; 4],
}

/// Two-point Gauss rule on [0, 1]: exact for cubics.
const GAUSS: [(f64, f64); 2] = [
    (0.211_324_865_405_187_1, 0.5),
    (0.788_675_134_594_812_9, 0.5),
];

impl Column {
    /// A column; the top must not lie below the bottom at any corner.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming the value for an origin or
    /// corner height that is not finite, a cell size that is not finite and
    /// positive, or a top height below the bottom height at a corner.
    pub fn new(x0: f64, y0: f64, size: f64, bottom: [f64; 4], top: [f64; 4]) -> Result<Self> {
        require_finite("column x0", x0)?;
        require_finite("column y0", y0)?;
        require_positive("column cell size", size)?;
        for k in 0..4 {
            require_finite("column bottom height", bottom[k])?;
            require_finite("column top height", top[k])?;
            if top[k] < bottom[k] {
                return Err(DismechError::InvalidParameter {
                    name: "column top height (below the bottom at a corner)",
                    value: top[k],
                    requirement: "must not be below the bottom height",
                });
            }
        }
        Ok(Self {
            x0,
            y0,
            size,
            bottom,
            top,
        })
    }

    /// The lower-left corner `(x0, y0)` of the cell.
    pub fn origin(&self) -> (f64, f64) {
        (self.x0, self.y0)
    }

    /// Side of the cell (m).
    pub fn size(&self) -> f64 {
        self.size
    }

    /// Corner heights of the bottom face, in the order of [`Column::new`].
    pub fn bottom(&self) -> [f64; 4] {
        self.bottom
    }

    /// Corner heights of the top face, in the order of [`Column::new`].
    pub fn top(&self) -> [f64; 4] {
        self.top
    }

    /// Height of a bilinear face at local coordinates (ξ, η) ∈ [0, 1]².
    fn bilinear(corners: &[f64; 4], xi: f64, eta: f64) -> f64 {
        corners[0] * (1.0 - xi) * (1.0 - eta)
            + corners[1] * xi * (1.0 - eta)
            + corners[2] * xi * eta
            + corners[3] * (1.0 - xi) * eta
    }

    /// Height of the bottom face at (ξ, η).
    pub fn bottom_at(&self, xi: f64, eta: f64) -> f64 {
        Self::bilinear(&self.bottom, xi, eta)
    }

    /// Height of the top face at (ξ, η).
    pub fn top_at(&self, xi: f64, eta: f64) -> f64 {
        Self::bilinear(&self.top, xi, eta)
    }

    /// `∫∫ f(ξ, η, z_b, z_t) dx dy` by 2×2 Gauss points (exact for the
    /// polynomial integrands used here).
    fn integrate(&self, f: impl Fn(f64, f64, f64, f64) -> f64) -> f64 {
        let mut sum = 0.0;
        for &(xi, wx) in &GAUSS {
            for &(eta, wy) in &GAUSS {
                sum += wx * wy * f(xi, eta, self.bottom_at(xi, eta), self.top_at(xi, eta));
            }
        }
        sum * self.size * self.size
    }

    /// Volume (m³).
    pub fn volume(&self) -> f64 {
        self.integrate(|_, _, zb, zt| zt - zb)
    }

    /// Centroid (m).
    pub fn centroid(&self) -> Point3<f64> {
        let v = self.volume();
        let (x0, y0, s) = (self.x0, self.y0, self.size);
        let mx = self.integrate(|xi, _, zb, zt| (x0 + xi * s) * (zt - zb));
        let my = self.integrate(|_, eta, zb, zt| (y0 + eta * s) * (zt - zb));
        let mz = self.integrate(|_, _, zb, zt| 0.5 * (zt * zt - zb * zb));
        Point3::new(mx / v, my / v, mz / v)
    }

    /// The column cut into `count` layers of equal thickness (bottom first),
    /// as HPM splits a column into bottom, middle and top elements (§3).
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming `layer count` when `count`
    /// is 0.
    pub fn layers(&self, count: usize) -> Result<Vec<Column>> {
        require_positive("layer count", count as f64)?;
        let at = |k: usize| {
            let f = k as f64 / count as f64;
            std::array::from_fn::<f64, 4, _>(|c| {
                self.bottom[c] + f * (self.top[c] - self.bottom[c])
            })
        };
        (0..count)
            .map(|k| Column::new(self.x0, self.y0, self.size, at(k), at(k + 1)))
            .collect()
    }
}

impl Shape for Column {
    fn kind(&self) -> ShapeKind {
        ShapeKind::Column
    }
    fn dimension(&self) -> usize {
        3
    }
    fn measure(&self) -> f64 {
        self.volume()
    }
    /// Mass and the moment of inertia about the vertical axis through the
    /// centroid.
    fn mass_properties(&self, density: f64) -> MassProperties {
        let c = self.centroid();
        let (x0, y0, s) = (self.x0, self.y0, self.size);
        let polar = self.integrate(|xi, eta, zb, zt| {
            let (dx, dy) = (x0 + xi * s - c.x, y0 + eta * s - c.y);
            (dx * dx + dy * dy) * (zt - zb)
        });
        MassProperties {
            mass: density * self.volume(),
            inertia: density * polar,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    #[test]
    fn box_column_has_the_box_volume_and_centroid() {
        let c = Column::new(10.0, 20.0, 10.0, [1.0; 4], [5.0; 4]).unwrap();
        assert_relative_eq!(c.volume(), 400.0);
        let g = c.centroid();
        assert_relative_eq!(g.x, 15.0);
        assert_relative_eq!(g.y, 25.0);
        assert_relative_eq!(g.z, 3.0);
        // I_z of a box about its axis: m (a² + b²) / 12.
        assert_relative_eq!(
            c.mass_properties(2.0).inertia,
            800.0 * 200.0 / 12.0,
            max_relative = 1e-12
        );
    }

    #[test]
    fn wedge_column_centroid_is_at_one_third() {
        // Top rises linearly from 0 at x0 to h at x0 + s, flat bottom: a
        // triangular prism whose centroid sits at x = 2s/3, z = h/3.
        let (s, h) = (3.0, 6.0);
        let c = Column::new(0.0, 0.0, s, [0.0; 4], [0.0, h, h, 0.0]).unwrap();
        assert_relative_eq!(c.volume(), 0.5 * s * h * s, max_relative = 1e-12);
        let g = c.centroid();
        assert_relative_eq!(g.x, 2.0 * s / 3.0, max_relative = 1e-12);
        assert_relative_eq!(g.z, h / 3.0, max_relative = 1e-12);
    }

    #[test]
    fn column_with_top_below_bottom_is_refused() {
        assert!(Column::new(0.0, 0.0, 1.0, [1.0; 4], [2.0, 2.0, 0.5, 2.0]).is_err());
    }

    proptest! {
        /// Gauss integration equals a fine midpoint sum, and the layers add
        /// up to the column.
        #[test]
        fn column_volume_and_centroid_match_a_fine_sum_and_layers_add_up(
            bottom in prop::array::uniform4(-5.0f64..0.0), thickness in prop::array::uniform4(0.1f64..5.0), layers in 1usize..8
        ) {
            let top = std::array::from_fn(|k| bottom[k] + thickness[k]);
            let c = Column::new(0.0, 0.0, 2.0, bottom, top).unwrap();
            let n = 400;
            let (mut v, mut mz) = (0.0, 0.0);
            for i in 0..n {
                for j in 0..n {
                    let (xi, eta) = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
                    let (zb, zt) = (c.bottom_at(xi, eta), c.top_at(xi, eta));
                    v += (zt - zb) * 4.0 / (n * n) as f64;
                    mz += 0.5 * (zt * zt - zb * zb) * 4.0 / (n * n) as f64;
                }
            }
            prop_assert!((c.volume() - v).abs() <= 1e-5 * v);
            prop_assert!((c.centroid().z - mz / v).abs() <= 1e-5 * (1.0 + (mz / v).abs()));
            let sum: f64 = c.layers(layers).unwrap().iter().map(|l| l.volume()).sum();
            prop_assert!((sum - c.volume()).abs() <= 1e-12 * c.volume());
        }
    }
}
