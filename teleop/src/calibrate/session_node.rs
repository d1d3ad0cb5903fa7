//! The calibration session over ROS 2: the hand shows each of the seven poses in turn, the user
//! copies it, and the glove keypoints, the commanded poses and the capture windows go into one
//! MCAP log (rosbag2-style, like a trial log) for [`fit_session`](super::fit_session).
//!
//! The session subscribes to the station's keypoint topic (type and QoS from the station
//! configuration) and publishes `sensor_msgs/JointState` on its joint-target topic, so the
//! station must not run at the same time. It starts at the first keypoint message (the glove
//! must be streaming) and then follows the [`CaptureSchedule`]: pose `k` is commanded (and
//! re-sent every 100 ms) from `k·slot_s`; its capture window is the last `capture_s` of the
//! slot. Every keypoint message received from the start is logged at its receive time.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::Duration;

use anyhow::{Context as _, bail};
use calibration::{CaptureSchedule, PoseSet};
use futures::StreamExt;
use msgs::{Float32MultiArray, JointState, PoseArray};
use retarget::HandModel;
use serde_json::json;
use tokio::sync::watch;
use tokio::time::Instant;

use crate::calibrate::session_events::{SESSION_METADATA, capture_event, pose_event};
use crate::clock::StationClock;
use crate::mcap_log::{OfferedQos, TrialWriter, TrialWriterOptions};
use crate::ros::RosNode;
use crate::ros::convert::{KeypointMessage, header};
use crate::station::station_config::{KeypointFormat, StationConfig};

/// How often the commanded pose is re-sent, seconds.
const RESEND_S: f64 = 0.1;

/// What a session needs.
#[derive(Debug, Clone)]
pub struct SessionOptions {
    /// Topics, message types, QoS, layout and network (the station's configuration).
    pub station: StationConfig,
    /// Slot and capture lengths.
    pub schedule: CaptureSchedule,
    /// The log to write (`.part` while recording).
    pub out: PathBuf,
    /// How long to wait for the first glove keypoints.
    pub glove_wait: Duration,
    /// Extra metadata for the log (user, glove, ...).
    pub metadata: BTreeMap<String, String>,
    /// Print the instructions and progress on stderr.
    pub verbose: bool,
}

/// What a session recorded.
#[derive(Debug, Clone, PartialEq)]
pub struct SessionReport {
    /// The finished log.
    pub path: PathBuf,
    /// Keypoint messages received inside each pose's capture window, in capture order.
    pub frames_per_pose: Vec<usize>,
    /// Keypoint messages logged in all.
    pub frames: u64,
}

/// One step of the schedule.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Step {
    Pose(usize),
    CaptureStart(usize),
    CaptureEnd(usize),
}

fn steps(schedule: &CaptureSchedule, poses: usize) -> Vec<(f64, Step)> {
    let mut out = Vec::with_capacity(3 * poses);
    for k in 0..poses {
        let (start, end) = schedule.capture_window(k);
        out.push((k as f64 * schedule.slot_s, Step::Pose(k)));
        out.push((start, Step::CaptureStart(k)));
        out.push((end, Step::CaptureEnd(k)));
    }
    // Stable: at a shared instant a capture ends before the next pose is commanded.
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out
}

