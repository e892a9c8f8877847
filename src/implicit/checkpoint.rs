//! Checkpoints of the implicit driver: the state of a run saved, and
//! restored into the model built again as at the start (see
//! [`crate::checkpoint`] for what is saved, the format and its version).

use std::any::type_name;
use std::borrow::Cow;
use std::path::Path;

use nalgebra::{SVector, Vector3};
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use super::super::body::{Body, BodyGeometry, BodyMaterial};
use super::super::detect::{ContactKey, Previous};
use super::super::report::ContactReport;
use super::{FixedPoint, ImplicitDynamics};
use crate::checkpoint::{self as format, Driver, Piece, IN_MEMORY};
use crate::error::Result;
use crate::integrate::ImplicitIntegrator;
use crate::law::TangentLaw;
use crate::math::Vec2;

/// What a body is, apart from its motion: compared with the model's on
/// restore.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct BodyDefinition {
    /// `polygon`, `ellipse` or `wall`.
    kind: Cow<'static, str>,
    /// The polygon's vertices (0 for the others).
    vertices: usize,
    material: BodyMaterial,
    group: usize,
    /// The mask of the prescribed unknowns, if any.
    prescribed: Option<Vec<bool>>,
    edge_tractions: Vec<(usize, Vec2)>,
}

/// The kind of a geometry, as [`BodyDefinition::kind`] names it.
fn kind_of(geometry: &BodyGeometry) -> &'static str {
    match geometry {
        BodyGeometry::Polygon(_) => "polygon",
        BodyGeometry::Ellipse(_) => "ellipse",
        BodyGeometry::Wall(_) => "wall",
    }
}

impl BodyDefinition {
    fn of<const N: usize>(body: &Body<N>) -> Self {
        Self {
            kind: Cow::Borrowed(kind_of(body.geometry())),
            vertices: body.vertex_count(),
            material: *body.material(),
            group: body.group,
            prescribed: body.prescribed.as_ref().map(|p| p.mask.to_vec()),
            edge_tractions: body.edge_tractions.clone(),
        }
    }

    /// The first field in which `self` (the checkpoint's) and `model`
    /// differ, with both values.
    fn difference(&self, model: &Self) -> Option<(&'static str, String, String)> {
        let differs = |name, a: &dyn std::fmt::Debug, b: &dyn std::fmt::Debug| {
            Some((name, format!("{a:?}"), format!("{b:?}")))
        };
        if self.kind != model.kind {
            differs("kind", &self.kind, &model.kind)
        } else if self.vertices != model.vertices {
            differs("vertex count", &self.vertices, &model.vertices)
        } else if self.material != model.material {
            differs("material", &self.material, &model.material)
        } else if self.group != model.group {
            differs("group", &self.group, &model.group)
        } else if self.prescribed != model.prescribed {
            differs("prescribed unknowns", &self.prescribed, &model.prescribed)
        } else if self.edge_tractions != model.edge_tractions {
            differs(
                "edge tractions",
                &self.edge_tractions,
                &model.edge_tractions,
            )
        } else {
            None
        }
    }
}

/// The model a checkpoint was written from, read first and compared with
/// the one it is restored into.
#[derive(Serialize, Deserialize)]
struct ModelRecord<'a> {
    /// The driver's type, `ImplicitDynamics<N, K, L, I, S>` spelled out.
    model_type: Cow<'a, str>,
    laws: Piece<'a>,
    integrator: Piece<'a>,
    settings: Vec<u8>,
    bodies: Vec<BodyDefinition>,
    /// Each fixed point's body, anchor and stiffness.
    fixed_points: Vec<(usize, [u64; 3])>,
}

/// A body's state: what a step changes.
#[derive(Serialize, Deserialize)]
struct BodyState<const N: usize> {
    geometry: BodyGeometry,
    stress: Vector3<f64>,
    velocity: SVector<f64, N>,
    acceleration: SVector<f64, N>,
    displacement: SVector<f64, N>,
}

