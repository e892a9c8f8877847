//! GeoTIFF: a raster written as one band of 64-bit floats with its
//! georeferencing, and a GeoTIFF DEM read back; the format as written and
//! as read is described in the [`grid`](super) module's documentation.

use std::io::Cursor;
use std::path::Path;

use tiff::decoder::{Decoder, DecodingResult, Limits};
use tiff::encoder::{colortype::Gray64Float, TiffEncoder};
use tiff::tags::Tag;
use tiff::ColorType;

use super::error::{
    CrsProblem, FileKind, GeoTiffProblem as Problem, GridCellProblem, GridError, MissingTags,
    TiffDamage,
};
use super::{Raster, MAX_GRID_CELLS};
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
    /// `PCSCitationGeoKey` (`ProjectedCitationGeoKey` in GeoTIFF 1.1).
    pub const PROJECTED_CITATION: u16 = 3073;
    /// The `GeoAsciiParamsTag` (34737), where ASCII keys keep their text.
    pub const ASCII_PARAMS: u16 = 34737;
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

/// The `GeoKeyDirectory` of a file written: a header (directory version
/// 1, key revision 1.1, the number of keys), then each key as
/// `(id, location, count, value)`, ids ascending: a short's value in the
/// key itself (location 0), a text as `count` characters from `value` in
/// the `GeoAsciiParamsTag`. Without a coordinate system: a projected model
/// with a user-defined projected CRS in metres. With one (`citation`, the
/// length of the text `ESRI PE String = <wkt>|`): the model user-defined
/// and `PCSCitationGeoKey` pointing at that text, as ArcGIS writes it and
/// where GDAL reads an ESRI WKT (its `gt_wkt_srs.cpp` looks there for a
/// model that is neither projected, geographic nor geocentric).
fn geokey_directory(citation: Option<u16>) -> Vec<u16> {
    use geokey::*;
    let model = if citation.is_some() {
        USER_DEFINED
    } else {
        PROJECTED
    };
    let mut keys = vec![
        [MODEL_TYPE, 0, 1, model],
        [RASTER_TYPE, 0, 1, PIXEL_IS_AREA],
        [PROJECTED_CRS, 0, 1, USER_DEFINED],
    ];
    if let Some(length) = citation {
        keys.push([PROJECTED_CITATION, ASCII_PARAMS, length, 0]);
    }
    keys.push([LINEAR_UNITS, 0, 1, METRE]);
    let mut directory = vec![1, 1, 1, keys.len() as u16];
    directory.extend(keys.into_iter().flatten());
    directory
}

/// The longest citation text GDAL reads whole: it reads
/// `PCSCitationGeoKey` into 2 400 bytes with the terminating zero.
pub const MAX_CRS_CITATION: usize = 2399;

/// The `GeoAsciiParamsTag` text for an ESRI WKT: `ESRI PE String = <wkt>|`
/// (`|` ends each key's text), or why it cannot be written: a WKT with
/// `|` or a character outside printable ASCII, or a text longer than
/// [`MAX_CRS_CITATION`].
fn esri_citation(wkt: &str) -> std::result::Result<String, CrsProblem> {
    let wkt = wkt.trim();
    if let Some(character) = wkt.chars().find(|&c| !(' '..='~').contains(&c) || c == '|') {
        return Err(CrsProblem::Character { character });
    }
    let text = format!("ESRI PE String = {wkt}|");
    if text.len() > MAX_CRS_CITATION {
        return Err(CrsProblem::TooLong {
            length: wkt.len(),
            limit: MAX_CRS_CITATION,
        });
    }
    Ok(text)
}

