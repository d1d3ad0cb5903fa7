//! A disk that stalls stalls only the log (`POMDAR_TEST_SLOW_DISK_MS`: every flush of a log
//! and every atomic file write takes that much longer), with simulated 100 Hz gloves on
//! loopback DDS:
//!
//! - `pomdar demo --out` recording a 10 s run at 1 s per flush: the station's loop hands each
//!   message to the recorder thread and goes on, so no glove frame reaches it late enough to
//!   hold a command, and every message the station recorded is in the log, or counted as
//!   dropped;
//! - `pomdar calibrate --simulate` at 0.5 s: the session log is written on a thread of its
//!   own, so the frames reach the session as the glove sent them, every pose is captured once
//!   with the frames the glove's rate promises, and the fit recovers the user;
//! - a scripted `pomdar trial --simulate` session at 0.5 s: the console's own disk waits
//!   (scoring a log, the manifest) neither hold up the station nor make the console take the
//!   station for silent, so every trial starts at once and none is cancelled.

use std::process::Command;

use calibration::POSE_NAMES;
use pomdar_tests::pomdar_binary::pomdar_binary;
use pomdar_tests::station_harness::test_domain;
use pomdar_tests::{files_with_extension, path_arg, scratch_dir, simulated_calibration_errors};
use serde_json::Value;
use station::WatchdogConfig;
use teleop::calibrate::session_events::{QUALITY_EVENT, capture_attempts};
use teleop::mcap_log::TRIAL_EVENTS_TOPIC;
use teleop::mcap_log::TrialReader;
use teleop::mcap_log::slow_disk::SLOW_DISK_ENV;

#[test]
fn a_disk_stalling_a_second_per_flush_holds_no_command_and_loses_no_uncounted_message() {
    let out = scratch_dir("slow_disk");
    let domain = test_domain().to_string();
    let output = Command::new(pomdar_binary().unwrap())
        .args(["demo", "--duration", "10", "--json", "--domain-id", &domain])
        .args(["--out", path_arg(&out)])
        .env(SLOW_DISK_ENV, "1000")
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stdout}\n{stderr}");
    let summary: Value = serde_json::from_str(&stdout).unwrap();
    println!("{summary:#}");

    // No gap between new frames as long as the hold timeout: nothing was held while the glove
    // played (the commands held after it stopped are the watchdog doing its job).
    let hold_ms = WatchdogConfig::default().hold_timeout_ms as f64;
    let gap = summary["longest_input_gap"]["received_ms"]
        .as_f64()
        .unwrap();
    assert!(
        gap < hold_ms,
        "a {gap:.0} ms gap between glove frames at the station (hold after {hold_ms} ms)"
    );
    let field = |name: &str| summary[name].as_u64().unwrap();
    // The log is created before the station starts (two flushes: 2 s); the glove waits for
    // the station, so about 8 of its 10 s reach it.
    assert!(field("frames_new") > 500, "{summary}");

    let logs = files_with_extension(&out, "mcap").unwrap();
    assert_eq!(logs.len(), 1, "{logs:?}");
    let log = TrialReader::open(&logs[0]).unwrap();
    let count = |topic: &str| log.topic(topic).map_or(0, |t| t.message_count);
    // What the robot received and the station's own counts, against what the log holds:
    // every message, or the shortfall is what the station counted as dropped.
    let expected = [
        ("/pomdar/hand/joint_targets", field("hand_targets")),
        ("/franka/end_effector_pose_cmd", field("arm_targets")),
        (
            "/ingress/mano",
            field("frames_new") + field("frames_repeated") + field("rejected_frames"),
        ),
    ];
    let mut shortfall = 0;
    for (topic, sent) in expected {
        let logged = count(topic);
        assert!(logged <= sent, "{topic}: {logged} logged of {sent}");
        shortfall += sent - logged;
    }
    let dropped = field("log_dropped");
    if dropped == 0 {
        assert_eq!(shortfall, 0, "nothing dropped, yet messages are missing");
    } else {
        assert!(
            shortfall <= dropped,
            "{shortfall} missing, {dropped} counted"
        );
    }
    assert_eq!(count("/pomdar/trial_events"), 2, "start and stop");
}

