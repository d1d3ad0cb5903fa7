//! The relay's status for the station, twice a second: the readers of each robot topic on this
//! computer (the robot's drivers), the clock offset estimate and the totals
//! ([`RelayStatus`]), and its RTPS sockets' guard (`datagram_guard`, as in the station's
//! status), as JSON on `[robot_link]`'s status topic (best effort: after a cut link, no queue
//! of old statuses arrives).

use std::time::Duration;

use msgs::{Float32MultiArray, JointState, PoseStamped, RosMessage, StringMsg};
use ros2_client::Publisher;
use station::link_clock::RelayStatus;
use tokio::sync::watch;

use super::legs::{Leg, LegContext};
use crate::ros::RosNode;

/// How often the relay publishes its status.
pub const STATUS_PERIOD: Duration = Duration::from_millis(500);

/// The legs whose robot-side readers are counted.
pub struct RobotListeners<'a> {
    pub node: &'a RosNode,
    pub joint: Option<&'a Leg<JointState>>,
    pub policy: Option<&'a Leg<Float32MultiArray>>,
    pub arm: Option<&'a Leg<PoseStamped>>,
}

impl RobotListeners<'_> {
    fn count<M: RosMessage>(&self, leg: Option<&Leg<M>>, status: &mut RelayStatus) {
        if let Some(leg) = leg {
            let readers = self.node.matched_subscriptions(&leg.publisher) as u64;
            status.robot_listeners.insert(leg.route.to.clone(), readers);
        }
    }

    fn count_all(&self, status: &mut RelayStatus) {
        self.count(self.joint, status);
        self.count(self.policy, status);
        self.count(self.arm, status);
    }
}

/// The status now, and the report's readers updated.
fn status_now(listeners: &RobotListeners<'_>, context: &LegContext<'_>) -> RelayStatus {
    let mut status = RelayStatus::default();
    listeners.count_all(&mut status);
    if let Ok(mut report) = context.report.lock() {
        for (topic, readers) in &status.robot_listeners {
            report
                .topics
                .entry(topic.clone())
                .or_default()
                .robot_listeners = *readers;
        }
        status.clock_offset_ms = report.clock_offset_ms;
        for topic in report.topics.values() {
            status.forwarded += topic.ages.forwarded;
            status.dropped += topic.ages.dropped();
            status.publish_failed += topic.publish_failed;
        }
    }
    status
}

/// Publish the status every [`STATUS_PERIOD`] until `shutdown`.
pub async fn publish_status(
    publisher: &Publisher<StringMsg>,
    listeners: &RobotListeners<'_>,
    context: &LegContext<'_>,
    mut shutdown: watch::Receiver<bool>,
) {
    let mut tick = tokio::time::interval(STATUS_PERIOD);
    tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
    loop {
        tokio::select! {
            _ = shutdown.changed() => if *shutdown.borrow() { break } else { continue },
            _ = tick.tick() => {}
        }
        let mut status = serde_json::to_value(status_now(listeners, context)).unwrap_or_default();
        if let Some(fields) = status.as_object_mut() {
            fields.insert(
                "datagram_guard".into(),
                crate::ros::participant_guard::status(),
            );
        }
        let data = status.to_string();
        // A status that cannot go out is retried at the next tick; the station treats a
        // missing status as "unknown", never as a hand listening.
        let _ = publisher.async_publish(StringMsg { data }).await;
    }
}
