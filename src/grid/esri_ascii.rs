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

use std::path::Path;

use super::{Raster, MAX_GRID_CELLS};
use crate::error::{DismechError, Result};
use crate::output::write_atomically;

fn format_error(
    file: &str,
    line: usize,
    column: usize,
    message: impl Into<String>,
) -> DismechError {
    DismechError::GridFormat {
        file: file.to_string(),
        line,
        column,
        message: message.into(),
    }
}

/// Read an ESRI ASCII grid file.
pub fn read_esri_ascii(path: &Path) -> Result<Raster> {
    let name = path.display().to_string();
    let text = std::fs::read_to_string(path)
        .map_err(|e| format_error(&name, 0, 0, format!("cannot read the file: {e}")))?;
    parse_esri_ascii(&text, &name)
}

/// A header entry: key and value as written, and where the value stands.
#[derive(Clone, Copy)]
struct Entry<'a> {
    key: &'a str,
    value: &'a str,
    line: usize,
}

impl Entry<'_> {
    fn error(&self, file: &str, requirement: impl Into<String>) -> DismechError {
        DismechError::GridHeader {
            file: file.to_string(),
            line: self.line,
            key: self.key.to_string(),
            value: self.value.to_string(),
            requirement: requirement.into(),
        }
    }

    /// The value as a count of cells: digits only, at least 1.
    fn count(&self, file: &str) -> Result<u64> {
        let digits = self.value.strip_prefix('+').unwrap_or(self.value);
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return Err(self.error(
                file,
                "must be a whole number of cells written in digits (e.g. 24)",
            ));
        }
        match digits.parse::<u64>() {
            Ok(0) => Err(self.error(file, "must be at least 1")),
            Ok(n) => Ok(n),
            Err(_) => Err(self.error(
                file,
                format!("is far more than the {MAX_GRID_CELLS} cells a grid may hold"),
            )),
        }
    }

    /// The value as a number (`nan` and `inf` included).
    fn number(&self, file: &str) -> Result<f64> {
        self.value
            .parse()
            .map_err(|_| self.error(file, "is not a number"))
    }

    /// The value as a finite number.
    fn finite(&self, file: &str) -> Result<f64> {
        let v = self.number(file)?;
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.error(file, "must be a finite number"))
        }
    }
}

/// Parse the text of an ESRI ASCII grid; `name` is used in errors.
///
/// Errors: [`DismechError::GridHeader`] for a header value that cannot be
/// used, [`DismechError::GridTooLarge`] for more than [`MAX_GRID_CELLS`]
/// cells, [`DismechError::GridFormat`] for anything else (a missing key, a
/// value that is not a number, too few or too many values).
pub fn parse_esri_ascii(text: &str, name: &str) -> Result<Raster> {
    // Tokens with their line and column.
    let mut tokens = text.lines().enumerate().flat_map(|(l, line)| {
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
    });
    let mut header: [Option<Entry>; 6] = [None; 6];
    let mut centred = (false, false);
    let keys = ["ncols", "nrows", "xll", "yll", "cellsize", "nodata_value"];
    let first_value;
    loop {
        let Some((line, column, token)) = tokens.next() else {
            return Err(format_error(name, 0, 0, "the file ends inside the header"));
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
            return Err(format_error(
                name,
                line,
                column,
                format!("`{token}` has no value"),
            ));
        };
        if header[slot].is_some() {
            return Err(format_error(
                name,
                line,
                column,
                format!("`{token}` is given twice"),
            ));
        }
        header[slot] = Some(Entry {
            key: token,
            value,
            line: vline,
        });
    }
    let required = |slot: usize| -> Result<Entry> {
        header[slot].ok_or_else(|| {
            let shown = match keys[slot] {
                "xll" => "xllcorner or xllcenter",
                "yll" => "yllcorner or yllcenter",
                other => other,
            };
            format_error(name, 0, 0, format!("the header has no `{shown}`"))
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
        return Err(DismechError::GridTooLarge {
            file: name.to_string(),
            columns,
            rows,
            cells,
            cap: MAX_GRID_CELLS,
        });
    }
    // Lossless: each factor is at most the product, at most MAX_GRID_CELLS.
    let (columns, rows, cells) = (columns as usize, rows as usize, cells as usize);

    let cell = size.finite(name)?;
    if cell <= 0.0 {
        return Err(size.error(name, "must be positive"));
    }
    let corner = |entry: Entry, centred: bool, count: usize| -> Result<f64> {
        let v = entry.finite(name)?;
        let start = if centred { v - 0.5 * cell } else { v };
        let end = start + count as f64 * cell;
        if start.is_finite() && end.is_finite() {
            Ok(start)
        } else {
            Err(entry.error(
                name,
                format!(
                    "the grid would reach past the largest finite coordinate ({count} cells of {cell} from there)"
                ),
            ))
        }
    };
    let x0 = corner(xll, centred.0, columns)?;
    let y0 = corner(yll, centred.1, rows)?;
    let nodata = header[5].map(|entry| entry.number(name)).transpose()?;
    let is_nodata = |v: f64| nodata.is_some_and(|n| n == v || (n.is_nan() && v.is_nan()));

    // Each value takes at least two bytes of text (a digit and a separator):
    // the capacity follows the text, never the header alone.
    let mut values = Vec::with_capacity(cells.min(text.len() / 2 + 1));
    for (line, column, token) in std::iter::once(first_value).chain(tokens) {
        if values.len() == cells {
            return Err(format_error(
                name,
                line,
                column,
                format!("more values than ncols × nrows = {columns} × {rows} = {cells}"),
            ));
        }
        let value: f64 = token.parse().map_err(|_| {
            let (r, c) = (values.len() / columns, values.len() % columns);
            format_error(
                name,
                line,
                column,
                format!("`{token}` is not a number (grid row {r}, column {c})"),
            )
        })?;
        if is_nodata(value) {
            values.push(None);
        } else if value.is_finite() {
            values.push(Some(value));
        } else {
            let (r, c) = (values.len() / columns, values.len() % columns);
            return Err(format_error(
                name,
                line,
                column,
                format!("`{token}` is not finite (grid row {r}, column {c}); mark missing cells with NODATA_value"),
            ));
        }
    }
    if values.len() != cells {
        let (r, c) = (values.len() / columns, values.len() % columns);
        return Err(format_error(
            name,
            0,
            0,
            format!(
                "{} values for ncols × nrows = {columns} × {rows} = {cells}: the data stop in grid row {r} after {c} of {columns} values",
                values.len(),
            ),
        ));
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
            DismechError::GridFormat {
                file,
                line,
                column,
                message,
            } => {
                assert_eq!((file.as_str(), line, column), ("slip.asc", 8, 3));
                assert!(message.contains("row 1, column 1"), "{message}");
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
