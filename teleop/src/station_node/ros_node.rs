//! The station as a ROS 2 node: subscriptions and the timer step one [`Station`], and what it
//! returns goes out as `sensor_msgs/JointState`, the lab's `/hand/policy_output`, a
//! `geometry_msgs/PoseStamped` arm target, and a JSON status on `std_msgs/String`.
//!
//! Every input is stamped on receipt from the one [`StationClock`], recorded (when recording)
//! with that time and its sender's DDS source time, and then stepped: the log holds every input
//! the station saw, so `pomdar resim` reproduces the run's commands. The node keeps no station
//! state of its own: only its endpoints, its recorder and what only it can measure (publish
//! failures, unreadable samples, listeners, wall-clock step times and latency).
//!
//! Stamps: a command's header carries the DDS source time of the glove frame it was computed
//! from (its receive time when the sender gives none), so any subscriber can measure
//! end-to-end latency; held commands, arm targets and the status carry the station's one
//! clock. docs/FAULTS.md lists what the station does on each input fault.

use std::collections::BTreeMap;
use std::sync::Arc;
use std::time::{Duration, Instant};

use futures::{StreamExt, stream::BoxStream};
use msgs::{Float32MultiArray, JointState, PoseArray, PoseStamped, StringMsg};
use retarget::HandModel;
use ros2_client::{MessageInfo, Publisher, Subscription};
use serde::Serialize;
use serde_json::json;
use station::convert::KeypointMessage;
use station::{
    ControlInput, Counters, GateDecision, InputGap, KeypointFormat, KeypointFrame, Station,
    StationConfig, StationInput, Totals,
};
use tokio::sync::{mpsc, watch};

use crate::clock::StationClock;
use crate::ros::{QosConfig, RosNode};
use crate::samples::Samples;
use crate::station_node::error::NodeError;
use crate::station_node::loop_turns::LoopTurns;
pub use crate::station_node::operator::{LatestInput, OperatorCommand, StationEvent, StationHooks};
use crate::station_node::recorder::{RecordingOptions, StationRecorder};
use crate::station_node::recorder_thread::{LogQueue, LogReport};
use crate::station_node::relay_view::RelayView;
use crate::station_node::ros_tools_node::{ServiceRequest, ToolEndpoints, ToolScene};

mod output_steps;
mod tool_steps;
use crate::station_driver::{build_station, tick_period};

/// Totals when the station stops.
#[derive(Debug, Clone, PartialEq)]
pub struct StationSummary {
    /// Frame and solver counters.
    pub counters: Counters,
    /// What the station sent and refused.
    pub totals: Totals,
    /// What the node could not do: publish failures and unreadable samples, by topic.
    pub faults: NodeFaults,
    /// Whether a second publisher on the arm command topic was seen.
    pub second_publisher_seen: bool,
    /// The longest gap between new glove frames, as received and as sent.
    pub longest_input_gap: Option<InputGap>,
    /// Wall time of each step that retargeted a new frame, milliseconds.
    pub step_time: Samples,
    /// Mean palm-to-tip key-vector error of each solve, millimetres.
    pub tip_error_mm: Samples,
    /// The logs written (one per trial), in order.
    pub recorded: Vec<std::path::PathBuf>,
}

/// What the node could not do, by topic.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct NodeFaults {
    /// Messages whose publishing failed (not sent), by topic.
    pub publish_failed: BTreeMap<String, u64>,
    /// Samples the subscription could not deliver (undecodable or lost in DDS), by topic.
    pub input_errors: BTreeMap<String, u64>,
    /// Log writes dropped because the recorder thread's queue was full (the disk stalled).
    pub log_dropped: u64,
}

impl NodeFaults {
    fn count(map: &mut BTreeMap<String, u64>, topic: &str) {
        *map.entry(topic.to_string()).or_default() += 1;
    }
}

/// Build the station first (a bad profile or configuration fails before any log or node
/// exists), then run it until `shutdown` turns true.
pub async fn run_station(
    config: StationConfig,
    model: HandModel,
    clock: StationClock,
    shutdown: watch::Receiver<bool>,
    operator: mpsc::UnboundedReceiver<OperatorCommand>,
    recording: Option<RecordingOptions>,
) -> Result<StationSummary, NodeError> {
    run_station_observed(
        config,
        model,
        clock,
        shutdown,
        operator,
        recording,
        StationHooks::default(),
    )
    .await
}

