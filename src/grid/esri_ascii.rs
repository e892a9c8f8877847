//! The ESRI ASCII grid format.
//!
//! ```text
//! ncols         4
//! nrows         3
//! xllcorner     0.0        (or xllcenter: the centre of the lower-left cell)
//! yllcorner     0.0        (or yllcenter)
//! cellsize      10.0
//! NODATA_value  -9999      (optional)
//! 1 2 3 4                  (rows from north to south)
//! ...
//! ```
//!
//! Keys are case-insensitive. Values may be spread over lines in any way;
//! there must be exactly `ncols × nrows` of them. A NODATA value of `nan`
//! (as some GIS tools write) marks the cells written `nan`. Errors name the
//! file, the line and the column, and for the header the key and its value.
//!
//! The header is checked before any value is read: `ncols` and `nrows` must
//! be whole numbers written in digits, at least 1, with `ncols × nrows`
//! (computed exactly) at most [`MAX_GRID_CELLS`]; the cell size, corner and
//! grid extent must be finite. Memory for the values grows with the values
//! actually read, never with the size the header claims.
//!
//! A file is checked before its text is read ([`read_esri_ascii`]): it must
//! be a regular file (a FIFO would block the reader forever, `/dev/zero`
//! never ends), its header must end within its first [`MAX_HEADER_BYTES`],
//! and its size may not exceed what the header's `ncols × nrows` values can
//! need, [`MAX_BYTES_PER_VALUE`] a value: a 3 GB file of zeros, sparse or
//! not, is refused after reading 64 KiB of it.

use std::path::Path;

use super::error::{FileKind, GridError, GridFormatProblem as Problem, GridHeaderProblem};
use super::{Raster, MAX_GRID_CELLS};
use crate::error::{DismechError, Result};
use crate::io::write_atomically;

fn format_error(file: &str, line: usize, column: usize, problem: Problem) -> DismechError {
    DismechError::Grid(GridError::Format {
        file: file.to_string(),
        line,
        column,
        problem,
    })
}

/// The most bytes read before the header is checked: the header must end
/// (the first value begin) within them.
pub const MAX_HEADER_BYTES: usize = 64 * 1024;

/// The most bytes of text a value of a grid file may take on average,
/// separators included, on top of [`MAX_HEADER_BYTES`] for the header. A
/// number written in full (`-1.2345678901234567e-308`) takes 24; 256 leaves
/// room for any padding a writer uses. A larger file is refused before its
/// values are read: it is not the grid its header describes.
pub const MAX_BYTES_PER_VALUE: u64 = 256;

