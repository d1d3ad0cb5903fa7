//! Benchmark of `pomdar ingress avp`: what the ingress adds between a Vision Pro hand update
//! and the keypoints on ROS 2.
//!
//! A headset is served in process (tonic's server, the same messages and codec, over real
//! HTTP/2 on loopback); the ingress connects to it as to a headset. `cargo bench -p teleop
//! --bench avp_ingress` prints one JSON line each:
//! - `avp_convert`: one update (27 joints) decoded from its protobuf bytes and converted, per
//!   update, p50 / p99 over 5,000 updates;
//! - `avp_latency`: update handed to the headset's stream → `/ingress/mano` received by a
//!   subscriber over loopback DDS, at 90 updates/s (the headset's rate) for 10 s (p50 / p99 /
//!   max);
//! - `avp_throughput`: 20,000 updates streamed as fast as the headset side can; updates/s
//!   published by the ingress and heard by the subscriber.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a benchmark fails loudly

use std::collections::HashMap;
use std::convert::Infallible;
use std::pin::Pin;
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll};
use std::time::{Duration, Instant};

use futures::{Stream, StreamExt};
use msgs::Float32MultiArray;
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion};
use prost::Message as _;
use retarget::KeypointLayout;
use retarget::human_hand::{HumanHandShape, Motion, MotionKind, SimGlove};
use teleop::clock::StationClock;
use teleop::ingress::avp_config::AvpConfig;
use teleop::ingress::avp_frame::convert_update;
use teleop::ingress::avp_node::run_avp_ingress;
use teleop::ingress::avp_proto::{Decoded, HandUpdate, HandUpdateCodec};
use teleop::ingress::avp_update_builder::hand_update;
use teleop::ingress::ingress_config::Hand;
use teleop::ros::NetworkContext as _;
use teleop::ros::{NetworkConfig, QosConfig, RosNode};
use tokio::sync::{mpsc, watch};
use tonic::codegen::http;
use tonic::server::{NamedService, ServerStreamingService};

