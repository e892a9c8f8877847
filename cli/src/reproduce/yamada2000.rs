//! Yamada & Tamura (2000), *A rigid-plastic analysis for granular materials
//! and its application to bearing capacity problems* (paper 002).
//!
//! Reproduced here: the two-element example of §2.2, eqs. (26)–(28), all
//! 28 entries of Table 1 (rolling U-model) against the table and eq. (32),
//! the non-rolling U-model against Table 3 and eq. (38) for k = 2 … 10, the
//! L-model's global cohesion c_G = P / (2 l_L) for growing n against
//! eq. (20), and unequal lattices m ≠ n (which the authors' simplex could
//! not solve). The geometry is the lattice of [`dismech::limit::lattice`]
//! with R = 1, C_p = 1 and walls 2C_p.

use std::fmt::Write as _;

use super::StudyOptions;
use crate::reproduce::katsuki1990;
use dismech::dem::DemSimulation;
use dismech::error::Result;
use dismech::explicit::{DemSettings, RunOutcome};
use dismech::integrate::ExplicitEuler;
use dismech::law::RigidPlastic;
use dismech::law::SpringDashpotCoulomb;
use dismech::limit::lattice::Lattice;
use dismech::limit::{
    analyse, mechanism_uniqueness, model_from_packing, LimitModel, LimitResult, LimitStatus,
    PackingLimitSettings, Uniqueness,
};
use dismech::lp::LinearProgramSolver;
use dismech::math::{perp, Point};
use dismech::math::{SplitMix64, Vec2};
use dismech::reference::lattice_limit_load::{eq20, eq32, eq38};
use dismech::reference::two_elements;
use dismech::scene::{Frame, Scene};
use dismech_cli::output::plot::mechanism_picture;
use dismech_cli::output::plot::{line_chart, Series};
use dismech_cli::output::{number, write_csv, Check, Reference, Rule, Summary};

/// File name of the paper.
pub const PAPER: &str = "002_d116351db0f49329.txt";

/// Table 1 of the paper (rolling U-model, k = m = n, P / C_p), row k/2 − 1,
/// column n' − 1.
pub const TABLE1: [&[f64]; 7] = [
    &[2.41],
    &[5.95, 8.07],
    &[9.01, 11.60, 13.72],
    &[11.96, 14.59, 17.26, 19.38],
    &[14.53, 17.37, 20.33, 22.92, 25.04],
    &[17.53, 20.18, 23.27, 25.98, 28.57, 30.69],
    &[20.60, 22.99, 26.14, 28.93, 31.64, 34.23, 36.36],
];

/// Table 3 of the paper (non-rolling U-model, P / C_p), k = 2 … 10; entries
/// the table leaves blank are absent.
pub const TABLE3: [&[f64]; 5] = [
    &[4.83],
    &[10.49, 8.07],
    &[16.14, 22.14],
    &[21.80, 27.80, 33.80],
    &[27.46, 33.46, 39.46, 45.46],
];

/// Agreement with a printed table entry. The tables print two decimals and
/// mostly *truncate* rather than round (11.6066 is printed 11.60, 13.7279
/// 13.72, 30.6985 30.69), so an entry matches when within one unit of the
/// last printed digit.
const PRINT_TOLERANCE: f64 = 0.01;
/// Relative agreement with a closed form.
const FORMULA_TOLERANCE: f64 = 1e-6;

/// Agreement of an LP optimum with a table entry: within one unit of the
/// last printed digit of the paper's value.
fn table_rule(table: f64) -> Rule {
    Rule::near(Reference::paper(table), PRINT_TOLERANCE)
}

/// Agreement of an LP optimum with a closed form: within
/// `FORMULA_TOLERANCE (1 + |formula|)`.
fn formula_rule(formula: f64, formula_name: &str) -> Rule {
    Rule::near(
        Reference::named(formula_name, formula),
        FORMULA_TOLERANCE * (1.0 + formula.abs()),
    )
}

