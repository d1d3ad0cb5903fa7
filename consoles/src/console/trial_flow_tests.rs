use scoring::{Outcome, TrialScore};
use serde_json::json;

use super::*;
use crate::console::manifest::test_manifest;

const S: i64 = 1_000_000_000;

fn manifest(practice: u32, trials: u32) -> Manifest {
    test_manifest("V1", practice, trials)
}

fn healthy(now_ns: i64) -> Health {
    Health::from_status(
        &json!({"state": "engaged", "input_rate_hz": 100.0, "input_age_ms": 3.0}),
        now_ns,
    )
}

fn score(progress: f64, correctness: f64) -> TrialScore {
    TrialScore {
        file: String::new(),
        task: "V1".into(),
        embodiment: "orca_full".into(),
        user: None,
        operator: None,
        trial_index: None,
        metadata: std::collections::BTreeMap::new(),
        practice: false,
        outcome: Outcome::Completed,
        time_s: 4.0,
        progress,
        correctness,
        speed: None,
        score: None,
        counted: true,
        notes: vec![],
    }
}

fn notches() -> CorrectnessKind {
    CorrectnessKind::Notches { count: 6 }
}

/// Runs one trial from idle: start, countdown, `marks`, stop; returns the effects in order.
fn run_trial(flow: &mut TrialFlow, t: &mut i64, marks: &[Action]) -> Vec<Effect> {
    let mut effects = flow.act(Action::Start, &healthy(*t), *t);
    *t += 3 * S;
    effects.extend(flow.tick(&healthy(*t), *t));
    for mark in marks {
        *t += S;
        effects.extend(flow.act(mark.clone(), &healthy(*t), *t));
    }
    *t += S;
    effects.extend(flow.act(Action::StartStop, &healthy(*t), *t));
    effects
}

#[test]
fn practice_then_recorded_trials_with_marks_in_their_logs() {
    let mut flow = TrialFlow::new(manifest(1, 2), notches(), 3.0, StartLimits::default());
    let mut t = 0;
    let effects = run_trial(&mut flow, &mut t, &[Action::Progress(None), Action::Drop]);
    assert_eq!(
        effects,
        vec![
            Effect::StartTrial {
                file: "V1-p01.mcap".into(),
                slot: Slot {
                    practice: true,
                    index: 1
                }
            },
            Effect::TrialEvent(json!({"event": "progress", "value": 1.0})),
            Effect::TrialEvent(json!({"event": "drop"})),
            Effect::StopTrial,
        ]
    );
    assert!(
        matches!(flow.phase(), TrialPhase::Finishing { time_s, .. } if (*time_s - 3.0).abs() < 1e-9)
    );
    assert_eq!(
        flow.trial_logged(Ok(score(1.0, 1.0 / 6.0))),
        vec![Effect::SaveManifest]
    );
    assert_eq!(flow.phase(), &TrialPhase::Idle);
    for _ in 0..2 {
        run_trial(&mut flow, &mut t, &[Action::Progress(None)]);
        flow.trial_logged(Ok(score(1.0, 0.5)));
    }
    assert_eq!(flow.phase(), &TrialPhase::Complete);
    let files: Vec<&str> = flow
        .manifest
        .trials
        .iter()
        .map(|t| t.file.as_str())
        .collect();
    assert_eq!(files, ["V1-p01.mcap", "V1-t01.mcap", "V1-t02.mcap"]);
    assert_eq!(flow.manifest.series(), vec![0.5, 0.5]);
}

#[test]
fn a_start_is_refused_while_input_is_stale_and_the_countdown_rechecks() {
    let mut flow = TrialFlow::new(manifest(0, 1), notches(), 3.0, StartLimits::default());
    let stale = Health::from_status(
        &json!({"state": "held", "input_rate_hz": 100.0, "input_age_ms": 900.0}),
        0,
    );
    assert!(flow.act(Action::Start, &stale, 0).is_empty());
    assert_eq!(flow.phase(), &TrialPhase::Idle);
    assert!(flow.messages().last().is_some_and(|m| m.contains("stale")));
    flow.act(Action::Start, &healthy(0), 0);
    assert!(matches!(flow.phase(), TrialPhase::Countdown { .. }));
    assert!(flow.tick(&healthy(S), S).is_empty());
    let late = Health::from_status(
        &json!({"state": "engaged", "input_rate_hz": 5.0, "input_age_ms": 1.0}),
        3 * S,
    );
    assert!(flow.tick(&late, 3 * S).is_empty());
    assert_eq!(flow.phase(), &TrialPhase::Idle);
}

