//! The Apple Vision Pro ingress node: the headset's gRPC stream in, the lab's ROS 2 topics out.
//!
//! A link task connects to the headset (`connect_timeout_s` per attempt), sends the discovery
//! request ([`super::avp_proto::discovery_request`]) and forwards each streamed message, stamped
//! at receipt with this computer's clock, to the node loop. When the stream ends or fails, or an
//! attempt fails, the link waits `reconnect_min_s`, doubling per failed attempt up to
//! `reconnect_max_s`, and tries again; the first message of a new stream resets the wait. The
//! node loop converts each update ([`super::avp_frame`]) and publishes a frame only when an
//! update arrives and differs from the last one published (an identical update is counted as a
//! duplicate). An update that is not hand data is counted under its kind and logged the first
//! time; nothing the headset sends stops the node. Once a second the counts, the connection
//! state and the source go out as JSON on the status topic.

use std::net::{IpAddr, Ipv4Addr};
use std::time::Duration;

use msgs::{Float32MultiArray, PoseStamped, StringMsg};
use ros2_client::Publisher;
use tokio::sync::{mpsc, watch};
use tonic::transport::{Channel, Endpoint};

use crate::clock::StationClock;
use crate::ingress::avp_config::AvpConfig;
use crate::ingress::avp_frame::{UpdateError, convert_update};
use crate::ingress::avp_proto::{
    Decoded, Hand as AvpHand, HandUpdate, HandUpdateCodec, discovery_request, stream_path,
};
use crate::ingress::error::IngressError;
use crate::ingress::ingress_config::Hand;
use crate::ingress::ingress_counters::{IngressCounters, SourceInfo};
use crate::ingress::rokoko_node::status_line;
use crate::ros::{QosConfig, RosNode};
use station::convert::{header, isometry_to_pose};

/// How often the status goes out.
const STATUS_PERIOD: Duration = Duration::from_secs(1);

/// Print a status line on stderr every this many status periods (with `print_status`).
const PRINT_EVERY: u64 = 5;

/// Updates the link may hold for the node loop before it stops reading the stream.
const LINK_QUEUE: usize = 64;

/// What the link task reports.
#[derive(Debug)]
enum LinkEvent {
    /// A stream is open (the `n`th connection since start, from 1).
    Connected(u64),
    /// An attempt failed, or the open stream ended; the link waits `retry_in` and tries again.
    Lost {
        reason: String,
        retry_in: Duration,
        was_connected: bool,
    },
    /// A streamed message and its receive time.
    Message(Box<Decoded>, i64),
}

/// The node's publishers.
struct Publishers {
    keypoints: Publisher<Float32MultiArray>,
    wrist: Publisher<PoseStamped>,
    status: Publisher<StringMsg>,
}

/// The node loop's state.
struct AvpIngress {
    config: AvpConfig,
    source: SourceInfo,
    counters: IngressCounters,
    publishers: Publishers,
    /// The last hand published, to tell a repeated update.
    last_hand: Option<AvpHand>,
    /// Whether the operator was told the headset cannot be reached yet.
    waiting_reported: bool,
}

/// The source as the status names it.
pub fn avp_source(config: &AvpConfig) -> SourceInfo {
    SourceInfo {
        kind: "avp",
        device: config.device(),
    }
}

