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

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use calibration::{CaptureSchedule, CaptureThresholds, FitProgress, PoseSet};
use futures::StreamExt;
use msgs::{Float32MultiArray, JointState, PoseArray};
use retarget::HandModel;
use serde_json::json;
use tokio::sync::{mpsc, watch};
use tokio::time::Instant;

use crate::calibrate::CalibrateError;
use crate::calibrate::calibration_console::{ConsoleFront, FrontAction};
use crate::calibrate::calibration_view::CalState;
use crate::calibrate::fit_session::{FitOptions, FitOutcome, fit_done, fit_session_with};
use crate::calibrate::pose_session::{
    CalibrationAction, Effect, PosePhase, PoseSession, PoseStep, SessionTiming,
};
use crate::calibrate::session_events::{POSE_NOT_SENT_EVENT, SESSION_METADATA};
use crate::clock::StationClock;
use crate::disk_wait::without_holding_the_runtime;
use crate::mcap_log::{
    FinishedTrial, LogError, OfferedQos, TrialWriter, TrialWriterOptions, WriterThread,
    continue_finished,
};
use crate::ros::RosNode;
use crate::tui::script::ScriptError;
use crate::tui::terminal::Input;
use crate::tui::terminal_shell::{Next, TurnLoop, Wakeups, run_turns};
use station::convert::{KeypointMessage, header};
use station::{KeypointFormat, StationConfig};

/// What one wake-up of the session's loop brought: the operator's actions and the session's
/// effects so far (the consoles' shared turn, [`crate::tui::terminal_shell::Turn`]).
type Turn = crate::tui::terminal_shell::Turn<CalibrationAction, Effect>;

/// How often the commanded pose is re-sent, seconds.
const RESEND_S: f64 = 0.1;

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
        log: SessionLog {
            writer: unstarted.started(),
            frames: 0,
            path: None,
        },
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

/// Each pose's joint targets, in capture order.
fn pose_targets(model: &HandModel) -> Result<Vec<Vec<f64>>, CalibrateError> {
    let pose_set = PoseSet::orca_v1();
    pose_set
        .poses
        .iter()
        .map(|p| p.joint_vector(model))
        .collect::<Result<_, _>>()
        .map_err(|source| CalibrateError::PoseTargets { source })
}

/// Creates the session log (`.part` while recording): the keypoint and joint-target
/// channels and the session's metadata.
fn open_session_log(
    options: &SessionOptions,
    model: &HandModel,
    timing: SessionTiming,
) -> Result<TrialWriter, LogError> {
    let config = &options.station;
    let topic = config.input.keypoints_topic.clone();
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
        ("settle_s".to_string(), timing.settle_s.to_string()),
        ("capture_s".to_string(), timing.capture_s.to_string()),
        ("captures_judged".to_string(), "true".to_string()),
        ("poses".to_string(), calibration::POSE_NAMES.join(",")),
        (
            "station_version".to_string(),
            env!("CARGO_PKG_VERSION").to_string(),
        ),
    ]);
    writer.write_metadata(SESSION_METADATA, metadata)?;
    Ok(writer)
}

/// The fit task's result, once it has ended (pending while there is none).
async fn joined<T>(
    task: &mut Option<tokio::task::JoinHandle<T>>,
) -> Result<T, tokio::task::JoinError> {
    match task.as_mut() {
        Some(task) => task.await,
        None => std::future::pending().await,
    }
}

/// Writes still queued for the session log when the fit starts from which the console says
/// that the disk is slow (half a second of a 100 Hz glove): finishing the log waits for them.
const SLOW_DISK_QUEUE: usize = 50;

/// The session log until the session's topics are up: written on a thread of its own (a
/// flush waiting on the disk must not hold the frames back, or they would reach the session
/// late and in a burst, and be judged by the wrong window); removed if the session cannot
/// start.
struct UnstartedLog {
    writer: Option<WriterThread>,
    path: PathBuf,
}

impl UnstartedLog {
    fn open(
        options: &SessionOptions,
        model: &HandModel,
        timing: SessionTiming,
    ) -> Result<UnstartedLog, LogError> {
        let writer = open_session_log(options, model, timing)?;
        let writer = WriterThread::spawn(writer)
            .map_err(|e| LogError::io(&options.out, "start the thread that writes", e))?;
        Ok(UnstartedLog {
            writer: Some(writer),
            path: options.out.clone(),
        })
    }

