//! `pomdar replay`: republish a log's recorded topics over ROS 2 with their original timing
//! (mock topics), so the station or any ROS node runs as if live.
//!
//! Messages go out in log-time order, each at `start + (log_time − first_log_time) / rate` on
//! the replay's clock. Topics of the types the station knows are republished
//! (`Float32MultiArray`, `PoseStamped`, `PoseArray`, `JointState`, `String`); others are
//! reported and skipped.

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use msgs::{Float32MultiArray, JointState, PoseArray, PoseStamped, RosMessage, StringMsg};
use ros2_client::Publisher;
use serde::Serialize;
use tokio::sync::watch;

use crate::mcap_log::{LogError, LoggedMessage, TrialReader};
use crate::ros::{NetworkConfig, QosConfig, RosError, RosNode};

/// A replay that cannot start, or a message that cannot be republished.
#[derive(Debug, thiserror::Error)]
pub enum ReplayError {
    /// The speed factor is not a positive number.
    #[error("--rate must be a positive number, got {rate}")]
    Rate {
        /// The factor given.
        rate: f64,
    },
    /// A topic asked for is not in the log, or is of a type the replay does not know.
    #[error("topic {topic} is not in the log or has an unsupported type")]
    Topic {
        /// The topic asked for.
        topic: String,
    },
    /// Joining the DDS domain, or creating the node or a publisher, failed.
    #[error(transparent)]
    Ros(#[from] RosError),
    /// A recorded message does not decode as its channel's type.
    #[error(transparent)]
    Log(#[from] LogError),
    /// The DDS writer refused a message.
    #[error("publish on {topic}: {reason:?}")]
    Publish {
        /// The topic.
        topic: String,
        /// The writer's error (its debug form: RustDDS's errors carry the message).
        reason: String,
    },
}

/// Replay settings.
#[derive(Debug, Clone, PartialEq)]
pub struct ReplayOptions {
    /// Speed factor (1 = original timing, 2 = twice as fast).
    pub rate: f64,
    /// Topics to republish; empty = every topic of a known type.
    pub topics: Vec<String>,
    /// Start again from the beginning after the last message.
    pub looped: bool,
    /// QoS of the republished topics.
    pub qos: QosConfig,
    /// Wait up to this long for a subscriber to each topic before starting.
    pub wait_for_subscribers: Duration,
}

impl Default for ReplayOptions {
    fn default() -> Self {
        ReplayOptions {
            rate: 1.0,
            topics: Vec::new(),
            looped: false,
            qos: QosConfig::reliable(1000),
            wait_for_subscribers: Duration::from_secs(5),
        }
    }
}

/// What a replay sent.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct ReplayReport {
    /// Messages published, by topic.
    pub published: BTreeMap<String, u64>,
    /// Topics skipped (unknown type or not selected), with their type.
    pub skipped: BTreeMap<String, String>,
    /// Passes over the log.
    pub passes: u64,
}

enum AnyPublisher {
    Array(Publisher<Float32MultiArray>),
    Pose(Publisher<PoseStamped>),
    PoseArray(Publisher<PoseArray>),
    Joints(Publisher<JointState>),
    Text(Publisher<StringMsg>),
}

impl AnyPublisher {
    fn create(
        node: &mut RosNode,
        topic: &str,
        type_name: &str,
        qos: QosConfig,
    ) -> Result<Option<AnyPublisher>, ReplayError> {
        let is = |d: &msgs::MsgDefinition| {
            type_name == d.ros_type_name() || type_name == d.resource_name()
        };
        Ok(Some(if is(&Float32MultiArray::DEFINITION) {
            AnyPublisher::Array(node.publisher(topic, qos)?)
        } else if is(&PoseStamped::DEFINITION) {
            AnyPublisher::Pose(node.publisher(topic, qos)?)
        } else if is(&PoseArray::DEFINITION) {
            AnyPublisher::PoseArray(node.publisher(topic, qos)?)
        } else if is(&JointState::DEFINITION) {
            AnyPublisher::Joints(node.publisher(topic, qos)?)
        } else if is(&StringMsg::DEFINITION) {
            AnyPublisher::Text(node.publisher(topic, qos)?)
        } else {
            return Ok(None);
        }))
    }