/// Read an ESRI ASCII grid file.
///
/// The file is checked before its values are read: it must be a regular
/// file (a FIFO would block the reader, a device such as `/dev/zero` never
/// ends), its header must end within its first [`MAX_HEADER_BYTES`], and it
/// may be no larger than [`MAX_HEADER_BYTES`] plus [`MAX_BYTES_PER_VALUE`]
/// for each of the header's `ncols × nrows` values. Then the whole text is
/// parsed as by [`parse_esri_ascii`].
///
/// # Errors
/// [`GridError::Format`] (line 0) for a path that cannot be read
/// ([`Problem::CannotRead`]) or is not a regular file
/// ([`Problem::NotRegularFile`], naming what it is), a file that is not
/// UTF-8 text ([`Problem::NotUtf8`]), a header that does not end within
/// [`MAX_HEADER_BYTES`] ([`Problem::NoCompleteHeader`]), or a file larger
/// than its header's grid can need ([`Problem::FileTooLarge`], naming both
/// sizes); then those of [`parse_esri_ascii`], a header's
/// [`GridError::Header`] and [`GridError::TooLarge`] before
/// any value is read.
pub fn read_esri_ascii(path: &Path) -> Result<Raster> {
    use std::io::Read;
    let name = path.display().to_string();
    let cannot = |e: std::io::Error| {
        let problem = Problem::CannotRead {
            kind: e.kind(),
            message: e.to_string(),
        };
        format_error(&name, 0, 0, problem)
    };
    let not_regular = |kind: std::fs::FileType| {
        let problem = Problem::NotRegularFile {
            kind: FileKind::of(kind),
        };
        format_error(&name, 0, 0, problem)
    };
    // The kind first, without opening: opening a FIFO blocks until a writer
    // comes.
    let kind = std::fs::metadata(path).map_err(cannot)?.file_type();
    if !kind.is_file() {
        return Err(not_regular(kind));
    }
    let mut file = std::fs::File::open(path).map_err(cannot)?;
    // The file opened is the one checked, even if the path changed since.
    let meta = file.metadata().map_err(cannot)?;
    if !meta.is_file() {
        return Err(not_regular(meta.file_type()));
    }
    let size = meta.len();
    let mut bytes = Vec::with_capacity(size.min(MAX_HEADER_BYTES as u64) as usize);
    (&mut file)
        .take(MAX_HEADER_BYTES as u64)
        .read_to_end(&mut bytes)
        .map_err(cannot)?;
    if bytes.len() == MAX_HEADER_BYTES {
        // More may follow: the header decides how much the file may hold.
        let limit = allowed_size(&bytes, &name, size)?;
        let rest = size.saturating_sub(bytes.len() as u64).min(limit) as usize;
        bytes.reserve_exact(rest);
        (&mut file)
            .take(limit + 1 - bytes.len() as u64)
            .read_to_end(&mut bytes)
            .map_err(cannot)?;
        if bytes.len() as u64 > limit {
            // It grew while being read.
            return Err(too_big(&name, bytes.len() as u64, limit));
        }
    }
    let text = String::from_utf8(bytes).map_err(|e| {
        let offset = e.utf8_error().valid_up_to();
        format_error(&name, 0, 0, Problem::NotUtf8 { offset })
    })?;
    parse_esri_ascii(&text, &name)
}

/// The largest size a file may have whose first [`MAX_HEADER_BYTES`] are
/// `head`, from the grid its header describes; the header's errors, or a
/// [`GridError::Format`] when the header does not end in `head` or
/// the file's `size` is over the limit.
fn allowed_size(head: &[u8], name: &str, size: u64) -> Result<u64> {
    // Whole tokens only: cut at the last whitespace, and at the end of the
    // text that is valid UTF-8 (a character may be cut at the end).
    let text = match std::str::from_utf8(head) {
        Ok(text) => text,
        Err(e) if e.error_len().is_none() => {
            std::str::from_utf8(&head[..e.valid_up_to()]).unwrap_or_default()
        }
        Err(e) => {
            let offset = e.valid_up_to();
            return Err(format_error(name, 0, 0, Problem::NotUtf8 { offset }));
        }
    };
    let text = &text[..text.rfind(char::is_whitespace).unwrap_or(0)];
    let Ok((header, _)) = parse_header(&mut tokens(text), name)? else {
        return Err(format_error(name, 0, 0, Problem::NoCompleteHeader { size }));
    };
    let limit = (header.cells as u64)
        .saturating_mul(MAX_BYTES_PER_VALUE)
        .saturating_add(MAX_HEADER_BYTES as u64);
    if size > limit {
        return Err(too_big(name, size, limit));
    }
    Ok(limit)
}

/// A file of `size` bytes, over the `limit` its header's grid can need.
fn too_big(name: &str, size: u64, limit: u64) -> DismechError {
    format_error(name, 0, 0, Problem::FileTooLarge { size, limit })
}

/// A header entry: key and value as written, and where the value stands.
#[derive(Clone, Copy)]
struct Entry<'a> {
    key: &'a str,
    value: &'a str,
    line: usize,
}

