//! A frame (the named datasets of one instant) and a time series of
//! frames in a folder, indexed by one `.pvd` file per dataset name.

use std::path::{Path, PathBuf};

use super::xml::Dataset;
use super::VtkProblem;
use crate::error::{DismechError, Result};
use crate::io::write_atomically;

/// One dataset of a frame and the name its files and index take
/// (`particles` → `particles_000012.vtu`, `particles.pvd`).
#[derive(Debug, Clone, PartialEq)]
pub struct Piece {
    /// Letters, digits, `_` and `-` only.
    pub name: String,
    /// The dataset.
    pub data: Dataset,
}

/// The datasets of one instant: e.g. a DEM run's `particles`, `contacts`
/// and `walls`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct VtkFrame {
    pieces: Vec<Piece>,
}

impl VtkFrame {
    /// A frame without a piece.
    pub fn new() -> Self {
        Self::default()
    }

    /// Add the dataset `data` under `name`.
    ///
    /// # Errors
    /// [`DismechError::VtkData`] for a name that is empty, has a character
    /// other than a letter, a digit, `_` or `-` (it names files:
    /// [`VtkProblem::PieceName`]), or is already in the frame
    /// ([`VtkProblem::DuplicatePiece`]).
    pub fn push(&mut self, name: &str, data: Dataset) -> Result<()> {
        let valid = !name.is_empty()
            && name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
        if !valid {
            return Err(DismechError::VtkData {
                reason: VtkProblem::PieceName {
                    name: name.to_string(),
                },
            });
        }
        if self.get(name).is_some() {
            return Err(DismechError::VtkData {
                reason: VtkProblem::DuplicatePiece {
                    name: name.to_string(),
                },
            });
        }
        self.pieces.push(Piece {
            name: name.to_string(),
            data,
        });
        Ok(())
    }

    /// The pieces, in the order they were added.
    pub fn pieces(&self) -> &[Piece] {
        &self.pieces
    }

    /// The dataset named `name`.
    pub fn get(&self, name: &str) -> Option<&Dataset> {
        self.pieces.iter().find(|p| p.name == name).map(|p| &p.data)
    }
}

/// A dataset of a series: its time and its file, relative to the folder.
#[derive(Debug, Clone, PartialEq)]
pub struct PvdEntry {
    /// Time (s; any increasing number for a series that is not in time).
    pub time: f64,
    /// File name in the series' folder.
    pub file: String,
}

/// A time series of frames in a folder: each [`PvdSeries::write_frame`]
/// writes the frame's pieces as `NAME_FFFFFF.vtp|vtu` (`FFFFFF` the frame
/// number from 0) and then rewrites `NAME.pvd`, the index ParaView opens
/// as one time series, for each piece. Every file is written whole or not
/// at all ([`write_atomically`]), and the indices are rewritten only once
/// every file of the frame is in place: a reader (ParaView reloading, a
/// run stopped midway) sees the frames up to the last complete one.
///
/// The series starts empty: files of an earlier series in the folder are
/// overwritten frame by frame, and those past its last frame stay but are
/// in no index.
#[derive(Debug, Clone, PartialEq)]
pub struct PvdSeries {
    folder: PathBuf,
    frames: usize,
    last_time: Option<f64>,
    indices: Vec<(String, Vec<PvdEntry>)>,
}

impl PvdSeries {
    /// An empty series in `folder` (created if needed).
    ///
    /// # Errors
    /// [`DismechError::Output`] when the folder cannot be created.
    pub fn new(folder: impl Into<PathBuf>) -> Result<Self> {
        let folder = folder.into();
        std::fs::create_dir_all(&folder).map_err(|e| DismechError::Output {
            path: folder.display().to_string(),
            message: e.to_string(),
        })?;
        Ok(Self {
            folder,
            frames: 0,
            last_time: None,
            indices: Vec::new(),
        })
    }

    /// The folder.
    pub fn folder(&self) -> &Path {
        &self.folder
    }

    /// The time of the last frame written, if any.
    pub fn last_time(&self) -> Option<f64> {
        self.last_time
    }

    /// Frames written so far.
    pub fn frames(&self) -> usize {
        self.frames
    }

    /// The names of the pieces written so far, in the order first met.
    pub fn piece_names(&self) -> impl Iterator<Item = &str> {
        self.indices.iter().map(|(name, _)| name.as_str())
    }

