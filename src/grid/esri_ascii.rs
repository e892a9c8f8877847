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
//! there must be exactly `ncols × nrows` of them. Errors name the file, the
//! line and the column.

use std::path::Path;

use super::Raster;
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

/// Parse the text of an ESRI ASCII grid; `name` is used in errors.
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
    let mut header: [Option<f64>; 6] = [None; 6];
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
        let Some((vline, vcolumn, value)) = tokens.next() else {
            return Err(format_error(
                name,
                line,
                column,
                format!("`{token}` has no value"),
            ));
        };
        let parsed: f64 = value.parse().map_err(|_| {
            format_error(
                name,
                vline,
                vcolumn,
                format!("`{value}` is not a number (value of `{token}`)"),
            )
        })?;
        if header[slot].is_some() {
            return Err(format_error(
                name,
                line,
                column,
                format!("`{token}` is given twice"),
            ));
        }
        header[slot] = Some(parsed);
    }
    for (slot, key) in keys.iter().enumerate().take(5) {
        if header[slot].is_none() {
            let shown = match *key {
                "xll" => "xllcorner or xllcenter",
                "yll" => "yllcorner or yllcenter",
                other => other,
            };
            return Err(format_error(
                name,
                0,
                0,
                format!("the header has no `{shown}`"),
            ));
        }
    }
    let count = |v: f64, key: &str| -> Result<usize> {
        if v.fract() == 0.0 && v >= 1.0 {
            Ok(v as usize)
        } else {
            Err(format_error(
                name,
                0,
                0,
                format!("`{key}` = {v} is not a positive whole number"),
            ))
        }
    };
    let columns = count(header[0].unwrap_or(0.0), "ncols")?;
    let rows = count(header[1].unwrap_or(0.0), "nrows")?;
    let cell = header[4].unwrap_or(0.0);
    if !(cell.is_finite() && cell > 0.0) {
        return Err(format_error(
            name,
            0,
            0,
            format!("`cellsize` = {cell} must be positive"),
        ));
    }
    let shift = |c: bool| if c { 0.5 * cell } else { 0.0 };
    let x0 = header[2].unwrap_or(0.0) - shift(centred.0);
    let y0 = header[3].unwrap_or(0.0) - shift(centred.1);
    let nodata = header[5];

    let mut values = Vec::with_capacity(columns * rows);
    for (line, column, token) in std::iter::once(first_value).chain(tokens) {
        if values.len() == columns * rows {
            return Err(format_error(
                name,
                line,
                column,
                format!("more values than ncols × nrows = {}", columns * rows),
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
        if nodata == Some(value) {
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
    if values.len() != columns * rows {
        return Err(format_error(
            name,
            0,
            0,
            format!(
                "{} values for ncols × nrows = {}",
                values.len(),
                columns * rows
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
