//! Checkpoints of the time-stepping drivers: a run saved to bytes (or a
//! file) and resumed later to the same bits, as if it had never stopped.
//!
//! | driver | save | resume |
//! |---|---|---|
//! | explicit ([`crate::explicit::ExplicitDynamics`], [`crate::dem::DemSimulation`]) | [`checkpoint`](crate::explicit::ExplicitDynamics::checkpoint), [`save_checkpoint`](crate::explicit::ExplicitDynamics::save_checkpoint) | [`ExplicitDynamics::restore`](crate::explicit::ExplicitDynamics::restore)`(law, integrator, &bytes)`, [`load_checkpoint`](crate::explicit::ExplicitDynamics::load_checkpoint)`(law, integrator, path)` |
//! | implicit ([`crate::implicit::ImplicitDynamics`], [`crate::dda::DdaModel`]) | [`checkpoint`](crate::implicit::ImplicitDynamics::checkpoint), [`save_checkpoint`](crate::implicit::ImplicitDynamics::save_checkpoint) | the model built again as at the start, then [`restore`](crate::implicit::ImplicitDynamics::restore)`(&bytes)` or [`load_checkpoint`](crate::implicit::ImplicitDynamics::load_checkpoint)`(path)` |
//!
//! # What is saved
//!
//! Everything the next step reads, so that N steps in one go and k steps,
//! a checkpoint, a new process and N − k steps give the same positions,
//! velocities, rotations, stresses, contact forces and time to the last
//! bit:
//!
//! * **explicit driver**: the whole scene (each particle's shape, pose,
//!   velocities, mass, inertia and external force; the walls; gravity),
//!   the [`DemSettings`](crate::explicit::DemSettings), the time and the
//!   step count, each particle's increment of the last step (the shear
//!   increments of the next step are measured from it) and its force and
//!   moment of the last step, the neighbour list as it stands (its pairs
//!   in their order, each contact point's law state, overlap, point,
//!   normal and force, the poses it was built at, its skin and the steps
//!   since its build, whether it must be built again, how many times it
//!   was built), and the energies the rest and blow-up tests measure from
//!   (the initial potential and kinetic energies, the work of the
//!   prescribed particles, the initial overlap, the stable-step estimate);
//! * **implicit driver**: each body's geometry as it stands (a polygon's
//!   vertices about its centroid with its normals, area and moments as the
//!   last step left them; an ellipse's axes), stress, velocity,
//!   acceleration and total displacement; the fixed points' material
//!   points; the time; the step in use and the step asked for (so a step
//!   halved before the checkpoint grows back as it would have), the search
//!   distance in use; the contact history of every contact that did not
//!   open (the law's state), the edge each vertex touched and the normal
//!   angle of each smooth pair (where the next detection starts), the
//!   contact reports of the last step, and the count of linear solves.
//!
//! What is rebuilt rather than saved is rebuilt by the code that built it
//! in the run, from saved values, to the same bits: the explicit driver's
//! per-particle pair records, ellipse rotations, masses and weights, the
//! neighbour list's indices by block; the implicit driver's candidate
//! pairs (found again at the start of every step), the tangent's pattern
//! and the linear solver's analysis (made again for the first step's
//! pattern: an analysis depends on the pattern alone, so
//! [`symbolic_analyses`](crate::implicit::ImplicitDynamics::symbolic_analyses)
//! counts one more after a restore, and nothing else differs).
//!
//! # What the user supplies again, and what is checked
//!
//! Code is not saved: a law, an integrator or a prescribed motion may be a
//! user's own type or closure.
//!
//! * **explicit driver**: the contact law and the integrator. The
//!   checkpoint keeps their type names and their serialized parameters
//!   and refuses others ([`CheckpointProblem::ModelMismatch`] naming which:
//!   a law with another friction coefficient is refused). The scene and
//!   the settings come from the checkpoint, so they cannot mismatch.
//! * **implicit driver**: the whole model, built again the way it was
//!   built at the start (the same bodies with their materials, prescribed
//!   unknowns and motions, groups and edge tractions; the same laws,
//!   kinematics, integrator, solver, settings and fixed points); its state
//!   is then replaced by the checkpoint's. The checkpoint refuses a model
//!   with another number of bodies, a body of another kind or vertex
//!   count, material, group, prescribed unknowns or edge tractions,
//!   other laws, settings or integrator (their serialized parameters),
//!   another kinematics or solver type, or other fixed points, naming the
//!   first difference. A prescribed motion is a closure and cannot be
//!   compared: it must be the one of the run.
//!
//! The scene's types ([`Scene`](crate::scene::Scene),
//! [`Particle`](crate::scene::Particle), the shapes,
//! [`Frame`](crate::scene::Frame)) implement serde as well, for a user's
//! own files: a circle, an ellipse and a frame are read back through their
//! checking constructors, a polygon with the checks its type states.
//!
//! The checkpoint methods need the law's state to be
//! `Serialize + DeserializeOwned` and the law and the integrator (and for
//! the implicit driver the settings, which are) to be `Serialize`: they
//! sit in an `impl` block of their own, so a user's law without serde
//! still runs everything else. The crate's laws
//! ([`SpringDashpotCoulomb`](crate::law::SpringDashpotCoulomb),
//! [`PenaltyCoulomb`](crate::law::PenaltyCoulomb)), their states and its
//! integrators implement them.
//!
//! # Format
//!
//! A header of 29 bytes, then the payload:
//!
//! | bytes | what |
//! |---|---|
//! | 0–7 | the signature `dismechK` |
//! | 8–11 | the format version, little-endian ([`FORMAT_VERSION`]) |
//! | 12 | the driver: 1 explicit, 2 implicit |
//! | 13–20 | the payload's length in bytes, little-endian |
//! | 21–28 | the payload's FNV-1a 64-bit checksum, little-endian |
//! | 29– | the payload: the driver's state in [postcard](https://docs.rs/postcard) (serde's compact binary format: varints, floats as their 8 bytes, so every value reads back to the same bits) |
//!
//! A checkpoint is refused with [`DismechError::Checkpoint`] naming where
//! it came from (the path, or `bytes` for an in-memory one) and a typed
//! [`CheckpointProblem`]: not a checkpoint, a version this build does not
//! read, another driver's, truncated, corrupt (checksum, undecodable or
//! inconsistent contents), or another model's. No input makes it panic.
//! [`save_checkpoint`](crate::explicit::ExplicitDynamics::save_checkpoint)
//! writes through [`crate::io::write_atomically`]: a file is whole or not
//! there. The format changes with the crate's saved types; a change bumps
//! [`FORMAT_VERSION`], and an older build refuses the newer file rather
//! than misreading it.
//!
//! # Example
//!
//! ```
//! # fn main() -> dismech::error::Result<()> {
//! use dismech::dem::DemSimulation;
//! use dismech::explicit::DemSettings;
//! use dismech::integrate::ExplicitEuler;
//! use dismech::law::SpringDashpotCoulomb;
//! use dismech::math::{Point, Vec2};
//! use dismech::scene::{Frame, Scene};
//!
//! let mut scene = Scene::new(Frame::open_box(1.0, 1.0)?, Vec2::new(0.0, -9.81))?;
//! scene.add_circle(Point::new(0.5, 0.1), 0.1, 2600.0)?;
//! scene.add_circle(Point::new(0.52, 0.31), 0.1, 2600.0)?;
//! let law = SpringDashpotCoulomb::katsuki(1e8, 0.3, 0.25, 0.5)?;
//! let settings = DemSettings { dt: 1e-5, ..DemSettings::default() };
//! let mut straight = DemSimulation::new(scene.clone(), law, ExplicitEuler, settings)?;
//! let mut first = DemSimulation::new(scene, law, ExplicitEuler, settings)?;
//! for _ in 0..200 {
//!     straight.step()?;
//!     first.step()?;
//! }
//! // Save (to bytes here; `save_checkpoint(path)` writes a file), stop ...
//! let bytes = first.checkpoint()?;
//! drop(first);
//! // ... and resume with the same law and integrator.
//! let mut resumed: DemSimulation<SpringDashpotCoulomb> =
//!     DemSimulation::restore(law, ExplicitEuler, &bytes)?;
//! for _ in 0..200 {
//!     straight.step()?;
//!     resumed.step()?;
//! }
//! assert_eq!(resumed.time().to_bits(), straight.time().to_bits());
//! for (a, b) in resumed.scene().particles.iter().zip(&straight.scene().particles) {
//!     assert_eq!(a.pose.position.x.to_bits(), b.pose.position.x.to_bits());
//!     assert_eq!(a.velocity.y.to_bits(), b.velocity.y.to_bits());
//! }
//! # Ok(()) }
//! ```
//!
//! The implicit driver is restored into its model built again:
//!
//! ```
//! # fn main() -> dismech::error::Result<()> {
//! use dismech::dda::{Block, BlockMaterial, DdaModel, DdaSettings, PlaneState, Prescribed};
//! use dismech::law::{FrictionIntegration, PenaltyCoulomb};
//! use dismech::math::Point;
//!
//! // The model as the run builds it at the start: a block on a fixed base.
//! let model = || -> dismech::error::Result<DdaModel> {
//!     let rock = BlockMaterial { density: 2200.0, youngs_modulus: 1e9, poisson_ratio: 0.25,
//!                                plane: PlaneState::Stress };
//!     let square = |x0: f64, y0: f64, x1: f64, y1: f64| {
//!         [Point::new(x0, y0), Point::new(x1, y0), Point::new(x1, y1), Point::new(x0, y1)]
//!     };
//!     let mut base = Block::new(&square(-2.0, -0.5, 2.0, 0.0), rock, 0)?;
//!     base.prescribed = Some(Prescribed::fixed());
//!     let block = Block::new(&square(-0.5, 0.0, 0.5, 0.5), rock, 1)?;
//!     let law = PenaltyCoulomb::new(1e9, 0.5, FrictionIntegration::ReturnMapping)?;
//!     DdaModel::new(vec![base, block], law, DdaSettings::default())
//! };
//! let mut straight = model()?;
//! let mut first = model()?;
//! for _ in 0..5 {
//!     straight.advance(1e-3)?;
//!     first.advance(1e-3)?;
//! }
//! let bytes = first.checkpoint()?; // or first.save_checkpoint(path)
//! drop(first);
//! let mut resumed = model()?;
//! resumed.restore(&bytes)?; // or resumed.load_checkpoint(path)
//! for _ in 0..5 {
//!     straight.advance(1e-3)?;
//!     resumed.advance(1e-3)?;
//! }
//! assert_eq!(resumed.time().to_bits(), straight.time().to_bits());
//! assert_eq!(resumed.blocks()[1].velocity, straight.blocks()[1].velocity);
//! assert_eq!(resumed.blocks()[1].stress, straight.blocks()[1].stress);
//! # Ok(()) }
//! ```