#[test]
fn grasp_levels_are_checked_and_the_last_one_counts() {
    let mut flow = TrialFlow::new(
        manifest(0, 1),
        CorrectnessKind::Grasp {},
        0.0,
        StartLimits::default(),
    );
    flow.act(Action::Start, &healthy(0), 0);
    flow.tick(&healthy(0), 0);
    assert!(flow.act(Action::Progress(None), &healthy(0), 0).is_empty());
    assert!(
        flow.act(Action::Progress(Some(0.7)), &healthy(0), 0)
            .is_empty()
    );
    assert_eq!(
        flow.act(Action::Progress(Some(1.0)), &healthy(0), 0).len(),
        1
    );
    assert_eq!(flow.marks(), (1.0, 0));
    flow.act(Action::Drop, &healthy(0), 0);
    assert_eq!(flow.marks(), (0.5, 1));
}

#[test]
fn redo_sets_the_trial_aside_and_runs_its_slot_again() {
    let mut flow = TrialFlow::new(manifest(0, 2), notches(), 0.0, StartLimits::default());
    let mut t = 0;
    run_trial(&mut flow, &mut t, &[]);
    flow.trial_logged(Ok(score(0.0, 0.0)));
    assert_eq!(
        flow.act(Action::Redo, &healthy(t), t),
        vec![
            Effect::SetAside {
                from: "V1-t01.mcap".into(),
                to: "V1-t01.mcap.redone".into()
            },
            Effect::SaveManifest
        ]
    );
    // Redo during a trial: aborted, logged, set aside.
    flow.act(Action::Start, &healthy(t), t);
    flow.tick(&healthy(t), t);
    let effects = flow.act(Action::Redo, &healthy(t + S), t + S);
    assert_eq!(
        effects[0],
        Effect::TrialEvent(json!({"event": "abort", "reason": "redo"}))
    );
    let effects = flow.trial_logged(Ok(score(0.0, 0.0)));
    assert_eq!(
        effects[0],
        Effect::SetAside {
            from: "V1-t01-a2.mcap".into(),
            to: "V1-t01-a2.mcap.redone".into()
        }
    );
    assert_eq!(flow.manifest.next_slot(), Some((false, 1)));
    run_trial(&mut flow, &mut t, &[]);
    assert_eq!(flow.manifest.trials.len(), 2);
    assert!(matches!(flow.phase(), TrialPhase::Finishing { file, .. } if file == "V1-t01-a3.mcap"));
}

#[test]
fn quit_during_a_trial_needs_a_second_press_and_interrupt_does_not() {
    let mut flow = TrialFlow::new(manifest(0, 2), notches(), 0.0, StartLimits::default());
    flow.act(Action::Start, &healthy(0), 0);
    flow.tick(&healthy(0), 0);
    assert!(flow.act(Action::Quit, &healthy(S), S).is_empty());
    let effects = flow.act(Action::Quit, &healthy(S), S);
    assert_eq!(
        effects,
        vec![
            Effect::TrialEvent(json!({"event": "abort", "reason": "quit"})),
            Effect::StopTrial
        ]
    );
    let effects = flow.trial_logged(Ok(score(0.0, 0.0)));
    assert_eq!(effects.last(), Some(&Effect::Quit));
    assert_eq!(flow.manifest.trials[0].status, TrialStatus::Interrupted);

    let mut flow = TrialFlow::new(manifest(0, 2), notches(), 0.0, StartLimits::default());
    flow.act(Action::Start, &healthy(0), 0);
    flow.tick(&healthy(0), 0);
    let effects = flow.act(Action::Interrupt, &healthy(S), S);
    assert_eq!(
        effects[0],
        Effect::TrialEvent(json!({"event": "abort", "reason": "interrupted"}))
    );
    assert_eq!(flow.act(Action::Interrupt, &Health::default(), S), vec![]);
}

#[test]
fn an_unscorable_log_is_kept_and_its_slot_runs_again() {
    let mut flow = TrialFlow::new(manifest(0, 1), notches(), 0.0, StartLimits::default());
    let mut t = 0;
    run_trial(&mut flow, &mut t, &[]);
    flow.trial_logged(Err("missing stop event".into()));
    assert_eq!(flow.manifest.trials[0].status, TrialStatus::Unscorable);
    assert_eq!(flow.phase(), &TrialPhase::Idle);
    assert_eq!(flow.manifest.next_slot(), Some((false, 1)));
}

