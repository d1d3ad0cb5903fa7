//! The ingress node: Rokoko Studio's UDP stream in, the lab's ROS 2 topics out.
//!
//! One datagram is one frame. A frame is published only when a packet arrives and is new
//! (see [`super::ingress_counters`]): no timer republishes stale data. Keypoints go out as
//! `std_msgs/Float32MultiArray` (N × 3, metres, ROS frame) and the hand bone's pose as
//! `geometry_msgs/PoseStamped`, stamped with this computer's clock at receipt. The socket is
//! bound to the configured address only (127.0.0.1 by default); with `allowed_senders`, a
//! datagram from anyone else is dropped and counted (`refused.sender`). A bad packet is
//! counted under its kind and logged at most once per kind every 10 s (with the count of
//! lines held back); nothing about a packet stops the node. Once a second the counts go out
//! as JSON on the status topic.

use std::net::SocketAddr;
use std::time::Duration;

use msgs::{Float32MultiArray, PoseStamped, StringMsg};
use ros2_client::Publisher;
use tokio::net::UdpSocket;
use tokio::sync::{oneshot, watch};

use crate::clock::StationClock;
use crate::ingress::error::IngressError;
use crate::ingress::ingress_config::{AllowedSender, IngressConfig};
use crate::ingress::ingress_counters::{IngressCounters, Order, OrderRule, SourceInfo};
use crate::ingress::log_limit::{LogLimiter, held_back};
use crate::ingress::rokoko_packet::{Selection, parse_packet};
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
    let senders = config.senders()?;
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
    if senders.is_empty() && !local.ip().is_loopback() {
        eprintln!(
            "warning: rokoko ingress: listening on UDP {local} with no allowed_senders: any host \
             that reaches this port can move the robot hand; name Studio's address in \
             allowed_senders (docs/SECURITY.md)"
        );
    }
    // One byte more than the limit, so an oversized datagram shows as such.
    let mut buffer = vec![0u8; config.max_packet_bytes + 1];
    let source = rokoko_source(&config, local);
    let mut stream = Stream {
        config: &config,
        senders,
        publishers,
        counters: IngressCounters::default(),
        log: LogLimiter::default(),
    };
    stream.counters.status(clock.now_ns(), &source);
    let mut ticks = 0u64;
    let mut status_tick = tokio::time::interval(STATUS_PERIOD);
    status_tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
    loop {
        tokio::select! {
            _ = shutdown.changed() => if *shutdown.borrow() { break },
            _ = status_tick.tick() => {
                let status = stream.counters.status(clock.now_ns(), &source);
                ticks += 1;
                if print_status && ticks.is_multiple_of(PRINT_EVERY) {
                    eprintln!("{}", status_line(&status));
                }
                stream.status(status.to_string()).await;
            }
            received = socket.recv_from(&mut buffer) => {
                let now = clock.now_ns();
                match received {
                    Ok((n, from)) => stream.datagram(&buffer[..n], from, now).await?,
                    // e.g. ICMP port-unreachable echoes on some systems: not fatal.
                    Err(e) => stream.refuse("socket_error", now, || format!("receive error: {e}")),
                }
            }
        }
    }
    let status = stream.counters.status(clock.now_ns(), &source);
    stream.status(status.to_string()).await;
    Ok(stream.counters)
}

/// The stream's state between datagrams.
struct Stream<'c> {
    config: &'c IngressConfig,
    senders: Vec<AllowedSender>,
    publishers: Publishers,
    counters: IngressCounters,
    log: LogLimiter,
}

impl Stream<'_> {
    /// Publish the status report.
    async fn status(&mut self, status: String) {
        self.publishers
            .status(self.config, &mut self.counters, status)
            .await;
    }

    /// Count a refused datagram under `kind`; log it unless a line of that kind went out in
    /// the last [`LOG_PERIOD_S`](crate::ingress::log_limit::LOG_PERIOD_S) seconds.
    fn refuse(&mut self, kind: &'static str, now_ns: i64, what: impl FnOnce() -> String) {
        self.counters.refused(kind);
        if let Some(held) = self.log.allow(kind, now_ns) {
            eprintln!(
                "warning: rokoko ingress: {} (counted as refused.{kind} on the status topic){}",
                what(),
                held_back(held)
            );
        }
    }

    /// One datagram from `from`: checked (sender, packet, order), then published.
    async fn datagram(
        &mut self,
        bytes: &[u8],
        from: SocketAddr,
        now: i64,
    ) -> Result<(), IngressError> {
        self.counters.received(now);
        if !self.senders.is_empty() && !self.senders.iter().any(|s| s.matches(from)) {
            self.refuse("sender", now, || {
                format!("datagram from {from} dropped: not in allowed_senders")
            });
            return Ok(());
        }
        let selection = Selection {
            actor: self.config.actor.as_deref(),
            hand: self.config.hand,
            layout: self.config.layout,
            max_packet_bytes: self.config.max_packet_bytes,
            position_scale_to_m: self.config.position_scale_to_m,
        };
        let frame = match parse_packet(bytes, &selection) {
            Ok(frame) => frame,
            Err(e) => {
                self.refuse(e.kind(), now, || format!("packet from {from} refused: {e}"));
                return Ok(());
            }
        };
        let rule = OrderRule {
            restart_after_s: self.config.restart_after_backwards_s,
            confirm_packets: self.config.restart_confirm_packets,
        };
        match self.counters.order(frame.timestamp_s, rule) {
            Order::Duplicate | Order::OutOfOrder => return Ok(()),
            Order::RestartUnconfirmed => {
                if let Some(held) = self.log.allow("restart_unconfirmed", now) {
                    eprintln!(
                        "note: rokoko ingress: packet from {from} stamped {:.3} s, far before the \
                         stream's newest: dropped unless {} such packets in a row confirm a \
                         restart{}",
                        frame.timestamp_s,
                        self.config.restart_confirm_packets,
                        held_back(held)
                    );
                }
                return Ok(());
            }
            Order::Restart => {
                if let Some(held) = self.log.allow("restart", now) {
                    eprintln!(
                        "note: rokoko ingress: the studio timestamp went back to {:.3} s: stream \
                         restarted{}",
                        frame.timestamp_s,
                        held_back(held)
                    );
                }
            }
            Order::New => {}
        }
        let rows: Vec<[f32; 3]> = frame
            .keypoints
            .iter()
            .map(|p| [p.x as f32, p.y as f32, p.z as f32])
            .collect();
        let array = Float32MultiArray::from_points(&rows)?;
        let pose = PoseStamped {
            header: header(now, &self.config.wrist_frame_id),
            pose: isometry_to_pose(&frame.wrist),
        };
        self.publishers
            .frame(self.config, &mut self.counters, array, pose)
            .await;
        Ok(())
    }
}

/// The source as the status names it.
pub fn rokoko_source(config: &IngressConfig, local: SocketAddr) -> SourceInfo {
    SourceInfo {
        kind: "rokoko",
        device: format!(
            "Rokoko Studio Live on UDP {local} from {}, actor {}",
            if config.allowed_senders.is_empty() {
                "any sender".to_string()
            } else {
                config.allowed_senders.join(", ")
            },
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
