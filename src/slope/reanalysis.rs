//! HPM re-analysis of a trial surface found by a search: the surface made
//! a slip-surface raster on the DEM's grid and analysed by paper 001's
//! HPM ([`crate::hpm`]), elastic and, if asked, nonlinear, for what a
//! column method cannot give: the deformation of the slide and the local
//! Fs along its slip surface (paper 001, §5).
//!
//! The slip-surface raster holds the surface's lower half at every cell
//! centre of its plan footprint where the DEM has data
//! ([`surface_raster`]), the same heights [`super::surface_columns`] gives
//! the search's columns; HPM's valid columns are the cells where it lies
//! below the ground (§5), its corner heights interpolated from these
//! cell-centre values (eq. 23). A re-analysis is therefore the same as an
//! HPM run on that raster read from a file, bit for bit.
//!
//! **Ground.** On layered ground ([`Ground`]) each column takes its
//! layers, as the search's Hovland takes them at the cell centre
//! (Scoops3D's convention): its slip springs the strength of the layer
//! the slip surface crosses there ([`HpmModel::set_column_strength`]),
//! its elements the weight of the layers over their height, each layer's
//! bottom at the cell centre a level plane through the column
//! ([`HpmModel::set_column_strata`]: eqs. 8–10 summed layer by layer).
//! Paper 001 averages the ground's values (§3); one material, or layers
//! of equal unit weights and strength, give the one-material model bit for
//! bit. A pore-pressure ratio r_u (Bishop & Morgenstern 1960) puts the
//! pore pressure `u = r_u σ_v` on the slip surface under each column
//! ([`HpmModel::set_column_pore_pressure`]), `σ_v` the column's total
//! weight per unit plan area (from HPM's elements, whose heights are
//! interpolated at the corners, where the search takes `γ (ground −
//! base)` at the cell centre) and r_u at its cell centre, as the search
//! reads it: the slip springs then carry the effective normal traction.
//! HPM's normal forces are those of equilibrium, not floored at zero as
//! the search's `N − u A` is. The water table of the
//! terrain becomes HPM's: the elements below it weigh the submerged unit
//! weight `γ − γ_w` of their layer (eqs. 8–10) and take the seepage force
//! `−γ_w ∇z_w` per unit volume ([`crate::hpm::Element::seepage`]), where
//! Hovland's method of the search keeps the total weight and takes the
//! pore pressure `γ_w h_p` off the base's normal force: both are the same
//! hydrostatic pore pressure under the table, and on a planar slope under
//! a parallel table they give the same Fs. The seismic coefficient acts
//! along the surface's sliding direction of Hovland's method (eqs.
//! 11–13), on the total weight in both.

use super::error::SlopeError;
use crate::error::{DismechError, Result};
use crate::grid::Raster;
use crate::hpm::{
    ColumnMaps, HpmMaterial, HpmModel, HpmResult, HpmSettings, HpmSolver, NamedRaster,
    NonlinearSettings, Seismic, SlopeGrids, WeightStratum,
};
use crate::law::Strength;

use super::ground::{Ground, PoreRatio, ToGround};
use super::hovland::SurfaceFs;
use super::layer_problem::LayerProblem;
use super::material::{SlopeLoads, SlopeMaterial};
use super::surface::TrialSurface;
use super::terrain::Terrain;

/// The stiffness of the ground and of the slip springs, which a limit
/// equilibrium search does not need and HPM does ([`HpmMaterial`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HpmStiffness {
    /// Young's modulus E of the soil (Pa).
    pub youngs_modulus: f64,
    /// Poisson's ratio ν, in [0, 0.5).
    pub poisson_ratio: f64,
    /// Modulus E_slip of the slip springs (eq. 30) (Pa).
    pub slip_modulus: f64,
    /// Shear stiffness `k_s = k_t` of the slip springs (Pa/m); `None`
    /// takes `E_slip / ((1 + ν) h_I)` of eq. (30).
    pub slip_shear_stiffness: Option<f64>,
}

impl Default for HpmStiffness {
    /// Paper 001's §5: E = E_slip = 1 GPa, ν = 0.2, k_s = 100 MPa/m.
    fn default() -> Self {
        let paper = HpmMaterial::paper();
        Self {
            youngs_modulus: paper.youngs_modulus,
            poisson_ratio: paper.poisson_ratio,
            slip_modulus: paper.slip_modulus,
            slip_shear_stiffness: paper.slip_shear_stiffness,
        }
    }
}

impl HpmStiffness {
    /// HPM's material of `material` with this stiffness; the submerged unit
    /// weight is `γ − γ_w`.
    ///
    /// # Errors
    /// Those of [`HpmMaterial::validate`], naming the value; a unit weight
    /// not above `γ_w` gives a submerged unit weight that is not positive.
    pub fn material(&self, material: &SlopeMaterial, loads: &SlopeLoads) -> Result<HpmMaterial> {
        let m = HpmMaterial {
            youngs_modulus: self.youngs_modulus,
            poisson_ratio: self.poisson_ratio,
            cohesion: material.cohesion,
            friction_coefficient: material.friction_coefficient,
            unit_weight: material.unit_weight,
            submerged_unit_weight: material.unit_weight - loads.water_unit_weight,
            slip_modulus: self.slip_modulus,
            slip_shear_stiffness: self.slip_shear_stiffness,
        };
        m.validate()?;
        Ok(m)
    }
}

