//! `pomdar ingress avp` against a fake Apple Vision Pro: the hand-tracking app's gRPC service
//! generated from its published proto with Python's grpcio (`tests/interop/avp/`), streaming a
//! scripted right hand (an open hand, a pinch, a moving and turning wrist), over real HTTP/2 on
//! loopback, with the ingress publishing over real DDS on loopback.
//!
//! - every keypoint frame and wrist pose on DDS equals the one the fake headset computed on its
//!   own (numpy, the documented frame maths) to 1e-6 m, in order, for 27-joint (forearm) and
//!   25-joint updates;
//! - the first request carries the discovery marker with the client's address and version;
//! - the headset stops and comes back on the same port: the ingress reconnects and streams on;
//! - undecodable, untracked, non-finite, short, wrong-hand, benchmark and repeated updates are
//!   counted by kind on the status topic, never published, never fatal.

use std::io::{BufRead, BufReader, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::{Arc, Mutex, mpsc};
use std::time::{Duration, Instant};

use futures::StreamExt;
use msgs::{Float32MultiArray, PoseStamped, StringMsg};
use nalgebra::{Isometry3, Point3, Quaternion, UnitQuaternion, Vector3};
use pomdar_tests::interop::{interop_python, interop_script};
use pomdar_tests::station_harness::{loopback, test_domain};
use serde_json::Value;
use station::convert::{array_to_points, pose_to_isometry};
use teleop::clock::StationClock;
use teleop::ingress::avp_config::AvpConfig;
use teleop::ingress::avp_node::run_avp_ingress;
use teleop::ros::NetworkContext as _;
use teleop::ros::{QosConfig, RosNode};
use tokio::sync::watch;

/// What the listener heard from the ingress.
#[derive(Default)]
struct Heard {
    keypoints: Vec<Vec<Point3<f64>>>,
    wrists: Vec<(Isometry3<f64>, String)>,
    status: Vec<Value>,
}

/// The fake headset: its process, its stdin and its stdout's JSON lines.
struct Headset {
    child: Child,
    stdin: ChildStdin,
    lines: mpsc::Receiver<Value>,
}

impl Headset {
    fn start(python: &std::path::Path) -> Headset {
        let generated = pomdar_tests::workspace_root().join("target/interop-avp-generated");
        let mut child = Command::new(python)
            .arg(interop_script("avp/fake_headset.py"))
            .arg("--generated")
            .arg(&generated)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .expect("cannot start the fake headset");
        let stdin = child.stdin.take().unwrap();
        let stdout = child.stdout.take().unwrap();
        let (tx, lines) = mpsc::channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stdout).lines().map_while(Result::ok) {
                let value = serde_json::from_str(&line)
                    .unwrap_or_else(|_| panic!("fake headset printed {line:?}"));
                if tx.send(value).is_err() {
                    break;
                }
            }
        });
        Headset {
            child,
            stdin,
            lines,
        }
    }

    /// The next line with `"event": event` (earlier lines are skipped), within 30 s; the
    /// runtime's other tasks go on meanwhile.
    fn wait(&self, event: &str) -> Value {
        tokio::task::block_in_place(|| self.wait_blocking(event))
    }

    fn wait_blocking(&self, event: &str) -> Value {
        let deadline = Instant::now() + Duration::from_secs(30);
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            let line = self
                .lines
                .recv_timeout(left)
                .unwrap_or_else(|_| panic!("the fake headset never said {event:?}"));
            if line["event"] == event {
                return line;
            }
        }
    }

    fn send(&mut self, command: &str) {
        writeln!(self.stdin, "{command}").unwrap();
        self.stdin.flush().unwrap();
    }
}

impl Drop for Headset {
    fn drop(&mut self) {
        self.child.kill().ok();
        self.child.wait().ok();
    }
}

fn listen(domain: u16) -> (RosNode, Arc<Mutex<Heard>>) {
    let context = loopback(domain).context().unwrap();
    let mut node = RosNode::new(&context, "/", "avp_test_listener").unwrap();
    let qos = QosConfig::best_effort(1000);
    let heard = Arc::new(Mutex::new(Heard::default()));
    let keypoints = node
        .subscription::<Float32MultiArray>("/ingress/mano", qos)
        .unwrap();
    let wrist = node
        .subscription::<PoseStamped>("/ingress/wrist", qos)
        .unwrap();
    let status = node
        .subscription::<StringMsg>("/ingress/status", QosConfig::reliable(100))
        .unwrap();
    let h = heard.clone();
    tokio::spawn(async move {
        let mut stream = Box::pin(keypoints.async_stream());
        while let Some(Ok((m, _))) = stream.next().await {
            let points = array_to_points(&m).unwrap();
            h.lock().unwrap().keypoints.push(points);
        }
    });
    let h = heard.clone();
    tokio::spawn(async move {
        let mut stream = Box::pin(wrist.async_stream());
        while let Some(Ok((m, _))) = stream.next().await {
            let pose = pose_to_isometry(&m.pose).unwrap();
            h.lock().unwrap().wrists.push((pose, m.header.frame_id));
        }
    });
    let h = heard.clone();
    tokio::spawn(async move {
        let mut stream = Box::pin(status.async_stream());
        while let Some(Ok((m, _))) = stream.next().await {
            let value = serde_json::from_str(&m.data).unwrap();
            h.lock().unwrap().status.push(value);
        }
    });
    (node, heard)
}

