//! Deterministic re-simulation: the station's processing fed from a log, with the log's clock.
//!
//! Every keypoint, wrist and arm-feedback message of the input log is handed to the same
//! [`StationCore`] and [`OutputStage`] the ROS node uses, in log-time order, with its log time
//! as "now"; control ticks fall on the log's clock: every `1 / rate_hz` from the first message
//! (or on every new frame) for plain glove recordings, and at the recorded times of the
//! station's own joint targets for a log the station recorded, so re-simulating a recorded
//! run with the same configuration reproduces its joint targets exactly. The outputs go to a new log, stamped with tick times only — no wall
//! clock reaches the output, so re-simulating the same log with the same configuration gives
//! the same file, byte for byte. Wall-clock processing time is measured for the statistics
//! only.

use std::collections::BTreeMap;
use std::time::Instant;

use anyhow::Context as _;
use msgs::PoseStamped;
use nalgebra::Isometry3;
use retarget::{HandModel, KeypointLayout};
use serde::Serialize;

use crate::mcap_log::{LoggedMessage, TrialReader, TrialWriter};
use crate::ros::convert::{KeypointMessage, pose_to_isometry};
use crate::sim::samples::Samples;
use crate::station::frame_gate::Verdict;
use crate::station::output_stage::OutputStage;
use crate::station::ros_station::station_core;
use crate::station::station_config::{ControlMode, KeypointFormat, StationConfig};
use crate::station::station_core::StationCore;

/// What a re-simulation did.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct ResimStats {
    /// Keypoint messages read.
    pub frames_read: u64,
    /// New (changed, accepted) frames.
    pub frames_new: u64,
    /// Repeated frames.
    pub frames_repeated: u64,
    /// Rejected frames by reason.
    pub rejected: BTreeMap<String, u64>,
    /// Hand commands written.
    pub joint_targets: u64,
    /// Arm targets written.
    pub arm_targets: u64,
    /// The keypoint layout used.
    pub layout: String,
    /// Where the control ticks came from: "recorded" (the station's own tick times in the
    /// log) or "log clock" (a grid at `rate_hz`, or every new frame).
    pub ticks: String,
    /// Wall time of each control step that retargeted a new frame, ms: p50.
    pub step_ms_p50: Option<f64>,
    /// Wall time of each control step that retargeted a new frame, ms: p99.
    pub step_ms_p99: Option<f64>,
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
) -> anyhow::Result<KeypointMessage> {
    Ok(match format {
        KeypointFormat::Float32MultiArray => KeypointMessage::Array(message.decode()?),
        KeypointFormat::PoseArray => KeypointMessage::Poses(message.decode()?),
    })
}

struct Replayer<'w> {
    core: StationCore,
    stage: OutputStage,
    writer: &'w mut TrialWriter,
    config: StationConfig,
    frame_source_ns: i64,
    glove_wrist: Option<Isometry3<f64>>,
    robot_pose: Option<Isometry3<f64>>,
    engaged_once: bool,
    stats: ResimStats,
    step_ms: Samples,
}

impl Replayer<'_> {
    fn tick(&mut self, now_ns: i64) -> anyhow::Result<()> {
        let started = Instant::now();
        let tick = self.core.tick(now_ns);
        let outputs = self.stage.outputs(
            &tick,
            now_ns,
            self.frame_source_ns,
            self.glove_wrist,
            self.robot_pose,
            false,
        );
        for warning in self.stage.take_warnings() {
            eprintln!("{warning}");
        }
        if outputs.fresh_hand {
            self.step_ms.push(started.elapsed().as_secs_f64() * 1e3);
        }
        let out = &self.config.output;
        if let Some(m) = outputs.joint_state {
            self.writer
                .write(&out.joint_targets_topic, now_ns, now_ns, &m)?;
            self.stats.joint_targets += 1;
        }
        if let Some(m) = outputs.policy {
            self.writer
                .write(&self.config.policy_output.topic, now_ns, now_ns, &m)?;
        }
        if let Some(m) = outputs.arm {
            self.writer
                .write(&out.arm_target_topic, now_ns, now_ns, &m)?;
            self.stats.arm_targets += 1;
        }
        Ok(())
    }
}

