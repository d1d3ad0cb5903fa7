//! The review on synthetic trials: every fact and sentence from a log built to contain it, and
//! none from a clean one.

use nalgebra::Point3;
use retarget::quality::human_pinch;
use retarget::{Finger, HandModel, KeypointLayout};
use serde_json::json;

use crate::pinches::{DistanceSeries, pinch_attempts, robot_distances};
use crate::{
    FeedbackKind, FeedbackSettings, GloveFrame, JointSample, ReviewContext, TrialInput,
    TrialWindow, WorkspaceLimits, review, review_chart,
};

const S: i64 = 1_000_000_000;
const MS: i64 = 1_000_000;
const T0: i64 = 1_000 * S;
const LAYOUT: KeypointLayout = KeypointLayout::Lab21;

/// A glove frame at `t_ns` with the thumb tip `gap_mm` from `pinched`'s tip (far otherwise).
fn frame(t_ns: i64, pinched: Option<(Finger, f64)>) -> GloveFrame {
    let mut points: Vec<Point3<f64>> = (0..LAYOUT.len())
        .map(|i| Point3::new(i as f64 * 0.01, 0.0, 0.0))
        .collect();
    for f in Finger::OPPOSING {
        points[LAYOUT.tip(f)] = Point3::new(0.1, f.index() as f64 * 0.03, 0.05);
    }
    points[LAYOUT.tip(Finger::Thumb)] = Point3::new(0.0, 0.0, 0.0);
    if let Some((finger, gap_mm)) = pinched {
        points[LAYOUT.tip(finger)] = Point3::new(gap_mm * 1e-3, 0.0, 0.0);
    }
    GloveFrame { t_ns, points }
}

/// Command `k` of a 25 Hz stream: fresh (stamped 5 ms earlier) or held (stamped at its time).
fn command(model: &HandModel, t_ns: i64, held: bool) -> JointSample {
    JointSample {
        t_ns,
        stamp_ns: if held { t_ns } else { t_ns - 5 * MS },
        names: model.ros_dof_names().to_vec(),
        position: model.zero_pose(),
    }
}

fn status(state: &str, rejected_jump: u64, refused: u64, engaged: bool) -> serde_json::Value {
    json!({
        "state": state,
        "input_rate_hz": 50.0,
        "counters": {"rejected": {"jump": rejected_jump, "outlier": 0}},
        "arm_refused": if refused > 0 { json!({"workspace": refused}) } else { json!({}) },
        "arm": {"engaged": engaged, "constraint": "vertical_axis"},
    })
}

/// A 10 s trial: glove at 50 Hz, commands at 25 Hz, status at 5 Hz; with `faults`, a 400 ms
/// glove gap from 4.0 s (held commands from 4.15 s), a little-finger pinch from 6 s to 7 s
/// and 6 rejected frames at 8 s; an index pinch from 2 s to 3 s either way.
fn trial(model: &HandModel, faults: bool) -> TrialInput {
    let gap = |t: i64| faults && (4 * S..4 * S + 400 * MS).contains(&(t - T0));
    let glove_frames = (0..500)
        .map(|k| T0 + k * 20 * MS)
        .filter(|t| !gap(*t))
        .map(|t| {
            let ts = t - T0;
            let pinched = match ts {
                _ if (2 * S..3 * S).contains(&ts) => Some((Finger::Index, 8.0)),
                _ if faults && (6 * S..7 * S).contains(&ts) => Some((Finger::Little, 6.0)),
                _ => None,
            };
            frame(t, pinched)
        })
        .collect();
    let joint_targets = (0..250)
        .map(|k| T0 + k * 40 * MS)
        .map(|t| {
            command(
                model,
                t,
                faults && (4150 * MS..4400 * MS).contains(&(t - T0)),
            )
        })
        .collect();
    let statuses = (0..=50)
        .map(|k| {
            let ts = k * 200 * MS;
            let state = if faults && ts == 4200 * MS {
                "held"
            } else {
                "engaged"
            };
            let rejected = if faults && ts >= 8 * S { 6 } else { 0 };
            (T0 + ts, status(state, rejected, 0, true))
        })
        .collect();
    TrialInput {
        source: "trial.mcap".into(),
        metadata: [("task", "H5"), ("embodiment", "orca_full")]
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .into(),
        events: vec![
            (T0, json!({"event": "start"})),
            (T0 + 5 * S, json!({"event": "progress", "value": 0.5})),
            (T0 + 10 * S, json!({"event": "stop"})),
        ],
        statuses,
        glove_frames,
        joint_targets,
        hand_states: Vec::new(),
        arm_targets: Vec::new(),
    }
}

