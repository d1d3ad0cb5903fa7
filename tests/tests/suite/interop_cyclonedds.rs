//! The station with a ROS 2 peer nobody on this team wrote: Eclipse Cyclone DDS (PyPI
//! `cyclonedds`, its own C DDS stack and CDR), run as `tests/interop/cyclone_peer.py` on
//! loopback. The peer plays the glove (`/ingress/mano` Float32MultiArray 22 × 3 and
//! `/ingress/wrist` PoseStamped, ROS 2 naming and the QoS of the station's configuration) and
//! listens to the station's JointState, arm PoseStamped and `/hand/policy_output`.
//!
//! Values are checked both ways against the station's own recording of the run:
//! - inputs: every message the station decoded (its log) equals what Cyclone sent, frame for
//!   frame, including the wrist header and the DDS source timestamp;
//! - outputs: what Cyclone decoded equals, message for message, what the station sent (its log);
//! - the joint targets equal, bit for bit, what the station's control step (retargeter and all)
//!   computes in process from those frames (`teleop::resim` on the station's log: receive and
//!   tick times as recorded), and each names its frame by the frame's source time;
//! - the arm targets keep the vertical-axis constraint and follow the wrist's vertical motion.
//!
//! The recording itself is then decoded by the independent MCAP readers to the same values.

use std::path::{Path, PathBuf};

use msgs::{Float32MultiArray, JointState, PoseStamped, Time};
use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use pomdar_tests::cyclone_peer::{assert_same_messages, decode, run_station_with_peer};
use pomdar_tests::interop::{
    assert_readers_decode_as_we_do, independent_readers_with_values, interop_python,
};
use pomdar_tests::station_harness::{check_arm_targets, loopback, test_domain};
use retarget::human_hand::{HumanHandShape, Motion, MotionKind, SimGlove};
use retarget::{HandModel, KeypointLayout};
use serde_json::{Value, json};
use station::arm::Constraint;
use station::{ControlMode, StationConfig};
use teleop::mcap_log::{TrialReader, TrialWriter, TrialWriterOptions};
use teleop::resim::resim;
use teleop::ros::QosConfig;

const FRAMES: usize = 60;
const PERIOD_S: f64 = 0.02;

/// Every-frame control; reliable glove input so no frame is lost;
/// watchdog timeouts well above any scheduling stall of a loaded 2-core machine, so every
/// frame gets a fresh target (the watchdog is not this test's subject).
fn config(domain: u16) -> StationConfig {
    let mut config = StationConfig {
        network: loopback(domain),
        ..StationConfig::default()
    };
    config.control.mode = ControlMode::OnArrival;
    config.control.auto_engage = true;
    config.input.qos = QosConfig::reliable(1000);
    config.output.qos = QosConfig::reliable(1000);
    config.output.status_rate_hz = 20.0;
    config.arm.constraint = Constraint::VerticalAxis;
    config.watchdog.hold_timeout_ms = 2000;
    config.watchdog.disengage_timeout_ms = 5000;
    config
}

/// The glove wrist at `t`: a circle in the horizontal plane plus a vertical bob.
fn wrist(t: f64) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(0.03 * t.sin(), 0.03 * t.cos(), 0.02 * (4.0 * t).sin()),
        UnitQuaternion::from_euler_angles(0.1 * t.sin(), 0.0, 0.0),
    )
}

/// The glove frames as the station will receive them (f32 keypoints), and the wrist poses.
fn frames() -> (Vec<Vec<[f32; 3]>>, Vec<Isometry3<f64>>) {
    let shape = HumanHandShape::average();
    let motion = Motion::new(MotionKind::OpenClose, 4.0, &shape).unwrap();
    let glove = SimGlove::new(shape, motion, KeypointLayout::Lab22).unwrap();
    (0..FRAMES)
        .map(|i| {
            let t = i as f64 * PERIOD_S;
            let rows = glove
                .frame(t)
                .0
                .iter()
                .map(|p| [p.x as f32, p.y as f32, p.z as f32])
                .collect();
            (rows, wrist(t))
        })
        .unzip()
}

fn qos_json(qos: QosConfig) -> Value {
    serde_json::to_value(qos).unwrap()
}

