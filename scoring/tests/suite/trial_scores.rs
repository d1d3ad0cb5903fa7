//! Golden scores of hand-made trial logs: every correctness kind, aborted and timed-out trials
//! under each rule, and malformed logs refused with the file and the reason.

use crate::common;

use common::*;
use scoring::{
    Outcome, ScoringError, ScoringRules, TaskCatalog, TrialLog, TrialScore, UnfinishedRule,
    score_trial,
};
use serde_json::json;

fn score(log: &TrialLog, rules: &ScoringRules) -> Result<TrialScore, ScoringError> {
    score_trial(
        log,
        &TaskCatalog::builtin(),
        Some(&baseline(10.0, &[])),
        rules,
    )
}

fn scored(log: &TrialLog) -> TrialScore {
    score(log, &ScoringRules::default()).unwrap()
}

#[test]
fn notches_four_of_six_in_twenty_seconds() {
    // V1: 6 notches. 4 passed → 4/6; baseline 10 s, 20 s → speed 0.5.
    let s = scored(&stopped_trial(
        "v1.mcap",
        "V1",
        "orca_full",
        &[1.0, 1.0, 1.0, 1.0],
        20.0,
    ));
    assert_eq!(s.outcome, Outcome::Completed);
    assert_close(s.time_s, 20.0, 1e-12, "time");
    assert_close(s.correctness, 4.0 / 6.0, 1e-12, "correctness");
    assert_close(s.speed.unwrap(), 0.5, 1e-12, "speed");
    assert_close(
        s.score.unwrap(),
        0.8 * 4.0 / 6.0 + 0.2 * 0.5,
        1e-12,
        "score",
    );
    assert!(s.counted);
}

#[test]
fn curves_are_capped_at_the_count_and_an_undo_counts() {
    // H2: 3 curves. 1 + 1 − 1 (undo) + 1 + 1 + 1 = 4 → capped at 3 → 1.0; 8 s → speed 1.25.
    let s = scored(&stopped_trial(
        "h2.mcap",
        "H2",
        "orca_full",
        &[1.0, 1.0, -1.0, 1.0, 1.0, 1.0],
        8.0,
    ));
    assert_close(s.correctness, 1.0, 0.0, "correctness");
    assert_close(
        s.score.unwrap(),
        0.8 + 0.2 * 1.25,
        1e-12,
        "superhuman score",
    );
    assert!(
        s.notes.iter().any(|n| n.contains("counted as 3")),
        "{:?}",
        s.notes
    );
}

#[test]
fn rotation_sums_degrees_over_360() {
    // C1: 90 + 180 + 45 = 315° → 0.875; 40 s → speed 0.25.
    let s = scored(&stopped_trial(
        "c1.mcap",
        "C1",
        "orca_5",
        &[90.0, 180.0, 45.0],
        40.0,
    ));
    assert_close(s.correctness, 0.875, 1e-12, "correctness");
    assert_close(s.progress, 315.0, 1e-12, "degrees");
    assert_close(s.score.unwrap(), 0.8 * 0.875 + 0.2 * 0.25, 1e-12, "score");
    // More than a turn is capped at 1; turning back more than forward is 0.
    let s = scored(&stopped_trial(
        "c2.mcap",
        "C2",
        "orca_5",
        &[300.0, 200.0],
        10.0,
    ));
    assert_close(s.correctness, 1.0, 0.0, "capped");
    let s = scored(&stopped_trial(
        "c3.mcap",
        "C3",
        "orca_5",
        &[20.0, -50.0],
        10.0,
    ));
    assert_close(s.correctness, 0.0, 0.0, "net negative");
}

#[test]
fn distance_is_millimetres_over_200() {
    // H4: 100 + 50 mm → 0.75; 8 s → speed 1.25.
    let s = scored(&stopped_trial(
        "h4.mcap",
        "H4",
        "orca_full",
        &[100.0, 50.0],
        8.0,
    ));
    assert_close(s.correctness, 0.75, 1e-12, "correctness");
    assert_close(s.score.unwrap(), 0.8 * 0.75 + 0.2 * 1.25, 1e-12, "score");
}