    /// The session started: the log is kept.
    fn started(mut self) -> Option<WriterThread> {
        self.writer.take()
    }
}

impl Drop for UnstartedLog {
    fn drop(&mut self) {
        if let Some(w) = self.writer.take() {
            drop(without_holding_the_runtime(|| w.finish()));
            std::fs::remove_file(&self.path).ok();
        }
    }
}

/// The session log while it is written.
struct SessionLog {
    /// The log, until it is finished (for the fit, or at the end).
    writer: Option<WriterThread>,
    /// Keypoint messages logged.
    frames: u64,
    /// The finished log.
    path: Option<PathBuf>,
}

/// The pose the hand is sent to, re-sent every [`RESEND_S`].
struct HandCommand {
    /// Each pose's joint targets.
    targets: Vec<Vec<f64>>,
    /// The hand's joint names.
    names: Vec<String>,
    /// The pose being commanded.
    current: Option<usize>,
    /// Sends of a pose that could not be published.
    not_sent: u64,
    /// When to re-send it.
    resend: tokio::time::Interval,
}

/// The fit, once the session is recorded.
struct FitRun {
    /// What to fit and where the profile goes (`session` is set to the log).
    options: FitOptions,
    /// The fit's progress, from its blocking task.
    progress_tx: mpsc::UnboundedSender<FitProgress>,
    progress_rx: mpsc::UnboundedReceiver<FitProgress>,
    /// The running fit.
    task: Option<tokio::task::JoinHandle<Result<FitOutcome, CalibrateError>>>,
    /// Set on Ctrl-C or the shutdown: the running fit stops at its next evaluation and writes
    /// no profile.
    cancel: Arc<AtomicBool>,
    /// Its result.
    outcome: Option<FitOutcome>,
}

/// How the session ends.
#[derive(Default)]
struct SessionEnd {
    /// Ctrl-C or the shutdown signal.
    interrupted: bool,
    /// A script that timed out or ended at a review.
    failure: Option<ScriptFailure>,
    /// The session quit complete.
    completed: bool,
}

/// Why a script ended the session.
enum ScriptFailure {
    /// A wait timed out.
    TimedOut(ScriptError),
    /// The script ended with a capture under review.
    EndedInReview,
}

impl ScriptFailure {
    /// What the console and the log's abort event say.
    fn reason(&self) -> String {
        match self {
            ScriptFailure::TimedOut(e) => e.to_string(),
            ScriptFailure::EndedInReview => {
                "the script ended with a capture under review: add 'retry' or 'accept'".to_string()
            }
        }
    }

    /// The session's error, naming its log.
    fn error(self, log: PathBuf) -> CalibrateError {
        match self {
            ScriptFailure::TimedOut(source) => CalibrateError::ScriptTimedOut { source, log },
            ScriptFailure::EndedInReview => CalibrateError::ScriptEndedInReview { log },
        }
    }
}

/// A running session: the pose session, its log, the hand, the fit and the console.
struct SessionRun<'a> {
    options: &'a SessionOptions,
    /// The session pose by pose (pure).
    session: PoseSession,
    log: SessionLog,
    hand: HandCommand,
    fit: FitRun,
    /// The operator's side.
    front: &'a mut ConsoleFront,
    /// The pose and attempt a simulated user follows, and the last sent.
    cue: Option<watch::Sender<Option<PoseCue>>>,
    cued: Option<PoseCue>,
    clock: StationClock,
    /// When the session started waiting for the glove.
    started: Instant,
    end: SessionEnd,
}

impl HandCommand {
    fn new(targets: Vec<Vec<f64>>, names: Vec<String>) -> HandCommand {
        HandCommand {
            targets,
            names,
            current: None,
            not_sent: 0,
            resend: tokio::time::interval(Duration::from_secs_f64(RESEND_S)),
        }
    }
}

impl FitRun {
    fn new(options: FitOptions) -> FitRun {
        let (progress_tx, progress_rx) = mpsc::unbounded_channel();
        FitRun {
            options,
            progress_tx,
            progress_rx,
            task: None,
            cancel: Arc::new(AtomicBool::new(false)),
            outcome: None,
        }
    }
}