/// Re-simulate `reader`'s glove input through the station configured by `config`, writing
/// the outputs to `writer` (the caller finishes it).
pub fn resim(
    reader: &TrialReader,
    config: &StationConfig,
    model: HandModel,
    writer: &mut TrialWriter,
) -> anyhow::Result<ResimStats> {
    let mut messages: Vec<&LoggedMessage> = reader.messages().collect();
    messages.sort_by_key(|m| m.log_time_ns); // stable: file order within equal times
    let input = &config.input;
    let format = input.keypoints_format;
    let first_count = messages
        .iter()
        .find(|m| m.topic == input.keypoints_topic)
        .map(|m| keypoints(m, format))
        .transpose()?
        .map(|k| k.points().len());
    let mut config = config.clone();
    config.retarget.layout = layout_for(&config, first_count);
    let core = station_core(&config, model.clone())?;
    let stage = OutputStage::new(&config, &model)?;
    let mut r = Replayer {
        core,
        stage,
        writer,
        config: config.clone(),
        frame_source_ns: 0,
        glove_wrist: None,
        robot_pose: None,
        engaged_once: false,
        stats: ResimStats {
            layout: config.retarget.layout.name().to_string(),
            ..ResimStats::default()
        },
        step_ms: Samples::default(),
    };
    // A log the station recorded carries its tick times: the joint targets' log times.
    let recorded_ticks: Vec<i64> = messages
        .iter()
        .filter(|m| m.topic == config.output.joint_targets_topic)
        .map(|m| m.log_time_ns)
        .collect();
    let replay_ticks = !recorded_ticks.is_empty();
    r.stats.ticks = if replay_ticks {
        "recorded".into()
    } else {
        "log clock".into()
    };
    let mut recorded = recorded_ticks.into_iter().peekable();
    let period_ns = (1e9 / config.control.rate_hz).round() as i64;
    let mut next_tick = messages.first().map(|m| m.log_time_ns + period_ns);
    for message in &messages {
        let now = message.log_time_ns;
        if replay_ticks {
            while let Some(t) = recorded.next_if(|t| *t < now) {
                r.tick(t)?;
            }
        } else if config.control.mode == ControlMode::Rate {
            while let Some(t) = next_tick.filter(|t| *t <= now) {
                r.tick(t)?;
                next_tick = Some(t + period_ns);
            }
        }
        if message.topic == input.keypoints_topic {
            r.stats.frames_read += 1;
            let points = keypoints(message, format)
                .with_context(|| format!("keypoints at log time {now} ns"))?
                .points();
            let source_ns = (message.publish_time_ns > 0).then_some(message.publish_time_ns);
            match r.core.on_stamped_keypoints(&points, source_ns, now) {
                Verdict::New => {
                    r.frame_source_ns = if message.publish_time_ns > 0 {
                        message.publish_time_ns
                    } else {
                        now
                    };
                    if !r.engaged_once {
                        r.engaged_once = r.core.engage(now);
                    }
                    if config.control.mode == ControlMode::EveryFrame && !replay_ticks {
                        r.tick(now)?;
                    }
                }
                Verdict::Repeat | Verdict::Rejected(_) => {}
            }
        } else if message.topic == input.wrist_topic {
            r.glove_wrist = pose_to_isometry(&message.decode::<PoseStamped>()?.pose);
        } else if message.topic == input.arm_feedback_topic {
            r.robot_pose = pose_to_isometry(&message.decode::<PoseStamped>()?.pose);
        }
    }
    for t in recorded {
        r.tick(t)?;
    }
    let counters = r.core.counters().clone();
    r.stats.frames_new = counters.frames_new;
    r.stats.frames_repeated = counters.frames_repeated;
    r.stats.rejected = counters.rejected;
    r.stats.step_ms_p50 = r.step_ms.percentile(0.5);
    r.stats.step_ms_p99 = r.step_ms.percentile(0.99);
    Ok(r.stats)
}