use std::any::type_name;
use std::borrow::Cow;
use std::path::Path;

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use crate::error::{DismechError, Result};

/// The version of the checkpoint format this build writes and reads (2:
/// the implicit driver's settings gained `slip_reversal_quantile`).
pub const FORMAT_VERSION: u32 = 2;

/// The first eight bytes of every checkpoint.
const SIGNATURE: [u8; 8] = *b"dismechK";

/// The bytes before the payload: signature, version, driver, length,
/// checksum.
const HEADER: usize = 8 + 4 + 1 + 8 + 8;

/// What is wrong with a checkpoint (see [`DismechError::Checkpoint`],
/// which names where it came from).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CheckpointProblem {
    /// It does not start with the signature of a dismech checkpoint.
    #[error("not a dismech checkpoint (it does not start with the signature `dismechK`)")]
    NotACheckpoint,
    /// It was written in a format version this build does not read.
    #[error("format version {found}, which this build does not read (it reads version {supported}); resume it with the version of dismech that wrote it")]
    UnsupportedVersion {
        /// The version in the file.
        found: u32,
        /// The version this build reads.
        supported: u32,
    },
    /// It is the checkpoint of another driver.
    #[error("a checkpoint of the {found} driver, restored into the {expected} driver")]
    WrongDriver {
        /// The driver that wrote it.
        found: String,
        /// The driver asked to read it.
        expected: &'static str,
    },
    /// It ends before its header or its payload does.
    #[error("truncated: {found} bytes where {expected} were written (an interrupted copy?)")]
    Truncated {
        /// The length it announces (header and payload).
        expected: u64,
        /// The length found.
        found: u64,
    },
    /// Its contents are damaged: the checksum does not match, it cannot be
    /// decoded, or what it holds is inconsistent.
    #[error("corrupt: {0}")]
    Corrupt(String),
    /// The model it is restored into is not the one it was written from.
    #[error("not the model it was written from: {what} (in the checkpoint: {checkpoint}; in the model: {model})")]
    ModelMismatch {
        /// What differs (e.g. `number of bodies`, `contact law`).
        what: String,
        /// The checkpoint's value.
        checkpoint: String,
        /// The model's value.
        model: String,
    },
    /// The file could not be read.
    #[error("cannot be read: {0}")]
    Unreadable(String),
    /// The state could not be encoded (a law state's `Serialize` failed).
    #[error("cannot be encoded: {0}")]
    Unencodable(String),
}

