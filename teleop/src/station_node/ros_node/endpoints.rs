//! The node's endpoints on DDS: opening its publishers and subscriptions (the commands on the
//! relay's wire topics when a relay carries them, the keypoints in their configured format,
//! the ROS tools' endpoints), the select loop's input streams and timers, the commands'
//! listeners for the status, and whether another publisher contests the arm's topic.

use std::time::Duration;

use futures::{StreamExt, stream::BoxStream};
use msgs::{Float32MultiArray, JointState, PoseArray, PoseStamped, StringMsg};
use ros2_client::{MessageInfo, Publisher, Subscription};
use serde_json::json;
use station::convert::KeypointMessage;
use station::{KeypointFormat, StationConfig};

use crate::ros::{QosConfig, RosNode};
use crate::station_driver::tick_period;
use crate::station_node::error::NodeError;
use crate::station_node::relay_view::RelayView;
use crate::station_node::ros_tools_node::{ServiceRequest, ToolEndpoints};

/// The node's publishers and subscriptions, and the node last (fields drop in order: the
/// endpoints before their node, `ros::teardown`).
pub(super) struct Endpoints {
    /// The hand command publisher; `None` in a human study (no robot, nothing commanded).
    pub(super) joint: Option<Publisher<JointState>>,
    pub(super) policy: Option<Publisher<Float32MultiArray>>,
    pub(super) arm: Option<Publisher<PoseStamped>>,
    /// The station's own subscription to the arm command topic: counts its publishers.
    arm_monitor: Option<Subscription<PoseStamped>>,
    pub(super) status: Publisher<StringMsg>,
    keypoints: KeypointSubscription,
    wrist: Subscription<PoseStamped>,
    feedback: Subscription<PoseStamped>,
    /// The ingress's status (for the keypoint source), when configured.
    ingress_status: Option<Subscription<StringMsg>>,
    /// `pomdar relay`'s status, when the commands go through one.
    pub(super) relay_status: Option<Subscription<StringMsg>>,
    /// `/tf`, markers, diagnostics, the hand's state, the services.
    pub(super) tools: ToolEndpoints,
    node: RosNode,
}

/// The keypoint subscription, in the configured format.
enum KeypointSubscription {
    Array(Subscription<Float32MultiArray>),
    Poses(Subscription<PoseArray>),
}

pub(super) type Received<M> = ros2_client::ReadResult<(M, MessageInfo)>;

/// The node's input streams and timers.
pub(super) struct Streams<'a> {
    pub(super) keypoints: BoxStream<'a, Received<KeypointMessage>>,
    pub(super) wrist: BoxStream<'a, Received<PoseStamped>>,
    pub(super) feedback: BoxStream<'a, Received<PoseStamped>>,
    pub(super) hand_state: BoxStream<'a, Received<JointState>>,
    pub(super) ingress_status: BoxStream<'a, Received<StringMsg>>,
    pub(super) services: BoxStream<'a, ServiceRequest>,
    pub(super) tick: tokio::time::Interval,
    pub(super) status_tick: tokio::time::Interval,
}

