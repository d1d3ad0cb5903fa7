//! The pose-by-pose session: captures judged by their quality, retries, decisions logged,
//! the fit started after the seventh pose. Times are made up (no clock is read).

use calibration::{CaptureSchedule, PoseSet, SyntheticUser, human_copies};
use retarget::HandModel;
use retarget::human_hand::HandVariation;

use super::*;

const MS: i64 = 1_000_000;

fn steps() -> Vec<PoseStep> {
    PoseSet::orca_v1()
        .poses
        .iter()
        .map(|p| PoseStep {
            name: p.name.clone(),
            instruction: p.instruction.clone(),
        })
        .collect()
}

/// Frames of a steady user (2 mm noise) or a shaking one (8 mm) holding pose `k`.
fn frames(k: usize, noise_sd_m: f64) -> Vec<Vec<Point3<f64>>> {
    let copies = human_copies(&HandModel::orca_v1_right(), &PoseSet::orca_v1()).unwrap();
    SyntheticUser {
        hand_scale: 1.0,
        glove_rpy_rad: [0.0; 3],
        noise_sd_m,
        seed: 5,
        variation: HandVariation::NONE,
    }
    .capture_frames(
        KeypointLayout::Lab22,
        &CaptureSchedule::default(),
        &copies,
        k,
        100.0,
    )
    .unwrap()
}

struct Run {
    session: PoseSession,
    now: i64,
    effects: Vec<Effect>,
}

impl Run {
    fn new(policy: Policy) -> Run {
        let session = PoseSession::new(
            steps(),
            KeypointLayout::Lab22,
            CaptureThresholds::default(),
            SessionTiming {
                settle_s: 1.5,
                capture_s: 1.0,
            },
            policy,
        );
        Run {
            session,
            now: 1_000 * MS,
            effects: Vec::new(),
        }
    }

    /// Feeds the current pose's frames at 100 Hz until the phase is no longer settling or
    /// capturing (the capture was judged), `noise` per attempt.
    fn hold_pose(&mut self, noise_sd_m: f64) {
        let PosePhase::Settling { pose, attempt, .. } = *self.session.phase() else {
            panic!("not settling: {:?}", self.session.phase());
        };
        let held = frames(pose, noise_sd_m);
        let mut i = 0;
        while matches!(
            *self.session.phase(),
            PosePhase::Settling { pose: p, attempt: a, .. } | PosePhase::Capturing { pose: p, attempt: a, .. }
                if (p, a) == (pose, attempt)
        ) {
            self.now += 10 * MS;
            let f = held[i % held.len()].clone();
            i += 1;
            let e = self.session.frame(f, self.now);
            self.effects.extend(e);
        }
    }

    fn act(&mut self, action: CalibrationAction) {
        self.now += 100 * MS;
        let e = self.session.act(action, self.now);
        self.effects.extend(e);
    }

    fn events(&self, name: &str) -> Vec<&Value> {
        self.effects
            .iter()
            .filter_map(|e| match e {
                Effect::Log { event, .. } if event["event"] == name => Some(event),
                _ => None,
            })
            .collect()
    }
}

fn start(policy: Policy) -> Run {
    let mut run = Run::new(policy);
    assert_eq!(*run.session.phase(), PosePhase::WaitingGlove);
    run.effects = run.session.frame(frames(0, 0.002)[0].clone(), run.now);
    assert!(matches!(
        run.session.phase(),
        PosePhase::Settling {
            pose: 0,
            attempt: 1,
            ..
        }
    ));
    assert_eq!(run.effects[1], Effect::Command(0));
    run
}

