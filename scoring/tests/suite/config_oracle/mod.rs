//! What must hold for the scoring inputs: whatever loads is consistent — rules validate
//! against their catalog, a baseline table survives its own writer, a checked trial has a
//! positive finite time with its marks inside it, and its score is finite with correctness in
//! [0, 1].
//!
//! Shared by the stable proptest fuzzing (`tests/fuzz_config.rs`) and the cargo-fuzz target
//! (`fuzz/fuzz_targets/scoring_files.rs`).

use std::collections::BTreeMap;

use scoring::{BaselineTable, ScoringRules, TaskCatalog, TrialLog, TrialRecord, score_record};

/// A baseline table for two tasks of the built-in catalog.
pub const BASELINE: &str = "[baseline]\nexample = false\nsource = \"lab, 2026-11\"\n\n[[task]]\nid = \"V1\"\nmean_s = 10.0\nstd_s = 1.5\nn = 5\n\n[[task]]\nid = \"G2\"\nmean_s = 7.5\nn = 3\n";

/// `text` as each kind of scoring file (with the built-in catalog where one is needed);
/// whatever loads is checked.
pub fn check_text(text: &str) {
    let builtin = TaskCatalog::builtin();
    if let Ok(catalog) = TaskCatalog::from_toml_str(text, "tasks.toml") {
        let _ = ScoringRules::from_toml_str("", "rules.toml", &catalog);
        let _ = BaselineTable::from_toml_str(BASELINE, "base.toml", &catalog);
    }
    if let Ok(rules) = ScoringRules::from_toml_str(text, "rules.toml", &builtin) {
        assert!(rules.validate("rules.toml", &builtin).is_ok());
    }
    if let Ok(table) = BaselineTable::from_toml_str(text, "base.toml", &builtin) {
        let again = BaselineTable::from_toml_str(&table.to_toml(), "base.toml", &builtin);
        assert_eq!(again.ok().as_ref(), Some(&table), "baseline round trip");
    }
}

/// A trial log from JSON (`{"metadata": {..}, "events": [[ns, {..}], ..]}`), for byte-level
/// fuzzers; `None` when the JSON is not of that shape.
pub fn trial_log_from_json(bytes: &[u8]) -> Option<TrialLog> {
    let value: serde_json::Value = serde_json::from_slice(bytes).ok()?;
    let metadata: BTreeMap<String, String> = value
        .get("metadata")?
        .as_object()?
        .iter()
        .filter_map(|(k, v)| Some((k.clone(), v.as_str()?.to_string())))
        .collect();
    let events = value
        .get("events")?
        .as_array()?
        .iter()
        .filter_map(|e| Some((e.get(0)?.as_i64()?, e.get(1)?.clone())))
        .collect();
    Some(TrialLog {
        source: "fuzz.mcap".into(),
        metadata,
        events,
    })
}

pub fn check_trial(log: &TrialLog) {
    let catalog = TaskCatalog::builtin();
    let Ok(record) = TrialRecord::from_log(log, &catalog) else {
        return;
    };
    let time = record.time_s();
    assert!(time.is_finite() && time > 0.0, "trial time {time}");
    assert!(
        record
            .marks
            .iter()
            .all(|(t, _)| *t >= record.start_ns && *t <= record.end_ns),
        "a mark outside the trial"
    );
    let baseline = BaselineTable::from_toml_str(BASELINE, "base.toml", &catalog).unwrap();
    let rules = ScoringRules::default();
    for baseline in [None, Some(&baseline)] {
        if let Ok(score) = score_record(&record, &catalog, baseline, &rules) {
            assert!((0.0..=1.0).contains(&score.correctness), "{score:?}");
            assert!(
                score.score.is_none_or(f64::is_finite) && score.time_s.is_finite(),
                "{score:?}"
            );
            assert!(score.speed.is_none_or(f64::is_finite), "{score:?}");
        }
    }
}