#[test]
fn an_engage_before_fresh_input_waits_for_it_then_gives_up() {
    let mut flow = TrialFlow::new(manifest(0, 1), notches(), 0.0, StartLimits::default());
    let none = Health::default();
    assert_eq!(flow.act(Action::Engage, &none, 0), vec![Effect::Engage]);
    assert!(
        flow.messages()
            .last()
            .is_some_and(|m| m.contains("waiting for fresh glove input"))
    );
    assert!(flow.tick(&none, S / 10).is_empty());
    assert_eq!(flow.tick(&none, S), vec![Effect::Engage]);
    assert!(flow.tick(&none, 11 * S).is_empty());
    assert!(
        flow.messages()
            .last()
            .is_some_and(|m| m.contains("given up"))
    );
    // Engaged while pending: no more requests.
    flow.act(Action::Engage, &none, 20 * S);
    assert!(flow.tick(&healthy(21 * S), 21 * S).is_empty());
    assert!(flow.tick(&none, 22 * S).is_empty());
    // The toggle disengages an engaged station.
    assert_eq!(
        flow.act(Action::ToggleEngage, &healthy(23 * S), 23 * S),
        vec![Effect::Disengage]
    );
}

#[test]
fn a_start_while_the_glove_rate_settles_waits_for_it() {
    let mut flow = TrialFlow::new(manifest(0, 1), notches(), 1.0, StartLimits::default());
    let settling = Health::from_status(
        &json!({"state": "engaged", "input_rate_hz": 9.0, "input_age_ms": 3.0}),
        0,
    );
    assert!(flow.act(Action::Start, &settling, 0).is_empty());
    assert_eq!(flow.phase(), &TrialPhase::Idle);
    assert!(
        flow.messages()
            .last()
            .is_some_and(|m| m.contains("start: waiting for the station"))
    );
    assert!(flow.tick(&settling, S).is_empty());
    flow.tick(&healthy(2 * S), 2 * S);
    assert!(matches!(flow.phase(), TrialPhase::Countdown { ends_ns, .. } if *ends_ns == 3 * S));
    // One that never settles is given up, with the reason.
    let mut flow = TrialFlow::new(manifest(0, 1), notches(), 1.0, StartLimits::default());
    flow.act(Action::Start, &settling, 0);
    let late = Health::from_status(
        &json!({"state": "engaged", "input_rate_hz": 9.0, "input_age_ms": 3.0}),
        11 * S,
    );
    flow.tick(&late, 11 * S);
    assert_eq!(flow.phase(), &TrialPhase::Idle);
    assert!(
        flow.messages()
            .last()
            .is_some_and(|m| m.contains("cannot start: glove rate 9.0 Hz"))
    );
    // Abort cancels a pending start.
    flow.act(Action::Start, &settling, 12 * S);
    flow.act(Action::Abort, &settling, 12 * S);
    flow.tick(&healthy(13 * S), 13 * S);
    assert_eq!(flow.phase(), &TrialPhase::Idle);
}

#[test]
fn a_human_study_starts_on_glove_health_alone_and_never_engages() {
    let limits = StartLimits {
        drives_robot: false,
        ..StartLimits::default()
    };
    let mut flow = TrialFlow::new(manifest(0, 1), notches(), 1.0, limits);
    let glove = |rate: f64, t: i64| {
        Health::from_status(
            &json!({"state": "disengaged", "input_rate_hz": rate, "input_age_ms": 3.0}),
            t,
        )
    };
    assert!(flow.act(Action::Engage, &glove(100.0, 0), 0).is_empty());
    assert!(
        flow.messages()
            .last()
            .is_some_and(|m| m.contains("drives no robot"))
    );
    // A settling glove rate is waited for, as for a robot.
    assert!(flow.act(Action::Start, &glove(9.0, 0), 0).is_empty());
    assert_eq!(flow.phase(), &TrialPhase::Idle);
    flow.tick(&glove(100.0, S), S);
    assert!(matches!(flow.phase(), TrialPhase::Countdown { .. }));
    let effects = flow.tick(&glove(100.0, 2 * S), 2 * S);
    assert!(
        effects
            .iter()
            .any(|e| matches!(e, Effect::StartTrial { .. })),
        "{effects:?}"
    );
    assert!(!effects.iter().any(|e| matches!(e, Effect::Engage)));
}
