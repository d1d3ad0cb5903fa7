//! Helpers shared by the workspace integration tests in `tests/tests/`.

pub mod command_rule;
pub mod cyclone_peer;
pub mod dependency_rule;
pub mod deployment_guide;
pub mod guide_session;
pub mod interop;
pub mod layer_rule;
pub mod line_console;
pub mod load_turns;
pub mod module_graph;
pub mod netns_lab;
pub mod pomdar_binary;
pub mod stamped_glove;
pub mod station_harness;

use std::path::{Path, PathBuf};

/// The workspace root (the directory holding the top-level `Cargo.toml`).
pub fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_else(|| PathBuf::from("."))
}

/// Every file below `dir` (recursively) whose name ends in `.{extension}`, sorted.
pub fn files_with_extension(dir: &Path, extension: &str) -> std::io::Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(dir) = pending.pop() {
        for entry in std::fs::read_dir(&dir)? {
            let path = entry?.path();
            if path.is_dir() {
                pending.push(path);
            } else if path.extension().is_some_and(|e| e == extension) {
                out.push(path);
            }
        }
    }
    out.sort();
    Ok(out)
}

/// A fresh, empty scratch directory for this test process: `$TMPDIR/pomdar-{name}-{pid}`
/// (whatever an earlier run of the same process id left is removed).
pub fn scratch_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pomdar-{name}-{}", std::process::id()));
    if let Err(e) = std::fs::remove_dir_all(&dir)
        && e.kind() != std::io::ErrorKind::NotFound
    {
        panic!("cannot clear the scratch directory {}: {e}", dir.display());
    }
    if let Err(e) = std::fs::create_dir_all(&dir) {
        panic!("cannot create the scratch directory {}: {e}", dir.display());
    }
    dir
}

/// A path as a command-line argument (test paths are UTF-8).
pub fn path_arg(path: &Path) -> &str {
    match path.to_str() {
        Some(text) => text,
        None => panic!("not UTF-8: {}", path.display()),
    }
}

/// From `pomdar calibrate --simulate`'s stdout: the line comparing the fit with the simulated
/// user's true transform, its scale error (%) and its rotation error (degrees).
pub fn simulated_calibration_errors(stdout: &str) -> (String, f64, f64) {
    let Some(line) = stdout
        .lines()
        .find(|l| l.trim_start().starts_with("scale error"))
    else {
        panic!("no error summary in:\n{stdout}");
    };
    let number_after = |label: &str| -> f64 {
        let Some(at) = line.find(label) else {
            panic!("no '{label}' in {line:?}");
        };
        let rest = &line[at + label.len()..];
        let end = rest
            .find(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | '-' | '+')))
            .unwrap_or(rest.len());
        match rest[..end].parse() {
            Ok(value) => value,
            Err(e) => panic!("'{label}' in {line:?}: {e}"),
        }
    };
    (
        line.to_string(),
        number_after("scale error "),
        number_after("rotation error "),
    )
}

/// The `event` names of a trial log's events, in order.
///
/// # Panics
/// When the log cannot be read or an event is not JSON with an `event` name (a test's
/// failure report).
pub fn trial_event_names(path: &Path) -> Vec<String> {
    let events = teleop::mcap_log::read_trial_events(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    events
        .events
        .iter()
        .map(|(_, text)| {
            let event: serde_json::Value = serde_json::from_str(text)
                .unwrap_or_else(|e| panic!("{}: event {text:?}: {e}", path.display()));
            event["event"]
                .as_str()
                .unwrap_or_else(|| panic!("{}: event without a name: {text}", path.display()))
                .to_string()
        })
        .collect()
}

/// (file, status) of every trial in a console session's manifest (`DIR/session.json`).
///
/// # Panics
/// When the manifest cannot be read or lacks the fields (a test's failure report).
pub fn session_trial_statuses(dir: &Path) -> Vec<(String, String)> {
    let path = dir.join("session.json");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let manifest: serde_json::Value =
        serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let field = |t: &serde_json::Value, key: &str| {
        t[key]
            .as_str()
            .unwrap_or_else(|| panic!("{}: a trial without {key}", path.display()))
            .to_string()
    };
    manifest["trials"]
        .as_array()
        .unwrap_or_else(|| panic!("{}: no trials", path.display()))
        .iter()
        .map(|t| (field(t, "file"), field(t, "status")))
        .collect()
}