/// Run the ingress until `shutdown`; with `print_status` a one-line status goes to stderr every
/// 5 s and connection changes are reported there. Returns the final counts.
pub async fn run_avp_ingress(
    config: AvpConfig,
    clock: StationClock,
    mut shutdown: watch::Receiver<bool>,
    print_status: bool,
) -> Result<IngressCounters, IngressError> {
    config.validate()?;
    let mut node = RosNode::join(&config.network, "/", "pomdar_avp_ingress")?;
    let publishers = Publishers {
        keypoints: node.publisher(&config.keypoints_topic, config.qos)?,
        wrist: node.publisher(&config.wrist_topic, config.qos)?,
        status: node.publisher(&config.status_topic, QosConfig::reliable(10))?,
    };
    let (tx, mut events) = mpsc::channel(LINK_QUEUE);
    let link = tokio::spawn(run_link(config.clone(), clock, tx));
    let mut counters = IngressCounters::default();
    counters.connected = Some(false);
    let mut ingress = AvpIngress {
        source: avp_source(&config),
        config,
        counters,
        publishers,
        last_hand: None,
        waiting_reported: false,
    };
    ingress.counters.status(clock.now_ns(), &ingress.source);
    let mut ticks = 0u64;
    let mut status_tick = tokio::time::interval(STATUS_PERIOD);
    status_tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
    loop {
        tokio::select! {
            _ = shutdown.changed() => if *shutdown.borrow() { break },
            _ = status_tick.tick() => {
                ticks += 1;
                let print = print_status && ticks.is_multiple_of(PRINT_EVERY);
                ingress.publish_status(clock.now_ns(), print).await;
            }
            Some(event) = events.recv() => ingress.on_link(event, print_status).await,
        }
    }
    link.abort();
    ingress.publish_status(clock.now_ns(), false).await;
    Ok(ingress.counters)
}

impl AvpIngress {
    async fn on_link(&mut self, event: LinkEvent, print: bool) {
        match event {
            LinkEvent::Connected(n) => {
                self.counters.connected = Some(true);
                self.counters.reconnects = n.saturating_sub(1);
                if print {
                    let again = if n > 1 { " again" } else { "" };
                    eprintln!(
                        "note: avp ingress: streaming from {}{again}",
                        self.source.device
                    );
                }
            }
            LinkEvent::Lost {
                reason,
                retry_in,
                was_connected,
            } => {
                self.counters.connected = Some(false);
                if print && !was_connected && !self.waiting_reported {
                    self.waiting_reported = true;
                    eprintln!(
                        "note: avp ingress: waiting for the headset at {} ({reason}); \
                         retrying every {:.2}–{:.1} s (is the app started, on this network?)",
                        self.source.device,
                        retry_in.as_secs_f64(),
                        self.config.reconnect_max_s
                    );
                }
                if print && was_connected {
                    eprintln!(
                        "warning: avp ingress: the stream from {} ended ({reason}); \
                         reconnecting every {:.2}–{:.1} s",
                        self.source.device,
                        retry_in.as_secs_f64(),
                        self.config.reconnect_max_s
                    );
                }
            }
            LinkEvent::Message(decoded, received_ns) => {
                self.counters.received(received_ns);
                let update = match *decoded {
                    Ok(update) => update,
                    Err(e) => {
                        let reason = e.to_string();
                        self.refuse(&UpdateError::Undecodable { reason });
                        return;
                    }
                };
                self.on_update(&update, received_ns).await;
            }
        }
    }

    async fn on_update(&mut self, update: &HandUpdate, received_ns: i64) {
        let frame = match convert_update(update, self.config.hand, self.config.layout) {
            Ok(frame) => frame,
            Err(e) => {
                self.refuse(&e);
                return;
            }
        };
        let hand = match self.config.hand {
            Hand::Right => update.right_hand.clone(),
            Hand::Left => update.left_hand.clone(),
        };
        if hand == self.last_hand {
            self.counters.duplicates += 1;
            return;
        }
        self.last_hand = hand;
        let rows: Vec<[f32; 3]> = frame
            .keypoints
            .iter()
            .map(|p| [p.x as f32, p.y as f32, p.z as f32])
            .collect();
        let Ok(array) = Float32MultiArray::from_points(&rows) else {
            self.refuse(&UpdateError::JointCount { count: rows.len() });
            return;
        };
        let pose = PoseStamped {
            header: header(received_ns, &self.config.wrist_frame_id),
            pose: isometry_to_pose(&frame.wrist),
        };
        let keypoints_sent = self.publishers.keypoints.async_publish(array).await.is_ok();
        let wrist_sent = self.publishers.wrist.async_publish(pose).await.is_ok();
        self.counters.frame_sent(
            (&self.config.keypoints_topic, keypoints_sent),
            (&self.config.wrist_topic, wrist_sent),
        );
    }

    fn refuse(&mut self, error: &UpdateError) {
        if self.counters.refused(error.kind()) {
            eprintln!(
                "warning: avp ingress: update from {} refused: {error} \
                 (further '{}' updates are counted on the status topic, not logged)",
                self.source.device,
                error.kind()
            );
        }
    }