fn percentile(sorted: &[f64], p: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

/// The update for update id `k`: a hand of the simulated glove, its wrist raised by `k` × 10 µm
/// so the subscriber can tell which update a frame came from.
fn tagged_update(glove: &SimGlove, k: usize) -> HandUpdate {
    let (points, _) = glove.frame(0.0);
    let lift = nalgebra::Vector3::new(0.0, 0.0, k as f64 * 1e-5);
    let lab22: [Point3<f64>; 22] = std::array::from_fn(|i| points[i] + lift);
    let wrist = Isometry3::from_parts(
        Translation3::from(lab22[1].coords),
        UnitQuaternion::identity(),
    );
    hand_update(&lab22, &wrist, true, Hand::Right)
}

/// The update id a frame carries (its wrist point's height over the untagged one).
fn tag_of(frame: &Float32MultiArray, base_z: f32) -> usize {
    ((frame.data[5] - base_z) as f64 / 1e-5).round() as usize
}

fn bench_convert(glove: &SimGlove) {
    let bytes: Vec<Vec<u8>> = (0..5_000)
        .map(|k| tagged_update(glove, k).encode_to_vec())
        .collect();
    let mut times: Vec<f64> = bytes
        .iter()
        .map(|b| {
            let start = Instant::now();
            let update = HandUpdate::decode(&b[..]).unwrap();
            std::hint::black_box(
                convert_update(&update, Hand::Right, KeypointLayout::Lab22).unwrap(),
            );
            start.elapsed().as_secs_f64() * 1e6
        })
        .collect();
    times.sort_by(f64::total_cmp);
    println!(
        "{{\"bench\":\"avp_convert\",\"update_bytes\":{},\"p50_us\":{:.1},\"p99_us\":{:.1}}}",
        bytes[0].len(),
        percentile(&times, 0.5),
        percentile(&times, 0.99)
    );
}

/// The headset's service: the first call streams what the bench sends on its channel.
#[derive(Clone)]
struct Headset {
    updates: Arc<Mutex<Option<mpsc::Receiver<HandUpdate>>>>,
}

impl NamedService for Headset {
    const NAME: &'static str = "handtracking.HandTrackingService";
}

type UpdateStream = Pin<Box<dyn Stream<Item = Result<HandUpdate, tonic::Status>> + Send>>;

impl ServerStreamingService<Decoded> for Headset {
    type Response = HandUpdate;
    type ResponseStream = UpdateStream;
    type Future = std::future::Ready<Result<tonic::Response<UpdateStream>, tonic::Status>>;

    fn call(&mut self, _request: tonic::Request<Decoded>) -> Self::Future {
        let Some(rx) = self.updates.lock().unwrap().take() else {
            return std::future::ready(Err(tonic::Status::unavailable("one stream only")));
        };
        let stream = tonic::codegen::tokio_stream::wrappers::ReceiverStream::new(rx).map(Ok);
        std::future::ready(Ok(tonic::Response::new(Box::pin(stream) as UpdateStream)))
    }
}

impl tonic::codegen::Service<http::Request<tonic::body::Body>> for Headset {
    type Response = http::Response<tonic::body::Body>;
    type Error = Infallible;
    type Future = tonic::codegen::BoxFuture<Self::Response, Infallible>;

    fn poll_ready(&mut self, _: &mut Context<'_>) -> Poll<Result<(), Infallible>> {
        Poll::Ready(Ok(()))
    }

    fn call(&mut self, request: http::Request<tonic::body::Body>) -> Self::Future {
        let service = self.clone();
        Box::pin(async move {
            let mut grpc = tonic::server::Grpc::new(HandUpdateCodec);
            Ok(grpc.server_streaming(service, request).await)
        })
    }
}

/// Serve a headset on loopback; the sender feeds its one stream.
async fn serve_headset() -> (u16, mpsc::Sender<HandUpdate>) {
    let (tx, rx) = mpsc::channel(64);
    let headset = Headset {
        updates: Arc::new(Mutex::new(Some(rx))),
    };
    let incoming = tonic::transport::server::TcpIncoming::bind(([127, 0, 0, 1], 0).into())
        .unwrap()
        .with_nodelay(Some(true));
    let port = incoming.local_addr().unwrap().port();
    tokio::spawn(tonic::transport::Server::builder().serve_with_incoming(headset, incoming));
    (port, tx)
}

type Heard = mpsc::UnboundedReceiver<(i64, usize)>;

fn listen(network: &NetworkConfig, clock: StationClock, base_z: f32) -> Heard {
    let context = network.context().unwrap();
    let mut node = RosNode::new(&context, "/", "avp_bench_listener").unwrap();
    let sub = node
        .subscription::<Float32MultiArray>("/ingress/mano", QosConfig::best_effort(1000))
        .unwrap();
    let (tx, rx) = mpsc::unbounded_channel();
    tokio::spawn(async move {
        let _node = node;
        let mut stream = Box::pin(sub.async_stream());
        while let Some(Ok((m, _))) = stream.next().await {
            tx.send((clock.now_ns(), tag_of(&m, base_z))).ok();
        }
    });
    rx
}

/// Latency at 90 updates/s over ids `first..first + 900`.
async fn bench_latency(
    glove: &SimGlove,
    tx: &mpsc::Sender<HandUpdate>,
    heard: &mut Heard,
    clock: StationClock,
    first: usize,
) {
    let mut sent_ns = HashMap::new();
    let mut latencies = Vec::new();
    let mut interval = tokio::time::interval(Duration::from_secs_f64(1.0 / 90.0));
    let updates: Vec<_> = (first..first + 900)
        .map(|k| tagged_update(glove, k))
        .collect();
    for (k, update) in (first..).zip(updates) {
        interval.tick().await;
        sent_ns.insert(k, clock.now_ns());
        tx.send(update).await.unwrap();
        while let Ok((at, tag)) = heard.try_recv() {
            if let Some(t0) = sent_ns.get(&tag) {
                latencies.push((at - t0) as f64 * 1e-6);
            }
        }
    }
    tokio::time::sleep(Duration::from_millis(300)).await;
    while let Ok((at, tag)) = heard.try_recv() {
        if let Some(t0) = sent_ns.get(&tag) {
            latencies.push((at - t0) as f64 * 1e-6);
        }
    }
    latencies.sort_by(f64::total_cmp);
    println!(
        "{{\"bench\":\"avp_latency\",\"rate_hz\":90,\"sent\":900,\"received\":{},\"p50_ms\":{:.3},\"p99_ms\":{:.3},\"max_ms\":{:.3}}}",
        latencies.len(),
        percentile(&latencies, 0.5),
        percentile(&latencies, 0.99),
        latencies.last().copied().unwrap_or(f64::NAN)
    );
}

/// Throughput: 20,000 updates (built beforehand) streamed as fast as the channel takes them.
async fn bench_throughput(
    glove: &SimGlove,
    tx: mpsc::Sender<HandUpdate>,
    heard: &mut Heard,
    base: usize,
) {
    let updates: Vec<_> = (base..base + 20_000)
        .map(|k| tagged_update(glove, k % 60_000))
        .collect();
    let sender = tokio::spawn(async move {
        let n = updates.len();
        for u in updates {
            tx.send(u).await.unwrap();
        }
        n
    });
    let (mut first, mut last, mut count) = (None, 0i64, 0usize);
    while let Ok(Some((at, _))) =
        tokio::time::timeout(Duration::from_millis(500), heard.recv()).await
    {
        first.get_or_insert(at);
        last = at;
        count += 1;
    }
    let sent = sender.await.unwrap();
    let seconds = (last - first.unwrap_or(last)) as f64 * 1e-9;
    println!(
        "{{\"bench\":\"avp_throughput\",\"sent\":{sent},\"published_and_heard\":{count},\"seconds\":{seconds:.2},\"per_s\":{:.0}}}",
        count as f64 / seconds.max(1e-9)
    );
}

async fn bench_live(glove: &SimGlove) {
    let network = NetworkConfig {
        domain_id: Some(170 + (std::process::id() % 30) as u16),
        interfaces: vec![[127, 0, 0, 1].into()],
    };
    let clock = StationClock::new();
    let (port, tx) = serve_headset().await;
    let base_z = {
        let update = tagged_update(glove, 0);
        let frame = convert_update(&update, Hand::Right, KeypointLayout::Lab22).unwrap();
        frame.keypoints[1].z as f32
    };
    let mut heard = listen(&network, clock, base_z);
    let config = AvpConfig {
        address: "127.0.0.1".into(),
        port,
        network,
        ..AvpConfig::default()
    };
    let (shutdown, shutdown_rx) = watch::channel(false);
    let ingress = tokio::spawn(run_avp_ingress(config, clock, shutdown_rx, false));
    // Discovery: updates until the subscriber hears one.
    let start = Instant::now();
    let mut k = 1;
    loop {
        tx.send(tagged_update(glove, k)).await.unwrap();
        k += 1;
        if tokio::time::timeout(Duration::from_millis(50), heard.recv())
            .await
            .is_ok()
        {
            break;
        }
        assert!(start.elapsed() < Duration::from_secs(15), "no discovery");
    }
    tokio::time::sleep(Duration::from_millis(200)).await;
    while heard.try_recv().is_ok() {}
    bench_latency(glove, &tx, &mut heard, clock, k).await;
    bench_throughput(glove, tx, &mut heard, k + 900).await;
    shutdown.send(true).unwrap();
    let counters = ingress.await.unwrap().unwrap();
    eprintln!(
        "ingress: received {}, published {}, duplicates {}",
        counters.received, counters.published, counters.duplicates
    );
}

fn main() {
    let shape = HumanHandShape::average();
    let motion = Motion::new(MotionKind::TaskLike, 4.0, &shape).unwrap();
    let glove = SimGlove::new(shape, motion, KeypointLayout::Lab22).unwrap();
    bench_convert(&glove);
    tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap()
        .block_on(bench_live(&glove));
}
