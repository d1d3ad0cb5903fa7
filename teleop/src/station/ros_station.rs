//! The station as a ROS 2 node: subscriptions feed [`StationCore`], a timer ticks it, and its
//! commands go out as `sensor_msgs/JointState`, the lab's `/hand/policy_output`, a
//! `geometry_msgs/PoseStamped` arm target, and a JSON status on `std_msgs/String`.
//!
//! Stamps: a command's header carries the DDS source time of the glove frame it was computed
//! from (its receive time when the sender gives none), so any subscriber can measure
//! end-to-end latency; held commands, arm targets and the status carry the station's one
//! clock. Frames that arrive together are taken together (the newest wins); frames stamped
//! before the newest accepted one are rejected as late. docs/FAULTS.md lists what the station
//! does on each input fault.

use std::time::Duration;

use anyhow::Context as _;
use futures::{FutureExt as _, StreamExt};
use msgs::{Float32MultiArray, JointState, PoseArray, PoseStamped, StringMsg};
use nalgebra::Isometry3;
use retarget::{EmbodimentCatalog, HandModel, Retargeter};
use serde_json::json;
use tokio::sync::{mpsc, watch};

use crate::calibrate::profile_file::{describe, load_profile};
use crate::clock::StationClock;
use crate::ros::convert::{KeypointMessage, pose_to_isometry};
use crate::ros::{QosConfig, RosNode};
use crate::sim::samples::Samples;
use crate::station::frame_gate::{FrameGate, Verdict};
use crate::station::output_stage::OutputStage;
use crate::station::rate_meter::RateMeter;
use crate::station::recorder::{RecordingOptions, StationRecorder};
use crate::station::station_config::{ControlMode, KeypointFormat, StationConfig};
use crate::station::station_core::{Counters, StationCore};
use crate::station::watchdog::Watchdog;

/// Most keypoint frames taken in one go when they arrive together (see the keypoint branch of
/// [`run_station`]); more wait for the next turn of the loop, so a flood cannot starve the
/// control timer.
const MAX_BURST_FRAMES: usize = 1000;

/// What the operator (console, test, demo) tells a running station.
#[derive(Debug, Clone, PartialEq)]
pub enum OperatorCommand {
    /// Engage: drive hand and arm once input is fresh.
    Engage,
    /// Disengage: stop driving the arm; the hand holds.
    Disengage,
    /// A trial event for the log (`/pomdar/trial_events`, flushed at once), e.g.
    /// `{"event": "progress", "value": 1}`, `{"event": "drop"}`, `{"event": "abort"}`,
    /// `{"event": "note", "text": "..."}`. The station adds the event's time.
    TrialEvent(serde_json::Value),
    /// Start recording a new trial to its own log (finishing the current one, if any).
    StartTrial(RecordingOptions),
    /// Finish the current trial's log (stop event, summary, rename from `.part`).
    StopTrial,
}

/// What a running station reports to the process that runs it (the operator console), besides
/// its ROS topics. Without hooks the messages go to stderr.
#[derive(Debug, Default)]
pub struct StationHooks {
    /// The status JSON, as published on the status topic, at the status rate.
    pub status: Option<watch::Sender<Option<serde_json::Value>>>,
    /// Trial log starts and ends, and messages for the operator.
    pub events: Option<mpsc::UnboundedSender<StationEvent>>,
}

/// A station event for the process that runs it.
#[derive(Debug, Clone, PartialEq)]
pub enum StationEvent {
    /// A trial log was created (its final path).
    TrialStarted(std::path::PathBuf),
    /// A trial log could not be created.
    TrialStartFailed {
        /// The log that was asked for.
        path: std::path::PathBuf,
        /// Why.
        error: String,
    },
    /// A trial log was finished and renamed to its final path.
    TrialFinished(std::path::PathBuf),
    /// A trial log could not be finished (its `.part` stays for `pomdar recover`).
    TrialFinishFailed {
        /// The log.
        path: std::path::PathBuf,
        /// Why.
        error: String,
    },
    /// A warning or error for the operator.
    Message(String),
}

