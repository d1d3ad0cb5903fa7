//! `pomdar replay` of the reference recording into a running station over loopback DDS: the
//! station receives every glove frame of the recording, in order and unchanged, and its joint
//! targets are exactly what the in-process re-simulation computes from what it received.
//!
//! The station takes its time steps from the frames' own stamps (the replayer's DDS source
//! times, which keep the recording's spacing however the frames are delivered), so its targets
//! match the in-process re-simulation of the reference on at least 99 % of the frames (the
//! figure is printed), and they equal the re-simulation of its own log exactly.

use std::time::Duration;

use msgs::Float32MultiArray;
use msgs::JointState;
use pomdar_tests::interop::reference_file;
use pomdar_tests::scratch_dir;
use pomdar_tests::station_harness::{Harness, test_domain, timing_independent_config};
use retarget::HandModel;
use teleop::mcap_log::{TrialReader, TrialWriter, TrialWriterOptions};
use teleop::replay::{ReplayOptions, replay};
use teleop::ros::QosConfig;
use teleop::station_node::recorder::RecordingOptions;
use tokio::sync::watch;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn replayed_reference_matches_the_in_process_resimulation() {
    let Some(path) = reference_file("rokoko_orca_2024-11-20.mcap") else {
        return;
    };
    let mut config = timing_independent_config();
    config.watchdog.hold_timeout_ms = 2000;
    config.watchdog.disengage_timeout_ms = 5000;

    let dir = scratch_dir("replay-station");

    // In process, from the reference's log times.
    let reader = TrialReader::open(&path).unwrap();
    let (expected, frames_new) = resimulated_targets(&reader, &config, &dir.join("resim.mcap"));
    assert_eq!(expected.len() as u64, frames_new);

    // Over DDS: the station under test, recording what it receives, and the recording replayed
    // in real time (30 s).
    let live_log = dir.join("live.mcap");
    let recording = RecordingOptions {
        path: live_log.clone(),
        metadata: [("source", "replay_station test"), ("task", "replay")]
            .into_iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect(),
    };
    let h = Harness::start_recording(config.clone(), test_domain(), Some(recording))
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
    let live_targets = h.target_positions();
    h.stop().await.unwrap();

    // The glove frames arrived in order and unchanged, every distinct one of them (the
    // recording ends on repeats, which may still be in flight when the station stops).
    let topic = config.input.keypoints_topic.as_str();
    let live = TrialReader::open(&live_log).unwrap();
    let sent = reader.decode_topic::<Float32MultiArray>(topic).unwrap();
    let received = live.decode_topic::<Float32MultiArray>(topic).unwrap();
    assert!(received.len() <= sent.len(), "more glove frames than sent");
    let altered = sent
        .iter()
        .zip(&received)
        .position(|(a, b)| a.data != b.data);
    assert_eq!(
        altered, None,
        "first glove frame received altered or out of order"
    );
    let last_new = sent
        .windows(2)
        .rposition(|w| w[0].data != w[1].data)
        .map_or(0, |i| i + 1);
    assert!(
        received.len() > last_new,
        "{} of {} glove frames received: the last new one ({last_new}) is missing",
        received.len(),
        sent.len()
    );

    // The station's targets are the re-simulation of what it received, exactly.
    let (from_live, live_new) = resimulated_targets(&live, &config, &dir.join("resim-live.mcap"));
    assert_eq!(live_new, frames_new, "distinct glove frames received");
    assert_eq!(live_targets.len(), from_live.len(), "joint targets");
    for (i, (l, r)) in live_targets.iter().zip(&from_live).enumerate() {
        assert_eq!(l, &r.position, "joint target {i}");
    }

    // Against the reference's re-simulation (log times as time steps): a figure.
    let matching = expected
        .iter()
        .zip(&live_targets)
        .filter(|(e, l)| {
            e.position
                .iter()
                .zip(l.iter())
                .all(|(a, b)| (a - b).abs() <= 1e-6)
        })
        .count();
    println!(
        "replay → station over DDS: {} of {} glove frames received, {} joint targets equal to the re-simulation of its log; {matching} of {} equal to the reference's re-simulation ({:.1} %)",
        received.len(),
        sent.len(),
        live_targets.len(),
        expected.len(),
        100.0 * matching as f64 / expected.len() as f64
    );
    assert!(
        matching as f64 >= 0.99 * expected.len() as f64,
        "{matching} of {} joint targets match the in-process re-simulation (≥ 99 % required)",
        expected.len()
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// The joint targets of `log` re-simulated with `config` (written to `out`), and the number
/// of distinct glove frames.
fn resimulated_targets(
    log: &TrialReader,
    config: &station::StationConfig,
    out: &std::path::Path,
) -> (Vec<JointState>, u64) {
    let mut writer = TrialWriter::create(out, TrialWriterOptions::default()).unwrap();
    let stats = teleop::resim::resim(log, config, HandModel::orca_v1_right(), &mut writer).unwrap();
    writer.finish().unwrap();
    let targets = TrialReader::open(out)
        .unwrap()
        .decode_topic::<JointState>("/pomdar/hand/joint_targets")
        .unwrap();
    (targets, stats.frames_new)
}
