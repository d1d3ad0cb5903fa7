//! Reference data and independent readers for the workspace tests.

use std::path::{Path, PathBuf};

use msgs::{
    DiagnosticArray, Float32MultiArray, Float64MultiArray, JointState, MarkerArray, PoseArray,
    PoseStamped, RosMessage, StringMsg, TFMessage,
};
use serde_json::Value;
use teleop::mcap_log::{LoggedMessage, TrialReader};

use crate::workspace_root;

/// `../shared/reference/NAME` beside the checkout, or `None` (with a printed skip notice)
/// where it is absent. Panics instead under `CI` (see [`under_ci`]): `.ci/run` refuses to run
/// without the directory, and a file missing from it is a failure, never a silent skip.
pub fn reference_file(name: &str) -> Option<PathBuf> {
    let dir = workspace_root().join("../shared/reference");
    reference_file_in(&dir, name, under_ci())
}

/// Whether the tests run under CI (`CI=true`, as `.ci/run` sets it, or `CI=1`): there a
/// missing tool or reference file fails the test instead of skipping it.
pub fn under_ci() -> bool {
    ci_flag(std::env::var("CI").ok().as_deref())
}

/// Whether a `CI` value means CI: `true` or `1` (any case); unset, empty, `false`, `0` or
/// anything else does not.
pub fn ci_flag(value: Option<&str>) -> bool {
    value.is_some_and(|v| v.trim() == "1" || v.trim().eq_ignore_ascii_case("true"))
}

/// `DIR/NAME` if it is a file; else `None` with a skip notice, or a panic naming the path
/// when `ci`. (The decision of [`reference_file`], with the environment as a parameter.)
pub fn reference_file_in(dir: &Path, name: &str, ci: bool) -> Option<PathBuf> {
    let path = dir.join(name);
    if path.is_file() {
        return Some(path);
    }
    assert!(
        !ci,
        "CI needs the reference file {} (../shared/reference beside the checkout)",
        path.display()
    );
    eprintln!("SKIPPED: {} not found", path.display());
    None
}

/// The interop tools' Python (`target/interop-venv`, installed from PyPI by
/// `tests/interop/setup_python.sh`), or `None` with a printed skip notice where it is not
/// installed. Panics instead when the `CI` environment variable is set: `.ci/run` installs it
/// first, so there a missing tool is a failure, never a silent skip.
pub fn interop_python() -> Option<PathBuf> {
    let python = workspace_root().join("target/interop-venv/bin/python");
    if python.is_file() {
        return Some(python);
    }
    assert!(
        !under_ci(),
        "CI must run tests/interop/setup_python.sh first ({} not found)",
        python.display()
    );
    eprintln!(
        "SKIPPED: interop tools ({} not found; run tests/interop/setup_python.sh)",
        python.display()
    );
    None
}

/// The path of `tests/interop/NAME`.
pub fn interop_script(name: &str) -> PathBuf {
    workspace_root().join("tests/interop").join(name)
}

/// Run `tests/interop/SCRIPT ARGS...` with the interop Python and parse the JSON it prints.
/// Panics, with its output, when it fails or prints something else.
pub fn run_interop_script(python: &Path, script: &str, args: &[&std::ffi::OsStr]) -> Value {
    let output = std::process::Command::new(python)
        .arg(interop_script(script))
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run {script}: {e}"));
    let report: Value = serde_json::from_slice(&output.stdout).unwrap_or_else(|_| {
        panic!(
            "{script} output: {} {}",
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        )
    });
    assert!(
        output.status.success(),
        "{script} failed: {report} {}",
        String::from_utf8_lossy(&output.stderr)
    );
    report
}

/// The independent readers' JSON report on `path` (`tests/interop/read_mcap.py`: Python
/// `mcap` + `mcap-ros2-support`, and `rosbags`): per reader, message counts per topic.
/// Panics when a reader fails. `None` where the interop Python is not installed (see
/// [`interop_python`]).
pub fn independent_readers(path: &Path) -> Option<Value> {
    let python = interop_python()?;
    Some(run_interop_script(
        &python,
        "read_mcap.py",
        &[path.as_os_str()],
    ))
}