/// The rule of a table entry's check: the table's value (if the table
/// gives one) or the closed form.
fn entry_rule(table: Option<f64>, formula: f64, formula_name: &str) -> Rule {
    match table {
        Some(t) => Rule::AnyOf(vec![table_rule(t), formula_rule(formula, formula_name)]),
        None => formula_rule(formula, formula_name),
    }
}

/// Which reference an LP optimum agrees with.
fn agreement(lp: f64, table: Option<f64>, formula: f64, formula_name: &str) -> String {
    let table_ok = table.is_some_and(|t| table_rule(t).passes(lp));
    let formula_ok = formula_rule(formula, formula_name).passes(lp);
    match (table_ok, formula_ok) {
        (true, true) => "both".into(),
        (true, false) => "table only".into(),
        (false, true) => format!("{formula_name} only"),
        (false, false) => "neither".into(),
    }
}

fn solve(lattice: &Lattice, solver: &mut LinearProgramSolver) -> Result<LimitResult> {
    analyse(&lattice.build()?, solver)
}

/// The kinematic (upper-bound) load of a result, NaN without a collapse.
fn upper(r: &LimitResult) -> f64 {
    r.kinematic_load.unwrap_or(f64::NAN)
}

/// The static (lower-bound) load of a result, NaN without a collapse.
fn lower(r: &LimitResult) -> f64 {
    r.static_load.unwrap_or(f64::NAN)
}

/// Relative primal–dual gap of a solved LP.
fn gap(r: &LimitResult) -> f64 {
    (upper(r) - lower(r)).abs() / (1.0 + upper(r).abs())
}

