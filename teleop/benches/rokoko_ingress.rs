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

use std::net::UdpSocket;
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
    let context = network.context().unwrap();
    let mut node = RosNode::new(&context, "/", "rokoko_bench_listener").unwrap();
    let sub = node
        .subscription::<Float32MultiArray>("/ingress/mano", QosConfig::best_effort(1000))
        .unwrap();
    let (heard_tx, mut heard_rx) = tokio::sync::mpsc::unbounded_channel::<(i64, f32)>();
    let listener = tokio::spawn(async move {
        let mut stream = Box::pin(sub.async_stream());
        while let Some(Ok((m, _))) = stream.next().await {
            // The packet's id rides in the forearm point's x (see below).
            heard_tx.send((clock.now_ns(), m.data[0])).ok();
        }
    });
    let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    let (points, wrist) = glove.frame(0.0);
    let tagged = |k: usize| {
        let mut p = points.clone();
        p[0].x = k as f64;
        right_hand_packet(k as f64 * 0.01, KeypointLayout::Lab22, &p, &wrist)
    };
    // Discovery.
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

    // Latency at 100 packets/s.
    let mut sent_ns = std::collections::HashMap::new();
    let mut latencies = Vec::new();
    let mut interval = tokio::time::interval(Duration::from_millis(10));
    let first = k + 1;
    for id in first..first + 1_000 {
        interval.tick().await;
        sent_ns.insert(id, clock.now_ns());
        socket.send_to(&tagged(id), addr).unwrap();
        while let Ok((at, tag)) = heard_rx.try_recv() {
            if let Some(t0) = sent_ns.get(&(tag as usize)) {
                latencies.push((at - t0) as f64 * 1e-6);
            }
        }
    }
    tokio::time::sleep(Duration::from_millis(200)).await;
    while let Ok((at, tag)) = heard_rx.try_recv() {
        if let Some(t0) = sent_ns.get(&(tag as usize)) {
            latencies.push((at - t0) as f64 * 1e-6);
        }
    }
    latencies.sort_by(f64::total_cmp);
    println!(
        "{{\"bench\":\"rokoko_latency\",\"sent\":1000,\"received\":{},\"p50_ms\":{:.3},\"p99_ms\":{:.3},\"max_ms\":{:.3}}}",
        latencies.len(),
        percentile(&latencies, 0.5),
        percentile(&latencies, 0.99),
        latencies.last().copied().unwrap_or(f64::NAN)
    );

    // Throughput: 20,000 packets built beforehand, sent from another thread as fast as it
    // can; the rate is what the subscriber received over the time it was receiving (what
    // overflows the socket buffer is dropped by the kernel, not counted).
    let base = first + 1_000;
    let packets: Vec<Vec<u8>> = (base..base + 20_000).map(tagged).collect();
    let sender = std::thread::spawn(move || {
        for p in &packets {
            socket.send_to(p, addr).unwrap();
        }
        packets.len()
    });
    let mut first_ns = None;
    let mut last_ns = 0;
    let mut count = 0usize;
    while let Ok(Some((at, tag))) =
        tokio::time::timeout(Duration::from_millis(500), heard_rx.recv()).await
    {
        if tag as usize >= base {
            first_ns.get_or_insert(at);
            last_ns = at;
            count += 1;
        }
    }
    let sent = sender.join().unwrap();
    shutdown.send(true).unwrap();
    let counters = ingress.await.unwrap().unwrap();
    listener.abort();
    let seconds = (last_ns - first_ns.unwrap_or(last_ns)) as f64 * 1e-9;
    println!(
        "{{\"bench\":\"rokoko_throughput\",\"sent\":{sent},\"received_by_ingress\":{},\"published_and_heard\":{count},\"seconds\":{seconds:.2},\"per_s\":{:.0}}}",
        counters.received as usize - (base - 1),
        count as f64 / seconds.max(1e-9)
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
