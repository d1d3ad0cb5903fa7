//! `pomdar calibrate` naming a pose the fit cannot match and capturing it again alone (the
//! built binary, simulated user on loopback DDS). The simulated user stays in pinch_middle
//! through pinch_ring's first capture: a steady capture, accepted, of the wrong pose. After
//! the fit the console names pinch_ring in words and offers to capture it again; the script
//! takes the offer; only pinch_ring is captured again, the fit runs again on the continued
//! log, and the fit changes. `--from` on that log fits the same profile.

use std::path::Path;

use calibration::{CalibrationProfile, FitCheck, POSE_NAMES, PoseSet, poses_that_do_not_fit};
use msgs::StringMsg;
use pomdar_tests::pomdar_binary::run_pomdar as pomdar;
use pomdar_tests::station_harness::test_domain;
use pomdar_tests::{path_arg, scratch_dir};
use serde_json::Value;
use teleop::calibrate::pose_session::REDO_EVENT;
use teleop::calibrate::session_events::{capture_attempts, capture_windows};
use teleop::mcap_log::{TRIAL_EVENTS_TOPIC, TrialReader};

const WRONG_POSE: &str = "pinch_ring";

fn read_profile(path: &Path) -> CalibrationProfile {
    CalibrationProfile::from_toml_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The number before `unit` after `prefix` in `line`.
fn number_after(line: &str, prefix: &str, unit: &str) -> f64 {
    let rest = &line[line.find(prefix).unwrap() + prefix.len()..];
    rest[..rest.find(unit).unwrap()].trim().parse().unwrap()
}

/// The continued log: pinch_ring captured twice, both accepted, the second used; every other
/// pose once; the redo and both fits' stops recorded.
fn check_continued_log(session: &Path) {
    let log = TrialReader::open(session).unwrap();
    let attempts = capture_attempts(&log).unwrap();
    for pose in POSE_NAMES {
        let of_pose: Vec<_> = attempts.iter().filter(|a| a.pose == pose).collect();
        let expected = if pose == WRONG_POSE { 2 } else { 1 };
        assert_eq!(of_pose.len(), expected, "{pose}: {of_pose:?}");
        assert!(
            of_pose
                .iter()
                .all(|a| a.decision.as_deref() == Some("accepted"))
        );
    }
    let ring: Vec<_> = attempts.iter().filter(|a| a.pose == WRONG_POSE).collect();
    assert_eq!(capture_windows(&log).unwrap()[WRONG_POSE], ring[1].window);
    let events: Vec<Value> = log
        .messages_on(TRIAL_EVENTS_TOPIC)
        .map(|m| m.decode::<StringMsg>().unwrap())
        .filter_map(|s| serde_json::from_str(&s.data).ok())
        .collect();
    let redo: Vec<&Value> = events.iter().filter(|e| e["event"] == REDO_EVENT).collect();
    assert_eq!(redo.len(), 1, "{redo:?}");
    assert_eq!(redo[0]["pose"], WRONG_POSE);
    assert_eq!(events.iter().filter(|e| e["event"] == "stop").count(), 2);
}

#[test]
fn a_pose_the_fit_cannot_match_is_named_and_captured_again_alone() {
    let dir = scratch_dir("calibrate-redo");
    let (profile, session) = (dir.join("profile.toml"), dir.join("session.mcap"));
    let script = dir.join("redo.script");
    std::fs::write(
        &script,
        "# the fit names pinch_ring: capture it again\n\
         wait complete 600\n\
         +0.3 retry\n\
         wait fitting 90\n\
         wait complete 600\n\
         quit\n",
    )
    .unwrap();
    let domain = test_domain().to_string();
    let output = pomdar(&[
        "calibrate",
        "--simulate",
        "--hand-scale",
        "1.15",
        "--glove-rpy",
        "8,-6,5",
        "--seed",
        "7",
        "--simulate-wrong-pose",
        WRONG_POSE,
        "--user",
        "wrong",
        "--out",
        path_arg(&profile),
        "--session-out",
        path_arg(&session),
        "--domain-id",
        &domain,
        "--script",
        path_arg(&script),
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "calibrate failed:\n{stderr}");

    // Named in words after the first fit, and offered.
    let named = stderr
        .lines()
        .find(|l| l.contains("pinch_ring: the thumb stays"))
        .unwrap_or_else(|| panic!("pinch_ring not named:\n{stderr}"));
    assert!(named.ends_with("— redo the pose?"), "{named}");
    let gap_mm = number_after(named, "the thumb stays", "mm");
    assert!(gap_mm > FitCheck::default().pinch_gap_mm, "{named}");
    assert!(
        stderr.contains("r captures pinch_ring again and fits again"),
        "{stderr}"
    );
    // No other pose was named.
    for pose in POSE_NAMES.iter().filter(|p| **p != WRONG_POSE) {
        for sentence in ["the thumb stays", "its joints stay"] {
            assert!(
                !stderr.contains(&format!("{pose}: {sentence}")),
                "{pose} named:\n{stderr}"
            );
        }
    }

    // The fit changed, and its objective came down.
    let changed = stderr
        .lines()
        .find(|l| l.contains("the fit changed: objective"))
        .unwrap_or_else(|| panic!("no second fit:\n{stderr}"));
    let before = number_after(changed, "objective", "→");
    let after = number_after(changed, "→", "rad");
    assert!(after < before, "{changed}");

    check_continued_log(&session);

    // The profile written last fits every pose; the recorded log fits to the same profile.
    let fitted = read_profile(&profile);
    let misfits = poses_that_do_not_fit(&fitted.poses, &PoseSet::orca_v1(), &FitCheck::default());
    assert!(misfits.is_empty(), "{misfits:?}");
    assert!((fitted.objective.after_rad - after).abs() < 1e-3);
    let again = dir.join("again.toml");
    let output = pomdar(&[
        "calibrate",
        "--from",
        path_arg(&session),
        "--user",
        "wrong",
        "--out",
        path_arg(&again),
    ]);
    assert!(output.status.success());
    assert_eq!(read_profile(&again).parameters, fitted.parameters);
}
