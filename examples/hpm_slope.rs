//! HPM slope stability on grid columns (paper 001) composed from library
//! pieces: ground and slip surface read from ESRI ASCII grids, columns cut
//! into layers, elastic and nonlinear analyses, static and seismic,
//! Hovland's method beside them; the static analyses' maps (local Fs,
//! displacement, strain per column) written for a GIS, as ESRI ASCII grids
//! and GeoTIFF on the input grid, into `target/hpm_slope_maps/`.
//!
//! `cargo run --release --example hpm_slope [ground.asc slip.asc [water.asc]]`
//! (default: the representative slope of the reproduction, shipped in
//! `examples/data/`).

use std::path::PathBuf;

use dismech::error::DismechError;
use dismech::grid::RasterFormat;
use dismech::hpm::{
    hovland, HpmMaterial, HpmModel, HpmSettings, HpmSolver, NonlinearSettings, Seismic, SlopeGrids,
};

fn main() -> Result<(), DismechError> {
    let data = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/data");
    let args: Vec<PathBuf> = std::env::args().skip(1).map(PathBuf::from).collect();
    let (ground, slip) = match args.as_slice() {
        [g, s, ..] => (g.clone(), s.clone()),
        _ => (data.join("hpm_ground.asc"), data.join("hpm_slip.asc")),
    };
    // 1. Grids: valid columns are the cells with the slip surface below the ground.
    let grids = SlopeGrids::read(&ground, &slip, args.get(2).map(PathBuf::as_path))?;
    // 2. Material of the paper's §5 and three layers per column.
    let model = HpmModel::new(&grids, &HpmMaterial::paper(), &HpmSettings::default())?;
    println!(
        "{} columns, {} elements, {} DOF",
        model.columns.len(),
        model.elements.len(),
        model.dof()
    );
    // 3. One factorisation of the elastic stiffness serves every analysis.
    let mut solver = HpmSolver::new(&model)?;
    for (case, load, maps_prefix) in [
        ("static", Seismic::none(), Some("static")),
        (
            "seismic k_h = 0.15 towards -y",
            Seismic {
                coefficient: 0.15,
                direction: (0.0, -1.0),
            },
            None,
        ),
    ] {
        let elastic = solver.elastic(&model, &load)?;
        let nonlinear = solver.nonlinear(&model, &load, 1.0, &NonlinearSettings::default())?;
        let hov = hovland(&model, &load, (0.0, -1.0))?;
        println!(
            "{case}: Fs elastic {:.4}, nonlinear {:.4} ({:?}), Hovland {:.4}",
            elastic.safety_factor(&model)?,
            nonlinear.safety_factor(&model)?,
            nonlinear.convergence,
            hov.safety_factor
        );
        if let Some(prefix) = maps_prefix {
            // 4. Maps on the input grid, for a GIS.
            let maps = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/hpm_slope_maps");
            let mut files = nonlinear.maps(&model, &grids)?.write(
                &maps,
                &format!("nonlinear_{prefix}"),
                &RasterFormat::ALL,
            )?;
            files.extend(hov.maps(&model, &grids)?.write(
                &maps,
                &format!("hovland_{prefix}"),
                &RasterFormat::ALL,
            )?);
            println!("{} maps written in {}", files.len(), maps.display());
        }
    }
    Ok(())
}