impl StationHooks {
    fn send(&self, event: StationEvent) {
        match &self.events {
            Some(tx) => {
                tx.send(event).ok();
            }
            None => match event {
                StationEvent::TrialStartFailed { path, error } => {
                    eprintln!("error: cannot start recording {}: {error}", path.display());
                }
                StationEvent::TrialFinishFailed { error, .. } => {
                    eprintln!("error: cannot finish the trial log: {error}");
                }
                StationEvent::Message(text) => eprintln!("{text}"),
                StationEvent::TrialStarted(_) | StationEvent::TrialFinished(_) => {}
            },
        }
    }
}

/// Totals when the station stops.
#[derive(Debug, Clone, PartialEq)]
pub struct StationSummary {
    /// Frame and solver counters.
    pub counters: Counters,
    /// Hand commands published.
    pub hand_commands: u64,
    /// Arm targets published.
    pub arm_targets: u64,
    /// Wrist poses rejected (non-finite, non-unit quaternion).
    pub wrist_rejected: u64,
    /// Whether a second publisher on the arm command topic was seen.
    pub second_publisher_seen: bool,
    /// Wall time of each control step that retargeted a new frame, milliseconds.
    pub step_time: Samples,
    /// Mean palm-to-tip key-vector error of each solve, millimetres.
    pub tip_error_mm: Samples,
    /// The logs written (one per trial), in order.
    pub recorded: Vec<std::path::PathBuf>,
}

/// Build the core for a configuration. With a `calibration_profile`, the profile is loaded
/// (errors name the file and the key), checked against the model and the layout, applied, and
/// described in one line on stderr.
pub fn station_core(config: &StationConfig, model: HandModel) -> anyhow::Result<StationCore> {
    let (core, description) = station_core_described(config, model)?;
    if let Some(line) = description {
        eprintln!("{line}");
    }
    Ok(core)
}

/// [`station_core`], returning the profile's one-line description instead of printing it.
pub fn station_core_described(
    config: &StationConfig,
    model: HandModel,
) -> anyhow::Result<(StationCore, Option<String>)> {
    let profile = match &config.calibration_profile {
        Some(path) => Some(load_profile(path, &model, config.retarget.layout)?),
        None => None,
    };
    let mut retargeter = Retargeter::new(
        model,
        config.retarget.clone(),
        &EmbodimentCatalog::builtin(),
    )
    .context("retargeter")?;
    let description = profile.as_ref().map(describe);
    if let Some(profile) = profile {
        retargeter
            .set_calibration(profile.parameters)
            .context("calibration profile")?;
    }
    Ok((
        StationCore::new(
            retargeter,
            FrameGate::new(config.retarget.layout, config.gate.clone()),
            Watchdog::new(config.watchdog.clone()),
        ),
        description,
    ))
}

