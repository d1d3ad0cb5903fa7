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
use std::time::Duration;

use anyhow::{Context as _, bail};
use calibration::{CaptureSchedule, CaptureThresholds, PoseSet};
use futures::StreamExt;
use msgs::{Float32MultiArray, JointState, PoseArray};
use retarget::HandModel;
use serde_json::json;
use tokio::sync::{mpsc, watch};
use tokio::time::Instant;

use crate::calibrate::calibration_console::{ConsoleFront, FrontAction};
use crate::calibrate::calibration_view::CalState;
use crate::calibrate::fit_session::{FitOptions, FitOutcome, fit_session_with};
use crate::calibrate::pose_session::{Effect, Phase, PoseSession, PoseStep, SessionTiming};
use crate::calibrate::session_events::SESSION_METADATA;
use crate::clock::StationClock;
use crate::mcap_log::{OfferedQos, TrialWriter, TrialWriterOptions};
use crate::ros::NetworkContext as _;
use crate::ros::RosNode;
use station::convert::{KeypointMessage, header};
use station::{KeypointFormat, StationConfig};

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
    mut fit: FitOptions,
    mut shutdown: watch::Receiver<bool>,
) -> anyhow::Result<SessionReport> {
    options.schedule.validate()?;
    let timing = SessionTiming {
        settle_s: options.schedule.slot_s - options.schedule.capture_s,
        capture_s: options.schedule.capture_s,
    };
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

    let mut session = PoseSession::new(
        pose_steps(),
        config.retarget.layout,
        options.thresholds,
        timing,
        front.policy(),
    );
    let mut writer = Some(writer);
    let mut current: Option<usize> = None;
    let mut cued: Option<PoseCue> = None;
    let mut frames = 0u64;
    let (progress_tx, mut progress_rx) = mpsc::unbounded_channel();
    let mut fit_task: Option<tokio::task::JoinHandle<anyhow::Result<FitOutcome>>> = None;
    let mut fit_outcome: Option<FitOutcome> = None;
    let mut session_path: Option<PathBuf> = None;
    let mut resend = tokio::time::interval(Duration::from_secs_f64(RESEND_S));
    let mut tick = tokio::time::interval(Duration::from_millis(50));
    let started = Instant::now();
    let mut interrupted = false;
    let mut failure: Option<String> = None;
    let mut completed = false;
    loop {
        let mut effects = Vec::new();
        let mut actions = Vec::new();
        tokio::select! {
            changed = shutdown.changed() => {
                if changed.is_err() || *shutdown.borrow() {
                    interrupted = true;
                }
            }
            item = keypoints.next() => {
                if let Some(Ok((message, source))) = item {
                    let now = clock.now_ns();
                    if let Some(w) = writer.as_mut() {
                        let source_ns = source.map_or(now, |t| t.to_nanos());
                        match &message {
                            KeypointMessage::Array(m) => w.write(&topic, now, source_ns, m)?,
                            KeypointMessage::Poses(m) => w.write(&topic, now, source_ns, m)?,
                        }
                        frames += 1;
                    }
                    effects.extend(session.frame(message.points(), now));
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
                    if let Some(w) = writer.as_mut() {
                        w.write(&config.output.joint_targets_topic, now, now, &message)?;
                    }
                    joint_pub.async_publish(message).await.ok();
                }
            }
            _ = tick.tick() => {}
            Some(input) = front.next_input() => match ConsoleFront::key_action(&input) {
                Some(FrontAction::Interrupt) => interrupted = true,
                Some(FrontAction::Act(a)) => actions.push(a),
                None => {}
            },
            Some(p) = progress_rx.recv() => session.fit_progressed(p),
            result = async {
                match fit_task.as_mut() {
                    Some(task) => task.await,
                    None => std::future::pending().await,
                }
            }, if fit_task.is_some() => {
                fit_task = None;
                let outcome = match result {
                    Ok(Ok(outcome)) => Ok(outcome),
                    Ok(Err(e)) => Err(format!("{e:#}")),
                    Err(e) => Err(format!("the fit task failed: {e}")),
                };
                let line = outcome.as_ref().map(|o| format!("profile written: {} (user {})", fit.out.display(), o.profile.user)).map_err(Clone::clone);
                if let Ok(o) = &outcome {
                    let mut lines = o.table.clone();
                    lines.push(format!("profile: {}", fit.out.display()));
                    front.set_results(lines);
                }
                fit_outcome = outcome.ok();
                effects.extend(session.fit_finished(line));
            }
        }
        let now = clock.now_ns();
        if interrupted {
            if let Some(mut w) = writer.take() {
                w.write_event(now, &json!({"event": "abort", "reason": "interrupted"}))?;
                let finished = w.finish()?;
                bail!(
                    "calibration session interrupted; partial log {}",
                    finished.path.display()
                );
            }
            bail!(
                "calibration interrupted during the fit; the session is kept in {}: fit it again with --from",
                session_path
                    .as_ref()
                    .map_or(String::new(), |p| p.display().to_string())
            );
        }
        if *session.phase() == Phase::WaitingGlove && started.elapsed() > options.glove_wait {
            if let Some(w) = writer.take() {
                drop(w.finish());
            }
            std::fs::remove_file(&options.out).ok();
            bail!(
                "no glove keypoints on {topic} within {:.0} s (domain {}): is the glove streaming?",
                options.glove_wait.as_secs_f64(),
                crate::ros::domain_id(config.network.domain_id)?
            );
        }
        match front.script_action(CalState::of(&session)) {
            Ok(Some(a)) => actions.push(a),
            Ok(None) => {}
            Err(e) => {
                session.say(e.clone());
                failure = Some(e);
                actions.push(crate::calibrate::pose_session::CalibrationAction::Quit);
            }
        }
        for action in actions {
            effects.extend(session.act(action, now));
        }
        effects.extend(session.tick(now));
        let mut quit = false;
        for effect in effects {
            match effect {
                Effect::Command(k) => {
                    current = Some(k);
                    resend.reset_immediately();
                }
                Effect::Log { at_ns, event } => {
                    if let Some(w) = writer.as_mut() {
                        w.write_event(at_ns, &event)?;
                    }
                }
                Effect::Fit { .. } => {
                    current = None;
                    if let Some(w) = writer.take() {
                        let finished = w.finish().context("finishing the session log")?;
                        session.say(format!("session recorded: {}", finished.path.display()));
                        fit.session = finished.path.clone();
                        session_path = Some(finished.path);
                        let options = fit.clone();
                        let tx = progress_tx.clone();
                        fit_task = Some(tokio::task::spawn_blocking(move || {
                            fit_session_with(&options, &mut |p| {
                                tx.send(p).ok();
                            })
                        }));
                    }
                }
                Effect::Quit { completed: done } => {
                    quit = true;
                    completed = done;
                }
            }
        }
        if let Phase::Settling { pose, attempt, .. } = *session.phase() {
            let now_cue = PoseCue { pose, attempt };
            if cued != Some(now_cue) {
                cued = Some(now_cue);
                if let Some(cue) = &cue {
                    cue.send(Some(now_cue)).ok();
                }
            }
        }
        // A script that has ended decides nothing more: a finished session ends the console,
        // a capture left under review is an error.
        if front.script_finished() == Some(true) && !quit {
            match CalState::of(&session) {
                CalState::Complete => {
                    quit = true;
                    completed = true;
                }
                CalState::Failed => quit = true,
                CalState::Review => {
                    let e = "the script ended with a capture under review: add 'retry' or 'accept'"
                        .to_string();
                    session.say(e.clone());
                    failure = Some(e);
                    quit = true;
                }
                _ => {}
            }
        }
        front.show(&session, now)?;
        if quit {
            break;
        }
    }
    if let Some(mut w) = writer.take() {
        if failure.is_some() {
            w.write_event(
                clock.now_ns(),
                &json!({"event": "abort", "reason": failure.clone()}),
            )?;
        }
        let finished = w.finish()?;
        session_path = Some(finished.path);
    }
    let path = session_path.unwrap_or_else(|| options.out.clone());
    if let Some(reason) = failure {
        bail!("{reason}; the session log is kept in {}", path.display());
    }
    match (completed, fit_outcome, session.phase()) {
        (true, Some(fit), _) => {
            let accepted = |k: usize| session.attempts()[k].iter().find(|a| a.accepted);
            Ok(SessionReport {
                path,
                frames_per_pose: (0..session.poses().len())
                    .map(|k| accepted(k).map_or(0, |a| a.quality.frames))
                    .collect(),
                captures_per_pose: session.attempts().iter().map(Vec::len).collect(),
                frames,
                fit,
            })
        }
        (_, _, Phase::Failed(reason)) => {
            bail!(
                "{reason}; the session log is kept in {} (once the problem is fixed, fit it again with --from if every pose was accepted)",
                path.display()
            )
        }
        _ => bail!(
            "calibration session abandoned; its log is kept in {}",
            path.display()
        ),
    }
}