    fn subscribers(&self, node: &RosNode) -> usize {
        match self {
            AnyPublisher::Array(p) => node.matched_subscriptions(p),
            AnyPublisher::Pose(p) => node.matched_subscriptions(p),
            AnyPublisher::PoseArray(p) => node.matched_subscriptions(p),
            AnyPublisher::Joints(p) => node.matched_subscriptions(p),
            AnyPublisher::Text(p) => node.matched_subscriptions(p),
        }
    }

    async fn publish(&self, message: &LoggedMessage) -> Result<(), ReplayError> {
        let failed = |reason| ReplayError::Publish {
            topic: message.topic.clone(),
            reason,
        };
        match self {
            AnyPublisher::Array(p) => p
                .async_publish(message.decode()?)
                .await
                .map_err(|e| failed(format!("{e:?}"))),
            AnyPublisher::Pose(p) => p
                .async_publish(message.decode()?)
                .await
                .map_err(|e| failed(format!("{e:?}"))),
            AnyPublisher::PoseArray(p) => p
                .async_publish(message.decode()?)
                .await
                .map_err(|e| failed(format!("{e:?}"))),
            AnyPublisher::Joints(p) => p
                .async_publish(message.decode()?)
                .await
                .map_err(|e| failed(format!("{e:?}"))),
            AnyPublisher::Text(p) => p
                .async_publish(message.decode()?)
                .await
                .map_err(|e| failed(format!("{e:?}"))),
        }
    }
}

/// Replay `reader` on `network` until done (or `shutdown`).
pub async fn replay(
    reader: &TrialReader,
    network: &NetworkConfig,
    options: &ReplayOptions,
    mut shutdown: watch::Receiver<bool>,
) -> Result<ReplayReport, ReplayError> {
    if !(options.rate > 0.0 && options.rate.is_finite()) {
        return Err(ReplayError::Rate { rate: options.rate });
    }
    let mut node = RosNode::join(network, "/", "pomdar_replay")?;
    let mut report = ReplayReport::default();
    let mut publishers: BTreeMap<String, AnyPublisher> = BTreeMap::new();
    for topic in reader.topics() {
        let selected = options.topics.is_empty() || options.topics.contains(&topic.topic);
        match selected
            .then(|| AnyPublisher::create(&mut node, &topic.topic, &topic.type_name, options.qos))
            .transpose()?
            .flatten()
        {
            Some(p) => {
                publishers.insert(topic.topic.clone(), p);
            }
            None => {
                report
                    .skipped
                    .insert(topic.topic.clone(), topic.type_name.clone());
            }
        }
    }
    if let Some(wanted) = options
        .topics
        .iter()
        .find(|wanted| !publishers.contains_key(*wanted))
    {
        return Err(ReplayError::Topic {
            topic: wanted.clone(),
        });
    }
    let waiting = Instant::now();
    while publishers.values().any(|p| p.subscribers(&node) == 0)
        && waiting.elapsed() < options.wait_for_subscribers
    {
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
    let mut messages: Vec<&LoggedMessage> = reader
        .messages()
        .filter(|m| publishers.contains_key(&m.topic))
        .collect();
    messages.sort_by_key(|m| m.log_time_ns);
    let Some(first) = messages.first().map(|m| m.log_time_ns) else {
        return Ok(report);
    };
    loop {
        let start = Instant::now();
        for message in &messages {
            let due =
                Duration::from_secs_f64((message.log_time_ns - first) as f64 * 1e-9 / options.rate);
            if let Some(wait) = due.checked_sub(start.elapsed()) {
                tokio::select! {
                    _ = shutdown.changed() => if *shutdown.borrow() { return Ok(report) },
                    _ = tokio::time::sleep(wait) => {}
                }
            }
            if let Some(publisher) = publishers.get(&message.topic) {
                publisher.publish(message).await?;
                *report.published.entry(message.topic.clone()).or_default() += 1;
            }
        }
        report.passes += 1;
        if *shutdown.borrow() {
            return Ok(report);
        }
        if !options.looped {
            // The participant's event loop sends what was published on its own thread;
            // dropping it at once lost the last frames of a replay on a loaded machine.
            tokio::select! {
                _ = shutdown.changed() => {}
                _ = tokio::time::sleep(SEND_LINGER) => {}
            }
            return Ok(report);
        }
    }
}

/// How long the replay's participant stays up after its last message, so that the samples
/// still queued in its event loop are sent.
const SEND_LINGER: Duration = Duration::from_millis(300);
