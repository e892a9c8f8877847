//! The frame of an implicit run ([`ImplicitDynamics`], DDA's
//! [`crate::dda::DdaModel`] among them): `bodies` and `contacts`.

use std::f64::consts::TAU;

use nalgebra::SVector;

use super::outline::{contact_lines, kind, push_outline, xyz, ContactLine};
use super::series::VtkFrame;
use super::xml::{DataArray, Dataset, UnstructuredGrid, Values};
use crate::error::Result;
use crate::implicit::{Body, BodyGeometry, ContactReport, ImplicitDynamics, PlaneState};
use crate::integrate::ImplicitIntegrator;
use crate::kinematics::{Advance, Kinematics, PlacedEllipse, PlacedPolygon};
use crate::law::TangentLaw;
use crate::linsolve::{LinearSolver, SparseMatrix};
use crate::math::{Point, Vec2};

/// The state of `model` after its last accepted step as a frame of two
/// pieces ([`bodies_frame`] on its bodies, kinematics and contacts; see
/// the [module documentation](super) for every array).
///
/// # Errors
/// [`crate::error::DismechError::InvalidParameter`] naming `outline
/// segments` for fewer than 3 segments.
pub fn implicit_frame<const N: usize, K, L, I, S>(
    model: &ImplicitDynamics<N, K, L, I, S>,
    segments: usize,
) -> Result<VtkFrame>
where
    K: Kinematics<N> + Advance<PlacedPolygon, N> + Advance<PlacedEllipse, N>,
    L: TangentLaw<2>,
    I: ImplicitIntegrator,
    S: LinearSolver<SparseMatrix>,
{
    bodies_frame(
        model.bodies(),
        model.kinematics(),
        model.contacts(),
        segments,
    )
}

/// Bodies of `N` unknowns moved by `kinematics`, and their contacts, as a
/// frame of two pieces:
///
/// * `bodies` (`.vtu`): each body's current outline as one cell, cell `k`
///   body `k` (a polygon's vertices; an ellipse or a circle as a polygon
///   of `segments` sides; a wall as a line), with the velocity of every
///   outline point (point data) and the body's motion and stress (cell
///   data);
/// * `contacts` (`.vtp`): each contact as a poly-line from A's centroid
///   through A's contact point to B's centroid (to the point where B is a
///   wall).
///
/// # Errors
/// [`crate::error::DismechError::InvalidParameter`] naming `outline
/// segments` for fewer than 3 segments.
pub fn bodies_frame<const N: usize, K: Kinematics<N>, St>(
    bodies: &[Body<N>],
    kinematics: &K,
    contacts: &[ContactReport<St>],
    segments: usize,
) -> Result<VtkFrame> {
    super::outline::check_segments(segments)?;
    let zero = SVector::<f64, N>::zeros();
    let jacobian = kinematics.map_jacobian(&zero);
    let mut grid = UnstructuredGrid::default();
    let mut point_velocity = Vec::new();
    let mut rates = Vec::with_capacity(bodies.len());
    for body in bodies {
        let outline = outline(body.geometry(), segments);
        let c = body.centroid();
        for p in &outline {
            let v = kinematics.point_jacobian(&zero, &(p - c)) * body.velocity;
            point_velocity.push([v[0], v[1], 0.0]);
        }
        push_outline(&mut grid, &outline);
        // The rates of the map parameters (t_x, t_y, F₁₁−1, F₁₂, F₂₁, F₂₂−1).
        rates.push(jacobian * body.velocity);
    }
    grid.point_data = vec![DataArray::vectors("velocity", &point_velocity)];
    let translation = |b: &Body<N>| -> [f64; 3] {
        if N >= 2 {
            [b.displacement[0], b.displacement[1], 0.0]
        } else {
            [0.0; 3]
        }
    };
    grid.cell_data = vec![
        DataArray::integers("id", (0..bodies.len() as i64).collect()),
        DataArray::codes(
            "kind",
            bodies.iter().map(|b| body_kind(b.geometry())).collect(),
        ),
        DataArray::integers("group", bodies.iter().map(|b| b.group as i64).collect()),
        DataArray::codes(
            "fixed",
            bodies.iter().map(|b| u8::from(b.is_fixed())).collect(),
        ),
        DataArray::scalars("area", bodies.iter().map(Body::area).collect()),
        DataArray::vectors(
            "centroid",
            &bodies
                .iter()
                .map(|b| xyz(&b.centroid()))
                .collect::<Vec<_>>(),
        ),
        DataArray::vectors(
            "velocity",
            &rates.iter().map(|r| [r[0], r[1], 0.0]).collect::<Vec<_>>(),
        ),
        DataArray::scalars(
            "angular_velocity",
            rates.iter().map(|r| 0.5 * (r[4] - r[3])).collect(),
        ),
        DataArray::vectors(
            "displacement",
            &bodies.iter().map(translation).collect::<Vec<_>>(),
        ),
        DataArray::tensors(
            "stress",
            &bodies.iter().map(stress_tensor).collect::<Vec<_>>(),
        ),
    ];
    if N > 0 {
        for (name, of) in [
            (
                "dof_velocity",
                (|b: &Body<N>| b.velocity) as fn(&Body<N>) -> SVector<f64, N>,
            ),
            ("dof_displacement", |b: &Body<N>| b.displacement),
        ] {
            grid.cell_data.push(DataArray::new(
                name,
                N,
                Values::Float64(
                    bodies
                        .iter()
                        .flat_map(|b| of(b).iter().copied().collect::<Vec<_>>())
                        .collect(),
                ),
            ));
        }
    }

    let centre_of = |k: usize| match bodies[k].geometry() {
        BodyGeometry::Wall(_) => None,
        _ => Some(bodies[k].centroid()),
    };
    let lines: Vec<ContactLine> = contacts
        .iter()
        .map(|c| ContactLine {
            a_centre: centre_of(c.bodies.0).unwrap_or(c.point),
            b_centre: centre_of(c.bodies.1),
            point: c.point,
            // The report's normal runs from B into A and its force acts on
            // A: the file's convention is A to B and the force on B.
            normal: -c.normal,
            force: -c.force_on_a,
        })
        .collect();
    let mut contact_data = contact_lines(&lines);
    contact_data.cell_data.extend([
        DataArray::integers(
            "body_a",
            contacts.iter().map(|c| c.bodies.0 as i64).collect(),
        ),
        DataArray::integers(
            "body_b",
            contacts.iter().map(|c| c.bodies.1 as i64).collect(),
        ),
        DataArray::scalars("gap", contacts.iter().map(|c| c.gap).collect()),
        DataArray::scalars("shear", contacts.iter().map(|c| c.shear).collect()),
        DataArray::new(
            "law_force",
            2,
            Values::Float64(
                contacts
                    .iter()
                    .flat_map(|c| [c.force.0, c.force.1])
                    .collect(),
            ),
        )
        .with_component_names(&["normal", "shear"]),
    ]);

    let mut frame = VtkFrame::new();
    frame.push("bodies", Dataset::UnstructuredGrid(grid))?;
    frame.push("contacts", Dataset::PolyData(contact_data))?;
    Ok(frame)
}

