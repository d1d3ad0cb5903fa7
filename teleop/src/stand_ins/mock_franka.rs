//! The mock Franka arm: moves its end effector toward `geometry_msgs/PoseStamped` commands at
//! a limited speed and publishes its current pose (the station's arm feedback).

use std::sync::{Arc, Mutex};
use std::time::Duration;

use futures::StreamExt;
use msgs::PoseStamped;
use nalgebra::Isometry3;
use tokio::sync::watch;

use crate::clock::StationClock;
use crate::ros::{NetworkConfig, QosConfig, RosNode};
use crate::stand_ins::error::SimError;
use station::convert::{header, isometry_to_pose, pose_to_isometry};

/// What the mock arm saw.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MockFrankaReport {
    /// Commands received.
    pub commands: u64,
    /// Commands with a non-finite value or a non-unit quaternion (ignored).
    pub rejected: u64,
    /// Every accepted command, in order.
    pub targets: Vec<Isometry3<f64>>,
    /// Pose feedback messages whose publishing failed (not sent).
    pub publish_failed: u64,
}

/// The mock arm's settings.
#[derive(Debug, Clone, PartialEq)]
pub struct MockFrankaConfig {
    /// Pose command topic.
    pub command_topic: String,
    /// Pose feedback topic.
    pub pose_topic: String,
    /// Initial end-effector pose, base frame.
    pub start: Isometry3<f64>,
    /// Translation speed limit, m/s.
    pub max_speed_m_s: f64,
    /// Rotation speed limit, rad/s.
    pub max_rate_rad_s: f64,
    /// Feedback rate, Hz.
    pub rate_hz: f64,
}

/// Follow commands and publish the pose until `shutdown`; `report` is updated live.
pub async fn run_mock_franka(
    config: MockFrankaConfig,
    network: NetworkConfig,
    clock: StationClock,
    report: Arc<Mutex<MockFrankaReport>>,
    mut shutdown: watch::Receiver<bool>,
) -> Result<(), SimError> {
    let MockFrankaConfig {
        command_topic,
        pose_topic,
        start,
        max_speed_m_s,
        max_rate_rad_s,
        rate_hz,
    } = config;
    let mut node = RosNode::join(&network, "/", "pomdar_mock_franka")?;
    let command_sub = node.subscription::<PoseStamped>(&command_topic, QosConfig::reliable(50))?;
    let pose_pub = node.publisher::<PoseStamped>(&pose_topic, QosConfig::best_effort(10))?;
    let mut commands = Box::pin(command_sub.async_stream());
    let mut pose = start;
    let mut target = start;
    let period = 1.0 / rate_hz;
    let mut interval = tokio::time::interval(Duration::from_secs_f64(period));
    loop {
        tokio::select! {
            _ = shutdown.changed() => if *shutdown.borrow() { break },
            Some(Ok((message, _))) = commands.next() => {
                let Ok(mut report) = report.lock() else { break };
                report.commands += 1;
                match pose_to_isometry(&message.pose) {
                    Some(iso) => { target = iso; report.targets.push(iso); }
                    None => report.rejected += 1,
                }
            }
            _ = interval.tick() => {
                slew_pose(&mut pose, &target, max_speed_m_s * period, max_rate_rad_s * period);
                let message = PoseStamped { header: header(clock.now_ns(), "world"), pose: isometry_to_pose(&pose) };
                if pose_pub.async_publish(message).await.is_err() {
                    let Ok(mut report) = report.lock() else { break };
                    report.publish_failed += 1;
                }
            }
        }
    }
    Ok(())
}

/// Move `pose` toward `target` by at most `max_step_m` and `max_turn_rad` (an arm's speed
/// limits over one period): the station core's own step limits.
pub fn slew_pose(
    pose: &mut Isometry3<f64>,
    target: &Isometry3<f64>,
    max_step_m: f64,
    max_turn_rad: f64,
) {
    use station::arm::{cap_rotation, cap_translation};
    let translation = cap_translation(
        &pose.translation.vector,
        &target.translation.vector,
        max_step_m,
    );
    let rotation = cap_rotation(&pose.rotation, &target.rotation, max_turn_rad);
    pose.translation.vector = translation.value;
    pose.rotation = rotation.value;
}
