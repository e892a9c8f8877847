//! Ground as it is: strength layers bounded below by elevation rasters,
//! and pore pressure from a pore-pressure ratio r_u as an alternative to
//! the water table.
//!
//! **Layers.** The ground is a stack of [`Layer`]s, top to bottom, each
//! with its own Mohr–Coulomb strength and unit weight
//! ([`SlopeMaterial`]) and bounded below by an elevation raster on the
//! DEM's grid (the last layer unbounded below). At a cell, a bottom that
//! lies above the ground, or above the bottom of the layer above, is
//! clipped to it: the layer pinches out there (thickness 0). For a column
//! of a trial surface with ground `g` and base `b` at the cell centre:
//!
//! - its vertical stress at the base is `σ_v = Σ_i γ_i t_i`, with `t_i`
//!   the thickness of layer i between the base and the ground, summed top
//!   to bottom (the weight of the column is `σ_v d²`);
//! - its base strength (c, μ) is that of the layer the slip surface passes
//!   through at the cell centre, the first layer from the top whose
//!   (clipped) bottom lies strictly below the base (a base exactly on a
//!   boundary takes the strength of the layer below). This is Scoops3D's
//!   convention (Reid, Christian & Brien, USGS Techniques and Methods
//!   14-A1, 2015: the strength of the layer containing the base of each
//!   column, the weight from every layer above it).
//!
//! One material ([`SlopeMaterial`]) is a one-layer ground
//! ([`Ground::from`]), and gives exactly the results of the single
//! material: `σ_v = γ (g − b)` with the same floating-point operations.
//!
//! **Pore-pressure ratio.** With a pore-pressure ratio r_u (Bishop &
//! Morgenstern, Géotechnique 10(4), 1960), the pore pressure on the base
//! of a column is `u = r_u σ_v`, with `σ_v` the layered vertical stress
//! above. It is a constant or a raster on the DEM's grid
//! ([`PoreRatio`]), each value in `[0, 1)`, and replaces the water table:
//! a terrain with a water table and a ground with r_u together are an
//! error ([`crate::slope::SlopeError::PorePressureTwice`]).

use super::error::SlopeError;
use crate::error::{DismechError, Result};
use crate::hpm::NamedRaster;

use super::layer_problem::LayerProblem;
use super::material::SlopeMaterial;
use super::terrain::Terrain;

/// One strength layer of the ground: its material and the elevation of
/// its bottom.
#[derive(Debug, Clone, PartialEq)]
pub struct Layer {
    /// The layer's name (errors name it).
    pub name: String,
    /// Elevation of the layer's bottom (m) at each cell centre, on the
    /// DEM's grid; `None` for the last layer, unbounded below. A cell where
    /// the bottom lies above the ground or above the layer above is
    /// clipped to it. A no-data cell is allowed only where no trial
    /// surface needs the layer's bottom (a column there is refused,
    /// [`super::Refusal::NoData`]).
    pub bottom: Option<NamedRaster>,
    /// The layer's strength and unit weight.
    pub material: SlopeMaterial,
}

impl Layer {
    /// [`SlopeError::InvalidLayer`] naming this layer, for `problem`.
    fn invalid(&self, problem: LayerProblem) -> DismechError {
        DismechError::Slope(SlopeError::InvalidLayer {
            layer: self.name.clone(),
            problem,
        })
    }

    /// Its material checked ([`SlopeMaterial::validate`]); a failure is
    /// [`LayerProblem::Material`] naming the layer.
    fn check_material(&self) -> Result<()> {
        self.material
            .validate()
            .map_err(|e| self.invalid(LayerProblem::Material(Box::new(e))))
    }
}

/// A pore-pressure ratio r_u (Bishop & Morgenstern 1960): the pore
/// pressure on a base is `u = r_u σ_v`, with `σ_v = Σ γ_i t_i` the
/// vertical stress of the layers above it.
#[derive(Debug, Clone, PartialEq)]
pub enum PoreRatio {
    /// The same r_u at every cell.
    Constant(f64),
    /// r_u at each cell centre, on the DEM's grid; a column on a no-data
    /// cell is refused ([`super::Refusal::NoData`]).
    Raster(NamedRaster),
}