/// [`run_station`], reporting its status and trial logs through `hooks`.
pub async fn run_station_observed(
    config: StationConfig,
    model: HandModel,
    clock: StationClock,
    mut shutdown: watch::Receiver<bool>,
    mut operator: mpsc::UnboundedReceiver<OperatorCommand>,
    recording: Option<RecordingOptions>,
    hooks: StationHooks,
) -> Result<StationSummary, NodeError> {
    let scene = ToolScene::new(&model, &config);
    let (station, description) = build_station(&config, model)?;
    if let Some(line) = description {
        hooks.send(StationEvent::Message(line));
    }
    let recorder = match &recording {
        Some(options) => {
            let options = with_source(options, None, &config);
            Some(StationRecorder::start(&options, &config, clock.now_ns())?)
        }
        None => None,
    };
    let (log, mut log_reports) = LogQueue::spawn(recorder)?;
    let endpoints = Endpoints::open(&config, hooks.robot_description.is_some())?;
    let mut streams = endpoints.streams(&config);
    let mut node = StationNode {
        station,
        scene,
        last_points: Vec::new(),
        config: Arc::new(config),
        clock,
        log,
        hooks,
        faults: NodeFaults::default(),
        second_publisher_seen: false,
        last_latency_ms: None,
        step_time: Samples::default(),
        tip_error_mm: Samples::default(),
        recorded: Vec::new(),
        keypoint_source: None,
        relay: RelayView::default(),
        turns: LoopTurns::default(),
    };
    node.send_latched(&endpoints).await;
    loop {
        tokio::select! {
            _ = shutdown.changed() => {
                if *shutdown.borrow() { break; }
            }
            Some(command) = operator.recv() => {
                let t = Instant::now();
                node.on_operator(command, &endpoints).await;
                node.turns.ended("operator", t);
            }
            Some(item) = streams.keypoints.next() => {
                let t = Instant::now();
                node.on_keypoints(item, &endpoints).await;
                node.turns.ended("keypoints", t);
            }
            Some(item) = streams.wrist.next() => node.on_wrist(item),
            Some(item) = streams.feedback.next() => node.on_feedback(item),
            Some(item) = streams.hand_state.next() => node.on_hand_state(item),
            Some(item) = streams.ingress_status.next() => node.on_ingress_status(item),
            Some(request) = streams.services.next() => {
                let t = Instant::now();
                node.on_service(request, &endpoints).await;
                node.turns.ended("service", t);
            }
            Some(report) = log_reports.recv() => node.on_log_report(report),
            _ = streams.tick.tick() => {
                let t = Instant::now();
                node.drive(StationInput::Control(ControlInput::Tick), &endpoints).await;
                node.turns.ended("tick", t);
            }
            _ = streams.status_tick.tick() => {
                let t = Instant::now();
                node.on_status_tick(&endpoints).await;
                node.turns.ended("status", t);
            }
        }
    }
    Ok(node.finish(log_reports).await)
}

/// The node's publishers and subscriptions, and the node last (fields drop in order: the
/// endpoints before their node, `ros::teardown`).
struct Endpoints {
    /// The hand command publisher; `None` in a human study (no robot, nothing commanded).
    joint: Option<Publisher<JointState>>,
    policy: Option<Publisher<Float32MultiArray>>,
    arm: Option<Publisher<PoseStamped>>,
    /// The station's own subscription to the arm command topic: counts its publishers.
    arm_monitor: Option<Subscription<PoseStamped>>,
    status: Publisher<StringMsg>,
    keypoints: KeypointSubscription,
    wrist: Subscription<PoseStamped>,
    feedback: Subscription<PoseStamped>,
    /// The ingress's status (for the keypoint source), when configured.
    ingress_status: Option<Subscription<StringMsg>>,
    /// `pomdar relay`'s status, when the commands go through one.
    relay_status: Option<Subscription<StringMsg>>,
    /// `/tf`, markers, diagnostics, the hand's state, the services.
    tools: ToolEndpoints,
    node: RosNode,
}

