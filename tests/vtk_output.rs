//! ParaView output ([`dismech::vtk`]): a small model of each driver is run,
//! its frames are written as a `.pvd` series, and VTK's own readers read
//! them back (`tests/vtk_read_back.py`, run by `python3` with the
//! `python3-vtk9` package, which `.ci/run` installs); the values VTK reads
//! are compared with the model's: particle `k`'s velocity with the
//! driver's, a contact's normal force with its force along its normal, a
//! hexahedron's volume as VTK computes it with the element's.
//!
//! The tests fail, not skip, where no `python3` can `import vtk`: set
//! `DISMECH_PYTHON` to an interpreter that can, or install `python3-vtk9`.

use std::path::{Path, PathBuf};
use std::process::Command;

use dismech::dda::{Block, BlockMaterial, DdaModel, DdaSettings, PlaneState, Prescribed};
use dismech::dem::DemSimulation;
use dismech::error::DismechError;
use dismech::explicit::{ContactTarget, DemSettings};
use dismech::grid::Raster;
use dismech::hpm::{
    displacement_at, strain_tensor, ElementDofs, HpmMaterial, HpmModel, HpmSettings, HpmSolver,
    NamedRaster, Seismic, SlopeGrids, ELEMENT_DOF,
};
use dismech::implicit::BodyGeometry;
use dismech::integrate::ExplicitEuler;
use dismech::law::{
    Damping, FrictionIntegration, NormalStiffness, PenaltyCoulomb, Regime, RigidPlastic,
    SpringDashpotCoulomb,
};
use dismech::limit::{analyse, LimitModel, LimitStatus, Partner};
use dismech::lp::LinearProgramSolver;
use dismech::math::{perp, Point, Pose2, Vec2};
use dismech::scene::{Frame, Particle, Scene};
use dismech::shape::{AnyShape2, Circle, Polygon};
use dismech::vtk::{
    dem_frame, hpm_frame, implicit_frame, kind, limit_frame, Cells, DataArray, DataKind, Dataset,
    PolyData, PvdSeries, UnstructuredGrid, VtkFrame, VtkProblem,
};
use serde_json::Value;

const SEGMENTS: usize = 24;

/// An interpreter that can `import vtk`: `DISMECH_PYTHON`, else `python3`,
/// else Debian's `/usr/bin/python3` (where `python3-vtk9` installs the
/// module, should another `python3` come first on the path).
fn python() -> String {
    if let Ok(p) = std::env::var("DISMECH_PYTHON") {
        return p;
    }
    for candidate in ["python3", "/usr/bin/python3"] {
        let imports = Command::new(candidate)
            .args(["-c", "import vtk"])
            .output()
            .is_ok_and(|o| o.status.success());
        if imports {
            return candidate.to_string();
        }
    }
    panic!(
        "no python3 that can `import vtk`: install python3-vtk9 (`apt-get install python3-vtk9`, \
         as .ci/run does), or name an interpreter with VTK's module in DISMECH_PYTHON"
    );
}

/// What VTK reads of `paths` (`.pvd` indices or single files), by path.
fn read_back(paths: &[PathBuf]) -> Value {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/vtk_read_back.py");
    let out = Command::new(python())
        .arg(script)
        .args(paths)
        .output()
        .expect("python3 runs");
    assert!(
        out.status.success(),
        "tests/vtk_read_back.py failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("the script prints JSON")
}

/// An empty folder for a test's files.
fn output_folder(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("vtk_output")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// A number as the script writes it (non-finite ones as strings).
fn num(v: &Value) -> f64 {
    match v {
        Value::Number(n) => n.as_f64().unwrap(),
        Value::String(s) => s.parse().unwrap(),
        _ => panic!("not a number: {v}"),
    }
}

/// One dataset as VTK read it.
struct Data<'a>(&'a Value);

impl Data<'_> {
    fn cells(&self) -> usize {
        self.0["cells"].as_array().unwrap().len()
    }
    fn cell(&self, k: usize) -> Vec<usize> {
        self.0["cells"][k]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_u64().unwrap() as usize)
            .collect()
    }
    fn cell_type(&self, k: usize) -> u64 {
        self.0["cell_types"][k].as_u64().unwrap()
    }
    fn cell_size(&self, k: usize) -> f64 {
        num(&self.0["cell_size"][k])
    }
    fn point(&self, i: usize) -> [f64; 3] {
        std::array::from_fn(|c| num(&self.0["points"][3 * i + c]))
    }
    /// The points of cell `k`, in the plane.
    fn cell_points(&self, k: usize) -> Vec<Point> {
        self.cell(k)
            .iter()
            .map(|&i| {
                let p = self.point(i);
                assert_eq!(p[2], 0.0);
                Point::new(p[0], p[1])
            })
            .collect()
    }
    fn tuple(&self, data: &str, name: &str, k: usize) -> Vec<f64> {
        let a = &self.0[data][name];
        assert!(!a.is_null(), "no {data} array `{name}`");
        let n = a["components"].as_u64().unwrap() as usize;
        (0..n).map(|c| num(&a["values"][n * k + c])).collect()
    }
    fn cell_value(&self, name: &str, k: usize) -> Vec<f64> {
        self.tuple("cell_data", name, k)
    }
    fn cell_scalar(&self, name: &str, k: usize) -> f64 {
        let t = self.cell_value(name, k);
        assert_eq!(t.len(), 1, "`{name}` is not a scalar");
        t[0]
    }
    fn cell_vec2(&self, name: &str, k: usize) -> Vec2 {
        let t = self.cell_value(name, k);
        assert_eq!(t.len(), 3, "`{name}` is not a vector");
        assert_eq!(t[2], 0.0, "`{name}` leaves the plane");
        Vec2::new(t[0], t[1])
    }
    fn point_vec2(&self, name: &str, i: usize) -> Vec2 {
        let t = self.tuple("point_data", name, i);
        assert_eq!(t.len(), 3);
        assert_eq!(t[2], 0.0);
        Vec2::new(t[0], t[1])
    }
}