/// Check that a GeoTIFF can keep the coordinate system `wkt` (an ESRI WKT,
/// as a `.prj` holds it) in its citation key, as
/// [`write_geotiff_with_crs`] writes it: so that a bad `.prj` is refused
/// before a long computation whose results would carry it.
///
/// # Errors
/// Why it cannot be kept: [`CrsProblem::Character`] for a character
/// outside printable ASCII or `|`, [`CrsProblem::TooLong`] for a text
/// longer than [`MAX_CRS_CITATION`].
pub fn check_crs_wkt(wkt: &str) -> std::result::Result<(), CrsProblem> {
    esri_citation(wkt).map(|_| ())
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

/// The bytes of `raster` as a GeoTIFF file (see the [`grid`](super#geotiff) module's documentation).
///
/// # Errors
/// The encoder's, as text (none for a [`Raster`], whose sides fit TIFF's
/// 32-bit sizes and whose values fit its 4 GiB).
fn encode(raster: &Raster, wkt: Option<&str>) -> std::result::Result<Vec<u8>, String> {
    let citation = wkt
        .map(esri_citation)
        .transpose()
        .map_err(|e| e.to_string())?;
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
    let length = citation.as_ref().map(|c| c.len() as u16);
    tags.write_tag(Tag::GeoKeyDirectoryTag, &geokey_directory(length)[..])
        .map_err(|e| e.to_string())?;
    if let Some(text) = &citation {
        tags.write_tag(Tag::GeoAsciiParamsTag, text.as_str())
            .map_err(|e| e.to_string())?;
    }
    tags.write_tag(Tag::GdalNodata, nodata_text(nodata).as_str())
        .map_err(|e| e.to_string())?;
    image.write_data(&values).map_err(|e| e.to_string())?;
    Ok(bytes.into_inner())
}

/// Write a raster as a GeoTIFF file (one band of 64-bit floats, its
/// georeferencing and no-data value in the GeoTIFF and GDAL tags: see the
/// [`grid`](super#geotiff) module's documentation), atomically.
///
/// # Errors
/// [`DismechError::Output`] naming the path when the file cannot be
/// encoded or written, or its folder created (see
/// [`crate::io::write_atomically`]); the file is then not there.
pub fn write_geotiff(path: &Path, raster: &Raster) -> Result<()> {
    write_geotiff_with_crs(path, raster, None)
}

/// [`write_geotiff`], with the coordinate system `wkt` where given: an
/// ESRI WKT, as a `.prj` beside an ESRI ASCII grid holds it, kept in the
/// GeoTIFF's citation keys as `ESRI PE String = <wkt>`, where GDAL reads
/// it (`gdalinfo` then shows that coordinate system).
///
/// # Errors
/// As [`write_geotiff`]; [`DismechError::Output`] naming the path also for
/// a WKT that a GeoTIFF's ASCII key cannot hold (a character outside
/// printable ASCII, or `|`); the file is then not there.
pub fn write_geotiff_with_crs(path: &Path, raster: &Raster, wkt: Option<&str>) -> Result<()> {
    let bytes = encode(raster, wkt).map_err(|message| DismechError::Output {
        path: path.display().to_string(),
        message: format!("cannot encode the GeoTIFF: {message}"),
    })?;
    write_atomically(path, &bytes)
}

/// The most bytes of decoded values a compressed GeoTIFF may claim per
/// byte of its file: 4 096, above the largest ratio LZW (a 12-bit code for
/// at most 4 096 bytes) or Deflate (1 032) can reach, so no valid file is
/// refused, while a small hostile file cannot make the reader allocate
/// more than 4 096 times its size. An uncompressed file must hold every
/// value it claims.
pub const MAX_GEOTIFF_EXPANSION: u64 = 4096;

/// What [`read_geotiff`] reads of the GeoKey directory: the raster type
/// (`true` for `RasterPixelIsPoint`).
fn pixel_is_point(keys: &[u16]) -> std::result::Result<bool, Problem> {
    let count = keys.get(3).copied().unwrap_or(0) as usize;
    if keys.len() < 4 || keys.len() < 4 + 4 * count {
        return Err(Problem::KeyDirectoryDamaged {
            values: keys.len(),
            keys: count,
        });
    }
    for key in keys[4..4 + 4 * count].chunks_exact(4) {
        if key[0] == geokey::RASTER_TYPE {
            return match (key[1], key[3]) {
                (0, 1) => Ok(false),
                (0, 2) => Ok(true),
                (location, value) => Err(Problem::RasterType { value, location }),
            };
        }
    }
    Ok(false)
}

/// The bytes of a value of TIFF field type `kind` (TIFF 6.0 §2, BigTIFF),
/// `None` for a type the decoder skips.
fn type_bytes(kind: u16) -> Option<u64> {
    match kind {
        1 | 2 | 6 | 7 => Some(1),
        3 | 8 => Some(2),
        4 | 9 | 11 | 13 => Some(4),
        5 | 10 | 12 | 16..=18 => Some(8),
        _ => None,
    }
}

/// Check the first directory of a TIFF file of `size` bytes before the
/// decoder reads it: every entry's values (`count × type size` bytes, in
/// the entry or at its offset) must lie within the file. The decoder sizes
/// a tag's buffer by its count before it reads it; checked here, no tag
/// can make it allocate more than the file holds.
fn check_first_directory(
    file: &mut (impl std::io::Read + std::io::Seek),
    size: u64,
) -> std::result::Result<(), TiffDamage> {
    use std::io::SeekFrom;
    let mut read = |at: u64, n: usize| -> std::result::Result<Vec<u8>, TiffDamage> {
        let mut buf = vec![0; n];
        file.seek(SeekFrom::Start(at))
            .and_then(|_| file.read_exact(&mut buf))
            .map_err(|e| TiffDamage::ShortRead {
                bytes: n,
                offset: at,
                size,
                message: e.to_string(),
            })?;
        Ok(buf)
    };
    let header = read(0, 8)?;
    let little = match &header[..2] {
        b"II" => true,
        b"MM" => false,
        _ => {
            let start = [header[0], header[1]];
            return Err(TiffDamage::ByteOrder { start });
        }
    };
    let uint = |b: &[u8]| -> u64 {
        let mut v = 0u64;
        for (k, &byte) in b.iter().enumerate() {
            let shift = if little { 8 * k } else { 8 * (b.len() - 1 - k) };
            v |= u64::from(byte) << shift;
        }
        v
    };
    let big = match uint(&header[2..4]) {
        42 => false,
        43 => true,
        version => return Err(TiffDamage::Version { version }),
    };
    let (first, count_bytes, entry_bytes, inline) = if big {
        (uint(&read(8, 8)?), 8, 20, 8)
    } else {
        (uint(&header[4..8]), 2, 12, 4)
    };
    let count = uint(&read(first, count_bytes)?);
    let table = count.saturating_mul(entry_bytes as u64);
    if first
        .saturating_add(count_bytes as u64)
        .saturating_add(table)
        > size
    {
        return Err(TiffDamage::DirectoryOutside {
            offset: first,
            count,
            size,
        });
    }
    let entries = read(first + count_bytes as u64, table as usize)?;
    for entry in entries.chunks_exact(entry_bytes) {
        let tag = uint(&entry[..2]);
        let Some(unit) = type_bytes(uint(&entry[2..4]) as u16) else {
            continue;
        };
        let (n, offset) = if big {
            (uint(&entry[4..12]), uint(&entry[12..20]))
        } else {
            (uint(&entry[4..8]), uint(&entry[8..12]))
        };
        let bytes = n.saturating_mul(unit);
        if bytes > inline && offset.saturating_add(bytes) > size {
            return Err(TiffDamage::TagOutside {
                tag,
                count: n,
                bytes,
                offset,
                size,
            });
        }
    }
    Ok(())
}

/// The sample values as `f64`, with the no-data value compared in the
/// samples' own type (a 32-bit file's `GDAL_NODATA` is the 32-bit value).
fn samples(result: DecodingResult, nodata: Option<f64>) -> Vec<Option<f64>> {
    fn convert<T: Copy>(
        values: Vec<T>,
        to_f64: impl Fn(T) -> f64,
        nodata: Option<f64>,
    ) -> Vec<Option<f64>> {
        values
            .into_iter()
            .map(|v| {
                let v = to_f64(v);
                let missing = v.is_nan() || nodata == Some(v);
                (!missing).then_some(v)
            })
            .collect()
    }
    let narrow = nodata.map(|n| n as f32 as f64);
    match result {
        DecodingResult::U8(v) => convert(v, f64::from, nodata),
        DecodingResult::U16(v) => convert(v, f64::from, nodata),
        DecodingResult::U32(v) => convert(v, f64::from, nodata),
        DecodingResult::U64(v) => convert(v, |x| x as f64, nodata),
        DecodingResult::I8(v) => convert(v, f64::from, nodata),
        DecodingResult::I16(v) => convert(v, f64::from, nodata),
        DecodingResult::I32(v) => convert(v, f64::from, nodata),
        DecodingResult::I64(v) => convert(v, |x| x as f64, nodata),
        DecodingResult::F16(v) => convert(v, f64::from, nodata),
        DecodingResult::F32(v) => convert(v, f64::from, narrow),
        DecodingResult::F64(v) => convert(v, |x| x, nodata),
    }
}

/// Read a GeoTIFF file as a [`Raster`] (a DEM, or a map written by
/// [`write_geotiff`], whose values read back to the same bits; its lower
/// corner is found again from the upper-left tie point, `top − rows d`,
/// which may differ from the written `yll` in the last bit).
///
/// What is read: the first image, which must have one band (`Gray`,
/// any integer or floating-point sample type of the `tiff` crate;
/// uncompressed, LZW or Deflate; strips or tiles); its georeferencing from
/// `ModelPixelScale` (square cells: the x and y scales equal within 1e-9
/// of a cell) and one tie point `ModelTiepoint` `(i, j, 0, x, y, z)`
/// (the corner of raster point (i, j), or with `GTRasterTypeGeoKey` =
/// `RasterPixelIsPoint` its centre); `GDAL_NODATA` as the no-data value
/// (compared in the samples' type); NaN samples are no data as well. The
/// coordinate reference system is not read (a [`Raster`] holds none).
///
/// Before any value is decoded, the file is checked as
/// [`super::read_esri_ascii`] checks a text grid: it must be a regular
/// file; the values of every tag of its first directory must lie within
/// it; `width × height` at most [`MAX_GRID_CELLS`]; an uncompressed
/// file at least as large as its values, a compressed one no smaller than
/// its values over [`MAX_GEOTIFF_EXPANSION`]. So the memory the reader
/// takes is bounded by the file's size.
///
/// # Errors
/// [`GridError::GeoTiff`] naming the file and, where one is at fault,
/// the tag and its value, its [`Problem`] one of: a path that cannot be
/// read ([`Problem::CannotRead`]) or is not a regular file
/// ([`Problem::NotRegularFile`]), not a TIFF or a damaged one
/// ([`Problem::Unreadable`], with the decoder's message), more than one
/// band ([`Problem::NotOneBand`]), no `ModelPixelScale` or
/// `ModelTiepoint` ([`Problem::NotGeoreferenced`], or
/// [`Problem::Transformation`] for a `ModelTransformation` instead), cells
/// that are not square ([`Problem::CellsNotSquare`]) or a scale that is
/// not finite and positive ([`Problem::ScaleNotPositive`],
/// [`Problem::ScaleTooShort`]), more than one tie point
/// ([`Problem::TiepointCount`]), a `GTRasterTypeGeoKey` other than area or
/// point ([`Problem::RasterType`], [`Problem::KeyDirectoryDamaged`]), a
/// `GDAL_NODATA` that is not a number ([`Problem::NodataNotNumber`],
/// [`Problem::NodataNotText`]), a tag that is not numbers
/// ([`Problem::TagNotNumbers`]), or values the file cannot hold
/// ([`Problem::ValuesExceedFile`], [`Problem::ValueCount`]);
/// [`GridError::TooLarge`] for more than [`MAX_GRID_CELLS`] cells;
/// [`GridError::Cell`] ([`GridCellProblem::NotFinite`]) for an
/// infinite value (naming its row and column); and
/// [`Problem::Georeference`], holding the error of [`Raster::new`], for a
/// corner or extent that is not finite.
pub fn read_geotiff(path: &Path) -> Result<Raster> {
    let name = path.display().to_string();
    let fail = |problem: Problem| {
        DismechError::Grid(GridError::GeoTiff {
            file: name.clone(),
            problem,
        })
    };
    let cannot = |e: std::io::Error| {
        fail(Problem::CannotRead {
            kind: e.kind(),
            message: e.to_string(),
        })
    };
    let kind = std::fs::metadata(path).map_err(cannot)?.file_type();
    let not_regular = |kind: std::fs::FileType| {
        fail(Problem::NotRegularFile {
            kind: FileKind::of(kind),
        })
    };
    if !kind.is_file() {
        return Err(not_regular(kind));
    }
    let file = std::fs::File::open(path).map_err(cannot)?;
    let meta = file.metadata().map_err(cannot)?;
    if !meta.is_file() {
        return Err(not_regular(meta.file_type()));
    }
    decode(std::io::BufReader::new(file), meta.len(), &name)
}

/// Read the bytes of a GeoTIFF file as a [`Raster`], as [`read_geotiff`]
/// reads a file; `name` names it in errors.
///
/// # Errors
/// Those of [`read_geotiff`] but for the path's.
pub fn parse_geotiff(bytes: &[u8], name: &str) -> Result<Raster> {
    decode(Cursor::new(bytes), bytes.len() as u64, name)
}

/// [`read_geotiff`] after the checks of the path: `reader` holds `size`
/// bytes.
fn decode<R: std::io::Read + std::io::Seek>(
    mut reader: R,
    size: u64,
    name: &str,
) -> Result<Raster> {
    let name = name.to_string();
    let fail = |problem: Problem| {
        DismechError::Grid(GridError::GeoTiff {
            file: name.clone(),
            problem,
        })
    };
    let tiff_error = |e: tiff::TiffError| {
        let damage = TiffDamage::Decoder {
            message: e.to_string(),
        };
        fail(Problem::Unreadable { damage })
    };
    check_first_directory(&mut reader, size)
        .map_err(|damage| fail(Problem::Unreadable { damage }))?;
    reader.rewind().map_err(|e| {
        fail(Problem::CannotRead {
            kind: e.kind(),
            message: e.to_string(),
        })
    })?;
    let mut decoder = Decoder::new(reader).map_err(tiff_error)?;

    let (width, height) = decoder.dimensions().map_err(tiff_error)?;
    let cells = u128::from(width) * u128::from(height);
    if cells > MAX_GRID_CELLS as u128 {
        return Err(DismechError::Grid(GridError::TooLarge {
            file: name.clone(),
            columns: u64::from(width),
            rows: u64::from(height),
            cells,
            cap: MAX_GRID_CELLS,
        }));
    }
    let bits = match decoder.colortype().map_err(tiff_error)? {
        ColorType::Gray(bits) => u64::from(bits),
        other => {
            let color = format!("{other:?}");
            return Err(fail(Problem::NotOneBand { color }));
        }
    };
    let compression: u16 = decoder
        .find_tag_unsigned(Tag::Compression)
        .map_err(tiff_error)?
        .unwrap_or(1);
    let bytes = (cells as u64).saturating_mul(bits.div_ceil(8));
    let holds = if compression == 1 {
        size
    } else {
        size.saturating_mul(MAX_GEOTIFF_EXPANSION)
    };
    if bytes > holds {
        return Err(fail(Problem::ValuesExceedFile {
            width,
            height,
            bits,
            bytes,
            size,
            compression,
        }));
    }

    let not_numbers = |tag: &'static str, number: u16, e: tiff::TiffError| {
        fail(Problem::TagNotNumbers {
            tag,
            number,
            message: e.to_string(),
        })
    };
    let f64_tag =
        |decoder: &mut Decoder<R>, tag: Tag, number: u16, what: &'static str| match decoder
            .find_tag(tag)
            .map_err(tiff_error)?
        {
            None => Ok(None),
            Some(v) => v
                .into_f64_vec()
                .map(Some)
                .map_err(|e| not_numbers(what, number, e)),
        };
    let scale = f64_tag(
        &mut decoder,
        Tag::ModelPixelScaleTag,
        33550,
        "ModelPixelScale",
    )?;
    let tie = f64_tag(&mut decoder, Tag::ModelTiepointTag, 33922, "ModelTiepoint")?;
    let (scale, tie) = match (scale, tie) {
        (Some(scale), Some(tie)) => (scale, tie),
        (scale, tie) => {
            let transformation = decoder
                .find_tag(Tag::ModelTransformationTag)
                .map_err(tiff_error)?
                .is_some();
            let missing = match (scale.is_none(), tie.is_none()) {
                (true, true) => MissingTags::ScaleAndTiepoint,
                (true, false) => MissingTags::Scale,
                _ => MissingTags::Tiepoint,
            };
            return Err(fail(if transformation {
                Problem::Transformation { missing }
            } else {
                Problem::NotGeoreferenced { missing }
            }));
        }
    };
    let (sx, sy) = match scale[..] {
        [sx, sy, ..] => (sx, sy),
        _ => {
            return Err(fail(Problem::ScaleTooShort {
                scale: scale.clone(),
            }))
        }
    };
    if !(sx.is_finite() && sx > 0.0 && sy.is_finite() && sy > 0.0) {
        return Err(fail(Problem::ScaleNotPositive { x: sx, y: sy }));
    }
    if (sx - sy).abs() > 1e-9 * sx {
        return Err(fail(Problem::CellsNotSquare { x: sx, y: sy }));
    }
    let [i, j, _, x, y, _] = tie[..] else {
        return Err(fail(Problem::TiepointCount { values: tie.len() }));
    };
    let keys = match decoder
        .find_tag(Tag::GeoKeyDirectoryTag)
        .map_err(tiff_error)?
    {
        None => Vec::new(),
        Some(v) => v
            .into_u16_vec()
            .map_err(|e| not_numbers("GeoKeyDirectory", 34735, e))?,
    };
    let point = if keys.is_empty() {
        false
    } else {
        pixel_is_point(&keys).map_err(fail)?
    };
    let shift = if point { 0.5 } else { 0.0 };
    let x_left = x - (i + shift) * sx;
    let y_top = y + (j + shift) * sy;
    let nodata = match decoder.find_tag(Tag::GdalNodata).map_err(tiff_error)? {
        None => None,
        Some(v) => {
            let text = v.into_string().map_err(|e| {
                fail(Problem::NodataNotText {
                    message: e.to_string(),
                })
            })?;
            let trimmed = text.trim_matches(|c: char| c.is_whitespace() || c == '\0');
            Some(trimmed.parse::<f64>().map_err(|_| {
                fail(Problem::NodataNotNumber {
                    text: trimmed.to_string(),
                })
            })?)
        }
    };

    let mut limits = Limits::default();
    limits.decoding_buffer_size = usize::try_from(bytes.max(1)).unwrap_or(usize::MAX);
    // A chunk's compressed bytes lie in the file.
    limits.intermediate_buffer_size = usize::try_from(size.max(1)).unwrap_or(usize::MAX);
    let mut decoder = decoder.with_limits(limits);
    let values = samples(decoder.read_image().map_err(tiff_error)?, nodata);
    let (columns, rows) = (width as usize, height as usize);
    if values.len() != columns * rows {
        return Err(fail(Problem::ValueCount {
            decoded: values.len(),
            width,
            height,
        }));
    }
    if let Some(k) = values.iter().position(|v| v.is_some_and(f64::is_infinite)) {
        return Err(DismechError::Grid(GridError::Cell {
            file: name,
            row: k / columns,
            column: k % columns,
            problem: GridCellProblem::NotFinite {
                value: values[k].unwrap_or_default(),
            },
        }));
    }
    Raster::new(columns, rows, x_left, y_top - rows as f64 * sx, sx, values).map_err(|e| {
        fail(Problem::Georeference {
            error: Box::new(e),
            tiepoint: tie.clone(),
            scale: scale.clone(),
            width,
            height,
        })
    })
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
        let bytes = encode(&raster, None).unwrap();
        let mut decoder = Decoder::new(Cursor::new(bytes)).unwrap();
        assert_eq!(decoder.dimensions().unwrap(), (4, 3));
        let scale = decoder.get_tag_f64_vec(Tag::ModelPixelScaleTag).unwrap();
        assert_eq!(scale, [2.5, 2.5, 0.0]);
        let tie = decoder.get_tag_f64_vec(Tag::ModelTiepointTag).unwrap();
        assert_eq!(tie, [0.0, 0.0, 0.0, 1000.0, 2007.5, 0.0]);
        let keys = decoder.get_tag_u16_vec(Tag::GeoKeyDirectoryTag).unwrap();
        assert_eq!(keys, geokey_directory(None));
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
        let mut decoder = Decoder::new(Cursor::new(encode(&raster, None).unwrap())).unwrap();
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
    fn geotiff_reads_back_to_the_same_raster() {
        let dir = std::env::temp_dir().join(format!("dismech-geotiff-rt-{}", std::process::id()));
        let path = dir.join("fs.tif");
        write_geotiff(&path, &sample()).unwrap();
        assert_eq!(read_geotiff(&path).unwrap(), sample());
        let minus = Raster::new(2, 1, 0.0, 0.0, 1.0, vec![Some(-9999.0), None]).unwrap();
        write_geotiff(&path, &minus).unwrap();
        assert_eq!(read_geotiff(&path).unwrap(), minus);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_coordinate_system_adds_its_citation_key_in_order() {
        let keys = geokey_directory(Some(40));
        assert_eq!(keys[..4], [1, 1, 1, 5]);
        let ids: Vec<u16> = keys[4..].chunks_exact(4).map(|k| k[0]).collect();
        assert_eq!(ids, [1024, 1025, 3072, 3073, 3076]);
        assert_eq!(keys[4..8], [1024, 0, 1, geokey::USER_DEFINED]);
        assert_eq!(keys[16..20], [3073, 34737, 40, 0]);
        assert_eq!(pixel_is_point(&keys), Ok(false));
    }

    #[test]
    fn the_raster_type_key_is_found_and_a_damaged_directory_named() {
        assert_eq!(pixel_is_point(&geokey_directory(None)), Ok(false));
        let mut point = geokey_directory(None);
        point[11] = 2;
        assert_eq!(pixel_is_point(&point), Ok(true));
        point[11] = 7;
        assert!(pixel_is_point(&point)
            .unwrap_err()
            .to_string()
            .contains("= 7"));
        assert_eq!(
            pixel_is_point(&point),
            Err(Problem::RasterType {
                value: 7,
                location: 0
            })
        );
        assert!(pixel_is_point(&[1, 1, 1, 9, 1024])
            .unwrap_err()
            .to_string()
            .contains("announces 9 keys"));
    }

    #[test]
    fn geotiff_is_written_atomically_and_an_unwritable_path_is_named() {
        let dir = std::env::temp_dir().join(format!("dismech-geotiff-{}", std::process::id()));
        let path = dir.join("fs.tif");
        write_geotiff(&path, &sample()).unwrap();
        assert_eq!(
            std::fs::read(&path).unwrap(),
            encode(&sample(), None).unwrap()
        );
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
