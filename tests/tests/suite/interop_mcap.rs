//! The station reads MCAP it did not write: the same glove recording written by two independent
//! writers from PyPI (`tests/interop/write_mcap.py`: `rosbags`' rosbag2 writer with storage
//! mcap and zstd chunks, with its own message definitions and CDR; the `mcap` writer with
//! `mcap-ros2-support`, lz4 chunks, its own CDR from .msg schema texts).
//!
//! - `TrialReader` decodes every message of both files to exactly the values written (keypoints
//!   as f32, wrist poses with header, joint states, UTF-8 strings), with their log times,
//!   publish times, sequence numbers, types, encodings, statistics and (rosbags) offered QoS;
//! - `pomdar resim` (the built binary) re-simulates both files to exactly the outputs it
//!   computes from the same recording written by the station's own `TrialWriter`: same joint
//!   targets, arm targets (vertical axis: they follow the wrist) and policy outputs at the same
//!   times, and the same statistics;
//! - the independent readers decode the station's re-simulation logs to the same values as the
//!   station (the other kinds of station file are checked in `interop_cyclonedds.rs`, a live
//!   trial, and `calibrate_cli.rs`, a calibration session).

use std::path::{Path, PathBuf};
use std::process::Command;

use msgs::{Float32MultiArray, JointState, PoseStamped, StringMsg};
use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use pomdar_tests::interop::{
    assert_readers_decode_as_we_do, independent_readers_with_values, interop_python,
    run_interop_script,
};
use pomdar_tests::pomdar_binary::pomdar_binary;
use retarget::KeypointLayout;
use retarget::human_hand::{HumanHandShape, Motion, MotionKind, SimGlove};
use serde_json::{Value, json};
use station::convert::{header, isometry_to_pose};
use teleop::mcap_log::{OfferedQos, TrialReader, TrialWriter, TrialWriterOptions};

const FRAMES: usize = 50;
const PERIOD_NS: i64 = 20_000_000;
/// Log time of the first frame (a fixed instant: the files are reproducible).
const T0_NS: i64 = 1_763_000_000_123_456_789;
const KEYPOINTS: &str = "/ingress/mano";
const WRIST: &str = "/ingress/wrist";
const JOINT_STATES: &str = "/joint_states";
const NOTES: &str = "/notes";
const QOS_DEPTH: u32 = 10;

/// The recording every writer writes: topic, log time and message, in log-time order.
struct Recording {
    keypoints: Vec<(i64, Float32MultiArray)>,
    wrists: Vec<(i64, PoseStamped)>,
    joint_states: Vec<(i64, JointState)>,
    notes: Vec<(i64, StringMsg)>,
}

fn wrist(t: f64) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(0.03 * t.sin(), 0.03 * t.cos(), 0.02 * (4.0 * t).sin()),
        UnitQuaternion::from_euler_angles(0.1 * t.sin(), 0.05, -0.2),
    )
}

fn recording() -> Recording {
    let shape = HumanHandShape::average();
    let motion = Motion::new(MotionKind::OpenClose, 4.0, &shape).unwrap();
    let glove = SimGlove::new(shape, motion, KeypointLayout::Lab22).unwrap();
    let mut keypoints = Vec::new();
    let mut wrists = Vec::new();
    for i in 0..FRAMES {
        let log_ns = T0_NS + i as i64 * PERIOD_NS;
        let t = i as f64 * PERIOD_NS as f64 * 1e-9;
        let rows: Vec<[f32; 3]> = glove
            .frame(t)
            .0
            .iter()
            .map(|p| [p.x as f32, p.y as f32, p.z as f32])
            .collect();
        keypoints.push((log_ns, Float32MultiArray::from_points(&rows).unwrap()));
        wrists.push((
            log_ns,
            PoseStamped {
                header: header(log_ns - 2_000_000, "coil"),
                pose: isometry_to_pose(&wrist(t)),
            },
        ));
    }
    let joint_states = (0..3)
        .map(|k| {
            let log_ns = T0_NS + 5_000_000 + k * 300_000_000;
            let message = JointState {
                header: header(log_ns - 1, ""),
                name: vec!["index_mcp".into(), "wrist".into()],
                position: vec![0.25 * k as f64, -1.0e-7],
                velocity: vec![],
                effort: vec![1.5, k as f64 - 0.125],
            };
            (log_ns, message)
        })
        .collect();
    let notes = [
        (T0_NS + 7_000_000, "start"),
        (T0_NS + 900_000_000, "Grüße, 手"),
    ]
    .into_iter()
    .map(|(t, text)| (t, StringMsg { data: text.into() }))
    .collect();
    Recording {
        keypoints,
        wrists,
        joint_states,
        notes,
    }
}

