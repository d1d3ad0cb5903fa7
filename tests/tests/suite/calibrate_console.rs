//! `pomdar calibrate` in its console (the built binary, simulated user on loopback DDS): a
//! scripted session where one pose's first capture is bad (the simulated user shakes) and the
//! script retries it, and a session without an operator where the bad capture is retried
//! automatically. Checked: the session log keeps both captures of that pose with their
//! quality and marks the accepted one, the fit uses the accepted captures and still recovers
//! the user, and the printed table has every pose's error before and after.

use std::path::{Path, PathBuf};

use calibration::{CalibrationProfile, POSE_NAMES};
use msgs::StringMsg;
use pomdar_tests::pomdar_binary::run_pomdar as pomdar;
use pomdar_tests::station_harness::test_domain;
use pomdar_tests::{path_arg, scratch_dir, simulated_calibration_errors};
use serde_json::Value;
use teleop::calibrate::session_events::{
    CaptureAttempt, QUALITY_EVENT, capture_attempts, capture_windows,
};
use teleop::mcap_log::{TRIAL_EVENTS_TOPIC, TrialReader};

const BAD_POSE: &str = "pinch_ring";

struct Run {
    profile: PathBuf,
    session: PathBuf,
    stdout: String,
    stderr: String,
}

/// A simulated session (hand scale 1.15, glove 8,-6,5°, shaking at the first capture of
/// [`BAD_POSE`]), with `extra` arguments.
fn run(name: &str, extra: &[&str]) -> Run {
    let dir = scratch_dir(&format!("calibrate-console-{name}"));
    let profile = dir.join("profile.toml");
    let session = dir.join("session.mcap");
    let domain = test_domain().to_string();
    let mut args = vec![
        "calibrate",
        "--simulate",
        "--hand-scale",
        "1.15",
        "--glove-rpy",
        "8,-6,5",
        "--seed",
        "7",
        "--simulate-bad-pose",
        BAD_POSE,
        "--user",
        "shaky",
        "--out",
        path_arg(&profile),
        "--session-out",
        path_arg(&session),
        "--domain-id",
        &domain,
    ];
    args.extend_from_slice(extra);
    let output = pomdar(&args);
    let run = Run {
        profile: profile.clone(),
        session: session.clone(),
        stdout: String::from_utf8(output.stdout).unwrap(),
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
    };
    assert!(
        output.status.success(),
        "calibrate failed:\n{}\n{}",
        run.stdout,
        run.stderr
    );
    run
}

/// The quality events of the session log, by (pose, attempt).
fn quality_events(log: &TrialReader) -> Vec<Value> {
    log.messages_on(TRIAL_EVENTS_TOPIC)
        .map(|m| m.decode::<StringMsg>().unwrap())
        .filter_map(|s| serde_json::from_str::<Value>(&s.data).ok())
        .filter(|e| e["event"] == QUALITY_EVENT)
        .collect()
}

/// The log keeps both captures of the bad pose, the first bad and retried (by `by`), the
/// second accepted; every other pose one accepted capture; the fit's windows are the
/// accepted ones.
fn check_session(run: &Run, by: &str) {
    let log = TrialReader::open(&run.session).unwrap();
    let attempts = capture_attempts(&log).unwrap();
    for pose in POSE_NAMES {
        let of_pose: Vec<&CaptureAttempt> = attempts.iter().filter(|a| a.pose == pose).collect();
        if pose == BAD_POSE {
            assert_eq!(of_pose.len(), 2, "{of_pose:?}");
            assert_eq!(
                (
                    of_pose[0].attempt,
                    of_pose[0].quality.as_deref(),
                    of_pose[0].decision.as_deref()
                ),
                (1, Some("bad"), Some("retry")),
                "{of_pose:?}"
            );
            assert_eq!(of_pose[1].attempt, 2);
            assert_eq!(of_pose[1].decision.as_deref(), Some("accepted"));
            assert_ne!(of_pose[1].quality.as_deref(), Some("bad"));
            assert!(of_pose[1].window.0 >= of_pose[0].window.1);
        } else {
            assert_eq!(of_pose.len(), 1, "{pose}: {of_pose:?}");
            assert_eq!(of_pose[0].decision.as_deref(), Some("accepted"));
        }
    }
    let windows = capture_windows(&log).unwrap();
    assert_eq!(windows.len(), 7);
    let ring: Vec<&CaptureAttempt> = attempts.iter().filter(|a| a.pose == BAD_POSE).collect();
    assert_eq!(
        windows[BAD_POSE], ring[1].window,
        "the fit must use the accepted capture"
    );
    // The recorded measures: the shaking capture is far over the jitter limit.
    let ring_quality: Vec<Value> = quality_events(&log)
        .into_iter()
        .filter(|e| e["pose"] == BAD_POSE)
        .collect();
    assert_eq!(ring_quality.len(), 2);
    let jitter = |e: &Value| e["jitter_mm"].as_f64().unwrap();
    let limit = ring_quality[0]["jitter_limit_mm"].as_f64().unwrap();
    assert!(jitter(&ring_quality[0]) > limit, "{ring_quality:?}");
    assert!(jitter(&ring_quality[1]) <= limit, "{ring_quality:?}");
    assert!(ring_quality[1]["frames"].as_u64().unwrap() >= 50);
    // Who decided the retry.
    let decisions: Vec<Value> = log
        .messages_on(TRIAL_EVENTS_TOPIC)
        .map(|m| m.decode::<StringMsg>().unwrap())
        .filter_map(|s| serde_json::from_str::<Value>(&s.data).ok())
        .filter(|e| e["event"] == "calibration_capture_decision" && e["decision"] == "retry")
        .collect();
    assert_eq!(decisions.len(), 1, "{decisions:?}");
    assert_eq!(decisions[0]["by"], by);
}