/// Run the station until `shutdown` turns true.
pub async fn run_station(
    config: StationConfig,
    model: HandModel,
    clock: StationClock,
    shutdown: watch::Receiver<bool>,
    operator: mpsc::UnboundedReceiver<OperatorCommand>,
    recording: Option<RecordingOptions>,
) -> anyhow::Result<StationSummary> {
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
) -> anyhow::Result<StationSummary> {
    // The core first: a bad profile or configuration fails before any log is created.
    let (mut core, description) = station_core_described(&config, model.clone())?;
    if let Some(line) = description {
        hooks.send(StationEvent::Message(line));
    }
    let mut recorder = match &recording {
        Some(options) => Some(StationRecorder::start(options, &config, clock.now_ns())?),
        None => None,
    };
    let mut stage = OutputStage::new(&config, &model)?;

    let context = config.network.context()?;
    let mut node = RosNode::new(&context, "/", "pomdar_station")?;
    let input_qos = config.input.qos;
    let output_qos = config.output.qos;
    let format = config.input.keypoints_format;
    let array_sub = match format {
        KeypointFormat::Float32MultiArray => {
            Some(node.subscription::<Float32MultiArray>(&config.input.keypoints_topic, input_qos)?)
        }
        KeypointFormat::PoseArray => None,
    };
    let pose_array_sub = match format {
        KeypointFormat::PoseArray => {
            Some(node.subscription::<PoseArray>(&config.input.keypoints_topic, input_qos)?)
        }
        KeypointFormat::Float32MultiArray => None,
    };
    let wrist_sub = node.subscription::<PoseStamped>(&config.input.wrist_topic, input_qos)?;
    let feedback_sub = node.subscription::<PoseStamped>(
        &config.input.arm_feedback_topic,
        QosConfig::best_effort(10),
    )?;
    let joint_pub = node.publisher::<JointState>(&config.output.joint_targets_topic, output_qos)?;
    let policy_pub = if config.policy_output.topic.is_empty() {
        None
    } else {
        Some(node.publisher::<Float32MultiArray>(&config.policy_output.topic, output_qos)?)
    };
    let arm_enabled = !config.output.arm_target_topic.is_empty();
    let (arm_pub, arm_monitor) = if arm_enabled {
        (
            Some(node.publisher::<PoseStamped>(&config.output.arm_target_topic, output_qos)?),
            Some(node.subscription::<PoseStamped>(&config.output.arm_target_topic, output_qos)?),
        )
    } else {
        (None, None)
    };
    let status_pub =
        node.publisher::<StringMsg>(&config.output.status_topic, QosConfig::reliable(10))?;

    let mut keypoints = match (&array_sub, &pose_array_sub) {
        (Some(sub), _) => sub
            .async_stream()
            .map(|r| {
                r.map(|(m, info)| {
                    (
                        KeypointMessage::Array(m),
                        info.source_timestamp().map(|t| t.to_nanos()),
                    )
                })
            })
            .boxed(),
        (None, Some(sub)) => sub
            .async_stream()
            .map(|r| {
                r.map(|(m, info)| {
                    (
                        KeypointMessage::Poses(m),
                        info.source_timestamp().map(|t| t.to_nanos()),
                    )
                })
            })
            .boxed(),
        (None, None) => futures::stream::pending().boxed(),
    };
    let mut wrists = Box::pin(wrist_sub.async_stream());
    let mut feedback = Box::pin(feedback_sub.async_stream());
    let mut tick = tokio::time::interval(Duration::from_secs_f64(1.0 / config.control.rate_hz));
    tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
    let mut status_tick =
        tokio::time::interval(Duration::from_secs_f64(1.0 / config.output.status_rate_hz));

    let mut glove_wrist: Option<Isometry3<f64>> = None;
    let mut robot_pose: Option<Isometry3<f64>> = None;
    let mut frame_source_ns: i64 = 0;
    let mut input_rate = RateMeter::new(1.0);
    let mut repeat_rate = RateMeter::new(1.0);
    let mut output_rate = RateMeter::new(1.0);
    let mut auto_engage_pending = config.control.auto_engage;
    let mut summary = StationSummary {
        counters: Counters::default(),
        hand_commands: 0,
        arm_targets: 0,
        wrist_rejected: 0,
        second_publisher_seen: false,
        step_time: Samples::default(),
        tip_error_mm: Samples::default(),
        recorded: Vec::new(),
    };
    let mut second_publisher = false;
    let mut last_latency_ms = f64::NAN;

    loop {
        let mut tick_now = false;
        tokio::select! {
            _ = shutdown.changed() => {
                if *shutdown.borrow() { break; }
            }
            Some(command) = operator.recv() => {
                let now = clock.now_ns();
                match command {
                    OperatorCommand::Engage => { core.engage(now); }
                    OperatorCommand::Disengage => core.disengage(),
                    OperatorCommand::TrialEvent(event) => {
                        if let Some(r) = recorder.as_mut() {
                            r.event(now, &event);
                        }
                    }
                    OperatorCommand::StartTrial(options) => {
                        if let Some(r) = recorder.take() {
                            finish_trial(r, now, &core, &mut summary, &hooks);
                        }
                        match StationRecorder::start(&options, &config, now) {
                            Ok(r) => {
                                recorder = Some(r);
                                hooks.send(StationEvent::TrialStarted(options.path.clone()));
                            }
                            Err(e) => hooks.send(StationEvent::TrialStartFailed {
                                path: options.path.clone(),
                                error: format!("{e:#}"),
                            }),
                        }
                    }
                    OperatorCommand::StopTrial => {
                        if let Some(r) = recorder.take() {
                            finish_trial(r, now, &core, &mut summary, &hooks);
                        }
                    }
                }
            }
            Some(item) = keypoints.next() => {
                // A burst (frames queued while the station was busy, or delivered together after
                // a network stall) is taken whole before the next control step: every frame is
                // recorded and judged, the newest wins, and every-frame control solves once for
                // it instead of working through a backlog of stale frames.
                let mut next = Some(item);
                let mut taken = 0;
                while let Some(item) = next.take() {
                    taken += 1;
                    let now = clock.now_ns();
                    if let Ok((message, source_ns)) = item {
                        if let Some(r) = recorder.as_mut() {
                            r.keypoints(&config.input.keypoints_topic, now, source_ns, &message);
                        }
                        let points = message.points();
                        match core.on_stamped_keypoints(&points, source_ns, now) {
                            Verdict::New => {
                                input_rate.record(now);
                                frame_source_ns = source_ns.unwrap_or(now);
                                if auto_engage_pending && core.engage(now) {
                                    auto_engage_pending = false;
                                }
                                tick_now = config.control.mode == ControlMode::EveryFrame;
                            }
                            Verdict::Repeat => repeat_rate.record(now),
                            Verdict::Rejected(_) => {}
                        }
                    }
                    if taken < MAX_BURST_FRAMES {
                        next = keypoints.next().now_or_never().flatten();
                    }
                }
            }
            Some(Ok((pose, info))) = wrists.next() => {
                if let Some(r) = recorder.as_mut() {
                    r.input(&config.input.wrist_topic, clock.now_ns(), info.source_timestamp().map(|t| t.to_nanos()), &pose);
                }
                match pose_to_isometry(&pose.pose) {
                    Some(iso) => glove_wrist = Some(iso),
                    None => summary.wrist_rejected += 1,
                }
            }
            Some(Ok((pose, info))) = feedback.next() => {
                if let Some(r) = recorder.as_mut() {
                    r.input(&config.input.arm_feedback_topic, clock.now_ns(), info.source_timestamp().map(|t| t.to_nanos()), &pose);
                }
                robot_pose = pose_to_isometry(&pose.pose);
            }
            _ = tick.tick() => tick_now = true,
            _ = status_tick.tick() => {
                let now = clock.now_ns();
                if let Some(monitor) = &arm_monitor {
                    let publishers = monitor.get_publisher_count(node.node());
                    if publishers > 1 && !second_publisher {
                        hooks.send(StationEvent::Message(format!(
                            "warning: {} publishers on {}: refusing to drive the arm until the other stops",
                            publishers, config.output.arm_target_topic
                        )));
                    }
                    second_publisher = publishers > 1;
                    summary.second_publisher_seen |= second_publisher;
                }
                let status = json!({
                    "stamp_ns": now,
                    "state": core.state(),
                    "input_rate_hz": input_rate.rate_hz(now),
                    "repeat_rate_hz": repeat_rate.rate_hz(now),
                    "output_rate_hz": output_rate.rate_hz(now),
                    "input_age_ms": core.input_age_ns(now).map(|a| a as f64 * 1e-6),
                    "processing_latency_ms": if last_latency_ms.is_finite() { Some(last_latency_ms) } else { None },
                    "counters": core.counters(),
                    "wrist_rejected": summary.wrist_rejected,
                    // Matched readers of the commands (the station's own arm monitor is one).
                    "listeners": {
                        "hand": joint_pub.get_subscription_count(node.node()),
                        "arm": arm_pub.as_ref().map(|p| p.get_subscription_count(node.node()).saturating_sub(1)),
                    },
                    "arm": {
                        "enabled": arm_enabled,
                        "engaged": stage.arm().is_engaged(),
                        "second_publisher": second_publisher,
                        "constraint": stage.arm().constraint(),
                    },
                });
                if let Some(tx) = &hooks.status {
                    tx.send(Some(status.clone())).ok();
                }
                let status = StringMsg { data: status.to_string() };
                if let Some(r) = recorder.as_mut() {
                    r.output(&config.output.status_topic, now, &status);
                    r.tick(now);
                    if let Some(error) = r.take_error() {
                        hooks.send(StationEvent::Message(error));
                    }
                }
                status_pub.async_publish(status).await.ok();
            }
        }
        if !tick_now {
            continue;
        }
        let now = clock.now_ns();
        let started = std::time::Instant::now();
        let step = core.tick(now);
        if step.hand.as_ref().is_some_and(|h| !h.held) {
            summary
                .step_time
                .push(started.elapsed().as_secs_f64() * 1e3);
            summary.tip_error_mm.push(core.counters().last_tip_error_mm);
        }
        let outputs = stage.outputs(
            &step,
            now,
            frame_source_ns,
            glove_wrist,
            robot_pose,
            second_publisher,
        );
        for warning in stage.take_warnings() {
            hooks.send(StationEvent::Message(warning));
        }
        if let Some(message) = outputs.joint_state {
            if let Some(r) = recorder.as_mut() {
                r.output(&config.output.joint_targets_topic, now, &message);
            }
            joint_pub.async_publish(message).await.ok();
            summary.hand_commands += 1;
            output_rate.record(now);
            if let (true, Some(hand)) = (outputs.fresh_hand, &step.hand) {
                last_latency_ms = (clock.now_ns() - hand.frame_received_ns) as f64 * 1e-6;
            }
        }
        if let (Some(message), Some(publisher)) = (outputs.policy, &policy_pub) {
            if let Some(r) = recorder.as_mut() {
                r.output(&config.policy_output.topic, now, &message);
            }
            publisher.async_publish(message).await.ok();
        }
        if let (Some(message), Some(publisher)) = (outputs.arm, &arm_pub) {
            if let Some(r) = recorder.as_mut() {
                r.output(&config.output.arm_target_topic, now, &message);
            }
            publisher.async_publish(message).await.ok();
            summary.arm_targets += 1;
        }
    }
    summary.counters = core.counters().clone();
    if let Some(r) = recorder {
        finish_trial(r, clock.now_ns(), &core, &mut summary, &hooks);
    }
    Ok(summary)
}

/// Finish a trial's log with the run's totals so far; a failure is reported, never fatal.
fn finish_trial(
    recorder: StationRecorder,
    now_ns: i64,
    core: &StationCore,
    summary: &mut StationSummary,
    hooks: &StationHooks,
) {
    let totals = json!({
        "frames_new": core.counters().frames_new,
        "hand_commands": summary.hand_commands,
        "arm_targets": summary.arm_targets,
    });
    let mut recorder = recorder;
    if let Some(error) = recorder.take_error() {
        hooks.send(StationEvent::Message(error));
    }
    let path = recorder.path().to_path_buf();
    match recorder.finish(now_ns, totals) {
        Ok(finished) => {
            hooks.send(StationEvent::TrialFinished(finished.path.clone()));
            summary.recorded.push(finished.path);
        }
        Err(e) => hooks.send(StationEvent::TrialFinishFailed {
            path,
            error: format!("{e:#}"),
        }),
    }
}
