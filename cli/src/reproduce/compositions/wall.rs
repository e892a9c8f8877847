//! One running-bond wall by the polygon DEM and the DDA
//! ([`dismech_cli::compositions::block_wall`]): global equilibrium in both, and
//! what separates their bottom courses, shown by stiffness variants.

use std::fmt::Write as _;

use super::{pictures, Collector, Item, Rule};
use dismech::error::Result;
use dismech_cli::compositions::block_wall::{dem_vs_dda_variants, RunningBondWall, WallComparison};
use dismech_cli::output::plot::{line_chart, Series};
use dismech_cli::output::write_csv;

/// The wall as specified (first) and its variants: the wall, the suffix of
/// its value's id, what it shows.
fn wall_variants() -> [(RunningBondWall, &'static str, &'static str); 6] {
    let wall = RunningBondWall::default();
    [
        (wall, "", "the wall as specified"),
        (
            wall.scaled(1.0, 100.0),
            ".blocks_x100",
            "DDA blocks 100 times stiffer: the difference falls about 100 times",
        ),
        (
            wall.scaled(1.0, 1e4),
            ".blocks_x10000",
            "nearly rigid DDA blocks: the difference keeps falling in proportion to k/E, so nothing else (contact points, loading path, rest precision) separates the methods at this level",
        ),
        (
            wall.scaled(10.0, 1.0),
            ".contacts_x10",
            "contacts 10 times stiffer in both methods: the blocks' share of the compliance, and the difference, grow (about 5 times: at k/E = 0.67 the blocks are no longer a small part of it)",
        ),
        (
            wall.scaled(10.0, 10.0),
            ".both_x10",
            "contacts and blocks 10 times stiffer: k/E unchanged, the same difference",
        ),
        (
            RunningBondWall {
                dem_stiffness_ratio: 0.25,
                ..wall.scaled(1.0, 1e4)
            },
            ".dem_shear_quarter",
            "nearly rigid DDA blocks, but DEM shear springs of k_s/k_n = 0.25 (paper 000's ratio) against the DDA's one penalty: the shear springs take part in sharing the weight, hence k_s = k_n in the DEM",
        ),
    ]
}

/// The running-bond wall by the polygon DEM and the DDA.
pub(super) fn polygon_dem_vs_dda(c: &mut Collector) -> Result<()> {
    let variants = wall_variants();
    let walls: Vec<RunningBondWall> = variants.iter().map(|v| v.0).collect();
    let runs = dem_vs_dda_variants(&walls)?;
    let base = &runs[0];
    c.section(
        "Polygon DEM vs DDA: a running-bond wall at rest (`compositions::block_wall`)",
        &wall_text(base),
    );
    for (id, name, solution) in [
        (
            "polygon_dem_vs_dda.base_reaction_ratio.dem",
            "polygon DEM",
            &base.dem,
        ),
        (
            "polygon_dem_vs_dda.base_reaction_ratio.dda",
            "DDA",
            &base.dda,
        ),
    ] {
        c.check(
            Item {
                id,
                what: &format!("vertical force of the base on the wall at rest by the {name}, over the total weight of the blocks"),
                reference: "global equilibrium",
                unit: "-",
                note: if name == "DDA" {
                    "the DDA keeps the density as a block strains, so its mass follows its area: the compressed blocks weigh a few 1e-7 less"
                } else {
                    "rigid blocks at rest: the base carries the weight to the rest criterion's precision"
                },
            },
            Rule::Near {
                target: 1.0,
                tolerance: 0.005,
            },
            solution.base_reaction_ratio(),
        );
    }
    for ((wall, suffix, shows), run) in variants.iter().zip(&runs) {
        c.value(
            Item {
                id: &format!("polygon_dem_vs_dda.bottom_course_difference{suffix}"),
                what: &format!(
                    "largest difference between the DEM's and the DDA's vertical base force on a bottom-course block, over a block's weight; k = {:e} N/m per m, E = {:e} Pa (k/E = {:.2e}), DEM k_s/k_n = {}",
                    wall.contact_stiffness,
                    wall.youngs_modulus,
                    wall.contact_stiffness / wall.youngs_modulus,
                    wall.dem_stiffness_ratio
                ),
                reference: "none exact: the share of each block is statically indeterminate",
                unit: "W_block",
                note: shows,
            },
            None,
            run.bottom_course_difference,
        );
    }
    wall_outputs(c, &runs)?;
    c.text(&wall_explanation(&runs));
    Ok(())
}

