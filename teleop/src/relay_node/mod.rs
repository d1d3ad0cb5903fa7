//! `pomdar relay`'s node, on the robot's computer: the station's commands from the relay
//! topics (best effort across the lab network: a cut link loses what was sent into it, and
//! nothing is resent) onto the robot's own topics (with `output.qos`, the reliability the
//! robot's drivers ask for, over this computer's loopback), each command older than
//! `[robot_link] max_age_ms` on arrival dropped ([`station::robot_link`]).
//!
//! The ages are judged on this computer's wall clock as it is at each arrival
//! ([`WallClock`]), and the smallest age per window estimates how far the two clocks are
//! apart ([`station::link_clock`]): the relay says so when it eats into the limit. Twice a
//! second it publishes [`RelayStatus`](station::link_clock::RelayStatus) for the station: the robot side's readers and that
//! offset.

mod legs;
mod status;

use std::collections::BTreeMap;
use std::sync::Mutex;

use msgs::{Float32MultiArray, JointState, PoseStamped};
use serde::Serialize;
use station::StationConfig;
use station::link_clock::ClockOffsetMonitor;
use station::robot_link::AgeCounts;
use tokio::sync::watch;

use crate::clock::WallClock;
use crate::ros::{NetworkConfig, QosConfig, RosError, RosNode};
use legs::{LegContext, open_leg, relay_leg};

/// One relayed topic: from the station's relay topic to the robot's.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RelayRoute {
    /// The relay topic the station publishes on.
    pub from: String,
    /// The robot's topic.
    pub to: String,
}

/// The routes of a configuration: joint targets, policy output and arm target, those it has.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct RelayRoutes {
    /// The hand's joint targets (`sensor_msgs/JointState`).
    pub joint_targets: Option<RelayRoute>,
    /// The lab's policy output (`std_msgs/Float32MultiArray`).
    pub policy_output: Option<RelayRoute>,
    /// The arm target (`geometry_msgs/PoseStamped`).
    pub arm_target: Option<RelayRoute>,
}

impl RelayRoutes {
    /// The routes of `config`; None when it relays nothing (`robot_link.relay_prefix` empty).
    pub fn of(config: &StationConfig) -> Option<RelayRoutes> {
        let link = &config.robot_link;
        if !link.relayed() || !config.drives_robot() {
            return None;
        }
        let route = |topic: &str| {
            (!topic.is_empty()).then(|| RelayRoute {
                from: link.wire_topic(topic),
                to: topic.to_string(),
            })
        };
        Some(RelayRoutes {
            joint_targets: route(&config.output.joint_targets_topic),
            policy_output: route(&config.policy_output.topic),
            arm_target: route(&config.output.arm_target_topic),
        })
    }

    /// Every route, in order.
    pub fn all(&self) -> Vec<&RelayRoute> {
        [&self.joint_targets, &self.policy_output, &self.arm_target]
            .into_iter()
            .flatten()
            .collect()
    }
}

/// What the relay did on one topic.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize)]
pub struct TopicRelayReport {
    /// The age gate's decisions.
    pub ages: AgeCounts,
    /// Samples the subscription could not deliver (undecodable, lost in DDS).
    pub input_errors: u64,
    /// Forwarded commands the robot-side writer refused.
    pub publish_failed: u64,
    /// The robot side's readers of this topic (its drivers), at the last status.
    pub robot_listeners: u64,
}

/// What the relay did, by the robot's topic.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct RelayReport {
    /// Per robot topic.
    pub topics: BTreeMap<String, TopicRelayReport>,
    /// The last estimate of the clock offset (this computer's clock minus the station's),
    /// milliseconds.
    pub clock_offset_ms: Option<f64>,
}

/// The relay's fixed settings.
#[derive(Debug, Clone)]
pub struct RelaySettings {
    /// The routes.
    pub routes: RelayRoutes,
    /// The QoS of the relay topics' subscriptions (best effort).
    pub link_qos: QosConfig,
    /// The QoS of the robot topics' publishers (the configuration's `output.qos`).
    pub robot_qos: QosConfig,
    /// Older commands are dropped, milliseconds.
    pub max_age_ms: u64,
    /// Where the relay's status goes (best effort), for the station.
    pub status_topic: String,
}

impl RelaySettings {
    /// The settings of a configuration that relays (see [`RelayRoutes::of`]).
    pub fn of(config: &StationConfig) -> Option<RelaySettings> {
        Some(RelaySettings {
            routes: RelayRoutes::of(config)?,
            link_qos: QosConfig::best_effort(config.output.qos.depth),
            robot_qos: config.output.qos,
            max_age_ms: config.robot_link.max_age_ms,
            status_topic: config.robot_link.relay_status_topic(),
        })
    }
}

/// Relay until `shutdown`; `report` is updated live. `clock` is this computer's wall clock (a
/// test shifts it to stand for another computer's).
pub async fn run_relay(
    settings: &RelaySettings,
    network: &NetworkConfig,
    clock: WallClock,
    report: &Mutex<RelayReport>,
    shutdown: watch::Receiver<bool>,
) -> Result<(), RosError> {
    let mut node = RosNode::join(network, "/", "pomdar_relay")?;
    let routes = &settings.routes;
    let joint = open_leg::<JointState>(&mut node, routes.joint_targets.as_ref(), settings)?;
    let policy = open_leg::<Float32MultiArray>(&mut node, routes.policy_output.as_ref(), settings)?;
    let arm = open_leg::<PoseStamped>(&mut node, routes.arm_target.as_ref(), settings)?;
    let status = node.publisher(&settings.status_topic, QosConfig::best_effort(10))?;
    let context = LegContext {
        max_age_ms: settings.max_age_ms,
        clock,
        report,
        offset: Mutex::new(ClockOffsetMonitor::new(settings.max_age_ms)),
    };
    let listeners = status::RobotListeners {
        node: &node,
        joint: joint.as_ref(),
        policy: policy.as_ref(),
        arm: arm.as_ref(),
    };
    tokio::join!(
        relay_leg(joint.as_ref(), &context, shutdown.clone()),
        relay_leg(policy.as_ref(), &context, shutdown.clone()),
        relay_leg(arm.as_ref(), &context, shutdown.clone()),
        status::publish_status(&status, &listeners, &context, shutdown),
    );
    drop((joint, policy, arm, status));
    Ok(())
}
