//! Grid-file errors: [`GridError`], joined into [`DismechError::Grid`],
//! and the causes its variants carry ([`GridFormatProblem`],
//! [`GridHeaderProblem`], [`GeoTiffProblem`], [`GridCellProblem`],
//! [`GridExtent`]), one variant a cause, so that a caller can `match` on
//! it; each one's Display is the message's text.

use super::{MAX_BYTES_PER_VALUE, MAX_GRID_CELLS, MAX_HEADER_BYTES};
use crate::error::DismechError;

/// Why a grid file cannot be read or used; joined into
/// [`DismechError::Grid`]. Each names the file.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GridError {
    /// A grid file (ESRI ASCII raster) is malformed.
    #[error("{file}, line {line}, column {column}: {problem}")]
    Format {
        /// The file (or the name given to the text).
        file: String,
        /// Line number, from 1 (0 when the problem is the file as a whole).
        line: usize,
        /// Column (character position in the line), from 1.
        column: usize,
        /// What is wrong.
        problem: GridFormatProblem,
    },
    /// A value of a grid file's header cannot be used (a count that is not
    /// a whole number, a cell size that is not positive, a coordinate or
    /// NODATA value that is not a number...).
    #[error("{file}, line {line}: `{key} {value}`: {requirement}")]
    Header {
        /// The file (or the name given to the text).
        file: String,
        /// Line of the value, from 1.
        line: usize,
        /// The key as written in the file (e.g. `ncols`).
        key: String,
        /// The value as written in the file.
        value: String,
        /// What the value must satisfy.
        requirement: GridHeaderProblem,
    },
    /// A grid file's header asks for more cells than a grid may hold
    /// ([`MAX_GRID_CELLS`]); refused before any value is read.
    #[error("{file}: ncols × nrows = {columns} × {rows} = {cells} cells, more than the {cap} cells a grid may hold; crop or coarsen the grid")]
    TooLarge {
        /// The file (or the name given to the text).
        file: String,
        /// `ncols` as given.
        columns: u64,
        /// `nrows` as given.
        rows: u64,
        /// Their exact product.
        cells: u128,
        /// The largest number of cells accepted.
        cap: usize,
    },
    /// A GeoTIFF file cannot be read as a raster: not a TIFF, damaged, or a
    /// TIFF without what a raster needs (one band, square cells, a tie
    /// point), naming the tag and its value.
    #[error("{file}: {problem}")]
    GeoTiff {
        /// The file.
        file: String,
        /// What is wrong, naming the tag and its value.
        problem: GeoTiffProblem,
    },
    /// A cell of a grid file cannot be used (no data inside the slide, a
    /// water table missing over a column, ...).
    #[error("{file}, grid row {row}, column {column}: {problem}")]
    Cell {
        /// The file (or the name given to the raster).
        file: String,
        /// Grid row, from 0 at the top (north) as in the file.
        row: usize,
        /// Grid column, from 0 at the left (west).
        column: usize,
        /// What is wrong.
        problem: GridCellProblem,
    },
    /// Two grid files do not lie on the same grid.
    #[error("{file} does not lie on the grid of {reference}: {found} against {expected} (rows × columns, cell size, lower-left corner)")]
    Mismatch {
        /// The file that differs.
        file: String,
        /// The file whose grid is the reference.
        reference: String,
        /// The grid of `file` (boxed: it keeps the error small).
        found: Box<GridExtent>,
        /// The grid of `reference`.
        expected: Box<GridExtent>,
    },
}

/// What a path that is not a regular file is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum FileKind {
    /// A FIFO (named pipe): reading it would block.
    #[error("a FIFO (named pipe)")]
    Fifo,
    /// A character device (e.g. `/dev/zero`, which never ends).
    #[error("a character device")]
    CharacterDevice,
    /// A block device.
    #[error("a block device")]
    BlockDevice,
    /// A socket.
    #[error("a socket")]
    Socket,
    /// A directory.
    #[error("a directory")]
    Directory,
    /// Anything else that is not a regular file.
    #[error("not a regular file")]
    Other,
}