    /// The entries of piece `name`'s index.
    pub fn entries(&self, name: &str) -> &[PvdEntry] {
        self.indices
            .iter()
            .find(|(n, _)| n == name)
            .map_or(&[], |(_, e)| e.as_slice())
    }

    /// The index file of piece `name`: `FOLDER/NAME.pvd`.
    pub fn pvd_path(&self, name: &str) -> PathBuf {
        self.folder.join(format!("{name}.pvd"))
    }

    /// Write `frame` as the series' state at `time`, then rewrite the
    /// index of each of its pieces.
    ///
    /// # Errors
    /// [`DismechError::InvalidParameter`] naming `frame time` for a time
    /// that is not finite or not after the last frame's;
    /// [`DismechError::VtkData`] for a dataset whose arrays or cells do not
    /// fit it ([`Dataset::to_xml`]); [`DismechError::Output`] naming the
    /// file that could not be written (the indices then still list the
    /// frames before).
    pub fn write_frame(&mut self, time: f64, frame: &VtkFrame) -> Result<()> {
        if !time.is_finite() || self.last_time.is_some_and(|t| time <= t) {
            return Err(DismechError::InvalidParameter {
                name: "frame time",
                value: time,
                requirement: "must be finite and after the last frame's time",
            });
        }
        let mut written = Vec::with_capacity(frame.pieces().len());
        for piece in frame.pieces() {
            let file = format!(
                "{}_{:06}.{}",
                piece.name,
                self.frames,
                piece.data.extension()
            );
            write_atomically(&self.folder.join(&file), piece.data.to_xml()?.as_bytes())?;
            written.push((piece.name.clone(), file));
        }
        // The indices are updated in a copy and kept only once every one is
        // written: a frame whose index could not be written is retried whole
        // (the same file names), never listed twice.
        let mut indices = self.indices.clone();
        for (name, file) in written {
            let k = match indices.iter().position(|(n, _)| *n == name) {
                Some(k) => k,
                None => {
                    indices.push((name.clone(), Vec::new()));
                    indices.len() - 1
                }
            };
            indices[k].1.push(PvdEntry { time, file });
            write_atomically(&self.pvd_path(&name), pvd_text(&indices[k].1).as_bytes())?;
        }
        self.indices = indices;
        self.frames += 1;
        self.last_time = Some(time);
        Ok(())
    }
}

/// The text of a `.pvd` index (a VTK `Collection`) of `entries`.
pub fn pvd_text(entries: &[PvdEntry]) -> String {
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n",
    );
    for e in entries {
        s.push_str(&format!(
            "    <DataSet timestep=\"{:e}\" group=\"\" part=\"0\" file=\"{}\"/>\n",
            e.time, e.file
        ));
    }
    s.push_str("  </Collection>\n</VTKFile>\n");
    s
}

/// Write one dataset to `path` (whole or not at all); the path's extension
/// should be [`Dataset::extension`].
///
/// # Errors
/// [`DismechError::VtkData`] for a dataset whose arrays or cells do not
/// fit it; [`DismechError::Output`] naming the path when it cannot be
/// written.
pub fn write_dataset(path: &Path, data: &Dataset) -> Result<()> {
    write_atomically(path, data.to_xml()?.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vtk::xml::PolyData;

    #[test]
    fn a_series_indexes_each_piece_and_refuses_time_going_back() {
        let dir = std::env::temp_dir().join(format!("dismech-pvd-{}", std::process::id()));
        let mut series = PvdSeries::new(&dir).unwrap();
        let mut frame = VtkFrame::new();
        frame
            .push("a", Dataset::PolyData(PolyData::default()))
            .unwrap();
        assert!(frame
            .push("a", Dataset::PolyData(PolyData::default()))
            .is_err());
        assert!(frame
            .push("b/c", Dataset::PolyData(PolyData::default()))
            .is_err());
        series.write_frame(0.0, &frame).unwrap();
        series.write_frame(0.5, &frame).unwrap();
        assert!(series.write_frame(0.5, &frame).is_err());
        assert!(series.write_frame(f64::NAN, &frame).is_err());
        assert_eq!(series.frames(), 2);
        let pvd = std::fs::read_to_string(series.pvd_path("a")).unwrap();
        assert!(pvd.contains("timestep=\"5e-1\" group=\"\" part=\"0\" file=\"a_000001.vtp\""));
        assert_eq!(series.entries("a").len(), 2);
        assert!(dir.join("a_000000.vtp").is_file());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