/// The datasets of one piece's `.pvd` index, with their times.
fn frames_of<'a>(read: &'a Value, pvd: &Path) -> Vec<(f64, Data<'a>)> {
    read[pvd.to_str().unwrap()]["pvd"]
        .as_array()
        .unwrap_or_else(|| panic!("{} was not read", pvd.display()))
        .iter()
        .map(|e| (num(&e["timestep"]), Data(&e["data"])))
        .collect()
}

/// `a` and `b` agree to `rel` of `scale`.
fn close(a: f64, b: f64, scale: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * scale.abs().max(f64::MIN_POSITIVE)
}

#[track_caller]
fn assert_close(a: f64, b: f64, scale: f64, what: &str) {
    assert!(
        close(a, b, scale, 1e-12),
        "{what}: VTK read {a}, the model has {b}"
    );
}

#[track_caller]
fn assert_close2(a: Vec2, b: Vec2, scale: f64, what: &str) {
    assert_close(a.x, b.x, scale, what);
    assert_close(a.y, b.y, scale, what);
}

/// The shape kinds' codes of the files.
fn kind_of(shape: &AnyShape2) -> u8 {
    match shape {
        AnyShape2::Circle(_) => kind::CIRCLE,
        AnyShape2::Ellipse(_) => kind::ELLIPSE,
        AnyShape2::Polygon(_) => kind::POLYGON,
        AnyShape2::Segment(_) => kind::SEGMENT,
    }
}

fn regime_code(r: Regime) -> f64 {
    match r {
        Regime::Open => 0.0,
        Regime::Stick => 1.0,
        Regime::Slip => 2.0,
    }
}

/// The pieces' `.pvd` indices of a series, by name.
fn indices(series: &PvdSeries, names: &[&str]) -> Vec<PathBuf> {
    names.iter().map(|n| series.pvd_path(n)).collect()
}

// ---------------------------------------------------------------- DEM