/// Run the study and write its outputs into `options.dir`
/// (staged, to become `OUT/yamada2000/`).
pub fn reproduce(options: &StudyOptions) -> Result<Summary> {
    let dir = options.dir.clone();
    let mut solver = LinearProgramSolver::default();
    let mut checks = Vec::new();
    let mut files = Vec::new();
    let mut max_gap = 0.0f64;
    let mut report = String::from("# Yamada & Tamura (2000): LP limit loads against the paper\n\n");

    // §2.2 and eqs. (26)–(28).
    let two = analyse(&two_elements(1.0)?, &mut solver)?;
    max_gap = max_gap.max(gap(&two));
    let root2 = std::f64::consts::SQRT_2;
    let mut exact = vec![(
        "sec2_2.two_elements",
        "two-element example of §2.2, P/C_p = 1 + √2",
        upper(&two),
        1.0 + root2,
    )];
    for (id, text, k, np, value) in [
        ("eq26", "P(2,2,1)/C_p = 1 + √2, eq. (26)", 2, 1, 1.0 + root2),
        (
            "eq27",
            "P(4,4,1)/C_p = 1 + 7√2/2, eq. (27)",
            4,
            1,
            1.0 + 3.5 * root2,
        ),
        (
            "eq28",
            "P(4,4,2)/C_p = 1 + 5√2, eq. (28)",
            4,
            2,
            1.0 + 5.0 * root2,
        ),
    ] {
        let r = solve(&Lattice::u_model(k, k, np, true), &mut solver)?;
        max_gap = max_gap.max(gap(&r));
        exact.push((id, text, upper(&r), value));
    }
    for (id, text, computed, paper) in exact {
        checks.push(Check::new(
            id,
            format!("{text}; LP optimum (relative tolerance {FORMULA_TOLERANCE:e})"),
            "C_p",
            computed,
            &Rule::near(Reference::paper(paper), FORMULA_TOLERANCE * paper),
        ));
    }

    // Table 1: rolling U-model.
    report.push_str("## Table 1 — rolling U-model, P/C_p\n\n| k | n' | Table 1 | eq. (32) | LP (primal) | LP (dual) | LP agrees with |\n|---|---|---|---|---|---|---|\n");
    let mut rows = Vec::new();
    for (row, values) in TABLE1.iter().enumerate() {
        let k = 2 * (row + 1);
        for (col, &paper) in values.iter().enumerate() {
            let np = col + 1;
            let r = solve(&Lattice::u_model(k, k, np, true), &mut solver)?;
            max_gap = max_gap.max(gap(&r));
            let formula = eq32(k, np);
            let lp = upper(&r);
            let agrees = agreement(lp, Some(paper), formula, "eq. (32)");
            let _ = writeln!(
                report,
                "| {k} | {np} | {paper:.2} | {formula:.4} | {lp:.4} | {:.4} | {agrees} |",
                lower(&r)
            );
            rows.push(vec![k as f64, np as f64, paper, formula, lp, lower(&r)]);
            checks.push(Check::new(
                format!("table1.k{k}.n{np}"),
                format!(
                    "rolling U-model P(k,k,n')/C_p by LP, against Table 1 (to its last printed digit) or eq. (32); agrees with: {agrees}"
                ),
                "C_p",
                lp,
                &entry_rule(Some(paper), formula, "eq. (32)"),
            ));
        }
    }
    write_csv(
        &dir.join("table1.csv"),
        &["k", "n_prime", "table1", "eq32", "lp_primal", "lp_dual"],
        &rows,
    )?;
    files.push("table1.csv".into());

    // Table 3: non-rolling U-model.
    report.push_str("\n## Table 3 — non-rolling U-model, P/C_p\n\n| k | n' | Table 3 | eq. (38) | LP (primal) | LP (dual) | LP agrees with |\n|---|---|---|---|---|---|---|\n");
    let mut rows = Vec::new();
    for k in (2..=10).step_by(2) {
        for np in 1..=k / 2 {
            let paper = TABLE3[k / 2 - 1].get(np - 1).copied();
            let r = solve(&Lattice::u_model(k, k, np, false), &mut solver)?;
            max_gap = max_gap.max(gap(&r));
            let formula = eq38(k, np);
            let lp = upper(&r);
            let agrees = agreement(lp, paper, formula, "eq. (38)");
            let shown = paper
                .map(|p| format!("{p:.2}"))
                .unwrap_or_else(|| "—".into());
            let _ = writeln!(
                report,
                "| {k} | {np} | {shown} | {formula:.4} | {lp:.4} | {:.4} | {agrees} |",
                lower(&r)
            );
            rows.push(vec![
                k as f64,
                np as f64,
                paper.unwrap_or(f64::NAN),
                formula,
                lp,
                lower(&r),
            ]);
            checks.push(Check::new(
                format!("table3.k{k}.n{np}"),
                format!(
                    "non-rolling U-model P(k,k,n')/C_p by LP, against Table 3 (to its last printed digit) or eq. (38); agrees with: {agrees}"
                ),
                "C_p",
                lp,
                &entry_rule(paper, formula, "eq. (38)"),
            ));
        }
    }
    write_csv(
        &dir.join("table3.csv"),
        &["k", "n_prime", "table3", "eq38", "lp_primal", "lp_dual"],
        &rows,
    )?;
    files.push("table3.csv".into());

    // Eq. (20): global cohesion of the rolling L-model for growing n.
    report.push_str("\n## Eq. (20) — rolling L-model, c_G R / C_p = P / (2 l_L)\n\n| m | n = 16 | n = 64 | n = 256 | eq. (20) | ratio at n = 256 |\n|---|---|---|---|---|---|\n");
    let sizes = [4usize, 8, 16, 32, 64, 128, 256];
    let mut rows = Vec::new();
    let mut series = Vec::new();
    for m in [2usize, 4, 6, 8] {
        let formula = eq20(m);
        let mut values = Vec::new();
        for &n in &sizes {
            let lattice = Lattice::l_model(m, n, true);
            let r = solve(&lattice, &mut solver)?;
            max_gap = max_gap.max(gap(&r));
            let c_g = upper(&r) / (2.0 * lattice.plate_length());
            values.push((n as f64, c_g));
            rows.push(vec![m as f64, n as f64, c_g, formula]);
        }
        let at = |n: usize| values[sizes.iter().position(|&s| s == n).unwrap_or(0)].1;
        let ratio = at(256) / formula;
        let _ = writeln!(
            report,
            "| {m} | {:.4} | {:.4} | {:.4} | {formula:.4} | {ratio:.4} |",
            at(16),
            at(64),
            at(256)
        );
        checks.push(Check::new(
            format!("eq20.cG_over_formula.m{m}"),
            format!(
                "rolling L-model c_G = P/(2 l_L) at n = 256 divided by eq. (20) ({formula:.4}); c_G rises towards eq. (20) as n grows"
            ),
            "-",
            ratio,
            &Rule::near(Reference::number(1.0), 0.01),
        ));
        series.push(Series {
            name: format!("m = {m} (LP)"),
            points: values.clone(),
            markers: true,
        });
        series.push(Series {
            name: format!("m = {m}, eq. (20)"),
            points: vec![
                (sizes[0] as f64, formula),
                (sizes[sizes.len() - 1] as f64, formula),
            ],
            markers: false,
        });
    }
    write_csv(
        &dir.join("eq20.csv"),
        &["m", "n", "c_g_lp", "c_g_eq20"],
        &rows,
    )?;
    files.push("eq20.csv".into());
    line_chart(
        &dir.join("eq20_global_cohesion.svg"),
        "Rolling L-model: global cohesion c_G R / C_p against n",
        "elements per column n",
        "c_G R / C_p",
        &series,
    )?;
    files.push("eq20_global_cohesion.svg".into());

    // Unequal lattices.
    report.push_str("\n## Unequal lattices (m ≠ n), rolling U-model, n' = 1\n\n| m | n | status | P/C_p |\n|---|---|---|---|\n");
    let mut rows = Vec::new();
    for (m, n) in [
        (2usize, 4usize),
        (4, 2),
        (4, 8),
        (8, 4),
        (6, 10),
        (10, 6),
        (8, 16),
        (16, 8),
    ] {
        let r = solve(&Lattice::u_model(m, n, 1, true), &mut solver)?;
        if r.status == LimitStatus::Collapse {
            max_gap = max_gap.max(gap(&r));
        }
        let shown = r
            .load
            .map(|p| format!("{p:.4}"))
            .unwrap_or_else(|| "no mechanism".into());
        let _ = writeln!(report, "| {m} | {n} | {:?} | {shown} |", r.status);
        rows.push(vec![m as f64, n as f64, r.load.unwrap_or(f64::NAN)]);
    }
    write_csv(&dir.join("unequal.csv"), &["m", "n", "p_over_cp"], &rows)?;
    files.push("unequal.csv".into());

    // Bearing-capacity factor N_c = P / (c_G l_U) against s = n'/k (Fig. 10).
    let nc = bearing_capacity_curves(&mut solver, &mut max_gap)?;
    let mut rows = Vec::new();
    let mut series = Vec::new();
    for curve in &nc {
        for &(s, value) in &curve.points {
            rows.push(vec![
                curve.k as f64,
                if curve.rolling { 1.0 } else { 0.0 },
                s,
                value,
            ]);
        }
        series.push(Series {
            name: format!(
                "{}, k = {} (LP)",
                if curve.rolling {
                    "rolling"
                } else {
                    "non-rolling"
                },
                curve.k
            ),
            points: curve.points.clone(),
            markers: true,
        });
    }
    let s_axis: Vec<f64> = (5..=50).map(|i| i as f64 / 100.0).collect();
    series.push(Series {
        name: "N_c = 2 + 1/s, eq. (34)".into(),
        points: s_axis.iter().map(|&s| (s, 2.0 + 1.0 / s)).collect(),
        markers: false,
    });
    series.push(Series {
        name: "N_c = 5√2/3 + 10/(9s), eq. (40)".into(),
        points: s_axis
            .iter()
            .map(|&s| (s, 5.0 * root2 / 3.0 + 10.0 / (9.0 * s)))
            .collect(),
        markers: false,
    });
    write_csv(
        &dir.join("bearing_capacity.csv"),
        &["k", "rolling", "s", "n_c"],
        &rows,
    )?;
    files.push("bearing_capacity.csv".into());
    line_chart(
        &dir.join("bearing_capacity.svg"),
        "Bearing-capacity factor N_c against s = n'/k (cf. Fig. 10)",
        "s = n'/k",
        "N_c = P / (c_G l_U)",
        &series,
    )?;
    files.push("bearing_capacity.svg".into());
    report.push_str("\n## Bearing-capacity factor N_c = P/(c_G l_U) (Fig. 10)\n\nc_G = 1/(4 sin²α) C_p/R = 0.5 for rolling (eq. 21); 0.9 for non-rolling (the paper's value, §3.2). Values in `bearing_capacity.csv`, plot `bearing_capacity.svg`.\n\n| model | k | s | N_c (LP) | formula |\n|---|---|---|---|---|\n");
    for curve in &nc {
        for &(s, value) in curve.points.iter().step_by(3) {
            let formula = if curve.rolling {
                2.0 + 1.0 / s
            } else {
                5.0 * root2 / 3.0 + 10.0 / (9.0 * s)
            };
            let _ = writeln!(
                report,
                "| {} | {} | {s:.3} | {value:.3} | {formula:.3} |",
                if curve.rolling {
                    "rolling"
                } else {
                    "non-rolling"
                },
                curve.k
            );
        }
    }

    // Mechanisms (Figs. 4, 6–8 rolling; 13–15 non-rolling).
    report.push_str("\n## Mechanisms\n\n| figure | model | P/C_p | optimum unique | file |\n|---|---|---|---|---|\n");
    for (figure, k, np, rolling) in [
        ("Fig. 4", 2usize, 1usize, true),
        ("Fig. 6", 4, 1, true),
        ("Fig. 7", 4, 2, true),
        ("Fig. 8", 10, 1, true),
        ("Fig. 13", 2, 1, false),
        ("Fig. 14", 4, 1, false),
        ("Fig. 15", 10, 2, false),
    ] {
        let name = format!(
            "mechanism_{}_k{k}_n{np}.svg",
            if rolling { "rolling" } else { "nonrolling" }
        );
        let model = Lattice::u_model(k, k, np, rolling).build()?;
        let r = analyse(&model, &mut solver)?;
        max_gap = max_gap.max(gap(&r));
        let uniqueness = mechanism_uniqueness(&model, &mut solver, &r)?;
        let note = uniqueness_note(&uniqueness);
        plot_mechanism(
            &dir.join(&name),
            &format!(
                "{figure}: {} U-model ({k},{k},{np}), P = {:.4} C_p; {note}",
                if rolling { "rolling" } else { "non-rolling" },
                upper(&r)
            ),
            &model,
            &uniqueness.vertex,
        )?;
        let _ = writeln!(
            report,
            "| {figure} | ({k},{k},{np}) {} | {:.4} | {} | `{name}` |",
            if rolling { "rolling" } else { "non-rolling" },
            upper(&r),
            uniqueness.unique
        );
        files.push(name);
    }

    // Past the paper: a random polydisperse packing settled by the DEM,
    // then its limit load by LP (the paper's future work (2)).
    let (sim, _) = settle_polydisperse(options)?;
    report.push_str("\n## DEM → LP: a settled polydisperse packing\n\n120 circles, radii uniform in [0.05, 0.09] m (fixed seed), settled under gravity with paper 000's law in an open box 1.6 m wide; its left wall then becomes a smooth plate pushed into the packing at unit speed. Contacts C_p = 1 between elements, 2C_p on the floor and the right wall, no weight (a c-material as in the paper).\n\n| model | status | P/C_p | primal − dual | optimum unique | file |\n|---|---|---|---|---|---|\n");
    for rolling in [true, false] {
        let settings = PackingLimitSettings {
            rolling,
            contact_law: RigidPlastic::cohesive(1.0)?,
            wall_law: RigidPlastic::cohesive(2.0)?,
            plate_law: RigidPlastic::cohesive(0.0)?,
            plate_wall: "left".into(),
            self_weight: false,
        };
        let model = model_from_packing(sim.scene(), sim.contacts(), &settings)?;
        let r = analyse(&model, &mut solver)?;
        let label = if rolling { "rolling" } else { "non-rolling" };
        let name = format!(
            "dem_packing_mechanism_{}.svg",
            if rolling { "rolling" } else { "nonrolling" }
        );
        let (shown, unique) = if r.status == LimitStatus::Collapse {
            max_gap = max_gap.max(gap(&r));
            let u = mechanism_uniqueness(&model, &mut solver, &r)?;
            let note = uniqueness_note(&u);
            plot_mechanism(
                &dir.join(&name),
                &format!("DEM packing, {label}: P = {:.3} C_p; {note}", upper(&r)),
                &model,
                &u.vertex,
            )?;
            files.push(name.clone());
            (format!("{:.4}", upper(&r)), u.unique.to_string())
        } else {
            ("—".to_string(), "—".to_string())
        };
        let _ = writeln!(
            report,
            "| {label} | {:?} | {shown} | {:.2e} | {unique} | `{name}` |",
            r.status,
            upper(&r) - lower(&r)
        );
        checks.push(Check::new(
            format!("dem_to_lp.{label}.p_over_cp"),
            format!("limit load of the DEM-settled polydisperse packing ({label}) by LP (no paper value)"),
            "C_p",
            r.load.unwrap_or(f64::NAN),
            &Rule::holds(
                format!(
                    "a mechanism is found (status {:?}) and primal and dual agree within 1e-6 (relative gap {})",
                    r.status,
                    number(gap(&r))
                ),
                r.status == LimitStatus::Collapse && gap(&r) <= 1e-6,
            ),
        ));
    }

    checks.push(Check::new(
        "primal_dual_gap.max",
        "largest |kinematic − static| / (1 + |P|) over every solved LP of the study",
        "-",
        max_gap,
        &Rule::AtMost(Reference::number(1e-6)),
    ));
    Summary {
        study: "yamada2000".into(),
        paper: PAPER.into(),
        checks,
        values: Vec::new(),
        files,
    }
    .write_with_report(&dir, &report)
}

