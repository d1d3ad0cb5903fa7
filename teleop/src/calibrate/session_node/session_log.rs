//! The session's MCAP log: created with its channels and metadata before the session's topics
//! are up (and removed if the session cannot start), written on a thread of its own while the
//! session records, finished for the fit (with the count of poses that could not be sent), and
//! the finished log continued when a pose is captured again after the fit.

use std::path::PathBuf;

use msgs::{Float32MultiArray, JointState, PoseArray};
use retarget::HandModel;
use serde_json::json;
use station::KeypointFormat;
use station::convert::KeypointMessage;

use crate::calibrate::pose_session::SessionTiming;
use crate::calibrate::session_events::{POSE_NOT_SENT_EVENT, SESSION_METADATA};
use crate::disk_wait::without_holding_the_runtime;
use crate::mcap_log::{
    FinishedTrial, LogError, OfferedQos, TrialWriter, TrialWriterOptions, WriterThread,
    continue_finished,
};

use super::SessionOptions;

/// Writes still queued for the session log when the fit starts from which the console says
/// that the disk is slow (half a second of a 100 Hz glove): finishing the log waits for them.
pub(super) const SLOW_DISK_QUEUE: usize = 50;

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

/// The session log until the session's topics are up: written on a thread of its own (a
/// flush waiting on the disk must not hold the frames back, or they would reach the session
/// late and in a burst, and be judged by the wrong window); removed if the session cannot
/// start.
pub(super) struct UnstartedLog {
    writer: Option<WriterThread>,
    path: PathBuf,
}

impl UnstartedLog {
    /// Creates the log at the session's `out` and starts the thread that writes it.
    pub(super) fn open(
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
    pub(super) fn started(mut self) -> Option<WriterThread> {
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
pub(super) struct SessionLog {
    /// The log, until it is finished (for the fit, or at the end).
    pub(super) writer: Option<WriterThread>,
    /// Keypoint messages logged.
    pub(super) frames: u64,
    /// The finished log.
    pub(super) path: Option<PathBuf>,
}

impl SessionLog {
    /// The log of a session that has started, written by `writer`.
    pub(super) fn new(writer: Option<WriterThread>) -> SessionLog {
        SessionLog {
            writer,
            frames: 0,
            path: None,
        }
    }

    /// A keypoint message on `topic`, logged (while the log is written) at its receive time
    /// `now` with its source time.
    pub(super) fn keypoints(
        &mut self,
        topic: &str,
        message: &KeypointMessage,
        now: i64,
        source_ns: i64,
    ) -> Result<(), LogError> {
        if let Some(w) = self.writer.as_ref() {
            let topic = topic.to_string();
            match message.clone() {
                KeypointMessage::Array(m) => {
                    w.write(move |w| w.write(&topic, now, source_ns, &m))?
                }
                KeypointMessage::Poses(m) => {
                    w.write(move |w| w.write(&topic, now, source_ns, &m))?
                }
            }
            self.frames += 1;
        }
        Ok(())
    }

    /// A pose sent to the hand on `topic`, logged (while the log is written) at `now`.
    pub(super) fn pose_sent(
        &self,
        topic: &str,
        now: i64,
        message: &JointState,
    ) -> Result<(), LogError> {
        if let Some(w) = self.writer.as_ref() {
            let (topic, logged) = (topic.to_string(), message.clone());
            w.write(move |w| w.write(&topic, now, now, &logged))?;
        }
        Ok(())
    }

    /// A session event, logged (while the log is written) at `at_ns`.
    pub(super) fn event(&self, at_ns: i64, event: serde_json::Value) -> Result<(), LogError> {
        if let Some(w) = self.writer.as_ref() {
            w.write(move |w| w.write_event(at_ns, &event))?;
        }
        Ok(())
    }

    /// A pose is captured again after the fit: the finished log is copied into a writer that
    /// replaces it when the next fit starts (the old log stays complete until then).
    pub(super) fn continue_finished(&mut self) -> Result<(), LogError> {
        let Some(path) = self.path.clone() else {
            return Ok(());
        };
        let writer = without_holding_the_runtime(|| {
            continue_finished(&path, TrialWriterOptions::default())
        })?;
        let writer = WriterThread::spawn(writer)
            .map_err(|e| LogError::io(&path, "start the thread that writes", e))?;
        self.writer = Some(writer);
        Ok(())
    }
}

/// Finishes the log, after an event counting the `poses_not_sent` on `joint_topic` (if any).
/// Waits for the log's writes without holding up the simulated user or the station.
pub(super) fn finish_log(
    w: WriterThread,
    now: i64,
    poses_not_sent: u64,
    joint_topic: &str,
) -> Result<FinishedTrial, LogError> {
    if poses_not_sent > 0 {
        let event = json!({
            "event": POSE_NOT_SENT_EVENT,
            "topic": joint_topic,
            "count": poses_not_sent,
        });
        w.write(move |w| w.write_event(now, &event))?;
    }
    without_holding_the_runtime(|| w.finish())
}