#[test]
fn steady_captures_are_accepted_pose_by_pose_and_then_the_fit_starts() {
    let mut run = start(Policy::Operator);
    for k in 0..7 {
        assert!(
            matches!(run.session.phase(), PosePhase::Settling { pose, attempt: 1, .. } if *pose == k)
        );
        run.hold_pose(0.002);
    }
    assert_eq!(*run.session.phase(), PosePhase::Fitting);
    assert!(matches!(run.effects.last(), Some(Effect::Fit { .. })));
    let commanded: Vec<usize> = run
        .effects
        .iter()
        .filter_map(|e| match e {
            Effect::Command(k) => Some(*k),
            _ => None,
        })
        .collect();
    assert_eq!(commanded, (0..7).collect::<Vec<_>>());
    let decisions = run.events(DECISION_EVENT);
    assert_eq!(decisions.len(), 7);
    assert!(
        decisions
            .iter()
            .all(|d| d["decision"] == "accepted" && d["by"] == "auto")
    );
    // Each capture window: 1 s of frames at 100 Hz, about 100 expected from the settling.
    for a in run.session.attempts() {
        assert_eq!(a.len(), 1);
        assert!(a[0].accepted);
        let q = &a[0].quality;
        assert!((99..=101).contains(&q.frames), "{q:?}");
        assert!(
            q.expected_frames.is_some_and(|e| (99..=101).contains(&e)),
            "{q:?}"
        );
    }
    // The capture windows open and close in order, settle_s after each pose event.
    let starts = run.events(CAPTURE_EVENT_NAME);
    assert_eq!(starts.len(), 14);
    let stop = run.events("stop");
    assert_eq!(stop[0]["summary"]["poses"][6]["accepted"], 1);

    // The fit's outcome: complete, and q leaves.
    let e = run.session.fit_finished(Ok(fitted(Vec::new())));
    assert!(e.is_empty(), "an operator's session waits for q: {e:?}");
    assert_eq!(*run.session.phase(), PosePhase::Complete);
    assert_eq!(run.session.redo_offer(), None);
    // Nothing to capture again when every pose fits.
    assert!(
        run.session
            .act(CalibrationAction::Retry, run.now)
            .is_empty()
    );
    assert_eq!(*run.session.phase(), PosePhase::Complete);
    assert_eq!(
        run.session.act(CalibrationAction::Quit, run.now),
        vec![Effect::Quit { completed: true }]
    );
}

fn fitted(misfits: Vec<(usize, String)>) -> FitDone {
    FitDone {
        lines: vec!["profile written: profiles/u.toml (user u)".into()],
        misfits,
    }
}

/// A session of seven steady captures, fitted, with pinch_ring (2) and closed (6) named.
fn fitted_with_misfits(policy: Policy) -> Run {
    let mut run = start(policy);
    for _ in 0..7 {
        run.hold_pose(0.002);
    }
    let e = run.session.fit_finished(Ok(fitted(vec![
        (
            2,
            "pinch_ring: the thumb stays 54 mm off the ring finger".into(),
        ),
        (6, "closed: its joints stay 0.51 rad from the pose".into()),
    ])));
    run.effects.extend(e);
    run
}

#[test]
fn after_the_fit_the_worst_pose_is_offered_and_captured_again_alone_then_refitted() {
    let mut run = fitted_with_misfits(Policy::Operator);
    assert_eq!(*run.session.phase(), PosePhase::Complete);
    assert_eq!(run.session.redo_offer(), Some(2));
    let said: Vec<&str> = run.session.messages().collect();
    assert!(said.iter().any(|m| m.starts_with("pinch_ring: the thumb")));
    assert!(said.iter().any(|m| m.starts_with("closed: its joints")));
    assert!(
        said.contains(&"r captures pinch_ring again and fits again; q keeps this fit"),
        "{said:?}"
    );
    run.effects.clear();
    run.act(CalibrationAction::Retry);
    // The log is continued before anything is written to it; then pinch_ring, attempt 2.
    assert_eq!(run.effects[0], Effect::ContinueLog);
    assert_eq!(run.events(REDO_EVENT)[0]["pose"], "pinch_ring");
    assert!(run.effects.contains(&Effect::Command(2)));
    assert!(matches!(
        run.session.phase(),
        PosePhase::Settling {
            pose: 2,
            attempt: 2,
            ..
        }
    ));
    run.hold_pose(0.002);
    // Accepted: straight to the fit, no other pose captured again.
    assert_eq!(*run.session.phase(), PosePhase::Fitting);
    assert!(matches!(run.effects.last(), Some(Effect::Fit { .. })));
    let captures: Vec<usize> = run.session.attempts().iter().map(Vec::len).collect();
    assert_eq!(captures, [1, 1, 2, 1, 1, 1, 1]);
    assert!(std::ptr::eq(
        run.session.accepted(2).unwrap(),
        &run.session.attempts()[2][1]
    ));
    let stop = run.events("stop");
    assert_eq!(stop[0]["summary"]["poses"][2]["accepted"], 2);
    // The second fit matches every pose: nothing more is offered.
    run.session.fit_finished(Ok(fitted(Vec::new())));
    assert_eq!(run.session.redo_offer(), None);
    assert_eq!(*run.session.phase(), PosePhase::Complete);
}

