//! The ingress node: Rokoko Studio's UDP stream in, the lab's ROS 2 topics out.
//!
//! One datagram is one frame. A frame is published only when a packet arrives and is new
//! (see [`super::ingress_counters`]): no timer republishes stale data. Keypoints go out as
//! `std_msgs/Float32MultiArray` (N × 3, metres, ROS frame) and the hand bone's pose as
//! `geometry_msgs/PoseStamped`, stamped with this computer's clock at receipt. A bad packet
//! is counted under its kind and logged the first time that kind occurs; nothing about a
//! packet stops the node. Once a second the counts go out as JSON on the status topic.

use std::net::SocketAddr;
use std::time::Duration;

use msgs::{Float32MultiArray, PoseStamped, StringMsg};
use ros2_client::Publisher;
use tokio::net::UdpSocket;
use tokio::sync::{oneshot, watch};

use crate::clock::StationClock;
use crate::ingress::error::IngressError;
use crate::ingress::ingress_config::IngressConfig;
use crate::ingress::ingress_counters::{IngressCounters, Order, SourceInfo};
use crate::ingress::rokoko_packet::{PacketError, Selection, parse_packet};
use crate::ros::{QosConfig, RosNode};
use station::convert::{header, isometry_to_pose};

/// How often the status goes out.
const STATUS_PERIOD: Duration = Duration::from_secs(1);

/// Print a status line on stderr every this many status periods (with `print_status`).
const PRINT_EVERY: u64 = 5;

/// The node's publishers.
struct Publishers {
    keypoints: Publisher<Float32MultiArray>,
    wrist: Publisher<PoseStamped>,
    status: Publisher<StringMsg>,
}

impl Publishers {
    /// Publish the status report; a failure is counted.
    async fn status(&self, config: &IngressConfig, counters: &mut IngressCounters, status: String) {
        if self
            .status
            .async_publish(StringMsg { data: status })
            .await
            .is_err()
        {
            counters.publish_failed(&config.status_topic);
        }
    }

    /// Publish a frame's keypoints and wrist pose; failures are counted.
    async fn frame(
        &self,
        config: &IngressConfig,
        counters: &mut IngressCounters,
        array: Float32MultiArray,
        pose: PoseStamped,
    ) {
        let keypoints_sent = self.keypoints.async_publish(array).await.is_ok();
        let wrist_sent = self.wrist.async_publish(pose).await.is_ok();
        counters.frame_sent(
            (&config.keypoints_topic, keypoints_sent),
            (&config.wrist_topic, wrist_sent),
        );
    }
}

