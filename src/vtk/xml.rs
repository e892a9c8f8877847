//! The datasets of a VTK XML file and their writer: PolyData (`.vtp`) and
//! UnstructuredGrid (`.vtu`), every array inline in base64 binary.
//!
//! Binary, not ASCII: the values are the bits of the `f64`s (exact), an
//! infinite value (a prescribed particle's mass, a column's local factor of
//! safety where nothing shears it) reads back as infinite (VTK's ASCII
//! reader refuses `inf`), and the files are about half the size. Each
//! array is `base64(n ‖ bytes)`, `n` the byte count as a little-endian
//! `UInt64` (`header_type="UInt64"`), the bytes little-endian
//! (`byte_order="LittleEndian"`), uncompressed.

use super::{DataKind, VtkProblem};
use crate::error::{DismechError, Result};

/// VTK's cell types used here (`vtkCellType.h`).
pub mod cell_type {
    /// A point (`VTK_VERTEX`).
    pub const VERTEX: u8 = 1;
    /// A segment between two points (`VTK_LINE`).
    pub const LINE: u8 = 3;
    /// A chain of segments (`VTK_POLY_LINE`).
    pub const POLY_LINE: u8 = 4;
    /// A polygon, its points in order around it (`VTK_POLYGON`).
    pub const POLYGON: u8 = 7;
    /// A hexahedron: a bottom quadrilateral, counter-clockwise seen from
    /// the top, then the top one above it (`VTK_HEXAHEDRON`).
    pub const HEXAHEDRON: u8 = 12;
}

/// The values of a data array, by VTK type.
#[derive(Debug, Clone, PartialEq)]
pub enum Values {
    /// `Float64`.
    Float64(Vec<f64>),
    /// `Int64`.
    Int64(Vec<i64>),
    /// `UInt8` (flags and codes).
    UInt8(Vec<u8>),
}

impl Values {
    /// Number of values (components times tuples).
    pub fn len(&self) -> usize {
        match self {
            Values::Float64(v) => v.len(),
            Values::Int64(v) => v.len(),
            Values::UInt8(v) => v.len(),
        }
    }

    /// Whether there is no value.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn type_name(&self) -> &'static str {
        match self {
            Values::Float64(_) => "Float64",
            Values::Int64(_) => "Int64",
            Values::UInt8(_) => "UInt8",
        }
    }

    fn little_endian_bytes(&self) -> std::borrow::Cow<'_, [u8]> {
        match self {
            Values::Float64(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            Values::Int64(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            Values::UInt8(v) => std::borrow::Cow::Borrowed(v),
        }
    }
}

/// A named array of point or cell data: `components` values per point or
/// cell, tuple after tuple.
#[derive(Debug, Clone, PartialEq)]
pub struct DataArray {
    /// The name ParaView lists it by.
    pub name: String,
    /// Values per tuple (1 a scalar, 3 a vector, 9 a tensor row by row).
    pub components: usize,
    /// The values, tuple after tuple.
    pub values: Values,
    /// Names of the components (`ComponentName0`…), or none.
    pub component_names: Vec<String>,
}

impl DataArray {
    /// A scalar per tuple.
    pub fn scalars(name: &str, values: Vec<f64>) -> Self {
        Self::new(name, 1, Values::Float64(values))
    }

    /// A vector `(x, y, z)` per tuple.
    pub fn vectors(name: &str, values: &[[f64; 3]]) -> Self {
        Self::new(
            name,
            3,
            Values::Float64(values.iter().flatten().copied().collect()),
        )
    }

    /// A 3×3 tensor per tuple, row by row (`xx, xy, xz, yx, …, zz`).
    pub fn tensors(name: &str, values: &[[f64; 9]]) -> Self {
        Self::new(
            name,
            9,
            Values::Float64(values.iter().flatten().copied().collect()),
        )
    }

    /// An integer per tuple (indices).
    pub fn integers(name: &str, values: Vec<i64>) -> Self {
        Self::new(name, 1, Values::Int64(values))
    }

    /// A small code or flag per tuple.
    pub fn codes(name: &str, values: Vec<u8>) -> Self {
        Self::new(name, 1, Values::UInt8(values))
    }

    /// `components` values per tuple of any type.
    pub fn new(name: &str, components: usize, values: Values) -> Self {
        Self {
            name: name.to_string(),
            components,
            values,
            component_names: Vec::new(),
        }
    }

    /// The same array with its components named.
    pub fn with_component_names(mut self, names: &[&str]) -> Self {
        self.component_names = names.iter().map(|s| s.to_string()).collect();
        self
    }

