//! Deterministic re-simulation: the one [`Station`] fed from a log, with the log's clock.
//!
//! A log the station recorded holds every input it was stepped with: each glove, wrist and
//! arm-feedback message with its receive time (log time) and its sender's stamp (publish
//! time), and each control input — timer tick, engage, disengage, second publisher on the arm
//! topic — on `/pomdar/station_control`. Re-simulating it steps a new station with exactly
//! those inputs, at exactly those times, so the same configuration reproduces the run's
//! commands byte for byte. A plain glove recording (no control channel) has no operator and no
//! timer: the station engages on its first fresh frame (as `pomdar station --engage` would) and
//! its timer ticks on the log's clock every `1 / rate_hz` from the first message. The outputs go
//! to a new log stamped with the log's clock only, so the same log and configuration give the
//! same file, byte for byte. Wall-clock step time is measured for the statistics only.

use std::collections::BTreeMap;
use std::time::Instant;

use msgs::{PoseStamped, StringMsg};
use retarget::{HandModel, KeypointLayout};
use serde::Serialize;
use station::convert::KeypointMessage;
use station::{
    ControlInput, KeypointFormat, KeypointFrame, Station, StationConfig, StationInput,
    StationOutputs,
};

use crate::mcap_log::{LogError, LoggedMessage, TrialReader, TrialWriter};
use crate::samples::Samples;
use crate::station_driver::{
    Engage, McapSink, SetupError, TickSchedule, build_station, route, set_engage, tick_period_ns,
};
use crate::station_node::control_input_log::{STATION_CONTROL_TOPIC, control_input};

/// A log that cannot be re-simulated.
#[derive(Debug, thiserror::Error)]
pub enum ResimError {
    /// Reading the log, decoding one of its messages or writing the outputs failed.
    #[error(transparent)]
    Log(#[from] LogError),
    /// The station cannot be set up (configuration, calibration profile).
    #[error(transparent)]
    Setup(#[from] SetupError),
    /// A keypoint message does not decode as the configured keypoint format.
    #[error("keypoints at log time {log_time_ns} ns: {source}")]
    Keypoints {
        /// The message's log time, ns.
        log_time_ns: i64,
        /// The decoding error (names the topic).
        #[source]
        source: LogError,
    },
    /// A recorded control input that is not one the station knows.
    #[error("{topic} at log time {log_time_ns} ns: {source}")]
    Control {
        /// The control topic.
        topic: &'static str,
        /// The message's log time, ns.
        log_time_ns: i64,
        /// The JSON error (quotes the input).
        #[source]
        source: serde_json::Error,
    },
}

/// What a re-simulation did.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct ResimStats {
    /// Keypoint messages read.
    pub frames_read: u64,
    /// New (changed, accepted) frames.
    pub frames_new: u64,
    /// Repeated frames.
    pub frames_repeated: u64,
    /// New frames with one leapt point put back (a tracker's outlier).
    pub frames_repaired: u64,
    /// Rejected frames by reason.
    pub rejected: BTreeMap<String, u64>,
    /// Hand commands written.
    pub joint_targets: u64,
    /// Arm targets written.
    pub arm_targets: u64,
    /// The keypoint layout used.
    pub layout: String,
    /// The calibration profile applied (who, when, the transform), if any.
    pub profile: Option<String>,
    /// Where the control inputs came from: "recorded" (the station's own ticks and operator
    /// commands in the log) or "log clock" (ticks every `1 / rate_hz` on the log's clock, engaged
    /// on the first fresh frame).
    pub ticks: String,
    /// Wall time of each step that retargeted a new frame, ms: p50.
    pub step_ms_p50: Option<f64>,
    /// Wall time of each step that retargeted a new frame, ms: p99.
    pub step_ms_p99: Option<f64>,
}

/// Where a log's control inputs come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InputOrigin {
    /// The station recorded the log: its control inputs are in it.
    Recorded,
    /// A glove recording: ticks on the log's clock, engaged on the first fresh frame.
    LogClock,
}

/// One input of a log with the time the station is stepped at.
#[derive(Debug, Clone, PartialEq)]
pub struct TimedInput {
    /// Receive time (log time), nanoseconds.
    pub now_ns: i64,
    /// The input.
    pub input: StationInput,
}

/// Everything a station is stepped with to re-simulate a log.
#[derive(Debug, Clone)]
pub struct LogInputs {
    /// The inputs in the order the station takes them.
    pub inputs: Vec<TimedInput>,
    /// Where the control inputs came from.
    pub origin: InputOrigin,
    /// The configuration to re-simulate with: the caller's, with the log's layout and, for a
    /// glove recording, engaging on the first fresh frame.
    pub config: StationConfig,
}

/// If the configuration names a lab layout but the log carries the other lab layout (22 vs
/// 21 points), use the log's.
pub(crate) fn layout_for(
    config: &StationConfig,
    first_frame_points: Option<usize>,
) -> KeypointLayout {
    let configured = config.retarget.layout;
    match (configured, first_frame_points) {
        (KeypointLayout::Lab22, Some(21)) => KeypointLayout::Lab21,
        (KeypointLayout::Lab21, Some(22)) => KeypointLayout::Lab22,
        _ => configured,
    }
}

pub(crate) fn keypoints(
    message: &LoggedMessage,
    format: KeypointFormat,
) -> Result<KeypointMessage, LogError> {
    Ok(match format {
        KeypointFormat::Float32MultiArray => KeypointMessage::Array(message.decode()?),
        KeypointFormat::PoseArray => KeypointMessage::Poses(message.decode()?),
    })
}

