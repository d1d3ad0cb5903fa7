//! Fuzzing of the scoring inputs on stable Rust: the task catalog, the rules and a baseline
//! table, mutated key by key (`fuzz/support/toml_mutation.rs`) and as text, and trial logs
//! generated structure-aware (metadata and event sequences of every kind, in and out of
//! order, with wrong fields and non-objects). No panic; errors are `Err`; what loads is
//! consistent — rules validate against their catalog, a baseline table survives its own
//! writer, a checked trial has a positive finite time with its marks inside it, and its score
//! is finite with correctness in [0, 1].
//!
//! CI budget: 1,500 cases per property; `PROPTEST_CASES=N` for longer.

use crate::config_oracle;
use crate::toml_mutation;

use std::collections::BTreeMap;

use proptest::prelude::*;
use scoring::{POMDAR_TASKS_TOML, TrialLog};
use serde_json::{Value, json};
use toml_mutation::{budget, edits, mutate};

const S: i64 = 1_000_000_000;

fn shipped(path: &str) -> String {
    std::fs::read_to_string(format!("{}/../{path}", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

use config_oracle::BASELINE;

fn event() -> impl Strategy<Value = (i64, Value)> {
    let kind = prop::sample::select(vec![
        "start", "progress", "drop", "abort", "note", "stop", "pause", "",
    ]);
    let number = prop_oneof![
        Just(json!(0)),
        Just(json!(1)),
        Just(json!(-1)),
        Just(json!(1e300)),
        Just(json!(-1e300)),
        Just(json!(u64::MAX)),
        Just(json!("1")),
        Just(Value::Null),
        (-500.0f64..500.0).prop_map(|v| json!(v)),
    ];
    let body = (kind, number, any::<bool>()).prop_map(|(kind, value, text)| {
        let mut e = json!({"event": kind, "value": value});
        if text {
            e["text"] = json!("operator note");
            e["reason"] = json!(42);
        }
        e
    });
    let shape = prop_oneof![
        8 => body,
        1 => Just(json!(["start"])),
        1 => Just(json!({"value": 1})),
        1 => Just(json!({"event": 3})),
    ];
    (0i64..120 * S, shape)
}

fn trial_logs() -> impl Strategy<Value = TrialLog> {
    let task = prop::sample::select(vec!["V1", "V3", "C2", "H4", "G2", "G6", "X9", ""]);
    let embodiment = prop::sample::select(vec!["orca_full", "human", "orca_2", ""]);
    let practice = prop::sample::select(vec!["true", "false", "yes", ""]);
    (
        task,
        embodiment,
        practice,
        prop::collection::vec(event(), 0..12),
        any::<bool>(),
    )
        .prop_map(|(task, embodiment, practice, mut events, sorted)| {
            if sorted {
                events.sort_by_key(|(t, _)| *t);
            }
            TrialLog {
                source: "fuzz.mcap".into(),
                metadata: BTreeMap::from([
                    ("task".into(), task.into()),
                    ("embodiment".into(), embodiment.into()),
                    ("practice".into(), practice.into()),
                ]),
                events,
            }
        })
}

/// A trial built to pass the checks, so scoring itself gets exercised: start, some
/// progress, drops and notes, then stop or abort.
fn valid_trial_logs() -> impl Strategy<Value = TrialLog> {
    let task = prop::sample::select(vec![
        "V1", "V2", "V3", "H1", "C1", "C4", "H4", "H5", "G1", "G3", "G6",
    ]);
    let mark = prop_oneof![
        (-1000.0f64..1000.0).prop_map(|v| json!({"event": "progress", "value": v})),
        Just(json!({"event": "drop"})),
        Just(json!({"event": "note", "text": "n"})),
    ];
    (
        task,
        prop::collection::vec(mark, 0..10),
        1i64..10_000 * S,
        any::<bool>(),
    )
        .prop_map(|(task, marks, length, abort)| {
            let mut events = vec![(0, json!({"event": "start"}))];
            let n = marks.len() as i64 + 1;
            for (i, m) in marks.into_iter().enumerate() {
                events.push((length * (i as i64 + 1) / n, m));
            }
            let end = if abort { "abort" } else { "stop" };
            events.push((length, json!({"event": end})));
            TrialLog {
                source: "fuzz.mcap".into(),
                metadata: BTreeMap::from([
                    ("task".into(), task.into()),
                    ("embodiment".into(), "orca_full".into()),
                    ("practice".into(), "false".into()),
                ]),
                events,
            }
        })
}

proptest! {
    #![proptest_config(budget(1500))]

    // Each mutated file is tried as every kind of scoring file.

    #[test]
    fn mutated_catalogs_load_and_carry_rules_or_fail(
        shipped_copy in any::<bool>(),
        edits in prop::collection::vec(edits(), 1..4),
    ) {
        let seed = if shipped_copy {
            shipped("launch_configs/tasks/pomdar_tasks.toml")
        } else {
            POMDAR_TASKS_TOML.to_string()
        };
        config_oracle::check_text(&mutate(&seed, &edits));
    }

    #[test]
    fn mutated_rules_load_and_validate_or_fail(edits in prop::collection::vec(edits(), 1..4)) {
        config_oracle::check_text(&mutate(
            &shipped("launch_configs/scoring/default_rules.toml"),
            &edits,
        ));
    }

    #[test]
    fn mutated_baselines_load_and_survive_their_writer_or_fail(
        edits in prop::collection::vec(edits(), 1..4),
    ) {
        config_oracle::check_text(&mutate(BASELINE, &edits));
    }

    #[test]
    fn generated_trial_logs_check_and_score_consistently_or_fail(log in trial_logs()) {
        config_oracle::check_trial(&log);
        // The JSON form the cargo-fuzz target reads carries the same log (numbers may come
        // back an ulp apart: serde_json's default float parsing is not exact).
        let events: Vec<Value> = log.events.iter().map(|(t, e)| json!([t, e])).collect();
        let text = json!({"metadata": log.metadata, "events": events}).to_string();
        let back = config_oracle::trial_log_from_json(text.as_bytes()).unwrap();
        prop_assert_eq!(&back.metadata, &log.metadata);
        let times = |l: &TrialLog| l.events.iter().map(|(t, _)| *t).collect::<Vec<_>>();
        prop_assert_eq!(times(&back), times(&log));
    }

    #[test]
    fn valid_trial_logs_score_within_range(log in valid_trial_logs()) {
        config_oracle::check_trial(&log);
    }
}