/// The keypoint subscription, in the configured format.
enum KeypointSubscription {
    Array(Subscription<Float32MultiArray>),
    Poses(Subscription<PoseArray>),
}

type Received<M> = ros2_client::ReadResult<(M, MessageInfo)>;

/// The node's input streams and timers.
struct Streams<'a> {
    keypoints: BoxStream<'a, Received<KeypointMessage>>,
    wrist: BoxStream<'a, Received<PoseStamped>>,
    feedback: BoxStream<'a, Received<PoseStamped>>,
    hand_state: BoxStream<'a, Received<JointState>>,
    ingress_status: BoxStream<'a, Received<StringMsg>>,
    services: BoxStream<'a, ServiceRequest>,
    tick: tokio::time::Interval,
    status_tick: tokio::time::Interval,
}

impl Endpoints {
    fn open(config: &StationConfig, has_description: bool) -> Result<Endpoints, NodeError> {
        let mut node = RosNode::join(&config.network, "/", "pomdar_station")?;
        let (input_qos, output_qos) = (config.input.qos, config.output.qos);
        let topic = &config.input.keypoints_topic;
        let keypoints = match config.input.keypoints_format {
            KeypointFormat::Float32MultiArray => {
                KeypointSubscription::Array(node.subscription(topic, input_qos)?)
            }
            KeypointFormat::PoseArray => {
                KeypointSubscription::Poses(node.subscription(topic, input_qos)?)
            }
        };
        let robot = config.drives_robot();
        // Relayed (`[robot_link]`): best effort on the relay topics, `pomdar relay` on the
        // robot's computer republishes; nothing old is kept or resent after a cut.
        let link = &config.robot_link;
        let command_qos = link.command_qos(output_qos);
        let arm_topic = &config.output.arm_target_topic;
        let (arm, arm_monitor) = if arm_topic.is_empty() || !robot {
            (None, None)
        } else {
            let wire = link.wire_topic(arm_topic);
            (
                Some(node.publisher(&wire, command_qos)?),
                Some(node.subscription(&wire, command_qos)?),
            )
        };
        let policy = match config.policy_output.topic.as_str() {
            "" => None,
            _ if !robot => None,
            topic => Some(node.publisher(&link.wire_topic(topic), command_qos)?),
        };
        let joint = match robot {
            true => Some(node.publisher(
                &link.wire_topic(&config.output.joint_targets_topic),
                command_qos,
            )?),
            false => None,
        };
        Ok(Endpoints {
            joint,
            policy,
            arm,
            arm_monitor,
            status: node.publisher(&config.output.status_topic, QosConfig::reliable(10))?,
            keypoints,
            wrist: node.subscription(&config.input.wrist_topic, input_qos)?,
            feedback: node
                .subscription(&config.input.arm_feedback_topic, QosConfig::best_effort(10))?,
            ingress_status: match config.input.ingress_status_topic.as_str() {
                "" => None,
                topic => Some(node.subscription(topic, QosConfig::reliable(10))?),
            },
            relay_status: match link.relayed() && robot {
                true => {
                    Some(node.subscription(&link.relay_status_topic(), QosConfig::best_effort(10))?)
                }
                false => None,
            },
            tools: ToolEndpoints::open(&mut node, config, has_description)?,
            node,
        })
    }

