//! A folder written whole or not at all: its files go into a hidden
//! staging sibling, which takes the folder's place by rename once every
//! file is written. A run that fails or is killed before then leaves the
//! previous folder untouched; readers see the old files or the new ones,
//! never a mix of both.

use std::path::{Path, PathBuf};

use dismech::error::{DismechError, Result};

fn output_error(path: &Path, e: impl std::fmt::Display) -> DismechError {
    DismechError::Output {
        path: path.display().to_string(),
        message: e.to_string(),
    }
}

/// A folder being written: write into [`StagedFolder::path`], then
/// [`StagedFolder::commit`] to put it in place of the target. Dropped
/// without a commit (an error, a panic), the staging folder is removed and
/// the target left as it was.
///
/// The staging folder is `PARENT/.NAME.partial-PID`; the previous target
/// is moved to `PARENT/.NAME.old-PID` for the instant between the two
/// renames of the commit and removed after. Leftovers of a run killed
/// before its commit are removed by the next [`StagedFolder::new`] on the
/// same target, and a target killed between the two renames is restored
/// from its `.old` copy.
#[derive(Debug)]
pub struct StagedFolder {
    target: PathBuf,
    staging: PathBuf,
    committed: bool,
}

impl StagedFolder {
    /// Start writing the folder `target`: clean the leftovers of killed
    /// runs and create an empty staging folder beside it. A target that
    /// exists but is not a folder is refused here, before anything is
    /// computed for it.
    pub fn new(target: &Path) -> Result<Self> {
        Self::staging(target)
    }

    /// [`Self::new`] for a folder a user names (`--out`), which is replaced
    /// whole: a target that exists with files in it but without `marker`
    /// (the file every run of the command writes there, e.g.
    /// `summary.json`) is refused rather than replaced, so that a folder
    /// holding other files (the input's own) is not removed.
    ///
    /// # Errors
    /// Those of [`Self::new`], and [`DismechError::Output`] naming the
    /// target when it holds files but no `marker`.
    pub fn new_replacing_runs(target: &Path, marker: &str) -> Result<Self> {
        if let Ok(mut entries) = std::fs::read_dir(target) {
            if entries.next().is_some() && !target.join(marker).is_file() {
                return Err(output_error(
                    target,
                    format!(
                        "the folder holds files but no {marker}, so it is not the output of an earlier run: it would be replaced whole; give a new or empty folder"
                    ),
                ));
            }
        }
        Self::staging(target)
    }

    fn staging(target: &Path) -> Result<Self> {
        let (parent, name) = split(target)?;
        std::fs::create_dir_all(&parent).map_err(|e| output_error(&parent, e))?;
        recover(&parent, &name, target)?;
        refuse_non_folder(target)?;
        let staging = parent.join(format!(".{name}.partial-{}", std::process::id()));
        if staging.exists() {
            std::fs::remove_dir_all(&staging).map_err(|e| output_error(&staging, e))?;
        }
        std::fs::create_dir(&staging).map_err(|e| output_error(&staging, e))?;
        Ok(Self {
            target: target.to_path_buf(),
            staging,
            committed: false,
        })
    }

    /// The folder to write into.
    pub fn path(&self) -> &Path {
        &self.staging
    }

    /// The folder the files end up in.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Put the staging folder in place of the target. A target that exists
    /// but is not a folder is refused, not replaced.
    pub fn commit(mut self) -> Result<()> {
        let (parent, name) = split(&self.target)?;
        let old = parent.join(format!(".{name}.old-{}", std::process::id()));
        let had_old = match std::fs::symlink_metadata(&self.target) {
            Ok(meta) if meta.is_dir() => {
                std::fs::rename(&self.target, &old).map_err(|e| output_error(&self.target, e))?;
                true
            }
            Ok(_) => return Err(not_a_folder(&self.target)),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => false,
            Err(e) => return Err(output_error(&self.target, e)),
        };
        if let Err(e) = std::fs::rename(&self.staging, &self.target) {
            if had_old {
                let _ = std::fs::rename(&old, &self.target);
            }
            return Err(output_error(&self.target, e));
        }
        self.committed = true;
        if had_old {
            std::fs::remove_dir_all(&old).map_err(|e| output_error(&old, e))?;
        }
        Ok(())
    }
}

