//! What the station offers the lab's ROS tools, read and called by a ROS 2 tool nobody on this
//! team wrote: Eclipse Cyclone DDS (PyPI `cyclonedds`) running
//! `tests/interop/cyclone_tools_peer.py` on loopback, with the message types written there
//! from the ROS 2 interface definitions.
//!
//! The peer plays the glove, receives `/tf`, `/tf_static` (latched), the keypoint markers and
//! `/diagnostics`, and calls the disengage, engage and trial-start services as rmw_cyclonedds
//! does (the station configured with `ros_tools.services.mapping = "cyclone"`: a 16-byte request
//! header, the client's id and a sequence number, in front of request and reply). Checked:
//! - every reply is addressed to its call (the header comes back unchanged) and says what the
//!   station did: disengaged, engaged, no trial console;
//! - what Cyclone decoded equals, message for message, what the station sent (its log): every
//!   `/tf` and marker message, the latched `/tf_static`, and a contiguous run of
//!   `/diagnostics` (those sent before the peer joined it cannot have);
//! - the independent MCAP readers decode the station's log, the new types included, to the
//!   values this project's types decode.

use std::path::PathBuf;

use msgs::{DiagnosticArray, DiagnosticStatus, MarkerArray, TFMessage};
use pomdar_tests::cyclone_peer::{assert_same_messages, decode, run_station_with_peer};
use pomdar_tests::interop::{
    assert_readers_decode_as_we_do, independent_readers_with_values, interop_python,
};
use pomdar_tests::station_harness::{loopback, test_domain};
use retarget::KeypointLayout;
use retarget::human_hand::{HumanHandShape, Motion, MotionKind, SimGlove};
use serde_json::{Value, json};
use station::ros_tools::ServiceMapping;
use station::{ControlMode, StationConfig};
use teleop::mcap_log::TrialReader;
use teleop::ros::QosConfig;

const FRAMES: usize = 60;
const PERIOD_S: f64 = 0.02;
/// After which frame the peer calls which service (and what the answer must say).
const CALLS: [(usize, &str, bool, &str); 3] = [
    (19, "disengage", true, "disengaged"),
    (29, "engage", true, "the station is engaged"),
    (FRAMES - 1, "trial_start", false, "no trial console"),
];

/// Every-frame control, reliable deep queues, watchdog far off (so after the last frame's
/// target the station sends no more hand commands), services as rmw_cyclonedds carries them.
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
    config.watchdog.hold_timeout_ms = 2000;
    config.watchdog.disengage_timeout_ms = 5000;
    config.ros_tools.services.mapping = ServiceMapping::Cyclone;
    config
}

fn service_name<'a>(config: &'a StationConfig, key: &str) -> &'a str {
    let services = &config.ros_tools.services;
    match key {
        "disengage" => &services.disengage,
        "engage" => &services.engage,
        "trial_start" => &services.trial_start,
        other => panic!("no service {other}"),
    }
}

/// The peer's plan: domain, topics, services and their calls, QoS, frames.
fn plan(config: &StationConfig) -> Value {
    let shape = HumanHandShape::average();
    let motion = Motion::new(MotionKind::OpenClose, 4.0, &shape).unwrap();
    let glove = SimGlove::new(shape, motion, KeypointLayout::Lab22).unwrap();
    let frames: Vec<Value> = (0..FRAMES)
        .map(|i| {
            let points = glove.frame(i as f64 * PERIOD_S).0;
            let rows: Vec<[f64; 3]> = points
                .iter()
                .map(|p| [p.x, p.y, p.z].map(|c| f64::from(c as f32)))
                .collect();
            json!({"points": rows, "wrist": {"position": [0.0, 0.0, 0.0], "orientation": [0.0, 0.0, 0.0, 1.0]}})
        })
        .collect();
    let tools = &config.ros_tools;
    let calls: Vec<Value> = CALLS
        .iter()
        .map(|(after, key, _, _)| json!({"after_frame": after, "service": service_name(config, key)}))
        .collect();
    json!({
        "domain_id": config.network.domain_id,
        "topics": {
            "keypoints": config.input.keypoints_topic,
            "wrist": config.input.wrist_topic,
            "joint_targets": config.output.joint_targets_topic,
            "status": config.output.status_topic,
            "tf": "/tf",
            "tf_static": "/tf_static",
            "markers": tools.keypoint_markers_topic,
            "diagnostics": tools.diagnostics_topic,
        },
        "services": CALLS.iter().map(|(_, key, _, _)| service_name(config, key)).collect::<Vec<_>>(),
        "input_qos": serde_json::to_value(config.input.qos).unwrap(),
        "output_qos": serde_json::to_value(QosConfig::reliable(1000)).unwrap(),
        "status_qos": serde_json::to_value(QosConfig::reliable(10)).unwrap(),
        "service_qos": serde_json::to_value(QosConfig::reliable(10)).unwrap(),
        "wrist_frame_id": "coil",
        "period_s": PERIOD_S,
        "frames": frames,
        "calls": calls,
    })
}