/// Run the ingress until `shutdown`; `bound` receives the local UDP address once listening
/// (useful with port 0); with `print_status` a one-line status goes to stderr every 5 s.
/// Returns the final counts.
pub async fn run_rokoko_ingress(
    config: IngressConfig,
    clock: StationClock,
    mut shutdown: watch::Receiver<bool>,
    bound: Option<oneshot::Sender<SocketAddr>>,
    print_status: bool,
) -> Result<IngressCounters, IngressError> {
    config.validate()?;
    let socket = UdpSocket::bind((config.bind_address, config.port))
        .await
        .map_err(|source| IngressError::Bind {
            address: config.bind_address,
            port: config.port,
            source,
        })?;
    let local = socket
        .local_addr()
        .map_err(|source| IngressError::LocalAddress { source })?;
    let mut node = RosNode::join(&config.network, "/", "pomdar_rokoko_ingress")?;
    let publishers = Publishers {
        keypoints: node.publisher(&config.keypoints_topic, config.qos)?,
        wrist: node.publisher(&config.wrist_topic, config.qos)?,
        status: node.publisher(&config.status_topic, QosConfig::reliable(10))?,
    };
    if let Some(tx) = bound {
        tx.send(local).ok();
    }
    let selection = Selection {
        actor: config.actor.as_deref(),
        hand: config.hand,
        layout: config.layout,
        max_packet_bytes: config.max_packet_bytes,
        position_scale_to_m: config.position_scale_to_m,
    };
    // One byte more than the limit, so an oversized datagram shows as such.
    let mut buffer = vec![0u8; config.max_packet_bytes + 1];
    let source = rokoko_source(&config, local);
    let mut counters = IngressCounters::default();
    counters.status(clock.now_ns(), &source);
    let mut ticks = 0u64;
    let mut status_tick = tokio::time::interval(STATUS_PERIOD);
    status_tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
    loop {
        tokio::select! {
            _ = shutdown.changed() => if *shutdown.borrow() { break },
            _ = status_tick.tick() => {
                let status = counters.status(clock.now_ns(), &source);
                ticks += 1;
                if print_status && ticks.is_multiple_of(PRINT_EVERY) {
                    eprintln!("{}", status_line(&status));
                }
                publishers.status(&config, &mut counters, status.to_string()).await;
            }
            received = socket.recv_from(&mut buffer) => {
                let (n, from) = match received {
                    Ok(r) => r,
                    Err(e) => {
                        // e.g. ICMP port-unreachable echoes on some systems: not fatal.
                        if counters.refused("socket_error") {
                            eprintln!("warning: rokoko ingress: receive error: {e} (counted, not logged again)");
                        }
                        continue;
                    }
                };
                let now = clock.now_ns();
                counters.received(now);
                let frame = match parse_packet(&buffer[..n], &selection) {
                    Ok(frame) => frame,
                    Err(e) => {
                        log_refusal(&mut counters, &e, from);
                        continue;
                    }
                };
                match counters.order(frame.timestamp_s, config.restart_after_backwards_s) {
                    Order::Duplicate | Order::OutOfOrder => continue,
                    Order::Restart => eprintln!(
                        "note: rokoko ingress: the studio timestamp went back to {:.3} s: stream restarted",
                        frame.timestamp_s.unwrap_or_default()
                    ),
                    Order::New => {}
                }
                let rows: Vec<[f32; 3]> = frame
                    .keypoints
                    .iter()
                    .map(|p| [p.x as f32, p.y as f32, p.z as f32])
                    .collect();
                let array = Float32MultiArray::from_points(&rows)?;
                let pose = PoseStamped {
                    header: header(now, &config.wrist_frame_id),
                    pose: isometry_to_pose(&frame.wrist),
                };
                publishers.frame(&config, &mut counters, array, pose).await;
            }
        }
    }
    let status = counters.status(clock.now_ns(), &source);
    publishers
        .status(&config, &mut counters, status.to_string())
        .await;
    Ok(counters)
}

/// The source as the status names it.
pub fn rokoko_source(config: &IngressConfig, local: SocketAddr) -> SourceInfo {
    SourceInfo {
        kind: "rokoko",
        device: format!(
            "Rokoko Studio Live on UDP {local}, actor {}",
            config.actor.as_deref().unwrap_or("(first)")
        ),
    }
}

/// One line for the operator from a status report.
pub fn status_line(status: &serde_json::Value) -> String {
    let refused = status["refused"]
        .as_object()
        .map(|m| {
            m.iter()
                .map(|(k, v)| format!("{k} {v}"))
                .collect::<Vec<_>>()
                .join(", ")
        })
        .unwrap_or_default();
    let not_published = status["publish_failed"]
        .as_object()
        .filter(|m| !m.is_empty())
        .map(|m| {
            let topics: Vec<String> = m.iter().map(|(k, v)| format!("{k} {v}")).collect();
            format!("; not published: {}", topics.join(", "))
        })
        .unwrap_or_default();
    let connection = match status["connected"].as_bool() {
        Some(true) => "connected, ".to_string(),
        Some(false) => "NOT CONNECTED, ".to_string(),
        None => String::new(),
    };
    format!(
        "{} ingress: {connection}{} Hz, {} received, {} published, dropped {} (duplicates {}, out of order {}{}{}){}",
        status["source"]["kind"].as_str().unwrap_or("glove"),
        status["rate_hz"],
        status["received"],
        status["published"],
        status["dropped"],
        status["duplicates"],
        status["out_of_order"],
        if refused.is_empty() { "" } else { ", " },
        refused,
        not_published
    )
}

fn log_refusal(counters: &mut IngressCounters, error: &PacketError, from: SocketAddr) {
    if counters.refused(error.kind()) {
        eprintln!(
            "warning: rokoko ingress: packet from {from} refused: {error} \
             (further '{}' packets are counted on the status topic, not logged)",
            error.kind()
        );
    }
}