impl Entry<'_> {
    fn error(&self, file: &str, requirement: GridHeaderProblem) -> DismechError {
        DismechError::Grid(GridError::Header {
            file: file.to_string(),
            line: self.line,
            key: self.key.to_string(),
            value: self.value.to_string(),
            requirement,
        })
    }

    /// The value as a count of cells: digits only, at least 1.
    fn count(&self, file: &str) -> Result<u64> {
        let digits = self.value.strip_prefix('+').unwrap_or(self.value);
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return Err(self.error(file, GridHeaderProblem::NotWholeNumber));
        }
        match digits.parse::<u64>() {
            Ok(0) => Err(self.error(file, GridHeaderProblem::Zero)),
            Ok(n) => Ok(n),
            Err(_) => Err(self.error(file, GridHeaderProblem::CountOverflow)),
        }
    }

    /// The value as a number (`nan` and `inf` included).
    fn number(&self, file: &str) -> Result<f64> {
        self.value
            .parse()
            .map_err(|_| self.error(file, GridHeaderProblem::NotANumber))
    }

    /// The value as a finite number.
    fn finite(&self, file: &str) -> Result<f64> {
        let v = self.number(file)?;
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.error(file, GridHeaderProblem::NotFinite))
        }
    }
}

/// The tokens of `text` with their line and column (from 1).
fn tokens(text: &str) -> impl Iterator<Item = (usize, usize, &str)> {
    text.lines().enumerate().flat_map(|(l, line)| {
        let mut out = Vec::new();
        let mut start = None;
        for (c, ch) in line
            .char_indices()
            .chain(std::iter::once((line.len(), ' ')))
        {
            match (ch.is_whitespace(), start) {
                (false, None) => start = Some(c),
                (true, Some(s)) => {
                    out.push((l + 1, s + 1, &line[s..c]));
                    start = None;
                }
                _ => {}
            }
        }
        out
    })
}

/// A header, checked.
struct Header {
    columns: usize,
    rows: usize,
    cells: usize,
    x0: f64,
    y0: f64,
    cell: f64,
    nodata: Option<f64>,
}

/// A token with its line and column.
type Token<'a> = (usize, usize, &'a str);

/// Read and check the header from `tokens`, up to the first value, which
/// it returns with the header. The inner error is the tokens ending inside
/// the header (a key without its value, or no value after the keys): an
/// error of a whole text, not of a text cut short.
fn parse_header<'a>(
    tokens: &mut impl Iterator<Item = Token<'a>>,
    name: &str,
) -> Result<std::result::Result<(Header, Token<'a>), DismechError>> {
    let mut header: [Option<Entry>; 6] = [None; 6];
    let mut centred = (false, false);
    let keys = ["ncols", "nrows", "xll", "yll", "cellsize", "nodata_value"];
    let first_value;
    loop {
        let Some((line, column, token)) = tokens.next() else {
            return Ok(Err(format_error(name, 0, 0, Problem::EndsInsideHeader)));
        };
        let lower = token.to_ascii_lowercase();
        let slot = match lower.as_str() {
            "ncols" => Some(0),
            "nrows" => Some(1),
            "xllcorner" | "xllcenter" => {
                centred.0 = lower.ends_with("center");
                Some(2)
            }
            "yllcorner" | "yllcenter" => {
                centred.1 = lower.ends_with("center");
                Some(3)
            }
            "cellsize" => Some(4),
            "nodata_value" => Some(5),
            _ => None,
        };
        let Some(slot) = slot else {
            first_value = (line, column, token);
            break;
        };
        let Some((vline, _, value)) = tokens.next() else {
            let key = token.to_string();
            return Ok(Err(format_error(
                name,
                line,
                column,
                Problem::KeyWithoutValue { key },
            )));
        };
        if header[slot].is_some() {
            let key = token.to_string();
            return Err(format_error(name, line, column, Problem::KeyTwice { key }));
        }
        header[slot] = Some(Entry {
            key: token,
            value,
            line: vline,
        });
    }
    let required = |slot: usize| -> Result<Entry> {
        header[slot].ok_or_else(|| {
            let key = match keys[slot] {
                "xll" => "xllcorner or xllcenter",
                "yll" => "yllcorner or yllcenter",
                other => other,
            };
            format_error(name, 0, 0, Problem::MissingKey { key })
        })
    };
    let (ncols, nrows, xll, yll, size) = (
        required(0)?,
        required(1)?,
        required(2)?,
        required(3)?,
        required(4)?,
    );

    // Size first: nothing is allocated from it before it is checked.
    let (columns, rows) = (ncols.count(name)?, nrows.count(name)?);
    let cells = u128::from(columns) * u128::from(rows);
    if cells > MAX_GRID_CELLS as u128 {
        return Err(DismechError::Grid(GridError::TooLarge {
            file: name.to_string(),
            columns,
            rows,
            cells,
            cap: MAX_GRID_CELLS,
        }));
    }
    // Lossless: each factor is at most the product, at most MAX_GRID_CELLS.
    let (columns, rows, cells) = (columns as usize, rows as usize, cells as usize);

    let cell = size.finite(name)?;
    if cell <= 0.0 {
        return Err(size.error(name, GridHeaderProblem::NotPositive));
    }
    let corner = |entry: Entry, centred: bool, count: usize| -> Result<f64> {
        let v = entry.finite(name)?;
        let start = if centred { v - 0.5 * cell } else { v };
        let end = start + count as f64 * cell;
        if start.is_finite() && end.is_finite() {
            Ok(start)
        } else {
            let problem = GridHeaderProblem::ReachesInfinity {
                count,
                cell_size: cell,
            };
            Err(entry.error(name, problem))
        }
    };
    let x0 = corner(xll, centred.0, columns)?;
    let y0 = corner(yll, centred.1, rows)?;
    let nodata = header[5].map(|entry| entry.number(name)).transpose()?;
    Ok(Ok((
        Header {
            columns,
            rows,
            cells,
            x0,
            y0,
            cell,
            nodata,
        },
        first_value,
    )))
}

