//! record == resim(record): a live station over loopback DDS, recorded through auto-engage, an
//! invalid wrist pose, a clutch (disengage, re-engage) and a glove drop-out long enough to
//! disengage it, re-simulated from its own log with the same configuration, gives the same
//! commands — every joint target, policy output and arm target, at the same log time, with the
//! same bytes.

use std::time::Duration;

use nalgebra::{Isometry3, Point3, Quaternion, Translation3, UnitQuaternion};
use pomdar_tests::scratch_dir;
use pomdar_tests::station_harness::{Harness, test_domain};
use retarget::{HandModel, KeypointLayout};
use station::StationConfig;
use teleop::mcap_log::{TrialReader, TrialWriter, TrialWriterOptions};
use teleop::station_node::recorder::RecordingOptions;
use teleop::station_node::ros_node::OperatorCommand;

const COMMAND_TOPICS: [&str; 3] = [
    "/pomdar/hand/joint_targets",
    "/hand/policy_output",
    "/franka/end_effector_pose_cmd",
];

/// The glove at step `k`: the index finger flexing, the wrist sliding along x.
fn glove(model: &HandModel, k: usize) -> (Vec<Point3<f64>>, Isometry3<f64>) {
    let mut q = model.zero_pose();
    q[model.dof_index("index_mcp").unwrap()] = 0.6 + 0.5 * (k as f64 * 0.15).sin();
    let points = model.synthetic_keypoints(&model.forward_new(&q).unwrap(), KeypointLayout::Lab22);
    let wrist = Isometry3::from_parts(
        Translation3::new(0.002 * k as f64, 0.0, 0.0),
        UnitQuaternion::identity(),
    );
    (points, wrist)
}

/// A wrist pose whose quaternion has norm 2: the station must count and ignore it.
fn invalid_wrist() -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(0.0, 0.0, 0.0),
        UnitQuaternion::new_unchecked(Quaternion::new(2.0, 0.0, 0.0, 0.0)),
    )
}

async fn play(h: &Harness, model: &HandModel, steps: std::ops::Range<usize>) {
    for k in steps {
        let (points, wrist) = glove(model, k);
        h.publish(&points, &wrist).await.unwrap();
        tokio::time::sleep(Duration::from_millis(25)).await;
    }
}

/// Every message on the command topics as (topic, log time, bytes), in log order.
fn commands(log: &TrialReader) -> Vec<(String, i64, Vec<u8>)> {
    let mut messages: Vec<_> = log
        .messages()
        .filter(|m| COMMAND_TOPICS.contains(&m.topic.as_str()))
        .map(|m| (m.topic.clone(), m.log_time_ns, m.data.clone()))
        .collect();
    messages.sort_by_key(|m| m.1);
    messages
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_recorded_live_run_resimulates_to_the_same_commands_byte_for_byte() {
    let model = HandModel::orca_v1_right();
    let mut config = StationConfig::default();
    config.control.auto_engage = true;
    let dir = scratch_dir("record-resim");
    let live_log = dir.join("live.mcap");
    let recording = RecordingOptions {
        path: live_log.clone(),
        metadata: [("source", "record_resim test")]
            .into_iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect(),
    };
    let h = Harness::start_recording(config.clone(), test_domain(), Some(recording))
        .await
        .unwrap();
    play(&h, &model, 0..40).await; // auto-engage on the first fresh frame
    let (points, _) = glove(&model, 40);
    h.publish(&points, &invalid_wrist()).await.unwrap();
    play(&h, &model, 41..60).await;
    h.operator(OperatorCommand::Disengage); // the clutch: reposition, then engage again
    play(&h, &model, 60..70).await;
    h.operator(OperatorCommand::Engage);
    play(&h, &model, 70..90).await;
    tokio::time::sleep(Duration::from_millis(1300)).await; // drop-out: hold, then disengage
    play(&h, &model, 90..100).await;
    h.operator(OperatorCommand::Engage);
    play(&h, &model, 100..120).await;
    tokio::time::sleep(Duration::from_millis(200)).await;
    let summary = h.stop().await.unwrap();
    assert_eq!(summary.totals.wrist_rejected, 1, "the invalid wrist pose");

    let live = TrialReader::open(&live_log).unwrap();
    let out = dir.join("resim.mcap");
    let mut writer = TrialWriter::create(&out, TrialWriterOptions::default()).unwrap();
    let stats = teleop::resim::resim(&live, &config, model, &mut writer).unwrap();
    writer.finish().unwrap();
    assert_eq!(stats.ticks, "recorded");
    let resimulated = TrialReader::open(&out).unwrap();

    let (recorded, replayed) = (commands(&live), commands(&resimulated));
    let held = recorded.iter().filter(|m| m.0 == COMMAND_TOPICS[2]).count();
    println!(
        "record == resim: {} commands recorded ({held} arm targets), {} re-simulated",
        recorded.len(),
        replayed.len()
    );
    assert!(recorded.len() > 150, "{} commands", recorded.len());
    assert!(held > 20, "{held} arm targets");
    let first_difference = recorded.iter().zip(&replayed).position(|(a, b)| a != b);
    assert_eq!(first_difference, None, "first command that differs");
    assert_eq!(recorded.len(), replayed.len());
    std::fs::remove_dir_all(&dir).ok();
}