async fn wait_for(heard: &Arc<Mutex<Heard>>, what: &str, ok: impl Fn(&Heard) -> bool) {
    let start = Instant::now();
    while !ok(&heard.lock().unwrap()) {
        assert!(
            start.elapsed() < Duration::from_secs(20),
            "timed out waiting for {what}"
        );
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
}

fn point(v: &Value) -> Vector3<f64> {
    Vector3::new(
        v[0].as_f64().unwrap(),
        v[1].as_f64().unwrap(),
        v[2].as_f64().unwrap(),
    )
}

/// Every frame heard equals the headset's own expectation, in order.
fn check_frames(heard: &Heard, expected: &[Value]) {
    assert_eq!(heard.keypoints.len(), expected.len(), "keypoint frames");
    assert_eq!(heard.wrists.len(), expected.len(), "wrist poses");
    let mut worst = 0.0f64;
    for (i, (frame, want)) in heard.keypoints.iter().zip(expected).enumerate() {
        let points = want["keypoints"].as_array().unwrap();
        assert_eq!(frame.len(), 22, "frame {i}");
        for (k, (got, want)) in frame.iter().zip(points).enumerate() {
            let error = (got.coords - point(want)).amax();
            worst = worst.max(error);
            assert!(error < 1e-6, "frame {i} point {k}: {got} vs {want}");
        }
    }
    for (i, ((pose, frame_id), want)) in heard.wrists.iter().zip(expected).enumerate() {
        assert_eq!(frame_id, "avp_world");
        let p = point(&want["wrist"]["p"]);
        let q = &want["wrist"]["q"];
        let q = UnitQuaternion::from_quaternion(Quaternion::new(
            q[3].as_f64().unwrap(),
            q[0].as_f64().unwrap(),
            q[1].as_f64().unwrap(),
            q[2].as_f64().unwrap(),
        ));
        assert!((pose.translation.vector - p).amax() < 1e-6, "wrist {i}");
        assert!(pose.rotation.angle_to(&q) < 1e-6, "wrist {i} turned");
    }
    eprintln!(
        "{} frames, largest keypoint difference {worst:.2e} m",
        expected.len()
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_fake_headset_streams_through_the_ingress_to_dds() {
    let Some(python) = interop_python() else {
        return;
    };
    let domain = test_domain();
    let mut headset = Headset::start(&python);
    let port = headset.wait("listening")["port"].as_u64().unwrap() as u16;
    let (_listener, heard) = listen(domain);
    let config = AvpConfig {
        address: "127.0.0.1".into(),
        port,
        network: loopback(domain),
        ..AvpConfig::default()
    };
    let (shutdown, shutdown_rx) = watch::channel(false);
    let ingress = tokio::spawn(run_avp_ingress(
        config,
        StationClock::new(),
        shutdown_rx,
        false,
    ));

    // The first request: the discovery marker, this computer's address, the version code.
    let head = headset.wait("client")["head"].clone();
    let head: Vec<f64> = head
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(
        [head[0], head[1], head[2], head[3], head[4], head[12]],
        [888.0, 127.0, 0.0, 0.0, 1.0, 25_000.0]
    );
    wait_for(&heard, "the ingress connected, on the status topic", |h| {
        h.status.iter().any(|s| s["connected"] == true)
    })
    .await;
    // The keypoint and wrist readers are matched by now (one participant, one discovery);
    // leave a margin for the best-effort writers.
    tokio::time::sleep(Duration::from_millis(500)).await;
    headset.send("go");
    headset.wait("away");
    headset.wait("back");
    let report = headset.wait("report");
    let expected = report["expected"].as_array().unwrap().clone();
    assert_eq!(report["requests"], 2, "the ingress reconnected once");
    wait_for(&heard, "every frame", |h| {
        h.keypoints.len() >= expected.len()
    })
    .await;
    tokio::time::sleep(Duration::from_millis(300)).await;
    check_frames(&heard.lock().unwrap(), &expected);

    // Counted by kind on the status topic; the ingress is still running.
    let malformed = report["malformed"].as_object().unwrap().clone();
    let want_refused: usize = malformed
        .iter()
        .filter(|(k, _)| *k != "duplicate")
        .map(|(_, n)| n.as_u64().unwrap() as usize)
        .sum();
    assert_eq!(
        want_refused, 6,
        "the script sends six kinds of malformed update"
    );
    wait_for(&heard, "the counts on the status topic", |h| {
        h.status.last().is_some_and(|s| {
            s["published"].as_u64() == Some(expected.len() as u64) && s["reconnects"] == 1
        })
    })
    .await;
    let status = heard.lock().unwrap().status.last().unwrap().clone();
    for (kind, n) in &malformed {
        let counted = match kind.as_str() {
            "duplicate" => &status["duplicates"],
            kind => &status["refused"][kind],
        };
        assert_eq!(counted, n, "{kind}: {status}");
    }
    assert_eq!(status["source"]["kind"], "avp");
    assert_eq!(status["connected"], true);
    assert!(!ingress.is_finished(), "the ingress stopped");
    headset.send("quit");
    shutdown.send(true).unwrap();
    let counters = ingress.await.unwrap().unwrap();
    assert_eq!(counters.published as usize, expected.len());
}

/// The station's hand commands from a glove's frames, each frame's keypoints first passed
/// through `through` (as the topics carry them: `f32`).
fn station_commands(
    frames: &[(Vec<Point3<f64>>, Isometry3<f64>)],
    through: impl Fn(&[Point3<f64>], &Isometry3<f64>) -> (Vec<Point3<f64>>, Isometry3<f64>),
) -> Vec<Vec<f64>> {
    use station::{ControlInput, KeypointFrame, Station, StationInput};
    let config = pomdar_tests::station_harness::timing_independent_config();
    let mut station = Station::new(&config, retarget::HandModel::orca_v1_right(), None).unwrap();
    let mut commands = Vec::new();
    for (i, (points, wrist)) in frames.iter().enumerate() {
        let now = 1_000_000_000 + i as i64 * 40_000_000; // 25 Hz
        let (points, wrist) = through(points, wrist);
        station.step(
            StationInput::Wrist(station::convert::isometry_to_pose(&wrist)),
            now,
        );
        let frame = KeypointFrame {
            points,
            source_ns: now,
        };
        let outputs = station.step(StationInput::Keypoints(frame), now);
        commands.extend(outputs.hand.map(|h| h.joint_state.position));
        station.step(StationInput::Control(ControlInput::Tick), now + 1_000_000);
    }
    commands
}

fn as_f32(points: &[Point3<f64>]) -> Vec<Point3<f64>> {
    points
        .iter()
        .map(|p| p.map(|v| f64::from(v as f32)))
        .collect()
}

#[test]
fn avp_updates_drive_the_station_as_the_same_hand_on_the_lab_topics() {
    use prost::Message as _;
    use retarget::KeypointLayout;
    use retarget::human_hand::{HumanHandShape, Motion, MotionKind, SimGlove};
    use teleop::ingress::avp_frame::convert_update;
    use teleop::ingress::avp_proto::HandUpdate;
    use teleop::ingress::avp_update_builder::hand_update;
    use teleop::ingress::ingress_config::Hand;

    // A hand with pinches and a moving, turning wrist (the simulated glove's task-like motion),
    // placed in front of a headset wearer.
    let shape = HumanHandShape::average().scaled(1.08);
    let motion = Motion::new(MotionKind::TaskLike, 4.0, &shape).unwrap();
    let glove = SimGlove::new(shape, motion, KeypointLayout::Lab22).unwrap();
    let frames: Vec<_> = (0..150).map(|i| glove.frame(i as f64 * 0.04)).collect();

    let lab_topics = station_commands(&frames, |points, wrist| (as_f32(points), *wrist));
    let headset = station_commands(&frames, |points, wrist| {
        let lab22: [Point3<f64>; 22] = points.try_into().unwrap();
        // On the wire and back: protobuf bytes, decoded, converted as the ingress does.
        let bytes = hand_update(&lab22, wrist, true, Hand::Right).encode_to_vec();
        let update = HandUpdate::decode(&bytes[..]).unwrap();
        let frame = convert_update(&update, Hand::Right, KeypointLayout::Lab22).unwrap();
        (as_f32(&frame.keypoints), frame.wrist)
    });
    assert!(lab_topics.len() >= 50, "{} commands", lab_topics.len());
    assert_eq!(headset.len(), lab_topics.len());
    let worst = lab_topics
        .iter()
        .zip(&headset)
        .flat_map(|(a, b)| a.iter().zip(b).map(|(x, y)| (x - y).abs()))
        .fold(0.0f64, f64::max);
    eprintln!(
        "{} commands, largest joint difference {worst:.2e} rad",
        lab_topics.len()
    );
    assert!(worst < 1e-3, "largest joint difference {worst} rad");
}
