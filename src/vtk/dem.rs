//! The frame of an explicit DEM run ([`ExplicitDynamics`]): `particles`,
//! `contacts` and `walls`.

use super::outline::{
    contact_lines, push_outline, shape_kind, shape_outline, vec3, xyz, ContactLine,
};
use super::series::VtkFrame;
use super::xml::{DataArray, Dataset, PolyData, UnstructuredGrid};
use crate::error::Result;
use crate::explicit::{ContactTarget, ExplicitDynamics};
use crate::integrate::ExplicitIntegrator;
use crate::law::{ContactLaw, Regime};

/// The code of a contact's regime in the `regime` arrays: 0 open, 1
/// stick, 2 slip.
pub(super) fn regime_code(regime: Regime) -> u8 {
    match regime {
        Regime::Open => 0,
        Regime::Stick => 1,
        Regime::Slip => 2,
    }
}

/// The state of `dem` after its last step as a frame of three pieces (see
/// the [module documentation](super) for every array):
///
/// * `particles` (`.vtu`): each particle's outline as one cell, cell `k`
///   particle `k` (circles and ellipses as polygons of `segments` sides,
///   polygons as they are);
/// * `contacts` (`.vtp`): each contact point of [`ExplicitDynamics::contacts`]
///   as a poly-line from A's centre through the contact point to B's
///   centre (to the point for a wall);
/// * `walls` (`.vtp`): the frame's walls as lines, with the load the
///   particles put on each.
///
/// # Errors
/// [`crate::error::DismechError::InvalidParameter`] naming `outline segments`
/// for fewer than 3 segments.
pub fn dem_frame<L: ContactLaw<2>, I: ExplicitIntegrator>(
    dem: &ExplicitDynamics<L, I>,
    segments: usize,
) -> Result<VtkFrame> {
    super::outline::check_segments(segments)?;
    let scene = dem.scene();
    let particles = &scene.particles;
    let mut grid = UnstructuredGrid::default();
    let mut forces = Vec::with_capacity(particles.len());
    for (k, p) in particles.iter().enumerate() {
        push_outline(&mut grid, &shape_outline(&p.shape, &p.pose, segments));
        forces.push(dem.force_on(k)?);
    }
    grid.cell_data = vec![
        DataArray::integers("id", (0..particles.len() as i64).collect()),
        DataArray::codes(
            "kind",
            particles.iter().map(|p| shape_kind(&p.shape)).collect(),
        ),
        DataArray::codes(
            "prescribed",
            particles
                .iter()
                .map(|p| u8::from(p.is_prescribed()))
                .collect(),
        ),
        DataArray::scalars(
            "radius",
            particles
                .iter()
                .map(|p| p.shape.as_shape().bounding_radius())
                .collect(),
        ),
        DataArray::vectors(
            "centre",
            &particles
                .iter()
                .map(|p| xyz(&p.pose.position))
                .collect::<Vec<_>>(),
        ),
        DataArray::scalars("rotation", particles.iter().map(|p| p.pose.angle).collect()),
        DataArray::vectors(
            "velocity",
            &particles
                .iter()
                .map(|p| vec3(&p.velocity))
                .collect::<Vec<_>>(),
        ),
        DataArray::scalars(
            "angular_velocity",
            particles.iter().map(|p| p.angular_velocity).collect(),
        ),
        DataArray::scalars("mass", particles.iter().map(|p| p.mass).collect()),
        DataArray::vectors(
            "force",
            &forces.iter().map(|(f, _)| vec3(f)).collect::<Vec<_>>(),
        ),
        DataArray::scalars("moment", forces.iter().map(|(_, m)| *m).collect()),
    ];

    let records = dem.contacts();
    let walls = scene.frame.walls();
    let lines: Vec<ContactLine> = records
        .iter()
        .map(|c| ContactLine {
            a_centre: particles[c.particle].pose.position,
            b_centre: match c.target {
                ContactTarget::Particle(b) => Some(particles[b].pose.position),
                ContactTarget::Wall(_) => None,
            },
            point: c.point,
            normal: c.normal,
            force: c.force_on_target,
        })
        .collect();
    let mut contacts = contact_lines(&lines);
    contacts.cell_data.extend([
        DataArray::integers(
            "particle",
            records.iter().map(|c| c.particle as i64).collect(),
        ),
        DataArray::integers(
            "target",
            records
                .iter()
                .map(|c| match c.target {
                    ContactTarget::Particle(b) | ContactTarget::Wall(b) => b as i64,
                })
                .collect(),
        ),
        DataArray::codes(
            "target_is_wall",
            records
                .iter()
                .map(|c| u8::from(matches!(c.target, ContactTarget::Wall(_))))
                .collect(),
        ),
        DataArray::codes(
            "regime",
            records.iter().map(|c| regime_code(c.regime)).collect(),
        ),
        DataArray::scalars("overlap", records.iter().map(|c| c.overlap).collect()),
    ]);

    let mut wall_lines = PolyData::default();
    for w in walls {
        let first = wall_lines.points.len();
        wall_lines.points.extend([xyz(&w.start), xyz(&w.end)]);
        wall_lines.lines.push([first, first + 1]);
    }
    wall_lines.cell_data = vec![
        DataArray::integers("id", (0..walls.len() as i64).collect()),
        DataArray::vectors(
            "load",
            &(0..walls.len())
                .map(|w| vec3(&dem.wall_load(w)))
                .collect::<Vec<_>>(),
        ),
    ];

    let mut frame = VtkFrame::new();
    frame.push("particles", Dataset::UnstructuredGrid(grid))?;
    frame.push("contacts", Dataset::PolyData(contacts))?;
    frame.push("walls", Dataset::PolyData(wall_lines))?;
    Ok(frame)
}
