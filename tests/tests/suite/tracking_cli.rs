//! `pomdar tracking` as the operator runs it (the built binary) on a real trial log: `pomdar
//! demo` records a run of the station with the simulated glove and the mock ORCA hand on
//! loopback DDS (the hand's measured state recorded beside the commands), then the command
//! compares them per joint and writes its figure and JSON. A station-style trial without the
//! hand's state is refused with the file and the topic named.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use pomdar_tests::pomdar_binary::run_pomdar as pomdar;
use pomdar_tests::station_harness::test_domain;
use pomdar_tests::{files_with_extension, path_arg, scratch_dir};
use serde_json::Value;
use teleop::score::synthetic_trial::{SyntheticTrial, write_synthetic_trial};

/// The mock hand's first-order lag, ms (`MockHandConfig::default`).
const MOCK_HAND_TIME_CONSTANT_MS: f64 = 30.0;

/// Records a 4 s demo run in `dir` and returns its log.
fn record_demo(dir: &Path) -> PathBuf {
    let domain = test_domain().to_string();
    let out = pomdar(&[
        "demo",
        "--duration",
        "4",
        "--json",
        "--domain-id",
        &domain,
        "--out",
        path_arg(dir),
    ]);
    assert!(out.status.success(), "pomdar demo failed");
    let logs = files_with_extension(dir, "mcap").unwrap();
    assert_eq!(logs.len(), 1, "{logs:?}");
    logs[0].clone()
}

fn joints(report: &Value) -> &Vec<Value> {
    report["joints"].as_array().expect("joints")
}

#[test]
fn a_demo_run_is_compared_per_joint_with_its_figure_and_json() {
    let dir = scratch_dir("tracking-cli");
    let log = record_demo(&dir.join("run"));
    let out_dir = dir.join("report");
    let out = pomdar(&[
        "tracking",
        path_arg(&log),
        "--json",
        "--out",
        path_arg(&out_dir),
    ]);
    assert!(out.status.success(), "pomdar tracking failed");
    let report: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(report["measured_topic"], "/pomdar/hand/joint_states");
    assert_eq!(report["commanded_topic"], "/pomdar/hand/joint_targets");
    let joints = joints(&report);
    assert_eq!(joints.len(), 17);
    // The mock hand publishes at 100 Hz for the whole run: some 400 states in 4 s.
    assert!(report["states"].as_u64().unwrap() > 200, "{report}");
    for j in joints {
        assert!(j["measured_samples"].as_u64().unwrap() > 200, "{j}");
        assert!(j["compared_samples"].as_u64().unwrap() > 0, "{j}");
        assert!(j["rms_error_deg"].as_f64().unwrap() < 10.0, "{j}");
    }
    // The joints that move with the glove (a clear correlation) lag by about the hand's
    // time constant: tens of milliseconds, never the 0 or 300 ms ends.
    let mut lags: Vec<f64> = joints
        .iter()
        .filter(|j| j["lag_correlation"].as_f64().is_some_and(|r| r > 0.98))
        .map(|j| j["lag_ms"].as_f64().unwrap())
        .collect();
    assert!(lags.len() >= 8, "{lags:?}");
    lags.sort_by(f64::total_cmp);
    let median = lags[lags.len() / 2];
    assert!(
        (0.3 * MOCK_HAND_TIME_CONSTANT_MS..=3.0 * MOCK_HAND_TIME_CONSTANT_MS).contains(&median),
        "median lag {median} ms of {lags:?}"
    );

    // The files: the JSON is the report printed, the figure one titled panel per joint.
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("tracking.json")).unwrap())
            .unwrap();
    assert_eq!(json, report);
    let svg = std::fs::read_to_string(out_dir.join("tracking.svg")).unwrap();
    assert!(svg.starts_with("<svg ") && svg.trim_end().ends_with("</svg>"));
    assert_eq!(svg.matches(r#"class="panel""#).count(), 17);
    for j in joints {
        let title = format!(">{}  RMS ", j["joint"].as_str().unwrap());
        assert!(svg.contains(&title), "no panel titled {title}");
    }
    let png = std::fs::read(out_dir.join("tracking.png")).unwrap();
    let image = tiny_skia::Pixmap::decode_png(&png).unwrap();
    assert!(image.width() > 1000 && image.height() > 900);
    let leftovers: Vec<_> = std::fs::read_dir(&out_dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .filter(|n| n.to_string_lossy().ends_with(".part"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");

    // The table names every joint.
    let table = pomdar(&["tracking", path_arg(&log)]);
    assert!(table.status.success());
    let text = String::from_utf8_lossy(&table.stdout);
    for j in joints {
        assert!(text.contains(j["joint"].as_str().unwrap()), "{text}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_log_without_the_hands_state_is_refused_naming_the_file_and_topic() {
    let dir = scratch_dir("tracking-cli-no-state");
    let log = dir.join("trial.mcap");
    let trial = SyntheticTrial {
        metadata: BTreeMap::from([
            ("task".into(), "V1".into()),
            ("embodiment".into(), "orca_full".into()),
        ]),
        t0_ns: 1_732_100_000_000_000_000,
        duration_s: 3.0,
        events: vec![],
        keypoint_rate_hz: 100.0,
        joint_rate_hz: 25.0,
        seed: 3,
    };
    write_synthetic_trial(&log, &trial).unwrap();
    let out_dir = dir.join("report");
    let out = pomdar(&["tracking", path_arg(&log), "--out", path_arg(&out_dir)]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(path_arg(&log)) && stderr.contains("/pomdar/hand/joint_states"),
        "{stderr}"
    );
    assert!(out.stdout.is_empty());
    assert!(!out_dir.exists(), "nothing is written");
    std::fs::remove_dir_all(&dir).ok();
}
