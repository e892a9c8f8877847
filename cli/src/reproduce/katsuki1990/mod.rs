//! Katsuki & Ishikawa (1990), *Earth pressure analysis of filled materials
//! by distinct element method using ellipse model* (paper 000).
//!
//! **Example 1**: 179 circles, r = 0.07 m, in a rigid frame 2.0 m wide,
//! self-weight only. Material (SI, converted once here): ρ = 2.69 gf/cm³ =
//! 2690 kg/m³, E = 750 kgf/cm² = 73.55 MPa (1 kgf = 9.80665 N), ν = 0.3,
//! s = 0.25, μ = 0.577, Δt = 1e-4 s, g = 9.80665 m/s².
//!
//! Choices where the paper's figure is missing (Fig. 5(a)):
//! * the frame is an open box 2.0 m wide and 3.0 m tall;
//! * the circles start at rest and without contacts, in rows alternately of
//!   14 and 13 (horizontal pitch 2.0/14 m, the 13-rows shifted by half a
//!   pitch so the assembly settles into a hexagonal packing), row pitch
//!   0.16 m, the lowest row 5 mm above the floor; the last row is partial
//!   and centred;
//! * rest: kinetic energy below 1e-6 of the potential energy released *and*
//!   mean unbalanced force per particle below 1e-4 of the mean weight, at
//!   10 consecutive checks 100 steps apart (0.1 s), after at least 0.5 s.
//!
//! **Example 2** (shape anisotropy, patterns A–D) and **Example 3** (back
//! storage sand pressure, patterns A–E) use the same material, time step
//! and rest criterion; their patterns are in [`patterns`], the measurement
//! of eq. (23) in [`crate::reproduce::fill_patterns`], and the reasoning of
//! each in its module ([`shape_anisotropy`], [`back_pressure`]).

pub mod back_pressure;
pub mod patterns;
pub mod shape_anisotropy;

pub use back_pressure::{run_back_pressure, BackPressureRun, BACK_PRESSURE};
pub use patterns::{Pattern, EXAMPLE2, PATTERN_E};
pub use shape_anisotropy::{run_pattern, PatternRun};

use std::path::Path;

use super::StudyOptions;
use dismech::dem::DemSimulation;
use dismech::error::Result;
use dismech::explicit::{
    critical_time_step, ContactTarget, DemSettings, RestCriterion, RunOutcome,
};
use dismech::integrate::ExplicitEuler;
use dismech::law::SpringDashpotCoulomb;
use dismech::scene::{CircleRows, Scene};
use dismech_cli::output::plot::{line_chart, Series};
use dismech_cli::output::{write_csv, Check, Reference, Reported, Rule, Summary};

/// File name of the paper.
pub const PAPER: &str = "000_87caa095a10dc755.txt";
/// Standard gravity (m/s²), also the kgf → N factor.
pub const STANDARD_GRAVITY: f64 = 9.80665;
/// ρ = 2.69 gf/cm³ in kg/m³.
pub const DENSITY: f64 = 2.69 * 1e-3 / 1e-6;
/// E = 750 kgf/cm² in Pa.
pub const YOUNGS_MODULUS: f64 = 750.0 * STANDARD_GRAVITY / 1e-4;
/// Poisson's ratio ν.
pub const POISSON_RATIO: f64 = 0.3;
/// k_s / k_n.
pub const STIFFNESS_RATIO: f64 = 0.25;
/// Friction coefficient μ (φ = 30°).
pub const FRICTION: f64 = 0.577;
/// Time step Δt (s).
pub const TIME_STEP: f64 = 1e-4;

/// Geometry of an Example-1-type filling.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FillConfig {
    /// Number of circles.
    pub count: usize,
    /// Radius (m).
    pub radius: f64,
    /// Inner width of the frame (m).
    pub width: f64,
    /// Height of the frame walls (m).
    pub height: f64,
    /// Circles in a full row; rows alternate `per_row` and `per_row − 1`.
    pub per_row: usize,
    /// Vertical distance between rows at the start (m).
    pub row_pitch: f64,
}

