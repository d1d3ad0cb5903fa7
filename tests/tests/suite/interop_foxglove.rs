//! The live view (`--view`) is read by Foxglove's own client: `tests/interop/js/view_client.mjs`
//! (npm `@foxglove/ws-protocol` over `ws`, `@foxglove/rosmsg` and
//! `@foxglove/rosmsg2-serialization`) connects to the view's WebSocket server, subscribes, and
//! decodes every message with nothing but the schema the server advertised.
//!
//! - In process: a view fed through a station tap serves the ORCA hand's `/tf_static` and its
//!   drawing (a MarkerArray), both latched and sent before the client connected (replayed on
//!   subscribe), and a stream of `/tf` from the station's kinematics; the client sees channels
//!   with message encoding `cdr`, schema encoding `ros2msg` and the ROS type as schema name,
//!   and decodes to exactly the values sent, with their log times and no trailing bytes.
//! - End to end: `pomdar demo --view 127.0.0.1:0` (the built binary, loopback DDS, its own
//!   domain) prints where its view listens; the client decodes `/tf` with the hand's links
//!   where the station's kinematics put them for the joint targets of the same step, the
//!   fingertips on `/tf_static`, the glove keypoint markers, the hand's drawing (exactly the
//!   station's) and `/diagnostics`; Foxglove's MCAP reader (`read_mcap.mjs`) decodes every
//!   message of every channel of the run's log, these new ones included.

use std::io::{BufRead, BufReader, Read};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use msgs::{DiagnosticArray, JointState, MarkerArray, RosMessage, TFMessage};
use pomdar_tests::interop::{
    foxglove_mcap_reader, interop_js_script, interop_node, json_difference, json_lines,
};
use pomdar_tests::pomdar_binary::pomdar_binary;
use pomdar_tests::station_harness::test_domain;
use pomdar_tests::{files_with_extension, scratch_dir};
use retarget::HandModel;
use serde_json::Value;
use station::ros_tools::markers::hand_model_markers;
use station::ros_tools::{HandTf, RosToolsConfig, dof_of_published_name};
use teleop::mcap_log::TrialReader;
use teleop::station_node::tap::Tap;
use teleop::view::{ViewAddress, ViewServer};

/// Log time of the first message (a fixed instant, so expected values are exact).
const T0_NS: i64 = 1_764_000_000_000_000_000;
const TF: &str = "/tf";
const TF_STATIC: &str = "/tf_static";
const HAND_MODEL: &str = "/pomdar/markers/hand_model";
/// Live `/tf` messages the client must decode.
const LIVE_COUNT: usize = 20;
/// The client gives up after this long.
const CLIENT_TIMEOUT_MS: u64 = 15_000;

/// The ORCA hand's transform tree and model, as the station builds them.
struct Hand {
    model: HandModel,
    tree: HandTf,
}

impl Hand {
    fn orca() -> Hand {
        let model = HandModel::orca_v1_right();
        let tree = HandTf::new(&model, &RosToolsConfig::default());
        Hand { model, tree }
    }

    /// `/tf` number `k`: every moving link at a pose that differs in every joint from the
    /// other messages', stamped at its log time.
    fn tf(&self, k: usize) -> TFMessage {
        let q: Vec<f64> = (0..self.model.dof())
            .map(|j| 0.01 * (k as f64) + 0.001 * (j as f64))
            .collect();
        let state = self.model.forward_new(&q).unwrap();
        self.tree.moving(&state, live_log_time_ns(k))
    }

    /// `/tf_static`: the fixed links (fingertips).
    fn tf_static(&self) -> TFMessage {
        let state = self
            .model
            .forward_new(&vec![0.0; self.model.dof()])
            .unwrap();
        self.tree.fixed(&state, T0_NS - 2_000_000)
    }

    /// The hand's drawing.
    fn drawing(&self) -> MarkerArray {
        hand_model_markers(&self.tree, &self.model, T0_NS - 2_000_000)
    }
}

fn live_log_time_ns(k: usize) -> i64 {
    T0_NS + k as i64 * 10_000_000
}