/// One computed N_c(s) curve.
struct BearingCurve {
    k: usize,
    rolling: bool,
    points: Vec<(f64, f64)>,
}

/// N_c = P / (c_G l_U) for n' = 2 … k/2 − 1 at k = 20 and 40, rolling
/// (c_G = 0.5, eq. 21) and non-rolling (c_G = 0.9, §3.2).
fn bearing_capacity_curves(
    solver: &mut LinearProgramSolver,
    max_gap: &mut f64,
) -> Result<Vec<BearingCurve>> {
    let mut curves = Vec::new();
    for rolling in [true, false] {
        let c_g = if rolling { 0.5 } else { 0.9 };
        for k in [20usize, 40] {
            let mut points = Vec::new();
            // n' = 1 is left out: l_U = R there (eq. 22), far from the
            // 4 n' R sin α that eqs. (34) and (40) assume.
            for np in 2..k / 2 {
                let lattice = Lattice::u_model(k, k, np, rolling);
                let r = solve(&lattice, solver)?;
                if r.status == LimitStatus::Collapse {
                    *max_gap = max_gap.max(gap(&r));
                    points.push((
                        np as f64 / k as f64,
                        upper(&r) / (c_g * lattice.plate_length()),
                    ));
                }
            }
            curves.push(BearingCurve { k, rolling, points });
        }
    }
    Ok(curves)
}