    fn streams(&self, config: &StationConfig) -> Streams<'_> {
        let keypoints = match &self.keypoints {
            KeypointSubscription::Array(sub) => sub
                .async_stream()
                .map(|r| r.map(|(m, info)| (KeypointMessage::Array(m), info)))
                .boxed(),
            KeypointSubscription::Poses(sub) => sub
                .async_stream()
                .map(|r| r.map(|(m, info)| (KeypointMessage::Poses(m), info)))
                .boxed(),
        };
        let mut tick = tokio::time::interval(tick_period(config.control.rate_hz));
        tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
        Streams {
            keypoints,
            wrist: self.wrist.async_stream().boxed(),
            feedback: self.feedback.async_stream().boxed(),
            hand_state: match &self.tools.hand_state {
                Some(sub) => sub.async_stream().boxed(),
                None => futures::stream::pending().boxed(),
            },
            ingress_status: match &self.ingress_status {
                Some(sub) => sub.async_stream().boxed(),
                None => futures::stream::pending().boxed(),
            },
            services: self.tools.service_requests(),
            tick,
            status_tick: tokio::time::interval(Duration::from_secs_f64(
                1.0 / config.output.status_rate_hz,
            )),
        }
    }

    /// Matched readers of the commands (the station's own arm monitor is one of the arm's);
    /// behind a relay, the robot's readers as the relay last reported them
    /// ([`RelayView::listeners`]), and the `relay` object.
    fn listeners(&self, config: &StationConfig, relay: &RelayView, now: i64) -> serde_json::Value {
        let node = &self.node;
        let hand = self.joint.as_ref().map(|p| node.matched_subscriptions(p));
        let arm = (self.arm.as_ref()).map(|p| node.matched_subscriptions(p).saturating_sub(1));
        if self.relay_status.is_none() {
            return json!({ "hand": hand, "arm": arm });
        }
        let output = &config.output;
        let behind = |readers: Option<usize>, topic: &str| {
            readers.and_then(|n| relay.listeners(n, topic, now))
        };
        json!({
            "hand": behind(hand, &output.joint_targets_topic),
            "arm": behind(arm, &output.arm_target_topic),
            "relay": relay.document(hand.or(arm), now),
        })
    }

    /// Whether another publisher drives the arm command topic.
    fn arm_topic_contested(&self) -> bool {
        self.arm_monitor
            .as_ref()
            .is_some_and(|m| self.node.matched_publishers(m) > 1)
    }
}

/// `options` with the keypoint source in its metadata (`keypoint_source`, `keypoint_device`),
/// unless the caller set them: `source`, or `unknown` before an ingress named one.
fn with_source(
    options: &RecordingOptions,
    source: Option<&(String, String)>,
    config: &StationConfig,
) -> RecordingOptions {
    let mut options = options.clone();
    let (kind, device) = source.cloned().unwrap_or_else(|| {
        let topic = &config.input.ingress_status_topic;
        (
            "unknown".into(),
            format!("no source named on '{topic}' yet"),
        )
    });
    options
        .metadata
        .entry("keypoint_source".into())
        .or_insert(kind);
    options
        .metadata
        .entry("keypoint_device".into())
        .or_insert(device);
    options
}

/// The `source` (kind, device) an ingress status document names, if it names one.
fn keypoint_source(status: &str) -> Option<(String, String)> {
    let status: serde_json::Value = serde_json::from_str(status).ok()?;
    let source = status.get("source")?;
    let kind = source.get("kind")?.as_str()?.trim();
    let device = source.get("device").and_then(|d| d.as_str()).unwrap_or("");
    (!kind.is_empty()).then(|| (kind.to_string(), device.to_string()))
}

/// The sender's stamp of a sample, else its receive time.
fn source_or(info: &MessageInfo, received_ns: i64) -> i64 {
    info.source_timestamp()
        .map_or(received_ns, |t| t.to_nanos())
}

/// The node's state: the station, and what only the node knows.
struct StationNode {
    station: Station,
    /// What `/tf` and the markers are computed from.
    scene: ToolScene,
    /// The points of the last keypoint frame stepped (for its markers).
    last_points: Vec<nalgebra::Point3<f64>>,
    /// Shared, so a step can borrow topic names while it records and counts.
    config: Arc<StationConfig>,
    clock: StationClock,
    /// The trial log, written by its own thread.
    log: LogQueue,
    hooks: StationHooks,
    faults: NodeFaults,
    second_publisher_seen: bool,
    last_latency_ms: Option<f64>,
    step_time: Samples,
    tip_error_mm: Samples,
    recorded: Vec<std::path::PathBuf>,
    /// The keypoint source the ingress last named (kind, device).
    keypoint_source: Option<(String, String)>,
    /// What the relay (when commands go through one) last said.
    relay: RelayView,
    /// The longest turn of the loop so far.
    turns: LoopTurns,
}

