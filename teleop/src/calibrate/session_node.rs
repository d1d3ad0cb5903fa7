//! The calibration session over ROS 2, pose by pose: the hand is sent to each of the seven
//! poses (re-sent every 100 ms), the user copies it and settles, the glove is captured, the
//! capture is judged ([`super::capture_quality`]) and accepted or taken again
//! ([`PoseSession`]), and once every pose has an accepted capture the log is finished and
//! fitted ([`super::fit_session`]) with its progress in the console. The glove keypoints, the
//! commanded poses, every capture window with its quality and the decisions go into one MCAP
//! log (rosbag2-style, like a trial log; events in [`super::session_events`]).
//!
//! The session subscribes to the station's keypoint topic (type and QoS from the station
//! configuration) and publishes `sensor_msgs/JointState` on its joint-target topic, so the
//! station must not run at the same time. It starts at the first keypoint message (the glove
//! must be streaming); every keypoint message from then on is logged at its receive time.
//!
//! This file holds the session's options, [`run_session`] and its loop's wait; its parts are
//! in `session_node/`: the log (`session_log.rs`), the commanded pose (`hand_command.rs`), the
//! fit (`fit_run.rs`), the running session and its turn (`session_turn.rs`), how it ends
//! (`session_end.rs`) and its outcome (`session_outcome.rs`).

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::Duration;

use calibration::{CaptureSchedule, CaptureThresholds, PoseSet};
use futures::StreamExt;
use msgs::{Float32MultiArray, JointState, PoseArray};
use retarget::HandModel;
use tokio::sync::watch;
use tokio::time::Instant;

use crate::calibrate::CalibrateError;
use crate::calibrate::calibration_console::ConsoleFront;
use crate::calibrate::fit_session::{FitOptions, FitOutcome};
use crate::calibrate::pose_session::{
    CalibrationAction, Effect, PoseSession, PoseStep, SessionTiming,
};
use crate::clock::StationClock;
use crate::ros::RosNode;
use crate::tui::terminal_shell::{Next, TurnLoop, Wakeups, run_turns};
use station::convert::KeypointMessage;
use station::{KeypointFormat, StationConfig};

mod fit_run;
mod hand_command;
mod session_end;
mod session_log;
mod session_outcome;
mod session_turn;

use fit_run::{FitRun, joined};
use hand_command::{HandCommand, pose_targets};
use session_end::SessionEnd;
use session_log::{SessionLog, UnstartedLog};
use session_turn::{SessionRun, Turn};

/// What a session needs.
#[derive(Debug, Clone)]
pub struct SessionOptions {
    /// Topics, message types, QoS, layout and network (the station's configuration).
    pub station: StationConfig,
    /// Slot and capture lengths: each pose settles for `slot_s − capture_s`, then
    /// `capture_s` is captured.
    pub schedule: CaptureSchedule,
    /// When a capture is usable (the fit's own thresholds).
    pub thresholds: CaptureThresholds,
    /// The log to write (`.part` while recording).
    pub out: PathBuf,
    /// How long to wait for the first glove keypoints.
    pub glove_wait: Duration,
    /// Extra metadata for the log (user, glove, ...).
    pub metadata: BTreeMap<String, String>,
}

/// The pose and attempt the session is at, for a simulated user who follows the hand.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PoseCue {
    /// Index of the pose (capture order).
    pub pose: usize,
    /// 1-based attempt.
    pub attempt: u32,
}

/// What a finished session recorded and fitted.
#[derive(Debug, Clone)]
pub struct SessionReport {
    /// The finished log.
    pub path: PathBuf,
    /// Keypoint frames of each pose's accepted capture, in capture order.
    pub frames_per_pose: Vec<usize>,
    /// Captures of each pose (more than one when a pose was retried).
    pub captures_per_pose: Vec<usize>,
    /// Keypoint messages logged in all.
    pub frames: u64,
    /// Poses the hand was to be sent that could not be published (also in the log, as a
    /// `calibration_pose_not_sent` event).
    pub poses_not_sent: u64,
    /// The fit.
    pub fit: FitOutcome,
}

/// The poses of the session, with their instructions.
pub fn pose_steps() -> Vec<PoseStep> {
    PoseSet::orca_v1()
        .poses
        .into_iter()
        .map(|p| PoseStep {
            name: p.name,
            instruction: p.instruction,
        })
        .collect()
}