/// What a mechanism plot says of the optimum's uniqueness.
fn uniqueness_note(u: &Uniqueness) -> &'static str {
    if u.unique {
        "unique optimum"
    } else if u.spread.is_finite() {
        "optimum NOT unique: one vertex mechanism shown"
    } else {
        "optimum NOT unique: free elements move at no cost"
    }
}

/// Draw the mechanism of a solved model: velocity arrows and slipping
/// contacts (|slip| above 1e-6 of the plate speed).
fn plot_mechanism(
    path: &std::path::Path,
    title: &str,
    model: &LimitModel,
    r: &LimitResult,
) -> Result<()> {
    let circles: Vec<(Point, f64)> = model
        .bodies()
        .iter()
        .map(|b| (b.centre, b.radius()))
        .collect();
    let (mut lo, mut hi) = (
        Point::new(f64::INFINITY, f64::INFINITY),
        Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
    );
    for (c, radius) in &circles {
        lo = Point::new(lo.x.min(c.x - radius), lo.y.min(c.y - radius));
        hi = Point::new(hi.x.max(c.x + radius), hi.y.max(c.y + radius));
    }
    let lines: Vec<(Point, Point)> = model
        .supports()
        .iter()
        .map(|s| {
            let d = perp(&s.normal);
            let ts = [lo, hi, Point::new(lo.x, hi.y), Point::new(hi.x, lo.y)]
                .map(|q| (q - s.point).dot(&d));
            let (t0, t1) = ts
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &t| {
                    (a.min(t), b.max(t))
                });
            (s.point + d * t0, s.point + d * t1)
        })
        .collect();
    let arrows: Vec<_> = model
        .bodies()
        .iter()
        .zip(&r.velocities)
        .map(|(b, (v, _))| (b.centre, *v))
        .collect();
    let marks: Vec<Point> = model
        .contacts()
        .iter()
        .zip(&r.slip)
        .filter(|(_, s)| s.abs() > 1e-6)
        .map(|(c, _)| c.point)
        .collect();
    let radius = model.bodies().first().map(|b| b.radius()).unwrap_or(1.0);
    mechanism_picture(path, title, &circles, &lines, &arrows, &marks, 1.6 * radius)
}