impl Drop for StagedFolder {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.staging);
        }
    }
}

fn not_a_folder(target: &Path) -> DismechError {
    output_error(target, "it exists and is not a folder; it is not replaced")
}

/// Refuse a target that exists and is not a folder (a file, a link).
fn refuse_non_folder(target: &Path) -> Result<()> {
    match std::fs::symlink_metadata(target) {
        Ok(meta) if !meta.is_dir() => Err(not_a_folder(target)),
        _ => Ok(()),
    }
}

/// The parent folder and the file name of `target`.
fn split(target: &Path) -> Result<(PathBuf, String)> {
    let name = target
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or_else(|| output_error(target, "the path has no folder name"))?
        .to_string();
    let parent = match target.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    Ok((parent, name))
}

/// Whether the process whose id ends the name `file_name` (after
/// `prefix`) is still running, so that its folder belongs to a live run
/// (another `reproduce` writing the same study) and must be left alone.
/// Known where `/proc` lists the processes (Linux); elsewhere every such
/// folder counts as left by a killed run.
fn owned_by_a_live_run(file_name: &str, prefix: &str) -> bool {
    let Some(pid) = file_name
        .strip_prefix(prefix)
        .and_then(|p| p.parse::<u32>().ok())
    else {
        return false;
    };
    pid != std::process::id() && Path::new("/proc").join(pid.to_string()).exists()
}

