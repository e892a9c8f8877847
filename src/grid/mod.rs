//! Regular grids of values (rasters) as slope engineers keep them: ground
//! surface, slip surface and water table on one grid, read from and written
//! to ESRI ASCII grid files (`.asc`, the format of GIS tools and Scoops3D),
//! and as GeoTIFF (`.tif`, one band of 64-bit floats with the grid's
//! georeferencing) for a GIS; [`read_raster`] reads either by the file's
//! extension.
//!
//! # GeoTIFF
//!
//! [`write_geotiff`] writes a raster as one band of 64-bit floats that a
//! GIS (GDAL, QGIS, ArcGIS) lays where the input grid lay.
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
//! | `GeoAsciiParams` (34737) | only with a coordinate system ([`write_geotiff_with_crs`]): `ESRI PE String = <wkt>\|`, the text of `PCSCitationGeoKey` |
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
//! input DEM (as for the input itself) and the map falls on it. Where the
//! coordinate system is known as an ESRI WKT (the `.prj` beside an ESRI
//! grid), [`write_geotiff_with_crs`] keeps it as ArcGIS does:
//! `GTModelTypeGeoKey` = 32767 (user-defined) and `PCSCitationGeoKey` =
//! `ESRI PE String = <wkt>`, which GDAL reads as that coordinate system
//! (at most [`MAX_CRS_CITATION`] characters, what GDAL reads of the key).
//!
//! [`read_geotiff`] reads a GeoTIFF DEM back into a [`Raster`]: the
//! first image of the file, one band of any integer or floating-point
//! sample type (uncompressed, LZW or Deflate, strips or tiles), square
//! cells (`ModelPixelScale`), one tie point (`ModelTiepoint`, shifted half
//! a cell where `GTRasterTypeGeoKey` says `RasterPixelIsPoint`), and
//! `GDAL_NODATA` or NaN as no data. What it cannot use is refused with
//! [`GridError::GeoTiff`] naming the file, the tag and its value; no
//! file makes it panic, and the memory it takes is bounded by the file's
//! size (see [`read_geotiff`]).
//!
//! Values are written as 64-bit floats, so that every value reads back to
//! the same bits (a 32-bit float keeps about 7 significant digits). A
//! raster of [`MAX_GRID_CELLS`]
//! cells takes 800 MB, within classic TIFF's 4 GiB.

mod error;
mod esri_ascii;
mod format;
mod geotiff;
mod raster;

pub use error::{
    CrsProblem, FileKind, GeoTiffProblem, GridCellProblem, GridError, GridExtent,
    GridFormatProblem, GridHeaderProblem, MissingTags, TiffDamage,
};
pub use esri_ascii::{
    parse_esri_ascii, read_esri_ascii, to_esri_ascii, write_esri_ascii, MAX_BYTES_PER_VALUE,
    MAX_HEADER_BYTES,
};
pub use format::{read_raster, write_rasters, write_rasters_with_crs, RasterFormat};
pub use geotiff::{
    check_crs_wkt, parse_geotiff, read_geotiff, write_geotiff, write_geotiff_with_crs,
    GEOTIFF_NODATA, MAX_CRS_CITATION, MAX_GEOTIFF_EXPANSION,
};
pub use raster::{Raster, MAX_GRID_CELLS};
