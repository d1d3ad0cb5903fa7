//! The cargo-fuzz targets in `fuzz/` are not built by the workspace (they need nightly Rust,
//! docs/FUZZING.md), so nothing else would notice one going stale: every target the fuzz
//! manifest lists exists, every oracle module a target includes exists, and every oracle the
//! stable fuzz tests use has a cargo-fuzz target.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use pomdar_tests::{files_with_extension, workspace_root};

/// The files a source file includes with `#[path = "..."]`, resolved.
fn included(file: &Path) -> Vec<PathBuf> {
    let text = std::fs::read_to_string(file).unwrap();
    text.lines()
        .filter_map(|line| line.trim().strip_prefix("#[path = \""))
        .filter_map(|rest| rest.split('"').next())
        .map(|relative| file.parent().unwrap().join(relative))
        .collect()
}

#[test]
fn every_fuzz_target_and_the_oracles_it_includes_exist() {
    let root = workspace_root();
    let manifest: toml::Table = std::fs::read_to_string(root.join("fuzz/Cargo.toml"))
        .unwrap()
        .parse()
        .unwrap();
    let bins = manifest["bin"].as_array().unwrap();
    assert!(bins.len() >= 9, "{} fuzz targets", bins.len());
    let mut covered = BTreeSet::new();
    for bin in bins {
        let target = root.join("fuzz").join(bin["path"].as_str().unwrap());
        assert!(target.is_file(), "{} is missing", target.display());
        for oracle in included(&target) {
            let oracle = oracle.canonicalize().unwrap_or_else(|e| {
                panic!("{} includes {}: {e}", target.display(), oracle.display())
            });
            covered.insert(oracle);
        }
    }
    // Every oracle module beside the crates' tests has a long-run target.
    for crate_dir in ["msgs", "retarget", "calibration", "scoring", "teleop"] {
        let tests = root.join(crate_dir).join("tests");
        for file in files_with_extension(&tests, "rs").unwrap() {
            let is_oracle = file.file_name().is_some_and(|n| n == "mod.rs")
                && file
                    .parent()
                    .and_then(|d| d.file_name())
                    .and_then(|n| n.to_str())
                    .is_some_and(|n| n.ends_with("_oracle"));
            if is_oracle {
                assert!(
                    covered.contains(&file.canonicalize().unwrap()),
                    "{} has no cargo-fuzz target in fuzz/Cargo.toml",
                    file.display()
                );
            }
        }
    }
}