impl FillConfig {
    /// The paper's Example 1 (179 circles, 2.0 m frame).
    pub fn paper() -> Self {
        Self {
            count: 179,
            radius: 0.07,
            width: 2.0,
            height: 3.0,
            per_row: 14,
            row_pitch: 0.16,
        }
    }

    /// A smaller filling of the same kind (47 circles in a 1.0 m frame) that
    /// runs in a second.
    #[cfg(test)]
    pub fn reduced() -> Self {
        Self {
            count: 47,
            width: 1.0,
            height: 1.5,
            per_row: 7,
            ..Self::paper()
        }
    }
}

/// The scene of an Example-1-type filling: circles at rest in an open box
/// ([`CircleRows`], lowest row 5 mm above the floor).
pub fn fill_scene(config: &FillConfig) -> Result<Scene> {
    CircleRows {
        count: config.count,
        radius: config.radius,
        width: config.width,
        height: config.height,
        per_row: config.per_row,
        row_pitch: config.row_pitch,
        clearance: 0.005,
        density: DENSITY,
    }
    .scene(STANDARD_GRAVITY)
}

/// Paper 000's contact law with Example 1's material.
pub fn material_law() -> Result<SpringDashpotCoulomb> {
    SpringDashpotCoulomb::katsuki(YOUNGS_MODULUS, POISSON_RATIO, STIFFNESS_RATIO, FRICTION)
}

/// The rest criterion of Example 1.
pub fn rest_criterion() -> RestCriterion {
    RestCriterion {
        kinetic_to_released_ratio: 1e-6,
        min_time: 0.5,
        max_time: 30.0,
        check_every: 100,
        consecutive_checks: 10,
        unbalanced_force_ratio: 1e-4,
        ..RestCriterion::default()
    }
}

/// The equilibrium of a settled filling.
#[derive(Debug, Clone, PartialEq)]
pub struct FillEquilibrium {
    /// Total weight W (N/m).
    pub weight: f64,
    /// Σ vertical reactions of all walls on the particles (N/m).
    pub vertical_reaction: f64,
    /// Horizontal reaction of the left wall on the particles (N/m).
    pub left_horizontal: f64,
    /// Horizontal reaction of the right wall (N/m).
    pub right_horizontal: f64,
    /// Vertical (friction) reaction of the side walls (N/m).
    pub side_friction: f64,
    /// Height of the filling (m): highest particle top.
    pub fill_height: f64,
}

impl FillEquilibrium {
    /// Σ vertical reactions / W.
    pub fn vertical_ratio(&self) -> f64 {
        self.vertical_reaction / self.weight
    }
    /// |F_left + F_right| / W.
    pub fn horizontal_imbalance(&self) -> f64 {
        (self.left_horizontal + self.right_horizontal).abs() / self.weight
    }
}

/// Wall reactions of a DEM run in an [`dismech::scene::Frame::open_box`].
pub fn equilibrium(sim: &DemSimulation<SpringDashpotCoulomb, ExplicitEuler>) -> FillEquilibrium {
    let frame = &sim.scene().frame;
    let reaction = |name: &str| {
        frame
            .index_of(name)
            .map(|w| -sim.wall_load(w))
            .unwrap_or_default()
    };
    let (left, right, bottom) = (reaction("left"), reaction("right"), reaction("bottom"));
    let fill_height = sim
        .scene()
        .particles
        .iter()
        .map(|p| p.pose.position.y + p.shape.as_shape().bounding_radius())
        .fold(0.0, f64::max);
    FillEquilibrium {
        weight: sim.scene().total_weight(),
        vertical_reaction: left.y + right.y + bottom.y,
        left_horizontal: left.x,
        right_horizontal: right.x,
        side_friction: left.y + right.y,
        fill_height,
    }
}

