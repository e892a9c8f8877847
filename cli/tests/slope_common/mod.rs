//! What the tests of `dismech slope` share: the shipped terrain and a
//! scratch folder per test.

use std::path::{Path, PathBuf};

/// The shipped terrain (`examples/data/terrain/jacksboro_fault.asc`).
pub fn terrain_file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/data/terrain/jacksboro_fault.asc")
}

/// An empty folder `dismech-slope-{name}-{pid}` in the temporary folder.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("dismech-slope-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}