    async fn publish_status(&mut self, now_ns: i64, print: bool) {
        let status = self.counters.status(now_ns, &self.source);
        if print {
            eprintln!("{}", status_line(&status));
        }
        let message = StringMsg {
            data: status.to_string(),
        };
        if self.publishers.status.async_publish(message).await.is_err() {
            self.counters.publish_failed(&self.config.status_topic);
        }
    }
}

/// Connect, stream, and reconnect with backoff, forever (the node aborts it).
async fn run_link(config: AvpConfig, clock: StationClock, events: mpsc::Sender<LinkEvent>) {
    let min = Duration::from_secs_f64(config.reconnect_min_s);
    let max = Duration::from_secs_f64(config.reconnect_max_s);
    let mut wait = min;
    let mut connections = 0u64;
    loop {
        let (reason, was_connected) = match open_stream(&config).await {
            Err(reason) => (reason, false),
            Ok(mut stream) => {
                connections += 1;
                if events
                    .send(LinkEvent::Connected(connections))
                    .await
                    .is_err()
                {
                    return;
                }
                wait = min;
                let reason = loop {
                    match stream.message().await {
                        Ok(Some(decoded)) => {
                            let event = LinkEvent::Message(Box::new(decoded), clock.now_ns());
                            if events.send(event).await.is_err() {
                                return;
                            }
                        }
                        Ok(None) => break "the headset closed it".to_string(),
                        Err(status) => break describe(&status),
                    }
                };
                (reason, true)
            }
        };
        let lost = LinkEvent::Lost {
            reason,
            retry_in: wait,
            was_connected,
        };
        if events.send(lost).await.is_err() {
            return;
        }
        tokio::time::sleep(wait).await;
        wait = (wait * 2).min(max);
    }
}

/// One connection: the channel, the discovery request, the response stream.
async fn open_stream(config: &AvpConfig) -> Result<tonic::Streaming<Decoded>, String> {
    let endpoint = Endpoint::from_shared(config.uri())
        .map_err(|e| format!("bad address {}: {e}", config.uri()))?
        .connect_timeout(config.connect_timeout())
        .tcp_nodelay(true);
    let channel: Channel = tokio::time::timeout(config.connect_timeout(), endpoint.connect())
        .await
        .map_err(|_| "no answer within the connect timeout".to_string())?
        .map_err(|e| format!("cannot connect: {}", error_chain(&e)))?;
    let mut client =
        tonic::client::Grpc::new(channel).max_decoding_message_size(config.max_message_bytes);
    client
        .ready()
        .await
        .map_err(|e| format!("not ready: {}", error_chain(&e)))?;
    let request = discovery_request(local_ipv4(config).await);
    let response = client
        .server_streaming(tonic::Request::new(request), stream_path(), HandUpdateCodec)
        .await
        .map_err(|status| describe(&status))?;
    Ok(response.into_inner())
}

/// The address this computer reaches the headset from (announced in the discovery request);
/// 0.0.0.0 when it cannot be told (an IPv6 headset, no route).
async fn local_ipv4(config: &AvpConfig) -> Ipv4Addr {
    let probe = async {
        let socket = tokio::net::UdpSocket::bind((Ipv4Addr::UNSPECIFIED, 0))
            .await
            .ok()?;
        // A UDP connect sends nothing: it only picks the route and so the local address.
        socket
            .connect((config.address.as_str(), config.port))
            .await
            .ok()?;
        match socket.local_addr().ok()?.ip() {
            IpAddr::V4(ip) => Some(ip),
            IpAddr::V6(_) => None,
        }
    };
    probe.await.unwrap_or(Ipv4Addr::UNSPECIFIED)
}

/// A gRPC status for a person.
fn describe(status: &tonic::Status) -> String {
    format!("{:?}: {}", status.code(), status.message())
}

/// An error and its causes on one line.
fn error_chain(error: &dyn std::error::Error) -> String {
    let mut text = error.to_string();
    let mut source = error.source();
    while let Some(cause) = source {
        text.push_str(": ");
        text.push_str(&cause.to_string());
        source = cause.source();
    }
    text
}