/// The peer's plan: domain, topics, the station's QoS, the frames.
fn plan(config: &StationConfig, rows: &[Vec<[f32; 3]>], wrists: &[Isometry3<f64>]) -> Value {
    let frames: Vec<Value> = rows
        .iter()
        .zip(wrists)
        .map(|(rows, w)| {
            let q = w.rotation.quaternion();
            let p = w.translation.vector;
            json!({
                "points": rows.iter().map(|r| r.map(f64::from)).collect::<Vec<_>>(),
                "wrist": {"position": [p.x, p.y, p.z], "orientation": [q.i, q.j, q.k, q.w]},
            })
        })
        .collect();
    json!({
        "domain_id": config.network.domain_id,
        "topics": {
            "keypoints": config.input.keypoints_topic,
            "wrist": config.input.wrist_topic,
            "joint_targets": config.output.joint_targets_topic,
            "arm_target": config.output.arm_target_topic,
            "policy_output": config.policy_output.topic,
            "status": config.output.status_topic,
        },
        "input_qos": qos_json(config.input.qos),
        "output_qos": qos_json(config.output.qos),
        "status_qos": qos_json(QosConfig::reliable(10)),
        "wrist_frame_id": "coil",
        "period_s": PERIOD_S,
        "frames": frames,
    })
}

fn nanos(t: &Time) -> i64 {
    i64::from(t.sec) * 1_000_000_000 + i64::from(t.nanosec)
}

/// Inputs: the station decoded (its log) exactly what Cyclone sent, keypoints frame for frame
/// with their DDS source timestamps, and every wrist pose. Returns the source timestamps.
fn assert_station_decoded_what_cyclone_sent(
    report: &Value,
    log: &TrialReader,
    config: &StationConfig,
    rows: &[Vec<[f32; 3]>],
) -> Vec<i64> {
    let sent_keypoints: Vec<Float32MultiArray> = decode(report, "/sent/keypoints");
    let sent_wrists: Vec<PoseStamped> = decode(report, "/sent/wrist");
    let source_ns: Vec<i64> = decode(report, "/sent/source_ns");
    assert_eq!(sent_keypoints.len(), FRAMES);
    for (i, (message, frame)) in sent_keypoints.iter().zip(rows).enumerate() {
        assert_eq!(
            &message.points().unwrap(),
            frame,
            "frame {i} as Cyclone built it"
        );
    }
    let logged_keypoints: Vec<_> = log.messages_on(&config.input.keypoints_topic).collect();
    assert_eq!(
        logged_keypoints.len(),
        FRAMES,
        "keypoint frames the station received"
    );
    for (i, (logged, sent)) in logged_keypoints.iter().zip(&sent_keypoints).enumerate() {
        let decoded: Float32MultiArray = logged.decode().unwrap();
        assert_eq!(
            &decoded, sent,
            "keypoints {i}: as the station decoded them vs as sent"
        );
        assert_eq!(
            logged.publish_time_ns, source_ns[i],
            "keypoints {i}: the DDS source timestamp Cyclone wrote"
        );
    }
    let logged_wrists = log
        .decode_topic::<PoseStamped>(&config.input.wrist_topic)
        .unwrap();
    assert_eq!(
        logged_wrists.len(),
        sent_wrists.len(),
        "wrist poses received"
    );
    for (i, (decoded, sent)) in logged_wrists.iter().zip(&sent_wrists).enumerate() {
        assert_eq!(
            decoded, sent,
            "wrist pose {i}: as the station decoded it vs as sent"
        );
    }
    source_ns
}

/// What Cyclone received from the station.
struct Received {
    targets: Vec<JointState>,
    arm: Vec<PoseStamped>,
    policy: Vec<Float32MultiArray>,
}

/// Outputs: Cyclone decoded exactly what the station sent (its log), joint and arm targets
/// and policy outputs, and there were joint and arm targets.
fn assert_cyclone_decoded_what_the_station_sent(
    report: &Value,
    log: &TrialReader,
    config: &StationConfig,
) -> Received {
    let logged_targets = log
        .decode_topic::<JointState>(&config.output.joint_targets_topic)
        .unwrap();
    let targets: Vec<JointState> = decode(report, "/received/joint_targets");
    assert_same_messages("joint target", &targets, &logged_targets);
    let logged_arm = log
        .decode_topic::<PoseStamped>(&config.output.arm_target_topic)
        .unwrap();
    let arm: Vec<PoseStamped> = decode(report, "/received/arm_target");
    assert_same_messages("arm target", &arm, &logged_arm);
    let logged_policy = log
        .decode_topic::<Float32MultiArray>(&config.policy_output.topic)
        .unwrap();
    let policy: Vec<Float32MultiArray> = decode(report, "/received/policy_output");
    assert_same_messages("policy output", &policy, &logged_policy);
    assert!(!targets.is_empty() && !arm.is_empty());
    Received {
        targets,
        arm,
        policy,
    }
}