#[test]
fn grasp_levels_and_drops() {
    let events = |marks: &[serde_json::Value]| {
        let mut e = vec![(0.0, start())];
        for (i, m) in marks.iter().enumerate() {
            e.push(((i + 1) as f64, m.clone()));
        }
        e.push((20.0, stop()));
        trial("g.mcap", "G2", "orca_full", false, &e)
    };
    let drop = json!({"event": "drop"});
    // Lifted then dropped: 0.5.
    let s = scored(&events(&[progress(0.5), drop.clone()]));
    assert_close(s.correctness, 0.5, 0.0, "lifted, dropped");
    // A drop alone still means it was lifted: 0.5.
    let s = scored(&events(std::slice::from_ref(&drop)));
    assert_close(s.correctness, 0.5, 0.0, "drop alone");
    // Dropped, re-grasped and relocated: the last level, 1.
    let s = scored(&events(&[progress(0.5), drop.clone(), progress(1.0)]));
    assert_close(s.correctness, 1.0, 0.0, "relocated");
    assert_close(s.score.unwrap(), 0.8 + 0.2 * 0.5, 1e-12, "score");
    // Never lifted.
    let s = scored(&events(&[]));
    assert_close(s.correctness, 0.0, 0.0, "not lifted");
    // A level that is not 0, 0.5 or 1 is refused.
    let err = score(&events(&[progress(0.7)]), &ScoringRules::default()).unwrap_err();
    assert!(
        err.to_string()
            .starts_with("g.mcap: task G2: grasp level 0.7"),
        "{err}"
    );
}

#[test]
fn a_notch_task_refuses_fractions() {
    let err = score(
        &stopped_trial("v2.mcap", "V2", "orca_full", &[1.0, 0.5], 9.0),
        &ScoringRules::default(),
    )
    .unwrap_err();
    assert!(
        err.to_string()
            .contains("0.5 is not a whole number of notches"),
        "{err}"
    );
}

fn aborted_trial() -> TrialLog {
    // V3: 3 of 6 notches, aborted at 12 s; the station still writes stop at 12.5 s.
    trial(
        "aborted.mcap",
        "V3",
        "orca_full",
        false,
        &[
            (0.0, start()),
            (2.0, progress(1.0)),
            (4.0, progress(2.0)),
            (12.0, json!({"event": "abort", "reason": "object fell off"})),
            (12.5, stop()),
        ],
    )
}

#[test]
fn an_aborted_trial_under_each_rule() {
    let rules = |unfinished| ScoringRules {
        unfinished,
        ..ScoringRules::default()
    };
    let partial = score(&aborted_trial(), &rules(UnfinishedRule::Partial)).unwrap();
    assert_eq!(partial.outcome, Outcome::Aborted);
    assert_close(partial.time_s, 12.0, 1e-12, "time ends at the abort");
    assert_close(partial.correctness, 0.5, 0.0, "correctness reached");
    assert_eq!(partial.speed, Some(0.0));
    assert_close(
        partial.score.unwrap(),
        0.4,
        1e-12,
        "0.8 · 0.5, speed term 0",
    );
    assert!(partial.counted);
    assert!(partial.notes.iter().any(|n| n.contains("object fell off")));

    let zero = score(&aborted_trial(), &rules(UnfinishedRule::Zero)).unwrap();
    assert_eq!(zero.score, Some(0.0));
    assert_close(zero.correctness, 0.5, 0.0, "correctness still shown");
    assert!(zero.counted);

    let excluded = score(&aborted_trial(), &rules(UnfinishedRule::Exclude)).unwrap();
    assert!(!excluded.counted);
}

#[test]
fn an_aborted_trial_needs_no_stop() {
    let log = trial(
        "abort_only.mcap",
        "V3",
        "orca_full",
        false,
        &[(0.0, start()), (3.0, json!({"event": "abort"}))],
    );
    let s = scored(&log);
    assert_eq!(s.outcome, Outcome::Aborted);
    assert_close(s.time_s, 3.0, 1e-12, "time");
}