impl FileKind {
    /// The kind of a path whose type is `kind` (not a regular file).
    pub(super) fn of(kind: std::fs::FileType) -> FileKind {
        #[cfg(unix)]
        {
            use std::os::unix::fs::FileTypeExt;
            if kind.is_fifo() {
                return FileKind::Fifo;
            }
            if kind.is_char_device() {
                return FileKind::CharacterDevice;
            }
            if kind.is_block_device() {
                return FileKind::BlockDevice;
            }
            if kind.is_socket() {
                return FileKind::Socket;
            }
        }
        if kind.is_dir() {
            FileKind::Directory
        } else {
            FileKind::Other
        }
    }
}

/// Why an ESRI ASCII grid file is malformed ([`GridError::Format`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GridFormatProblem {
    /// The operating system could not read the file.
    #[error("cannot read the file: {message}")]
    CannotRead {
        /// The kind of the I/O error.
        kind: std::io::ErrorKind,
        /// The operating system's message.
        message: String,
    },
    /// The path is not a regular file.
    #[error("is {kind}, not a regular file: give the path of an ESRI ASCII grid file")]
    NotRegularFile {
        /// What it is.
        kind: FileKind,
    },
    /// The file is not UTF-8 text.
    #[error("is not UTF-8 text (invalid byte at offset {offset}): an ESRI ASCII grid is text")]
    NotUtf8 {
        /// Offset of the first invalid byte.
        offset: usize,
    },
    /// The header does not end within the first [`MAX_HEADER_BYTES`].
    #[error("no complete header in the first {MAX_HEADER_BYTES} bytes of a file of {size} bytes: an ESRI ASCII grid starts with ncols, nrows, xllcorner, yllcorner, cellsize (and NODATA_value), then its values")]
    NoCompleteHeader {
        /// The file's size in bytes.
        size: u64,
    },
    /// The file is larger than its header's grid can need.
    #[error("the file has {size} bytes, more than the {limit} its header's grid can need ({MAX_HEADER_BYTES} for the header and {MAX_BYTES_PER_VALUE} a value): it is not the grid its header describes (check ncols and nrows), or its values are padded far beyond any writer's")]
    FileTooLarge {
        /// The file's size in bytes.
        size: u64,
        /// The most bytes its header's grid can need.
        limit: u64,
    },
    /// The coordinate system beside a grid (its `.prj` file) cannot be
    /// read as text.
    #[error("the coordinate system beside the DEM cannot be read as text: {message}")]
    CrsUnreadable {
        /// The kind of the I/O error.
        kind: std::io::ErrorKind,
        /// The operating system's message.
        message: String,
    },
    /// The coordinate system beside a grid (its `.prj` file) is one a
    /// GeoTIFF cannot keep.
    #[error("the coordinate system beside the DEM: {problem}")]
    CrsNotKept {
        /// Why a GeoTIFF cannot keep it.
        problem: CrsProblem,
    },
    /// The text ends before the first value.
    #[error("the file ends inside the header")]
    EndsInsideHeader,
    /// A header key is the last word of the text.
    #[error("`{key}` has no value")]
    KeyWithoutValue {
        /// The key as written.
        key: String,
    },
    /// A header key is given twice.
    #[error("`{key}` is given twice")]
    KeyTwice {
        /// The key as written the second time.
        key: String,
    },
    /// A required header key is missing.
    #[error("the header has no `{key}`")]
    MissingKey {
        /// The key (`ncols`, `nrows`, `xllcorner or xllcenter`,
        /// `yllcorner or yllcenter`, `cellsize`).
        key: &'static str,
    },
    /// More values than `ncols × nrows`.
    #[error("more values than ncols × nrows = {columns} × {rows} = {}", columns * rows)]
    TooManyValues {
        /// `ncols`.
        columns: usize,
        /// `nrows`.
        rows: usize,
    },
    /// A value that is not a number.
    #[error("`{text}` is not a number (grid row {row}, column {column})")]
    NotANumber {
        /// The value as written.
        text: String,
        /// Grid row, from 0 at the top.
        row: usize,
        /// Grid column, from 0 at the left.
        column: usize,
    },
    /// A value that is infinite or NaN and not the NODATA value.
    #[error("`{text}` is not finite (grid row {row}, column {column}); mark missing cells with NODATA_value")]
    NotFinite {
        /// The value as written.
        text: String,
        /// Grid row, from 0 at the top.
        row: usize,
        /// Grid column, from 0 at the left.
        column: usize,
    },
    /// Fewer values than `ncols × nrows`.
    #[error("{found} values for ncols × nrows = {columns} × {rows} = {}: the data stop in grid row {} after {} of {columns} values", columns * rows, found / columns, found % columns)]
    TooFewValues {
        /// The values found.
        found: usize,
        /// `ncols`.
        columns: usize,
        /// `nrows`.
        rows: usize,
    },
}