/// A trial surface as a slip-surface raster on the DEM's grid: its lower
/// half at each cell centre of its plan footprint where the DEM has data
/// (also where it lies above the ground: HPM's valid columns are those
/// where it lies below, §5), raised to the bedrock where it would go below
/// it ([`Terrain::with_bedrock`], as [`super::surface_columns`] does), no
/// data elsewhere.
///
/// # Errors
/// Those of [`Raster::new`] (none for a terrain's grid).
pub fn surface_raster<S: TrialSurface>(terrain: &Terrain, surface: &S) -> Result<Raster> {
    let dem = &terrain.dem().raster;
    let (rows, columns) = (dem.rows(), dem.columns());
    let mut values = vec![None; rows * columns];
    for r in 0..rows {
        for c in 0..columns {
            if dem.get(r, c).is_none() {
                continue;
            }
            let (x, y) = dem.cell_centre(r, c);
            let rock = terrain.bedrock_at(r, c).map(|(z, _)| z);
            values[r * columns + c] = surface.base(x, y).map(|(z, _)| match rock {
                Some(rock) if z < rock => rock,
                _ => z,
            });
        }
    }
    let (x0, y0) = dem.lower_left();
    Raster::new(columns, rows, x0, y0, dem.cell_size(), values)
}

/// An HPM re-analysis of one trial surface.
#[derive(Debug, Clone)]
pub struct HpmReanalysis {
    /// Ground (the DEM), slip surface ([`surface_raster`], named
    /// `slip surface`) and water table.
    pub grids: SlopeGrids,
    /// The HPM model on them.
    pub model: HpmModel,
    /// The seismic load (k_h along Hovland's sliding direction).
    pub seismic: Seismic,
    /// The elastic analysis.
    pub elastic: HpmResult,
    /// The nonlinear analysis, where asked.
    pub nonlinear: Option<HpmResult>,
}

impl HpmReanalysis {
    /// The maps of the elastic analysis ([`HpmResult::maps`]).
    ///
    /// # Errors
    /// Those of [`HpmResult::maps`] (none for a re-analysis).
    pub fn elastic_maps(&self) -> Result<ColumnMaps> {
        self.elastic.maps(&self.model, &self.grids)
    }

    /// The maps of the nonlinear analysis, where there is one.
    ///
    /// # Errors
    /// As [`Self::elastic_maps`].
    pub fn nonlinear_maps(&self) -> Result<Option<ColumnMaps>> {
        self.nonlinear
            .as_ref()
            .map(|r| r.maps(&self.model, &self.grids))
            .transpose()
    }
}

/// Put the pore pressure `u = r_u σ_v` of `ratio` on the slip surface
/// under each column of `model`, with `σ_v` the column's total weight per
/// unit plan area (its elements' weights over `d²`, the layers' where the
/// ground has layers) and r_u at its cell centre.
fn take_pore_ratio(model: &mut HpmModel, ratio: &PoreRatio) -> Result<()> {
    let plan = model.grid.2 * model.grid.2;
    for k in 0..model.columns.len() {
        let column = &model.columns[k];
        let (r, c) = column.cell;
        let ru = ratio.at(r, c).ok_or_else(|| {
            DismechError::Slope(SlopeError::HpmGround {
                reason: format!(
                    "the pore-pressure ratio r_u ({}) has no data at cell (row {r}, column {c}), a column of the slide",
                    ratio.describe()
                ),
            })
        })?;
        let sigma_v: f64 = model.elements[column.elements.clone()]
            .iter()
            .map(|e| e.weight + e.buoyancy)
            .sum::<f64>()
            / plan;
        model.set_column_pore_pressure(k, ru * sigma_v)?;
    }
    Ok(())
}

/// HPM's material of each layer of `ground` (its unit weights: `γ`, and
/// `γ − γ_w` below a water table), in the layers' order.
fn layer_materials(
    ground: &Ground,
    stiffness: &HpmStiffness,
    loads: &SlopeLoads,
) -> Result<Vec<HpmMaterial>> {
    ground
        .layers()
        .iter()
        .map(|layer| {
            stiffness.material(&layer.material, loads).map_err(|e| {
                DismechError::Slope(SlopeError::InvalidLayer {
                    layer: layer.name.clone(),
                    problem: LayerProblem::Material(Box::new(e)),
                })
            })
        })
        .collect()
}

