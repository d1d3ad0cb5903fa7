//! The mock ORCA hand: follows `sensor_msgs/JointState` targets with a first-order lag within
//! its joint limits, and publishes its state; it measures the end-to-end latency of each
//! target (receive time minus the header stamp, which the station sets to the glove frame's
//! publish time).

use std::sync::{Arc, Mutex};
use std::time::Duration;

use futures::StreamExt;
use msgs::JointState;
use retarget::HandModel;
use tokio::sync::watch;

use crate::clock::StationClock;
use crate::ros::NetworkContext as _;
use crate::ros::{NetworkConfig, QosConfig, RosNode};
use crate::sim::error::SimError;
use crate::sim::samples::Samples;
use station::convert::header;

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
}

impl Default for MockHandConfig {
    fn default() -> Self {
        MockHandConfig {
            targets_topic: "/pomdar/hand/joint_targets".into(),
            state_topic: "/pomdar/hand/joint_states".into(),
            time_constant_s: 0.03,
            rate_hz: 100.0,
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
    let MockHandConfig {
        targets_topic,
        state_topic,
        time_constant_s,
        rate_hz,
    } = config;
    let context = network.context()?;
    let mut node = RosNode::new(&context, "/", "pomdar_mock_hand")?;
    let targets_sub = node.subscription::<JointState>(&targets_topic, QosConfig::reliable(50))?;
    let state_pub = node.publisher::<JointState>(&state_topic, QosConfig::best_effort(10))?;
    let mut targets = Box::pin(targets_sub.async_stream());
    let names: Vec<String> = model.ros_dof_names().to_vec();
    let limits: Vec<_> = model.limits().collect();
    let mut state = model.zero_pose();
    let mut target = state.clone();
    let period = 1.0 / rate_hz;
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
                let mut ok = message.name.len() == message.position.len();
                let mut next = target.clone();
                for (name, value) in message.name.iter().zip(&message.position) {
                    match station::ros_tools::dof_of_published_name(&model, name, None) {
                        Some(i) if value.is_finite() => next[i] = limits[i].clamp(*value),
                        _ => ok = false,
                    }
                }
                if ok {
                    target = next;
                    report.last_target = Some(target.clone());
                } else {
                    report.rejected += 1;
                }
            }
            _ = interval.tick() => {
                let alpha = 1.0 - (-period / time_constant_s).exp();
                for (s, t) in state.iter_mut().zip(&target) {
                    *s += alpha * (t - *s);
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