/// The profile is valid and the printed comparison with the truth within 3 % and 3°; the
/// table has each pose's errors before and after.
fn check_fit(run: &Run) {
    let profile =
        CalibrationProfile::from_toml_str(&std::fs::read_to_string(&run.profile).unwrap()).unwrap();
    profile.validate().unwrap();
    assert_eq!(profile.user, "shaky");
    assert!(profile.objective.after_rad < profile.objective.before_rad);
    assert!(
        run.stdout.contains("before (rad)") && run.stdout.contains("after (rad)"),
        "{}",
        run.stdout
    );
    for (pose, report) in POSE_NAMES.iter().zip(&profile.poses) {
        let line = run
            .stdout
            .lines()
            .find(|l| l.starts_with(pose) && l[pose.len()..].starts_with(' '))
            .unwrap_or_else(|| panic!("no table row for {pose} in:\n{}", run.stdout));
        let numbers: Vec<f64> = line[pose.len()..]
            .split_whitespace()
            .filter_map(|w| w.parse().ok())
            .collect();
        assert!(numbers.len() >= 3, "{line}");
        assert!(
            (numbers[1] - report.joint_rms_before_rad).abs() < 1e-3
                && (numbers[2] - report.joint_rms_after_rad).abs() < 1e-3,
            "{line} vs {report:?}"
        );
    }
    let (line, scale_error_pct, rotation_error_deg) = simulated_calibration_errors(&run.stdout);
    assert!(
        scale_error_pct.abs() <= 3.0 && rotation_error_deg <= 3.0,
        "{line}"
    );
    assert!(
        run.stdout
            .contains(&format!("wrote {} (user shaky)", run.profile.display())),
        "{}",
        run.stdout
    );
}

#[test]
fn a_scripted_session_retries_the_bad_capture_and_fits_the_accepted_ones() {
    let dir = scratch_dir("calibrate-console-script");
    let script = dir.join("retry.script");
    std::fs::write(
        &script,
        "# the shaking capture of pinch_ring waits for a decision: capture it again\n\
         wait review 90\n\
         +0.3 retry\n\
         wait complete 600\n\
         quit\n",
    )
    .unwrap();
    let run = run("scripted", &["--script", path_arg(&script)]);
    check_session(&run, "operator");
    check_fit(&run);
    // The line console showed the meter of the bad capture and the review.
    assert!(
        run.stderr
            .contains(&format!("{BAD_POSE} capture 1: [..........] BAD")),
        "{}",
        run.stderr
    );
    assert!(run.stderr.contains("CAPTURE REVIEW"), "{}", run.stderr);
    assert!(
        run.stderr.contains("captured again: pinch_ring ×2"),
        "{}",
        run.stderr
    );

    // Fitting the recorded session again (--from) uses the same accepted captures.
    let again = dir.join("again.toml");
    let output = pomdar(&[
        "calibrate",
        "--from",
        path_arg(&run.session),
        "--user",
        "shaky",
        "--out",
        path_arg(&again),
    ]);
    assert!(output.status.success());
    let read =
        |p: &Path| CalibrationProfile::from_toml_str(&std::fs::read_to_string(p).unwrap()).unwrap();
    assert_eq!(read(&again).parameters, read(&run.profile).parameters);
}

#[test]
fn without_an_operator_a_bad_capture_is_retried_automatically() {
    let run = run("automatic", &[]);
    check_session(&run, "auto");
    check_fit(&run);
}

#[test]
fn a_script_that_waits_for_nothing_fails_naming_its_line() {
    let dir = scratch_dir("calibrate-console-timeout");
    let script = dir.join("bad.script");
    std::fs::write(&script, "wait fitting 0.5\n").unwrap();
    let output = pomdar(&[
        "calibrate",
        "--simulate",
        "--user",
        "x",
        "--out",
        path_arg(&dir.join("p.toml")),
        "--session-out",
        path_arg(&dir.join("s.mcap")),
        "--domain-id",
        &test_domain().to_string(),
        "--script",
        path_arg(&script),
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert!(
        stderr.contains("script line 1") && stderr.contains("'fitting'"),
        "{stderr}"
    );
    assert!(!dir.join("p.toml").exists(), "a profile was written");
    // The abandoned session's log is kept, with the reason.
    assert!(dir.join("s.mcap").exists());
}