fn context<'a>(model: &'a HandModel, settings: &'a FeedbackSettings) -> ReviewContext<'a> {
    ReviewContext {
        model,
        joint_name_prefix: None,
        layout: LAYOUT,
        workspace: None,
        hold_timeout_ms: Some(150.0),
        settings,
    }
}

#[test]
fn a_glove_gap_and_a_pinch_the_robot_missed_are_found_with_their_times_and_said() {
    let model = HandModel::orca_v1_right();
    let settings = FeedbackSettings::default();
    let (facts, series) = review(&trial(&model, true), &context(&model, &settings)).unwrap();
    assert!((facts.duration_s - 10.0).abs() < 1e-9);
    assert_eq!(facts.ending, "stopped");
    // The hold: commands 4.16–4.36 s held, the glove's gap 3.98 → 4.40 s.
    let [hold] = &facts.holds[..] else {
        panic!("{:?}", facts.holds)
    };
    assert!((hold.from_s - 4.16).abs() < 1e-9, "{hold:?}");
    assert!((hold.glove_gap_ms - 420.0).abs() < 1e-6, "{hold:?}");
    assert_eq!(hold.commands, 6);
    assert!(facts.drive.iter().any(|s| s.state == "held"));
    // The zero pose keeps the thumb far from every finger: no pinch closes.
    let fingers: Vec<(&str, bool)> = facts
        .pinches
        .iter()
        .map(|p| (p.finger.as_str(), p.closed))
        .collect();
    assert_eq!(fingers, [("index", false), ("little", false)]);
    assert!((facts.pinches[1].from_s - 6.0).abs() < 1e-9);
    assert_eq!(facts.glove.rejected.len(), 1);
    assert!((facts.glove.rejected[0].t_s - 8.0).abs() < 1e-9);
    let kinds: Vec<FeedbackKind> = facts.feedback.iter().map(|f| f.kind).collect();
    assert_eq!(
        kinds,
        [
            FeedbackKind::Holds,
            FeedbackKind::PinchNotClosed,
            FeedbackKind::PinchNotClosed,
            FeedbackKind::RejectedFrames
        ]
    );
    assert_eq!(facts.feedback[0].text, "held once (glove gap 420 ms)");
    assert!(
        facts.feedback[2]
            .text
            .starts_with("little pinch did not close in 1 of 1 attempts (robot ")
    );
    assert_eq!(facts.feedback[3].text, "6 glove frames rejected (jump)");
    // The figure's data: three lanes, the distance panel with both hands' series.
    let chart = review_chart(&facts, &series);
    assert_eq!(chart.lanes.len(), 3);
    assert!(
        chart
            .panels
            .iter()
            .any(|p| p.title.starts_with("thumb–finger") && p.series.len() == 8)
    );
    assert!(chart.title.contains("H5") && chart.title.contains("4 feedback"));
}

#[test]
fn a_clean_trial_gets_no_feedback() {
    let model = HandModel::orca_v1_right();
    let settings = FeedbackSettings {
        // The zero pose never closes a pinch: this trial's index pinch is not a fault.
        pinch_misses_min: 2,
        ..FeedbackSettings::default()
    };
    let (facts, _) = review(&trial(&model, false), &context(&model, &settings)).unwrap();
    assert!(facts.holds.is_empty());
    assert_eq!(facts.pinches.len(), 1);
    assert!(facts.feedback.is_empty(), "{:?}", facts.feedback);
}

#[test]
fn a_pinch_is_closed_when_the_robot_comes_within_15_mm_in_time() {
    let frames: Vec<GloveFrame> = (0..50)
        .map(|k| T0 + k * 20 * MS)
        .map(|t| {
            frame(
                t,
                (T0 + 200 * MS..T0 + 600 * MS)
                    .contains(&t)
                    .then_some((Finger::Index, 10.0)),
            )
        })
        .collect();
    assert!(human_pinch(LAYOUT, &frames[15].points).is_some());
    let window = TrialWindow {
        start_ns: T0,
        end_ns: T0 + S,
    };
    let robot = |closing_at_s: f64| DistanceSeries {
        t_s: (0..25).map(|k| k as f64 * 0.04).collect(),
        mm: std::array::from_fn(|_| {
            (0..25)
                .map(|k| {
                    if k as f64 * 0.04 >= closing_at_s {
                        12.0
                    } else {
                        30.0
                    }
                })
                .collect()
        }),
    };
    // Closing 0.2 s after the pinch's last frame (0.58 s): in time; 0.4 s after: not.
    let in_time = pinch_attempts(&frames, LAYOUT, &window, &robot(0.78));
    assert!(in_time[0].closed && (in_time[0].robot_min_mm - 12.0).abs() < 1e-9);
    let late = pinch_attempts(&frames, LAYOUT, &window, &robot(0.98));
    assert!(!late[0].closed && (late[0].robot_min_mm - 30.0).abs() < 1e-9);
    assert!((late[0].human_min_mm - 10.0).abs() < 1e-9);
}