/// The plan for `write_mcap.py`: the same recording as plain JSON.
fn plan(r: &Recording) -> Value {
    let frames: Vec<Value> = r
        .keypoints
        .iter()
        .zip(&r.wrists)
        .map(|((t, k), (_, w))| {
            let p = &w.pose;
            json!({
                "log_time_ns": t,
                "points": k.points().unwrap().iter().map(|row| row.map(f64::from)).collect::<Vec<_>>(),
                "wrist": {
                    "stamp_ns": nanos(&w.header.stamp),
                    "frame_id": w.header.frame_id,
                    "position": [p.position.x, p.position.y, p.position.z],
                    "orientation": [p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w],
                },
            })
        })
        .collect();
    let joint_states: Vec<Value> = r
        .joint_states
        .iter()
        .map(|(t, m)| {
            json!({"log_time_ns": t, "stamp_ns": nanos(&m.header.stamp), "name": m.name,
                   "position": m.position, "velocity": m.velocity, "effort": m.effort})
        })
        .collect();
    let notes: Vec<Value> = r
        .notes
        .iter()
        .map(|(t, m)| json!({"log_time_ns": t, "text": m.data}))
        .collect();
    json!({
        "keypoints_topic": KEYPOINTS, "wrist_topic": WRIST,
        "joint_states_topic": JOINT_STATES, "notes_topic": NOTES, "qos_depth": QOS_DEPTH,
        "frames": frames, "joint_states": joint_states, "notes": notes,
    })
}

fn nanos(t: &msgs::Time) -> i64 {
    i64::from(t.sec) * 1_000_000_000 + i64::from(t.nanosec)
}

/// The same recording written by the station's own writer (the reference for resim), with
/// publish time = log time - `publish_lead_ns` (a fresh command is stamped with its frame's
/// publish time, so the reference must have the other writer's).
fn write_reference(r: &Recording, path: &Path, publish_lead_ns: i64) {
    let mut writer = TrialWriter::create(path, TrialWriterOptions::default()).unwrap();
    let qos = [OfferedQos::reliable(QOS_DEPTH)];
    writer
        .add_channel::<Float32MultiArray>(KEYPOINTS, &qos)
        .unwrap();
    writer.add_channel::<PoseStamped>(WRIST, &qos).unwrap();
    writer
        .add_channel::<JointState>(JOINT_STATES, &qos)
        .unwrap();
    writer.add_channel::<StringMsg>(NOTES, &qos).unwrap();
    let mut all: Vec<(i64, u8, usize)> = Vec::new();
    // Same order as write_mcap.py: by log time, the wrist before the keypoints of a frame.
    for i in 0..FRAMES {
        all.push((r.wrists[i].0, 0, i));
        all.push((r.keypoints[i].0, 1, i));
    }
    all.extend(r.joint_states.iter().enumerate().map(|(i, m)| (m.0, 2, i)));
    all.extend(r.notes.iter().enumerate().map(|(i, m)| (m.0, 3, i)));
    all.sort_by_key(|m| m.0);
    for (t, kind, i) in all {
        let p = t - publish_lead_ns;
        match kind {
            0 => writer.write(WRIST, t, p, &r.wrists[i].1),
            1 => writer.write(KEYPOINTS, t, p, &r.keypoints[i].1),
            2 => writer.write(JOINT_STATES, t, p, &r.joint_states[i].1),
            _ => writer.write(NOTES, t, p, &r.notes[i].1),
        }
        .unwrap();
    }
    writer.finish().unwrap();
}

