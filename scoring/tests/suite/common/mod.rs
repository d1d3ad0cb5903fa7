//! Hand-made trial logs for the scoring tests.

#![allow(dead_code)] // each test file uses part of it

use std::collections::BTreeMap;

use scoring::{BaselineTable, TaskCatalog, TrialLog};
use serde_json::{Value, json};

/// Log time of a trial's start event, ns (2024-11-20).
pub const T0_NS: i64 = 1_732_100_000_000_000_000;

/// `seconds` after [`T0_NS`].
pub fn at(seconds: f64) -> i64 {
    T0_NS + (seconds * 1e9).round() as i64
}

/// The `pomdar_trial` metadata of a trial.
pub fn metadata(task: &str, embodiment: &str, practice: bool) -> BTreeMap<String, String> {
    BTreeMap::from([
        ("task".to_string(), task.to_string()),
        ("embodiment".to_string(), embodiment.to_string()),
        ("practice".to_string(), practice.to_string()),
        ("user".to_string(), "u1".to_string()),
        ("operator".to_string(), "op".to_string()),
        ("trial_index".to_string(), "1".to_string()),
    ])
}

/// A trial log: `events` as (seconds after T0, JSON).
pub fn trial(
    file: &str,
    task: &str,
    embodiment: &str,
    practice: bool,
    events: &[(f64, Value)],
) -> TrialLog {
    TrialLog {
        source: file.to_string(),
        metadata: metadata(task, embodiment, practice),
        events: events.iter().map(|(t, e)| (at(*t), e.clone())).collect(),
    }
}

/// start at 0, `progress` values at 1 s, 2 s, ..., stop at `stop_s`.
pub fn stopped_trial(
    file: &str,
    task: &str,
    embodiment: &str,
    progress: &[f64],
    stop_s: f64,
) -> TrialLog {
    let mut events = vec![(0.0, json!({"event": "start"}))];
    for (i, v) in progress.iter().enumerate() {
        events.push(((i + 1) as f64, json!({"event": "progress", "value": v})));
    }
    events.push((stop_s, json!({"event": "stop", "summary": {}})));
    trial(file, task, embodiment, false, &events)
}

pub fn start() -> Value {
    json!({"event": "start"})
}

pub fn stop() -> Value {
    json!({"event": "stop", "summary": {"frames": 10}})
}

pub fn progress(value: f64) -> Value {
    json!({"event": "progress", "value": value})
}

/// A baseline table for tests: every task of the catalog at `mean_s`, except `missing`.
/// Test values, labelled as such in the source note.
pub fn baseline(mean_s: f64, missing: &[&str]) -> BaselineTable {
    let catalog = TaskCatalog::builtin();
    let mut text = String::from(
        "[baseline]\nexample = false\nsource = \"test fixture: hand-made times, not human data\"\n",
    );
    for t in &catalog.tasks {
        if !missing.contains(&t.id.as_str()) {
            text.push_str(&format!(
                "\n[[task]]\nid = \"{}\"\nmean_s = {mean_s:?}\nn = 18\nstd_s = 1.5\n",
                t.id
            ));
        }
    }
    BaselineTable::from_toml_str(&text, "test_baseline.toml", &catalog).unwrap()
}

/// `|a - b| <= tol`, with a readable failure.
pub fn assert_close(a: f64, b: f64, tol: f64, what: &str) {
    assert!((a - b).abs() <= tol, "{what}: {a} is not {b} ± {tol}");
}
