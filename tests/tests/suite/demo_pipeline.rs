//! The demo pipeline end to end over loopback DDS: the simulated glove node → the station →
//! the mock ORCA hand and mock Franka nodes, each on its own participant, as `pomdar demo`
//! runs them.

use std::path::Path;

use pomdar_tests::interop::{assert_readers_agree, independent_readers};
use pomdar_tests::station_harness::{check_arm_targets, test_domain};
use station::StationConfig;
use station::arm::{ArmConfig, Constraint};
use teleop::demo::{DemoOptions, DemoOutcome, DemoSummary, run_demo};
use teleop::mcap_log::TrialReader;
use teleop::stand_ins::sim_glove_node::SimGloveConfig;

/// The run's summary: glove above 80 Hz while it sends (its first to last frame: the wait for
/// discovery is not glove time), one joint target per new glove frame over the same span
/// (commands on frame arrival, the default), nothing rejected; the mock arm's targets on the
/// horizontal axis line through the first, inside the box, within the step caps.
fn assert_run(outcome: &DemoOutcome, arm: &ArmConfig) {
    let s = &outcome.summary;
    println!("{}", serde_json::to_string(s).unwrap());
    assert!(s.input_rate_hz > 80.0, "glove at {} Hz", s.input_rate_hz);
    assert!(
        s.output_rate_hz >= 0.9 * s.input_rate_hz && s.output_rate_hz <= 1.15 * s.input_rate_hz,
        "joint targets at {} Hz for glove frames at {} Hz",
        s.output_rate_hz,
        s.input_rate_hz
    );
    assert_eq!(s.rejected_frames, 0);
    assert_eq!(outcome.hand.rejected, 0);
    assert!(outcome.hand.last_target.is_some());

    assert!(
        outcome.arm.targets.len() > 40,
        "{} arm targets",
        outcome.arm.targets.len()
    );
    check_arm_targets(&outcome.arm.targets, arm, Some(arm.horizontal_axis));
}

/// The run's log: the same topics and counts as the run, with schemas, QoS, statistics and
/// the trial metadata.
fn assert_log_matches_run(log: &TrialReader, summary: &DemoSummary) {
    let count = |topic: &str| log.topic(topic).map_or(0, |t| t.message_count);
    assert_eq!(count("/pomdar/hand/joint_targets"), summary.hand_targets);
    assert_eq!(count("/franka/end_effector_pose_cmd"), summary.arm_targets);
    assert_eq!(
        count("/ingress/mano"),
        summary.frames_new + summary.frames_repeated + summary.rejected_frames,
        "every received frame"
    );
    assert!(
        count("/ingress/wrist") > 0
            && count("/pomdar/status") > 0
            && count("/hand/policy_output") > 0
    );
    assert_eq!(count("/pomdar/trial_events"), 2, "start and stop");
    for topic in log.topics() {
        assert!(topic.schema_text.contains(' '), "{}: schema", topic.topic);
        assert!(
            topic.offered_qos().is_some_and(|q| q.is_ok()),
            "{}: offered_qos_profiles",
            topic.topic
        );
    }
    let statistics = log.statistics().expect("statistics record");
    assert_eq!(statistics.message_count, log.message_count() as u64);
    let trial = log.metadata_named("pomdar_trial").expect("trial metadata");
    assert_eq!(trial["embodiment"], "orca_full");
    assert_eq!(trial["keypoint_source"], "simulated");
    assert!(trial["config_digest"].starts_with("fnv1a64:"));
}

/// Re-simulating the recorded run with the same configuration reproduces its joint targets
/// exactly (positions and stamps).
fn assert_resim_reproduces_the_run(log: &TrialReader, config: &StationConfig, out_dir: &Path) {
    let resim_out = out_dir.join("resim.mcap");
    let mut writer = teleop::mcap_log::TrialWriter::create(&resim_out, Default::default()).unwrap();
    let stats = teleop::resim::resim(
        log,
        config,
        retarget::HandModel::orca_v1_right(),
        &mut writer,
    )
    .unwrap();
    writer.finish().unwrap();
    assert_eq!(stats.ticks, "recorded");
    let recorded = log
        .decode_topic::<msgs::JointState>("/pomdar/hand/joint_targets")
        .unwrap();
    let resimulated = TrialReader::open(&resim_out)
        .unwrap()
        .decode_topic::<msgs::JointState>("/pomdar/hand/joint_targets")
        .unwrap();
    assert_eq!(resimulated.len(), recorded.len());
    for (i, (a, b)) in recorded.iter().zip(&resimulated).enumerate() {
        assert_eq!(a.position, b.position, "joint target {i}");
        assert_eq!(a.header.stamp, b.header.stamp, "stamp of joint target {i}");
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn sim_glove_station_mock_hand_and_arm() {
    let mut station = StationConfig::default();
    station.arm.constraint = Constraint::HorizontalAxis;
    let arm = station.arm.clone();
    // The configuration the demo runs (it engages on the first fresh frame).
    let mut station_config = station.clone();
    station_config.control.auto_engage = true;
    let out_dir = std::env::temp_dir().join(format!("pomdar-demo-{}", std::process::id()));
    std::fs::remove_dir_all(&out_dir).ok();
    let outcome = run_demo(DemoOptions {
        duration_s: 3.0,
        domain_id: test_domain(),
        station,
        glove: SimGloveConfig::default(),
        live: false,
        out: Some(out_dir.clone()),
        tap: None,
        physics: None,
    })
    .await
    .unwrap();
    assert_run(&outcome, &arm);

    // The run's log, then the independent readers decode every message.
    let path = outcome.recorded.clone().expect("the demo recorded its run");
    assert!(
        !teleop::mcap_log::part_path_for(&path).exists(),
        ".part left behind"
    );
    let log = TrialReader::open(&path).unwrap();
    assert_log_matches_run(&log, &outcome.summary);
    assert_resim_reproduces_the_run(&log, &station_config, &out_dir);
    if let Some(report) = independent_readers(&path) {
        assert_readers_agree(&report, &log);
    }
    std::fs::remove_dir_all(&out_dir).ok();
}
