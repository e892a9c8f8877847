//! The frame of an HPM analysis ([`crate::hpm::HpmSolver`]): `elements`
//! and `slip`.

use nalgebra::Point3;

use super::dem::regime_code;
use super::series::VtkFrame;
use super::xml::{cell_type, DataArray, Dataset, PolyData, UnstructuredGrid, Values};
use crate::error::{DismechError, Result};
use crate::hpm::{displacement_at, strain_tensor, ElementDofs, HpmModel, HpmResult, ELEMENT_DOF};

/// The displacements, strains and local factors of safety of `result`,
/// an analysis of `model`, as a frame of two pieces (see the [module
/// documentation](super) for every array):
///
/// * `elements` (`.vtu`): each element (a layer of a grid column) as a
///   hexahedron, cell `k` element `k`, with its own eight corners, so that
///   the displacement at each corner (point data) is the element's own
///   linear field (HPM's elements are independent fields tied by penalty
///   springs: their corners do not move together);
/// * `slip` (`.vtp`): each slip-surface spring (a Gauss point under a
///   bottom element) as a vertex, with its tractions.
///
/// # Errors
/// [`DismechError::VtkData`] ([`super::VtkProblem::NotThisHpmResult`])
/// when `result` is not an analysis of `model` (its displacements are not
/// 12 per element, or its tractions not one per slip spring).
pub fn hpm_frame(model: &HpmModel, result: &HpmResult) -> Result<VtkFrame> {
    let elements = &model.elements;
    if result.displacements.len() != ELEMENT_DOF * elements.len()
        || result.tractions.len() != model.slip.len()
    {
        return Err(DismechError::VtkData {
            reason: super::VtkProblem::NotThisHpmResult {
                displacements: result.displacements.len(),
                tractions: result.tractions.len(),
                elements: elements.len(),
                springs: model.slip.len(),
            },
        });
    }
    let dofs = |e: usize| {
        ElementDofs::from_column_slice(
            &result.displacements[ELEMENT_DOF * e..ELEMENT_DOF * (e + 1)],
        )
    };
    let local_fs = result.local_safety_factors(model);

    let mut grid = UnstructuredGrid::default();
    let mut corner_displacement = Vec::with_capacity(8 * elements.len());
    for (k, e) in elements.iter().enumerate() {
        let (x0, y0) = e.shape.origin();
        let s = e.shape.size();
        let plan = [(x0, y0), (x0 + s, y0), (x0 + s, y0 + s), (x0, y0 + s)];
        let first = grid.points.len();
        for heights in [e.shape.bottom(), e.shape.top()] {
            for (c, &(x, y)) in plan.iter().enumerate() {
                let corner = Point3::new(x, y, heights[c]);
                let u = displacement_at(&e.centre, &dofs(k), &corner);
                grid.points.push([corner.x, corner.y, corner.z]);
                corner_displacement.push([u.x, u.y, u.z]);
            }
        }
        grid.push_cell(cell_type::HEXAHEDRON, first..first + 8);
    }
    grid.point_data = vec![DataArray::vectors("displacement", &corner_displacement)];
    let column_of = |e: &crate::hpm::Element| &model.columns[e.column];
    grid.cell_data = vec![
        DataArray::integers("id", (0..elements.len() as i64).collect()),
        DataArray::integers("column", elements.iter().map(|e| e.column as i64).collect()),
        DataArray::integers("layer", elements.iter().map(|e| e.layer as i64).collect()),
        DataArray::new(
            "cell",
            2,
            Values::Int64(
                elements
                    .iter()
                    .flat_map(|e| {
                        let (row, col) = column_of(e).cell;
                        [row as i64, col as i64]
                    })
                    .collect(),
            ),
        )
        .with_component_names(&["row", "column"]),
        DataArray::vectors(
            "centre",
            &elements
                .iter()
                .map(|e| [e.centre.x, e.centre.y, e.centre.z])
                .collect::<Vec<_>>(),
        ),
        DataArray::scalars("volume", elements.iter().map(|e| e.volume).collect()),
        DataArray::scalars("weight", elements.iter().map(|e| e.weight).collect()),
        DataArray::vectors(
            "displacement",
            &(0..elements.len())
                .map(|k| {
                    let d = dofs(k);
                    [d[0], d[1], d[2]]
                })
                .collect::<Vec<_>>(),
        ),
        DataArray::vectors(
            "rotation",
            &(0..elements.len())
                .map(|k| {
                    let d = dofs(k);
                    [d[3], d[4], d[5]]
                })
                .collect::<Vec<_>>(),
        ),
        DataArray::tensors(
            "strain",
            &(0..elements.len())
                .map(|k| {
                    let t = strain_tensor(&dofs(k));
                    std::array::from_fn(|i| t[(i / 3, i % 3)])
                })
                .collect::<Vec<_>>(),
        ),
        DataArray::scalars(
            "local_safety_factor",
            elements.iter().map(|e| local_fs[e.column]).collect(),
        ),
    ];

    let mut slip = PolyData::default();
    for (k, spring) in model.slip.iter().enumerate() {
        let p = spring.point.point.position;
        slip.points.push([p.x, p.y, p.z]);
        slip.verts.push([k]);
    }
    let springs = &model.slip;
    let tractions = &result.tractions;
    slip.cell_data = vec![
        DataArray::integers(
            "element",
            springs.iter().map(|s| s.element as i64).collect(),
        ),
        DataArray::integers("column", springs.iter().map(|s| s.column as i64).collect()),
        DataArray::scalars("area", springs.iter().map(|s| s.point.point.area).collect()),
        DataArray::vectors(
            "normal",
            &springs
                .iter()
                .map(|s| {
                    let n = s.point.point.normal;
                    [n.x, n.y, n.z]
                })
                .collect::<Vec<_>>(),
        ),
        DataArray::scalars(
            "normal_traction",
            tractions.iter().map(|t| t.normal).collect(),
        ),
        DataArray::vectors(
            "shear_traction",
            &springs
                .iter()
                .zip(tractions)
                .map(|(s, t)| {
                    let v = s.point.s * t.shear[0] + s.point.t * t.shear[1];
                    [v.x, v.y, v.z]
                })
                .collect::<Vec<_>>(),
        ),
        DataArray::codes(
            "regime",
            tractions.iter().map(|t| regime_code(t.regime)).collect(),
        ),
        DataArray::vectors(
            "displacement",
            &springs
                .iter()
                .map(|s| {
                    let e = &elements[s.element];
                    let u = displacement_at(&e.centre, &dofs(s.element), &s.point.point.position);
                    [u.x, u.y, u.z]
                })
                .collect::<Vec<_>>(),
        ),
    ];

    let mut frame = VtkFrame::new();
    frame.push("elements", Dataset::UnstructuredGrid(grid))?;
    frame.push("slip", Dataset::PolyData(slip))?;
    Ok(frame)
}