#[test]
fn quitting_a_redo_keeps_the_fit_and_without_an_operator_nothing_is_offered() {
    let mut run = fitted_with_misfits(Policy::Operator);
    run.act(CalibrationAction::Retry);
    run.effects.clear();
    run.act(CalibrationAction::Quit);
    assert_eq!(run.effects.last(), Some(&Effect::Quit { completed: true }));
    assert_eq!(run.events("abort").len(), 1);

    let run = fitted_with_misfits(Policy::Automatic { max_attempts: 3 });
    assert_eq!(run.session.redo_offer(), None);
    assert_eq!(run.effects.last(), Some(&Effect::Quit { completed: true }));
    // The sentences are said all the same.
    assert!(
        run.session
            .messages()
            .any(|m| m.starts_with("pinch_ring: the thumb"))
    );
}

const CAPTURE_EVENT_NAME: &str = crate::calibrate::session_events::CAPTURE_EVENT;

#[test]
fn a_bad_capture_waits_for_retry_and_is_kept_beside_the_accepted_one() {
    let mut run = start(Policy::Operator);
    run.hold_pose(0.002);
    run.hold_pose(0.002);
    // pinch_ring: the user shakes.
    run.hold_pose(0.008);
    assert_eq!(
        *run.session.phase(),
        PosePhase::Review {
            pose: 2,
            attempt: 1
        }
    );
    assert_eq!(
        run.session.attempts()[2][0].quality.level,
        QualityLevel::Bad
    );
    // Accepting a bad capture is refused; the session stays in review.
    run.act(CalibrationAction::Accept);
    assert!(matches!(run.session.phase(), PosePhase::Review { .. }));
    assert!(
        run.session
            .messages()
            .last()
            .is_some_and(|m| m.contains("cannot be fitted"))
    );
    run.act(CalibrationAction::Retry);
    assert!(matches!(
        run.session.phase(),
        PosePhase::Settling {
            pose: 2,
            attempt: 2,
            ..
        }
    ));
    assert_eq!(
        run.effects
            .last()
            .map(|e| matches!(e, Effect::Log { event, .. } if event["attempt"] == 2)),
        Some(true)
    );
    run.hold_pose(0.002);
    assert!(matches!(
        run.session.phase(),
        PosePhase::Settling { pose: 3, .. }
    ));
    let ring = &run.session.attempts()[2];
    assert_eq!(ring.len(), 2);
    assert_eq!(
        (ring[0].accepted, ring[1].accepted, ring[1].quality.level),
        (false, true, QualityLevel::Good)
    );
    let decisions: Vec<(String, u64, String, String)> = run
        .events(DECISION_EVENT)
        .iter()
        .filter(|d| d["pose"] == "pinch_ring")
        .map(|d| {
            (
                d["pose"].as_str().unwrap_or("").to_string(),
                d["attempt"].as_u64().unwrap_or(0),
                d["decision"].as_str().unwrap_or("").to_string(),
                d["by"].as_str().unwrap_or("").to_string(),
            )
        })
        .collect();
    assert_eq!(
        decisions,
        vec![
            ("pinch_ring".into(), 1, "retry".into(), "operator".into()),
            ("pinch_ring".into(), 2, "accepted".into(), "auto".into()),
        ]
    );
    let qualities: Vec<&str> = run
        .events(QUALITY_EVENT)
        .iter()
        .filter(|q| q["pose"] == "pinch_ring")
        .map(|q| q["quality"].as_str().unwrap_or(""))
        .collect();
    assert_eq!(qualities, ["bad", "good"]);
}