/// 120 circles with radii uniform in [0.05, 0.09] m, placed on a 0.2 m grid
/// with a random shift and settled in an open box 1.6 m wide with paper
/// 000's material.
fn settle_polydisperse(
    _options: &StudyOptions,
) -> Result<(
    DemSimulation<SpringDashpotCoulomb, ExplicitEuler>,
    RunOutcome,
)> {
    let mut scene = Scene::new(
        Frame::open_box(1.6, 3.6)?,
        Vec2::new(0.0, -katsuki1990::STANDARD_GRAVITY),
    )?;
    let mut random = SplitMix64(2000);
    for k in 0..120 {
        let (row, col) = (k / 8, k % 8);
        let radius = 0.05 + 0.04 * random.next_uniform();
        let slack = 0.1 - radius - 0.001;
        let shift = (2.0 * random.next_uniform() - 1.0) * slack;
        let centre = Point::new(0.1 + 0.2 * col as f64 + shift, 0.1 + 0.2 * row as f64);
        scene.add_circle(centre, radius, katsuki1990::DENSITY)?;
    }
    let settings = DemSettings {
        dt: katsuki1990::TIME_STEP,
        ..DemSettings::default()
    };
    let mut sim = DemSimulation::new(scene, katsuki1990::material_law()?, ExplicitEuler, settings)?;
    let outcome = sim.run_to_rest(&katsuki1990::rest_criterion(), |_, _| {})?;
    Ok((sim, outcome))
}