    /// Number of tuples.
    pub fn tuples(&self) -> usize {
        self.values.len() / self.components.max(1)
    }
}

/// Cells as VTK's XML lists them: the points of every cell one after the
/// other (`connectivity`) and where each cell ends (`offsets`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Cells {
    connectivity: Vec<i64>,
    offsets: Vec<i64>,
}

impl Cells {
    /// No cell.
    pub fn new() -> Self {
        Self::default()
    }

    /// Add a cell through the points numbered `points`.
    pub fn push(&mut self, points: impl IntoIterator<Item = usize>) {
        self.connectivity
            .extend(points.into_iter().map(|p| p as i64));
        self.offsets.push(self.connectivity.len() as i64);
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.offsets.len()
    }

    /// Whether there is no cell.
    pub fn is_empty(&self) -> bool {
        self.offsets.is_empty()
    }

    /// The points of cell `k`.
    pub fn cell(&self, k: usize) -> &[i64] {
        let start = if k == 0 {
            0
        } else {
            self.offsets[k - 1] as usize
        };
        &self.connectivity[start..self.offsets[k] as usize]
    }
}

/// A VTK PolyData (`.vtp`): points, and vertices, lines (poly-lines) and
/// polygons through them. Its cell data run over the vertices, then the
/// lines, then the polygons.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PolyData {
    /// The points (m).
    pub points: Vec<[f64; 3]>,
    /// Vertex cells (one point each here).
    pub verts: Cells,
    /// Line cells: two points, or a chain of them.
    pub lines: Cells,
    /// Polygon cells.
    pub polys: Cells,
    /// One tuple per point.
    pub point_data: Vec<DataArray>,
    /// One tuple per cell: vertices, then lines, then polygons.
    pub cell_data: Vec<DataArray>,
}

/// A VTK UnstructuredGrid (`.vtu`): points and cells of any type, in any
/// order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct UnstructuredGrid {
    /// The points (m).
    pub points: Vec<[f64; 3]>,
    /// The cells.
    pub cells: Cells,
    /// The type of each cell ([`cell_type`]).
    pub types: Vec<u8>,
    /// One tuple per point.
    pub point_data: Vec<DataArray>,
    /// One tuple per cell.
    pub cell_data: Vec<DataArray>,
}

impl UnstructuredGrid {
    /// Add a cell of type `kind` through `points`.
    pub fn push_cell(&mut self, kind: u8, points: impl IntoIterator<Item = usize>) {
        self.cells.push(points);
        self.types.push(kind);
    }
}

/// One dataset: one file.
#[derive(Debug, Clone, PartialEq)]
pub enum Dataset {
    /// A `.vtp` file.
    PolyData(PolyData),
    /// A `.vtu` file.
    UnstructuredGrid(UnstructuredGrid),
}

