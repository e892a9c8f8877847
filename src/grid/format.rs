//! The file formats a raster is written in, and a set of named maps
//! written in one go.

use std::path::{Path, PathBuf};

use super::{read_esri_ascii, read_geotiff, write_esri_ascii, write_geotiff_with_crs, Raster};
use crate::error::Result;

/// A raster file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RasterFormat {
    /// ESRI ASCII grid, `.asc` ([`write_esri_ascii`]): text, the format
    /// of Scoops3D and of the input grids.
    EsriAscii,
    /// GeoTIFF, `.tif` ([`super::write_geotiff`]): one band of 64-bit floats with
    /// the grid's georeferencing, what a GIS opens first.
    GeoTiff,
}

impl RasterFormat {
    /// Both formats, ESRI ASCII first.
    pub const ALL: [RasterFormat; 2] = [RasterFormat::EsriAscii, RasterFormat::GeoTiff];

    /// The file extension, without the dot: `asc` or `tif`.
    pub fn extension(self) -> &'static str {
        match self {
            RasterFormat::EsriAscii => "asc",
            RasterFormat::GeoTiff => "tif",
        }
    }

    /// The format of a file by its extension: `.tif` or `.tiff` (any case)
    /// GeoTIFF, anything else ESRI ASCII.
    pub fn of_path(path: &Path) -> RasterFormat {
        match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("tif") || e.eq_ignore_ascii_case("tiff") => {
                RasterFormat::GeoTiff
            }
            _ => RasterFormat::EsriAscii,
        }
    }

    /// Read a raster in this format ([`read_esri_ascii`],
    /// [`read_geotiff`]).
    ///
    /// # Errors
    /// Those of the format's reader, naming the file.
    pub fn read(self, path: &Path) -> Result<Raster> {
        match self {
            RasterFormat::EsriAscii => read_esri_ascii(path),
            RasterFormat::GeoTiff => read_geotiff(path),
        }
    }

    /// Write `raster` to `path` in this format, atomically.
    ///
    /// # Errors
    /// [`crate::error::DismechError::Output`] naming the path when the file
    /// cannot be written (it is then not there).
    pub fn write(self, path: &Path, raster: &Raster) -> Result<()> {
        self.write_with_crs(path, raster, None)
    }

    /// [`Self::write`], a GeoTIFF with the coordinate system `wkt` (an ESRI
    /// WKT, [`write_geotiff_with_crs`]) where given. An ESRI ASCII grid has
    /// no place for it: a GIS reads it from a `.prj` file beside the grid,
    /// which is the caller's to write.
    ///
    /// # Errors
    /// As [`Self::write`]; for GeoTIFF those of [`write_geotiff_with_crs`].
    pub fn write_with_crs(self, path: &Path, raster: &Raster, wkt: Option<&str>) -> Result<()> {
        match self {
            RasterFormat::EsriAscii => write_esri_ascii(path, raster),
            RasterFormat::GeoTiff => write_geotiff_with_crs(path, raster, wkt),
        }
    }
}

/// Read a raster file in the format of its extension
/// ([`RasterFormat::of_path`]: `.tif` or `.tiff` GeoTIFF, anything else
/// ESRI ASCII).
///
/// # Errors
/// Those of [`read_esri_ascii`] or [`read_geotiff`], naming the file.
pub fn read_raster(path: &Path) -> Result<Raster> {
    RasterFormat::of_path(path).read(path)
}

/// Write each named raster as `{prefix}_{name}.{extension}` in `folder`
/// (created if needed), in each of `formats`, each file atomically;
/// returns the paths, raster by raster and, for each, format by format in
/// the order given.
///
/// # Errors
/// [`crate::error::DismechError::Output`] naming the path of the first
/// file that cannot be written (it is then not there; those before it
/// are).
pub fn write_rasters(
    folder: &Path,
    prefix: &str,
    rasters: &[(&str, &Raster)],
    formats: &[RasterFormat],
) -> Result<Vec<PathBuf>> {
    write_rasters_with_crs(folder, prefix, rasters, formats, None)
}

/// [`write_rasters`], the GeoTIFF files with the coordinate system `wkt`
/// where given ([`RasterFormat::write_with_crs`]).
///
/// # Errors
/// As [`write_rasters`].
pub fn write_rasters_with_crs(
    folder: &Path,
    prefix: &str,
    rasters: &[(&str, &Raster)],
    formats: &[RasterFormat],
    wkt: Option<&str>,
) -> Result<Vec<PathBuf>> {
    let mut paths = Vec::with_capacity(rasters.len() * formats.len());
    for (name, raster) in rasters {
        for format in formats {
            let path = folder.join(format!("{prefix}_{name}.{}", format.extension()));
            format.write_with_crs(&path, raster, wkt)?;
            paths.push(path);
        }
    }
    Ok(paths)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::read_esri_ascii;

    #[test]
    fn rasters_are_written_in_every_format_asked_in_order() {
        let dir = std::env::temp_dir().join(format!("dismech-rasters-{}", std::process::id()));
        let a = Raster::from_fn(3, 2, 0.0, 0.0, 1.0, |x, y| Some(x + y)).unwrap();
        let b = Raster::from_fn(3, 2, 0.0, 0.0, 1.0, |x, _| Some(x)).unwrap();
        let paths = write_rasters(&dir, "p", &[("a", &a), ("b", &b)], &RasterFormat::ALL).unwrap();
        let names: Vec<_> = paths
            .iter()
            .map(|p| p.file_name().unwrap().to_str().unwrap().to_string())
            .collect();
        assert_eq!(names, ["p_a.asc", "p_a.tif", "p_b.asc", "p_b.tif"]);
        assert_eq!(read_esri_ascii(&paths[2]).unwrap(), b);
        assert_eq!(&std::fs::read(&paths[1]).unwrap()[..4], b"II*\0");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
