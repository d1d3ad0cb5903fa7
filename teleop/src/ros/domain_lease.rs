//! ROS domain ids held on this machine: an all-in-one run or a test that needs a domain of its
//! own leases one that no other holder on the machine has, so that runs side by side (two test
//! processes, tests of one binary in parallel) never discover each other's participants.
//!
//! A lease is an exclusive lock on `$TMPDIR/pomdar-domain-leases/<id>.lock`, held by this
//! process until it exits (the operating system releases it then, however the process ends).
//! Nothing is written to the files: a stale file is an unlocked file, free to lease again.

use std::fs::{File, OpenOptions, TryLockError};
use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Domain ids for tests: below [`ALL_IN_ONE_DOMAINS`] and away from 0, the lab's usual.
pub const TEST_DOMAINS: RangeInclusive<u16> = 1..=149;

/// Domain ids of all-in-one runs (the demo, a simulated trial or calibration) given no
/// `--domain-id`.
pub const ALL_IN_ONE_DOMAINS: RangeInclusive<u16> = 150..=229;

/// The locks this process holds (kept open until exit).
static HELD: Mutex<Vec<File>> = Mutex::new(Vec::new());

/// Why no domain could be leased.
#[derive(Debug, thiserror::Error)]
pub enum LeaseError {
    /// The lease directory or a lock file cannot be created.
    #[error("domain lease file {path}: {source}")]
    Io {
        /// The file or directory.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// Every id of the range is held by this or another process.
    #[error("every ROS domain id in {first}–{last} is leased on this machine")]
    Exhausted {
        /// The range's first id.
        first: u16,
        /// The range's last id.
        last: u16,
    },
}

/// The directory of the lock files.
fn lease_dir() -> PathBuf {
    std::env::temp_dir().join("pomdar-domain-leases")
}

/// A domain id from `range` that no other lease holder on this machine has, held by this
/// process until it exits. Each call leases a new id.
pub fn lease_domain(range: RangeInclusive<u16>) -> Result<u16, LeaseError> {
    lease_in(&lease_dir(), range)
}

/// [`lease_domain`] with the lock files in `dir`.
fn lease_in(dir: &Path, range: RangeInclusive<u16>) -> Result<u16, LeaseError> {
    std::fs::create_dir_all(dir).map_err(|source| LeaseError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut held = HELD
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    for id in range.clone() {
        let path = dir.join(format!("{id}.lock"));
        let file = OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&path)
            .map_err(|source| LeaseError::Io {
                path: path.clone(),
                source,
            })?;
        match file.try_lock() {
            Ok(()) => {
                held.push(file);
                return Ok(id);
            }
            Err(TryLockError::WouldBlock) => {}
            Err(TryLockError::Error(source)) => return Err(LeaseError::Io { path, source }),
        }
    }
    Err(LeaseError::Exhausted {
        first: *range.start(),
        last: *range.end(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("pomdar-lease-{name}-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        dir
    }

    #[test]
    fn each_lease_is_a_new_id_until_the_range_is_spent() {
        let dir = scratch("spent");
        let first = lease_in(&dir, 7..=8).unwrap();
        let second = lease_in(&dir, 7..=8).unwrap();
        assert_eq!((first, second), (7, 8));
        let e = lease_in(&dir, 7..=8).unwrap_err();
        assert!(
            matches!(e, LeaseError::Exhausted { first: 7, last: 8 }),
            "{e}"
        );
        assert!(e.to_string().contains("7–8"), "{e}");
    }

    #[test]
    fn an_id_locked_elsewhere_is_passed_over() {
        let dir = scratch("elsewhere");
        std::fs::create_dir_all(&dir).unwrap();
        // Another holder: a lock on its own open file, as another process would have.
        let other = File::create(dir.join("3.lock")).unwrap();
        other.try_lock().unwrap();
        assert_eq!(lease_in(&dir, 3..=4).unwrap(), 4);
    }
}
