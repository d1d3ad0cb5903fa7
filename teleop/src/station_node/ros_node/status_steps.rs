//! The node's status: on each status tick the contested arm topic stepped into the station
//! (when it changed), the station's status document with what only the node knows (latency,
//! step time, the loop's longest turn, the commands' listeners, the node's faults, the
//! datagram guard, the hand's tracking) handed to the hooks and the tap, recorded and
//! published, and the diagnostics sent with it.

use std::sync::Arc;

use msgs::StringMsg;
use serde_json::json;
use station::{ControlInput, StationInput};

use super::{Endpoints, NodeFaults, StationNode};

impl StationNode {
    /// The status tick: a change in the arm topic's contest stepped into the station, then the
    /// status recorded, shown and published, with the diagnostics.
    pub(super) async fn on_status_tick(&mut self, endpoints: &Endpoints) {
        let contested = endpoints.arm_topic_contested();
        if contested != self.station.arm_blocked() {
            self.second_publisher_seen |= contested;
            let blocked = ControlInput::ArmBlocked { blocked: contested };
            self.drive(StationInput::Control(blocked), endpoints).await;
        }
        let now = self.clock.now_ns();
        let status = self.status_document(now, endpoints);
        if let Some(tx) = &self.hooks.status {
            tx.send(Some(status.clone())).ok();
        }
        let message = StringMsg {
            data: status.to_string(),
        };
        if let Some(tap) = &self.hooks.tap {
            tap.send(&self.config.output.status_topic, &message, now, false);
        }
        self.send_diagnostics(now, endpoints).await;
        if self.log.is_open() {
            let (topic, status) = (self.config.output.status_topic.clone(), message.clone());
            self.log.write(move |r| {
                r.output(&topic, now, &status);
                r.tick(now);
            });
        }
        if endpoints.status.async_publish(message).await.is_err() {
            let config = Arc::clone(&self.config);
            NodeFaults::count(&mut self.faults.publish_failed, &config.output.status_topic);
        }
    }

    /// The station's status with what only the node knows.
    fn status_document(&mut self, now: i64, endpoints: &Endpoints) -> serde_json::Value {
        self.faults.log_dropped = self.log.dropped_total();
        let mut status = serde_json::to_value(self.station.status(now)).unwrap_or_default();
        if let Some(fields) = status.as_object_mut() {
            fields.insert("stamp_ns".into(), json!(now));
            fields.insert("processing_latency_ms".into(), json!(self.last_latency_ms));
            fields.insert("last_step_ms".into(), json!(self.step_time.last()));
            fields.insert("longest_turn".into(), json!(self.turns));
            if let Some(subscription) = &endpoints.relay_status {
                self.relay.poll(subscription, now);
            }
            let listeners = endpoints.listeners(&self.config, &self.relay, now);
            fields.insert("listeners".into(), listeners);
            fields.insert("node".into(), json!(self.faults));
            fields.insert(
                "datagram_guard".into(),
                crate::ros::participant_guard::status(),
            );
            fields.insert("hand_feedback".into(), self.scene.tracking_status(now));
        }
        status
    }
}
