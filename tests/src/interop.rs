//! Reference data and independent readers for the workspace tests.

use std::path::{Path, PathBuf};

use crate::workspace_root;

/// `../shared/reference/NAME` beside the checkout, or `None` (with a printed skip notice)
/// where it is absent; `.ci/run` refuses to run without it.
pub fn reference_file(name: &str) -> Option<PathBuf> {
    let path = workspace_root().join("../shared/reference").join(name);
    if path.is_file() {
        Some(path)
    } else {
        eprintln!("SKIPPED: {} not found", path.display());
        None
    }
}

/// The independent readers' JSON report on `path` (`tests/interop/read_mcap.py`: Python
/// `mcap` + `mcap-ros2-support`, and `rosbags`): per reader, message counts per topic.
/// Panics when a reader fails. `None`, with a notice, where the interop Python is not
/// installed — never in CI, where `.ci/run` installs it first.
pub fn independent_readers(path: &Path) -> Option<serde_json::Value> {
    let python = workspace_root().join("target/interop-venv/bin/python");
    if !python.is_file() {
        assert!(
            std::env::var_os("CI").is_none(),
            "CI must run tests/interop/setup_python.sh first"
        );
        eprintln!(
            "SKIPPED: independent readers ({} not found; run tests/interop/setup_python.sh)",
            python.display()
        );
        return None;
    }
    let output = std::process::Command::new(python)
        .arg(workspace_root().join("tests/interop/read_mcap.py"))
        .arg(path)
        .output()
        .unwrap_or_else(|e| panic!("cannot run the interop readers: {e}"));
    let report: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap_or_else(|_| {
        panic!(
            "reader output: {} {}",
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        )
    });
    assert!(output.status.success(), "{report}");
    Some(report)
}

/// Assert that both independent readers counted, on every topic, what our reader counts.
pub fn assert_readers_agree(report: &serde_json::Value, ours: &teleop::mcap_log::TrialReader) {
    for reader in ["mcap_ros2", "rosbags"] {
        for topic in ours.topics() {
            assert_eq!(
                report[reader]["counts"][&topic.topic].as_u64(),
                Some(topic.message_count),
                "{reader} on {}",
                topic.topic
            );
        }
    }
}