/// The client, started on `url` for `topics` (`TOPIC=N`), its stdout read in a thread.
struct Client {
    child: Child,
    stdout: std::thread::JoinHandle<Vec<u8>>,
}

impl Client {
    fn start(node: &Path, url: &str, topics: &[String]) -> Client {
        let mut child = Command::new(node)
            .arg(interop_js_script("view_client.mjs"))
            .arg(url)
            .arg("--topics")
            .arg(topics.join(","))
            .arg("--timeout-ms")
            .arg(CLIENT_TIMEOUT_MS.to_string())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("cannot run node view_client.mjs");
        let mut out = child.stdout.take().unwrap();
        let stdout = std::thread::spawn(move || {
            let mut bytes = Vec::new();
            out.read_to_end(&mut bytes).ok();
            bytes
        });
        Client { child, stdout }
    }

    fn exited(&mut self) -> bool {
        self.child.try_wait().unwrap().is_some()
    }

    /// Wait for the exit; the printed lines. Panics when the client failed.
    fn finish(mut self) -> Vec<Value> {
        let status = self.child.wait().unwrap();
        let lines = json_lines("view_client.mjs", &self.stdout.join().unwrap());
        assert!(
            status.success(),
            "view_client.mjs failed ({status}); it printed {lines:?}"
        );
        lines
    }
}

fn as_json<M: serde::Serialize>(message: &M) -> Value {
    serde_json::to_value(message).unwrap()
}

/// The one `advertise` line of `topic`: encodings and schema name as the view promises.
fn assert_advertised<M: RosMessage>(lines: &[Value], topic: &str) {
    let advertised: Vec<&Value> = lines
        .iter()
        .filter(|l| l["kind"] == "advertise" && l["topic"] == topic)
        .collect();
    assert_eq!(advertised.len(), 1, "{topic} advertised {advertised:?}");
    let a = advertised[0];
    assert_eq!(a["encoding"], "cdr", "{a}");
    assert_eq!(a["schemaEncoding"], "ros2msg", "{a}");
    assert_eq!(a["schemaName"], M::ros_type_name().as_str(), "{a}");
}

/// The decoded messages of `topic`, checked for trailing bytes.
fn decoded_on<'a>(lines: &'a [Value], topic: &str) -> Vec<&'a Value> {
    let decoded: Vec<&Value> = lines
        .iter()
        .filter(|l| l["kind"] == "message" && l["topic"] == topic)
        .collect();
    for line in &decoded {
        assert_eq!(
            line["trailingBytes"], false,
            "{topic}: bytes left after decoding with the advertised schema: {line}"
        );
    }
    decoded
}

