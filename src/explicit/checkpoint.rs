//! Checkpoints of the explicit driver: the scene, the settings and the
//! run's whole state saved, and a run resumed from them with the law and
//! the integrator supplied again (see [`crate::checkpoint`] for what is
//! saved, the format and its version).

use std::borrow::Cow;
use std::path::Path;

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use super::super::neighbours::ListState;
use super::{DemSettings, ExplicitDynamics};
use crate::checkpoint::{self as format, Driver, Piece, IN_MEMORY};
use crate::error::{DismechError, Result};
use crate::explicit::ExplicitError;
use crate::integrate::ExplicitIntegrator;
use crate::law::{BoundedStiffness, ContactLaw};
use crate::math::Vec2;
use crate::scene::Scene;

/// What the explicit driver's checkpoint holds (see [`crate::checkpoint`]).
#[derive(Serialize, Deserialize)]
#[serde(bound(
    serialize = "S: Serialize + Clone",
    deserialize = "S: Deserialize<'de> + Clone"
))]
struct ExplicitState<'a, S: Clone> {
    law: Piece<'a>,
    integrator: Piece<'a>,
    scene: Cow<'a, Scene>,
    settings: DemSettings,
    step: u64,
    time: f64,
    initial_potential: f64,
    initial_kinetic: f64,
    prescribed_work: f64,
    initial_overlap: f64,
    stable_estimate: Option<f64>,
    /// Each particle's increment of the last step (translation, rotation).
    increments: Vec<(Vec2, f64)>,
    /// Each particle's `[f_x, f_y, m]` of the last step.
    forces: Cow<'a, [f64]>,
    list: ListState<'a, S>,
}