/// Parse the text of an ESRI ASCII grid; `name` is used in errors.
///
/// # Errors
/// [`GridError::Header`] for a header value that cannot be used
/// (its [`GridHeaderProblem`] says what it must satisfy),
/// [`GridError::TooLarge`] for more than [`MAX_GRID_CELLS`] cells,
/// [`GridError::Format`] for anything else: a header cut short
/// ([`Problem::EndsInsideHeader`], [`Problem::KeyWithoutValue`]), a key
/// given twice ([`Problem::KeyTwice`]) or missing
/// ([`Problem::MissingKey`]), a value that is not a number
/// ([`Problem::NotANumber`]) or not finite ([`Problem::NotFinite`]), too
/// many or too few values ([`Problem::TooManyValues`],
/// [`Problem::TooFewValues`]).
pub fn parse_esri_ascii(text: &str, name: &str) -> Result<Raster> {
    let mut tokens = tokens(text);
    let (header, first_value) = parse_header(&mut tokens, name)??;
    let Header {
        columns,
        rows,
        cells,
        x0,
        y0,
        cell,
        nodata,
    } = header;
    let is_nodata = |v: f64| nodata.is_some_and(|n| n == v || (n.is_nan() && v.is_nan()));

    // Each value takes at least two bytes of text (a digit and a separator):
    // the capacity follows the text, never the header alone.
    let mut values = Vec::with_capacity(cells.min(text.len() / 2 + 1));
    for (line, column, token) in std::iter::once(first_value).chain(tokens) {
        if values.len() == cells {
            let problem = Problem::TooManyValues { columns, rows };
            return Err(format_error(name, line, column, problem));
        }
        let value: f64 = token.parse().map_err(|_| {
            let problem = Problem::NotANumber {
                text: token.to_string(),
                row: values.len() / columns,
                column: values.len() % columns,
            };
            format_error(name, line, column, problem)
        })?;
        if is_nodata(value) {
            values.push(None);
        } else if value.is_finite() {
            values.push(Some(value));
        } else {
            let problem = Problem::NotFinite {
                text: token.to_string(),
                row: values.len() / columns,
                column: values.len() % columns,
            };
            return Err(format_error(name, line, column, problem));
        }
    }
    if values.len() != cells {
        let problem = Problem::TooFewValues {
            found: values.len(),
            columns,
            rows,
        };
        return Err(format_error(name, 0, 0, problem));
    }
    Raster::new(columns, rows, x0, y0, cell, values)
}

