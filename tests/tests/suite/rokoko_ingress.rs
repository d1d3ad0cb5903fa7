//! `pomdar ingress rokoko` over real sockets: Rokoko Studio packets (built by the project from
//! the documented JSON v3 format) sent over UDP on loopback to the ingress, which publishes
//! over real DDS on loopback.
//!
//! - the published keypoints and wrist pose equal the packet's hand, converted from Studio's
//!   left-handed y-up frame to ROS's, including a packet written by hand whose ROS values
//!   are worked out by hand;
//! - malformed, truncated, oversized, duplicated, out-of-order and bone-missing packets are
//!   not published and are counted by kind on the status topic; the stream goes on;
//! - the door: by default the socket is bound to 127.0.0.1 only (a datagram sent to this
//!   host's non-loopback address is never received, when the host has one); a datagram from a
//!   sender not in `allowed_senders` is refused, counted (`refused.sender`) and not published;
//!   a packet without `scene.timestamp` is refused (`no_timestamp`), never published
//!   unordered; a single spoofed old-stamped packet does not reset the order (the next
//!   slightly late packet is still dropped as out of order), while a real restart (5 packets
//!   in a row) is accepted;
//! - end to end: packets → ingress → station → joint targets, each exactly the retargeter's
//!   answer for one of the frames (in order, the last frame's last), solved from the target
//!   before it.

use std::net::{SocketAddr, UdpSocket};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use futures::StreamExt;
use msgs::{Float32MultiArray, PoseStamped, StringMsg};
use nalgebra::{Isometry3, Point3, Vector3};
use pomdar_tests::station_harness::{Harness, loopback, test_domain, timing_independent_config};
use retarget::human_hand::{HumanHandShape, Motion, MotionKind, SimGlove};
use retarget::{HandModel, KeypointLayout, Retargeter};
use serde_json::{Value, json};
use station::StationConfig;
use station::convert::{array_to_points, pose_to_isometry};
use teleop::clock::StationClock;
use teleop::ingress::ingress_config::Hand;
use teleop::ingress::ingress_config::IngressConfig;
use teleop::ingress::ingress_counters::IngressCounters;
use teleop::ingress::rokoko_node::run_rokoko_ingress;
use teleop::ingress::rokoko_packet::bone_names;
use teleop::ingress::rokoko_packet_builder::right_hand_packet;
use teleop::ros::NetworkContext as _;
use teleop::ros::{QosConfig, RosNode};
use tokio::sync::{oneshot, watch};
use tokio::task::JoinHandle;

/// What the listener heard from the ingress.
#[derive(Default)]
struct Heard {
    keypoints: Vec<Vec<Point3<f64>>>,
    wrists: Vec<(i64, Isometry3<f64>, String)>,
    status: Vec<Value>,
}

struct Ingress {
    addr: SocketAddr,
    shutdown: watch::Sender<bool>,
    task: JoinHandle<Result<IngressCounters, teleop::ingress::IngressError>>,
    clock: StationClock,
}

async fn start_ingress(domain: u16, max_packet_bytes: usize) -> Ingress {
    let config = IngressConfig {
        bind_address: [127, 0, 0, 1].into(),
        port: 0,
        max_packet_bytes,
        network: loopback(domain),
        ..IngressConfig::default()
    };
    start_ingress_with(config).await
}

async fn start_ingress_with(config: IngressConfig) -> Ingress {
    let clock = StationClock::new();
    let (shutdown, shutdown_rx) = watch::channel(false);
    let (bound_tx, bound_rx) = oneshot::channel();
    let task = tokio::spawn(run_rokoko_ingress(
        config,
        clock,
        shutdown_rx,
        Some(bound_tx),
        false,
    ));
    let addr = bound_rx.await.expect("the ingress did not start");
    Ingress {
        addr,
        shutdown,
        task,
        clock,
    }
}