#[test]
fn without_an_operator_bad_captures_are_retried_until_the_limit() {
    let mut run = start(Policy::Automatic { max_attempts: 2 });
    run.hold_pose(0.008);
    assert!(matches!(
        run.session.phase(),
        PosePhase::Settling {
            pose: 0,
            attempt: 2,
            ..
        }
    ));
    run.hold_pose(0.008);
    assert!(
        matches!(run.session.phase(), PosePhase::Failed(r) if r.contains("pinch_index") && r.contains("2 bad captures"))
    );
    assert_eq!(run.effects.last(), Some(&Effect::Quit { completed: false }));
    assert_eq!(run.events("abort").len(), 1);

    // A retried pose that then succeeds goes on; the fit's end quits by itself.
    let mut run = start(Policy::Automatic { max_attempts: 3 });
    run.hold_pose(0.008);
    for _ in 0..7 {
        run.hold_pose(0.002);
    }
    assert_eq!(*run.session.phase(), PosePhase::Fitting);
    assert_eq!(run.session.attempts()[0].len(), 2);
    let e = run.session.fit_finished(Err("no convergence".into()));
    assert_eq!(e, vec![Effect::Quit { completed: false }]);
    assert!(matches!(run.session.phase(), PosePhase::Failed(_)));
}

#[test]
fn a_poor_capture_is_the_operators_call_and_actions_out_of_place_are_refused() {
    let mut run = start(Policy::Operator);
    // Half the frames of the glove's rate: the capture is poor.
    let PosePhase::Settling { .. } = *run.session.phase() else {
        panic!()
    };
    let held = frames(0, 0.002);
    let mut i = 0;
    while matches!(
        run.session.phase(),
        PosePhase::Settling { pose: 0, .. } | PosePhase::Capturing { pose: 0, .. }
    ) {
        let capturing = matches!(run.session.phase(), PosePhase::Capturing { .. });
        run.now += if capturing { 20 * MS } else { 10 * MS };
        let e = run.session.frame(held[i % held.len()].clone(), run.now);
        run.effects.extend(e);
        i += 1;
    }
    assert_eq!(
        *run.session.phase(),
        PosePhase::Review {
            pose: 0,
            attempt: 1
        }
    );
    assert_eq!(
        run.session.attempts()[0][0].quality.level,
        QualityLevel::Poor
    );
    run.act(CalibrationAction::Accept);
    assert!(matches!(
        run.session.phase(),
        PosePhase::Settling { pose: 1, .. }
    ));
    assert!(run.session.attempts()[0][0].accepted);
    assert_eq!(run.events(DECISION_EVENT)[0]["by"], "operator");
    // Retry while settling: nothing happens but a message.
    let before = run.session.phase().clone();
    run.act(CalibrationAction::Retry);
    assert_eq!(*run.session.phase(), before);
    // Quit mid-session: abandoned, logged.
    run.act(CalibrationAction::Quit);
    assert_eq!(run.effects.last(), Some(&Effect::Quit { completed: false }));
    assert_eq!(run.events("abort").len(), 1);
}

#[test]
fn the_view_shows_the_pose_its_captures_and_what_to_press() {
    use crate::Level;
    use crate::calibrate::calibration_view::{CalState, CalibrationView};

    let mut run = start(Policy::Operator);
    run.hold_pose(0.002);
    run.hold_pose(0.008);
    let view = CalibrationView::build(&run.session, &[], &[], run.now);
    assert_eq!(view.state, CalState::Review);
    assert_eq!(view.title, "[2/7] pinch_middle");
    assert!(
        view.instruction.contains("middle finger"),
        "{}",
        view.instruction
    );
    assert_eq!(view.poses[0].1, "accepted (good)");
    assert_eq!(
        view.poses[1],
        (
            "pinch_middle".to_string(),
            "now (so far: bad)".to_string(),
            Level::Warn
        )
    );
    assert_eq!(view.poses[2].1, "-");
    assert!(
        view.detail[0].contains("r captures the pose again"),
        "{:?}",
        view.detail
    );
    let (fill, label, level) = view.meter.clone().unwrap();
    assert_eq!((fill, level), (0.0, Level::Bad));
    assert!(
        label.starts_with("pinch_middle capture 1: BAD · jitter"),
        "{label}"
    );
    assert_eq!(view.progress, None);

    run.act(CalibrationAction::Retry);
    let view = CalibrationView::build(&run.session, &[], &[], run.now);
    assert_eq!(view.state, CalState::Settling);
    assert_eq!(view.title, "[2/7] pinch_middle · capture 2");
    assert_eq!(view.banner, "COPY THE POSE  1.5 s");
}
