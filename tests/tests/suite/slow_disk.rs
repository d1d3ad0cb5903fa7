//! A disk that stalls stalls only the log: `pomdar demo --out` recording a 10 s run while
//! every flush of the log takes a second longer (`POMDAR_TEST_SLOW_DISK_MS=1000`), with the
//! simulated 100 Hz glove on loopback DDS. The station's loop hands each message to the
//! recorder thread and goes on, so no glove frame reaches it late enough to hold a command,
//! and every message the station recorded is in the log, or counted as dropped.

use std::process::Command;

use pomdar_tests::pomdar_binary::pomdar_binary;
use pomdar_tests::station_harness::test_domain;
use pomdar_tests::{files_with_extension, path_arg, scratch_dir};
use station::WatchdogConfig;
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
    let summary: serde_json::Value = serde_json::from_str(&stdout).unwrap();
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
