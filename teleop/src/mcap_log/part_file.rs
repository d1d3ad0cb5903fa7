//! `NAME.mcap.part` while writing, `NAME.mcap` when complete.
//!
//! A log is written under its final name plus `.part`, created exclusively (an existing `.part`
//! is an interrupted recording waiting for `pomdar recover`, never to be clobbered). When the
//! file is complete it is synced and renamed to the final name in one step, then the directory
//! is synced so the rename survives a power cut. A reader therefore never sees a final name on
//! an incomplete file.
//!
//! Without permission to overwrite, the final name is claimed with a hard link, which fails if
//! the name exists (no window between checking and renaming); on a file system without hard
//! links it falls back to check-then-rename.

use std::ffi::OsString;
use std::fs::{File, OpenOptions};
use std::io::ErrorKind;
use std::path::{Path, PathBuf};

use super::LogError;

/// `final_path` with `.part` appended to its file name (`trial.mcap` → `trial.mcap.part`).
pub fn part_path_for(final_path: &Path) -> PathBuf {
    let mut name = OsString::from(final_path.as_os_str());
    name.push(".part");
    PathBuf::from(name)
}

/// Creates `path` for writing; fails with [`LogError::AlreadyExists`] if it exists.
pub(crate) fn create_exclusive(path: &Path, hint: &'static str) -> Result<File, LogError> {
    OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(path)
        .map_err(|e| match e.kind() {
            ErrorKind::AlreadyExists => LogError::AlreadyExists {
                path: path.to_path_buf(),
                hint,
            },
            _ => LogError::io(path, "create", e),
        })
}

/// Fails with [`LogError::AlreadyExists`] if `path` exists.
pub(crate) fn refuse_existing(path: &Path, hint: &'static str) -> Result<(), LogError> {
    match path.try_exists() {
        Ok(false) => Ok(()),
        Ok(true) => Err(LogError::AlreadyExists {
            path: path.to_path_buf(),
            hint,
        }),
        Err(e) => Err(LogError::io(path, "check whether it exists", e)),
    }
}

/// What to say when the final file exists.
pub(crate) const FINAL_EXISTS_HINT: &str =
    "refusing to overwrite a finished log (set overwrite to replace it)";

/// Renames the complete, synced `part` to `final_path` and syncs the directory.
pub(crate) fn commit(part: &Path, final_path: &Path, overwrite: bool) -> Result<(), LogError> {
    let rename_action = || format!("rename to {}", final_path.display());
    if overwrite {
        std::fs::rename(part, final_path).map_err(|e| LogError::io(part, rename_action(), e))?;
    } else {
        match std::fs::hard_link(part, final_path) {
            Ok(()) => {
                std::fs::remove_file(part).map_err(|e| LogError::io(part, "remove", e))?;
            }
            Err(e) if e.kind() == ErrorKind::AlreadyExists => {
                return Err(LogError::AlreadyExists {
                    path: final_path.to_path_buf(),
                    hint: FINAL_EXISTS_HINT,
                });
            }
            // No hard links here (some network or FAT file systems): check, then rename.
            Err(_) => {
                refuse_existing(final_path, FINAL_EXISTS_HINT)?;
                std::fs::rename(part, final_path)
                    .map_err(|e| LogError::io(part, rename_action(), e))?;
            }
        }
    }
    sync_parent_dir(final_path)
}

/// Makes a rename in `path`'s directory durable (Unix; a no-op elsewhere).
fn sync_parent_dir(path: &Path) -> Result<(), LogError> {
    if !cfg!(unix) {
        return Ok(());
    }
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    File::open(dir)
        .and_then(|d| d.sync_all())
        .map_err(|e| LogError::io(dir, "sync directory", e))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    #[test]
    fn part_name_appends_suffix() {
        assert_eq!(
            part_path_for(Path::new("/logs/trial_01.mcap")),
            PathBuf::from("/logs/trial_01.mcap.part")
        );
    }

    #[test]
    fn commit_refuses_to_clobber_unless_told() {
        let dir = std::env::temp_dir().join(format!("mcap_log_commit_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (part, done) = (dir.join("a.mcap.part"), dir.join("a.mcap"));
        std::fs::write(&part, b"new").unwrap();
        std::fs::write(&done, b"old").unwrap();
        let err = commit(&part, &done, false).unwrap_err();
        assert!(matches!(err, LogError::AlreadyExists { .. }), "{err}");
        assert_eq!(std::fs::read(&done).unwrap(), b"old");
        assert!(part.exists());
        commit(&part, &done, true).unwrap();
        assert_eq!(std::fs::read(&done).unwrap(), b"new");
        assert!(!part.exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
