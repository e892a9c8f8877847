//! GeoTIFF: a raster as one band of 64-bit floats that a GIS (GDAL, QGIS,
//! ArcGIS) lays where the input grid lay.
//!
//! The file is a baseline TIFF (TIFF 6.0, uncompressed, strips, row 0 the
//! top row as in an ESRI ASCII grid) with the GeoTIFF tags of the OGC
//! GeoTIFF standard (OGC 19-008r4, GeoTIFF 1.1) and GDAL's no-data tag:
//!
//! | tag | what is written |
//! |---|---|
//! | `ModelPixelScale` (33550) | `(cellsize, cellsize, 0)` |
//! | `ModelTiepoint` (33922) | raster point `(0, 0, 0)`, the upper-left corner of the upper-left cell, at model point `(xllcorner, yllcorner + nrows × cellsize, 0)` |
//! | `GeoKeyDirectory` (34735) | version 1.1.1; `GTModelTypeGeoKey` = 1 (projected), `GTRasterTypeGeoKey` = 1 (`RasterPixelIsArea`), `ProjectedCSTypeGeoKey` = 32767 (user-defined), `ProjLinearUnitsGeoKey` = 9001 (metre) |
//! | `GDAL_NODATA` (42113) | the no-data value in text: [`GEOTIFF_NODATA`] (−9999, as the ESRI ASCII grids), or `nan` where a cell holds −9999 itself |
//!
//! An ESRI ASCII grid gives the lower-left corner of its grid and lists
//! its rows from the top; GeoTIFF ties the upper-left corner of pixel
//! (0, 0) to the model and lists its rows from the top too, so the values
//! are written in the grid's own order and the tie point is the grid's
//! upper-left corner, `nrows × cellsize` above `yllcorner`. With
//! `RasterPixelIsArea` a pixel is the square cell, not a point at its
//! centre: the same reading as ESRI's `xllcorner`.
//!
//! The coordinate reference system: an ESRI ASCII grid carries none (a GIS
//! keeps it beside the grid, in a `.prj` file), and a [`Raster`] holds
//! plane coordinates in metres. The file therefore says what is known —
//! projected (plane) coordinates in metres — and leaves the projection
//! user-defined (32767), which GDAL reads as a local, engineering
//! coordinate system in metres; a GIS user assigns the projection of the
//! input DEM (as for the input itself) and the map falls on it.
//!
//! Values are written as 64-bit floats, so that every value reads back to
//! the same bits (32-bit floats would round Fs, volumes and coordinates-
//! sized heights to 7 digits). A raster of [`MAX_GRID_CELLS`](super::MAX_GRID_CELLS)
//! cells takes 800 MB, within classic TIFF's 4 GiB.

use std::io::Cursor;
use std::path::Path;

use tiff::encoder::{colortype::Gray64Float, TiffEncoder};
use tiff::tags::Tag;

use super::Raster;
use crate::error::{DismechError, Result};
use crate::io::write_atomically;

/// The no-data value a GeoTIFF is written with (its `GDAL_NODATA` tag):
/// −9999, as the ESRI ASCII grids of [`super::write_esri_ascii`]. Where a
/// cell of the raster holds −9999 itself, NaN is written instead (a
/// raster's values are finite, so NaN marks no value).
pub const GEOTIFF_NODATA: f64 = -9999.0;

/// GeoKey values (OGC 19-008r4, requirements classes GeoKeyDirectoryTag
/// and the code lists of its annex).
mod geokey {
    /// `GTModelTypeGeoKey`.
    pub const MODEL_TYPE: u16 = 1024;
    /// `GTRasterTypeGeoKey`.
    pub const RASTER_TYPE: u16 = 1025;
    /// `ProjectedCSTypeGeoKey` (`ProjectedCRSGeoKey` in GeoTIFF 1.1).
    pub const PROJECTED_CRS: u16 = 3072;
    /// `ProjLinearUnitsGeoKey`.
    pub const LINEAR_UNITS: u16 = 3076;
    /// `ModelTypeProjected`.
    pub const PROJECTED: u16 = 1;
    /// `RasterPixelIsArea`.
    pub const PIXEL_IS_AREA: u16 = 1;
    /// User-defined.
    pub const USER_DEFINED: u16 = 32767;
    /// EPSG 9001, metre.
    pub const METRE: u16 = 9001;
}

/// The `GeoKeyDirectory` of every file written: a header (directory
/// version 1, key revision 1.1, four keys), then each key as
/// `(id, location 0 = the value itself, count 1, value)`, ids ascending.
fn geokey_directory() -> [u16; 20] {
    use geokey::*;
    [
        1,
        1,
        1,
        4,
        MODEL_TYPE,
        0,
        1,
        PROJECTED,
        RASTER_TYPE,
        0,
        1,
        PIXEL_IS_AREA,
        PROJECTED_CRS,
        0,
        1,
        USER_DEFINED,
        LINEAR_UNITS,
        0,
        1,
        METRE,
    ]
}

/// The no-data value for `raster`: [`GEOTIFF_NODATA`], or NaN where a cell
/// holds it.
fn nodata_for(raster: &Raster) -> f64 {
    if raster
        .values()
        .iter()
        .flatten()
        .any(|&v| v == GEOTIFF_NODATA)
    {
        f64::NAN
    } else {
        GEOTIFF_NODATA
    }
}

/// `GDAL_NODATA`'s text for `nodata`: `-9999` or `nan`.
fn nodata_text(nodata: f64) -> String {
    if nodata.is_nan() {
        "nan".to_string()
    } else {
        format!("{nodata}")
    }
}

