//! The frame of a limit analysis ([`crate::limit::analyse`],
//! [`crate::limit::analyse_static`]): `bodies`, `contacts` and `supports`.

use super::outline::{
    contact_lines, push_outline, shape_kind, shape_outline, vec3, xyz, ContactLine,
};
use super::series::VtkFrame;
use super::xml::{DataArray, Dataset, PolyData, UnstructuredGrid};
use crate::error::{DismechError, Result};
use crate::limit::{LimitModel, LimitResult, Partner};
use crate::math::{perp, Point, Vec2};

/// The collapse mechanism and the dual contact forces of `result`, a
/// limit analysis of `model`, as a frame of three pieces (see the [module
/// documentation](super) for every array):
///
/// * `bodies` (`.vtu`): each body's outline as one cell, cell `k` body
///   `k`, with the mechanism's velocity at every outline point (point
///   data: ParaView's *Warp By Vector* on it draws the mechanism);
/// * `contacts` (`.vtp`): each contact as a poly-line from A's centre
///   through the contact point to B's centre (to the point for a
///   support), with its dual forces, slip and opening rates;
/// * `supports` (`.vtp`): each support as a line across the bodies'
///   extent.
///
/// # Errors
/// [`DismechError::InvalidParameter`] naming `outline segments` for fewer
/// than 3 segments; [`DismechError::VtkData`] when `result` has no
/// mechanism ([`super::VtkProblem::NoMechanism`]: its status is neither
/// `Collapse` nor `ZeroLoad`, a locked or unbounded model, a solver in
/// trouble) or is not a result of `model` (another number of bodies, or of
/// contacts: [`super::VtkProblem::NotThisLimitResult`]).
pub fn limit_frame(model: &LimitModel, result: &LimitResult, segments: usize) -> Result<VtkFrame> {
    super::outline::check_segments(segments)?;
    let (bodies, contacts, supports) = (model.bodies(), model.contacts(), model.supports());
    if result.velocities.len() != bodies.len() {
        return Err(DismechError::VtkData {
            reason: super::VtkProblem::NoMechanism {
                status: result.status,
                velocities: result.velocities.len(),
                bodies: bodies.len(),
            },
        });
    }
    let per_contact = [
        &result.normal_force,
        &result.shear_force,
        &result.slip,
        &result.opening,
    ];
    if per_contact.iter().any(|v| v.len() != contacts.len()) {
        return Err(DismechError::VtkData {
            reason: super::VtkProblem::NotThisLimitResult {
                forces: result.normal_force.len(),
                contacts: contacts.len(),
            },
        });
    }

    let mut grid = UnstructuredGrid::default();
    let mut point_velocity = Vec::new();
    let mut lo = Point::new(f64::INFINITY, f64::INFINITY);
    let mut hi = Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY);
    for (b, &(v, omega)) in bodies.iter().zip(&result.velocities) {
        let outline = shape_outline(&b.shape, &b.pose(), segments);
        for p in &outline {
            let w = v + omega * perp(&(p - b.centre));
            point_velocity.push(vec3(&w));
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        push_outline(&mut grid, &outline);
    }
    grid.point_data = vec![DataArray::vectors("velocity", &point_velocity)];
    grid.cell_data = vec![
        DataArray::integers("id", (0..bodies.len() as i64).collect()),
        DataArray::codes(
            "kind",
            bodies.iter().map(|b| shape_kind(&b.shape)).collect(),
        ),
        DataArray::codes(
            "rotates",
            bodies.iter().map(|b| u8::from(b.rotates)).collect(),
        ),
        DataArray::vectors(
            "centre",
            &bodies.iter().map(|b| xyz(&b.centre)).collect::<Vec<_>>(),
        ),
        DataArray::vectors(
            "load",
            &bodies.iter().map(|b| vec3(&b.load)).collect::<Vec<_>>(),
        ),
        DataArray::vectors(
            "velocity",
            &result
                .velocities
                .iter()
                .map(|(v, _)| vec3(v))
                .collect::<Vec<_>>(),
        ),
        DataArray::scalars(
            "angular_velocity",
            result.velocities.iter().map(|(_, w)| *w).collect(),
        ),
    ];

    let lines: Vec<ContactLine> = contacts
        .iter()
        .enumerate()
        .map(|(k, c)| ContactLine {
            a_centre: bodies[c.body].centre,
            b_centre: match c.partner {
                Partner::Body(j) => Some(bodies[j].centre),
                Partner::Support(_) => None,
            },
            point: c.point,
            normal: c.normal,
            // The LP's shear force T resists the slip of B along the
            // tangent: on B it acts along −tangent.
            force: c.normal * result.normal_force[k] - c.tangent() * result.shear_force[k],
        })
        .collect();
    let mut contact_data = contact_lines(&lines);
    contact_data.cell_data.extend([
        DataArray::integers("body", contacts.iter().map(|c| c.body as i64).collect()),
        DataArray::integers(
            "partner",
            contacts
                .iter()
                .map(|c| match c.partner {
                    Partner::Body(j) | Partner::Support(j) => j as i64,
                })
                .collect(),
        ),
        DataArray::codes(
            "partner_is_support",
            contacts
                .iter()
                .map(|c| u8::from(matches!(c.partner, Partner::Support(_))))
                .collect(),
        ),
        DataArray::scalars("slip", result.slip.clone()),
        DataArray::scalars("opening", result.opening.clone()),
        DataArray::scalars(
            "cohesion",
            contacts.iter().map(|c| c.law.cohesion()).collect(),
        ),
        DataArray::scalars(
            "friction",
            contacts.iter().map(|c| c.law.friction()).collect(),
        ),
    ]);

    // Each support across the bodies' extent: centred where the line
    // passes nearest the middle of their box, as long as its diagonal.
    let (middle, half) = if bodies.is_empty() {
        (Point::origin(), 1.0)
    } else {
        (
            Point::from((lo.coords + hi.coords) * 0.5),
            0.5 * (hi - lo).norm(),
        )
    };
    let mut support_lines = PolyData::default();
    for s in supports {
        let d: Vec2 = perp(&s.normal);
        let foot = s.point + d * d.dot(&(middle - s.point));
        let first = support_lines.points.len();
        support_lines
            .points
            .extend([xyz(&(foot - d * half)), xyz(&(foot + d * half))]);
        support_lines.lines.push([first, first + 1]);
    }
    support_lines.cell_data = vec![
        DataArray::integers("id", (0..supports.len() as i64).collect()),
        DataArray::vectors(
            "normal",
            &supports.iter().map(|s| vec3(&s.normal)).collect::<Vec<_>>(),
        ),
        DataArray::vectors(
            "velocity",
            &supports
                .iter()
                .map(|s| vec3(&s.velocity))
                .collect::<Vec<_>>(),
        ),
    ];

    let mut frame = VtkFrame::new();
    frame.push("bodies", Dataset::UnstructuredGrid(grid))?;
    frame.push("contacts", Dataset::PolyData(contact_data))?;
    frame.push("supports", Dataset::PolyData(support_lines))?;
    Ok(frame)
}
