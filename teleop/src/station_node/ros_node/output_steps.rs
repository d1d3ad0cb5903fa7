//! The node's outputs on DDS: a step's [`StationOutputs`] taken in the router's order
//! ([`deliveries`], the order every loop sends in), each message recorded in the trial log,
//! shown to the tap and published, a failure counted; the latency from a new frame to its
//! published joint targets measured here.

use std::sync::Arc;

use msgs::PoseStamped;
use ros2_client::Publisher;
use serde::Serialize;
use station::{HandMessages, StationOutputs};

use super::{Endpoints, NodeFaults, StationNode};
use crate::station_driver::{Delivery, deliveries};
use crate::station_node::operator::StationEvent;

impl StationNode {
    /// Send a step's outputs in the router's order ([`deliveries`]): notices to the operator,
    /// then the hand's messages, then the arm's target, each recorded and published.
    pub(super) async fn send(&mut self, outputs: StationOutputs, now: i64, endpoints: &Endpoints) {
        for delivery in deliveries(&outputs) {
            match delivery {
                Delivery::Notice(notice) => {
                    self.hooks.send(StationEvent::Message(notice.to_string()))
                }
                Delivery::Hand { hand, fresh } => {
                    let received = outputs.fresh_frame_received_ns;
                    self.send_hand(hand, received, now, endpoints).await;
                    if endpoints.joint.is_some() {
                        self.send_hand_tools(fresh, now, endpoints).await;
                    }
                }
                Delivery::Arm(arm) => self.send_arm(arm, now, endpoints).await,
            }
        }
    }

    /// Publish the hand's joint targets (noting the latency from the frame `received`, when
    /// new) and its policy output; nothing in a human study (no hand publisher).
    async fn send_hand(
        &mut self,
        hand: &HandMessages,
        received: Option<i64>,
        now: i64,
        endpoints: &Endpoints,
    ) {
        let Some(joint) = &endpoints.joint else {
            return;
        };
        let config = Arc::clone(&self.config);
        let topic = &config.output.joint_targets_topic;
        let sent = self
            .publish(joint, topic, now, hand.joint_state.clone())
            .await;
        if let (true, Some(received)) = (sent, received) {
            self.last_latency_ms = Some((self.clock.now_ns() - received) as f64 * 1e-6);
        }
        if let (Some(message), Some(publisher)) = (&hand.policy, &endpoints.policy) {
            let topic = &config.policy_output.topic;
            self.publish(publisher, topic, now, message.clone()).await;
        }
    }

    /// Publish the arm's target and its `/tf` frame.
    async fn send_arm(&mut self, arm: &PoseStamped, now: i64, endpoints: &Endpoints) {
        let Some(publisher) = &endpoints.arm else {
            return;
        };
        let frame = self.scene.arm_target_tf(arm);
        let config = Arc::clone(&self.config);
        let topic = &config.output.arm_target_topic;
        self.publish(publisher, topic, now, arm.clone()).await;
        if let (Some(tf), Some(publisher)) = (frame, &endpoints.tools.tf) {
            self.publish(publisher, "/tf", now, tf).await;
        }
    }

    /// Record and publish `message`; whether it went out (a failure is counted).
    pub(super) async fn publish<M: msgs::RosMessage + Serialize + Clone + Send + 'static>(
        &mut self,
        publisher: &Publisher<M>,
        topic: &str,
        now: i64,
        message: M,
    ) -> bool {
        self.log_output(topic, now, &message);
        if let Some(tap) = &self.hooks.tap {
            tap.send(topic, &message, now, false);
        }
        let sent = publisher.async_publish(message).await.is_ok();
        if !sent {
            NodeFaults::count(&mut self.faults.publish_failed, topic);
        }
        sent
    }
}