/// Normal pressure on a side wall at each of its contacts, as paper 000
/// defines it for eq. (23): `(h, P_h / d)` with `h` the height of the
/// contact, `P_h` its normal force and `d` the mean distance between the
/// wall's contacts (`default_spacing` when the wall has fewer than two).
/// Sorted by height.
pub fn wall_pressure_profile(
    sim: &DemSimulation<SpringDashpotCoulomb, ExplicitEuler>,
    wall_name: &str,
    default_spacing: f64,
) -> Vec<(f64, f64)> {
    let Some(w) = sim.scene().frame.index_of(wall_name) else {
        return Vec::new();
    };
    let (forces, spacing) =
        crate::reproduce::fill_patterns::wall_normal_forces(sim, w, default_spacing);
    forces.iter().map(|&(h, f, _)| (h, f / spacing)).collect()
}

/// Build, check and settle a filling; `on_check(time, ratio)` reports
/// progress.
pub fn settle(
    config: &FillConfig,
    on_check: impl FnMut(f64, f64),
) -> Result<(
    DemSimulation<SpringDashpotCoulomb, ExplicitEuler>,
    RunOutcome,
)> {
    settle_scene(
        fill_scene(config)?,
        DemSettings::default().initial_overlap_tolerance,
        on_check,
    )
}

/// Run `scene` with Example 1's material, time step and rest criterion
/// until it is at rest; `on_check(time, ratio)` reports progress.
/// `overlap_tolerance` (m) is the largest overlap accepted at the start:
/// tiny for a filling that starts without contacts, a fraction of a
/// millimetre for an assembly that has settled and is loaded anew.
pub fn settle_scene(
    scene: Scene,
    overlap_tolerance: f64,
    on_check: impl FnMut(f64, f64),
) -> Result<(
    DemSimulation<SpringDashpotCoulomb, ExplicitEuler>,
    RunOutcome,
)> {
    let settings = DemSettings {
        dt: TIME_STEP,
        initial_overlap_tolerance: overlap_tolerance,
        ..DemSettings::default()
    };
    let mut sim = DemSimulation::new(scene, material_law()?, ExplicitEuler, settings)?;
    let outcome = sim.run_to_rest(&rest_criterion(), on_check)?;
    if let Some(hint) = outcome.not_at_rest_hint() {
        eprintln!("  {hint}");
    }
    Ok((sim, outcome))
}