/// `pomdar args…` with the slow disk at `delay_ms`; fails the test with its output on an
/// unsuccessful exit. Returns stdout and stderr.
fn pomdar_on_a_slow_disk(args: &[&str], delay_ms: u64) -> (String, String) {
    let output = Command::new(pomdar_binary().unwrap())
        .args(args)
        .env(SLOW_DISK_ENV, delay_ms.to_string())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    println!(
        "$ pomdar {}\n--- stdout\n{stdout}--- stderr\n{stderr}",
        args.join(" ")
    );
    assert!(output.status.success(), "{stdout}\n{stderr}");
    (stdout, stderr)
}

#[test]
fn a_calibration_on_a_disk_stalling_half_a_second_captures_each_pose_once_and_fits() {
    let dir = scratch_dir("slow_disk_calibrate");
    let (profile, session) = (dir.join("profile.toml"), dir.join("session.mcap"));
    let domain = test_domain().to_string();
    let (stdout, _) = pomdar_on_a_slow_disk(
        &[
            "calibrate",
            "--simulate",
            "--seed",
            "11",
            "--user",
            "slow",
            "--domain-id",
            &domain,
            "--out",
            path_arg(&profile),
            "--session-out",
            path_arg(&session),
        ],
        500,
    );
    let log = TrialReader::open(&session).unwrap();
    let attempts = capture_attempts(&log).unwrap();
    let poses: Vec<&str> = attempts.iter().map(|a| a.pose.as_str()).collect();
    assert_eq!(poses, POSE_NAMES, "each pose captured once: {attempts:?}");
    // Each capture holds what the glove's rate promises: no burst of late frames.
    let qualities: Vec<Value> = log
        .messages_on(TRIAL_EVENTS_TOPIC)
        .map(|m| m.decode::<msgs::StringMsg>().unwrap())
        .filter_map(|s| serde_json::from_str::<Value>(&s.data).ok())
        .filter(|e| e["event"] == QUALITY_EVENT)
        .collect();
    assert_eq!(qualities.len(), POSE_NAMES.len());
    for q in &qualities {
        let frames = q["frames"].as_u64().unwrap() as f64;
        let expected = q["expected_frames"].as_u64().unwrap() as f64;
        assert!(
            (frames - expected).abs() <= 0.1 * expected && (90.0..=110.0).contains(&frames),
            "{q}"
        );
        assert_ne!(q["quality"], "bad", "{q}");
    }
    let (line, scale_error_pct, rotation_error_deg) = simulated_calibration_errors(&stdout);
    assert!(
        scale_error_pct.abs() <= 3.0 && rotation_error_deg <= 3.0,
        "{line}"
    );
}

#[test]
fn a_trial_session_on_a_disk_stalling_half_a_second_starts_every_trial_at_once() {
    let dir = scratch_dir("slow_disk_trial");
    let baseline = dir.join("baseline.toml");
    std::fs::write(
        &baseline,
        "[baseline]\nexample = false\nsource = \"slow disk test\"\n\n\
         [[task]]\nid = \"V1\"\nmean_s = 4.0\nn = 3\n",
    )
    .unwrap();
    let trial = "start\nwait running 30\n+1 mark 1\n+1 stop\n";
    let script = dir.join("v1.script");
    // The first start a second after the console is ready: the station's glove rate is
    // counted over its last second, so a start in the glove's first second waits for it
    // (and says so: "waiting for the station (glove rate 12.0 Hz is below the minimum …)"),
    // which is the console doing its job at launch, not a wait on the disk.
    std::fs::write(
        &script,
        format!("engage\nwait ready 30\n+1 {trial}wait summary 30\n{trial}wait complete 30\n"),
    )
    .unwrap();
    let domain = test_domain().to_string();
    let (_, stderr) = pomdar_on_a_slow_disk(
        &[
            "trial",
            "--task",
            "V1",
            "--user",
            "sim",
            "--operator",
            "ci",
            "--practice",
            "1",
            "--trials",
            "1",
            "--simulate",
            "--countdown",
            "0.5",
            "--domain-id",
            &domain,
            "--baseline",
            path_arg(&baseline),
            "--script",
            path_arg(&script),
            "--out",
            path_arg(&dir.join("sessions")),
        ],
        500,
    );
    for said in [
        "waiting for the station",
        "countdown cancelled",
        "input is stale",
    ] {
        assert!(
            !stderr.contains(said),
            "the console said '{said}':\n{stderr}"
        );
    }
    assert!(stderr.contains("session complete"), "{stderr}");
}