/// Discs, an ellipse and a polygon falling onto a floor and onto each
/// other, and a fixed disc: three frames of the settling.
#[test]
fn dem_frames_read_back_with_the_particles_contacts_and_walls() {
    let mut scene = Scene::new(Frame::open_box(1.0, 1.0).unwrap(), Vec2::new(0.0, -9.81)).unwrap();
    let rho = 2600.0;
    scene.add_circle(Point::new(0.3, 0.051), 0.05, rho).unwrap();
    scene
        .add_circle(Point::new(0.35, 0.1385), 0.05, rho)
        .unwrap();
    scene.add_circle(Point::new(0.4, 0.051), 0.05, rho).unwrap();
    scene
        .add_ellipse(Point::new(0.6, 0.045), 0.08, 0.04, 0.1, rho)
        .unwrap();
    scene
        .add_polygon(
            &[(0.75, 0.002), (0.9, 0.002), (0.86, 0.08), (0.78, 0.1)]
                .map(|(x, y)| Point::new(x, y)),
            rho,
        )
        .unwrap();
    let fixed = scene.particles.len();
    scene.particles.push(Particle::fixed(
        Circle::new(0.04).unwrap().into(),
        Pose2::new(0.5, 0.6, 0.0),
    ));
    let law = SpringDashpotCoulomb::new(
        NormalStiffness::Constant(1e6),
        0.25,
        0.5,
        Damping::PerMass {
            normal: 20.0,
            shear: 10.0,
        },
    )
    .unwrap();
    let mut dem = DemSimulation::new(scene, law, ExplicitEuler, DemSettings::default()).unwrap();
    let dir = output_folder("dem");
    let mut series = PvdSeries::new(&dir).unwrap();
    // Each frame's time and velocities, to find them again in the files.
    let mut written = Vec::new();
    for _ in 0..3 {
        for _ in 0..1500 {
            dem.step().unwrap();
        }
        series
            .write_frame(dem.time(), &dem_frame(&dem, SEGMENTS).unwrap())
            .unwrap();
        let velocities: Vec<Vec2> = dem.scene().particles.iter().map(|p| p.velocity).collect();
        written.push((dem.time(), velocities));
    }
    let read = read_back(&indices(&series, &["particles", "contacts", "walls"]));

    let particles = frames_of(&read, &series.pvd_path("particles"));
    assert_eq!(particles.len(), 3);
    for ((time, data), (t, velocities)) in particles.iter().zip(&written) {
        assert_eq!(time, t);
        for (k, v) in velocities.iter().enumerate() {
            assert_eq!(data.cell_vec2("velocity", k), *v, "particle {k} at t = {t}");
        }
    }
    let last = &particles[2].1;
    let scene = dem.scene();
    assert_eq!(last.cells(), scene.particles.len());
    for (k, p) in scene.particles.iter().enumerate() {
        let outline = last.cell_points(k);
        assert_eq!(last.cell_type(k), 7, "particle {k} is a VTK_POLYGON");
        let c = p.pose.position;
        match &p.shape {
            AnyShape2::Circle(circle) => {
                assert_eq!(outline.len(), SEGMENTS);
                for q in &outline {
                    assert_close((q - c).norm(), circle.radius(), 1.0, "a circle's outline");
                }
                // VTK's area of the inscribed polygon.
                let n = SEGMENTS as f64;
                let area = 0.5 * n * circle.radius().powi(2) * (std::f64::consts::TAU / n).sin();
                assert_close(last.cell_size(k), area, area, "a circle's outline area");
            }
            AnyShape2::Ellipse(e) => {
                assert_eq!(outline.len(), SEGMENTS);
                for q in &outline {
                    assert!(e.implicit(&p.pose, q).abs() < 1e-12, "an ellipse's outline");
                }
            }
            AnyShape2::Polygon(polygon) => {
                let vertices: Vec<Point> = polygon.world_vertices(&p.pose).collect();
                assert_eq!(outline, vertices);
                let area = dismech::shape::Shape::measure(polygon);
                assert_close(last.cell_size(k), area, area, "a polygon's area");
            }
            AnyShape2::Segment(_) => unreachable!(),
        }
        let (force, moment) = dem.force_on(k).unwrap();
        assert_eq!(last.cell_scalar("id", k), k as f64);
        assert_eq!(last.cell_scalar("kind", k), f64::from(kind_of(&p.shape)));
        assert_eq!(
            last.cell_scalar("prescribed", k),
            f64::from(u8::from(k == fixed))
        );
        assert_eq!(
            last.cell_scalar("radius", k),
            p.shape.as_shape().bounding_radius()
        );
        assert_eq!(last.cell_vec2("centre", k), c.coords);
        assert_eq!(last.cell_scalar("rotation", k), p.pose.angle);
        assert_eq!(last.cell_vec2("velocity", k), p.velocity);
        assert_eq!(last.cell_scalar("angular_velocity", k), p.angular_velocity);
        assert_eq!(last.cell_scalar("mass", k), p.mass);
        assert_eq!(last.cell_vec2("force", k), force);
        assert_eq!(last.cell_scalar("moment", k), moment);
    }
    // The fixed disc's infinite mass survives the file.
    assert_eq!(last.cell_scalar("mass", fixed), f64::INFINITY);

    let contacts = frames_of(&read, &series.pvd_path("contacts"));
    assert_eq!(contacts.len(), 3);
    let data = &contacts[2].1;
    let records = dem.contacts();
    assert_eq!(data.cells(), records.len());
    let between_particles = records
        .iter()
        .filter(|c| matches!(c.target, ContactTarget::Particle(_)))
        .count();
    assert!(between_particles >= 2, "{records:?}");
    assert!(records.len() > between_particles + 3, "{records:?}");
    for (k, c) in records.iter().enumerate() {
        let a = scene.particles[c.particle].pose.position;
        let line = data.cell_points(k);
        // VTK reads a line cell of two points as a VTK_LINE, of more as a
        // VTK_POLY_LINE.
        let line_type = if line.len() == 2 { 3 } else { 4 };
        assert_eq!(data.cell_type(k), line_type, "contact {k}'s type");
        let (target, is_wall, expected) = match c.target {
            ContactTarget::Particle(b) => {
                (b, 0.0, vec![a, c.point, scene.particles[b].pose.position])
            }
            ContactTarget::Wall(w) => (w, 1.0, vec![a, c.point]),
        };
        assert_eq!(line, expected, "contact {k}");
        let f = c.force_on_target;
        let scale = f.norm();
        assert_eq!(data.cell_scalar("particle", k), c.particle as f64);
        assert_eq!(data.cell_scalar("target", k), target as f64);
        assert_eq!(data.cell_scalar("target_is_wall", k), is_wall);
        assert_eq!(data.cell_scalar("regime", k), regime_code(c.regime));
        assert_eq!(data.cell_scalar("overlap", k), c.overlap);
        assert_eq!(data.cell_vec2("point", k), c.point.coords);
        assert_eq!(data.cell_vec2("normal", k), c.normal);
        assert_eq!(data.cell_vec2("force", k), f);
        assert!(f.dot(&c.normal) > 0.0, "a contact in compression");
        assert_close(
            data.cell_scalar("normal_force", k),
            f.dot(&c.normal),
            scale,
            "normal force",
        );
        assert_close(
            data.cell_scalar("shear_force", k),
            f.dot(&perp(&c.normal)),
            scale,
            "shear force",
        );
    }

    let walls = frames_of(&read, &series.pvd_path("walls"));
    let data = &walls[2].1;
    let frame = &scene.frame;
    assert_eq!(data.cells(), frame.walls().len());
    for (w, segment) in frame.walls().iter().enumerate() {
        assert_eq!(data.cell_points(w), vec![segment.start, segment.end]);
        assert_eq!(data.cell_vec2("load", w), dem.wall_load(w));
    }
    let floor = frame.index_of("bottom").unwrap();
    assert!(data.cell_vec2("load", floor).y < 0.0);
}

