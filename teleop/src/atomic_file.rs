//! Writing a file atomically: readers see the old file or the complete new one, never a part.

use std::io::Write as _;
use std::path::{Path, PathBuf};

/// Writing a file atomically failed: creating its directory, or writing, syncing or renaming
/// its `.part` (then removed).
#[derive(Debug, thiserror::Error)]
#[error("cannot {action} {path}: {source}")]
pub struct AtomicWriteError {
    /// The directory (`create`) or the file (`write`).
    pub path: PathBuf,
    /// What was being done: `create` (the directory) or `write` (the file).
    pub action: &'static str,
    /// The OS error.
    #[source]
    pub source: std::io::Error,
}

/// `path` with `.part` appended.
fn part_path(path: &Path) -> PathBuf {
    let mut name = path.as_os_str().to_os_string();
    name.push(".part");
    PathBuf::from(name)
}

/// Write `bytes` to `path` atomically: `path.part`, fsync, rename over `path`, fsync of the
/// directory. Creates the directory if needed. On failure the `.part` is removed and `path`
/// is untouched. With the test-only slow disk set
/// ([`SLOW_DISK_ENV`](crate::mcap_log::slow_disk::SLOW_DISK_ENV)), the write takes that much
/// longer.
pub fn write_atomically(path: &Path, bytes: impl AsRef<[u8]>) -> Result<(), AtomicWriteError> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    if let Err(source) = std::fs::create_dir_all(&dir) {
        return Err(AtomicWriteError {
            path: dir,
            action: "create",
            source,
        });
    }
    let part = part_path(path);
    let written = (|| -> std::io::Result<()> {
        let mut file = std::fs::File::create(&part)?;
        file.write_all(bytes.as_ref())?;
        crate::mcap_log::slow_disk::stall();
        file.sync_all()?;
        drop(file);
        std::fs::rename(&part, path)?;
        // Make the rename durable too (best effort: not every platform opens directories).
        if let Ok(d) = std::fs::File::open(&dir) {
            d.sync_all().ok();
        }
        Ok(())
    })();
    if let Err(source) = written {
        std::fs::remove_file(&part).ok();
        return Err(AtomicWriteError {
            path: path.to_path_buf(),
            action: "write",
            source,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    #[test]
    fn atomic_writes_replace_the_file_and_leave_no_part() {
        let dir = std::env::temp_dir().join(format!("pomdar-atomic-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        let path = dir.join("sub/alice.toml");
        write_atomically(&path, "a = 1\n").unwrap();
        write_atomically(&path, b"a = 2\n").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "a = 2\n");
        assert!(!part_path(&path).exists());
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn errors_name_the_directory_or_the_file() {
        let dir = std::env::temp_dir().join(format!("pomdar-atomic-err-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("plain");
        std::fs::write(&file, "x").unwrap();
        let err = write_atomically(&file.join("sub/alice.toml"), "a = 1\n").unwrap_err();
        assert_eq!(err.action, "create");
        let text = err.to_string();
        assert!(
            text.starts_with(&format!("cannot create {}: ", file.join("sub").display())),
            "{text}"
        );
        let err = write_atomically(&dir, "a = 1\n").unwrap_err();
        assert!(
            err.to_string()
                .starts_with(&format!("cannot write {}: ", dir.display())),
            "{err}"
        );
        std::fs::remove_dir_all(&dir).ok();
    }
}