/// The joint targets are what the station's control step computes in process from the
/// frames as it received them (teleop::resim on its log: its receive times and its tick
/// times), bit for bit; each is stamped with the source time of a frame Cyclone sent, the
/// last with the last frame's. (Frames arriving together are solved once, for the newest,
/// so a loaded machine may give fewer targets than frames.)
fn assert_targets_as_computed_in_process(
    dir: &Path,
    log: &TrialReader,
    config: &StationConfig,
    received_targets: &[JointState],
    source_ns: &[i64],
) {
    let resim_path = dir.join("resim.mcap");
    let mut writer = TrialWriter::create(&resim_path, TrialWriterOptions::default()).unwrap();
    let stats = resim(log, config, HandModel::orca_v1_right(), &mut writer).unwrap();
    writer.finish().unwrap();
    assert_eq!(stats.ticks, "recorded");
    let computed = TrialReader::open(&resim_path)
        .unwrap()
        .decode_topic::<JointState>(&config.output.joint_targets_topic)
        .unwrap();
    assert_eq!(computed.len(), received_targets.len(), "joint targets");
    for (i, (c, r)) in computed.iter().zip(received_targets).enumerate() {
        assert_eq!(
            r, c,
            "joint target {i}: as Cyclone received it vs as computed in process"
        );
    }
    let stamps: Vec<i64> = received_targets
        .iter()
        .map(|m| nanos(&m.header.stamp))
        .collect();
    for (i, stamp) in stamps.iter().enumerate() {
        assert!(
            source_ns.contains(stamp),
            "joint target {i} is stamped {stamp}, not a frame's source time"
        );
    }
    assert!(
        stamps.windows(2).all(|w| w[0] < w[1]),
        "one target per frame solved"
    );
    assert_eq!(stamps.last(), source_ns.last(), "the last frame's target");
}

/// The arm follows the wrist along the vertical axis only.
fn assert_arm_follows_the_vertical_bob(received_arm: &[PoseStamped], config: &StationConfig) {
    let arm_poses: Vec<_> = received_arm
        .iter()
        .map(|m| station::convert::pose_to_isometry(&m.pose).unwrap())
        .collect();
    check_arm_targets(&arm_poses, &config.arm, Some(config.arm.vertical_axis));
    let first_z = arm_poses[0].translation.vector.z;
    let moved = arm_poses
        .iter()
        .map(|p| (p.translation.vector.z - first_z).abs())
        .fold(0.0, f64::max);
    assert!(
        moved > 0.005,
        "the arm should follow the vertical bob ({moved} m)"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn cyclone_dds_peer_drives_the_station_and_reads_its_outputs() {
    let Some(python) = interop_python() else {
        return;
    };
    let config = config(test_domain());
    let (rows, wrists) = frames();
    let dir = std::env::temp_dir().join(format!("pomdar-interop-cyclone-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    let plan_path = dir.join("plan.json");
    std::fs::write(&plan_path, plan(&config, &rows, &wrists).to_string()).unwrap();
    let log_path: PathBuf = dir.join("station.mcap");

    let script = "cyclone_peer.py";
    let report =
        run_station_with_peer(&python, script, &config, &plan_path, &log_path, FRAMES).await;
    let log = TrialReader::open(&log_path).unwrap();
    let source_ns = assert_station_decoded_what_cyclone_sent(&report, &log, &config, &rows);
    let received = assert_cyclone_decoded_what_the_station_sent(&report, &log, &config);
    assert_targets_as_computed_in_process(&dir, &log, &config, &received.targets, &source_ns);
    assert_arm_follows_the_vertical_bob(&received.arm, &config);
    println!(
        "Cyclone → station: {FRAMES} frames; station → Cyclone: {} joint targets, {} arm targets, {} policy outputs (matched in {:.2} s)",
        received.targets.len(),
        received.arm.len(),
        received.policy.len(),
        report["matched_s"].as_f64().unwrap_or(f64::NAN)
    );

    // The station's recording of this run: the independent readers decode every message to
    // the same values.
    if let Some(readers) = independent_readers_with_values(&log_path) {
        assert_readers_decode_as_we_do(&readers, &log);
    }
    std::fs::remove_dir_all(&dir).ok();
}