/// The station input a logged message holds, if it is one (`None` for the station's outputs
/// and other topics).
fn logged_input(
    message: &LoggedMessage,
    config: &StationConfig,
) -> Result<Option<StationInput>, ResimError> {
    let input = &config.input;
    let topic = message.topic.as_str();
    let now = message.log_time_ns;
    Ok(Some(if topic == input.keypoints_topic {
        let points = keypoints(message, input.keypoints_format)
            .map_err(|source| ResimError::Keypoints {
                log_time_ns: now,
                source,
            })?
            .points();
        // A log without sender stamps has publish time 0: the receive time stands in, as live.
        let source_ns = if message.publish_time_ns > 0 {
            message.publish_time_ns
        } else {
            now
        };
        StationInput::Keypoints(KeypointFrame { points, source_ns })
    } else if topic == input.wrist_topic {
        StationInput::Wrist(message.decode::<PoseStamped>()?.pose)
    } else if topic == input.arm_feedback_topic {
        StationInput::ArmFeedback(message.decode::<PoseStamped>()?.pose)
    } else if topic == STATION_CONTROL_TOPIC {
        let control = control_input(&message.decode::<StringMsg>()?).map_err(|source| {
            ResimError::Control {
                topic: STATION_CONTROL_TOPIC,
                log_time_ns: now,
                source,
            }
        })?;
        StationInput::Control(control)
    } else {
        return Ok(None);
    }))
}

/// The inputs of `reader`'s log for a station configured by `config`.
pub fn log_inputs(reader: &TrialReader, config: &StationConfig) -> Result<LogInputs, ResimError> {
    let mut messages: Vec<&LoggedMessage> = reader.messages().collect();
    messages.sort_by_key(|m| m.log_time_ns); // stable: file order within equal times
    let input = &config.input;
    let first_count = messages
        .iter()
        .find(|m| m.topic == input.keypoints_topic)
        .map(|m| keypoints(m, input.keypoints_format))
        .transpose()?
        .map(|k| k.points().len());
    let mut config = config.clone();
    config.retarget.layout = layout_for(&config, first_count);
    let origin = if messages.iter().any(|m| m.topic == STATION_CONTROL_TOPIC) {
        InputOrigin::Recorded
    } else {
        set_engage(&mut config, Engage::OnFirstFrame);
        InputOrigin::LogClock
    };
    let mut inputs = Vec::with_capacity(messages.len());
    for message in &messages {
        if let Some(input) = logged_input(message, &config)? {
            inputs.push(TimedInput {
                now_ns: message.log_time_ns,
                input,
            });
        }
    }
    if origin == InputOrigin::LogClock {
        inputs = with_log_clock_ticks(inputs, config.control.rate_hz);
    }
    Ok(LogInputs {
        inputs,
        origin,
        config,
    })
}

/// `inputs` with a tick every `1 / rate_hz` from the first one's time; a tick goes before the
/// inputs received after it, up to the last input.
fn with_log_clock_ticks(inputs: Vec<TimedInput>, rate_hz: f64) -> Vec<TimedInput> {
    let period_ns = tick_period_ns(rate_hz);
    let mut ticks = inputs
        .first()
        .map(|i| TickSchedule::starting_at(i.now_ns + period_ns, period_ns));
    let mut merged = Vec::with_capacity(inputs.len() * 2);
    for input in inputs {
        while let Some(t) = ticks.as_mut().and_then(|s| s.due(input.now_ns)) {
            merged.push(TimedInput {
                now_ns: t,
                input: StationInput::Control(ControlInput::Tick),
            });
        }
        merged.push(input);
    }
    merged
}

/// Re-simulate `reader`'s log through the station configured by `config`, writing the outputs
/// to `writer` (the caller finishes it).
pub fn resim(
    reader: &TrialReader,
    config: &StationConfig,
    model: HandModel,
    writer: &mut TrialWriter,
) -> Result<ResimStats, ResimError> {
    let log = log_inputs(reader, config)?;
    let (mut station, profile) = build_station(&log.config, model)?;
    let mut stats = ResimStats {
        layout: log.config.retarget.layout.name().to_string(),
        profile,
        ticks: match log.origin {
            InputOrigin::Recorded => "recorded".into(),
            InputOrigin::LogClock => "log clock".into(),
        },
        ..ResimStats::default()
    };
    let mut step_ms = Samples::default();
    let mut sink = McapSink::new(writer, &log.config);
    for TimedInput { now_ns, input } in log.inputs {
        stats.frames_read += u64::from(matches!(input, StationInput::Keypoints(_)));
        let started = Instant::now();
        let outputs = station.step(input, now_ns);
        if outputs.fresh_frame_received_ns.is_some() {
            step_ms.push(started.elapsed().as_secs_f64() * 1e3);
        }
        route(&outputs, now_ns, &mut sink)?;
    }
    stats.joint_targets = sink.hand_commands;
    stats.arm_targets = sink.arm_targets;
    let counters = station.counters();
    stats.frames_new = counters.frames_new;
    stats.frames_repeated = counters.frames_repeated;
    stats.frames_repaired = counters.frames_repaired;
    stats.rejected.clone_from(&counters.rejected);
    stats.step_ms_p50 = step_ms.percentile(0.5);
    stats.step_ms_p99 = step_ms.percentile(0.99);
    Ok(stats)
}

/// Step a station through `log` and hand each step's outputs to `visit`, with the station after
/// the step (for the command in force).
pub fn drive_station(
    station: &mut Station,
    log: LogInputs,
    mut visit: impl FnMut(&TimedInput, &StationOutputs, &Station),
) {
    for timed in log.inputs {
        let outputs = station.step(timed.input.clone(), timed.now_ns);
        visit(&timed, &outputs, station);
    }
}
