//! CSV tables of numbers, written whole or not at all.

use std::path::Path;

use dismech::error::Result;
use dismech::io::write_atomically;

/// Write a CSV table (header and rows of numbers) atomically.
pub fn write_csv(path: &Path, header: &[&str], rows: &[Vec<f64>]) -> Result<()> {
    let mut text = header.join(",");
    text.push('\n');
    for row in rows {
        let line: Vec<String> = row.iter().map(|v| format!("{v:.9e}")).collect();
        text.push_str(&line.join(","));
        text.push('\n');
    }
    write_atomically(path, text.as_bytes())
}
