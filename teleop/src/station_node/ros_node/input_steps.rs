//! The node's input steps: an operator's command, a keypoint frame, a wrist pose and the
//! arm's feedback (each stamped on receipt, queued for the trial log with its sender's time,
//! an unreadable sample counted), the ingress's status (the keypoint source it names), and the
//! step itself: a control input recorded, the station stepped, its step time and tip error
//! measured and its outputs sent.

use std::sync::Arc;
use std::time::Instant;

use msgs::{PoseStamped, StringMsg};
use station::convert::KeypointMessage;
use station::{ControlInput, GateDecision, KeypointFrame, StationInput};

use super::{Endpoints, NodeFaults, Received, StationNode, source_or};
use crate::station_node::operator::OperatorCommand;

impl StationNode {
    /// An operator's command: engage and disengage step the station; a trial's events, start
    /// and stop go to the log.
    pub(super) async fn on_operator(&mut self, command: OperatorCommand, endpoints: &Endpoints) {
        let now = self.clock.now_ns();
        match command {
            OperatorCommand::Engage => {
                self.drive(StationInput::Control(ControlInput::Engage), endpoints)
                    .await;
            }
            OperatorCommand::Disengage => {
                self.drive(StationInput::Control(ControlInput::Disengage), endpoints)
                    .await;
            }
            OperatorCommand::TrialEvent(event) => self.log.event(now, event),
            OperatorCommand::StartTrial(options) => self.start_trial(&options, now),
            OperatorCommand::StopTrial => self.finish_trial(now),
        }
    }

    /// A keypoint frame: queued for the log with its sender's time, then stepped.
    pub(super) async fn on_keypoints(
        &mut self,
        item: Received<KeypointMessage>,
        endpoints: &Endpoints,
    ) {
        let now = self.clock.now_ns();
        let config = Arc::clone(&self.config);
        let topic = &config.input.keypoints_topic;
        let Ok((message, info)) = item else {
            NodeFaults::count(&mut self.faults.input_errors, topic);
            return;
        };
        let source_ns = source_or(&info, now);
        if self.log.is_open() {
            let (topic, message) = (topic.clone(), message.clone());
            self.log
                .write(move |r| r.keypoints(&topic, now, Some(source_ns), &message));
        }
        let frame = KeypointFrame {
            points: message.points(),
            source_ns,
        };
        self.last_points.clone_from(&frame.points);
        self.step_and_send(StationInput::Keypoints(frame), now, endpoints)
            .await;
    }

    /// A wrist pose: recorded and stepped.
    pub(super) fn on_wrist(&mut self, item: Received<PoseStamped>) {
        let config = Arc::clone(&self.config);
        if let Some((pose, now)) = self.record_pose(&config.input.wrist_topic, item) {
            self.station.step(StationInput::Wrist(pose), now);
        }
    }

    /// The arm's measured pose: recorded and stepped.
    pub(super) fn on_feedback(&mut self, item: Received<PoseStamped>) {
        let config = Arc::clone(&self.config);
        if let Some((pose, now)) = self.record_pose(&config.input.arm_feedback_topic, item) {
            self.station.step(StationInput::ArmFeedback(pose), now);
        }
    }

    /// Record a received pose (or count it as unreadable); its pose for the station and its
    /// receive time.
    fn record_pose(
        &mut self,
        topic: &str,
        item: Received<PoseStamped>,
    ) -> Option<(msgs::Pose, i64)> {
        let now = self.clock.now_ns();
        let Ok((message, info)) = item else {
            NodeFaults::count(&mut self.faults.input_errors, topic);
            return None;
        };
        self.log_input(topic, now, Some(source_or(&info, now)), &message);
        Some((message.pose, now))
    }

    /// Record a control input and step the station with it.
    pub(super) async fn drive(&mut self, input: StationInput, endpoints: &Endpoints) {
        let now = self.clock.now_ns();
        if let StationInput::Control(control) = input {
            self.log.write(move |r| r.control(now, control));
        }
        self.step_and_send(input, now, endpoints).await;
    }

    /// Step the station and send what it returns.
    async fn step_and_send(&mut self, input: StationInput, now: i64, endpoints: &Endpoints) {
        let started = Instant::now();
        let outputs = self.station.step(input, now);
        if let (Some(GateDecision::New), Some(latest)) = (outputs.verdict, &self.hooks.latest_input)
        {
            latest.record(now);
        }
        if outputs.fresh_frame_received_ns.is_some() {
            self.step_time.push(started.elapsed().as_secs_f64() * 1e3);
            self.tip_error_mm
                .push(self.station.counters().last_tip_error_mm);
        }
        self.send(outputs, now, endpoints).await;
    }

    /// Remember the source an ingress's status names.
    pub(super) fn on_ingress_status(&mut self, item: Received<StringMsg>) {
        let Ok((message, _)) = item else {
            let config = Arc::clone(&self.config);
            NodeFaults::count(
                &mut self.faults.input_errors,
                &config.input.ingress_status_topic,
            );
            return;
        };
        if let Some(source) = keypoint_source(&message.data) {
            self.keypoint_source = Some(source);
        }
    }
}

/// The `source` (kind, device) an ingress status document names, if it names one.
fn keypoint_source(status: &str) -> Option<(String, String)> {
    let status: serde_json::Value = serde_json::from_str(status).ok()?;
    let source = status.get("source")?;
    let kind = source.get("kind")?.as_str()?.trim();
    let device = source.get("device").and_then(|d| d.as_str()).unwrap_or("");
    (!kind.is_empty()).then(|| (kind.to_string(), device.to_string()))
}