/// The bytes of `raster` as a GeoTIFF file (see the [module
/// documentation](self)).
///
/// # Errors
/// The encoder's, as text (none for a [`Raster`], whose sides fit TIFF's
/// 32-bit sizes and whose values fit its 4 GiB).
fn encode(raster: &Raster) -> std::result::Result<Vec<u8>, String> {
    let columns = u32::try_from(raster.columns()).map_err(|e| e.to_string())?;
    let rows = u32::try_from(raster.rows()).map_err(|e| e.to_string())?;
    let nodata = nodata_for(raster);
    let values: Vec<f64> = raster
        .values()
        .iter()
        .map(|v| v.unwrap_or(nodata))
        .collect();
    let (x0, y0) = raster.lower_left();
    let d = raster.cell_size();
    let top = y0 + raster.rows() as f64 * d;
    let mut bytes = Cursor::new(Vec::with_capacity(8 * values.len() + 1024));
    let mut tiff = TiffEncoder::new(&mut bytes).map_err(|e| e.to_string())?;
    let mut image = tiff
        .new_image::<Gray64Float>(columns, rows)
        .map_err(|e| e.to_string())?;
    let tags = image.encoder();
    tags.write_tag(Tag::ModelPixelScaleTag, &[d, d, 0.0][..])
        .map_err(|e| e.to_string())?;
    tags.write_tag(Tag::ModelTiepointTag, &[0.0, 0.0, 0.0, x0, top, 0.0][..])
        .map_err(|e| e.to_string())?;
    tags.write_tag(Tag::GeoKeyDirectoryTag, &geokey_directory()[..])
        .map_err(|e| e.to_string())?;
    tags.write_tag(Tag::GdalNodata, nodata_text(nodata).as_str())
        .map_err(|e| e.to_string())?;
    image.write_data(&values).map_err(|e| e.to_string())?;
    Ok(bytes.into_inner())
}

/// Write a raster as a GeoTIFF file (one band of 64-bit floats, its
/// georeferencing and no-data value in the GeoTIFF and GDAL tags: see the
/// [module documentation](self)), atomically.
///
/// # Errors
/// [`DismechError::Output`] naming the path when the file cannot be
/// encoded or written, or its folder created (see
/// [`crate::io::write_atomically`]); the file is then not there.
pub fn write_geotiff(path: &Path, raster: &Raster) -> Result<()> {
    let bytes = encode(raster).map_err(|message| DismechError::Output {
        path: path.display().to_string(),
        message: format!("cannot encode the GeoTIFF: {message}"),
    })?;
    write_atomically(path, &bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use tiff::decoder::{Decoder, DecodingResult};

    fn sample() -> Raster {
        Raster::from_fn(4, 3, 1000.0, 2000.0, 2.5, |x, y| {
            if x > 1008.0 {
                None
            } else {
                Some(x * 1e-3 + y / 3.0)
            }
        })
        .unwrap()
    }

    #[test]
    fn geotiff_holds_the_values_georeferencing_and_nodata() {
        let raster = sample();
        let bytes = encode(&raster).unwrap();
        let mut decoder = Decoder::new(Cursor::new(bytes)).unwrap();
        assert_eq!(decoder.dimensions().unwrap(), (4, 3));
        let scale = decoder.get_tag_f64_vec(Tag::ModelPixelScaleTag).unwrap();
        assert_eq!(scale, [2.5, 2.5, 0.0]);
        let tie = decoder.get_tag_f64_vec(Tag::ModelTiepointTag).unwrap();
        assert_eq!(tie, [0.0, 0.0, 0.0, 1000.0, 2007.5, 0.0]);
        let keys = decoder.get_tag_u16_vec(Tag::GeoKeyDirectoryTag).unwrap();
        assert_eq!(keys, geokey_directory());
        assert_eq!(
            decoder.get_tag_ascii_string(Tag::GdalNodata).unwrap(),
            "-9999"
        );
        let DecodingResult::F64(values) = decoder.read_image().unwrap() else {
            panic!("not 64-bit floats");
        };
        let expected: Vec<f64> = raster
            .values()
            .iter()
            .map(|v| v.unwrap_or(GEOTIFF_NODATA))
            .collect();
        assert_eq!(values, expected);
        assert_eq!(values[3], GEOTIFF_NODATA);
    }

    #[test]
    fn a_cell_holding_minus_9999_makes_the_nodata_nan() {
        let raster = Raster::new(2, 1, 0.0, 0.0, 1.0, vec![Some(-9999.0), None]).unwrap();
        let mut decoder = Decoder::new(Cursor::new(encode(&raster).unwrap())).unwrap();
        assert_eq!(
            decoder.get_tag_ascii_string(Tag::GdalNodata).unwrap(),
            "nan"
        );
        let DecodingResult::F64(values) = decoder.read_image().unwrap() else {
            panic!("not 64-bit floats");
        };
        assert_eq!(values[0], -9999.0);
        assert!(values[1].is_nan());
    }

    #[test]
    fn geotiff_is_written_atomically_and_an_unwritable_path_is_named() {
        let dir = std::env::temp_dir().join(format!("dismech-geotiff-{}", std::process::id()));
        let path = dir.join("fs.tif");
        write_geotiff(&path, &sample()).unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), encode(&sample()).unwrap());
        let names: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
        assert_eq!(names.len(), 1);
        // A folder where the file should go: nothing is written, the path is named.
        let blocked = dir.join("blocked.tif");
        std::fs::create_dir_all(&blocked).unwrap();
        let e = write_geotiff(&blocked, &sample()).unwrap_err().to_string();
        assert!(e.contains("blocked.tif"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