/// A slot the user supplies again: its type's name and its serialized
/// parameters, compared on restore.
#[derive(Serialize, Deserialize)]
pub(crate) struct Piece<'a> {
    pub(crate) type_name: Cow<'a, str>,
    pub(crate) parameters: Vec<u8>,
}

impl Piece<'static> {
    /// `value`'s piece.
    pub(crate) fn of<T: Serialize>(value: &T) -> Result<Self> {
        Ok(Self {
            type_name: Cow::Borrowed(type_name::<T>()),
            parameters: fingerprint(value)?,
        })
    }
}

impl Piece<'_> {
    /// Refuse `supplied` (named `what`) when it is not this piece.
    pub(crate) fn check(&self, what: &str, supplied: &Piece<'_>, origin: &str) -> Result<()> {
        if self.type_name != supplied.type_name {
            return Err(mismatch(
                origin,
                format!("{what} type"),
                &self.type_name,
                &supplied.type_name,
            ));
        }
        if self.parameters != supplied.parameters {
            return Err(mismatch(
                origin,
                format!("{what} parameters"),
                format!("{} with the parameters it was saved with", self.type_name),
                format!("{} with other parameters", supplied.type_name),
            ));
        }
        Ok(())
    }
}

/// The driver a checkpoint belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Driver {
    Explicit,
    Implicit,
}