/// Give each column of `model` the layers of `ground` at its cell centre:
/// its slip springs the strength of the layer the slip surface crosses,
/// its elements the weights of the layers over their height.
fn take_layers(
    model: &mut HpmModel,
    grids: &SlopeGrids,
    terrain: &Terrain,
    ground: &Ground,
    materials: &[HpmMaterial],
) -> Result<()> {
    for k in 0..model.columns.len() {
        let (r, c) = model.columns[k].cell;
        let no_data = || {
            DismechError::Slope(SlopeError::HpmGround {
                reason: format!(
                    "a layer's bottom has no data at cell (row {r}, column {c}), a column of the slide"
                ),
            })
        };
        let g = terrain.ground(r, c).ok_or_else(no_data)?;
        let z = grids.slip().raster.get(r, c).ok_or_else(no_data)?;
        // Each column's springs: the layer the slip surface crosses at the
        // cell centre, as the search's Hovland takes it.
        let at = ground.column(r, c, g, z).ok_or_else(no_data)?;
        model.set_column_strength(
            k,
            Strength {
                cohesion: at.cohesion,
                friction: at.friction_coefficient,
            },
        )?;
        // Its elements: the layers down to the lowest corner of its slip
        // surface, each with HPM's unit weights of its material.
        let lowest = model.columns[k]
            .shape
            .bottom()
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        let strata = ground.strata(r, c, g, lowest).ok_or_else(no_data)?;
        let strata: Vec<WeightStratum> = strata
            .iter()
            .map(|&(bottom, index)| WeightStratum {
                bottom,
                unit_weight: materials[index].unit_weight,
                submerged_unit_weight: materials[index].submerged_unit_weight,
            })
            .collect();
        model.set_column_strata(grids, k, &strata)?;
    }
    Ok(())
}

/// Re-analyse `surface` (a surface of a search over `terrain`, with
/// Hovland's result `hovland` giving its sliding direction) by HPM:
/// elastic always, nonlinear where `nonlinear` is given, on the ground
/// `ground` (one material, or layers) under `loads`, with the stiffness
/// `stiffness` and the discretisation `settings` (see the module's
/// documentation).
///
/// # Errors
/// Those of [`Ground::validate_on`] (a water table and a pore-pressure
/// ratio together: [`SlopeError::PorePressureTwice`]);
/// [`SlopeError::HpmGround`] for a layer's bottom or a pore-pressure
/// ratio without data under a column; [`SlopeError::InvalidLayer`]
/// naming a layer whose material HPM refuses
/// ([`HpmStiffness::material`]: under a water table, a unit weight not
/// above `γ_w`); those of [`HpmStiffness::material`], [`Seismic::validate`],
/// [`SlopeGrids::new`] (a surface that stays above the ground:
/// [`HpmError::NoValidColumn`](crate::hpm::HpmError::NoValidColumn)),
/// [`HpmModel::new`], [`HpmSolver::new`] and of the analyses.
#[allow(clippy::too_many_arguments)]
pub fn hpm_reanalysis<S: TrialSurface>(
    terrain: &Terrain,
    ground: &(impl ToGround + ?Sized),
    loads: &SlopeLoads,
    surface: &S,
    hovland: &SurfaceFs,
    stiffness: &HpmStiffness,
    settings: &HpmSettings,
    nonlinear: Option<&NonlinearSettings>,
) -> Result<HpmReanalysis> {
    let ground = ground.to_ground();
    ground.validate_on(terrain)?;
    // Dry ground: no element lies below a water table, so the submerged
    // unit weight is never taken; a unit weight at or below γ_w is no
    // reason to refuse.
    let loads_taken = match terrain.water() {
        Some(_) => *loads,
        None => SlopeLoads {
            water_unit_weight: 0.0,
            ..*loads
        },
    };
    // One material: HPM's own model. Layers: the model of the top layer's
    // material, each column then given its layers.
    let layers = match ground.layers() {
        [_] => None,
        _ => Some(layer_materials(&ground, stiffness, &loads_taken)?),
    };
    let material = match &layers {
        None => stiffness.material(&ground.layers()[0].material, &loads_taken)?,
        Some(materials) => materials[0],
    };
    let seismic = Seismic {
        coefficient: loads.seismic_coefficient,
        direction: hovland.direction,
    };
    seismic.validate()?;
    let slip = NamedRaster::new("slip surface", surface_raster(terrain, surface)?);
    let grids = SlopeGrids::new(terrain.dem().clone(), slip, terrain.water().cloned())?;
    let mut model = HpmModel::new(&grids, &material, settings)?;
    if let Some(materials) = &layers {
        take_layers(&mut model, &grids, terrain, &ground, materials)?;
    }
    if let Some(ratio) = ground.pore_ratio() {
        take_pore_ratio(&mut model, ratio)?;
    }
    let mut solver = HpmSolver::new(&model)?;
    let elastic = solver.elastic(&model, &seismic)?;
    let nonlinear = nonlinear
        .map(|s| solver.nonlinear(&model, &seismic, 1.0, s))
        .transpose()?;
    Ok(HpmReanalysis {
        grids,
        model,
        seismic,
        elastic,
        nonlinear,
    })
}