/// The wall's set-up in words.
fn wall_text(run: &WallComparison) -> String {
    let w = &run.wall;
    format!(
        "{} blocks in {} courses ({} full {} m × {} m blocks in the even courses, open head joints of {} m, \
         shorter end blocks in the odd courses), ρ = {} kg/m³ (W_block = {:.1} N/m), on a fixed base. \
         Same contact points in both methods (the corners that lie on a neighbour's face), same law per \
         point: k = {:e} N/m per m normal and shear (DEM `NormalStiffness::Constant`, k_s/k_n = {}; DDA \
         penalty p_c, eq. 8 uses one penalty for both), μ = {}. DEM: rigid blocks placed touching, critical \
         dashpots, run to rest ({} steps, unbalanced force {:.1e}). DDA: blocks of E = {:e} Pa, ν = {} \
         (plane stress), return mapping, static analysis ({} steps of 0.01 s, unbalanced force {:.1e}). \
         Contacts in slip at rest: DEM {}, DDA {}.",
        w.blocks().map_or(0, |b| b.len()),
        w.courses,
        w.blocks_per_course,
        w.block_length,
        w.block_height,
        w.joint,
        w.density,
        w.block_weight(),
        w.contact_stiffness,
        w.dem_stiffness_ratio,
        w.friction,
        run.dem.steps,
        run.dem.unbalanced,
        w.youngs_modulus,
        w.poisson_ratio,
        run.dda.steps,
        run.dda.unbalanced,
        run.dem.slipping,
        run.dda.slipping
    )
}

/// The explanation of the remaining difference, with the variants' table.
fn wall_explanation(runs: &[WallComparison]) -> String {
    let shear = runs.last().map_or(f64::NAN, |r| r.bottom_course_difference);
    let mut text = format!(
        "Why the bottom course differs. The base carries the weight in both methods, but how it is \
         shared among the bottom blocks is statically indeterminate: it follows from the compliances. \
         No contact slips, so both solutions are the linear elastic response of their model and the \
         path (DEM dynamics, DDA static steps) does not matter. With the same springs at the same points, \
         the only difference left is that the DDA blocks strain; their share of the compliance is set by \
         k/E. The variants show it: the difference scales with k/E and vanishes with it. The last \
         variant shows why the DEM's shear springs are as stiff as its normal ones: with the DDA's \
         single penalty against a DEM with k_s/k_n = 0.25, nearly rigid blocks differ by {:.1} % of a \
         block's weight.\n\n\
         | contact factor | modulus factor | DEM k_s/k_n | k/E | difference (W_block) | difference / (k/E) |\n|---|---|---|---|---|---|\n",
        100.0 * shear
    );
    let base = &runs[0].wall;
    for run in runs {
        let ratio = run.wall.contact_stiffness / run.wall.youngs_modulus;
        // The scaling with k/E holds for matched shear springs only.
        let scaled = if run.wall.dem_stiffness_ratio == base.dem_stiffness_ratio {
            format!("{:.4}", run.bottom_course_difference / ratio)
        } else {
            "—".into()
        };
        let _ = writeln!(
            text,
            "| {} | {} | {} | {ratio:.3e} | {:.3e} | {scaled} |",
            run.wall.contact_stiffness / base.contact_stiffness,
            run.wall.youngs_modulus / base.youngs_modulus,
            run.wall.dem_stiffness_ratio,
            run.bottom_course_difference,
        );
    }
    text
}

/// The wall's plots and CSV: contact forces side by side, the bottom
/// course by both methods.
fn wall_outputs(c: &mut Collector, runs: &[WallComparison]) -> Result<()> {
    let base = &runs[0];
    let stiff = &runs[1];
    let weight = base.wall.block_weight();
    pictures::wall_forces(
        &c.dir().join("wall_contact_forces.svg"),
        "Running-bond wall at rest, contact forces: polygon DEM (left), DDA (right)",
        &base.wall,
        &base.dem,
        &base.dda,
    )?;
    c.file("wall_contact_forces.svg");
    let index = |v: &[f64]| -> Vec<(f64, f64)> {
        v.iter()
            .enumerate()
            .map(|(i, f)| ((i + 1) as f64, f / weight))
            .collect()
    };
    let series = [
        ("polygon DEM (rigid blocks)", &base.dem.bottom_course),
        ("DDA, E as specified", &base.dda.bottom_course),
        ("DDA, E × 100", &stiff.dda.bottom_course),
    ]
    .map(|(name, v)| Series {
        name: name.into(),
        points: index(v),
        markers: true,
    });
    line_chart(
        &c.dir().join("wall_bottom_course.svg"),
        "Base force on each bottom-course block (DEM and DDA with E × 100 coincide)",
        "block of the bottom course (left to right)",
        "vertical base force / W_block",
        &series,
    )?;
    c.file("wall_bottom_course.svg");
    let rows: Vec<Vec<f64>> = (0..base.dem.bottom_course.len())
        .map(|i| {
            vec![
                (i + 1) as f64,
                base.dem.bottom_course[i] / weight,
                base.dda.bottom_course[i] / weight,
                stiff.dda.bottom_course[i] / weight,
            ]
        })
        .collect();
    write_csv(
        &c.dir().join("wall_bottom_course.csv"),
        &["block", "dem", "dda", "dda_blocks_x100"],
        &rows,
    )?;
    c.file("wall_bottom_course.csv");
    Ok(())
}
