//! The live view (`--view`) is read by Foxglove's own client: `tests/interop/js/view_client.mjs`
//! (npm `@foxglove/ws-protocol` over `ws`, `@foxglove/rosmsg` and
//! `@foxglove/rosmsg2-serialization`) connects to the view's WebSocket server, subscribes, and
//! decodes every message with nothing but the schema the server advertised.
//!
//! - In process: a view fed through a station tap serves a latched message sent before the
//!   client connected (replayed on subscribe) and a stream of live messages; the client sees
//!   channels with message encoding `cdr`, schema encoding `ros2msg` and the ROS type as schema
//!   name, and decodes to exactly the values sent, with their log times and no trailing bytes.

#![allow(clippy::unwrap_used, clippy::expect_used)] // in tests a panic is the failure report

use std::io::Read;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use msgs::{JointState, Point, Pose, PoseArray, Quaternion, RosMessage};
use pomdar_tests::interop::{interop_js_script, interop_node, json_difference, json_lines};
use serde_json::Value;
use station::convert::header;
use teleop::station_node::tap::Tap;
use teleop::view::{ViewAddress, ViewServer};

/// Log time of the first message (a fixed instant, so expected values are exact).
const T0_NS: i64 = 1_764_000_000_000_000_000;
const LIVE_TOPIC: &str = "/pomdar/hand/joint_targets";
const LATCHED_TOPIC: &str = "/pomdar/markers/hand_model";
/// Live messages the client must decode.
const LIVE_COUNT: usize = 20;
/// The client gives up after this long.
const CLIENT_TIMEOUT_MS: u64 = 15_000;

/// The latched message: something big enough to span many CDR alignments.
fn latched_message() -> PoseArray {
    PoseArray {
        header: header(T0_NS - 5_000_000, "right_palm"),
        poses: (0..17)
            .map(|i| Pose {
                position: Point {
                    x: 0.01 * f64::from(i),
                    y: -0.002 * f64::from(i),
                    z: 1.0e-9,
                },
                orientation: Quaternion {
                    x: 0.0,
                    y: 0.0,
                    z: (0.05 * f64::from(i)).sin(),
                    w: (0.05 * f64::from(i)).cos(),
                },
            })
            .collect(),
    }
}

/// Live message `k`: distinct values in every field.
fn live_message(k: usize) -> JointState {
    let k_f = k as f64;
    JointState {
        header: header(T0_NS + k as i64 * 10_000_000, "right_palm"),
        name: vec!["index_mcp".into(), "thumb_abd".into(), "wrist".into()],
        position: vec![0.01 * k_f, -0.5 + 1.0e-7 * k_f, 1.0 / 3.0],
        velocity: vec![],
        effort: vec![k_f - 0.125],
    }
}

fn live_log_time_ns(k: usize) -> i64 {
    T0_NS + k as i64 * 10_000_000 + 1_000
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

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn foxglove_client_decodes_what_the_view_serves() {
    let Some(node) = interop_node() else {
        return;
    };
    let tap = Tap::new(256);
    let view = ViewServer::start(ViewAddress::loopback(0), tap.subscribe())
        .await
        .unwrap();
    assert_ne!(view.local_address().port(), 0);
    assert!(view.announcement().contains(&view.url()));

    // Latched before any viewer exists: replayed when the client subscribes.
    let latched = latched_message();
    tap.send(LATCHED_TOPIC, &latched, T0_NS - 1_000_000, true);

    let topics = [
        format!("{LATCHED_TOPIC}=1"),
        format!("{LIVE_TOPIC}={LIVE_COUNT}"),
    ];
    let mut client = Client::start(&node, &view.url(), &topics);
    // Live messages until the client has what it wants (it subscribes on the topic's first
    // message, so the first few go to nobody).
    let deadline = Instant::now() + Duration::from_millis(CLIENT_TIMEOUT_MS + 2_000);
    let mut sent = 0;
    while !client.exited() && Instant::now() < deadline {
        tap.send(
            LIVE_TOPIC,
            &live_message(sent),
            live_log_time_ns(sent),
            false,
        );
        sent += 1;
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    let lines = client.finish();
    let report = view.stop().await;
    println!("sent {sent} live messages; view {report:?}");

    assert_advertised::<PoseArray>(&lines, LATCHED_TOPIC);
    assert_advertised::<JointState>(&lines, LIVE_TOPIC);

    let latched_seen = decoded_on(&lines, LATCHED_TOPIC);
    assert_eq!(latched_seen.len(), 1, "{latched_seen:?}");
    if let Some(d) = json_difference("", &as_json(&latched), &latched_seen[0]["message"]) {
        panic!("the latched message decodes differently: {d}");
    }
    assert_eq!(latched_seen[0]["logTimeNs"], T0_NS - 1_000_000);

    // Live: consecutive messages from where the subscription began, each exactly as sent.
    let live_seen = decoded_on(&lines, LIVE_TOPIC);
    assert!(live_seen.len() >= LIVE_COUNT, "{} live", live_seen.len());
    let first = (0..sent)
        .find(|&k| {
            json_difference("", &as_json(&live_message(k)), &live_seen[0]["message"]).is_none()
        })
        .unwrap_or_else(|| panic!("the first live message is none sent: {}", live_seen[0]));
    for (i, line) in live_seen.iter().enumerate() {
        let k = first + i;
        if let Some(d) = json_difference("", &as_json(&live_message(k)), &line["message"]) {
            panic!("live message {k} decodes differently: {d}");
        }
        assert_eq!(line["logTimeNs"], live_log_time_ns(k), "live message {k}");
    }

    assert_eq!(report.counts.lagged, 0);
    assert_eq!(report.counts.type_mismatch, 0);
    assert_eq!(
        report.counts.replayed, 1,
        "one late subscriber to one latched topic"
    );
    assert_eq!(report.counts.forwarded, sent as u64 + 1);
    assert_eq!(
        report.topics,
        vec![LIVE_TOPIC.to_string(), LATCHED_TOPIC.to_string()]
    );
}
