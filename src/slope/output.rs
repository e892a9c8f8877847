//! What a search writes: rasters on the DEM's grid (its origin and cell
//! size, so that a GIS lays them over the DEM) of the lowest Fs per cell
//! and of the volume, area and depth of the surface that gave it, as
//! Scoops3D writes its `*_fos3d_out.asc` and companions (Reid, Christian &
//! Brien, USGS 2015); and the most critical surfaces as CSV.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::error::Result;
use crate::grid::{write_rasters_with_crs, Raster, RasterFormat};
use crate::io::write_atomically;

use super::search::{CellMinimum, SearchResult};
use super::surface::TrialSurface;

/// The maps [`SearchResult::write_maps`] writes, `{prefix}_{name}.asc`
/// ([`SearchResult::write_maps_as`]: and `.tif`).
pub const MAP_NAMES: [&str; 4] = ["fs", "volume", "area", "depth"];

impl<S> SearchResult<S> {
    fn raster(&self, f: impl Fn(&CellMinimum) -> f64) -> Result<Raster> {
        let values = (0..self.rows * self.columns)
            .map(|k| self.cell(k / self.columns, k % self.columns).map(&f))
            .collect();
        Raster::new(
            self.columns,
            self.rows,
            self.lower_left.0,
            self.lower_left.1,
            self.cell_size,
            values,
        )
    }

    /// The lowest Fs per cell, no data where no trial surface had a column.
    ///
    /// # Errors
    /// Those of [`Raster::new`] (none for a result of [`super::search`]).
    pub fn safety_factor_raster(&self) -> Result<Raster> {
        self.raster(|m| m.safety_factor)
    }

    /// The volume (m³) of the surface that gave each cell its lowest Fs.
    ///
    /// # Errors
    /// As [`Self::safety_factor_raster`].
    pub fn volume_raster(&self) -> Result<Raster> {
        self.raster(|m| m.volume)
    }

    /// The plan area (m²) of the surface that gave each cell its lowest Fs.
    ///
    /// # Errors
    /// As [`Self::safety_factor_raster`].
    pub fn area_raster(&self) -> Result<Raster> {
        self.raster(|m| m.area)
    }

    /// The depth (m) of the surface that gave each cell its lowest Fs.
    ///
    /// # Errors
    /// As [`Self::safety_factor_raster`].
    pub fn depth_raster(&self) -> Result<Raster> {
        self.raster(|m| m.depth)
    }

    /// Write the four maps as ESRI ASCII grids `{prefix}_fs.asc`,
    /// `{prefix}_volume.asc`, `{prefix}_area.asc` and `{prefix}_depth.asc`
    /// in `folder` (created if needed), each atomically
    /// ([`write_esri_ascii`](crate::grid::write_esri_ascii)); returns their
    /// paths. [`Self::write_maps_as`] writes GeoTIFF as well.
    ///
    /// # Errors
    /// [`crate::error::DismechError::Output`] naming the path when a file
    /// cannot be written (it is then not there).
    pub fn write_maps(&self, folder: &Path, prefix: &str) -> Result<Vec<PathBuf>> {
        self.write_maps_as(folder, prefix, &[RasterFormat::EsriAscii])
    }

    /// Write the four maps ([`MAP_NAMES`]) as `{prefix}_{name}.asc`
    /// and/or `{prefix}_{name}.tif` in `folder` (created if needed), in
    /// each of `formats` (e.g. [`RasterFormat::ALL`] for the ESRI ASCII
    /// grids and GeoTIFF beside them), each file atomically
    /// ([`crate::grid::write_rasters`]); returns their paths, map by map and format by
    /// format.
    ///
    /// # Errors
    /// [`crate::error::DismechError::Output`] naming the path when a file
    /// cannot be written (it is then not there).
    pub fn write_maps_as(
        &self,
        folder: &Path,
        prefix: &str,
        formats: &[RasterFormat],
    ) -> Result<Vec<PathBuf>> {
        self.write_maps_with_crs(folder, prefix, formats, None)
    }

    /// [`Self::write_maps_as`], the GeoTIFF files with the coordinate
    /// system `wkt` (an ESRI WKT, as the DEM's `.prj` holds it) where
    /// given ([`write_rasters_with_crs`]).
    ///
    /// # Errors
    /// As [`Self::write_maps_as`]; a WKT a GeoTIFF cannot hold
    /// ([`crate::grid::write_geotiff_with_crs`]).
    pub fn write_maps_with_crs(
        &self,
        folder: &Path,
        prefix: &str,
        formats: &[RasterFormat],
        wkt: Option<&str>,
    ) -> Result<Vec<PathBuf>> {
        let rasters = [
            self.safety_factor_raster()?,
            self.volume_raster()?,
            self.area_raster()?,
            self.depth_raster()?,
        ];
        let named: Vec<(&str, &Raster)> = MAP_NAMES.iter().copied().zip(&rasters).collect();
        write_rasters_with_crs(folder, prefix, &named, formats, wkt)
    }
}

impl<S: TrialSurface> SearchResult<S> {
    /// The most critical surfaces as CSV: a header, then one line a
    /// surface, lowest Fs first: rank, trial, the surface's parameters
    /// ([`TrialSurface::PARAMETERS`]), Fs, columns, volume, area, depth,
    /// the sliding direction's azimuth (degrees from +x, counter-clockwise),
    /// `Σ W`, `Σ (c A + N' tan φ)` and `Σ T`. Numbers are written in full
    /// (Rust's shortest exact form), so that they read back bit for bit.
    pub fn critical_csv(&self) -> String {
        let mut text = String::from("rank,trial");
        for p in S::PARAMETERS {
            text.push(',');
            text.push_str(p);
        }
        text.push_str(
            ",fs,columns,volume_m3,area_m2,depth_m,direction_deg,weight_n,resisting_n,driving_n\n",
        );
        for (rank, c) in self.critical.iter().enumerate() {
            let _ = write!(text, "{},{}", rank + 1, c.trial);
            for v in c.surface.parameters() {
                let _ = write!(text, ",{v}");
            }
            let r = &c.result;
            let _ = writeln!(
                text,
                ",{},{},{},{},{},{},{},{},{}",
                r.safety_factor,
                r.columns,
                r.volume,
                r.area,
                r.depth,
                r.direction.1.atan2(r.direction.0).to_degrees(),
                r.weight,
                r.resisting,
                r.driving
            );
        }
        text
    }

    /// Write [`Self::critical_csv`] to `path`, atomically.
    ///
    /// # Errors
    /// [`crate::error::DismechError::Output`] naming the path when the file
    /// cannot be written (it is then not there).
    pub fn write_critical_csv(&self, path: &Path) -> Result<()> {
        write_atomically(path, self.critical_csv().as_bytes())
    }
}