impl StationNode {
    async fn on_operator(&mut self, command: OperatorCommand, endpoints: &Endpoints) {
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

    async fn on_keypoints(&mut self, item: Received<KeypointMessage>, endpoints: &Endpoints) {
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

    fn on_wrist(&mut self, item: Received<PoseStamped>) {
        let config = Arc::clone(&self.config);
        if let Some((pose, now)) = self.record_pose(&config.input.wrist_topic, item) {
            self.station.step(StationInput::Wrist(pose), now);
        }
    }

    fn on_feedback(&mut self, item: Received<PoseStamped>) {
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
    async fn drive(&mut self, input: StationInput, endpoints: &Endpoints) {
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

    async fn on_status_tick(&mut self, endpoints: &Endpoints) {
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

    /// Remember the source an ingress's status names.
    fn on_ingress_status(&mut self, item: Received<StringMsg>) {
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

    fn start_trial(&mut self, options: &RecordingOptions, now: i64) {
        self.finish_trial(now);
        let options = with_source(options, self.keypoint_source.as_ref(), &self.config);
        let flush = self.hooks.trial_log_flush_interval_ns;
        self.log
            .start(options, Arc::clone(&self.config), now, flush);
        self.record_latched(now);
    }

    /// Finish the current trial's log with the run's totals so far (on the recorder thread:
    /// its outcome comes back as a [`LogReport`]).
    fn finish_trial(&mut self, now_ns: i64) {
        if !self.log.is_open() {
            return;
        }
        let totals = self.station.totals();
        let summary = json!({
            "frames_new": self.station.counters().frames_new,
            "hand_commands": totals.hand_commands,
            "arm_targets": totals.arm_targets,
            "held_commands": totals.held_commands,
            "log_dropped": self.log.dropped_in_log(),
        });
        self.log.finish(now_ns, summary);
    }

    /// What the recorder thread did, for the operator.
    fn on_log_report(&mut self, report: LogReport) {
        let event = match report {
            LogReport::Started(path) => StationEvent::TrialStarted(path),
            LogReport::StartFailed {
                path,
                started,
                error,
            } => {
                self.log.start_failed(started);
                StationEvent::TrialStartFailed {
                    path,
                    error: error.to_string(),
                }
            }
            LogReport::WriteFailed(error) => StationEvent::Message(format!("error: {error}")),
            LogReport::Finished(finished) => {
                self.recorded.push(finished.path.clone());
                StationEvent::TrialFinished(finished.path)
            }
            LogReport::FinishFailed { path, error } => StationEvent::TrialFinishFailed {
                path,
                error: error.to_string(),
            },
        };
        self.hooks.send(event);
    }

    /// Queue a copy of an input `message` on `topic` for the log.
    fn log_input<M: msgs::RosMessage + Clone + Send + 'static>(
        &mut self,
        topic: &str,
        now: i64,
        source_ns: Option<i64>,
        message: &M,
    ) {
        if self.log.is_open() {
            let (topic, message) = (topic.to_string(), message.clone());
            self.log
                .write(move |r| r.input(&topic, now, source_ns, &message));
        }
    }

    /// Queue a copy of an output `message` on `topic` for the log.
    fn log_output<M: msgs::RosMessage + Clone + Send + 'static>(
        &mut self,
        topic: &str,
        now: i64,
        message: &M,
    ) {
        if self.log.is_open() {
            let (topic, message) = (topic.to_string(), message.clone());
            self.log.write(move |r| r.output(&topic, now, &message));
        }
    }

    /// Finishes the open trial and waits for the recorder thread to write everything queued.
    async fn finish(
        mut self,
        mut log_reports: mpsc::UnboundedReceiver<LogReport>,
    ) -> StationSummary {
        self.finish_trial(self.clock.now_ns());
        if let Some(thread) = self.log.close() {
            // A panic in the thread has already been printed; its log stays a `.part`.
            let _ = tokio::task::spawn_blocking(move || thread.join()).await;
        }
        while let Ok(report) = log_reports.try_recv() {
            self.on_log_report(report);
        }
        self.faults.log_dropped = self.log.dropped_total();
        StationSummary {
            counters: self.station.counters().clone(),
            totals: self.station.totals().clone(),
            faults: self.faults,
            second_publisher_seen: self.second_publisher_seen,
            longest_input_gap: self.station.longest_input_gap(),
            step_time: self.step_time,
            tip_error_mm: self.tip_error_mm,
            recorded: self.recorded,
        }
    }
}