/// Why a value of an ESRI ASCII grid's header cannot be used
/// ([`GridError::Header`]); the Display says what it must satisfy.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GridHeaderProblem {
    /// A count (`ncols`, `nrows`) not written as digits.
    #[error("must be a whole number of cells written in digits (e.g. 24)")]
    NotWholeNumber,
    /// A count of zero.
    #[error("must be at least 1")]
    Zero,
    /// A count too large for a 64-bit integer.
    #[error("is far more than the {MAX_GRID_CELLS} cells a grid may hold")]
    CountOverflow,
    /// A value that is not a number.
    #[error("is not a number")]
    NotANumber,
    /// A value that must be finite and is not.
    #[error("must be a finite number")]
    NotFinite,
    /// A cell size that is not positive.
    #[error("must be positive")]
    NotPositive,
    /// A corner from which the grid would reach past the largest finite
    /// coordinate.
    #[error("the grid would reach past the largest finite coordinate ({count} cells of {cell_size} from there)")]
    ReachesInfinity {
        /// Cells along the axis.
        count: usize,
        /// The cell size.
        cell_size: f64,
    },
}

/// Which georeferencing tags a GeoTIFF lacks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum MissingTags {
    /// Both `ModelPixelScale` and `ModelTiepoint`.
    #[error("ModelPixelScale (33550) and ModelTiepoint (33922)")]
    ScaleAndTiepoint,
    /// `ModelPixelScale`.
    #[error("ModelPixelScale (33550)")]
    Scale,
    /// `ModelTiepoint`.
    #[error("ModelTiepoint (33922)")]
    Tiepoint,
}

/// Why the structure of a TIFF file cannot be read
/// ([`GeoTiffProblem::Unreadable`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TiffDamage {
    /// The `tiff` crate's decoder refused the file.
    #[error("{message}")]
    Decoder {
        /// The decoder's message.
        message: String,
    },
    /// Bytes of the file's structure could not be read.
    #[error("cannot read {bytes} bytes at offset {offset} of {size}: {message}")]
    ShortRead {
        /// Bytes asked for.
        bytes: usize,
        /// Where.
        offset: u64,
        /// The file's size.
        size: u64,
        /// The operating system's message.
        message: String,
    },
    /// The first two bytes are not a TIFF byte order.
    #[error("it starts with {start:?}, not a TIFF byte order (`II` or `MM`)")]
    ByteOrder {
        /// The first two bytes.
        start: [u8; 2],
    },
    /// The version is neither TIFF's nor BigTIFF's.
    #[error("TIFF version {version}: expected 42 (TIFF) or 43 (BigTIFF)")]
    Version {
        /// The version found.
        version: u64,
    },
    /// The first directory's entries do not fit in the file.
    #[error("its first directory, at offset {offset}, announces {count} entries, which do not fit in the file's {size} bytes")]
    DirectoryOutside {
        /// Offset of the directory.
        offset: u64,
        /// Entries announced.
        count: u64,
        /// The file's size.
        size: u64,
    },
    /// A tag's values lie beyond the end of the file.
    #[error("tag {tag} announces {count} values ({bytes} bytes) at offset {offset}, beyond the file's {size} bytes")]
    TagOutside {
        /// The tag's number.
        tag: u64,
        /// Values announced.
        count: u64,
        /// Their bytes.
        bytes: u64,
        /// Where they would start.
        offset: u64,
        /// The file's size.
        size: u64,
    },
}