impl PoreRatio {
    /// Check every value is finite and in `[0, 1)`.
    ///
    /// # Errors
    /// [`SlopeError::PoreRatioOutOfRange`] naming the constant, or the
    /// raster's file and cell, and the value.
    pub fn validate(&self) -> Result<()> {
        let bad = |v: f64| !(v.is_finite() && (0.0..1.0).contains(&v));
        match self {
            PoreRatio::Constant(v) if bad(*v) => {
                Err(DismechError::Slope(SlopeError::PoreRatioOutOfRange {
                    source_name: "the constant".to_string(),
                    cell: None,
                    value: *v,
                }))
            }
            PoreRatio::Constant(_) => Ok(()),
            PoreRatio::Raster(r) => {
                let columns = r.raster.columns();
                for (i, v) in r.raster.values().iter().enumerate() {
                    if let Some(v) = v.filter(|v| bad(*v)) {
                        return Err(DismechError::Slope(SlopeError::PoreRatioOutOfRange {
                            source_name: r.name.clone(),
                            cell: Some((i / columns, i % columns)),
                            value: v,
                        }));
                    }
                }
                Ok(())
            }
        }
    }

    /// What it is, for messages: the constant's value or the file.
    pub fn describe(&self) -> String {
        match self {
            PoreRatio::Constant(v) => format!("= {v}"),
            PoreRatio::Raster(r) => r.name.clone(),
        }
    }

    pub(super) fn at(&self, row: usize, column: usize) -> Option<f64> {
        match self {
            PoreRatio::Constant(v) => Some(*v),
            PoreRatio::Raster(r) => r.raster.get(row, column),
        }
    }
}

/// The ground of a slope search: strength layers, top to bottom, and an
/// optional pore-pressure ratio (see the module's documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct Ground {
    layers: Vec<Layer>,
    pore_ratio: Option<PoreRatio>,
}

/// What the ground gives a column of a trial surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ColumnGround {
    /// Vertical stress at the base `σ_v = Σ γ_i t_i` (Pa).
    pub vertical_stress: f64,
    /// Cohesion of the layer the base passes through (Pa).
    pub cohesion: f64,
    /// Friction coefficient of the layer the base passes through.
    pub friction_coefficient: f64,
    /// `u = r_u σ_v` (Pa) where the ground has a pore-pressure ratio.
    pub ratio_pore_pressure: Option<f64>,
}

impl From<SlopeMaterial> for Ground {
    /// One layer, unbounded below, named `ground`, no pore-pressure ratio:
    /// the results of the single material, bit for bit.
    fn from(material: SlopeMaterial) -> Self {
        Self {
            layers: vec![Layer {
                name: "ground".to_string(),
                bottom: None,
                material,
            }],
            pore_ratio: None,
        }
    }
}

/// What a search runs on: one material ([`SlopeMaterial`], a one-layer
/// ground) or a layered [`Ground`].
pub trait ToGround {
    /// The ground.
    fn to_ground(&self) -> Ground;
}

impl ToGround for SlopeMaterial {
    /// [`Ground::from`] the material.
    fn to_ground(&self) -> Ground {
        Ground::from(*self)
    }
}

impl ToGround for Ground {
    /// A copy.
    fn to_ground(&self) -> Ground {
        self.clone()
    }
}

impl Ground {
    /// Layers, top to bottom: every one but the last bounded below by a
    /// raster, the last unbounded below.
    ///
    /// # Errors
    /// [`SlopeError::InvalidLayer`] naming the layer for no layer at all
    /// ([`LayerProblem::NoLayer`]), a layer other than the last without a
    /// bottom ([`LayerProblem::NoBottom`]), the last with one
    /// ([`LayerProblem::LastHasBottom`]), or a material that fails
    /// [`SlopeMaterial::validate`] ([`LayerProblem::Material`], with its
    /// value).
    pub fn layered(layers: Vec<Layer>) -> Result<Self> {
        let n = layers.len();
        if n == 0 {
            return Err(DismechError::Slope(SlopeError::InvalidLayer {
                layer: "(none)".to_string(),
                problem: LayerProblem::NoLayer,
            }));
        }
        for (i, layer) in layers.iter().enumerate() {
            layer.check_material()?;
            match (&layer.bottom, i + 1 == n) {
                (None, false) => {
                    return Err(layer.invalid(LayerProblem::NoBottom {
                        index: i + 1,
                        count: n,
                    }))
                }
                (Some(b), true) => {
                    return Err(layer.invalid(LayerProblem::LastHasBottom {
                        bottom: b.name.clone(),
                    }))
                }
                _ => {}
            }
        }
        Ok(Self {
            layers,
            pore_ratio: None,
        })
    }

    /// The same ground with the pore-pressure ratio `ratio`.
    ///
    /// # Errors
    /// Those of [`PoreRatio::validate`].
    pub fn with_pore_ratio(mut self, ratio: PoreRatio) -> Result<Self> {
        ratio.validate()?;
        self.pore_ratio = Some(ratio);
        Ok(self)
    }

    /// The layers, top to bottom.
    pub fn layers(&self) -> &[Layer] {
        &self.layers
    }