#[test]
fn a_timed_out_trial_counts_progress_up_to_the_limit() {
    // H3 (4 curves) with a 30 s limit for H3: curves at 10, 20, 35 s, stop at 40 s.
    let rules = ScoringRules {
        timeout_s: Some(120.0),
        task_timeout_s: [("H3".to_string(), 30.0)].into(),
        ..ScoringRules::default()
    };
    let log = trial(
        "late.mcap",
        "H3",
        "orca_3",
        false,
        &[
            (0.0, start()),
            (10.0, progress(1.0)),
            (20.0, progress(1.0)),
            (35.0, progress(1.0)),
            (40.0, stop()),
        ],
    );
    let s = score(&log, &rules).unwrap();
    assert_eq!(s.outcome, Outcome::TimedOut);
    assert_close(s.correctness, 0.5, 0.0, "2 of 4 curves within the limit");
    assert_close(s.score.unwrap(), 0.4, 1e-12, "partial: 0.8 · 0.5");
    // Under the global 120 s limit alone the same trial is complete.
    let lenient = ScoringRules {
        timeout_s: Some(120.0),
        ..ScoringRules::default()
    };
    let s = score(&log, &lenient).unwrap();
    assert_eq!(s.outcome, Outcome::Completed);
    assert_close(s.correctness, 0.75, 0.0, "3 of 4 curves");
}

#[test]
fn speed_can_require_full_correctness() {
    let rules = ScoringRules {
        speed_needs_full_correctness: true,
        ..ScoringRules::default()
    };
    let s = score(
        &stopped_trial("q.mcap", "V1", "orca_2", &[1.0], 1.0),
        &rules,
    )
    .unwrap();
    assert_eq!(s.speed, Some(0.0));
    assert_close(
        s.score.unwrap(),
        0.8 / 6.0,
        1e-12,
        "no reward for stopping early",
    );
}

#[test]
fn without_a_baseline_the_trial_has_correctness_only() {
    let log = stopped_trial("c4.mcap", "C4", "orca_full", &[180.0], 30.0);
    let catalog = TaskCatalog::builtin();
    let rules = ScoringRules::default();
    for table in [None, Some(baseline(10.0, &["C4"]))] {
        let s = score_trial(&log, &catalog, table.as_ref(), &rules).unwrap();
        assert_eq!(s.score, None);
        assert_eq!(s.speed, None);
        assert_close(s.correctness, 0.5, 0.0, "correctness");
    }
}

fn refusal(log: &TrialLog) -> String {
    let err = score(log, &ScoringRules::default()).unwrap_err();
    assert!(matches!(err, ScoringError::Trial { .. }), "{err:?}");
    err.to_string()
}

/// A V1 trial of `orca_full`, not practice, with `events`.
fn v1_trial(file: &str, events: &[(f64, serde_json::Value)]) -> TrialLog {
    trial(file, "V1", "orca_full", false, events)
}

/// Each log is refused with a message starting with its expected text.
fn assert_refused(cases: Vec<(TrialLog, &str)>) {
    for (log, expected) in cases {
        let message = refusal(&log);
        assert!(
            message.starts_with(expected),
            "got {message:?}, expected {expected:?}"
        );
    }
}