/// Every message on `topic` decodes to exactly `expected`, at the expected log times.
fn assert_topic<M>(log: &TrialReader, topic: &str, expected: &[(i64, M)])
where
    M: msgs::RosMessage + PartialEq + std::fmt::Debug,
{
    let name = log.path().display();
    let info = log
        .topic(topic)
        .unwrap_or_else(|| panic!("{name}: no {topic}"));
    assert_eq!(info.type_name, M::ros_type_name(), "{name}: {topic} type");
    assert_eq!(info.message_encoding, "cdr", "{name}: {topic} encoding");
    assert_eq!(info.schema_encoding, "ros2msg", "{name}: {topic} schema");
    let logged: Vec<_> = log.messages_on(topic).collect();
    assert_eq!(logged.len(), expected.len(), "{name}: {topic} count");
    for (i, (message, (t, value))) in logged.iter().zip(expected).enumerate() {
        assert_eq!(message.log_time_ns, *t, "{name}: {topic} {i} log time");
        let decoded: M = message
            .decode()
            .unwrap_or_else(|e| panic!("{name}: {topic} {i}: {e}"));
        assert_eq!(
            &decoded, value,
            "{name}: {topic} {i} as the station decodes it"
        );
    }
}

fn assert_reads_the_recording(log: &TrialReader, r: &Recording) {
    assert_eq!(log.profile(), "ros2");
    assert_topic(log, KEYPOINTS, &r.keypoints);
    assert_topic(log, WRIST, &r.wrists);
    assert_topic(log, JOINT_STATES, &r.joint_states);
    assert_topic(log, NOTES, &r.notes);
    let total = 2 * FRAMES + r.joint_states.len() + r.notes.len();
    assert_eq!(log.message_count(), total);
    let statistics = log.statistics().expect("statistics record");
    assert_eq!(statistics.message_count, total as u64);
}

struct Resimulated {
    stats: Value,
    log: TrialReader,
}

/// `pomdar resim INPUT --config CONFIG --out OUT --stats-json STATS`.
fn resim(input: &Path, config: &Path, out: &Path) -> Resimulated {
    let stats_path = out.with_extension("json");
    let output = Command::new(pomdar_binary().unwrap())
        .arg("resim")
        .arg(input)
        .arg("--config")
        .arg(config)
        .arg("--out")
        .arg(out)
        .arg("--stats-json")
        .arg(&stats_path)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "pomdar resim {}: {}",
        input.display(),
        String::from_utf8_lossy(&output.stderr)
    );
    Resimulated {
        stats: serde_json::from_str(&std::fs::read_to_string(&stats_path).unwrap()).unwrap(),
        log: TrialReader::open(out).unwrap(),
    }
}

/// The outputs of a re-simulation: per output topic, (log time, decoded message as JSON).
fn outputs(log: &TrialReader) -> Vec<(String, i64, Value)> {
    log.messages()
        .map(|m| {
            let value = pomdar_tests::interop::decoded_as_json(m).unwrap();
            (m.topic.clone(), m.log_time_ns, value)
        })
        .collect()
}

/// The `rosbags` file: every value, time and type as written; publish time = log time,
/// sequence 0; each topic's offered QoS as written.
fn assert_reads_the_rosbags_file(path: &Path, r: &Recording) {
    let rosbags = TrialReader::open(path).unwrap();
    assert_reads_the_recording(&rosbags, r);
    assert!(
        rosbags.library().starts_with("rosbags"),
        "{}",
        rosbags.library()
    );
    for m in rosbags.messages() {
        assert_eq!(
            (m.publish_time_ns, m.sequence),
            (m.log_time_ns, 0),
            "{}",
            m.topic
        );
    }
    for topic in rosbags.topics() {
        let qos = topic.offered_qos().expect("offered_qos_profiles").unwrap();
        assert_eq!(
            qos,
            vec![OfferedQos::reliable(QOS_DEPTH)],
            "{}",
            topic.topic
        );
    }
}

/// The `mcap` writer's file: every value, time and type as written; published 1 ms before
/// logged, sequence numbers from 1.
fn assert_reads_the_mcap_writer_file(path: &Path, r: &Recording) {
    let mcap = TrialReader::open(path).unwrap();
    assert_reads_the_recording(&mcap, r);
    assert!(
        mcap.library().contains("mcap-ros2-support"),
        "{}",
        mcap.library()
    );
    for (i, m) in mcap.messages().enumerate() {
        assert_eq!(m.publish_time_ns, m.log_time_ns - 1_000_000, "{}", m.topic);
        assert_eq!(m.sequence as usize, i + 1, "{}", m.topic);
    }
}

