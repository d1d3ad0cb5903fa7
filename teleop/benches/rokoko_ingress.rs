//! Benchmark of `pomdar ingress rokoko`: what the ingress adds between Rokoko Studio's UDP
//! packet and the keypoints on ROS 2.
//!
//! `cargo bench -p teleop --bench rokoko_ingress` prints one JSON line each:
//! - `parse`: one real-shaped packet (one actor, full body, face) parsed and converted, per
//!   packet, p50 / p99 over 5,000 packets;
//! - `latency`: UDP send → `/ingress/mano` received by a subscriber over loopback DDS, at
//!   100 packets/s for 10 s (p50 / p99 / max);
//! - `throughput`: 20,000 packets sent as fast as one thread can; packets/s parsed,
//!   published and heard by the subscriber (the rest overflowed the socket buffer).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a benchmark fails loudly

use std::net::{SocketAddr, UdpSocket};
use std::time::{Duration, Instant};

use futures::StreamExt;
use msgs::Float32MultiArray;
use retarget::KeypointLayout;
use retarget::human_hand::{HumanHandShape, Motion, MotionKind, SimGlove};
use teleop::clock::StationClock;
use teleop::ingress::ingress_config::IngressConfig;
use teleop::ingress::rokoko_node::run_rokoko_ingress;
use teleop::ingress::rokoko_packet::{Selection, parse_packet};
use teleop::ingress::rokoko_packet_builder::right_hand_packet;
use teleop::ros::NetworkContext as _;
use teleop::ros::{NetworkConfig, QosConfig, RosNode};
use tokio::sync::{oneshot, watch};

