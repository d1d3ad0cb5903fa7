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
//!
//! This file holds the public API, the node's state and the select loop; each of the loop's
//! steps is an `impl StationNode` block in a child module: the endpoints and streams
//! (`endpoints.rs`), the input steps and the step itself (`input_steps.rs`), the status
//! (`status_steps.rs`), the trial log (`trial_steps.rs`), the outputs (`output_steps.rs`) and
//! the ROS tools (`tool_steps.rs`).

use std::collections::BTreeMap;
use std::sync::Arc;
use std::time::Instant;

use futures::StreamExt;
use retarget::HandModel;
use serde::Serialize;
use station::{ControlInput, Counters, InputGap, Station, StationConfig, StationInput, Totals};
use tokio::sync::{mpsc, watch};

use crate::clock::StationClock;
use crate::samples::Samples;
use crate::station_driver::build_station;
use crate::station_node::error::NodeError;
use crate::station_node::loop_turns::LoopTurns;
pub use crate::station_node::operator::{LatestInput, OperatorCommand, StationEvent, StationHooks};
use crate::station_node::recorder::{RecordingOptions, StationRecorder};
use crate::station_node::recorder_thread::LogQueue;
use crate::station_node::relay_view::RelayView;
use crate::station_node::ros_tools_node::ToolScene;

mod endpoints;
mod input_steps;
mod output_steps;
mod status_steps;
mod tool_steps;
mod trial_steps;
// The endpoints' items, for this file and the child modules' `super::` paths.
use endpoints::{Endpoints, Received, source_or};
use trial_steps::with_source;

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