/// Why a GeoTIFF file cannot be read as a raster
/// ([`GridError::GeoTiff`]), naming the tag and its value where one is
/// at fault.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GeoTiffProblem {
    /// The operating system could not read the file.
    #[error("cannot read the file: {message}")]
    CannotRead {
        /// The kind of the I/O error.
        kind: std::io::ErrorKind,
        /// The operating system's message.
        message: String,
    },
    /// The path is not a regular file.
    #[error("is {kind}, not a regular file: give the path of a GeoTIFF file")]
    NotRegularFile {
        /// What it is.
        kind: FileKind,
    },
    /// Not a TIFF, or a damaged one.
    #[error("not a TIFF file that can be read: {damage}")]
    Unreadable {
        /// What is wrong with it.
        damage: TiffDamage,
    },
    /// An image that is not one band of values.
    #[error("its image is {color}: a raster is one band of values (a DEM), not a colour or multi-band image")]
    NotOneBand {
        /// The image's colour type, as the `tiff` crate names it.
        color: String,
    },
    /// More values than the file can hold.
    #[error("{width} × {height} values of {bits} bits ({bytes} bytes) cannot be held in a file of {size} bytes (compression {compression}): the file is truncated or damaged")]
    ValuesExceedFile {
        /// Columns.
        width: u32,
        /// Rows.
        height: u32,
        /// Bits a sample.
        bits: u64,
        /// Bytes of the values.
        bytes: u64,
        /// The file's size.
        size: u64,
        /// The `Compression` tag (1: none).
        compression: u16,
    },
    /// A tag whose values are not numbers.
    #[error("{tag} ({number}) cannot be read as numbers: {message}")]
    TagNotNumbers {
        /// The tag's name.
        tag: &'static str,
        /// The tag's number.
        number: u16,
        /// The decoder's message.
        message: String,
    },
    /// Georeferenced by a transformation matrix instead of a scale and a
    /// tie point.
    #[error("is georeferenced by a ModelTransformation (34264), which may rotate the grid; a raster needs {missing}: warp it onto a north-up grid (gdalwarp)")]
    Transformation {
        /// The tags it lacks.
        missing: MissingTags,
    },
    /// Not georeferenced.
    #[error("has no {missing}: it is not georeferenced (a GeoTIFF DEM has both)")]
    NotGeoreferenced {
        /// The tags it lacks.
        missing: MissingTags,
    },
    /// A `ModelPixelScale` of fewer than two values.
    #[error("ModelPixelScale (33550) = {scale:?}: expected (x scale, y scale, z scale)")]
    ScaleTooShort {
        /// The values.
        scale: Vec<f64>,
    },
    /// Cell sides that are not finite and positive.
    #[error("ModelPixelScale (33550) = ({x}, {y}): the cell sides must be finite and positive")]
    ScaleNotPositive {
        /// x scale.
        x: f64,
        /// y scale.
        y: f64,
    },
    /// Cells that are not square.
    #[error("ModelPixelScale (33550) = ({x}, {y}): cells of {x} × {y} m; a raster has square cells: resample it (gdalwarp -tr)")]
    CellsNotSquare {
        /// x scale.
        x: f64,
        /// y scale.
        y: f64,
    },
    /// A `ModelTiepoint` that is not one tie point.
    #[error("ModelTiepoint (33922) has {values} values: expected one tie point (i, j, k, x, y, z), 6 values")]
    TiepointCount {
        /// Values found.
        values: usize,
    },
    /// A GeoKey directory shorter than it announces.
    #[error("GeoKeyDirectory (34735) of {values} values announces {keys} keys: it is damaged")]
    KeyDirectoryDamaged {
        /// Values found.
        values: usize,
        /// Keys announced.
        keys: usize,
    },
    /// A raster type other than area or point.
    #[error("GTRasterTypeGeoKey (1025) = {value} (location {location}): expected 1 (RasterPixelIsArea) or 2 (RasterPixelIsPoint)")]
    RasterType {
        /// The key's value.
        value: u16,
        /// The key's location.
        location: u16,
    },
    /// A `GDAL_NODATA` that is not text.
    #[error("GDAL_NODATA (42113) is not text: {message}")]
    NodataNotText {
        /// The decoder's message.
        message: String,
    },
    /// A `GDAL_NODATA` that is not a number.
    #[error("GDAL_NODATA (42113) = `{text}`: not a number")]
    NodataNotNumber {
        /// The text, trimmed.
        text: String,
    },
    /// The decoder gave another number of values than cells.
    #[error("{decoded} values decoded for {width} × {height} cells")]
    ValueCount {
        /// Values decoded.
        decoded: usize,
        /// Columns.
        width: u32,
        /// Rows.
        height: u32,
    },
    /// A georeferencing that gives no finite grid.
    #[error("{error} (from ModelTiepoint (33922) = {tiepoint:?} and ModelPixelScale (33550) = {scale:?}, {width} × {height} cells)")]
    Georeference {
        /// The raster's refusal ([`crate::grid::Raster::new`]).
        error: Box<DismechError>,
        /// The tie point's values.
        tiepoint: Vec<f64>,
        /// The scale's values.
        scale: Vec<f64>,
        /// Columns.
        width: u32,
        /// Rows.
        height: u32,
    },
}