/// Checkpoints need the law's state to be serde's, and the law's and the
/// integrator's parameters to serialize (they are compared on restore):
/// a law without serde runs everything else.
impl<L, I> ExplicitDynamics<L, I>
where
    L: ContactLaw<2> + Serialize,
    L::State: Serialize + DeserializeOwned,
    I: ExplicitIntegrator + Serialize,
{
    /// The run's checkpoint: the scene, the settings and everything the
    /// next step reads (see [`crate::checkpoint`]), with the law's and the
    /// integrator's type names and parameters. [`Self::restore`] resumes
    /// it to the same bits.
    ///
    /// # Errors
    /// [`DismechError::Checkpoint`] when the law's state or parameters, or
    /// the integrator's, fail to serialize (their `Serialize`).
    pub fn checkpoint(&self) -> Result<Vec<u8>> {
        let state = ExplicitState {
            law: Piece::of(&self.law)?,
            integrator: Piece::of(&self.integrator)?,
            scene: Cow::Borrowed(&self.scene),
            settings: self.settings,
            step: self.step,
            time: self.time,
            initial_potential: self.initial_potential,
            initial_kinetic: self.initial_kinetic,
            prescribed_work: self.prescribed_work,
            initial_overlap: self.initial_overlap,
            stable_estimate: self.stable_estimate,
            increments: self.bodies.iter().map(|b| b.increment).collect(),
            forces: Cow::Borrowed(&self.system.force),
            list: self.neighbours.state(),
        };
        format::encode(Driver::Explicit, &state)
    }

    /// Write [`Self::checkpoint`] to `path`, whole or not at all
    /// ([`crate::io::write_atomically`]; the folder is created if needed).
    ///
    /// # Errors
    /// The errors of [`Self::checkpoint`]; [`DismechError::Output`] naming
    /// the path when it cannot be written.
    pub fn save_checkpoint(&self, path: &Path) -> Result<()> {
        crate::io::write_atomically(path, &self.checkpoint()?)
    }

    /// Resume the run of `checkpoint` (the bytes of [`Self::checkpoint`])
    /// with its contact law `law` and integrator `integrator`, supplied
    /// again: they must be of the types and have the parameters the run
    /// had. The scene and the settings come from the checkpoint. The next
    /// step is the one the run would have taken, to the last bit.
    ///
    /// # Errors
    /// [`DismechError::Checkpoint`] (origin `bytes`) with
    /// [`CheckpointProblem::NotACheckpoint`](crate::checkpoint::CheckpointProblem::NotACheckpoint),
    /// [`UnsupportedVersion`](crate::checkpoint::CheckpointProblem::UnsupportedVersion),
    /// [`WrongDriver`](crate::checkpoint::CheckpointProblem::WrongDriver) (an
    /// implicit driver's),
    /// [`Truncated`](crate::checkpoint::CheckpointProblem::Truncated),
    /// [`Corrupt`](crate::checkpoint::CheckpointProblem::Corrupt) (checksum,
    /// decoding, or a scene, settings or state the driver refuses or that
    /// do not fit each other), or
    /// [`ModelMismatch`](crate::checkpoint::CheckpointProblem::ModelMismatch)
    /// naming the contact law's or the integrator's type or parameters
    /// when they are not the run's; [`ExplicitError::OutOfMemory`] for a
    /// scene whose run the allocator refuses.
    pub fn restore(law: L, integrator: I, checkpoint: &[u8]) -> Result<Self>
    where
        L: BoundedStiffness<2>,
    {
        let mut sim = Self::restore_from(law, integrator, checkpoint, IN_MEMORY)?;
        sim.bounded_stiffness();
        Ok(sim)
    }

    /// [`Self::restore`] from the file at `path` (written by
    /// [`Self::save_checkpoint`]).
    ///
    /// # Errors
    /// The errors of [`Self::restore`], naming the path as the origin, and
    /// [`CheckpointProblem::Unreadable`](crate::checkpoint::CheckpointProblem::Unreadable)
    /// when the file cannot be read.
    pub fn load_checkpoint(law: L, integrator: I, path: &Path) -> Result<Self>
    where
        L: BoundedStiffness<2>,
    {
        let bytes = format::read(path)?;
        let mut sim = Self::restore_from(law, integrator, &bytes, &path.display().to_string())?;
        sim.bounded_stiffness();
        Ok(sim)
    }

    /// [`Self::restore`] for a law without a stiffness bound, of a run
    /// set up by [`Self::with_unchecked_time_step`].
    ///
    /// # Errors
    /// The errors of [`Self::restore`], and
    /// [`DismechError::InvalidParameter`] when the checkpoint's settings
    /// check the stable step (`check_stability`: a run of a law with a
    /// bound, which [`Self::restore`] resumes).
    pub fn restore_unchecked(law: L, integrator: I, checkpoint: &[u8]) -> Result<Self> {
        let sim = Self::restore_from(law, integrator, checkpoint, IN_MEMORY)?;
        if sim.settings.check_stability {
            return Err(DismechError::InvalidParameter {
                name: "check_stability (in the checkpoint's settings)",
                value: 1.0,
                requirement: "must be false to resume without a stiffness bound: resume the run with restore, whose law bounds its stiffness",
            });
        }
        Ok(sim)
    }

    fn restore_from(law: L, integrator: I, checkpoint: &[u8], origin: &str) -> Result<Self> {
        let payload = format::open(Driver::Explicit, checkpoint, origin)?;
        // The law and the integrator first: a law of another type has
        // another state, which would not decode.
        let (saved_law, saved_integrator): (Piece<'_>, Piece<'_>) =
            format::parse_start(payload, origin)?;
        saved_law.check("contact law", &Piece::of(&law)?, origin)?;
        saved_integrator.check("integrator", &Piece::of(&integrator)?, origin)?;
        let state: ExplicitState<'_, L::State> = format::parse(payload, origin)?;
        let overlap = state.settings.stability_overlap;
        if !(overlap.is_finite() && overlap > 0.0 && overlap <= 1.0) {
            return Err(format::corrupt(
                origin,
                format!("its settings' stability_overlap {overlap} lies outside (0, 1]"),
            ));
        }
        let n = state.scene.particles.len();
        if state.increments.len() != n || state.forces.len() != 3 * n {
            return Err(format::corrupt(
                origin,
                format!(
                    "{} increments and {} force components for {n} particles",
                    state.increments.len(),
                    state.forces.len()
                ),
            ));
        }
        let mut sim = Self::assemble(state.scene.into_owned(), law, integrator, state.settings)
            .map_err(|e| match e {
                DismechError::Explicit(ExplicitError::OutOfMemory { .. }) => e,
                refused => format::corrupt(
                    origin,
                    format!("the driver refuses its scene or settings: {refused}"),
                ),
            })?;
        sim.step = state.step;
        sim.time = state.time;
        sim.initial_potential = state.initial_potential;
        sim.initial_kinetic = state.initial_kinetic;
        sim.prescribed_work = state.prescribed_work;
        sim.initial_overlap = state.initial_overlap;
        sim.stable_estimate = state.stable_estimate;
        for (body, increment) in sim.bodies.iter_mut().zip(state.increments) {
            body.increment = increment;
        }
        sim.system.force = state.forces.into_owned();
        sim.neighbours
            .restore(state.list, &sim.scene.particles, sim.scene.frame.walls())
            .map_err(|reason| format::corrupt(origin, reason))?;
        Ok(sim)
    }
}
