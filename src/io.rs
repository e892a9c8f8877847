//! Files written whole or not at all: write-then-rename, so that a reader
//! never sees half a file (the grids' writer uses it).

use std::io::Write;
use std::path::Path;

use crate::error::{DismechError, Result};

fn output_error(path: &Path, e: impl std::fmt::Display) -> DismechError {
    DismechError::Output {
        path: path.display().to_string(),
        message: e.to_string(),
    }
}

/// Write `contents` to `path` through a temporary file in the same folder
/// and a rename; the folder is created if needed.
///
/// # Errors
/// [`DismechError::Output`] naming the path when the folder cannot be
/// created or the temporary file cannot be written, synced or renamed
/// (the temporary file is then removed).
pub fn write_atomically(path: &Path, contents: &[u8]) -> Result<()> {
    if let Some(dir) = path.parent() {
        if !dir.as_os_str().is_empty() {
            std::fs::create_dir_all(dir).map_err(|e| output_error(dir, e))?;
        }
    }
    let file_name = path
        .file_name()
        .ok_or_else(|| output_error(path, "the path has no file name"))?;
    let mut tmp_name = std::ffi::OsString::from(".");
    tmp_name.push(file_name);
    tmp_name.push(format!(".tmp{}", std::process::id()));
    let tmp = path.with_file_name(tmp_name);
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(contents)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(output_error(path, e));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atomic_write_leaves_only_the_final_file() {
        let dir = std::env::temp_dir().join(format!("dismech-atomic-{}", std::process::id()));
        let path = dir.join("a.txt");
        write_atomically(&path, b"hello").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"hello");
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names.len(), 1);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
