//! Writing a file atomically: readers see the old file or the complete new one, never a part.

use std::io::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Context as _;

/// `path` with `.part` appended.
fn part_path(path: &Path) -> PathBuf {
    let mut name = path.as_os_str().to_os_string();
    name.push(".part");
    PathBuf::from(name)
}

/// Write `bytes` to `path` atomically: `path.part`, fsync, rename over `path`, fsync of the
/// directory. Creates the directory if needed. On failure the `.part` is removed and `path`
/// is untouched.
pub fn write_atomically(path: &Path, bytes: impl AsRef<[u8]>) -> anyhow::Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    std::fs::create_dir_all(&dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let part = part_path(path);
    let written = (|| -> std::io::Result<()> {
        let mut file = std::fs::File::create(&part)?;
        file.write_all(bytes.as_ref())?;
        file.sync_all()?;
        drop(file);
        std::fs::rename(&part, path)?;
        // Make the rename durable too (best effort: not every platform opens directories).
        if let Ok(d) = std::fs::File::open(&dir) {
            d.sync_all().ok();
        }
        Ok(())
    })();
    if let Err(e) = written {
        std::fs::remove_file(&part).ok();
        return Err(e).with_context(|| format!("cannot write {}", path.display()));
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
}