/// The ESRI ASCII text of a raster (corner convention, NODATA −9999).
pub fn to_esri_ascii(raster: &Raster) -> String {
    let (x0, y0) = raster.lower_left();
    let mut text = format!(
        "ncols {}\nnrows {}\nxllcorner {}\nyllcorner {}\ncellsize {}\nNODATA_value -9999\n",
        raster.columns(),
        raster.rows(),
        x0,
        y0,
        raster.cell_size()
    );
    for row in raster.values().chunks(raster.columns()) {
        let line: Vec<String> = row
            .iter()
            .map(|v| v.map_or_else(|| "-9999".to_string(), |v| format!("{v}")))
            .collect();
        text.push_str(&line.join(" "));
        text.push('\n');
    }
    text
}

/// Write a raster as an ESRI ASCII grid file, atomically.
///
/// # Errors
/// [`DismechError::Output`](crate::error::DismechError::Output) naming the
/// path when its folder cannot be created or the file cannot be written
/// (see [`crate::io::write_atomically`]); the file is then not there.
pub fn write_esri_ascii(path: &Path, raster: &Raster) -> Result<()> {
    write_atomically(path, to_esri_ascii(raster).as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    const SAMPLE: &str = "NCOLS 3\nnrows 2\nxllcenter 5.0\nyllcorner 100\ncellsize 10\nNODATA_value -9999\n1 2 -9999\n4 5.5 6\n";

    #[test]
    fn esri_grid_is_read_with_centre_convention_and_no_data() {
        let r = parse_esri_ascii(SAMPLE, "sample.asc").unwrap();
        assert_eq!((r.columns(), r.rows()), (3, 2));
        assert_eq!(r.lower_left(), (0.0, 100.0));
        assert_eq!(r.get(0, 2), None);
        assert_eq!(r.get(1, 1), Some(5.5));
        // Row 0 is the top row: its centre is half a cell below the top.
        assert_eq!(r.cell_centre(0, 0), (5.0, 115.0));
    }

    #[test]
    fn esri_grid_round_trips_through_text() {
        let r = Raster::from_fn(4, 3, 1.0, 2.0, 0.5, |x, y| {
            if x > 2.5 {
                None
            } else {
                Some(x * y)
            }
        })
        .unwrap();
        let back = parse_esri_ascii(&to_esri_ascii(&r), "mem").unwrap();
        assert_eq!(back, r);
    }

    #[test]
    fn esri_grid_errors_name_file_line_and_column() {
        let bad = SAMPLE.replace("5.5", "5,5");
        match parse_esri_ascii(&bad, "slip.asc").unwrap_err() {
            DismechError::Grid(GridError::Format {
                file,
                line,
                column,
                problem,
            }) => {
                assert_eq!((file.as_str(), line, column), ("slip.asc", 8, 3));
                assert!(problem.to_string().contains("row 1, column 1"), "{problem}");
                let text = "5,5".to_string();
                let (row, column) = (1, 1);
                assert_eq!(problem, Problem::NotANumber { text, row, column });
            }
            other => panic!("{other}"),
        }
        let short = SAMPLE.replace(" 6\n", "\n");
        assert!(parse_esri_ascii(&short, "a.asc")
            .unwrap_err()
            .to_string()
            .contains("5 values"));
        let no_size = SAMPLE.replace("cellsize 10\n", "");
        assert!(parse_esri_ascii(&no_size, "a.asc")
            .unwrap_err()
            .to_string()
            .contains("cellsize"));
        let nan = SAMPLE.replace("5.5", "NaN");
        assert!(parse_esri_ascii(&nan, "a.asc")
            .unwrap_err()
            .to_string()
            .contains("not finite"));
    }
}