impl Endpoints {
    pub(super) fn open(
        config: &StationConfig,
        has_description: bool,
    ) -> Result<Endpoints, NodeError> {
        let mut node = RosNode::join(&config.network, "/", "pomdar_station")?;
        let (input_qos, output_qos) = (config.input.qos, config.output.qos);
        let topic = &config.input.keypoints_topic;
        let keypoints = match config.input.keypoints_format {
            KeypointFormat::Float32MultiArray => {
                KeypointSubscription::Array(node.subscription(topic, input_qos)?)
            }
            KeypointFormat::PoseArray => {
                KeypointSubscription::Poses(node.subscription(topic, input_qos)?)
            }
        };
        let robot = config.drives_robot();
        // Relayed (`[robot_link]`): best effort on the relay topics, `pomdar relay` on the
        // robot's computer republishes; nothing old is kept or resent after a cut.
        let link = &config.robot_link;
        let command_qos = link.command_qos(output_qos);
        let arm_topic = &config.output.arm_target_topic;
        let (arm, arm_monitor) = if arm_topic.is_empty() || !robot {
            (None, None)
        } else {
            let wire = link.wire_topic(arm_topic);
            (
                Some(node.publisher(&wire, command_qos)?),
                Some(node.subscription(&wire, command_qos)?),
            )
        };
        let policy = match config.policy_output.topic.as_str() {
            "" => None,
            _ if !robot => None,
            topic => Some(node.publisher(&link.wire_topic(topic), command_qos)?),
        };
        let joint = match robot {
            true => Some(node.publisher(
                &link.wire_topic(&config.output.joint_targets_topic),
                command_qos,
            )?),
            false => None,
        };
        Ok(Endpoints {
            joint,
            policy,
            arm,
            arm_monitor,
            status: node.publisher(&config.output.status_topic, QosConfig::reliable(10))?,
            keypoints,
            wrist: node.subscription(&config.input.wrist_topic, input_qos)?,
            feedback: node
                .subscription(&config.input.arm_feedback_topic, QosConfig::best_effort(10))?,
            ingress_status: match config.input.ingress_status_topic.as_str() {
                "" => None,
                topic => Some(node.subscription(topic, QosConfig::reliable(10))?),
            },
            relay_status: match link.relayed() && robot {
                true => {
                    Some(node.subscription(&link.relay_status_topic(), QosConfig::best_effort(10))?)
                }
                false => None,
            },
            tools: ToolEndpoints::open(&mut node, config, has_description)?,
            node,
        })
    }

    pub(super) fn streams(&self, config: &StationConfig) -> Streams<'_> {
        let keypoints = match &self.keypoints {
            KeypointSubscription::Array(sub) => sub
                .async_stream()
                .map(|r| r.map(|(m, info)| (KeypointMessage::Array(m), info)))
                .boxed(),
            KeypointSubscription::Poses(sub) => sub
                .async_stream()
                .map(|r| r.map(|(m, info)| (KeypointMessage::Poses(m), info)))
                .boxed(),
        };
        let mut tick = tokio::time::interval(tick_period(config.control.rate_hz));
        tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
        Streams {
            keypoints,
            wrist: self.wrist.async_stream().boxed(),
            feedback: self.feedback.async_stream().boxed(),
            hand_state: match &self.tools.hand_state {
                Some(sub) => sub.async_stream().boxed(),
                None => futures::stream::pending().boxed(),
            },
            ingress_status: match &self.ingress_status {
                Some(sub) => sub.async_stream().boxed(),
                None => futures::stream::pending().boxed(),
            },
            services: self.tools.service_requests(),
            tick,
            status_tick: tokio::time::interval(Duration::from_secs_f64(
                1.0 / config.output.status_rate_hz,
            )),
        }
    }

    /// Matched readers of the commands (the station's own arm monitor is one of the arm's);
    /// behind a relay, the robot's readers as the relay last reported them
    /// ([`RelayView::listeners`]), and the `relay` object.
    pub(super) fn listeners(
        &self,
        config: &StationConfig,
        relay: &RelayView,
        now: i64,
    ) -> serde_json::Value {
        let node = &self.node;
        let hand = self.joint.as_ref().map(|p| node.matched_subscriptions(p));
        let arm = (self.arm.as_ref()).map(|p| node.matched_subscriptions(p).saturating_sub(1));
        if self.relay_status.is_none() {
            return json!({ "hand": hand, "arm": arm });
        }
        let output = &config.output;
        let behind = |readers: Option<usize>, topic: &str| {
            readers.and_then(|n| relay.listeners(n, topic, now))
        };
        json!({
            "hand": behind(hand, &output.joint_targets_topic),
            "arm": behind(arm, &output.arm_target_topic),
            "relay": relay.document(hand.or(arm), now),
        })
    }

    /// Whether another publisher drives the arm command topic.
    pub(super) fn arm_topic_contested(&self) -> bool {
        self.arm_monitor
            .as_ref()
            .is_some_and(|m| self.node.matched_publishers(m) > 1)
    }
}

/// The sender's stamp of a sample, else its receive time.
pub(super) fn source_or(info: &MessageInfo, received_ns: i64) -> i64 {
    info.source_timestamp()
        .map_or(received_ns, |t| t.to_nanos())
}