/// Run a session; `origin` receives the session's time origin (station-clock ns) when it
/// starts (a simulated glove aligns its motion to it). Returns when the last capture window
/// closes; Ctrl-C (`shutdown`) abandons the session with an error, keeping what was logged.
pub async fn run_session(
    options: SessionOptions,
    model: &HandModel,
    clock: StationClock,
    origin: Option<watch::Sender<Option<i64>>>,
    mut shutdown: watch::Receiver<bool>,
) -> anyhow::Result<SessionReport> {
    options.schedule.validate()?;
    let config = &options.station;
    let pose_set = PoseSet::orca_v1();
    let targets: Vec<Vec<f64>> = pose_set
        .poses
        .iter()
        .map(|p| p.joint_vector(model))
        .collect::<Result<_, _>>()?;
    let names: Vec<String> = model.dof_names().map(str::to_string).collect();

    let context = config.network.context()?;
    let mut node = RosNode::new(&context, "/", "pomdar_calibration")?;
    let topic = config.input.keypoints_topic.clone();
    let (array_sub, poses_sub) = match config.input.keypoints_format {
        KeypointFormat::Float32MultiArray => (
            Some(node.subscription::<Float32MultiArray>(&topic, config.input.qos)?),
            None,
        ),
        KeypointFormat::PoseArray => (
            None,
            Some(node.subscription::<PoseArray>(&topic, config.input.qos)?),
        ),
    };
    let mut keypoints = match (&array_sub, &poses_sub) {
        (Some(sub), _) => sub
            .async_stream()
            .map(|r| r.map(|(m, i)| (KeypointMessage::Array(m), i.source_timestamp())))
            .boxed(),
        (None, Some(sub)) => sub
            .async_stream()
            .map(|r| r.map(|(m, i)| (KeypointMessage::Poses(m), i.source_timestamp())))
            .boxed(),
        (None, None) => futures::stream::pending().boxed(),
    };
    let joint_pub =
        node.publisher::<JointState>(&config.output.joint_targets_topic, config.output.qos)?;

    let mut writer = TrialWriter::create(&options.out, TrialWriterOptions::default())?;
    let input_qos = OfferedQos::from(config.input.qos);
    match config.input.keypoints_format {
        KeypointFormat::Float32MultiArray => {
            writer.add_channel::<Float32MultiArray>(&topic, &[input_qos])?
        }
        KeypointFormat::PoseArray => writer.add_channel::<PoseArray>(&topic, &[input_qos])?,
    };
    writer.add_channel::<JointState>(
        &config.output.joint_targets_topic,
        &[OfferedQos::from(config.output.qos)],
    )?;
    let mut metadata = options.metadata.clone();
    metadata.extend([
        (
            "layout".to_string(),
            config.retarget.layout.name().to_string(),
        ),
        ("keypoints_topic".to_string(), topic.clone()),
        (
            "joint_targets_topic".to_string(),
            config.output.joint_targets_topic.clone(),
        ),
        ("model".to_string(), model.name().to_string()),
        ("slot_s".to_string(), options.schedule.slot_s.to_string()),
        (
            "capture_s".to_string(),
            options.schedule.capture_s.to_string(),
        ),
        ("poses".to_string(), calibration::POSE_NAMES.join(",")),
        (
            "station_version".to_string(),
            env!("CARGO_PKG_VERSION").to_string(),
        ),
    ]);
    writer.write_metadata(SESSION_METADATA, metadata)?;

    // Start at the first glove frame.
    let waited = tokio::select! {
        first = keypoints.next() => first,
        _ = tokio::time::sleep(options.glove_wait) => None,
        _ = shutdown.changed() => None,
    };
    if waited.is_none() {
        drop(writer.finish());
        std::fs::remove_file(&options.out).ok();
        bail!(
            "no glove keypoints on {topic} within {:.0} s (domain {}): is the glove streaming?",
            options.glove_wait.as_secs_f64(),
            crate::ros::domain_id(config.network.domain_id)?
        );
    }
    let start_ns = clock.now_ns();
    let start = Instant::now();
    if let Some(origin) = &origin {
        origin.send(Some(start_ns)).ok();
    }
    writer.write_event(
        start_ns,
        &json!({"event": "start", "session": "calibration"}),
    )?;

    let schedule = steps(&options.schedule, targets.len());
    let end_s = options.schedule.duration_s(targets.len());
    let mut next = 0usize;
    let mut current: Option<usize> = None;
    let mut capturing: Option<usize> = None;
    let mut frames_per_pose = vec![0usize; targets.len()];
    let mut frames = 0u64;
    let mut resend = tokio::time::interval(Duration::from_secs_f64(RESEND_S));
    let say = |line: String| {
        if options.verbose {
            eprintln!("{line}");
        }
    };
    say(format!(
        "calibration session: {} poses, {} s each (capture the last {} s); copy the hand",
        targets.len(),
        options.schedule.slot_s,
        options.schedule.capture_s
    ));
    while next < schedule.len() {
        let (at_s, step) = schedule[next];
        let due = start + Duration::from_secs_f64(at_s.min(end_s));
        tokio::select! {
            _ = shutdown.changed() => {
                if *shutdown.borrow() {
                    let now = clock.now_ns();
                    writer.write_event(now, &json!({"event": "abort", "reason": "interrupted"}))?;
                    let finished = writer.finish()?;
                    bail!("calibration session interrupted; partial log {}", finished.path.display());
                }
            }
            item = keypoints.next() => {
                let Some(Ok((message, source))) = item else { continue };
                let now = clock.now_ns();
                let source_ns = source.map_or(now, |t| t.to_nanos());
                match &message {
                    KeypointMessage::Array(m) => writer.write(&topic, now, source_ns, m)?,
                    KeypointMessage::Poses(m) => writer.write(&topic, now, source_ns, m)?,
                }
                frames += 1;
                if let Some(k) = capturing {
                    frames_per_pose[k] += 1;
                }
            }
            _ = resend.tick() => {
                if let Some(k) = current {
                    let now = clock.now_ns();
                    let message = JointState {
                        header: header(now, ""),
                        name: names.clone(),
                        position: targets[k].clone(),
                        velocity: Vec::new(),
                        effort: Vec::new(),
                    };
                    writer.write(&config.output.joint_targets_topic, now, now, &message)?;
                    joint_pub.async_publish(message).await.ok();
                }
            }
            _ = tokio::time::sleep_until(due) => {
                let now = clock.now_ns();
                let pose = &pose_set.poses[match step {
                    Step::Pose(k) | Step::CaptureStart(k) | Step::CaptureEnd(k) => k,
                }];
                match step {
                    Step::Pose(k) => {
                        current = Some(k);
                        resend.reset_immediately();
                        writer.write_event(now, &pose_event(&pose.name, &pose.instruction))?;
                        say(format!("[{}/{}] {}: {}", k + 1, targets.len(), pose.name, pose.instruction));
                    }
                    Step::CaptureStart(k) => {
                        capturing = Some(k);
                        writer.write_event(now, &capture_event(&pose.name, true))?;
                        say(format!("      hold still: capturing {} s", options.schedule.capture_s));
                    }
                    Step::CaptureEnd(k) => {
                        capturing = None;
                        writer.write_event(now, &capture_event(&pose.name, false))?;
                        say(format!("      captured {} frames", frames_per_pose[k]));
                    }
                }
                next += 1;
            }
        }
        writer.flush_if_due(clock.now_ns())?;
    }
    writer.write_event(
        clock.now_ns(),
        &json!({"event": "stop", "summary": {"frames": frames, "frames_per_pose": frames_per_pose}}),
    )?;
    let finished = writer.finish().context("finishing the session log")?;
    Ok(SessionReport {
        path: finished.path,
        frames_per_pose,
        frames,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_schedule_ends_each_capture_before_the_next_pose() {
        let s = steps(&CaptureSchedule::default(), 7);
        assert_eq!(s.len(), 21);
        assert_eq!(s[0], (0.0, Step::Pose(0)));
        assert_eq!(s[1], (1.5, Step::CaptureStart(0)));
        assert_eq!(s[2], (2.5, Step::CaptureEnd(0)));
        assert_eq!(s[3], (2.5, Step::Pose(1)));
        assert_eq!(s[20].1, Step::CaptureEnd(6));
    }
}