fn listen(domain: u16) -> (RosNode, Arc<Mutex<Heard>>, Vec<JoinHandle<()>>) {
    let context = loopback(domain).context().unwrap();
    let mut node = RosNode::new(&context, "/", "rokoko_test_listener").unwrap();
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
    let a = tokio::spawn(async move {
        let mut stream = Box::pin(keypoints.async_stream());
        while let Some(Ok((m, _))) = stream.next().await {
            h.lock()
                .unwrap()
                .keypoints
                .push(array_to_points(&m).unwrap());
        }
    });
    let h = heard.clone();
    let b = tokio::spawn(async move {
        let mut stream = Box::pin(wrist.async_stream());
        while let Some(Ok((m, _))) = stream.next().await {
            let stamp = m.header.stamp.to_nanos();
            let pose = pose_to_isometry(&m.pose).unwrap();
            h.lock()
                .unwrap()
                .wrists
                .push((stamp, pose, m.header.frame_id));
        }
    });
    let h = heard.clone();
    let c = tokio::spawn(async move {
        let mut stream = Box::pin(status.async_stream());
        while let Some(Ok((m, _))) = stream.next().await {
            h.lock()
                .unwrap()
                .status
                .push(serde_json::from_str(&m.data).unwrap());
        }
    });
    (node, heard, vec![a, b, c])
}

async fn wait_for(heard: &Arc<Mutex<Heard>>, what: &str, ok: impl Fn(&Heard) -> bool) {
    let start = Instant::now();
    while !ok(&heard.lock().unwrap()) {
        assert!(
            start.elapsed() < Duration::from_secs(15),
            "timed out waiting for {what}"
        );
        tokio::time::sleep(Duration::from_millis(5)).await;
    }
}

fn glove() -> SimGlove {
    let shape = HumanHandShape::average();
    let motion = Motion::new(MotionKind::TaskLike, 4.0, &shape).unwrap();
    SimGlove::new(shape, motion, KeypointLayout::Lab22).unwrap()
}

/// Studio's bones for a right hand written out by hand: bone k at Studio (0.1 k, 1.5, −0.2),
/// the hand bone turned 90° about Studio's up axis.
fn hand_written_packet(timestamp_s: f64) -> Vec<u8> {
    let mut body = serde_json::Map::new();
    for (k, name) in bone_names(Hand::Right, KeypointLayout::Lab22)
        .iter()
        .enumerate()
    {
        body.insert(
            name.clone(),
            json!({"position": {"x": 0.1 * k as f64, "y": 1.5, "z": -0.2},
                   "rotation": {"x": 0.0, "y": 0.0, "z": 0.0, "w": 1.0}}),
        );
    }
    let h = std::f64::consts::FRAC_1_SQRT_2;
    body.insert(
        "rightHand".into(),
        json!({"position": {"x": 0.1, "y": 1.5, "z": -0.2},
               "rotation": {"x": 0.0, "y": h, "z": 0.0, "w": h}}),
    );
    json!({"version": "3,0", "fps": 100,
           "scene": {"timestamp": timestamp_s, "actors": [{"name": "Actor1", "body": body}],
                     "props": [], "characters": []}})
    .to_string()
    .into_bytes()
}

/// Sends `glove`'s frame at `t` as a Studio packet from `socket` to `addr`; returns its
/// keypoints.
fn send_glove_frame(
    socket: &UdpSocket,
    addr: SocketAddr,
    glove: &SimGlove,
    t: f64,
) -> Vec<Point3<f64>> {
    let (points, wrist) = glove.frame(t);
    socket
        .send_to(
            &right_hand_packet(t, KeypointLayout::Lab22, &points, &wrist),
            addr,
        )
        .unwrap();
    points
}