impl Dataset {
    /// The file extension ParaView knows it by: `vtp` or `vtu`.
    pub fn extension(&self) -> &'static str {
        match self {
            Dataset::PolyData(_) => "vtp",
            Dataset::UnstructuredGrid(_) => "vtu",
        }
    }

    /// Number of points.
    pub fn point_count(&self) -> usize {
        match self {
            Dataset::PolyData(d) => d.points.len(),
            Dataset::UnstructuredGrid(d) => d.points.len(),
        }
    }

    /// Number of cells.
    pub fn cell_count(&self) -> usize {
        match self {
            Dataset::PolyData(d) => d.verts.len() + d.lines.len() + d.polys.len(),
            Dataset::UnstructuredGrid(d) => d.cells.len(),
        }
    }

    /// The cell data array named `name`.
    pub fn cell_array(&self, name: &str) -> Option<&DataArray> {
        let arrays = match self {
            Dataset::PolyData(d) => &d.cell_data,
            Dataset::UnstructuredGrid(d) => &d.cell_data,
        };
        arrays.iter().find(|a| a.name == name)
    }

    /// The point data array named `name`.
    pub fn point_array(&self, name: &str) -> Option<&DataArray> {
        let arrays = match self {
            Dataset::PolyData(d) => &d.point_data,
            Dataset::UnstructuredGrid(d) => &d.point_data,
        };
        arrays.iter().find(|a| a.name == name)
    }

    /// The file's text: a VTK XML file, every array inline in base64.
    ///
    /// # Errors
    /// [`DismechError::VtkData`] naming the array or the cell when an
    /// array has no component ([`VtkProblem::NoComponent`]), a number of
    /// values that is not its components times the points (point data) or
    /// cells (cell data) ([`VtkProblem::ValueCount`]), or a name used twice
    /// ([`VtkProblem::NamedTwice`]); when a cell names a point the dataset
    /// does not have ([`VtkProblem::NoSuchPoint`]); or when an unstructured
    /// grid has not one type per cell ([`VtkProblem::CellTypeCount`]).
    pub fn to_xml(&self) -> Result<String> {
        self.validate()?;
        let mut out = String::with_capacity(64 + 12 * self.point_count());
        out.push_str("<?xml version=\"1.0\"?>\n");
        match self {
            Dataset::PolyData(d) => {
                out.push_str(&file_open("PolyData"));
                out.push_str("  <PolyData>\n");
                out.push_str(&format!(
                    "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"{}\" NumberOfStrips=\"0\" NumberOfPolys=\"{}\">\n",
                    d.points.len(),
                    d.verts.len(),
                    d.lines.len(),
                    d.polys.len()
                ));
                write_attributes(&mut out, "PointData", &d.point_data);
                write_attributes(&mut out, "CellData", &d.cell_data);
                write_points(&mut out, &d.points);
                for (tag, cells) in [
                    ("Verts", &d.verts),
                    ("Lines", &d.lines),
                    ("Polys", &d.polys),
                ] {
                    write_cells(&mut out, tag, cells, None);
                }
                out.push_str("    </Piece>\n  </PolyData>\n</VTKFile>\n");
            }
            Dataset::UnstructuredGrid(d) => {
                out.push_str(&file_open("UnstructuredGrid"));
                out.push_str("  <UnstructuredGrid>\n");
                out.push_str(&format!(
                    "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
                    d.points.len(),
                    d.cells.len()
                ));
                write_attributes(&mut out, "PointData", &d.point_data);
                write_attributes(&mut out, "CellData", &d.cell_data);
                write_points(&mut out, &d.points);
                write_cells(&mut out, "Cells", &d.cells, Some(&d.types));
                out.push_str("    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
            }
        }
        Ok(out)
    }

    fn validate(&self) -> Result<()> {
        let (points, point_data, cell_data, cell_lists): (usize, _, _, Vec<&Cells>) = match self {
            Dataset::PolyData(d) => (
                d.points.len(),
                &d.point_data,
                &d.cell_data,
                vec![&d.verts, &d.lines, &d.polys],
            ),
            Dataset::UnstructuredGrid(d) => {
                if d.types.len() != d.cells.len() {
                    return Err(invalid(VtkProblem::CellTypeCount {
                        types: d.types.len(),
                        cells: d.cells.len(),
                    }));
                }
                (d.points.len(), &d.point_data, &d.cell_data, vec![&d.cells])
            }
        };
        for cells in cell_lists {
            if let Some(&p) = cells
                .connectivity
                .iter()
                .find(|&&p| p < 0 || p as usize >= points)
            {
                return Err(invalid(VtkProblem::NoSuchPoint { point: p, points }));
            }
        }
        check_arrays(DataKind::Point, point_data, points)?;
        check_arrays(DataKind::Cell, cell_data, self.cell_count())
    }
}

fn invalid(reason: VtkProblem) -> DismechError {
    DismechError::VtkData { reason }
}

fn check_arrays(kind: DataKind, arrays: &[DataArray], tuples: usize) -> Result<()> {
    for (k, a) in arrays.iter().enumerate() {
        if a.components == 0 {
            return Err(invalid(VtkProblem::NoComponent {
                kind,
                name: a.name.clone(),
            }));
        }
        if a.values.len() != a.components * tuples {
            return Err(invalid(VtkProblem::ValueCount {
                kind,
                name: a.name.clone(),
                values: a.values.len(),
                components: a.components,
                tuples,
            }));
        }
        if arrays[..k].iter().any(|b| b.name == a.name) {
            return Err(invalid(VtkProblem::NamedTwice {
                kind,
                name: a.name.clone(),
            }));
        }
    }
    Ok(())
}

fn file_open(kind: &str) -> String {
    format!(
        "<VTKFile type=\"{kind}\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
    )
}

/// `<PointData>` or `<CellData>` with its arrays.
fn write_attributes(out: &mut String, tag: &str, arrays: &[DataArray]) {
    out.push_str(&format!("      <{tag}>\n"));
    for a in arrays {
        write_array(out, &a.name, a.components, &a.values, &a.component_names);
    }
    out.push_str(&format!("      </{tag}>\n"));
}

fn write_points(out: &mut String, points: &[[f64; 3]]) {
    out.push_str("      <Points>\n");
    let bytes: Vec<u8> = points
        .iter()
        .flatten()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    write_bytes(out, "Points", "Float64", 3, &bytes, &[]);
    out.push_str("      </Points>\n");
}