/// The current outline of a body.
fn outline(geometry: &BodyGeometry, segments: usize) -> Vec<Point> {
    match geometry {
        BodyGeometry::Polygon(p) => (0..p.vertex_count()).map(|k| p.vertex(k)).collect(),
        BodyGeometry::Ellipse(e) => {
            let (c, a) = (e.centre(), e.axes());
            (0..segments)
                .map(|k| {
                    let t = TAU * k as f64 / segments as f64;
                    c + a * Vec2::new(t.cos(), t.sin())
                })
                .collect()
        }
        BodyGeometry::Wall(s) => vec![s.start, s.end],
    }
}

/// The `kind` code of a body: an ellipse whose semi-axes are equal is a
/// circle.
fn body_kind(geometry: &BodyGeometry) -> u8 {
    match geometry {
        BodyGeometry::Polygon(_) => kind::POLYGON,
        BodyGeometry::Wall(_) => kind::SEGMENT,
        BodyGeometry::Ellipse(e) => {
            let m = e.matrix();
            let (p, q, r) = (m[(0, 0)], m[(0, 1)], m[(1, 1)]);
            let spread = (0.25 * (p - r) * (p - r) + q * q).sqrt();
            if spread <= 1e-12 * 0.5 * (p + r) {
                kind::CIRCLE
            } else {
                kind::ELLIPSE
            }
        }
    }
}

/// The body's uniform stress as a 3×3 tensor, row by row: σz is zero in
/// plane stress and `ν (σx + σy)` in plane strain.
fn stress_tensor<const N: usize>(body: &Body<N>) -> [f64; 9] {
    let (sx, sy, txy) = (body.stress[0], body.stress[1], body.stress[2]);
    let material = body.material();
    let sz = match material.plane {
        PlaneState::Stress => 0.0,
        PlaneState::Strain => material.poisson_ratio * (sx + sy),
    };
    [sx, txy, 0.0, txy, sy, 0.0, 0.0, 0.0, sz]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_strain_stress_has_its_out_of_plane_component() {
        use crate::implicit::BodyMaterial;
        let material = BodyMaterial {
            density: 1.0,
            youngs_modulus: 1.0,
            poisson_ratio: 0.25,
            plane: PlaneState::Strain,
        };
        let mut body = Body::<6>::circle(Point::origin(), 1.0, material, 0).unwrap();
        body.stress = nalgebra::Vector3::new(-2.0, -6.0, 1.0);
        assert_eq!(
            stress_tensor(&body),
            [-2.0, 1.0, 0.0, 1.0, -6.0, 0.0, 0.0, 0.0, -2.0]
        );
        assert_eq!(body_kind(body.geometry()), kind::CIRCLE);
    }
}
