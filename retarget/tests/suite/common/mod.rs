//! Helpers for tests that read `../shared/reference/` beside the checkout.

#![allow(dead_code)] // each test binary uses a part

pub mod poses;
pub mod recording;

use std::path::{Path, PathBuf};

/// `../shared/reference/NAME` relative to the workspace root, or `None` (with a printed skip
/// notice naming the path) when it is absent, as on a user's machine. Panics instead under CI
/// (`CI=true`, which `.ci/run` sets, or `CI=1`): there the file must exist and the
/// test must run.
pub fn reference_file(test: &str, name: &str) -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared/reference");
    // `CI=true` or `CI=1` is CI (as `pomdar_tests::interop::under_ci` reads it).
    let ci =
        std::env::var("CI").is_ok_and(|v| v.trim() == "1" || v.trim().eq_ignore_ascii_case("true"));
    reference_file_in(&dir, name, test, ci)
}

/// `DIR/NAME` if it is a file; else `None` with a skip notice for `test`, or a panic naming
/// the path when `ci`. (The decision of [`reference_file`], with the environment as a
/// parameter.)
pub fn reference_file_in(dir: &Path, name: &str, test: &str, ci: bool) -> Option<PathBuf> {
    let path = dir.join(name);
    if path.is_file() {
        return Some(path);
    }
    assert!(
        !ci,
        "{test}: CI needs the reference file {} (../shared/reference beside the checkout)",
        path.display()
    );
    eprintln!(
        "SKIPPED {test}: reference data not found at {} (it exists beside the checkout in CI \
         and developer sessions only)",
        path.display()
    );
    None
}