// ---------------------------------------------------------------- DDA

/// Two blocks and a disc with DDA's six unknowns on a fixed base, after
/// a few steps under gravity: deformed outlines, vertex velocities,
/// stresses and contacts.
#[test]
fn dda_frames_read_back_with_the_blocks_stresses_and_contacts() {
    let rock = BlockMaterial {
        density: 2200.0,
        youngs_modulus: 1e9,
        poisson_ratio: 0.25,
        plane: PlaneState::Stress,
    };
    let rect = |x0: f64, y0: f64, x1: f64, y1: f64| {
        [(x0, y0), (x1, y0), (x1, y1), (x0, y1)].map(|(x, y)| Point::new(x, y))
    };
    let mut base = Block::new(&rect(-2.0, -0.5, 2.0, 0.0), rock, 0).unwrap();
    base.prescribed = Some(Prescribed::fixed());
    let left = Block::new(&rect(-1.2, 0.0, -0.6, 0.5), rock, 1).unwrap();
    let mut right = Block::new(&rect(0.2, 0.0, 1.0, 0.3), rock, 2).unwrap();
    right.velocity[0] = 0.2;
    let disc = Block::circle(Point::new(-0.2, 0.15), 0.15, rock, 3).unwrap();
    let law = PenaltyCoulomb::new(1e9, 0.3, FrictionIntegration::ReturnMapping).unwrap();
    let settings = DdaSettings {
        gravity: Vec2::new(0.0, -9.8),
        ..DdaSettings::default()
    };
    let mut model = DdaModel::new(vec![base, left, right, disc], law, settings).unwrap();
    let dir = output_folder("dda");
    let mut series = PvdSeries::new(&dir).unwrap();
    for _ in 0..2 {
        for _ in 0..5 {
            // Every step converges (a failed one is an error).
            model.advance(1e-3).unwrap();
        }
        series
            .write_frame(model.time(), &implicit_frame(&model, SEGMENTS).unwrap())
            .unwrap();
    }
    let read = read_back(&indices(&series, &["bodies", "contacts"]));
    let bodies = frames_of(&read, &series.pvd_path("bodies"));
    assert_eq!(bodies.len(), 2);
    assert_eq!(bodies[1].0, model.time());
    let data = &bodies[1].1;
    let blocks = model.blocks();
    assert_eq!(data.cells(), blocks.len());
    let mut stressed = 0;
    for (k, b) in blocks.iter().enumerate() {
        let outline = data.cell_points(k);
        let c = b.centroid();
        if k < 3 {
            let vertices: Vec<Point> = (0..b.vertex_count()).map(|j| b.vertex(j)).collect();
            assert_eq!(outline, vertices, "block {k}'s deformed outline");
            assert_close(data.cell_size(k), b.area(), b.area(), "a block's area");
            assert_eq!(data.cell_scalar("kind", k), f64::from(kind::POLYGON));
        } else {
            assert_eq!(outline.len(), SEGMENTS);
            // The disc has strained into an ellipse: its outline is on
            // the ellipse of its axes matrix A, |A⁻¹ (x − c)| = 1.
            assert_eq!(data.cell_scalar("kind", k), f64::from(kind::ELLIPSE));
            let BodyGeometry::Ellipse(e) = b.geometry() else {
                unreachable!()
            };
            let inverse = e.axes().try_inverse().unwrap();
            for q in &outline {
                assert_close((inverse * (q - c)).norm(), 1.0, 1.0, "the disc's outline");
            }
        }
        // DDA's velocity field: (u̇, v̇) + [[ε̇x, γ̇/2 − ṙ], [γ̇/2 + ṙ, ε̇y]] (x − c).
        let v = &b.velocity;
        let field = |q: &Point| {
            let r = q - c;
            Vec2::new(
                v[0] + v[3] * r.x + (0.5 * v[5] - v[2]) * r.y,
                v[1] + (0.5 * v[5] + v[2]) * r.x + v[4] * r.y,
            )
        };
        let scale = v.norm() * (1.0 + b.area().sqrt());
        for (j, &i) in data.cell(k).iter().enumerate() {
            assert_close2(
                data.point_vec2("velocity", i),
                field(&outline[j]),
                scale,
                "an outline point's velocity",
            );
        }
        assert_eq!(data.cell_scalar("id", k), k as f64);
        assert_eq!(data.cell_scalar("fixed", k), f64::from(u8::from(k == 0)));
        assert_eq!(data.cell_vec2("velocity", k), Vec2::new(v[0], v[1]));
        assert_close(
            data.cell_scalar("angular_velocity", k),
            v[2],
            v.norm(),
            "spin",
        );
        assert_eq!(data.cell_vec2("centroid", k), c.coords);
        assert_eq!(
            data.cell_vec2("displacement", k),
            Vec2::new(b.displacement[0], b.displacement[1])
        );
        assert_eq!(data.cell_value("dof_velocity", k), v.as_slice());
        assert_eq!(
            data.cell_value("dof_displacement", k),
            b.displacement.as_slice()
        );
        let s = b.stress;
        assert_eq!(
            data.cell_value("stress", k),
            vec![s[0], s[2], 0.0, s[2], s[1], 0.0, 0.0, 0.0, 0.0]
        );
        if k > 0 && s.norm() > 0.0 {
            stressed += 1;
        }
    }
    assert_eq!(stressed, 3, "the loaded blocks carry a stress");
    assert!(blocks[2].velocity[0] > 0.0);

    let contacts = frames_of(&read, &series.pvd_path("contacts"));
    let data = &contacts[1].1;
    let reports = model.contacts();
    assert_eq!(data.cells(), reports.len());
    assert!(reports.len() >= 5, "{reports:?}");
    for (k, c) in reports.iter().enumerate() {
        let (a, b) = c.bodies;
        assert_eq!(
            data.cell_points(k),
            vec![blocks[a].centroid(), c.point, blocks[b].centroid()]
        );
        assert_eq!(data.cell_scalar("body_a", k), a as f64);
        assert_eq!(data.cell_scalar("body_b", k), b as f64);
        assert_eq!(data.cell_scalar("gap", k), c.gap);
        assert_eq!(data.cell_scalar("shear", k), c.shear);
        assert_eq!(data.cell_value("law_force", k), vec![c.force.0, c.force.1]);
        // The file's convention: normal from A to B, force on B.
        assert_eq!(data.cell_vec2("normal", k), -c.normal);
        assert_eq!(data.cell_vec2("force", k), -c.force_on_a);
        let scale = c.force_on_a.norm();
        assert_close(
            data.cell_scalar("normal_force", k),
            c.force_on_a.dot(&c.normal),
            scale,
            "normal force",
        );
        assert_close(
            data.cell_scalar("shear_force", k),
            c.force_on_a.dot(&perp(&c.normal)),
            scale,
            "shear force",
        );
    }
    let pressed: f64 = (0..reports.len())
        .map(|k| data.cell_scalar("normal_force", k))
        .sum();
    assert!(pressed > 0.0);
}