fn write_cells(out: &mut String, tag: &str, cells: &Cells, types: Option<&[u8]>) {
    out.push_str(&format!("      <{tag}>\n"));
    write_i64s(out, "connectivity", &cells.connectivity);
    write_i64s(out, "offsets", &cells.offsets);
    if let Some(types) = types {
        write_bytes(out, "types", "UInt8", 1, types, &[]);
    }
    out.push_str(&format!("      </{tag}>\n"));
}

fn write_array(
    out: &mut String,
    name: &str,
    components: usize,
    values: &Values,
    component_names: &[String],
) {
    let bytes = values.little_endian_bytes();
    write_bytes(
        out,
        name,
        values.type_name(),
        components,
        &bytes,
        component_names,
    );
}

fn write_i64s(out: &mut String, name: &str, values: &[i64]) {
    let bytes: Vec<u8> = values.iter().flat_map(|x| x.to_le_bytes()).collect();
    write_bytes(out, name, "Int64", 1, &bytes, &[]);
}

/// A `DataArray` element of `bytes`, little-endian values of type
/// `type_name`, inline as `base64(byte count ‖ bytes)`.
fn write_bytes(
    out: &mut String,
    name: &str,
    type_name: &str,
    components: usize,
    bytes: &[u8],
    component_names: &[String],
) {
    out.push_str(&format!(
        "        <DataArray type=\"{type_name}\" Name=\"{}\" NumberOfComponents=\"{components}\"",
        escape(name)
    ));
    for (k, c) in component_names.iter().enumerate() {
        out.push_str(&format!(" ComponentName{k}=\"{}\"", escape(c)));
    }
    out.push_str(" format=\"binary\">\n          ");
    let mut block = Vec::with_capacity(8 + bytes.len());
    block.extend_from_slice(&(bytes.len() as u64).to_le_bytes());
    block.extend_from_slice(bytes);
    base64_into(out, &block);
    out.push_str("\n        </DataArray>\n");
}

/// `text` with the characters XML gives a meaning to escaped.
fn escape(text: &str) -> String {
    let mut s = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => s.push_str("&amp;"),
            '<' => s.push_str("&lt;"),
            '>' => s.push_str("&gt;"),
            '"' => s.push_str("&quot;"),
            '\'' => s.push_str("&apos;"),
            _ => s.push(c),
        }
    }
    s
}

const BASE64: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/// Append the standard base64 of `bytes` (RFC 4648, padded) to `out`.
fn base64_into(out: &mut String, bytes: &[u8]) {
    out.reserve(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        let sextet = |k: u32| BASE64[((n >> (18 - 6 * k)) & 63) as usize] as char;
        out.push(sextet(0));
        out.push(sextet(1));
        out.push(if chunk.len() > 1 { sextet(2) } else { '=' });
        out.push(if chunk.len() > 2 { sextet(3) } else { '=' });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn base64(bytes: &[u8]) -> String {
        let mut s = String::new();
        base64_into(&mut s, bytes);
        s
    }

    #[test]
    fn base64_matches_rfc_4648() {
        // The test vectors of RFC 4648, §10.
        for (plain, coded) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(plain.as_bytes()), coded);
        }
    }

    #[test]
    fn cells_list_their_points_and_ends() {
        let mut cells = Cells::new();
        cells.push([0, 1, 2]);
        cells.push([2, 3]);
        assert_eq!(cells.len(), 2);
        assert_eq!(cells.cell(0), &[0, 1, 2]);
        assert_eq!(cells.cell(1), &[2, 3]);
        assert_eq!(cells.offsets, vec![3, 5]);
    }

    #[test]
    fn an_array_of_the_wrong_length_or_a_missing_point_is_refused() {
        let mut d = PolyData {
            points: vec![[0.0; 3], [1.0, 0.0, 0.0]],
            ..PolyData::default()
        };
        d.lines.push([0, 1]);
        d.cell_data.push(DataArray::scalars("f", vec![1.0, 2.0]));
        let e = Dataset::PolyData(d.clone()).to_xml().unwrap_err();
        assert!(e.to_string().contains("`f` has 2 values"), "{e}");
        d.cell_data[0] = DataArray::scalars("f", vec![1.0]);
        d.lines.push([1, 2]);
        d.cell_data[0] = DataArray::scalars("f", vec![1.0, 2.0]);
        let e = Dataset::PolyData(d).to_xml().unwrap_err();
        assert!(e.to_string().contains("point 2, of 2 points"), "{e}");
    }

    #[test]
    fn names_are_escaped() {
        assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
    }
}
