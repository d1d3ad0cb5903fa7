//! `pomdar relay`'s node, on the robot's computer: the station's commands from the relay
//! topics (best effort across the lab network: a cut link loses what was sent into it, and
//! nothing is resent) onto the robot's own topics (with `output.qos`, the reliability the
//! robot's drivers ask for, over this computer's loopback), each command older than
//! `[robot_link] max_age_ms` on arrival dropped ([`station::robot_link`]).

use std::collections::BTreeMap;
use std::sync::Mutex;

use futures::StreamExt as _;
use msgs::{Float32MultiArray, JointState, PoseStamped, RosMessage};
use ros2_client::{Publisher, Subscription};
use serde::Serialize;
use station::StationConfig;
use station::robot_link::{AgeCounts, AgeVerdict, CommandAgeGate};
use tokio::sync::watch;

use crate::clock::StationClock;
use crate::ingress::log_limit::LogLimiter;
use crate::ros::{NetworkConfig, QosConfig, RosError, RosNode};

/// How often at most the relay says it dropped commands, nanoseconds.
const WARNING_PERIOD_NS: i64 = 5_000_000_000;

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
}

/// What the relay did, by the robot's topic.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize)]
pub struct RelayReport {
    /// Per robot topic.
    pub topics: BTreeMap<String, TopicRelayReport>,
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
}

impl RelaySettings {
    /// The settings of a configuration that relays (see [`RelayRoutes::of`]).
    pub fn of(config: &StationConfig) -> Option<RelaySettings> {
        Some(RelaySettings {
            routes: RelayRoutes::of(config)?,
            link_qos: QosConfig::best_effort(config.output.qos.depth),
            robot_qos: config.output.qos,
            max_age_ms: config.robot_link.max_age_ms,
        })
    }
}

/// One topic's subscription and publisher.
struct Leg<M: RosMessage + 'static> {
    route: RelayRoute,
    subscription: Subscription<M>,
    publisher: Publisher<M>,
}

fn open_leg<M: RosMessage + 'static>(
    node: &mut RosNode,
    route: Option<&RelayRoute>,
    settings: &RelaySettings,
) -> Result<Option<Leg<M>>, RosError> {
    let Some(route) = route else { return Ok(None) };
    Ok(Some(Leg {
        route: route.clone(),
        subscription: node.subscription(&route.from, settings.link_qos)?,
        publisher: node.publisher(&route.to, settings.robot_qos)?,
    }))
}

/// Relay until `shutdown`; `report` is updated live.
pub async fn run_relay(
    settings: &RelaySettings,
    network: &NetworkConfig,
    clock: StationClock,
    report: &Mutex<RelayReport>,
    shutdown: watch::Receiver<bool>,
) -> Result<(), RosError> {
    let mut node = RosNode::join(network, "/", "pomdar_relay")?;
    let routes = &settings.routes;
    let joint = open_leg::<JointState>(&mut node, routes.joint_targets.as_ref(), settings)?;
    let policy = open_leg::<Float32MultiArray>(&mut node, routes.policy_output.as_ref(), settings)?;
    let arm = open_leg::<PoseStamped>(&mut node, routes.arm_target.as_ref(), settings)?;
    let context = LegContext {
        max_age_ms: settings.max_age_ms,
        clock: &clock,
        report,
    };
    tokio::join!(
        relay_leg(joint.as_ref(), &context, shutdown.clone()),
        relay_leg(policy.as_ref(), &context, shutdown.clone()),
        relay_leg(arm.as_ref(), &context, shutdown),
    );
    drop((joint, policy, arm));
    Ok(())
}

/// What every leg shares.
struct LegContext<'a> {
    max_age_ms: u64,
    clock: &'a StationClock,
    report: &'a Mutex<RelayReport>,
}

/// Drops since the last warning, said at most once per [`WARNING_PERIOD_NS`].
struct DropWarning {
    limiter: LogLimiter,
    counts_at_last: AgeCounts,
}

impl DropWarning {
    fn maybe_say(&mut self, topic: &str, counts: &AgeCounts, max_age_ms: u64, now_ns: i64) {
        if self.limiter.allow("dropped", now_ns).is_none() {
            return;
        }
        let old = counts.too_old - self.counts_at_last.too_old;
        let ahead = counts.from_the_future - self.counts_at_last.from_the_future;
        let unstamped = counts.unstamped - self.counts_at_last.unstamped;
        let mut parts = Vec::new();
        if old > 0 {
            parts.push(format!(
                "{old} older than {max_age_ms} ms (the oldest dropped so far {:.0} ms)",
                counts.oldest_dropped_ns as f64 * 1e-6
            ));
        }
        if ahead > 0 {
            parts.push(format!(
                "{ahead} sent more than {max_age_ms} ms ahead of this computer's clock (keep the station's and this computer's clocks in step, e.g. chrony)"
            ));
        }
        if unstamped > 0 {
            parts.push(format!("{unstamped} without a send time"));
        }
        eprintln!("relay: {topic}: dropped {}", parts.join(", "));
        self.counts_at_last = counts.clone();
    }
}

async fn relay_leg<M: RosMessage + 'static>(
    leg: Option<&Leg<M>>,
    context: &LegContext<'_>,
    mut shutdown: watch::Receiver<bool>,
) {
    let Some(leg) = leg else { return };
    let topic = leg.route.to.as_str();
    let mut gate = CommandAgeGate::new(context.max_age_ms);
    let mut warning = DropWarning {
        limiter: LogLimiter::new(WARNING_PERIOD_NS),
        counts_at_last: AgeCounts::default(),
    };
    let mut stream = Box::pin(leg.subscription.async_stream());
    loop {
        let received = tokio::select! {
            _ = shutdown.changed() => if *shutdown.borrow() { break } else { continue },
            next = stream.next() => match next { Some(received) => received, None => break },
        };
        let now = context.clock.now_ns();
        let (verdict, failed) = match received {
            Ok((message, info)) => {
                let sent = info.source_timestamp().map(|t| t.to_nanos());
                let verdict = gate.judge(sent, now);
                let failed =
                    verdict.forwards() && leg.publisher.async_publish(message).await.is_err();
                (Some(verdict), failed)
            }
            Err(_) => (None, false),
        };
        let Ok(mut report) = context.report.lock() else {
            break;
        };
        let entry = report.topics.entry(topic.to_string()).or_default();
        entry.ages = gate.counts().clone();
        entry.input_errors += u64::from(verdict.is_none());
        entry.publish_failed += u64::from(failed);
        if verdict.is_some_and(|v| !matches!(v, AgeVerdict::Forward)) {
            warning.maybe_say(topic, gate.counts(), context.max_age_ms, now);
        }
    }
}