/// Every message the client decoded on `topic` equals `expected` (and has its log time).
fn assert_latched(lines: &[Value], topic: &str, expected: &Value, log_time_ns: i64) {
    let seen = decoded_on(lines, topic);
    assert_eq!(seen.len(), 1, "{topic}: {seen:?}");
    if let Some(d) = json_difference("", expected, &seen[0]["message"]) {
        panic!("{topic} decodes differently: {d}");
    }
    assert_eq!(seen[0]["logTimeNs"], log_time_ns.to_string(), "{topic}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn foxglove_client_decodes_what_the_view_serves() {
    let Some(node) = interop_node() else {
        return;
    };
    let hand = Hand::orca();
    let tap = Tap::new(256);
    let view = ViewServer::start(ViewAddress::loopback(0), tap.subscribe())
        .await
        .unwrap();
    assert_ne!(view.local_address().port(), 0);
    assert!(view.announcement().contains(&view.url()));

    // Latched before any viewer exists: replayed when the client subscribes.
    let (fixed, drawing) = (hand.tf_static(), hand.drawing());
    tap.send(TF_STATIC, &fixed, T0_NS - 1_000_000, true);
    tap.send(HAND_MODEL, &drawing, T0_NS - 1_000_000, true);

    let topics = [
        format!("{TF_STATIC}=1"),
        format!("{HAND_MODEL}=1"),
        format!("{TF}={LIVE_COUNT}"),
    ];
    let mut client = Client::start(&node, &view.url(), &topics);
    // Live messages until the client has what it wants (it subscribes on the topic's first
    // message, so the first few go to nobody).
    let deadline = Instant::now() + Duration::from_millis(CLIENT_TIMEOUT_MS + 2_000);
    let mut sent = 0;
    while !client.exited() && Instant::now() < deadline {
        tap.send(TF, &hand.tf(sent), live_log_time_ns(sent), false);
        sent += 1;
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    let lines = client.finish();
    let report = view.stop().await;
    println!("sent {sent} /tf messages; view {report:?}");

    assert_advertised::<TFMessage>(&lines, TF_STATIC);
    assert_advertised::<MarkerArray>(&lines, HAND_MODEL);
    assert_advertised::<TFMessage>(&lines, TF);
    assert_latched(&lines, TF_STATIC, &as_json(&fixed), T0_NS - 1_000_000);
    assert_latched(&lines, HAND_MODEL, &as_json(&drawing), T0_NS - 1_000_000);
    assert!(!fixed.transforms.is_empty() && !drawing.markers.is_empty());

    // Live: consecutive messages from where the subscription began, each exactly as sent.
    let live_seen = decoded_on(&lines, TF);
    assert!(live_seen.len() >= LIVE_COUNT, "{} live", live_seen.len());
    let first = (0..sent)
        .find(|&k| json_difference("", &as_json(&hand.tf(k)), &live_seen[0]["message"]).is_none())
        .unwrap_or_else(|| panic!("the first /tf decoded is none sent: {}", live_seen[0]));
    for (i, line) in live_seen.iter().enumerate() {
        let k = first + i;
        if let Some(d) = json_difference("", &as_json(&hand.tf(k)), &line["message"]) {
            panic!("/tf message {k} decodes differently: {d}");
        }
        assert_eq!(
            line["logTimeNs"],
            live_log_time_ns(k).to_string(),
            "/tf message {k}"
        );
    }
    // The URDF's link names, as RViz and Foxglove expect them.
    let child_frames = |line: &Value| -> Vec<String> {
        line["message"]["transforms"]
            .as_array()
            .unwrap()
            .iter()
            .map(|t| t["child_frame_id"].as_str().unwrap().to_string())
            .collect()
    };
    let moving = child_frames(live_seen[0]);
    assert!(moving.contains(&"right_thumb_mp".to_string()), "{moving:?}");
    let fixed_frames = child_frames(decoded_on(&lines, TF_STATIC)[0]);
    assert!(
        fixed_frames.contains(&"right_index_fingertip".to_string()),
        "{fixed_frames:?}"
    );

    assert_eq!(report.counts.lagged, 0);
    assert_eq!(report.counts.type_mismatch, 0);
    assert_eq!(
        report.counts.replayed, 2,
        "one late subscriber to two latched topics"
    );
    assert_eq!(report.counts.forwarded, sent as u64 + 2);
    assert_eq!(
        report.topics,
        vec![
            HAND_MODEL.to_string(),
            TF.to_string(),
            TF_STATIC.to_string()
        ]
    );
}

const KEYPOINT_MARKERS: &str = "/pomdar/markers/keypoints";
const DIAGNOSTICS: &str = "/diagnostics";
const JOINT_TARGETS: &str = "/pomdar/hand/joint_targets";

/// `pomdar demo --view 127.0.0.1:0 --out DIR`, and the view's URL from its stderr.
fn start_demo(duration_s: f64, out: &Path) -> (Child, String) {
    let binary = pomdar_binary().unwrap();
    let mut demo = Command::new(binary)
        .args(["demo", "--json", "--duration", &duration_s.to_string()])
        .args(["--domain-id", &test_domain().to_string()])
        .args(["--view", "127.0.0.1:0"])
        .arg("--out")
        .arg(out)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let stderr = BufReader::new(demo.stderr.take().unwrap());
    let (url_tx, url_rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in stderr.lines().map_while(Result::ok) {
            eprintln!("demo: {line}");
            if let Some(rest) = line.strip_prefix("live view: ") {
                let url = rest
                    .split_whitespace()
                    .next()
                    .unwrap_or_default()
                    .to_string();
                url_tx.send(url).ok();
            }
        }
    });
    let url = url_rx
        .recv_timeout(Duration::from_secs(30))
        .expect("pomdar demo printed no `live view: ws://...` line");
    assert!(url.starts_with("ws://127.0.0.1:"), "{url}");
    (demo, url)
}

/// Nanoseconds of a decoded `builtin_interfaces/Time`.
fn stamp_ns(stamp: &Value) -> i64 {
    stamp["sec"].as_i64().unwrap() * 1_000_000_000 + stamp["nanosec"].as_i64().unwrap()
}

/// The decoded message as this project's type.
fn typed<M: serde::de::DeserializeOwned>(line: &Value) -> M {
    serde_json::from_value(line["message"].clone()).unwrap()
}

/// Every `/tf` of the hand (not the arm target's) is where the station's kinematics put the
/// links for the joint targets published in the same step (same log time); returns how many
/// were checked.
fn assert_tf_follows_the_joint_targets(lines: &[Value], hand: &Hand) -> usize {
    let targets: std::collections::HashMap<&str, JointState> = decoded_on(lines, JOINT_TARGETS)
        .into_iter()
        .map(|l| (l["logTimeNs"].as_str().unwrap(), typed(l)))
        .collect();
    let mut checked = 0;
    for line in decoded_on(lines, TF) {
        let tf: TFMessage = typed(line);
        if tf
            .transforms
            .iter()
            .any(|t| t.child_frame_id == "pomdar_arm_target")
        {
            continue;
        }
        let Some(target) = targets.get(line["logTimeNs"].as_str().unwrap()) else {
            continue;
        };
        let mut q = vec![f64::NAN; hand.model.dof()];
        for (name, position) in target.name.iter().zip(&target.position) {
            let dof = dof_of_published_name(&hand.model, name, None)
                .unwrap_or_else(|| panic!("joint target for unknown joint {name}"));
            q[dof] = *position;
        }
        let state = hand.model.forward_new(&q).unwrap();
        let stamp = tf.transforms[0].header.stamp.to_nanos();
        let expected = hand.tree.moving(&state, stamp);
        assert_eq!(tf.transforms.len(), expected.transforms.len());
        for (got, want) in tf.transforms.iter().zip(&expected.transforms) {
            assert_eq!(got.header, want.header);
            assert_eq!(got.child_frame_id, want.child_frame_id);
            let (g, w) = (&got.transform, &want.transform);
            let close = [
                (g.translation.x, w.translation.x),
                (g.translation.y, w.translation.y),
                (g.translation.z, w.translation.z),
                (g.rotation.x, w.rotation.x),
                (g.rotation.y, w.rotation.y),
                (g.rotation.z, w.rotation.z),
                (g.rotation.w, w.rotation.w),
            ]
            .iter()
            .all(|(a, b)| (a - b).abs() < 1e-12);
            assert!(close, "{}: {g:?} != {w:?}", got.child_frame_id);
        }
        checked += 1;
    }
    checked
}

#[test]
fn pomdar_demo_serves_the_hand_to_a_foxglove_client() {
    let Some(node) = interop_node() else {
        return;
    };
    let hand = Hand::orca();
    let out = scratch_dir("interop-foxglove-demo");
    let (mut demo, url) = start_demo(6.0, &out);
    let topics = [
        format!("{TF}=40"),
        format!("{TF_STATIC}=1"),
        format!("{HAND_MODEL}=1"),
        format!("{KEYPOINT_MARKERS}=20"),
        format!("{DIAGNOSTICS}=2"),
        format!("{JOINT_TARGETS}=20"),
    ];
    let lines = Client::start(&node, &url, &topics).finish();
    let status = demo.wait().unwrap();
    assert!(status.success(), "pomdar demo: {status}");

    assert_advertised::<TFMessage>(&lines, TF);
    assert_advertised::<TFMessage>(&lines, TF_STATIC);
    assert_advertised::<MarkerArray>(&lines, HAND_MODEL);
    assert_advertised::<MarkerArray>(&lines, KEYPOINT_MARKERS);
    assert_advertised::<DiagnosticArray>(&lines, DIAGNOSTICS);

    let checked = assert_tf_follows_the_joint_targets(&lines, &hand);
    println!("{checked} /tf messages checked against the joint targets of their step");
    assert!(
        checked >= 10,
        "only {checked} /tf messages matched a joint target"
    );

    // The latched ones, exactly the station's at their stamp.
    let fixed: TFMessage = typed(decoded_on(&lines, TF_STATIC)[0]);
    let stamp = fixed.transforms[0].header.stamp.to_nanos();
    let zero = hand
        .model
        .forward_new(&vec![0.0; hand.model.dof()])
        .unwrap();
    assert_eq!(fixed, hand.tree.fixed(&zero, stamp));
    assert!(
        fixed
            .transforms
            .iter()
            .any(|t| t.child_frame_id == "right_index_fingertip")
    );
    let drawing = decoded_on(&lines, HAND_MODEL)[0];
    let stamp = stamp_ns(&drawing["message"]["markers"][0]["header"]["stamp"]);
    if let Some(d) = json_difference(
        "",
        &as_json(&hand_model_markers(&hand.tree, &hand.model, stamp)),
        &drawing["message"],
    ) {
        panic!("the hand's drawing decodes differently: {d}");
    }

    // The glove's keypoints, drawn in the hand's frames.
    for line in decoded_on(&lines, KEYPOINT_MARKERS) {
        let markers: MarkerArray = typed(line);
        assert!(!markers.markers.is_empty(), "{line}");
        for m in &markers.markers {
            assert!(!m.header.frame_id.is_empty(), "{m:?}");
        }
        let points: usize = markers.markers.iter().map(|m| m.points.len()).sum();
        assert!(points >= 10, "{points} points in {line}");
    }
    let diagnostics: DiagnosticArray = typed(decoded_on(&lines, DIAGNOSTICS)[0]);
    assert!(!diagnostics.status.is_empty());

    let logs = files_with_extension(&out, "mcap").unwrap();
    assert_eq!(logs.len(), 1, "{logs:?}");
    assert_foxglove_reads_the_log(&logs[0]);
}

/// Foxglove's MCAP reader decodes every message of every channel of `log` with the schema
/// stored in it, as many per topic as ours reads, the ROS tools' topics among them.
fn assert_foxglove_reads_the_log(log: &Path) {
    let ours = TrialReader::open(log).unwrap();
    let lines = foxglove_mcap_reader(log).expect("node checked above");
    for topic in ours.topics() {
        let channel: Vec<&Value> = lines
            .iter()
            .filter(|l| l["kind"] == "channel" && l["topic"] == topic.topic.as_str())
            .collect();
        assert_eq!(channel.len(), 1, "{}: {channel:?}", topic.topic);
        assert_eq!(channel[0]["schemaName"], topic.type_name.as_str());
        let decoded = lines
            .iter()
            .filter(|l| l["kind"] == "message" && l["topic"] == topic.topic.as_str())
            .count() as u64;
        assert_eq!(decoded, topic.message_count, "{}", topic.topic);
    }
    for (topic, type_name) in [
        (TF, TFMessage::ros_type_name()),
        (TF_STATIC, TFMessage::ros_type_name()),
        (HAND_MODEL, MarkerArray::ros_type_name()),
        (KEYPOINT_MARKERS, MarkerArray::ros_type_name()),
        (DIAGNOSTICS, DiagnosticArray::ros_type_name()),
    ] {
        let info = ours
            .topic(topic)
            .unwrap_or_else(|| panic!("{}: no {topic}", log.display()));
        assert_eq!(info.type_name, type_name);
        assert!(info.message_count > 0, "{topic}");
    }
}