/// `pomdar resim` of the station's own file of the recording (publish times `publish_lead_ns`
/// before log times, like the `name` writer's): at least 20 joint and arm targets, every
/// frame read and new. Returns the re-simulation and its outputs.
fn resim_station_reference(
    dir: &Path,
    config: &Path,
    r: &Recording,
    name: &str,
    publish_lead_ns: i64,
) -> (Resimulated, Vec<(String, i64, Value)>) {
    let reference_path = dir.join(format!("station-as-{name}.mcap"));
    write_reference(r, &reference_path, publish_lead_ns);
    let reference = resim(
        &reference_path,
        config,
        &dir.join(format!("resim-station-as-{name}.mcap")),
    );
    let expected = outputs(&reference.log);
    let count = |topic: &str| expected.iter().filter(|(t, _, _)| t == topic).count();
    assert!(
        count("/pomdar/hand/joint_targets") >= 20 && count("/franka/end_effector_pose_cmd") >= 20,
        "reference resim outputs: {}",
        reference.stats
    );
    assert_eq!(reference.stats["frames_read"], FRAMES);
    assert_eq!(reference.stats["frames_new"], FRAMES);
    (reference, expected)
}

/// `pomdar resim` of the `name` writer's file gives the same statistics and outputs as the
/// station's own file of the same recording; the independent readers decode its log as the
/// station does.
fn assert_resim_matches_the_station_file(
    dir: &Path,
    config: &Path,
    r: &Recording,
    name: &str,
    input: &Path,
    publish_lead_ns: i64,
) {
    let (reference, expected) = resim_station_reference(dir, config, r, name, publish_lead_ns);
    let out = dir.join(format!("resim-{name}.mcap"));
    let resimulated = resim(input, config, &out);
    for key in [
        "frames_read",
        "frames_new",
        "frames_repeated",
        "rejected",
        "joint_targets",
        "arm_targets",
        "layout",
        "ticks",
    ] {
        assert_eq!(
            resimulated.stats[key], reference.stats[key],
            "resim of the {name} file: {key}"
        );
    }
    let got = outputs(&resimulated.log);
    assert_eq!(
        got.len(),
        expected.len(),
        "resim of the {name} file: outputs"
    );
    for (i, (g, e)) in got.iter().zip(&expected).enumerate() {
        assert_eq!(g, e, "resim of the {name} file: output {i}");
    }
    // The station's own log of this re-simulation, through the independent readers.
    if let Some(report) = independent_readers_with_values(&out) {
        assert_readers_decode_as_we_do(&report, &resimulated.log);
    }
}

#[test]
fn the_station_reads_mcap_written_by_rosbags_and_by_the_mcap_writer() {
    let Some(python) = interop_python() else {
        return;
    };
    let dir: PathBuf =
        std::env::temp_dir().join(format!("pomdar-interop-mcap-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    let r = recording();
    let plan_path = dir.join("plan.json");
    std::fs::write(&plan_path, plan(&r).to_string()).unwrap();
    let written = run_interop_script(
        &python,
        "write_mcap.py",
        &[plan_path.as_os_str(), dir.as_os_str()],
    );
    let rosbags_path = PathBuf::from(written["rosbags"].as_str().unwrap());
    let mcap_path = PathBuf::from(written["mcap_ros2"].as_str().unwrap());

    // TrialReader: every value, time and type as written.
    assert_reads_the_rosbags_file(&rosbags_path, &r);
    assert_reads_the_mcap_writer_file(&mcap_path, &r);

    // pomdar resim: the same outputs from each writer's file as from the station's own file
    // of the same recording.
    let config = dir.join("station.toml");
    std::fs::write(&config, "[arm]\nconstraint = \"vertical_axis\"\n").unwrap();
    for (name, input, publish_lead_ns) in [
        ("rosbags", &rosbags_path, 0),
        ("mcap_ros2", &mcap_path, 1_000_000),
    ] {
        assert_resim_matches_the_station_file(&dir, &config, &r, name, input, publish_lead_ns);
    }
    std::fs::remove_dir_all(&dir).ok();
}