impl Driver {
    fn tag(self) -> u8 {
        match self {
            Driver::Explicit => 1,
            Driver::Implicit => 2,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Driver::Explicit => "explicit",
            Driver::Implicit => "implicit",
        }
    }
}

/// Where a checkpoint in memory comes from, in errors.
pub(crate) const IN_MEMORY: &str = "bytes";

/// A [`DismechError::Checkpoint`] of `origin` (the file or the bytes the
/// checkpoint was read from), for `problem`.
pub fn refused(origin: &str, problem: CheckpointProblem) -> DismechError {
    DismechError::Checkpoint {
        origin: origin.to_string(),
        problem,
    }
}

/// A corrupt checkpoint of `origin`, for `reason`.
pub(crate) fn corrupt(origin: &str, reason: impl Into<String>) -> DismechError {
    refused(origin, CheckpointProblem::Corrupt(reason.into()))
}

/// A checkpoint of `origin` written from another model: `what` is
/// `checkpoint` there and `model` here (a program that wraps a driver's
/// checkpoint in its own file refuses a mismatch of its own data so).
pub fn mismatch(
    origin: &str,
    what: impl Into<String>,
    checkpoint: impl ToString,
    model: impl ToString,
) -> DismechError {
    refused(
        origin,
        CheckpointProblem::ModelMismatch {
            what: what.into(),
            checkpoint: checkpoint.to_string(),
            model: model.to_string(),
        },
    )
}

