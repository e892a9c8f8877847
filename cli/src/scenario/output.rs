//! `[output]`: what the run writes besides `summary.json`.

use serde::Deserialize;

/// The outputs.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Write a ParaView frame every this many steps (and at the start and
    /// the end); 0 writes the start and the end only. 100 by default.
    pub frames_every: Option<u64>,
    /// Sides of the polygons that draw circles and ellipses (≥ 3); 32 by
    /// default.
    pub segments: Option<usize>,
    /// Write a checkpoint every this many steps (and at the end of the
    /// run), to resume with `--resume`; none by default.
    pub checkpoint_every: Option<u64>,
    /// The folder of the checkpoints, relative to the scenario file's
    /// folder; beside the output folder by default.
    pub checkpoint_dir: Option<String>,
    /// Keep only the checkpoints of the newest this many steps (≥ 1): the
    /// older ones are removed once a newer one is written; all are kept
    /// by default.
    pub keep_checkpoints: Option<usize>,
}