impl SessionRun<'_> {
    /// A keypoint message: logged at its receive time `now` and given to the session.
    fn keypoints_received(
        &mut self,
        message: &KeypointMessage,
        now: i64,
        source_ns: i64,
    ) -> Result<Vec<Effect>, LogError> {
        let topic = &self.options.station.input.keypoints_topic;
        if let Some(w) = self.log.writer.as_ref() {
            let topic = topic.clone();
            match message.clone() {
                KeypointMessage::Array(m) => {
                    w.write(move |w| w.write(&topic, now, source_ns, &m))?
                }
                KeypointMessage::Poses(m) => {
                    w.write(move |w| w.write(&topic, now, source_ns, &m))?
                }
            }
            self.log.frames += 1;
        }
        Ok(self.session.frame(message.points(), now))
    }

    /// The commanded pose to send again (logged), if the hand is being sent to one.
    fn pose_to_resend(&mut self) -> Result<Option<JointState>, LogError> {
        let Some(k) = self.hand.current else {
            return Ok(None);
        };
        let config = &self.options.station;
        let now = self.clock.now_ns();
        let message = JointState {
            header: header(now, ""),
            name: self.hand.names.clone(),
            position: self.hand.targets[k].clone(),
            velocity: Vec::new(),
            effort: Vec::new(),
        };
        if let Some(w) = self.log.writer.as_ref() {
            let (topic, logged) = (config.output.joint_targets_topic.clone(), message.clone());
            w.write(move |w| w.write(&topic, now, now, &logged))?;
        }
        Ok(Some(message))
    }

    /// A pose sent to the hand, or why it could not be: a failure is counted, said in the
    /// console the first time, and logged when the log is finished.
    fn pose_sent<E: std::fmt::Display>(&mut self, sent: Result<(), E>) {
        if let Err(e) = sent {
            self.hand.not_sent += 1;
            if self.hand.not_sent == 1 {
                self.session.say(format!(
                    "cannot send the pose to the hand on {}: {e}",
                    self.options.station.output.joint_targets_topic
                ));
            }
        }
    }

    /// Finishes the log, after an event counting the poses that could not be sent (if any).
    /// Waits for the log's writes without holding up the simulated user or the station.
    fn finish_log(&self, w: WriterThread, now: i64) -> Result<FinishedTrial, LogError> {
        if self.hand.not_sent > 0 {
            let event = json!({
                "event": POSE_NOT_SENT_EVENT,
                "topic": self.options.station.output.joint_targets_topic,
                "count": self.hand.not_sent,
            });
            w.write(move |w| w.write_event(now, &event))?;
        }
        without_holding_the_runtime(|| w.finish())
    }

    /// A key: an action on the session, or Ctrl-C.
    fn key_pressed(&mut self, input: &Input, actions: &mut Vec<CalibrationAction>) {
        match ConsoleFront::key_action(input) {
            Some(FrontAction::Interrupt) => self.end.interrupted = true,
            Some(FrontAction::Act(a)) => actions.push(a),
            None => {}
        }
    }

    /// The fit task ended: its table in the console, its line and outcome to the session.
    fn fit_finished(
        &mut self,
        result: Result<Result<FitOutcome, CalibrateError>, tokio::task::JoinError>,
    ) -> Vec<Effect> {
        let fit = &self.fit.options;
        self.fit.task = None;
        let outcome = match result {
            Ok(Ok(outcome)) => Ok(outcome),
            Ok(Err(e)) => Err(e.to_string()),
            Err(e) => Err(format!("the fit task failed: {e}")),
        };
        let done = outcome
            .as_ref()
            .map(|o| fit_done(o, self.fit.outcome.as_ref(), fit))
            .map_err(Clone::clone);
        if let Ok(o) = &outcome {
            let mut lines = o.table.clone();
            lines.push(format!("profile: {}", fit.out.display()));
            self.front.set_results(lines);
        }
        self.fit.outcome = outcome.ok();
        self.session.fit_finished(done)
    }

    /// The rest of a turn after a wake-up: an interruption or a glove that never came ends
    /// the session; the script's and the operator's actions and the clock go to the session,
    /// its effects are carried out, the simulated user cued, the console shown.
    fn finish_turn(&mut self, mut turn: Turn) -> Result<Next, CalibrateError> {
        let now = self.clock.now_ns();
        if let Some(next) = self.stop_if_interrupted(now)? {
            self.front.show(&self.session, now)?;
            return Ok(next);
        }
        self.stop_if_no_glove()?;
        self.play_script(&mut turn.actions);
        for action in turn.actions {
            turn.effects.extend(self.session.act(action, now));
        }
        turn.effects.extend(self.session.tick(now));
        let mut next = self.carry_out(turn.effects)?;
        self.cue_pose();
        if next == Next::Continue {
            next = self.after_the_script();
        }
        self.front.show(&self.session, now)?;
        Ok(next)
    }

    /// Ctrl-C or the shutdown: while recording, the log is finished as aborted and the
    /// session ends with an error; during the fit, the fit is cancelled and the session waits
    /// for it to stop (at its next evaluation, writing no profile), then ends with an error
    /// naming the log (kept). After a fit that wrote its profile the session ends complete;
    /// after one that failed by itself, with the failure. `None`: not interrupted, the turn
    /// goes on.
    fn stop_if_interrupted(&mut self, now: i64) -> Result<Option<Next>, CalibrateError> {
        if !self.end.interrupted {
            return Ok(None);
        }
        if let Some(w) = self.log.writer.take() {
            let event = json!({"event": "abort", "reason": "interrupted"});
            w.write(move |w| w.write_event(now, &event))?;
            let finished = self.finish_log(w, now)?;
            return Err(CalibrateError::Interrupted { log: finished.path });
        }
        if self.fit.task.is_some() {
            if !self.fit.cancel.swap(true, Ordering::Relaxed) {
                self.session
                    .say("interrupted: stopping the fit; no profile will be written");
            }
            return Ok(Some(Next::Continue));
        }
        if self.fit.outcome.is_some() {
            self.end.completed = true;
            return Ok(Some(Next::Quit));
        }
        let log = self.log.path.clone().unwrap_or_default();
        if let (false, PosePhase::Failed(reason)) = (
            self.fit.cancel.load(Ordering::Relaxed),
            self.session.phase(),
        ) {
            return Err(CalibrateError::Failed {
                reason: reason.clone(),
                log,
            });
        }
        Err(CalibrateError::InterruptedFit { log })
    }

    /// No glove keypoints within the wait: the empty log is removed and the session ends
    /// with an error.
    fn stop_if_no_glove(&mut self) -> Result<(), CalibrateError> {
        let options = self.options;
        let config = &options.station;
        let topic = &config.input.keypoints_topic;
        if *self.session.phase() == PosePhase::WaitingGlove
            && self.started.elapsed() > options.glove_wait
        {
            if let Some(w) = self.log.writer.take() {
                drop(without_holding_the_runtime(|| w.finish()));
            }
            std::fs::remove_file(&options.out).ok();
            return Err(CalibrateError::NoGlove {
                topic: topic.clone(),
                wait_s: options.glove_wait.as_secs_f64(),
                domain: crate::ros::domain_id(config.network.domain_id)?,
            });
        }
        Ok(())
    }

    /// The script's due action; a script that timed out quits the session as a failure.
    fn play_script(&mut self, actions: &mut Vec<CalibrationAction>) {
        match self.front.script_action(CalState::of(&self.session)) {
            Ok(Some(a)) => actions.push(a),
            Ok(None) => {}
            Err(e) => {
                self.session.say(e.to_string());
                self.end.failure = Some(ScriptFailure::TimedOut(e));
                actions.push(CalibrationAction::Quit);
            }
        }
    }

    /// Carries out the session's effects: the pose to command, log events, the fit, quitting.
    fn carry_out(&mut self, effects: Vec<Effect>) -> Result<Next, CalibrateError> {
        let mut next = Next::Continue;
        for effect in effects {
            match effect {
                Effect::Command(k) => {
                    self.hand.current = Some(k);
                    self.hand.resend.reset_immediately();
                }
                Effect::Log { at_ns, event } => {
                    if let Some(w) = self.log.writer.as_ref() {
                        w.write(move |w| w.write_event(at_ns, &event))?;
                    }
                }
                Effect::ContinueLog => self.continue_log()?,
                Effect::Fit { .. } => {
                    self.hand.current = None;
                    self.start_fit()?;
                }
                Effect::Quit { completed: done } => {
                    next = Next::Quit;
                    self.end.completed = done;
                }
            }
        }
        Ok(next)
    }

    /// Every pose accepted: the log is finished and fitted in a blocking task, its progress
    /// sent back.
    fn start_fit(&mut self) -> Result<(), CalibrateError> {
        let Some(w) = self.log.writer.take() else {
            return Ok(());
        };
        let queued = w.pending();
        if queued >= SLOW_DISK_QUEUE {
            self.session.say(format!(
                "saving the session log: {queued} writes still queued (the disk is slow)"
            ));
            self.front.show(&self.session, self.clock.now_ns())?;
        }
        let finished = self
            .finish_log(w, self.clock.now_ns())
            .map_err(|source| CalibrateError::FinishLog { source })?;
        self.session
            .say(format!("session recorded: {}", finished.path.display()));
        self.fit.options.session = finished.path.clone();
        self.log.path = Some(finished.path);
        let options = self.fit.options.clone();
        let tx = self.fit.progress_tx.clone();
        let cancel = Arc::clone(&self.fit.cancel);
        self.fit.task = Some(tokio::task::spawn_blocking(move || {
            fit_session_with(
                &options,
                &mut |p| {
                    tx.send(p).ok();
                },
                &|| cancel.load(Ordering::Relaxed),
            )
        }));
        Ok(())
    }

    /// A pose is captured again after the fit: the finished log is copied into a writer that
    /// replaces it when the next fit starts (the old log stays complete until then).
    fn continue_log(&mut self) -> Result<(), CalibrateError> {
        let Some(path) = self.log.path.clone() else {
            return Ok(());
        };
        let writer = without_holding_the_runtime(|| {
            continue_finished(&path, TrialWriterOptions::default())
        })?;
        let writer = WriterThread::spawn(writer)
            .map_err(|e| LogError::io(&path, "start the thread that writes", e))?;
        self.log.writer = Some(writer);
        Ok(())
    }

    /// A simulated user is told each new pose and attempt.
    fn cue_pose(&mut self) {
        if let PosePhase::Settling { pose, attempt, .. } = *self.session.phase() {
            let now_cue = PoseCue { pose, attempt };
            if self.cued != Some(now_cue) {
                self.cued = Some(now_cue);
                if let Some(cue) = &self.cue {
                    cue.send(Some(now_cue)).ok();
                }
            }
        }
    }

    /// A script that has ended decides nothing more: a finished session ends the console,
    /// a capture left under review is an error.
    fn after_the_script(&mut self) -> Next {
        if self.front.script_finished() != Some(true) {
            return Next::Continue;
        }
        match CalState::of(&self.session) {
            CalState::Complete => {
                self.end.completed = true;
                Next::Quit
            }
            CalState::Failed => Next::Quit,
            CalState::Review => {
                let failure = ScriptFailure::EndedInReview;
                self.session.say(failure.reason());
                self.end.failure = Some(failure);
                Next::Quit
            }
            _ => Next::Continue,
        }
    }

    /// The session has quit: the log is finished (as aborted after a failure) and the
    /// session's outcome returned.
    fn finish(mut self) -> Result<SessionReport, CalibrateError> {
        let failure = self.end.failure.take();
        if let Some(w) = self.log.writer.take() {
            let now = self.clock.now_ns();
            if let Some(f) = &failure {
                let event = json!({"event": "abort", "reason": f.reason()});
                w.write(move |w| w.write_event(now, &event))?;
            }
            let finished = self.finish_log(w, now)?;
            self.log.path = Some(finished.path);
        }
        let path = self
            .log
            .path
            .take()
            .unwrap_or_else(|| self.options.out.clone());
        if let Some(failure) = failure {
            return Err(failure.error(path));
        }
        self.report(path)
    }

    /// The report of a complete session with its fit; otherwise why there is none.
    fn report(self, path: PathBuf) -> Result<SessionReport, CalibrateError> {
        let session = &self.session;
        match (self.end.completed, self.fit.outcome, session.phase()) {
            (true, Some(fit), _) => {
                let accepted = |k: usize| session.accepted(k);
                Ok(SessionReport {
                    path,
                    frames_per_pose: (0..session.poses().len())
                        .map(|k| accepted(k).map_or(0, |a| a.quality.frames))
                        .collect(),
                    captures_per_pose: session.attempts().iter().map(Vec::len).collect(),
                    frames: self.log.frames,
                    poses_not_sent: self.hand.not_sent,
                    fit,
                })
            }
            (_, _, PosePhase::Failed(reason)) => Err(CalibrateError::Failed {
                reason: reason.clone(),
                log: path,
            }),
            _ => Err(CalibrateError::Abandoned { log: path }),
        }
    }
}