pub(crate) fn progress_bar(
    options: &StudyOptions,
    label: &str,
    max_time: f64,
) -> indicatif::ProgressBar {
    if !options.progress {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new((max_time * 1000.0) as u64);
    if let Ok(style) = indicatif::ProgressStyle::with_template(
        "{prefix} [{elapsed_precise}] {bar:30} t = {pos} ms  {msg}",
    ) {
        bar.set_style(style);
    }
    bar.set_prefix(label.to_string());
    bar
}

/// Run Example 1 at full size and write its outputs into `options.dir`
/// (staged, to become `OUT/katsuki1990/`).
pub fn reproduce(options: &StudyOptions) -> Result<Summary> {
    let dir = options.dir.clone();
    let config = FillConfig::paper();
    let limit = critical_time_step(&fill_scene(&config)?, &material_law()?);
    let bar = progress_bar(options, "katsuki1990 ex1", rest_criterion().max_time);
    let (sim, outcome) = settle(&config, |t, ratio| {
        bar.set_position((t * 1000.0) as u64);
        bar.set_message(format!("KE/released = {ratio:.2e}"));
    })?;
    bar.finish_and_clear();
    let eq = equilibrium(&sim);
    let mut files = Vec::new();
    write_example1_outputs(&dir, &sim, &config, &mut files)?;
    write_csv(
        &dir.join("ex1_equilibrium.csv"),
        &[
            "weight_n_per_m",
            "vertical_reaction_n_per_m",
            "left_wall_horizontal_n_per_m",
            "right_wall_horizontal_n_per_m",
            "side_wall_friction_n_per_m",
            "fill_height_m",
            "settling_time_s",
            "steps",
        ],
        &[vec![
            eq.weight,
            eq.vertical_reaction,
            eq.left_horizontal,
            eq.right_horizontal,
            eq.side_friction,
            eq.fill_height,
            outcome.time,
            outcome.steps as f64,
        ]],
    )?;
    files.push("ex1_equilibrium.csv".into());

    let vertical = eq.vertical_ratio();
    let horizontal = eq.horizontal_imbalance();
    let rest_ratio = outcome.kinetic_energy / outcome.released_potential_energy;
    let mut checks = vec![
        Check::new(
            "ex1.vertical_reaction_ratio",
            "sum of vertical wall reactions (bottom + side-wall friction) / total weight",
            "-",
            vertical,
            &Rule::near(Reference::paper(1.0), 0.005),
        ),
        Check::new(
            "ex1.horizontal_imbalance_ratio",
            "|F_left + F_right| / total weight (horizontal reactions of the side walls cancel)",
            "-",
            horizontal,
            &Rule::near(Reference::paper(0.0), 0.01),
        ),
        Check::new(
            "ex1.rest_kinetic_ratio",
            "kinetic energy / potential energy released at the end of the run (at rest below the bound)",
            "-",
            rest_ratio,
            &Rule::Below(Reference::number(rest_criterion().kinetic_to_released_ratio)),
        ),
        Check::new(
            "ex1.stable_time_step",
            format!(
                "estimated stable limit of the explicit step (s), governed by the {}; the paper's dt = {TIME_STEP} s must be below it",
                limit.governing
            ),
            "s",
            limit.dt,
            &Rule::AtLeast(Reference::paper(TIME_STEP)),
        ),
    ];
    let spinner = if options.progress {
        indicatif::ProgressBar::new_spinner()
    } else {
        indicatif::ProgressBar::hidden()
    };
    spinner.set_message("katsuki1990: checking the ellipse contact on 100 000 random pairs");
    spinner.enable_steady_tick(std::time::Duration::from_millis(200));
    checks.extend(random_pair_checks());
    spinner.set_message(
        "katsuki1990: Examples 2 and 3 (patterns A-E settle, then take the back pressure)",
    );
    let (example_checks, values, report) = examples_2_and_3(&dir, 1.0, &mut files)?;
    checks.extend(example_checks);
    spinner.finish_and_clear();
    Summary {
        study: "katsuki1990".into(),
        paper: PAPER.into(),
        checks,
        values,
        files,
    }
    .write_with_report(&dir, &report)
}

fn write_example1_outputs(
    dir: &Path,
    sim: &DemSimulation<SpringDashpotCoulomb, ExplicitEuler>,
    config: &FillConfig,
    files: &mut Vec<String>,
) -> Result<()> {
    let scene = sim.scene();
    shape_anisotropy::picture(
        &dir.join("ex1_contact_forces.svg"),
        "Example 1: contact forces at rest (179 circles), cf. paper Fig. 5(b)",
        sim,
    )?;
    files.push("ex1_contact_forces.svg".into());

    let spacing = 2.0 * config.radius;
    let left = wall_pressure_profile(sim, "left", spacing);
    let right = wall_pressure_profile(sim, "right", spacing);
    let kpa = |v: &[(f64, f64)]| v.iter().map(|&(h, p)| (p / 1e3, h)).collect::<Vec<_>>();
    line_chart(
        &dir.join("ex1_wall_pressure.svg"),
        "Example 1: side-wall pressure P_h / d vs height (eq. 23)",
        "normal pressure (kPa)",
        "height above the floor (m)",
        &[
            Series {
                name: "left wall".into(),
                points: kpa(&left),
                markers: true,
            },
            Series {
                name: "right wall".into(),
                points: kpa(&right),
                markers: true,
            },
        ],
    )?;
    files.push("ex1_wall_pressure.svg".into());
    let rows: Vec<Vec<f64>> = left
        .iter()
        .map(|&(h, p)| vec![0.0, h, p])
        .chain(right.iter().map(|&(h, p)| vec![1.0, h, p]))
        .collect();
    write_csv(
        &dir.join("ex1_wall_pressure.csv"),
        &["wall_is_right", "height_m", "pressure_pa"],
        &rows,
    )?;
    files.push("ex1_wall_pressure.csv".into());

    let contact_rows: Vec<Vec<f64>> = sim
        .contacts()
        .iter()
        .map(|c| {
            let (kind, index) = match c.target {
                ContactTarget::Particle(j) => (0.0, j as f64),
                ContactTarget::Wall(w) => (1.0, w as f64),
            };
            vec![
                c.particle as f64,
                kind,
                index,
                c.point.x,
                c.point.y,
                c.force_on_target.x,
                c.force_on_target.y,
            ]
        })
        .collect();
    write_csv(
        &dir.join("ex1_contacts.csv"),
        &[
            "particle",
            "target_is_wall",
            "target",
            "x_m",
            "y_m",
            "fx_n_per_m",
            "fy_n_per_m",
        ],
        &contact_rows,
    )?;
    files.push("ex1_contacts.csv".into());
    let particle_rows: Vec<Vec<f64>> = scene
        .particles
        .iter()
        .map(|p| vec![p.pose.position.x, p.pose.position.y, p.pose.angle])
        .collect();
    write_csv(
        &dir.join("ex1_particles.csv"),
        &["x_m", "y_m", "angle_rad"],
        &particle_rows,
    )?;
    files.push("ex1_particles.csv".into());
    Ok(())
}

/// Examples 2 and 3 at `scale` (see [`Pattern::layout`]): settle patterns
/// A–E (two at a time), measure Example 2 on A–D, load all five with the
/// back pressure; returns the checks, the reported values and the Markdown
/// report.
pub fn examples_2_and_3(
    dir: &Path,
    scale: f64,
    files: &mut Vec<String>,
) -> Result<(Vec<Check>, Vec<Reported>, String)> {
    use rayon::prelude::*;
    let patterns: Vec<Pattern> = EXAMPLE2.iter().copied().chain([PATTERN_E]).collect();
    let settled: Vec<PatternRun> = patterns
        .par_iter()
        .map(|p| run_pattern(p, scale, |_, _| {}))
        .collect::<Result<_>>()?;
    let loaded: Vec<(Pattern, BackPressureRun)> = settled
        .par_iter()
        .map(|run| Ok((run.pattern, run_back_pressure(run, |_, _| {})?)))
        .collect::<Result<_>>()?;
    let (mut checks, mut values) =
        shape_anisotropy::example2_outputs(dir, &settled[..EXAMPLE2.len()], files)?;
    let (ex3_checks, ex3_values, ex3_table) = back_pressure::example3_outputs(dir, &loaded, files)?;
    checks.extend(ex3_checks);
    values.extend(ex3_values);
    Ok((
        checks,
        values,
        report(&settled[..EXAMPLE2.len()], &ex3_table),
    ))
}

/// The Markdown report of Examples 2 and 3.
fn report(example2: &[PatternRun], example3_rows: &[String]) -> String {
    let mut md = String::from(
        "# Katsuki & Ishikawa (1990): Examples 2 and 3\n\n\
         Patterns (Figs. 6(a) and 8(a) are missing; chosen here): every particle has the area of a circle of r = 0.07 m; ellipses have a/b = 2; frame 2.0 m wide; rows alternate n and n - 1 particles (running bond), started 10 mm apart and settled under self-weight with Example 1's material and rest criterion.\n\n\
         ## Example 2: earth-pressure coefficient K (eq. 23)\n\n\
         K at each side-wall contact is (P_h / d) / (sigma_v,max z / H), sigma_v,max = W / width, z the depth below the top of the filling. Representative K: median over both walls at depths 0.2-0.9 H. `K (d = wall contacts)` takes d as the spacing of the wall contacts (P_h / d is then the wall stress); `K (d = element spacing)` takes d as the row pitch.\n\n\
         | pattern | particles | omega (deg) | K (d = wall contacts) | K (d = element spacing) | paper K |\n\
         |---|---|---|---|---|---|\n",
    );
    for run in example2 {
        let paper = match run.pattern.name {
            "A" => "0.2-0.3",
            "C" => "0.6",
            "D" => "1.2-2.0",
            _ => "small (as A)",
        };
        md.push_str(&format!(
            "| {} ({}) | {} | {:.1} | {} | {} | {} |\n",
            run.pattern.name,
            run.pattern.description,
            run.sim.scene().particles.len(),
            run.mean_omega_deg(),
            run.k().2.map_or("none".into(), |k| format!("{k:.3}")),
            run.k_element_spacing()
                .map_or("none".into(), |k| format!("{k:.3}")),
            paper
        ));
    }
    md.push_str(
        "\nEach K is one realisation. Where the settling is chaotic (the upright ellipses of D, the mixed rows of B), round-off decides which way the particles tip, so the two walls' medians and the K above differ from one realisation to the next (the walls' medians by up to a fifth of K when each particle of D is moved by at most 1e-12 m before settling), although the layout is mirror-symmetric; the check `ex2.K_left_right_p` asks whether the walls differ beyond their contacts' scatter (Welch's t test at the 1 % level).\n",
    );
    md.push_str(&format!(
        "\n## Example 3: front-wall pressure under a uniform back pressure of {} kPa\n\n\
         The back wall is replaced by the pressure on the back particles (those within the smallest semi-axis of the back, and the first seen from the back at each height), each over its share of the height; the frame is closed by a lid; self-weight stays on. Centroid: height of the resultant front-wall force / H (1/3 triangular, 1/2 uniform).\n\n\
         | pattern | arrangement | front force / (p H) | centroid / H | lower-half share | reads as | paper |\n\
         |---|---|---|---|---|---|---|\n",
        BACK_PRESSURE / 1e3
    ));
    for row in example3_rows {
        md.push_str(row);
        md.push('\n');
    }
    md
}

/// Robustness of the ellipse contact over 100 000 random pairs against the
/// independent reference of [`dismech::reference::ellipse_contact`].
fn random_pair_checks() -> Vec<Check> {
    let s = dismech::reference::ellipse_contact::random_pair_statistics_parallel(100_000, 2026);
    let check = |id: &str, description: &str, computed: f64, bound: f64| {
        Check::new(
            id,
            description,
            "-",
            computed,
            &Rule::AtMost(Reference::number(bound)),
        )
    };
    vec![
        Check::new(
            "contact.random_pairs.count",
            format!(
                "random ellipse pairs tested (aspect 1-5, size ratio 1-10, overlap -5 % to 20 % of the smaller b), {} of them in contact by the reference",
                s.in_contact
            ),
            "-",
            s.count as f64,
            &Rule::holds(
                "all 100000 pairs ran and the reference finds some of them in contact",
                s.count == 100_000 && s.in_contact > 0,
            ),
        ),
        check(
            "contact.random_pairs.missed",
            "contacts the routine missed where the reference finds an overlap",
            s.missed as f64,
            0.0,
        ),
        check(
            "contact.random_pairs.false",
            "contacts the routine reported where the reference finds a gap",
            s.false_contacts as f64,
            0.0,
        ),
        check(
            "contact.random_pairs.max_point_error",
            "largest distance between the routine's and the reference's intersection points P1, P2, divided by the smaller b",
            s.max_point_error,
            1e-8,
        ),
    ]
}

#[cfg(test)]
mod tests;