// ---------------------------------------------------------------- limit analysis

/// Two blocks stacked on a floor, pushed sideways at the top by a live
/// load: the mechanism's velocities at the outlines and the dual forces.
#[test]
fn limit_frame_reads_back_with_the_mechanism_and_the_dual_forces() {
    let (w, h, weight) = (0.4, 0.4, 1e3);
    let mut model = LimitModel::new(1e-9).unwrap();
    let shape: AnyShape2 = Polygon::rectangle(w, h).unwrap().into();
    let lower = model
        .add_shape(shape.clone(), Pose2::new(0.0, h / 2.0, 0.0), true)
        .unwrap();
    let upper = model
        .add_shape(shape, Pose2::new(0.0, 1.5 * h, 0.0), true)
        .unwrap();
    for b in [lower, upper] {
        model.set_load(b, Vec2::new(0.0, -weight)).unwrap();
    }
    let floor = model
        .add_support("floor", Point::origin(), Vec2::y(), Vec2::zeros())
        .unwrap();
    let law = RigidPlastic::from_friction_angle_deg(0.0, 30.0, true).unwrap();
    for x in [-w / 2.0, w / 2.0] {
        model
            .add_contact_at(
                lower,
                Partner::Support(floor),
                law,
                Point::new(x, 0.0),
                -Vec2::y(),
            )
            .unwrap();
        model
            .add_contact_at(
                upper,
                Partner::Body(lower),
                law,
                Point::new(x, h),
                -Vec2::y(),
            )
            .unwrap();
    }
    model
        .set_live_load(upper, Vec2::x(), Point::new(-w / 2.0, 2.0 * h))
        .unwrap();
    let result = analyse(&model, &mut LinearProgramSolver::default()).unwrap();
    assert_eq!(result.status, LimitStatus::Collapse);

    let dir = output_folder("limit");
    let mut series = PvdSeries::new(&dir).unwrap();
    series
        .write_frame(0.0, &limit_frame(&model, &result, SEGMENTS).unwrap())
        .unwrap();
    let read = read_back(&indices(&series, &["bodies", "contacts", "supports"]));

    let data = &frames_of(&read, &series.pvd_path("bodies"))[0].1;
    assert_eq!(data.cells(), 2);
    let mut moving = 0;
    for (k, b) in model.bodies().iter().enumerate() {
        let (v, omega) = result.velocities[k];
        let AnyShape2::Polygon(polygon) = &b.shape else {
            unreachable!()
        };
        let vertices: Vec<Point> = polygon.world_vertices(&b.pose()).collect();
        assert_eq!(data.cell_points(k), vertices);
        let scale = v.norm() + omega.abs() * b.radius();
        for (j, &i) in data.cell(k).iter().enumerate() {
            let expected = v + omega * perp(&(vertices[j] - b.centre));
            assert_close2(
                data.point_vec2("velocity", i),
                expected,
                scale,
                "mechanism velocity",
            );
        }
        assert_eq!(data.cell_vec2("velocity", k), v);
        assert_eq!(data.cell_scalar("angular_velocity", k), omega);
        assert_eq!(data.cell_vec2("load", k), b.load);
        assert_eq!(data.cell_scalar("rotates", k), 1.0);
        assert_close(data.cell_size(k), w * h, w * h, "a block's area");
        if scale > 0.0 {
            moving += 1;
        }
    }
    assert!(moving >= 1, "{:?}", result.velocities);

    let data = &frames_of(&read, &series.pvd_path("contacts"))[0].1;
    let contacts = model.contacts();
    assert_eq!(data.cells(), contacts.len());
    let scale = weight * 2.0;
    for (k, c) in contacts.iter().enumerate() {
        let a = model.bodies()[c.body].centre;
        let (partner, expected) = match c.partner {
            Partner::Body(j) => (j, vec![a, c.point, model.bodies()[j].centre]),
            Partner::Support(j) => (j, vec![a, c.point]),
        };
        assert_eq!(data.cell_points(k), expected);
        assert_eq!(data.cell_scalar("body", k), c.body as f64);
        assert_eq!(data.cell_scalar("partner", k), partner as f64);
        assert_eq!(
            data.cell_scalar("partner_is_support", k),
            f64::from(u8::from(matches!(c.partner, Partner::Support(_))))
        );
        assert_eq!(data.cell_vec2("normal", k), c.normal);
        assert_close(
            data.cell_scalar("normal_force", k),
            result.normal_force[k],
            scale,
            "N",
        );
        assert_close(
            data.cell_scalar("shear_force", k),
            -result.shear_force[k],
            scale,
            "T",
        );
        assert_eq!(data.cell_scalar("slip", k), result.slip[k]);
        assert_eq!(data.cell_scalar("opening", k), result.opening[k]);
        assert_eq!(data.cell_scalar("friction", k), 30f64.to_radians().tan());
    }
    // The dual forces carry both weights onto the floor.
    let on_floor: f64 = contacts
        .iter()
        .enumerate()
        .filter(|(_, c)| matches!(c.partner, Partner::Support(_)))
        .map(|(k, _)| data.cell_scalar("normal_force", k))
        .sum();
    assert!(close(on_floor, 2.0 * weight, weight, 1e-6), "{on_floor}");

    let data = &frames_of(&read, &series.pvd_path("supports"))[0].1;
    assert_eq!(data.cells(), 1);
    for q in data.cell_points(0) {
        assert_eq!(q.y, 0.0, "the floor's line");
    }
    assert_eq!(data.cell_vec2("normal", 0), Vec2::y());

    // A result of another model has no frame of this one.
    let mut other = model.clone();
    other
        .add_shape(
            Polygon::rectangle(w, h).unwrap().into(),
            Pose2::new(2.0, h / 2.0, 0.0),
            true,
        )
        .unwrap();
    assert!(matches!(
        limit_frame(&other, &result, SEGMENTS),
        Err(DismechError::VtkData { .. })
    ));
    let bodies = other.bodies().len();
    assert!(matches!(
        limit_frame(&other, &result, SEGMENTS),
        Err(DismechError::VtkData {
            reason: VtkProblem::NoMechanism { velocities, bodies: b, .. }
        }) if velocities + 1 == bodies && b == bodies
    ));
}