/// FNV-1a, 64 bits.
fn checksum(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |hash, &b| {
        (hash ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// The serialized bytes of `value` (postcard), as the checkpoint keeps a
/// law's or an integrator's parameters to compare them on restore.
///
/// # Errors
/// [`DismechError::Checkpoint`] ([`CheckpointProblem::Unencodable`]) when
/// its `Serialize` fails.
pub(crate) fn fingerprint<T: Serialize + ?Sized>(value: &T) -> Result<Vec<u8>> {
    postcard::to_allocvec(value)
        .map_err(|e| refused(IN_MEMORY, CheckpointProblem::Unencodable(e.to_string())))
}

/// `state` framed as a checkpoint of `driver`.
///
/// # Errors
/// [`DismechError::Checkpoint`] ([`CheckpointProblem::Unencodable`]) when
/// a part's `Serialize` fails.
pub(crate) fn encode<T: Serialize>(driver: Driver, state: &T) -> Result<Vec<u8>> {
    let payload = fingerprint(state)?;
    let mut bytes = Vec::with_capacity(HEADER + payload.len());
    bytes.extend_from_slice(&SIGNATURE);
    bytes.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    bytes.push(driver.tag());
    bytes.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    bytes.extend_from_slice(&checksum(&payload).to_le_bytes());
    bytes.extend_from_slice(&payload);
    Ok(bytes)
}

/// The payload of a checkpoint of `driver` in `bytes`, which come from
/// `origin` (named in errors), its header and checksum checked.
///
/// # Errors
/// [`DismechError::Checkpoint`] for a signature, version or driver that is
/// not this one's, a checkpoint shorter or longer than it announces, or a
/// checksum that does not match.
pub(crate) fn open<'b>(driver: Driver, bytes: &'b [u8], origin: &str) -> Result<&'b [u8]> {
    let found = bytes.len() as u64;
    let truncated =
        |expected: u64| refused(origin, CheckpointProblem::Truncated { expected, found });
    let signature = &bytes[..bytes.len().min(SIGNATURE.len())];
    if signature != &SIGNATURE[..signature.len()] {
        return Err(refused(origin, CheckpointProblem::NotACheckpoint));
    }
    if bytes.len() < HEADER {
        return Err(truncated(HEADER as u64));
    }
    let word = |at: usize| u64::from_le_bytes(bytes[at..at + 8].try_into().unwrap_or([0; 8]));
    let version = u32::from_le_bytes(bytes[8..12].try_into().unwrap_or([0; 4]));
    if version != FORMAT_VERSION {
        return Err(refused(
            origin,
            CheckpointProblem::UnsupportedVersion {
                found: version,
                supported: FORMAT_VERSION,
            },
        ));
    }
    if bytes[12] != driver.tag() {
        let found = match bytes[12] {
            1 => Driver::Explicit.name().to_string(),
            2 => Driver::Implicit.name().to_string(),
            other => format!("unknown ({other})"),
        };
        return Err(refused(
            origin,
            CheckpointProblem::WrongDriver {
                found,
                expected: driver.name(),
            },
        ));
    }
    let (length, sum) = (word(13), word(21));
    let expected = (HEADER as u64).saturating_add(length);
    if found < expected {
        return Err(truncated(expected));
    }
    if found > expected {
        return Err(corrupt(
            origin,
            format!("{} bytes follow the payload", found - expected),
        ));
    }
    let payload = &bytes[HEADER..];
    if checksum(payload) != sum {
        return Err(corrupt(origin, "the checksum does not match the contents"));
    }
    Ok(payload)
}

/// What the start of `payload` (of [`open`]) holds: the parts a state
/// begins with, read before the rest so that a model of other types is
/// named as such rather than as a payload that does not decode.
///
/// # Errors
/// [`DismechError::Checkpoint`] ([`CheckpointProblem::Corrupt`]) when they
/// do not decode.
pub(crate) fn parse_start<T: DeserializeOwned>(payload: &[u8], origin: &str) -> Result<T> {
    postcard::take_from_bytes::<T>(payload)
        .map(|(start, _)| start)
        .map_err(|e| corrupt(origin, format!("the payload does not decode: {e}")))
}

/// The state in `payload` (of [`open`]), the whole of it.
///
/// # Errors
/// [`DismechError::Checkpoint`] ([`CheckpointProblem::Corrupt`]) when it
/// does not decode, or leaves bytes over.
pub(crate) fn parse<T: DeserializeOwned>(payload: &[u8], origin: &str) -> Result<T> {
    match postcard::take_from_bytes::<T>(payload) {
        Ok((state, [])) => Ok(state),
        Ok((_, rest)) => Err(corrupt(
            origin,
            format!("{} bytes of the payload are left over", rest.len()),
        )),
        Err(e) => Err(corrupt(origin, format!("the payload does not decode: {e}"))),
    }
}

/// [`open`], then [`parse`].
///
/// # Errors
/// Those of [`open`] and [`parse`].
#[cfg(test)]
fn decode<T: DeserializeOwned>(driver: Driver, bytes: &[u8], origin: &str) -> Result<T> {
    parse(open(driver, bytes, origin)?, origin)
}

/// The bytes of the checkpoint file at `path`.
///
/// # Errors
/// [`DismechError::Checkpoint`] ([`CheckpointProblem::Unreadable`]) naming
/// the path when it cannot be read.
pub(crate) fn read(path: &Path) -> Result<Vec<u8>> {
    std::fs::read(path).map_err(|e| {
        refused(
            &path.display().to_string(),
            CheckpointProblem::Unreadable(e.to_string()),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn refusal(bytes: &[u8]) -> CheckpointProblem {
        match decode::<Vec<f64>>(Driver::Explicit, bytes, IN_MEMORY) {
            Err(DismechError::Checkpoint { origin, problem }) => {
                assert_eq!(origin, IN_MEMORY);
                problem
            }
            other => panic!("{other:?}"),
        }
    }

    /// A value framed and read back is the same to the last bit, NaN
    /// payloads and signed zeros included.
    #[test]
    fn a_framed_state_reads_back_to_the_bit() {
        let values = vec![1.0, -0.0, f64::from_bits(0x7ff8_0000_0000_1234), 1e-310];
        let bytes = encode(Driver::Explicit, &values).unwrap();
        let back: Vec<f64> = decode(Driver::Explicit, &bytes, IN_MEMORY).unwrap();
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&back), bits(&values));
    }

    /// Every prefix of a checkpoint is refused as truncated (or, shorter
    /// than the signature, as truncated too, since it could be one), every
    /// single flipped bit of the payload as corrupt, and the header's
    /// fields by name.
    #[test]
    fn damaged_checkpoints_are_refused_by_what_is_wrong() {
        let bytes = encode(Driver::Explicit, &vec![0.5f64; 20]).unwrap();
        for cut in 0..bytes.len() {
            assert!(
                matches!(refusal(&bytes[..cut]), CheckpointProblem::Truncated { .. }),
                "cut at {cut}"
            );
        }
        for at in HEADER..bytes.len() {
            let mut flipped = bytes.clone();
            flipped[at] ^= 0x10;
            assert!(matches!(refusal(&flipped), CheckpointProblem::Corrupt(_)));
        }
        let mut other = bytes.clone();
        other[0] = b'x';
        assert_eq!(refusal(&other), CheckpointProblem::NotACheckpoint);
        let mut newer = bytes.clone();
        newer[8..12].copy_from_slice(&(FORMAT_VERSION + 1).to_le_bytes());
        assert_eq!(
            refusal(&newer),
            CheckpointProblem::UnsupportedVersion {
                found: FORMAT_VERSION + 1,
                supported: FORMAT_VERSION
            }
        );
        let mut older = bytes.clone();
        older[8..12].copy_from_slice(&(FORMAT_VERSION - 1).to_le_bytes());
        assert_eq!(
            refusal(&older),
            CheckpointProblem::UnsupportedVersion {
                found: FORMAT_VERSION - 1,
                supported: FORMAT_VERSION
            }
        );
        let mut longer = bytes.clone();
        longer.push(0);
        assert!(matches!(refusal(&longer), CheckpointProblem::Corrupt(_)));
        let implicit = encode(Driver::Implicit, &vec![0.5f64; 20]).unwrap();
        assert_eq!(
            refusal(&implicit),
            CheckpointProblem::WrongDriver {
                found: "implicit".into(),
                expected: "explicit"
            }
        );
    }
}