/// Run a session in `front` and fit it with `fit` (its `session` is set to the log); `cue`
/// follows the pose and attempt (a simulated user copies them). Returns when the profile is
/// written and the console is left; an abandoned, interrupted or failed session is an error
/// naming its log (kept).
pub async fn run_session(
    options: SessionOptions,
    model: &HandModel,
    clock: StationClock,
    cue: Option<watch::Sender<Option<PoseCue>>>,
    front: &mut ConsoleFront,
    fit: FitOptions,
    mut shutdown: watch::Receiver<bool>,
) -> Result<SessionReport, CalibrateError> {
    options
        .schedule
        .validate()
        .map_err(|source| CalibrateError::Schedule { source })?;
    let timing = SessionTiming {
        settle_s: options.schedule.slot_s - options.schedule.capture_s,
        capture_s: options.schedule.capture_s,
    };
    let config = &options.station;
    let targets = pose_targets(model)?;
    let prefix = config.output.joint_name_prefix.as_deref();
    let names = station::ros_tools::published_joint_names(model, prefix);

    // The log first: its creation waits on the disk, and frames queued meanwhile would reach
    // the session in a burst and inflate the glove's rate measured while the hand settles.
    let unstarted = UnstartedLog::open(&options, model, timing)?;
    // The glove's keypoints in, the hand's pose out, on the station's topics.
    let mut node = RosNode::join(&config.network, "/", "pomdar_calibration")?;
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
            .map(|r| r.map(|(m, i)| (KeypointMessage::Array(m), source_ns(&i))))
            .boxed(),
        (None, Some(sub)) => sub
            .async_stream()
            .map(|r| r.map(|(m, i)| (KeypointMessage::Poses(m), source_ns(&i))))
            .boxed(),
        (None, None) => futures::stream::pending().boxed(),
    };
    // Through `pomdar relay` when the station's commands go through one, as the station's own.
    let (joint_topic, joint_qos) =
        (config.robot_link).command_wire(&config.output.joint_targets_topic, config.output.qos);
    let joint_pub = node.publisher::<JointState>(&joint_topic, joint_qos)?;

    let mut run = SessionRun {
        options: &options,
        session: PoseSession::new(
            pose_steps(),
            config.retarget.layout,
            options.thresholds,
            timing,
            front.policy(),
        ),
        log: SessionLog::new(unstarted.started()),
        fit: FitRun::new(fit),
        hand: HandCommand::new(targets, names),
        front,
        cue,
        cued: None,
        clock,
        started: Instant::now(),
        end: SessionEnd::default(),
    };
    let mut turns = CalibrationLoop {
        run: &mut run,
        shutdown: &mut shutdown,
        keypoints: &mut keypoints,
        joint_pub: &joint_pub,
        wakeups: Wakeups::tick_only(),
    };
    run_turns(&mut turns).await?;
    run.finish()
}

/// The glove frame's source time, ns, when its sender stamped it.
fn source_ns(info: &ros2_client::MessageInfo) -> Option<i64> {
    info.source_timestamp().map(|t| t.to_nanos())
}

/// The session's turn loop for [`run_turns`]: what wakes it (Ctrl-C or the shutdown, a glove
/// frame, the pose's resend, the tick, a key, the fit's progress and end) around the session.
struct CalibrationLoop<'r, 'a, K> {
    run: &'r mut SessionRun<'a>,
    shutdown: &'r mut watch::Receiver<bool>,
    /// The glove's keypoint messages with their source time, ns.
    keypoints: &'r mut K,
    joint_pub: &'r ros2_client::Publisher<JointState>,
    wakeups: Wakeups,
}

impl<K, E> TurnLoop for CalibrationLoop<'_, '_, K>
where
    K: futures::Stream<Item = Result<(KeypointMessage, Option<i64>), E>> + Unpin,
{
    type Action = CalibrationAction;
    type Effect = Effect;
    type Error = CalibrateError;

    async fn wait(&mut self, turn: &mut Turn) -> Result<(), CalibrateError> {
        let run = &mut *self.run;
        let clock = run.clock;
        tokio::select! {
            changed = self.shutdown.changed(), if !run.end.interrupted => {
                if changed.is_err() || *self.shutdown.borrow() {
                    run.end.interrupted = true;
                }
            }
            item = self.keypoints.next() => {
                if let Some(Ok((message, source))) = item {
                    let now = clock.now_ns();
                    let source_ns = source.unwrap_or(now);
                    turn.effects.extend(run.keypoints_received(&message, now, source_ns)?);
                }
            }
            _ = run.hand.resend.tick() => {
                if let Some(message) = run.pose_to_resend()? {
                    run.pose_sent(self.joint_pub.async_publish(message).await);
                }
            }
            _ = self.wakeups.tick.tick() => {}
            Some(input) = run.front.next_input() => run.key_pressed(&input, &mut turn.actions),
            Some(p) = run.fit.progress_rx.recv() => run.session.fit_progressed(p),
            result = joined(&mut run.fit.task), if run.fit.task.is_some() => {
                turn.effects.extend(run.fit_finished(result));
            }
        }
        Ok(())
    }

    fn finish_turn(&mut self, turn: Turn) -> Result<Next, CalibrateError> {
        self.run.finish_turn(turn)
    }
}