/// Clean what killed runs left beside `target`: staging folders are
/// removed; a previous target moved aside is put back if the target is
/// missing (killed between the two renames of a commit), removed
/// otherwise. Folders of runs still going are left alone.
fn recover(parent: &Path, name: &str, target: &Path) -> Result<()> {
    let entries = std::fs::read_dir(parent).map_err(|e| output_error(parent, e))?;
    let (partial, old) = (format!(".{name}.partial-"), format!(".{name}.old-"));
    for entry in entries {
        let entry = entry.map_err(|e| output_error(parent, e))?;
        let file_name = entry.file_name();
        let Some(file_name) = file_name.to_str() else {
            continue;
        };
        let path = entry.path();
        if owned_by_a_live_run(file_name, &partial) || owned_by_a_live_run(file_name, &old) {
            continue;
        }
        if file_name.starts_with(&partial) {
            std::fs::remove_dir_all(&path).map_err(|e| output_error(&path, e))?;
        } else if file_name.starts_with(&old) {
            if target.exists() {
                std::fs::remove_dir_all(&path).map_err(|e| output_error(&path, e))?;
            } else {
                std::fs::rename(&path, target).map_err(|e| output_error(&path, e))?;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("dismech-folder-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn a_committed_folder_replaces_the_old_one_whole() {
        let out = scratch("commit");
        let target = out.join("study");
        std::fs::create_dir_all(&target).unwrap();
        std::fs::write(target.join("a.csv"), "old").unwrap();
        std::fs::write(target.join("only_old.csv"), "old").unwrap();
        let folder = StagedFolder::new(&target).unwrap();
        std::fs::write(folder.path().join("a.csv"), "new").unwrap();
        folder.commit().unwrap();
        assert_eq!(names(&out), ["study"]);
        assert_eq!(names(&target), ["a.csv"]);
        assert_eq!(
            std::fs::read_to_string(target.join("a.csv")).unwrap(),
            "new"
        );
        std::fs::remove_dir_all(&out).unwrap();
    }

    #[test]
    fn a_folder_dropped_before_its_commit_leaves_the_old_one() {
        let out = scratch("drop");
        let target = out.join("study");
        std::fs::create_dir_all(&target).unwrap();
        std::fs::write(target.join("a.csv"), "old").unwrap();
        {
            let folder = StagedFolder::new(&target).unwrap();
            std::fs::write(folder.path().join("a.csv"), "new").unwrap();
        }
        assert_eq!(names(&out), ["study"]);
        assert_eq!(
            std::fs::read_to_string(target.join("a.csv")).unwrap(),
            "old"
        );
        std::fs::remove_dir_all(&out).unwrap();
    }

    #[test]
    fn leftovers_of_a_killed_run_are_cleaned_or_restored() {
        let out = scratch("recover");
        let target = out.join("study");
        // Killed while writing (no process has this id): a staging folder
        // with a half-written file.
        std::fs::create_dir_all(out.join(".study.partial-4294967294")).unwrap();
        std::fs::write(out.join(".study.partial-4294967294/.a.csv.tmp1"), "half").unwrap();
        // Killed between the two renames of a commit: the target is aside.
        std::fs::create_dir_all(out.join(".study.old-4294967294")).unwrap();
        std::fs::write(out.join(".study.old-4294967294/a.csv"), "old").unwrap();
        let folder = StagedFolder::new(&target).unwrap();
        assert_eq!(
            std::fs::read_to_string(target.join("a.csv")).unwrap(),
            "old"
        );
        drop(folder);
        assert_eq!(names(&out), ["study"]);
        std::fs::remove_dir_all(&out).unwrap();
    }

    /// The staging folder of a run still going (process 1 always is) is
    /// not touched by another run of the same study.
    #[test]
    #[cfg(target_os = "linux")]
    fn a_live_run_s_staging_folder_is_left_alone() {
        let out = scratch("live");
        let target = out.join("study");
        std::fs::create_dir_all(out.join(".study.partial-1")).unwrap();
        let folder = StagedFolder::new(&target).unwrap();
        folder.commit().unwrap();
        assert_eq!(names(&out), [".study.partial-1", "study"]);
        std::fs::remove_dir_all(&out).unwrap();
    }

    #[test]
    fn a_target_that_is_a_file_is_not_replaced() {
        let out = scratch("file");
        let target = out.join("study");
        std::fs::write(&target, "mine").unwrap();
        let err = StagedFolder::new(&target).unwrap_err();
        assert!(err.to_string().contains("is not a folder"), "{err}");
        // Made a file while the folder was being written.
        std::fs::remove_file(&target).unwrap();
        let folder = StagedFolder::new(&target).unwrap();
        std::fs::write(&target, "mine").unwrap();
        let err = folder.commit().unwrap_err();
        assert!(err.to_string().contains("is not a folder"), "{err}");
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "mine");
        assert_eq!(names(&out), ["study"]);
        std::fs::remove_dir_all(&out).unwrap();
    }

    #[test]
    fn a_folder_of_other_files_is_not_replaced() {
        let parent = std::env::temp_dir().join(format!("dismech-foreign-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&parent);
        let target = parent.join("data");
        std::fs::create_dir_all(&target).unwrap();
        std::fs::write(target.join("dem.asc"), "the user's own").unwrap();
        let err = StagedFolder::new_replacing_runs(&target, "summary.json").unwrap_err();
        assert!(err.to_string().contains("no summary.json"), "{err}");
        assert_eq!(
            std::fs::read_to_string(target.join("dem.asc")).unwrap(),
            "the user's own"
        );
        // An earlier run's folder, and an empty one, are replaced.
        std::fs::write(target.join("summary.json"), "{}").unwrap();
        let folder = StagedFolder::new_replacing_runs(&target, "summary.json").unwrap();
        folder.commit().unwrap();
        assert!(!target.join("dem.asc").exists());
        let folder = StagedFolder::new_replacing_runs(&target, "summary.json").unwrap();
        folder.commit().unwrap();
        std::fs::remove_dir_all(&parent).unwrap();
    }
}
