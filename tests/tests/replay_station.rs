//! `pomdar replay` of the reference recording into a running station over loopback DDS gives
//! the same joint targets as the in-process re-simulation of the same recording (same
//! configuration), frame for frame; drops are counted and reported.
//!
//! The configuration makes the result independent of time steps (every-frame control, a joint
//! speed limit that never binds): the live station measures time steps from receive times,
//! the re-simulation from log times, and with a binding rate limit the two would legitimately
//! differ by the transport jitter times the speed limit.

#![allow(clippy::unwrap_used, clippy::expect_used)] // in tests a panic is the failure report

use std::time::Duration;

use msgs::JointState;
use pomdar_tests::interop::reference_file;
use pomdar_tests::station_harness::{Harness, test_domain, timing_independent_config};
use retarget::HandModel;
use teleop::mcap_log::{TrialReader, TrialWriter, TrialWriterOptions};
use teleop::replay::{ReplayOptions, replay};
use teleop::ros::QosConfig;
use tokio::sync::watch;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn replayed_reference_matches_the_in_process_resimulation() {
    let Some(path) = reference_file("rokoko_orca_2024-11-20.mcap") else {
        return;
    };
    let mut config = timing_independent_config();
    config.watchdog.hold_timeout_ms = 2000;
    config.watchdog.disengage_timeout_ms = 5000;

    // In process.
    let reader = TrialReader::open(&path).unwrap();
    let out = std::env::temp_dir().join(format!("pomdar-replay-resim-{}.mcap", std::process::id()));
    std::fs::remove_file(&out).ok();
    let mut writer = TrialWriter::create(&out, TrialWriterOptions::default()).unwrap();
    let stats =
        teleop::resim::resim(&reader, &config, HandModel::orca_v1_right(), &mut writer).unwrap();
    writer.finish().unwrap();
    let expected = TrialReader::open(&out)
        .unwrap()
        .decode_topic::<JointState>("/pomdar/hand/joint_targets")
        .unwrap();
    std::fs::remove_file(&out).ok();
    assert_eq!(expected.len() as u64, stats.frames_new);

    // Over DDS: the station under test, the recording replayed in real time (30 s).
    let h = Harness::start(config.clone(), test_domain(8))
        .await
        .unwrap();
    let options = ReplayOptions {
        rate: 1.0,
        topics: vec!["/ingress/mano".into(), "/ingress/wrist".into()],
        qos: QosConfig::reliable(2000),
        ..ReplayOptions::default()
    };
    let (_stop, stop_rx) = watch::channel(false);
    let report = replay(&reader, &h.network, &options, stop_rx)
        .await
        .unwrap();
    assert_eq!(report.published["/ingress/mano"], 6003);
    let _ = h
        .wait_until(Duration::from_secs(5), |heard| {
            heard.targets.len() >= expected.len()
        })
        .await;
    let live = h.target_positions();
    h.stop().await.unwrap();

    // Match frame for frame (each target names its frame by its stamp: the glove frame's
    // source time differs between replay and log, so match in order).
    let dropped = expected.len().saturating_sub(live.len());
    let matching = expected
        .iter()
        .zip(&live)
        .filter(|(e, l)| {
            e.position
                .iter()
                .zip(l.iter())
                .all(|(a, b)| (a - b).abs() <= 1e-6)
        })
        .count();
    let share = matching as f64 / expected.len() as f64;
    let worst = expected
        .iter()
        .zip(&live)
        .map(|(e, l)| {
            e.position
                .iter()
                .zip(l.iter())
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max);
    println!("largest difference {worst:.2e} rad");
    println!(
        "replay → station over DDS: {} of {} frames' targets match the re-simulation ({:.2} %), {dropped} dropped",
        matching,
        expected.len(),
        share * 100.0
    );
    assert!(share >= 0.99, "only {:.2} % match", share * 100.0);
}