fn percentile(sorted: &[f64], p: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

fn glove() -> SimGlove {
    let shape = HumanHandShape::average();
    let motion = Motion::new(MotionKind::TaskLike, 4.0, &shape).unwrap();
    SimGlove::new(shape, motion, KeypointLayout::Lab22).unwrap()
}

fn packet_at(glove: &SimGlove, t: f64) -> Vec<u8> {
    let (points, wrist) = glove.frame(t);
    right_hand_packet(t, KeypointLayout::Lab22, &points, &wrist)
}

fn bench_parse(glove: &SimGlove) {
    let config = IngressConfig::default();
    let selection = Selection {
        actor: None,
        hand: config.hand,
        layout: config.layout,
        max_packet_bytes: config.max_packet_bytes,
        position_scale_to_m: 1.0,
    };
    let packets: Vec<Vec<u8>> = (0..5_000)
        .map(|k| packet_at(glove, k as f64 * 0.01))
        .collect();
    let mut times: Vec<f64> = packets
        .iter()
        .map(|p| {
            let start = Instant::now();
            std::hint::black_box(parse_packet(p, &selection).unwrap());
            start.elapsed().as_secs_f64() * 1e6
        })
        .collect();
    times.sort_by(f64::total_cmp);
    println!(
        "{{\"bench\":\"rokoko_parse\",\"packet_bytes\":{},\"p50_us\":{:.1},\"p99_us\":{:.1}}}",
        packets[0].len(),
        percentile(&times, 0.5),
        percentile(&times, 0.99)
    );
}

/// The ingress's output as the bench hears it: (receive time in ns, the packet id tagged into
/// the forearm point's x).
type Heard = tokio::sync::mpsc::UnboundedReceiver<(i64, f32)>;

/// Subscribes to `/ingress/mano` on `network` and forwards, for each message, its receive
/// time and the packet id it carries; returns the receiver and the listening task.
fn listen(network: &NetworkConfig, clock: StationClock) -> (Heard, tokio::task::JoinHandle<()>) {
    let context = network.context().unwrap();
    let mut node = RosNode::new(&context, "/", "rokoko_bench_listener").unwrap();
    let sub = node
        .subscription::<Float32MultiArray>("/ingress/mano", QosConfig::best_effort(1000))
        .unwrap();
    let (heard_tx, heard_rx) = tokio::sync::mpsc::unbounded_channel::<(i64, f32)>();
    let listener = tokio::spawn(async move {
        // The node lives as long as its subscription is read.
        let _node = node;
        let mut stream = Box::pin(sub.async_stream());
        while let Some(Ok((m, _))) = stream.next().await {
            // The packet's id rides in the forearm point's x (see `bench_live`).
            heard_tx.send((clock.now_ns(), m.data[0])).ok();
        }
    });
    (heard_rx, listener)
}

/// Sends tagged packets until the subscriber hears one (DDS discovery), then lets the
/// pipeline drain and discards what was heard. Returns the last id sent.
async fn discover(
    socket: &UdpSocket,
    addr: SocketAddr,
    tagged: &impl Fn(usize) -> Vec<u8>,
    heard_rx: &mut Heard,
) -> usize {
    let start = Instant::now();
    let mut k = 0usize;
    loop {
        k += 1;
        socket.send_to(&tagged(k), addr).unwrap();
        if tokio::time::timeout(Duration::from_millis(50), heard_rx.recv())
            .await
            .is_ok()
        {
            break;
        }
        assert!(start.elapsed() < Duration::from_secs(15), "no discovery");
    }
    tokio::time::sleep(Duration::from_millis(200)).await;
    while heard_rx.try_recv().is_ok() {}
    k
}

/// Latency at 100 packets/s: sends ids `first..first + 1_000` and prints the `rokoko_latency`
/// line (p50 / p99 / max of send → heard).
async fn bench_latency(
    socket: &UdpSocket,
    addr: SocketAddr,
    tagged: &impl Fn(usize) -> Vec<u8>,
    heard_rx: &mut Heard,
    clock: StationClock,
    first: usize,
) {
    let mut sent_ns = std::collections::HashMap::new();
    let mut latencies = Vec::new();
    let mut collect = |heard_rx: &mut Heard, sent_ns: &std::collections::HashMap<usize, i64>| {
        while let Ok((at, tag)) = heard_rx.try_recv() {
            if let Some(t0) = sent_ns.get(&(tag as usize)) {
                latencies.push((at - t0) as f64 * 1e-6);
            }
        }
    };
    let mut interval = tokio::time::interval(Duration::from_millis(10));
    for id in first..first + 1_000 {
        interval.tick().await;
        sent_ns.insert(id, clock.now_ns());
        socket.send_to(&tagged(id), addr).unwrap();
        collect(heard_rx, &sent_ns);
    }
    tokio::time::sleep(Duration::from_millis(200)).await;
    collect(heard_rx, &sent_ns);
    latencies.sort_by(f64::total_cmp);
    println!(
        "{{\"bench\":\"rokoko_latency\",\"sent\":1000,\"received\":{},\"p50_ms\":{:.3},\"p99_ms\":{:.3},\"max_ms\":{:.3}}}",
        latencies.len(),
        percentile(&latencies, 0.5),
        percentile(&latencies, 0.99),
        latencies.last().copied().unwrap_or(f64::NAN)
    );
}

/// What the throughput pass saw: packets sent, and the packets with an id from the pass heard
/// by the subscriber, over how long.
struct Throughput {
    sent: usize,
    heard: usize,
    seconds: f64,
}

/// Throughput: `packets` (built beforehand, ids from `base`) sent from another thread as
/// fast as it can; the rate is what the subscriber received over the time it was receiving
/// (what overflows the socket buffer is dropped by the kernel, not counted).
async fn bench_throughput(
    socket: UdpSocket,
    addr: SocketAddr,
    packets: Vec<Vec<u8>>,
    heard_rx: &mut Heard,
    base: usize,
) -> Throughput {
    let sender = std::thread::spawn(move || {
        for p in &packets {
            socket.send_to(p, addr).unwrap();
        }
        packets.len()
    });
    let mut first_ns = None;
    let mut last_ns = 0;
    let mut heard = 0usize;
    while let Ok(Some((at, tag))) =
        tokio::time::timeout(Duration::from_millis(500), heard_rx.recv()).await
    {
        if tag as usize >= base {
            first_ns.get_or_insert(at);
            last_ns = at;
            heard += 1;
        }
    }
    Throughput {
        sent: sender.join().unwrap(),
        heard,
        seconds: (last_ns - first_ns.unwrap_or(last_ns)) as f64 * 1e-9,
    }
}

async fn bench_live(glove: &SimGlove) {
    let network = NetworkConfig {
        domain_id: Some(200 + (std::process::id() % 30) as u16),
        interfaces: vec![[127, 0, 0, 1].into()],
    };
    let config = IngressConfig {
        bind_address: [127, 0, 0, 1].into(),
        port: 0,
        network: network.clone(),
        ..IngressConfig::default()
    };
    let clock = StationClock::new();
    let (shutdown, shutdown_rx) = watch::channel(false);
    let (bound_tx, bound_rx) = oneshot::channel();
    let ingress = tokio::spawn(run_rokoko_ingress(
        config,
        clock,
        shutdown_rx,
        Some(bound_tx),
        false,
    ));
    let addr = bound_rx.await.unwrap();
    let (mut heard_rx, listener) = listen(&network, clock);
    let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    let (points, wrist) = glove.frame(0.0);
    let tagged = |k: usize| {
        let mut p = points.clone();
        p[0].x = k as f64;
        right_hand_packet(k as f64 * 0.01, KeypointLayout::Lab22, &p, &wrist)
    };

    let first = discover(&socket, addr, &tagged, &mut heard_rx).await + 1;
    bench_latency(&socket, addr, &tagged, &mut heard_rx, clock, first).await;

    let base = first + 1_000;
    let packets: Vec<Vec<u8>> = (base..base + 20_000).map(tagged).collect();
    let pass = bench_throughput(socket, addr, packets, &mut heard_rx, base).await;
    shutdown.send(true).unwrap();
    let counters = ingress.await.unwrap().unwrap();
    listener.abort();
    println!(
        "{{\"bench\":\"rokoko_throughput\",\"sent\":{},\"received_by_ingress\":{},\"published_and_heard\":{},\"seconds\":{:.2},\"per_s\":{:.0}}}",
        pass.sent,
        counters.received as usize - (base - 1),
        pass.heard,
        pass.seconds,
        pass.heard as f64 / pass.seconds.max(1e-9)
    );
}

fn main() {
    let glove = glove();
    bench_parse(&glove);
    tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap()
        .block_on(bench_live(&glove));
}