#[test]
fn logs_with_events_out_of_sequence_are_refused_with_the_file_and_the_reason() {
    assert_refused(vec![
        (
            v1_trial("no_start.mcap", &[(1.0, progress(1.0)), (5.0, stop())]),
            "no_start.mcap: missing start event (the first event is event 1 (progress, +0.000 s))",
        ),
        (
            v1_trial(
                "late_start.mcap",
                &[(1.0, progress(1.0)), (2.0, start()), (5.0, stop())],
            ),
            "late_start.mcap: event 1 (progress, +0.000 s) comes before the start event",
        ),
        (
            v1_trial(
                "only_notes.mcap",
                &[(1.0, json!({"event": "note", "text": "x"}))],
            ),
            "only_notes.mcap: missing start event",
        ),
        (
            v1_trial("no_stop.mcap", &[(0.0, start()), (1.0, progress(1.0))]),
            "no_stop.mcap: missing stop event (the trial was neither stopped nor aborted)",
        ),
        (
            v1_trial(
                "order.mcap",
                &[
                    (0.0, start()),
                    (5.0, progress(1.0)),
                    (3.0, progress(1.0)),
                    (9.0, stop()),
                ],
            ),
            "order.mcap: events out of order: event 3 (progress, +3.000 s) is earlier than event 2 (progress, +5.000 s)",
        ),
        (
            v1_trial(
                "twice.mcap",
                &[(0.0, start()), (1.0, start()), (9.0, stop())],
            ),
            "twice.mcap: duplicate start event: event 2 (start, +1.000 s)",
        ),
        (
            v1_trial(
                "after.mcap",
                &[(0.0, start()), (9.0, stop()), (10.0, progress(1.0))],
            ),
            "after.mcap: event 3 (progress, +10.000 s) comes after the stop event",
        ),
        (
            v1_trial(
                "after_abort.mcap",
                &[
                    (0.0, start()),
                    (4.0, json!({"event": "abort"})),
                    (5.0, progress(1.0)),
                ],
            ),
            "after_abort.mcap: event 3 (progress, +5.000 s) comes after the abort event",
        ),
        (
            v1_trial("zero.mcap", &[(0.0, start()), (0.0, stop())]),
            "zero.mcap: trial time is zero",
        ),
    ]);
}

#[test]
fn logs_with_an_unknown_task_or_malformed_events_are_refused_with_the_file_and_the_reason() {
    assert_refused(vec![
        (
            trial(
                "task.mcap",
                "X9",
                "orca_full",
                false,
                &[(0.0, start()), (3.0, stop())],
            ),
            "task.mcap: unknown task \"X9\"",
        ),
        (
            v1_trial(
                "event.mcap",
                &[
                    (0.0, start()),
                    (1.0, json!({"event": "progres", "value": 1})),
                    (3.0, stop()),
                ],
            ),
            "event.mcap: trial event 2: unknown event \"progres\"",
        ),
        (
            v1_trial(
                "value.mcap",
                &[
                    (0.0, start()),
                    (1.0, json!({"event": "progress"})),
                    (3.0, stop()),
                ],
            ),
            "value.mcap: trial event 2: progress {\"event\":\"progress\"} has no finite number \"value\"",
        ),
        (
            v1_trial(
                "shape.mcap",
                &[(0.0, start()), (1.0, json!(["start"])), (3.0, stop())],
            ),
            "shape.mcap: trial event 2: [\"start\"] has no string \"event\"",
        ),
    ]);
}

#[test]
fn missing_or_bad_metadata_is_refused_by_key() {
    for (key, value, expected) in [
        (
            "task",
            None,
            "m.mcap: the pomdar_trial metadata record has no 'task'",
        ),
        (
            "embodiment",
            None,
            "m.mcap: the pomdar_trial metadata record has no 'embodiment'",
        ),
        (
            "practice",
            None,
            "m.mcap: the pomdar_trial metadata record has no 'practice'",
        ),
        (
            "practice",
            Some("yes"),
            "m.mcap: metadata practice = \"yes\": expected \"true\" or \"false\"",
        ),
    ] {
        let mut log = stopped_trial("m.mcap", "V1", "orca_full", &[1.0], 5.0);
        match value {
            None => log.metadata.remove(key),
            Some(v) => log.metadata.insert(key.to_string(), v.to_string()),
        };
        let message = refusal(&log);
        assert!(message.starts_with(expected), "{message}");
    }
}

#[test]
fn notes_are_allowed_anywhere() {
    let note = json!({"event": "note", "text": "glove re-seated"});
    let log = trial(
        "notes.mcap",
        "V1",
        "orca_full",
        false,
        &[
            (0.0, note.clone()),
            (0.5, start()),
            (1.0, progress(1.0)),
            (2.0, note.clone()),
            (10.5, stop()),
            (11.0, note),
        ],
    );
    let s = scored(&log);
    assert_close(s.time_s, 10.0, 1e-12, "time");
    assert_eq!(
        s.notes
            .iter()
            .filter(|n| n.contains("glove re-seated"))
            .count(),
        3
    );
}
