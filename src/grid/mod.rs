//! Regular grids of values (rasters) as slope engineers keep them: ground
//! surface, slip surface and water table on one grid, read from and written
//! to ESRI ASCII grid files (`.asc`, the format of GIS tools and Scoops3D),
//! and as GeoTIFF (`.tif`, one band of 64-bit floats with the grid's
//! georeferencing) for a GIS; [`read_raster`] reads either by the file's
//! extension.

mod esri_ascii;
mod format;
mod geotiff;
mod raster;

pub use esri_ascii::{
    parse_esri_ascii, read_esri_ascii, to_esri_ascii, write_esri_ascii, MAX_BYTES_PER_VALUE,
    MAX_HEADER_BYTES,
};
pub use format::{read_raster, write_rasters, RasterFormat};
pub use geotiff::{
    parse_geotiff, read_geotiff, write_geotiff, GEOTIFF_NODATA, MAX_GEOTIFF_EXPANSION,
};
pub use raster::{Raster, MAX_GRID_CELLS};