    /// The pore-pressure ratio, if any.
    pub fn pore_ratio(&self) -> Option<&PoreRatio> {
        self.pore_ratio.as_ref()
    }

    /// Check the ground against a terrain: the materials, every raster on
    /// the DEM's grid, and one source of pore pressure.
    ///
    /// # Errors
    /// For a one-layer ground, those of [`SlopeMaterial::validate`] as
    /// they are; for several layers, [`SlopeError::InvalidLayer`] naming
    /// the layer for a material that fails it ([`LayerProblem::Material`])
    /// or a bottom raster on another grid ([`LayerProblem::BottomOffGrid`],
    /// naming both files); [`crate::grid::GridError::Mismatch`] for an r_u
    /// raster on another grid; those of [`PoreRatio::validate`];
    /// [`SlopeError::PorePressureTwice`] naming both when the terrain has
    /// a water table and the ground an r_u.
    pub fn validate_on(&self, terrain: &Terrain) -> Result<()> {
        if let [only] = self.layers.as_slice() {
            only.material.validate()?;
        }
        for layer in &self.layers {
            layer.check_material()?;
            if let Some(b) = &layer.bottom {
                b.require_grid_of(terrain.dem())
                    .map_err(|e| layer.invalid(LayerProblem::BottomOffGrid(Box::new(e))))?;
            }
        }
        if let Some(ratio) = &self.pore_ratio {
            ratio.validate()?;
            if let PoreRatio::Raster(r) = ratio {
                r.require_grid_of(terrain.dem())?;
            }
            if let Some(w) = terrain.water() {
                return Err(DismechError::Slope(SlopeError::PorePressureTwice {
                    water: w.name.clone(),
                    ratio: ratio.describe(),
                }));
            }
        }
        Ok(())
    }

    /// The layers at cell (row, column) with ground `ground` down to the
    /// elevation `down_to`, top to bottom: each layer's bottom, clipped as
    /// in [`Ground::column`], and its index in [`Ground::layers`]; a layer
    /// pinched out at the cell (thickness 0) is left out, and the first
    /// layer whose bottom lies below `down_to` is given as the last
    /// (`None`, unbounded below: nothing under it reaches `down_to`). The
    /// first layer given reaches up without bound (an HPM column's top may
    /// lie above the ground at its cell centre). `None` where a bottom
    /// raster has no data at the cell above that depth.
    pub fn strata(
        &self,
        row: usize,
        column: usize,
        ground: f64,
        down_to: f64,
    ) -> Option<Vec<(Option<f64>, usize)>> {
        let mut top = ground;
        let mut strata = Vec::with_capacity(self.layers.len());
        for (index, layer) in self.layers.iter().enumerate() {
            let bottom = match &layer.bottom {
                Some(b) => b.raster.get(row, column)?.min(top),
                None => f64::NEG_INFINITY,
            };
            if bottom == top {
                // Pinched out at the cell: not there.
                continue;
            }
            if bottom < down_to {
                strata.push((None, index));
                return Some(strata);
            }
            strata.push((Some(bottom), index));
            top = bottom;
        }
        // The last layer is unbounded below (`Ground::layered`), so the
        // loop returns.
        None
    }

    /// What the ground gives the column at cell (row, column) with ground
    /// `ground` and base `base` (< `ground`): the layered vertical stress,
    /// the strength of the layer the base passes through and the r_u pore
    /// pressure (see the module's documentation); `None` where a bottom
    /// raster or the r_u raster the column needs has no data.
    pub fn column(
        &self,
        row: usize,
        column: usize,
        ground: f64,
        base: f64,
    ) -> Option<ColumnGround> {
        let mut top = ground;
        let mut stress: Option<f64> = None;
        for layer in &self.layers {
            let bottom = match &layer.bottom {
                None => f64::NEG_INFINITY,
                Some(b) => b.raster.get(row, column)?.min(top),
            };
            let t = top - bottom.max(base);
            if t > 0.0 {
                let s = layer.material.unit_weight * t;
                stress = Some(stress.map_or(s, |acc| acc + s));
            }
            if bottom < base {
                let vertical_stress = stress.unwrap_or(0.0);
                let ratio_pore_pressure = match &self.pore_ratio {
                    None => None,
                    Some(r) => Some(r.at(row, column)? * vertical_stress),
                };
                return Some(ColumnGround {
                    vertical_stress,
                    cohesion: layer.material.cohesion,
                    friction_coefficient: layer.material.friction_coefficient,
                    ratio_pore_pressure,
                });
            }
            top = bottom;
        }
        // The last layer is unbounded below (`Ground::layered`), so the
        // loop returns; a ground built otherwise has no layer here.
        None
    }
}