// ---------------------------------------------------------------- HPM

/// A slab on a planar slip surface, 4 × 4 columns of three layers, elastic
/// HPM: hexahedra, corner displacements, strains and local Fs.
#[test]
fn hpm_frame_reads_back_with_hexahedra_displacements_and_strains() {
    let ground = Raster::from_fn(4, 4, 0.0, 0.0, 10.0, |_, y| Some(0.36 * y)).unwrap();
    let slip = Raster::from_fn(4, 4, 0.0, 0.0, 10.0, |_, y| Some(0.36 * y - 6.0)).unwrap();
    let grids = SlopeGrids::new(
        NamedRaster::new("ground", ground),
        NamedRaster::new("slip", slip),
        None,
    )
    .unwrap();
    let model = HpmModel::new(&grids, &HpmMaterial::paper(), &HpmSettings::default()).unwrap();
    let mut solver = HpmSolver::new(&model).unwrap();
    let result = solver.elastic(&model, &Seismic::none()).unwrap();

    let dir = output_folder("hpm");
    let mut series = PvdSeries::new(&dir).unwrap();
    let frame: VtkFrame = hpm_frame(&model, &result).unwrap();
    series.write_frame(0.0, &frame).unwrap();
    let read = read_back(&indices(&series, &["elements", "slip"]));

    let data = &frames_of(&read, &series.pvd_path("elements"))[0].1;
    assert_eq!(data.cells(), model.elements.len());
    assert_eq!(model.elements.len(), 16 * 3);
    let local_fs = result.local_safety_factors(&model);
    let largest = result
        .displacements
        .iter()
        .fold(0.0f64, |m, u| m.max(u.abs()));
    assert!(largest > 0.0);
    for (k, e) in model.elements.iter().enumerate() {
        assert_eq!(data.cell_type(k), 12, "element {k} is a VTK_HEXAHEDRON");
        // VTK's own volume of the hexahedron: the corners in its order.
        assert_close(data.cell_size(k), e.volume, e.volume, "an element's volume");
        let dofs = ElementDofs::from_column_slice(
            &result.displacements[ELEMENT_DOF * k..ELEMENT_DOF * (k + 1)],
        );
        let (x0, y0) = e.shape.origin();
        let s = e.shape.size();
        let plan = [(x0, y0), (x0 + s, y0), (x0 + s, y0 + s), (x0, y0 + s)];
        let cell = data.cell(k);
        assert_eq!(cell.len(), 8);
        for (j, &i) in cell.iter().enumerate() {
            let (x, y) = plan[j % 4];
            let z = if j < 4 {
                e.shape.bottom()[j]
            } else {
                e.shape.top()[j - 4]
            };
            assert_eq!(data.point(i), [x, y, z]);
            let u = displacement_at(&e.centre, &dofs, &nalgebra::Point3::new(x, y, z));
            let read = data.tuple("point_data", "displacement", i);
            for c in 0..3 {
                assert_close(read[c], u[c], largest, "a corner's displacement");
            }
        }
        assert_eq!(
            data.cell_value("displacement", k),
            dofs.as_slice()[0..3].to_vec()
        );
        assert_eq!(
            data.cell_value("rotation", k),
            dofs.as_slice()[3..6].to_vec()
        );
        let strain = strain_tensor(&dofs);
        let expected: Vec<f64> = (0..9).map(|i| strain[(i / 3, i % 3)]).collect();
        assert_eq!(data.cell_value("strain", k), expected);
        assert_eq!(
            data.cell_scalar("local_safety_factor", k),
            local_fs[e.column]
        );
        assert_eq!(data.cell_scalar("column", k), e.column as f64);
        assert_eq!(data.cell_scalar("layer", k), e.layer as f64);
        let (row, col) = model.columns[e.column].cell;
        assert_eq!(data.cell_value("cell", k), vec![row as f64, col as f64]);
        assert_eq!(data.cell_scalar("volume", k), e.volume);
    }

    let data = &frames_of(&read, &series.pvd_path("slip"))[0].1;
    assert_eq!(data.cells(), model.slip.len());
    for (k, (spring, t)) in model.slip.iter().zip(&result.tractions).enumerate() {
        assert_eq!(data.cell_type(k), 1, "a slip spring is a VTK_VERTEX");
        let p = spring.point.point.position;
        assert_eq!(data.point(data.cell(k)[0]), [p.x, p.y, p.z]);
        assert_eq!(data.cell_scalar("normal_traction", k), t.normal);
        assert!(t.normal > 0.0, "the slab presses on its slip surface");
        let shear = spring.point.s * t.shear[0] + spring.point.t * t.shear[1];
        let read = data.cell_value("shear_traction", k);
        for c in 0..3 {
            assert_close(read[c], shear[c], t.shear_magnitude(), "shear traction");
        }
        assert_eq!(data.cell_scalar("regime", k), regime_code(t.regime));
        assert_eq!(data.cell_scalar("element", k), spring.element as f64);
    }

    // A result of another model has no frame of this one.
    let mut short = result.clone();
    short.displacements.pop();
    assert!(matches!(
        hpm_frame(&model, &short),
        Err(DismechError::VtkData { .. })
    ));
    assert!(matches!(
        hpm_frame(&model, &short),
        Err(DismechError::VtkData {
            reason: VtkProblem::NotThisHpmResult { displacements, elements, .. }
        }) if displacements + 1 == 12 * elements
    ));
}

