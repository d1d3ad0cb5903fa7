//! Helpers for tests that read `../shared/reference/` beside the checkout.

#![allow(dead_code)] // each test binary uses a part

pub mod poses;
pub mod recording;

use std::path::PathBuf;

/// `../shared/reference/` relative to the workspace root, or `None` (with a printed skip
/// notice naming the path) when it is absent, as on a user's machine. CI fails when it is
/// absent (`.ci/run` checks), so these tests always run there.
pub fn reference_dir(test: &str) -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared/reference");
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!(
            "SKIPPED {test}: reference data not found at {} (it exists beside the checkout in CI \
             and developer sessions only)",
            dir.display()
        );
        None
    }
}