#[test]
fn robot_distances_follow_the_model_and_joints_missing_from_a_target_are_named() {
    let model = HandModel::orca_v1_right();
    let window = TrialWindow {
        start_ns: T0,
        end_ns: T0 + S,
    };
    let targets = vec![command(&model, T0 + 40 * MS, false)];
    let d = robot_distances(&targets, (&model, None), &window).unwrap();
    let fk = model.forward_new(&model.zero_pose()).unwrap();
    let tip = |f: Finger| fk.position(model.frames().tip(f));
    let expected = (tip(Finger::Index) - tip(Finger::Thumb)).norm() * 1e3;
    assert!((d.mm[0][0] - expected).abs() < 1e-9);
    let mut short = targets[0].clone();
    short.names.pop();
    short.position.pop();
    let error = robot_distances(&[short], (&model, None), &window).unwrap_err();
    assert!(error.contains("no joint named"), "{error}");
}

#[test]
fn the_wrist_at_its_limit_and_arm_refusals_are_said_past_their_thresholds() {
    let model = HandModel::orca_v1_right();
    let settings = FeedbackSettings::default();
    let mut input = trial(&model, false);
    // 3 of 10 arm targets on the box's top face.
    input.arm_targets = (0..10)
        .map(|k| (T0 + k * S, [0.5, 0.0, if k < 3 { 0.75 } else { 0.4 }]))
        .collect();
    input.statuses[20].1 = status("engaged", 0, 2, true);
    for s in &mut input.statuses[21..] {
        s.1 = status("engaged", 0, 2, true);
    }
    let mut context = context(&model, &settings);
    context.workspace = Some(WorkspaceLimits {
        min_m: [0.25, -0.45, 0.05],
        max_m: [0.75, 0.45, 0.75],
    });
    let (facts, _) = review(&input, &context).unwrap();
    let texts: Vec<&str> = facts.feedback.iter().map(|f| f.text.as_str()).collect();
    assert!(
        texts.contains(&"wrist at its limit 30 % of the time"),
        "{texts:?}"
    );
    assert!(texts.contains(&"arm refused 2× (workspace)"), "{texts:?}");
    assert_eq!(facts.arm.constraint.as_deref(), Some("vertical_axis"));
}

#[test]
fn joints_are_read_as_the_station_publishes_them_and_a_hand_state_that_fits_no_joint_is_a_note() {
    let model = HandModel::orca_v1_right();
    let settings = FeedbackSettings::default();
    let mut input = trial(&model, false);
    let renamed = |sample: &JointSample, prefix: &str| JointSample {
        names: model.dof_names().map(|n| format!("{prefix}{n}")).collect(),
        ..sample.clone()
    };
    // Commands under the configured prefix orca/…, the hand's state 2° off on every joint,
    // under the model's own names.
    input.joint_targets = input
        .joint_targets
        .iter()
        .map(|c| renamed(c, "orca/"))
        .collect();
    input.hand_states = input
        .joint_targets
        .iter()
        .map(|c| {
            let mut state = renamed(c, "");
            state.t_ns += 10 * MS;
            state
                .position
                .iter_mut()
                .for_each(|q| *q += 2f64.to_radians());
            state
        })
        .collect();
    let mut context = context(&model, &settings);
    context.joint_name_prefix = Some("orca/".into());
    let (facts, _) = review(&input, &context).unwrap();
    assert_eq!(facts.tracking_mean_deg.len(), 5, "{:?}", facts.notes);
    for (digit, error) in &facts.tracking_mean_deg {
        assert!((error - 2.0).abs() < 1e-6, "{digit}: {error}");
    }
    // A state naming nothing the model has: no tracking, said as a note, the rest reviewed.
    for state in &mut input.hand_states {
        state.names = (0..state.names.len())
            .map(|k| format!("joint{k}"))
            .collect();
    }
    let (facts, _) = review(&input, &context).unwrap();
    assert!(facts.tracking_mean_deg.is_empty());
    assert!(
        facts.notes[0]
            .starts_with("no tracking error: the hand's measured state has no joint named"),
        "{:?}",
        facts.notes
    );
}

#[test]
fn a_log_without_a_start_cannot_be_reviewed() {
    let model = HandModel::orca_v1_right();
    let settings = FeedbackSettings::default();
    let mut input = trial(&model, false);
    input.events.remove(0);
    let error = review(&input, &context(&model, &settings)).unwrap_err();
    assert!(
        error
            .to_string()
            .contains("trial.mcap: no trial `start` event"),
        "{error}"
    );
}