/// Why a cell of a grid cannot be used ([`GridError::Cell`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GridCellProblem {
    /// A value that is not finite.
    #[error("value {value}: not finite")]
    NotFinite {
        /// The value.
        value: f64,
    },
    /// No ground data where the slip surface is given.
    #[error("no ground data where the slip surface is given (inside the slide)")]
    NoGround,
    /// A hole in the slip surface with valid columns on both sides.
    #[error("no slip-surface data inside the slide (valid columns on both sides)")]
    SlipSurfaceHole,
    /// No water-table data over a valid column.
    #[error("no water-table data over a valid column")]
    NoWaterTable,
}

/// A grid's extent: what two rasters on one grid share.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridExtent {
    /// Rows.
    pub rows: usize,
    /// Columns.
    pub columns: usize,
    /// Cell size (m).
    pub cell_size: f64,
    /// Lower-left corner (m).
    pub lower_left: (f64, f64),
}

impl GridExtent {
    /// The extent of `raster`.
    pub fn of(raster: &super::Raster) -> GridExtent {
        GridExtent {
            rows: raster.rows(),
            columns: raster.columns(),
            cell_size: raster.cell_size(),
            lower_left: raster.lower_left(),
        }
    }
}

impl std::fmt::Display for GridExtent {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} × {} cells of {} m at {:?}",
            self.rows, self.columns, self.cell_size, self.lower_left
        )
    }
}

/// Why a GeoTIFF cannot keep a coordinate system (an ESRI WKT) in its
/// citation key.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum CrsProblem {
    /// A character outside printable ASCII, or `|` (which ends a key).
    #[error("the coordinate system's WKT holds {character:?}, which a GeoTIFF's ASCII key cannot keep (printable ASCII other than `|` only)")]
    Character {
        /// The first such character.
        character: char,
    },
    /// Longer than GDAL reads of the citation.
    #[error("the coordinate system's WKT is {length} characters long; GDAL reads at most {limit} of the citation `ESRI PE String = <wkt>|`")]
    TooLong {
        /// The WKT's length, trimmed.
        length: usize,
        /// [`super::MAX_CRS_CITATION`].
        limit: usize,
    },
}