/// The cause of a `VtkData` error, or a panic.
fn vtk_problem<T: std::fmt::Debug>(result: dismech::error::Result<T>) -> VtkProblem {
    match result {
        Err(DismechError::VtkData { reason }) => reason,
        other => panic!("{other:?}"),
    }
}

#[test]
fn datasets_and_frames_that_do_not_fit_carry_a_typed_cause() {
    let mut verts = Cells::new();
    verts.push([0]);
    let points = PolyData {
        points: vec![[0.0; 3], [1.0, 0.0, 0.0]],
        verts,
        ..PolyData::default()
    };
    let with_points = |arrays: Vec<DataArray>| {
        Dataset::PolyData(PolyData {
            point_data: arrays,
            ..points.clone()
        })
    };
    let name = "h".to_string();
    assert_eq!(
        vtk_problem(with_points(vec![DataArray::scalars("h", vec![1.0])]).to_xml()),
        VtkProblem::ValueCount {
            kind: DataKind::Point,
            name: name.clone(),
            values: 1,
            components: 1,
            tuples: 2
        }
    );
    let twice = vec![
        DataArray::scalars("h", vec![1.0, 2.0]),
        DataArray::scalars("h", vec![1.0, 2.0]),
    ];
    assert_eq!(
        vtk_problem(with_points(twice).to_xml()),
        VtkProblem::NamedTwice {
            kind: DataKind::Point,
            name
        }
    );
    let mut far = points.clone();
    far.lines.push([0, 5]);
    assert_eq!(
        vtk_problem(Dataset::PolyData(far).to_xml()),
        VtkProblem::NoSuchPoint {
            point: 5,
            points: 2
        }
    );
    let mut grid = UnstructuredGrid {
        points: vec![[0.0; 3]],
        ..UnstructuredGrid::default()
    };
    grid.cells.push([0]);
    assert_eq!(
        vtk_problem(Dataset::UnstructuredGrid(grid).to_xml()),
        VtkProblem::CellTypeCount { types: 0, cells: 1 }
    );
    let mut frame = VtkFrame::new();
    let name = "a b".to_string();
    assert_eq!(
        vtk_problem(frame.push("a b", Dataset::PolyData(points.clone()))),
        VtkProblem::PieceName { name }
    );
    frame.push("a", Dataset::PolyData(points.clone())).unwrap();
    let name = "a".to_string();
    let problem = vtk_problem(frame.push("a", Dataset::PolyData(points)));
    assert_eq!(problem, VtkProblem::DuplicatePiece { name });
    assert_eq!(problem.to_string(), "the frame already has a piece `a`");
}
