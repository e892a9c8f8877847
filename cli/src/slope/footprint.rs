//! Where a trial surface lies on the map: its columns' cells, the outline
//! around them and their centroid.

use dismech::grid::Raster;
use dismech::slope::SlipColumn;

use super::map::Segment;

/// The cell edges between a column of the surface and a cell that is not
/// one (the footprint's outline, holes included), in map units.
pub fn outline(dem: &Raster, columns: &[SlipColumn]) -> Vec<Segment> {
    let (rows, cols) = (dem.rows(), dem.columns());
    let mut inside = vec![false; rows * cols];
    for k in columns {
        inside[k.row * cols + k.column] = true;
    }
    let is_in = |r: isize, c: isize| {
        r >= 0
            && c >= 0
            && (r as usize) < rows
            && (c as usize) < cols
            && inside[r as usize * cols + c as usize]
    };
    let (x0, y0) = dem.lower_left();
    let d = dem.cell_size();
    let mut segments = Vec::new();
    for k in columns {
        let (r, c) = (k.row as isize, k.column as isize);
        let west = x0 + k.column as f64 * d;
        let south = y0 + (rows - 1 - k.row) as f64 * d;
        let (east, north) = (west + d, south + d);
        if !is_in(r - 1, c) {
            segments.push(((west, north), (east, north)));
        }
        if !is_in(r + 1, c) {
            segments.push(((west, south), (east, south)));
        }
        if !is_in(r, c - 1) {
            segments.push(((west, south), (west, north)));
        }
        if !is_in(r, c + 1) {
            segments.push(((east, south), (east, north)));
        }
    }
    segments
}

/// The mean of the columns' cell centres (m), `None` without a column.
pub fn centroid(dem: &Raster, columns: &[SlipColumn]) -> Option<(f64, f64)> {
    if columns.is_empty() {
        return None;
    }
    let (sx, sy) = columns.iter().fold((0.0, 0.0), |(sx, sy), k| {
        let (x, y) = dem.cell_centre(k.row, k.column);
        (sx + x, sy + y)
    });
    let n = columns.len() as f64;
    Some((sx / n, sy / n))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn column(row: usize, column: usize) -> SlipColumn {
        SlipColumn {
            row,
            column,
            ground: 1.0,
            base: 0.0,
            gradient: (0.0, 0.0),
            pressure_head: 0.0,
        }
    }

    #[test]
    fn an_l_shaped_footprint_has_eight_edges_around_its_three_cells() {
        let dem = Raster::from_fn(4, 3, 10.0, 20.0, 2.0, |_, _| Some(0.0)).unwrap();
        // Cells (1,1), (1,2), (2,1): an L of three cells.
        let cols = [column(1, 1), column(1, 2), column(2, 1)];
        let edges = outline(&dem, &cols);
        assert_eq!(edges.len(), 8);
        // The perimeter of three cells in an L: 8 edges of 2 m.
        let length: f64 = edges
            .iter()
            .map(|((ax, ay), (bx, by))| (bx - ax).hypot(by - ay))
            .sum();
        assert_eq!(length, 16.0);
        // Cell (1,1) spans x 12..14, y 22..24 (row 1 of 3 from the top).
        assert!(edges.contains(&((12.0, 24.0), (14.0, 24.0))));
        assert!(edges.contains(&((12.0, 22.0), (12.0, 24.0))));
        assert!(!edges.contains(&((14.0, 22.0), (14.0, 24.0))));
        assert_eq!(centroid(&dem, &cols), Some((41.0 / 3.0, 67.0 / 3.0)));
        assert_eq!(centroid(&dem, &[]), None);
    }
}