/// What the implicit driver's checkpoint holds (see [`crate::checkpoint`]).
/// Maps are kept as lists sorted by key, so that a run's checkpoint does
/// not depend on the order of its hash maps.
#[derive(Serialize, Deserialize)]
#[serde(bound(
    serialize = "S: Serialize + Clone",
    deserialize = "S: Deserialize<'de> + Clone"
))]
struct ImplicitState<'a, const N: usize, S: Clone> {
    model: ModelRecord<'a>,
    bodies: Vec<BodyState<N>>,
    /// Each fixed point's material point now.
    fixed_points: Vec<crate::math::Point>,
    time: f64,
    requested_dt: Option<f64>,
    current_dt: f64,
    search: f64,
    solves: usize,
    history: Vec<(ContactKey, S)>,
    edges: Vec<((usize, usize, usize), usize)>,
    angles: Vec<(ContactKey, f64)>,
    contacts: Cow<'a, [ContactReport<S>]>,
}

/// A fixed point's parts that do not move, as bits.
fn fixed_definition(point: &FixedPoint) -> (usize, [u64; 3]) {
    (
        point.body,
        [
            point.anchor.x.to_bits(),
            point.anchor.y.to_bits(),
            point.stiffness.to_bits(),
        ],
    )
}

/// Checkpoints need the law's state to be serde's, and the laws' and the
/// integrator's parameters to serialize (they are compared on restore):
/// a law without serde runs everything else.
impl<const N: usize, K, L, I, S> ImplicitDynamics<N, K, L, I, S>
where
    L: TangentLaw<2> + Serialize,
    L::State: Serialize + DeserializeOwned,
    I: ImplicitIntegrator + Serialize,
{
    fn model_record(&self) -> Result<ModelRecord<'static>> {
        Ok(ModelRecord {
            model_type: Cow::Borrowed(type_name::<Self>()),
            laws: Piece::of(&self.laws)?,
            integrator: Piece::of(&self.integrator)?,
            settings: format::fingerprint(&self.settings)?,
            bodies: self.bodies.iter().map(BodyDefinition::of).collect(),
            fixed_points: self.fixed_points.iter().map(fixed_definition).collect(),
        })
    }

    /// The run's checkpoint: each body's geometry and motion, the contact
    /// history and everything else the next step reads (see
    /// [`crate::checkpoint`]), with what is needed to check the model it
    /// is restored into. [`Self::restore`] resumes it to the same bits
    /// when it is taken between calls of [`Self::advance`] (or at an
    /// observer's [`crate::observe::Event::Finished`]); taken inside a call
    /// (at an [`crate::observe::Event::SubStep`]) it holds that sub-step's
    /// state but not the rest of the call's interval and its step control.
    ///
    /// # Errors
    /// [`DismechError::Checkpoint`](crate::error::DismechError::Checkpoint)
    /// when the law's state or parameters, or the integrator's, fail to
    /// serialize (their `Serialize`).
    pub fn checkpoint(&self) -> Result<Vec<u8>> {
        let mut history: Vec<(ContactKey, L::State)> = (self.history.iter())
            .map(|(key, state)| (*key, state.clone()))
            .collect();
        history.sort_by_key(|entry| entry.0);
        let mut edges: Vec<_> = self.previous.edges.iter().map(|(k, e)| (*k, *e)).collect();
        edges.sort_unstable();
        let mut angles: Vec<_> = self.previous.angles.iter().map(|(k, a)| (*k, *a)).collect();
        angles.sort_by_key(|entry| entry.0);
        let state = ImplicitState {
            model: self.model_record()?,
            bodies: (self.bodies.iter())
                .map(|b| BodyState {
                    geometry: b.geometry().clone(),
                    stress: b.stress,
                    velocity: b.velocity,
                    acceleration: b.acceleration,
                    displacement: b.displacement,
                })
                .collect(),
            fixed_points: self.fixed_points.iter().map(|f| f.point).collect(),
            time: self.time,
            requested_dt: self.requested_dt,
            current_dt: self.current_dt,
            search: self.search,
            solves: self.solves,
            history,
            edges,
            angles,
            contacts: Cow::Borrowed(&self.contacts),
        };
        format::encode(Driver::Implicit, &state)
    }

    /// Write [`Self::checkpoint`] to `path`, whole or not at all
    /// ([`crate::io::write_atomically`]; the folder is created if needed).
    ///
    /// # Errors
    /// The errors of [`Self::checkpoint`];
    /// [`DismechError::Output`](crate::error::DismechError::Output) naming
    /// the path when it cannot be written.
    pub fn save_checkpoint(&self, path: &Path) -> Result<()> {
        crate::io::write_atomically(path, &self.checkpoint()?)
    }

    /// Put the run of `checkpoint` (the bytes of [`Self::checkpoint`])
    /// into this model, which must be the model of that run built again as
    /// it was built at the start (the same bodies, materials, prescribed
    /// unknowns and motions, groups and edge tractions; laws, kinematics,
    /// integrator, solver and settings; fixed points). Its bodies' geometry
    /// and motion, time, step control, search distance and contact history
    /// become the checkpoint's: the next [`Self::advance`] takes the step
    /// the run would have taken, to the last bit. Nothing is changed when
    /// the checkpoint is refused.
    ///
    /// # Errors
    /// [`DismechError::Checkpoint`](crate::error::DismechError::Checkpoint)
    /// (origin `bytes`) with
    /// [`CheckpointProblem::NotACheckpoint`](crate::checkpoint::CheckpointProblem::NotACheckpoint),
    /// [`UnsupportedVersion`](crate::checkpoint::CheckpointProblem::UnsupportedVersion),
    /// [`WrongDriver`](crate::checkpoint::CheckpointProblem::WrongDriver) (an
    /// explicit driver's),
    /// [`Truncated`](crate::checkpoint::CheckpointProblem::Truncated),
    /// [`Corrupt`](crate::checkpoint::CheckpointProblem::Corrupt) (checksum,
    /// decoding, or contents that do not fit each other), or
    /// [`ModelMismatch`](crate::checkpoint::CheckpointProblem::ModelMismatch)
    /// naming the first difference of the model: its type (`N`, `K`, `L`,
    /// `I`, `S`), its laws', integrator's or settings' parameters, its
    /// number of bodies, a body's kind, vertex count, material, group,
    /// prescribed unknowns or edge tractions, or its fixed points.
    pub fn restore(&mut self, checkpoint: &[u8]) -> Result<()> {
        self.restore_from(checkpoint, IN_MEMORY)
    }

    /// [`Self::restore`] from the file at `path` (written by
    /// [`Self::save_checkpoint`]).
    ///
    /// # Errors
    /// The errors of [`Self::restore`], naming the path as the origin, and
    /// [`CheckpointProblem::Unreadable`](crate::checkpoint::CheckpointProblem::Unreadable)
    /// when the file cannot be read.
    pub fn load_checkpoint(&mut self, path: &Path) -> Result<()> {
        let bytes = format::read(path)?;
        self.restore_from(&bytes, &path.display().to_string())
    }

    fn restore_from(&mut self, checkpoint: &[u8], origin: &str) -> Result<()> {
        let payload = format::open(Driver::Implicit, checkpoint, origin)?;
        // The model first: a model of other types has other states, which
        // would not decode.
        let saved: ModelRecord<'_> = format::parse_start(payload, origin)?;
        self.check_model(&saved, origin)?;
        let state: ImplicitState<'_, N, L::State> = format::parse(payload, origin)?;
        let n = self.bodies.len();
        let corrupt = |reason: String| format::corrupt(origin, reason);
        if state.bodies.len() != n || state.fixed_points.len() != self.fixed_points.len() {
            return Err(corrupt(format!(
                "{} body states and {} fixed points for {n} bodies and {} fixed points",
                state.bodies.len(),
                state.fixed_points.len(),
                self.fixed_points.len()
            )));
        }
        for (i, (body, saved)) in self.bodies.iter().zip(&state.bodies).enumerate() {
            let vertices = match &saved.geometry {
                BodyGeometry::Polygon(p) => p.vertex_count(),
                _ => 0,
            };
            if kind_of(&saved.geometry) != kind_of(body.geometry())
                || vertices != body.vertex_count()
            {
                return Err(corrupt(format!(
                    "body {i}'s geometry is not a {} of {} vertices",
                    kind_of(body.geometry()),
                    body.vertex_count()
                )));
            }
        }
        let polygon_vertices = |i: usize| match &state.bodies[i].geometry {
            BodyGeometry::Polygon(p) => Some(p.vertex_count()),
            _ => None,
        };
        if let Some(((a, _, b, _), _)) =
            (state.history.iter()).find(|((a, _, b, _), _)| *a >= n || *b >= n)
        {
            return Err(corrupt(format!(
                "a contact history names bodies {a} and {b} of {n}"
            )));
        }
        for &((a, v, b), e) in &state.edges {
            let beyond = |i: usize, k: usize| polygon_vertices(i).is_some_and(|count| k >= count);
            if a >= n || b >= n || beyond(a, v) || beyond(b, e) {
                return Err(corrupt(format!(
                    "the previous step's edge {e} of body {b} under vertex {v} of body {a} is not in the model"
                )));
            }
        }
        // Checked: the state goes in.
        for (body, saved) in self.bodies.iter_mut().zip(state.bodies) {
            body.set_geometry(saved.geometry);
            body.stress = saved.stress;
            body.velocity = saved.velocity;
            body.acceleration = saved.acceleration;
            body.displacement = saved.displacement;
        }
        for (fixed, point) in self.fixed_points.iter_mut().zip(state.fixed_points) {
            fixed.point = point;
        }
        self.time = state.time;
        self.requested_dt = state.requested_dt;
        self.current_dt = state.current_dt;
        self.search = state.search;
        self.solves = state.solves;
        self.history = state.history.into_iter().collect();
        self.previous = Previous {
            edges: state.edges.into_iter().collect(),
            angles: state.angles.into_iter().collect(),
        };
        self.contacts = state.contacts.into_owned();
        Ok(())
    }

    /// Refuse a checkpoint of another model than this one, naming the
    /// first difference.
    fn check_model(&self, saved: &ModelRecord<'_>, origin: &str) -> Result<()> {
        let model = self.model_record()?;
        let mismatch = |what: String, a: &dyn ToString, b: &dyn ToString| {
            Err(format::mismatch(origin, what, a.to_string(), b.to_string()))
        };
        if saved.model_type != model.model_type {
            return mismatch("model type".into(), &saved.model_type, &model.model_type);
        }
        saved.laws.check("contact laws", &model.laws, origin)?;
        saved
            .integrator
            .check("integrator", &model.integrator, origin)?;
        if saved.settings != model.settings {
            return mismatch(
                "settings".into(),
                &"the settings it was saved with",
                &format!("other settings ({:?})", self.settings),
            );
        }
        if saved.bodies.len() != model.bodies.len() {
            return mismatch(
                "number of bodies".into(),
                &saved.bodies.len(),
                &model.bodies.len(),
            );
        }
        for (i, (a, b)) in saved.bodies.iter().zip(&model.bodies).enumerate() {
            if let Some((field, a, b)) = a.difference(b) {
                return mismatch(format!("body {i}'s {field}"), &a, &b);
            }
        }
        if saved.fixed_points.len() != model.fixed_points.len() {
            return mismatch(
                "number of fixed points".into(),
                &saved.fixed_points.len(),
                &model.fixed_points.len(),
            );
        }
        for (k, (a, b)) in (saved.fixed_points.iter())
            .zip(&model.fixed_points)
            .enumerate()
        {
            if a != b {
                let show = |(body, bits): &(usize, [u64; 3])| {
                    let [x, y, k] = bits.map(f64::from_bits);
                    format!("body {body}, anchor ({x}, {y}), stiffness {k}")
                };
                return mismatch(format!("fixed point {k}"), &show(a), &show(b));
            }
        }
        Ok(())
    }
}