/// As [`independent_readers`], with every decoded message per topic (`values`) as well; see
/// [`assert_readers_decode_as_we_do`].
pub fn independent_readers_with_values(path: &Path) -> Option<Value> {
    let python = interop_python()?;
    Some(run_interop_script(
        &python,
        "read_mcap.py",
        &["--values".as_ref(), path.as_os_str()],
    ))
}

/// Assert that both independent readers counted, on every topic, what our reader counts.
pub fn assert_readers_agree(report: &Value, ours: &TrialReader) {
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

/// A logged message decoded by this project's `msgs` types, as JSON keyed by the ROS field
/// names; an error for a type `msgs` does not have or a payload it cannot decode.
pub fn decoded_as_json(message: &LoggedMessage) -> Result<Value, String> {
    fn as_json<M: RosMessage + serde::Serialize>(message: &LoggedMessage) -> Result<Value, String> {
        let decoded: M = message.decode().map_err(|e| e.to_string())?;
        serde_json::to_value(decoded).map_err(|e| e.to_string())
    }
    if message.is::<Float32MultiArray>() {
        as_json::<Float32MultiArray>(message)
    } else if message.is::<Float64MultiArray>() {
        as_json::<Float64MultiArray>(message)
    } else if message.is::<JointState>() {
        as_json::<JointState>(message)
    } else if message.is::<PoseStamped>() {
        as_json::<PoseStamped>(message)
    } else if message.is::<PoseArray>() {
        as_json::<PoseArray>(message)
    } else if message.is::<StringMsg>() {
        as_json::<StringMsg>(message)
    } else if message.is::<TFMessage>() {
        as_json::<TFMessage>(message)
    } else if message.is::<MarkerArray>() {
        as_json::<MarkerArray>(message)
    } else if message.is::<DiagnosticArray>() {
        as_json::<DiagnosticArray>(message)
    } else {
        Err(format!(
            "no msgs type for {} on {}",
            message.type_name, message.topic
        ))
    }
}

/// The first difference between two decoded messages (numbers compare as `f64`, exactly), as
/// "at PATH: A != B"; `None` when they are equal.
pub fn json_difference(path: &str, ours: &Value, theirs: &Value) -> Option<String> {
    match (ours, theirs) {
        (Value::Number(a), Value::Number(b)) if a.as_f64() == b.as_f64() => None,
        (Value::Object(a), Value::Object(b)) => {
            let keys: std::collections::BTreeSet<&String> = a.keys().chain(b.keys()).collect();
            keys.into_iter().find_map(|k| {
                json_difference(
                    &format!("{path}.{k}"),
                    a.get(k).unwrap_or(&Value::Null),
                    b.get(k).unwrap_or(&Value::Null),
                )
            })
        }
        (Value::Array(a), Value::Array(b)) if a.len() == b.len() => a
            .iter()
            .zip(b)
            .enumerate()
            .find_map(|(i, (x, y))| json_difference(&format!("{path}[{i}]"), x, y)),
        (a, b) if a == b => None,
        (a, b) => Some(format!("at {path}: ours {a} != theirs {b}")),
    }
}

/// Assert that both independent readers (a report with `values`) decoded every message of
/// `ours`, topic by topic in log-time order, to exactly the values this project's `msgs` types
/// decode: same field names, same numbers, same strings. Panics naming the reader, the topic,
/// the message and the first differing field.
pub fn assert_readers_decode_as_we_do(report: &Value, ours: &TrialReader) {
    for reader in ["mcap_ros2", "rosbags"] {
        for topic in ours.topics() {
            let theirs = report[reader]["values"][&topic.topic]
                .as_array()
                .map_or(&[][..], Vec::as_slice);
            let mine: Vec<&LoggedMessage> = ours.messages_on(&topic.topic).collect();
            assert_eq!(
                theirs.len(),
                mine.len(),
                "{reader} decoded {} messages on {}, we read {}",
                theirs.len(),
                topic.topic,
                mine.len()
            );
            for (i, (message, their_value)) in mine.iter().zip(theirs).enumerate() {
                let our_value = decoded_as_json(message)
                    .unwrap_or_else(|e| panic!("{} message {i}: {e}", topic.topic));
                if let Some(difference) = json_difference("", &our_value, their_value) {
                    panic!(
                        "{reader} decodes {} message {i} ({}) differently: {difference}",
                        topic.topic, topic.type_name
                    );
                }
            }
        }
    }
}

/// Node.js for the JavaScript interop scripts (`tests/interop/js/`: Foxglove's WebSocket client,
/// MCAP reader and ROS 2 decoders, installed from npm by `tests/interop/setup_node.sh`), or
/// `None` with a printed skip notice where node or the packages are missing. Panics instead
/// when the `CI` environment variable is set (`.ci/run` installs them first).
pub fn interop_node() -> Option<PathBuf> {
    let js = workspace_root().join("tests/interop/js");
    let installed = js.join("node_modules/.installed-package-lock.json");
    let node = std::env::var_os("PATH").and_then(|path| {
        std::env::split_paths(&path)
            .map(|dir| dir.join("node"))
            .find(|candidate| candidate.is_file())
    });
    let missing = match (&node, installed.is_file()) {
        (Some(node), true) => return Some(node.clone()),
        (None, _) => "node is not on PATH".to_string(),
        (Some(_), false) => format!("{} not found", installed.display()),
    };
    assert!(
        !under_ci(),
        "CI must run tests/interop/setup_node.sh first ({missing})"
    );
    eprintln!("SKIPPED: JavaScript interop tools ({missing}; run tests/interop/setup_node.sh)");
    None
}

/// The path of `tests/interop/js/NAME`.
pub fn interop_js_script(name: &str) -> PathBuf {
    workspace_root().join("tests/interop/js").join(name)
}

/// The JSON lines a script printed; panics naming the script and the line that is not JSON.
pub fn json_lines(script: &str, stdout: &[u8]) -> Vec<Value> {
    String::from_utf8_lossy(stdout)
        .lines()
        .filter(|line| !line.trim().is_empty())
        .map(|line| {
            serde_json::from_str(line).unwrap_or_else(|e| {
                panic!("{script} printed a line that is not JSON ({e}): {line}")
            })
        })
        .collect()
}

/// Foxglove's MCAP reader and ROS 2 decoders on `path` (`tests/interop/js/read_mcap.mjs`): one
/// `{"kind":"channel",...}` per channel, then one `{"kind":"message","topic",...,"message"}`
/// per message in log-time order. Panics with the script's output when it fails. `None` where
/// node or the packages are not installed (see [`interop_node`]).
pub fn foxglove_mcap_reader(path: &Path) -> Option<Vec<Value>> {
    let node = interop_node()?;
    let output = std::process::Command::new(node)
        .arg(interop_js_script("read_mcap.mjs"))
        .arg(path)
        .output()
        .unwrap_or_else(|e| panic!("cannot run read_mcap.mjs: {e}"));
    assert!(
        output.status.success(),
        "read_mcap.mjs failed on {}: {}",
        path.display(),
        String::from_utf8_lossy(&output.stderr)
    );
    Some(json_lines("read_mcap.mjs", &output.stdout))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_present_reference_file_is_found_with_or_without_ci() {
        let root = workspace_root();
        for ci in [false, true] {
            assert_eq!(
                reference_file_in(&root, "Cargo.toml", ci),
                Some(root.join("Cargo.toml"))
            );
        }
    }

    #[test]
    fn a_missing_reference_file_is_skipped_outside_ci() {
        assert_eq!(
            reference_file_in(&workspace_root(), "no_such_reference.mcap", false),
            None
        );
    }

    #[test]
    #[should_panic(expected = "no_such_reference.mcap")]
    fn a_missing_reference_file_fails_under_ci() {
        reference_file_in(&workspace_root(), "no_such_reference.mcap", true);
    }

    #[test]
    fn a_directory_is_not_a_reference_file() {
        assert_eq!(reference_file_in(&workspace_root(), "tests", false), None);
    }

    #[test]
    fn only_true_or_1_means_ci() {
        for yes in ["true", "1", "TRUE", " True "] {
            assert!(ci_flag(Some(yes)), "{yes:?}");
        }
        for no in [
            None,
            Some(""),
            Some("false"),
            Some("0"),
            Some("no"),
            Some("yes"),
        ] {
            assert!(!ci_flag(no), "{no:?}");
        }
    }
}