/// Each call got one reply, addressed to it (rmw_cyclonedds' header unchanged), saying what
/// the station did.
fn assert_replies(report: &Value, config: &StationConfig) {
    let calls = report["calls"].as_array().unwrap();
    assert_eq!(calls.len(), CALLS.len());
    for (call, (_, key, success, says)) in calls.iter().zip(CALLS) {
        assert_eq!(call["service"], service_name(config, key));
        let replies = call["replies"].as_array().unwrap();
        assert_eq!(replies.len(), 1, "{key}: {replies:?}");
        let (request, reply) = (&call["request"], &replies[0]);
        println!("{key}: {request} -> {reply}");
        assert_eq!(reply["client_guid"], request["client_guid"], "{key}");
        assert_eq!(
            reply["sequence_number"], request["sequence_number"],
            "{key}"
        );
        assert_eq!(reply["success"], success, "{key}: {reply}");
        let message = reply["message"].as_str().unwrap();
        assert!(message.contains(says), "{key}: {message:?}");
    }
}

/// Cyclone decoded a contiguous run of what the station sent: those sent before the peer
/// joined are missing, and the last may have been sent as the station stopped.
fn assert_contiguous_run(what: &str, received: &[DiagnosticArray], sent: &[DiagnosticArray]) {
    let first = received.first().expect("no diagnostics reached Cyclone");
    let Some(offset) = sent.iter().position(|m| m == first) else {
        panic!("{what}: Cyclone's first message is none the station sent: {first:?}");
    };
    assert!(
        offset + received.len() <= sent.len(),
        "{what}: Cyclone received {} from {offset} of {}",
        received.len(),
        sent.len()
    );
    for (i, (r, s)) in received.iter().zip(&sent[offset..]).enumerate() {
        assert_eq!(
            r,
            s,
            "{what} {}: as Cyclone decoded it vs as sent",
            offset + i
        );
    }
}

fn assert_tool_topics_as_sent(report: &Value, log: &TrialReader, config: &StationConfig) {
    let tools = &config.ros_tools;
    let tf: Vec<TFMessage> = decode(report, "/received/tf");
    assert_same_messages("/tf", &tf, &log.decode_topic::<TFMessage>("/tf").unwrap());
    let moving: std::collections::BTreeSet<&str> = tf
        .iter()
        .flat_map(|m| &m.transforms)
        .map(|t| t.child_frame_id.as_str())
        .collect();
    assert!(moving.contains("right_index_pp"), "{moving:?}");
    assert!(
        moving.contains(tools.arm_target_frame.as_str()),
        "{moving:?}"
    );

    let tf_static: Vec<TFMessage> = decode(report, "/received/tf_static");
    let logged = log.decode_topic::<TFMessage>("/tf_static").unwrap();
    assert_same_messages("/tf_static", &tf_static, &logged);
    let fixed: Vec<&str> = (tf_static.iter().flat_map(|m| &m.transforms))
        .map(|t| t.child_frame_id.as_str())
        .collect();
    assert!(fixed.contains(&"right_index_fingertip"), "{fixed:?}");

    let topic = &tools.keypoint_markers_topic;
    let markers: Vec<MarkerArray> = decode(report, "/received/markers");
    assert_same_messages(topic, &markers, &log.decode_topic(topic).unwrap());
    assert!(markers.len() >= 30, "{} marker arrays", markers.len());

    let topic = &tools.diagnostics_topic;
    let diagnostics: Vec<DiagnosticArray> = decode(report, "/received/diagnostics");
    assert_contiguous_run(topic, &diagnostics, &log.decode_topic(topic).unwrap());
    assert!(diagnostics.len() >= 10, "{} diagnostics", diagnostics.len());
    assert!(
        diagnostics
            .iter()
            .any(|d| d.status[0].level == DiagnosticStatus::OK),
        "the glove was never OK"
    );
    println!(
        "station → Cyclone: {} /tf, {} /tf_static, {} marker arrays, {} diagnostics",
        tf.len(),
        tf_static.len(),
        markers.len(),
        diagnostics.len()
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn cyclone_dds_tool_reads_tf_markers_diagnostics_and_calls_the_services() {
    let Some(python) = interop_python() else {
        return;
    };
    let config = config(test_domain());
    let dir = std::env::temp_dir().join(format!("pomdar-interop-tools-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    let plan_path = dir.join("plan.json");
    std::fs::write(&plan_path, plan(&config).to_string()).unwrap();
    let log_path: PathBuf = dir.join("station.mcap");

    let script = "cyclone_tools_peer.py";
    let report =
        run_station_with_peer(&python, script, &config, &plan_path, &log_path, FRAMES).await;
    let log = TrialReader::open(&log_path).unwrap();
    assert_replies(&report, &config);
    assert_tool_topics_as_sent(&report, &log, &config);

    if let Some(readers) = independent_readers_with_values(&log_path) {
        assert_readers_decode_as_we_do(&readers, &log);
    }
    std::fs::remove_dir_all(&dir).ok();
}
