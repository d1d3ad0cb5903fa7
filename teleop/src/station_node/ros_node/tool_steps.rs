//! The node's steps for the lab's ROS tools: the latched messages (at start and into every
//! trial log), `/tf` and markers with each hand command, `/diagnostics` with each status, the
//! hand's measured state, and the services.

use msgs::{JointState, StringMsg, TriggerResponse};
use serde::Serialize;
use station::ros_tools::{ServiceAction, diagnostics};
use station::{ControlInput, StationInput};

use super::{Endpoints, Received, StationNode};
use crate::station_node::operator::StationEvent;
use crate::station_node::ros_tools_node::ServiceRequest;

impl StationNode {
    /// Publish the latched messages (`/tf_static`, the hand's drawing, `/robot_description`)
    /// once; they go into the log now and into every trial log that starts later.
    pub(super) async fn send_latched(&mut self, endpoints: &Endpoints) {
        let now = self.clock.now_ns();
        self.record_latched(now);
        let (fixed, drawing) = self.scene.latched(now);
        let tools = &endpoints.tools;
        if let Some(publisher) = &tools.tf_static {
            publisher.async_publish(fixed).await.ok();
        }
        if let Some(publisher) = &tools.hand_model_markers {
            publisher.async_publish(drawing).await.ok();
        }
        if let (Some(publisher), Some(text)) = (&tools.description, &self.hooks.robot_description) {
            let message = StringMsg { data: text.clone() };
            publisher.async_publish(message).await.ok();
        }
    }

    /// Record the latched messages into the running trial log and give them to the viewer.
    pub(super) fn record_latched(&mut self, now: i64) {
        let (fixed, drawing) = self.scene.latched(now);
        let config = std::sync::Arc::clone(&self.config);
        let tools = &config.ros_tools;
        let description = self.hooks.robot_description.clone();
        let mut latched: Vec<(&str, Latched)> = Vec::new();
        if tools.tf && config.drives_robot() {
            latched.push(("/tf_static", Latched::Tf(fixed)));
        }
        if !tools.hand_model_markers_topic.is_empty() && config.drives_robot() {
            latched.push((&tools.hand_model_markers_topic, Latched::Markers(drawing)));
        }
        if let Some(data) = description.filter(|_| !tools.robot_description_topic.is_empty()) {
            latched.push((
                &tools.robot_description_topic,
                Latched::Text(StringMsg { data }),
            ));
        }
        for (topic, message) in latched {
            match message {
                Latched::Tf(m) => self.keep(topic, now, &m),
                Latched::Markers(m) => self.keep(topic, now, &m),
                Latched::Text(m) => self.keep(topic, now, &m),
            }
        }
    }

    fn keep<M: msgs::RosMessage + Serialize + Clone + Send + 'static>(
        &mut self,
        topic: &str,
        now: i64,
        message: &M,
    ) {
        self.log_output(topic, now, message);
        if let Some(tap) = &self.hooks.tap {
            tap.send(topic, message, now, true);
        }
    }

    /// `/tf` at the command just sent, and the keypoint markers when it came from a fresh
    /// frame.
    pub(super) async fn send_hand_tools(&mut self, fresh: bool, now: i64, endpoints: &Endpoints) {
        let Some(command) = self.station.command_in_force() else {
            return;
        };
        let q = command.q.clone();
        let tools = &endpoints.tools;
        if let (Some(tf), Some(publisher)) = (self.scene.tf(&q, now), &tools.tf) {
            self.publish(publisher, "/tf", now, tf).await;
        }
        let Some(publisher) = tools.keypoint_markers.as_ref().filter(|_| fresh) else {
            return;
        };
        let Some(retargeter) = self.station.retargeter() else {
            return;
        };
        let calibration = *retargeter.calibration();
        let points = std::mem::take(&mut self.last_points);
        if let Some(markers) = self.scene.keypoint_markers(&points, &calibration, &q, now) {
            let topic = self.config.ros_tools.keypoint_markers_topic.clone();
            self.publish(publisher, &topic, now, markers).await;
        }
        self.last_points = points;
    }

    /// `/diagnostics` from the station's status.
    pub(super) async fn send_diagnostics(&mut self, now: i64, endpoints: &Endpoints) {
        let Some(publisher) = &endpoints.tools.diagnostics else {
            return;
        };
        let status = self.station.status(now);
        let message = diagnostics(&status, &self.config.watchdog, "pomdar_station", now);
        let topic = self.config.ros_tools.diagnostics_topic.clone();
        self.publish(publisher, &topic, now, message).await;
    }

    /// The hand's measured state: recorded, and compared with the command in force.
    pub(super) fn on_hand_state(&mut self, item: Received<JointState>) {
        let now = self.clock.now_ns();
        let topic = self.config.input.hand_state_topic.clone();
        let Ok((message, info)) = item else {
            super::NodeFaults::count(&mut self.faults.input_errors, &topic);
            return;
        };
        self.log_input(&topic, now, Some(super::source_or(&info, now)), &message);
        let command = self.station.command_in_force().map(|c| c.q.as_slice());
        self.scene.hand_state(&message, command, now);
    }

    /// A service call: engage and disengage step the station; trial actions go to the
    /// console. The answer says what was done, or why not.
    pub(super) async fn on_service(&mut self, request: ServiceRequest, endpoints: &Endpoints) {
        let (index, result) = request;
        let Some((action, name)) = endpoints.tools.service(index) else {
            return;
        };
        let name = name.to_string();
        let Ok((id, _)) = result else {
            super::NodeFaults::count(&mut self.faults.input_errors, &name);
            return;
        };
        let response = self.serve(action, endpoints).await;
        self.hooks.send(StationEvent::Message(format!(
            "service {name}: {}",
            response.message
        )));
        if !endpoints.tools.reply(index, id, response).await {
            super::NodeFaults::count(&mut self.faults.publish_failed, &name);
        }
    }

    /// Carry out a service call. Under an operator console every call reaches it as the
    /// operator's own key (so an engage asked before the glove flows waits as the key's
    /// does); a station without one engages and disengages itself and has no trials.
    async fn serve(&mut self, action: ServiceAction, endpoints: &Endpoints) -> TriggerResponse {
        let answer = |success: bool, message: &str| TriggerResponse {
            success,
            message: message.to_string(),
        };
        if self.hooks.events.is_some() {
            self.hooks.send(StationEvent::ServiceRequest(action));
            return answer(true, "passed to the trial console");
        }
        if !self.config.drives_robot() {
            return answer(false, "a human-study station drives no robot");
        }
        match action {
            ServiceAction::Engage => {
                self.drive(StationInput::Control(ControlInput::Engage), endpoints)
                    .await;
                let state = format!("{:?}", self.station.state()).to_lowercase();
                answer(true, &format!("engage requested; the station is {state}"))
            }
            ServiceAction::Disengage => {
                self.drive(StationInput::Control(ControlInput::Disengage), endpoints)
                    .await;
                answer(true, "disengaged: the hand holds, the arm stops")
            }
            _ => answer(
                false,
                "this station runs no trial console: start it with `pomdar trial`",
            ),
        }
    }
}

/// A latched message of one of the three kinds.
enum Latched {
    Tf(msgs::TFMessage),
    Markers(msgs::MarkerArray),
    Text(StringMsg),
}
