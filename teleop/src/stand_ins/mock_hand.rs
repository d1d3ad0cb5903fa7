//! The mock ORCA hand: follows `sensor_msgs/JointState` targets with a first-order lag within
//! its joint limits, and publishes its state; it measures the end-to-end latency of each
//! target (receive time minus the header stamp, which the station sets to the glove frame's
//! publish time). Optionally it also follows a policy output topic (`Float32MultiArray`)
//! decoded through the inverse of a hand-convention table, as the consumer of that topic
//! would read it (`pomdar hand-check` against the mock hand).

use std::sync::{Arc, Mutex};
use std::time::Duration;

use futures::StreamExt;
use msgs::{Float32MultiArray, JointState};
use retarget::HandModel;
use tokio::sync::watch;

use crate::clock::StationClock;
use crate::ros::{NetworkConfig, QosConfig, RosNode};
use crate::stand_ins::error::SimError;
use crate::stand_ins::samples::Samples;
use station::convert::header;
use station::policy_output::PolicyOutput;

/// What the mock hand saw.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MockHandReport {
    /// Targets received.
    pub targets: u64,
    /// End-to-end latency of each target computed from a new glove frame (the first target
    /// carrying a given stamp), milliseconds; repeats of a command are not counted.
    pub latency: Samples,
    /// Targets naming a joint the hand lacks or carrying a non-finite value.
    pub rejected: u64,
    /// Receive times of the targets, nanoseconds (for rate checks).
    pub receive_times_ns: Vec<i64>,
    /// The last target received, by model degree of freedom.
    pub last_target: Option<Vec<f64>>,
    /// State messages whose publishing failed (not sent).
    pub publish_failed: u64,
    /// Policy output arrays received and followed.
    pub policy_targets: u64,
    /// Policy output arrays of the wrong length or with a non-finite value.
    pub policy_rejected: u64,
    /// Every measured state published, by model degree of freedom (only with
    /// [`MockHandConfig::record_states`]).
    pub states: Vec<Vec<f64>>,
}

/// The mock hand's settings.
#[derive(Debug, Clone, PartialEq)]
pub struct MockHandConfig {
    /// Target topic (`sensor_msgs/JointState`).
    pub targets_topic: String,
    /// State topic (`sensor_msgs/JointState`).
    pub state_topic: String,
    /// First-order lag time constant, seconds.
    pub time_constant_s: f64,
    /// State publishing rate, Hz.
    pub rate_hz: f64,
    /// Also follow this policy output topic, decoded through the inverse of the table.
    pub policy: Option<PolicyInput>,
    /// Keep every measured state in the report (tests; grows without bound).
    pub record_states: bool,
}

/// A policy output topic the mock hand follows.
#[derive(Debug, Clone, PartialEq)]
pub struct PolicyInput {
    /// The topic (`std_msgs/Float32MultiArray`).
    pub topic: String,
    /// The table it is encoded with, resolved on the mock hand's model.
    pub table: PolicyOutput,
}

impl Default for MockHandConfig {
    fn default() -> Self {
        MockHandConfig {
            targets_topic: "/pomdar/hand/joint_targets".into(),
            state_topic: "/pomdar/hand/joint_states".into(),
            time_constant_s: 0.03,
            rate_hz: 100.0,
            policy: None,
            record_states: false,
        }
    }
}

/// Follow targets and publish the state until `shutdown`; `report` is updated live.
pub async fn run_mock_hand(
    model: HandModel,
    config: MockHandConfig,
    network: NetworkConfig,
    clock: StationClock,
    report: Arc<Mutex<MockHandReport>>,
    mut shutdown: watch::Receiver<bool>,
) -> Result<(), SimError> {
    let mut node = RosNode::join(&network, "/", "pomdar_mock_hand")?;
    let targets_sub =
        node.subscription::<JointState>(&config.targets_topic, QosConfig::reliable(50))?;
    let state_pub =
        node.publisher::<JointState>(&config.state_topic, QosConfig::best_effort(10))?;
    let mut targets = Box::pin(targets_sub.async_stream());
    // Best effort: matches the consumer topic's publisher whether it is reliable or not.
    let policy_sub = match &config.policy {
        Some(p) => {
            Some(node.subscription::<Float32MultiArray>(&p.topic, QosConfig::best_effort(50))?)
        }
        None => None,
    };
    let mut policy = match &policy_sub {
        Some(sub) => sub
            .async_stream()
            .filter_map(|m| async move { m.ok().map(|(message, _)| message.data) })
            .boxed(),
        None => futures::stream::pending().boxed(),
    };
    let names: Vec<String> = model.ros_dof_names().to_vec();
    let limits: Vec<_> = model.limits().collect();
    let mut state = model.zero_pose();
    let mut target = state.clone();
    let period = 1.0 / config.rate_hz;
    let mut last_stamp = None;
    let mut interval = tokio::time::interval(Duration::from_secs_f64(period));
    loop {
        tokio::select! {
            _ = shutdown.changed() => if *shutdown.borrow() { break },
            Some(Ok((message, _))) = targets.next() => {
                let now = clock.now_ns();
                let Ok(mut report) = report.lock() else { break };
                report.targets += 1;
                report.receive_times_ns.push(now);
                let stamp = message.header.stamp.to_nanos();
                if last_stamp != Some(stamp) {
                    report.latency.push((now - stamp) as f64 * 1e-6);
                    last_stamp = Some(stamp);
                }
                match joint_state_target(&model, &limits, &target, &message) {
                    Some(next) => {
                        target = next;
                        report.last_target = Some(target.clone());
                    }
                    None => report.rejected += 1,
                }
            }
            Some(values) = policy.next() => {
                let Ok(mut report) = report.lock() else { break };
                let decoded = config.policy.as_ref().and_then(|p| p.table.inverse(&values));
                match decoded {
                    Some(joints) => {
                        for (dof, value) in joints {
                            target[dof] = limits[dof].clamp(value);
                        }
                        report.policy_targets += 1;
                        report.last_target = Some(target.clone());
                    }
                    None => report.policy_rejected += 1,
                }
            }
            _ = interval.tick() => {
                let alpha = 1.0 - (-period / config.time_constant_s).exp();
                for (s, t) in state.iter_mut().zip(&target) {
                    *s += alpha * (t - *s);
                }
                if config.record_states {
                    let Ok(mut report) = report.lock() else { break };
                    report.states.push(state.clone());
                }
                let message = JointState {
                    header: header(clock.now_ns(), ""),
                    name: names.clone(),
                    position: state.clone(),
                    velocity: vec![],
                    effort: vec![],
                };
                if state_pub.async_publish(message).await.is_err() {
                    let Ok(mut report) = report.lock() else { break };
                    report.publish_failed += 1;
                }
            }
        }
    }
    Ok(())
}

/// The target a `JointState` sets (clamped to the limits), from `target`; `None` when it
/// names a joint the hand lacks or carries a non-finite value. (The mock hand's, the simulated
/// robot's and the lock-step trial's reading of a hand command.)
pub(crate) fn joint_state_target(
    model: &HandModel,
    limits: &[retarget::Limits],
    target: &[f64],
    message: &JointState,
) -> Option<Vec<f64>> {
    if message.name.len() != message.position.len() {
        return None;
    }
    let mut next = target.to_vec();
    for (name, value) in message.name.iter().zip(&message.position) {
        match station::ros_tools::dof_of_published_name(model, name, None) {
            Some(i) if value.is_finite() => next[i] = limits[i].clamp(*value),
            _ => return None,
        }
    }
    Some(next)
}