/// Until discovery completes, sends frames of the glove's start (timestamps rising from
/// `t`); then checks every keypoint frame heard came with its wrist. Returns the frames heard
/// and the last timestamp sent.
async fn warm_up(
    heard: &Arc<Mutex<Heard>>,
    socket: &UdpSocket,
    addr: SocketAddr,
    glove: &SimGlove,
) -> (usize, f64) {
    let mut t = 0.0;
    let start = Instant::now();
    while heard.lock().unwrap().keypoints.is_empty() {
        assert!(
            start.elapsed() < Duration::from_secs(15),
            "nothing published in 15 s"
        );
        t += 0.01;
        send_glove_frame(socket, addr, glove, t);
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    tokio::time::sleep(Duration::from_millis(100)).await;
    let warm = heard.lock().unwrap().keypoints.len();
    assert_eq!(heard.lock().unwrap().wrists.len(), warm);
    (warm, t)
}

/// The hand-written packet, and its values worked out by hand: Studio (x, y, z) → ROS
/// (z, −x, y), so bone k → (−0.2, −0.1 k, 1.5); the hand bone's turn about Studio's up
/// turns ROS forward (+x) to ROS right (−y). Stamped at receipt, on the ingress's clock.
async fn check_hand_written_packet(
    heard: &Arc<Mutex<Heard>>,
    ingress: &Ingress,
    socket: &UdpSocket,
    warm: usize,
    t: f64,
) {
    let before_ns = ingress.clock.now_ns();
    socket
        .send_to(&hand_written_packet(t), ingress.addr)
        .unwrap();
    wait_for(heard, "the hand-written frame", |h| {
        h.keypoints.len() > warm && h.wrists.len() > warm
    })
    .await;
    let h = heard.lock().unwrap();
    let points = &h.keypoints[warm];
    assert_eq!(points.len(), 22);
    for (k, p) in points.iter().enumerate() {
        let expected = Point3::new(-0.2, -0.1 * k as f64, 1.5);
        assert!((p - expected).norm() < 1e-6, "point {k}: {p} vs {expected}");
    }
    let (stamp, wrist, frame_id) = &h.wrists[warm];
    assert_eq!(frame_id, "rokoko_world");
    assert!((wrist.translation.vector - Vector3::new(-0.2, -0.1, 1.5)).norm() < 1e-6);
    let forward = wrist.rotation * Vector3::x();
    assert!(
        (forward - Vector3::new(0.0, -1.0, 0.0)).norm() < 1e-6,
        "{forward}"
    );
    assert!(
        *stamp >= before_ns && *stamp <= ingress.clock.now_ns(),
        "stamp {stamp}"
    );
}

/// One packet of each refused kind: malformed, truncated, oversized (over 30,000 bytes) and
/// missing a bone (the last two with a timestamp far ahead, so only the fault refuses them).
fn bad_packets(glove: &SimGlove) -> Vec<Vec<u8>> {
    let (p, w) = glove.frame(1.0);
    let good = right_hand_packet(0.0, KeypointLayout::Lab22, &p, &w);
    let mut missing: Value = serde_json::from_slice(&good).unwrap();
    missing["scene"]["timestamp"] = json!(1e6);
    missing["scene"]["actors"][0]["body"]
        .as_object_mut()
        .unwrap()
        .remove("rightThumbTip");
    let mut oversized: Value = serde_json::from_slice(&good).unwrap();
    oversized["scene"]["timestamp"] = json!(1e6);
    oversized["padding"] = json!("x".repeat(40_000));
    vec![
        b"not json at all".to_vec(),
        good[..good.len() / 3].to_vec(),
        oversized.to_string().into_bytes(),
        missing.to_string().into_bytes(),
    ]
}

/// A stream of 40 good frames from `good` (timestamps rising after `t`), with every kind of
/// bad packet mixed in from another socket: a duplicate, a late older frame, then the four
/// refused kinds. Returns the good frames' keypoints, in order.
async fn send_stream_with_bad_packets(
    good: &UdpSocket,
    addr: SocketAddr,
    glove: &SimGlove,
    mut t: f64,
) -> Vec<Vec<Point3<f64>>> {
    let mut expected: Vec<Vec<Point3<f64>>> = Vec::new();
    let bad = bad_packets(glove);
    let other = UdpSocket::bind("127.0.0.1:0").unwrap();
    for k in 0..40 {
        t += 0.01;
        expected.push(send_glove_frame(good, addr, glove, t));
        match k {
            // The same frame again (Studio or the network repeated it).
            10 => {
                send_glove_frame(&other, addr, glove, t);
            }
            // An older frame arriving late.
            20 => {
                send_glove_frame(&other, addr, glove, t - 0.05);
            }
            30..=33 => {
                other.send_to(&bad[k - 30], addr).unwrap();
            }
            _ => {}
        }
        tokio::time::sleep(Duration::from_millis(3)).await;
    }
    expected
}

/// Only the new, good frames are published (after the warm-up and the hand-written one), with
/// the keypoints sent; the status counts each drop by kind.
fn check_only_good_frames_published(
    heard: &Arc<Mutex<Heard>>,
    warm: usize,
    expected: &[Vec<Point3<f64>>],
) {
    let h = heard.lock().unwrap();
    assert_eq!(
        h.keypoints.len(),
        warm + 1 + expected.len(),
        "only new, good frames are published"
    );
    for (k, (got, want)) in h.keypoints[warm + 1..].iter().zip(expected).enumerate() {
        for (a, b) in got.iter().zip(want) {
            assert!((a - b).norm() < 1e-6, "frame {k}: {a} vs {b}");
        }
    }
    let s = h.status.last().unwrap();
    assert_eq!(s["duplicates"], 1, "{s}");
    assert_eq!(s["out_of_order"], 1, "{s}");
    for kind in ["malformed", "truncated", "oversized", "missing_bone"] {
        assert_eq!(s["refused"][kind], 1, "{kind}: {s}");
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn packets_become_the_lab_topics_and_bad_ones_are_counted() {
    let domain = test_domain();
    let (_node, heard, listeners) = listen(domain);
    let ingress = start_ingress(domain, 30_000).await;
    let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    let glove = glove();
    let (warm, t) = warm_up(&heard, &socket, ingress.addr, &glove).await;

    let socket2 = UdpSocket::bind("127.0.0.1:0").unwrap();
    let t = t + 0.01;
    check_hand_written_packet(&heard, &ingress, &socket2, warm, t).await;

    // A stream with every kind of bad packet mixed in; only the good new frames go out.
    let expected = send_stream_with_bad_packets(&socket2, ingress.addr, &glove, t).await;
    let total = warm + 1 + expected.len();
    wait_for(&heard, "every good frame", |h| h.keypoints.len() >= total).await;
    wait_for(&heard, "the status to count every drop", |h| {
        h.status.last().is_some_and(|s| s["dropped"] == 6)
    })
    .await;
    tokio::time::sleep(Duration::from_millis(200)).await;
    check_only_good_frames_published(&heard, warm, &expected);
    ingress.shutdown.send(true).unwrap();
    let counters = ingress.task.await.unwrap().unwrap();
    // Everything received was published or dropped (frames sent before the listener matched
    // were published unheard).
    assert_eq!(counters.published + counters.dropped(), counters.received);
    assert!(counters.published as usize >= total);
    for l in listeners {
        l.abort();
    }
}

/// Discovery: sends the glove's first frame (a new packet each time, same hand: the station
/// sees repeats) until the station answers; then the motion, 60 frames drifting 0.1 mm a
/// frame so each is new. Returns every distinct frame sent, the first first.
async fn drive_station(
    h: &Harness,
    socket: &UdpSocket,
    addr: SocketAddr,
    glove: &SimGlove,
) -> Vec<Vec<Point3<f64>>> {
    let start = Instant::now();
    let (first, first_wrist) = glove.frame(0.0);
    let mut frames = vec![first.clone()];
    let mut t = 0.0;
    while h.heard.lock().unwrap().targets.is_empty() {
        assert!(
            start.elapsed() < Duration::from_secs(15),
            "no joint target in 15 s"
        );
        t += 1e-3;
        socket
            .send_to(
                &right_hand_packet(t, KeypointLayout::Lab22, &first, &first_wrist),
                addr,
            )
            .unwrap();
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    tokio::time::sleep(Duration::from_millis(200)).await;
    for k in 1..=60 {
        let ts = k as f64 * 0.04;
        // The motion holds still at times: drift the hand 0.1 mm a frame so each is new.
        let (mut points, wrist) = glove.frame(ts);
        for p in &mut points {
            p.x += 1e-4 * k as f64;
        }
        socket
            .send_to(
                &right_hand_packet(t + ts, KeypointLayout::Lab22, &points, &wrist),
                addr,
            )
            .unwrap();
        frames.push(points);
        tokio::time::sleep(Duration::from_millis(30)).await;
    }
    frames
}

/// Largest absolute difference between two joint vectors.
fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The frames as the station received them (f32). The station solves the newest frame of
/// whatever arrived since its last step (on a loaded machine several packets can land
/// together), from its previous command: so each target must be the retargeter's answer
/// for one of the frames, solved from the target before it, the frames in order, the last
/// target the last frame's.
fn assert_each_target_answers_a_frame(
    live: &[Vec<f64>],
    frames: &[Vec<Point3<f64>>],
    config: &StationConfig,
) {
    let received: Vec<Vec<Point3<f64>>> = frames
        .iter()
        .map(|points| {
            points
                .iter()
                .map(|p| Point3::new(p.x as f32 as f64, p.y as f32 as f64, p.z as f32 as f64))
                .collect()
        })
        .collect();
    let mut retargeter = Retargeter::new(
        HandModel::orca_v1_right(),
        config.retarget.clone(),
        &retarget::EmbodimentCatalog::builtin(),
    )
    .unwrap();
    // The frames solved so far, in order; a target equal to the one before it is the command
    // held (published again without a new frame).
    let mut path: Vec<usize> = Vec::new();
    let mut worst = 0.0f64;
    for (i, target) in live.iter().enumerate() {
        if i > 0 && distance(target, &live[i - 1]) == 0.0 {
            continue;
        }
        let first = path.last().map_or(0, |&j| j + 1);
        let mut best = (f64::INFINITY, first);
        for (j, frame) in received.iter().enumerate().skip(first).take(24) {
            match i {
                0 => retargeter.reset(),
                _ => retargeter.set_command(&live[i - 1]).unwrap(),
            }
            let q = retargeter.retarget(frame, 0.04).unwrap().q;
            let d = distance(&q, target);
            if d < best.0 {
                best = (d, j);
            }
        }
        assert!(
            best.0 < 1e-5,
            "target {i} is no frame's answer (closest: frame {}, {:.2e} rad)",
            best.1,
            best.0
        );
        worst = worst.max(best.0);
        path.push(best.1);
    }
    assert_eq!(
        path.last(),
        Some(&(received.len() - 1)),
        "the last target answers the last frame"
    );
    println!(
        "packets -> ingress -> station: {} targets, {} of the {} frames solved, each the \
         retargeter's answer for its frame to {worst:.2e} rad",
        live.len(),
        path.len(),
        received.len()
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn packets_drive_the_station_to_the_retargeters_joint_targets() {
    let domain = test_domain();
    // The targets do not depend on when frames arrive: the in-process retargeter fed the
    // same frames agrees. The ingress publishes best effort.
    let mut config = timing_independent_config();
    config.input.qos = QosConfig::best_effort(2000);
    let h = Harness::start(config.clone(), domain).await.unwrap();
    let ingress = start_ingress(domain, 65_507).await;
    let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    let glove = glove();

    let frames = drive_station(&h, &socket, ingress.addr, &glove).await;
    h.wait_until(Duration::from_secs(10), |heard| {
        heard.targets.len() >= frames.len()
    })
    .await
    .unwrap();
    let live = h.target_positions();
    let summary = h.stop().await.unwrap();
    ingress.shutdown.send(true).unwrap();
    ingress.task.await.unwrap().unwrap();
    assert!(
        summary.counters.rejected.values().all(|&n| n == 0),
        "{:?}",
        summary.counters
    );
    assert_eq!(summary.counters.frames_new as usize, frames.len());
    assert_each_target_answers_a_frame(&live, &frames, &config);
}

/// A frame of `glove` at `t` stamped `stamp` (`None`: no `scene.timestamp` at all).
fn glove_packet(glove: &SimGlove, t: f64, stamp: Option<f64>) -> Vec<u8> {
    let (points, wrist) = glove.frame(t);
    let mut value: Value = serde_json::from_slice(&right_hand_packet(
        t,
        KeypointLayout::Lab22,
        &points,
        &wrist,
    ))
    .unwrap();
    match stamp {
        Some(s) => value["scene"]["timestamp"] = json!(s),
        None => {
            value["scene"].as_object_mut().unwrap().remove("timestamp");
        }
    }
    value.to_string().into_bytes()
}

/// This host's non-loopback IPv4 address, if it has a route off the host (a UDP "connect"
/// sends nothing; it only picks the source address).
fn non_loopback_address() -> Option<std::net::IpAddr> {
    let probe = UdpSocket::bind("0.0.0.0:0").ok()?;
    probe.connect("192.0.2.1:9").ok()?;
    let ip = probe.local_addr().ok()?.ip();
    (!ip.is_loopback() && !ip.is_unspecified()).then_some(ip)
}

/// Sends the door's test packets: from a stranger, without a timestamp, one spoofed old one,
/// one slightly late one, a new one (published), then a real restart (5 in a row, the last
/// published). Returns how many datagrams went to the ingress's address.
async fn send_door_packets(allowed: &UdpSocket, addr: SocketAddr, glove: &SimGlove, t: f64) -> u64 {
    let stranger = UdpSocket::bind("127.0.0.1:0").unwrap();
    let sends: Vec<(&UdpSocket, Option<f64>)> = vec![
        // A good frame far ahead from a sender not allowed: would be new, is refused.
        (&stranger, Some(t + 100.0)),
        // No timestamp: cannot be ordered, refused.
        (allowed, None),
        // One spoofed packet stamped far back: not a restart on its own.
        (allowed, Some(t - 100.0)),
        // Slightly late: still ordered against t (had the spoofed one reset the order, this
        // would be published).
        (allowed, Some(t - 0.005)),
        // New: published.
        (allowed, Some(t + 0.01)),
    ];
    let mut sent = 0;
    for (socket, stamp) in sends {
        socket
            .send_to(&glove_packet(glove, 1.0, stamp), addr)
            .unwrap();
        sent += 1;
        tokio::time::sleep(Duration::from_millis(5)).await;
    }
    // Studio restarted: 5 packets in a row stamped 10 s back, rising; only the fifth is
    // published.
    for k in 0..5 {
        let stamp = t - 10.0 + 0.01 * k as f64;
        allowed
            .send_to(&glove_packet(glove, 1.5, Some(stamp)), addr)
            .unwrap();
        sent += 1;
        tokio::time::sleep(Duration::from_millis(5)).await;
    }
    sent
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn strangers_unstamped_and_spoofed_packets_do_not_get_through() {
    let domain = test_domain();
    let (_node, heard, listeners) = listen(domain);
    let allowed = UdpSocket::bind("127.0.0.1:0").unwrap();
    // The default bind address; only `allowed`'s address and port may send.
    let config = IngressConfig {
        port: 0,
        allowed_senders: vec![allowed.local_addr().unwrap().to_string()],
        network: loopback(domain),
        ..IngressConfig::default()
    };
    let ingress = start_ingress_with(config).await;
    assert_eq!(
        ingress.addr.ip(),
        std::net::IpAddr::from([127, 0, 0, 1]),
        "bound to this host only by default"
    );
    let glove = glove();
    let (warm, t) = warm_up(&heard, &allowed, ingress.addr, &glove).await;
    let mut sent_to_ingress = (t / 0.01).round() as u64;
    // The same port on this host's other address: nothing listens there.
    match non_loopback_address() {
        Some(ip) => {
            let outside = UdpSocket::bind((ip, 0)).unwrap();
            outside
                .send_to(
                    &glove_packet(&glove, 1.0, Some(t + 50.0)),
                    (ip, ingress.addr.port()),
                )
                .ok();
        }
        None => println!("no non-loopback address on this host: that part is skipped"),
    }
    sent_to_ingress += send_door_packets(&allowed, ingress.addr, &glove, t).await;
    wait_for(&heard, "the new frame and the restarted stream's", |h| {
        h.keypoints.len() >= warm + 2
    })
    .await;
    wait_for(&heard, "the status to count every datagram", |h| {
        h.status
            .last()
            .is_some_and(|s| s["received"] == sent_to_ingress)
    })
    .await;
    tokio::time::sleep(Duration::from_millis(200)).await;
    ingress.shutdown.send(true).unwrap();
    let counters = ingress.task.await.unwrap().unwrap();
    let h = heard.lock().unwrap();
    assert_eq!(h.keypoints.len(), warm + 2, "only the two new frames");
    let s = h.status.last().unwrap();
    assert!(
        s["source"]["device"]
            .as_str()
            .unwrap()
            .starts_with("Rokoko Studio Live on UDP 127.0.0.1:"),
        "{s}"
    );
    assert_eq!(s["refused"]["sender"], 1, "{s}");
    assert_eq!(s["refused"]["no_timestamp"], 1, "{s}");
    assert_eq!(s["out_of_order"], 1, "{s}");
    assert_eq!(
        s["restart_unconfirmed"], 5,
        "1 spoofed + 4 before the restart: {s}"
    );
    assert_eq!(s["restarts"], 1, "{s}");
    assert_eq!(s["duplicates"], 0, "{s}");
    // The datagram sent to the other address never arrived.
    assert_eq!(counters.received, sent_to_ingress);
    assert_eq!(counters.published + counters.dropped(), counters.received);
    for l in listeners {
        l.abort();
    }
}
