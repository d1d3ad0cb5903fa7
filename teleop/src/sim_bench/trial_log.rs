//! A recorded run written as a live station writes its trial log: the glove's keypoints and
//! wrist pose as the station received them, the hand's joint targets as it sent them, the
//! metadata record and the trial events, through the station's own recorder. `pomdar score`
//! scores it, `pomdar replay` replays it, Foxglove opens it.

use std::collections::BTreeMap;
use std::path::Path;

use msgs::{Float32MultiArray, PoseStamped};
use serde_json::{Value, json};
use station::{HandMessages, Notice, StationConfig, StationInput, StationOutputs};

use super::error::BenchError;
use super::trial_events::{RUN_EPOCH_NS, UNFINISHED_REASON, log_ns, progress_event};
use crate::physics::lockstep::LockstepObserver;
use crate::stand_ins::progress_message::ProgressMessage;
use crate::station_driver::{OutputSink, route};
use crate::station_node::recorder::{RecordingOptions, StationRecorder};

/// Writes one run's trial log while it plays.
pub struct TrialLogWriter<'a> {
    recorder: StationRecorder,
    config: &'a StationConfig,
}

impl<'a> TrialLogWriter<'a> {
    /// Starts the log at `path` with `metadata` (the recorder adds the station's version,
    /// configuration digest, embodiment and layout) and the start event.
    pub fn start(
        path: &Path,
        config: &'a StationConfig,
        metadata: BTreeMap<String, String>,
    ) -> Result<TrialLogWriter<'a>, BenchError> {
        let options = RecordingOptions {
            path: path.to_path_buf(),
            metadata,
        };
        let recorder = StationRecorder::start(&options, config, log_ns(0.0))
            .map_err(|e| BenchError::Setup(format!("trial log {}: {e}", path.display())))?;
        Ok(TrialLogWriter { recorder, config })
    }

    /// Ends the log: `stop` at the completion, or `abort` and `stop` at `end_s`.
    pub fn finish(mut self, completed_at_s: Option<f64>, end_s: f64) -> Result<(), BenchError> {
        let path = self.recorder.path().to_path_buf();
        let failed = |e: String| BenchError::Setup(format!("trial log {}: {e}", path.display()));
        let (at, summary) = match completed_at_s {
            Some(t) => (t, "completed"),
            None => {
                let abort = json!({"event": "abort", "reason": UNFINISHED_REASON});
                self.recorder.event(log_ns(end_s), &abort);
                (end_s, "unfinished")
            }
        };
        if let Some(error) = self.recorder.take_error() {
            return Err(failed(error.to_string()));
        }
        self.recorder
            .finish(log_ns(at), Value::from(summary))
            .map(drop)
            .map_err(|e| failed(e.to_string()))
    }
}

impl LockstepObserver for TrialLogWriter<'_> {
    fn input(&mut self, now_ns: i64, input: &StationInput) {
        let t = RUN_EPOCH_NS + now_ns;
        match input {
            StationInput::Keypoints(frame) => {
                let rows: Vec<[f32; 3]> = frame
                    .points
                    .iter()
                    .map(|p| [p.x as f32, p.y as f32, p.z as f32])
                    .collect();
                if let Ok(array) = Float32MultiArray::from_points(&rows) {
                    self.recorder
                        .input(&self.config.input.keypoints_topic, t, Some(t), &array);
                }
            }
            StationInput::Wrist(pose) => {
                let message = PoseStamped {
                    header: station::convert::header(t, "coil"),
                    pose: *pose,
                };
                self.recorder
                    .input(&self.config.input.wrist_topic, t, Some(t), &message);
            }
            StationInput::ArmFeedback(_) | StationInput::Control(_) => {}
        }
        self.recorder.tick(t);
    }

    fn outputs(&mut self, now_ns: i64, outputs: &StationOutputs) {
        let Ok(()) = route(outputs, RUN_EPOCH_NS + now_ns, self);
    }

    fn progress(&mut self, event: &ProgressMessage) {
        self.recorder
            .event(log_ns(event.sim_time_s), &progress_event(event));
    }
}

/// The run's log takes the hand's joint targets as the station sent them (what `pomdar score`
/// and `pomdar replay` read); the run's notices reach the operator through its progress, and
/// its arm is not logged.
impl OutputSink for TrialLogWriter<'_> {
    type Error = std::convert::Infallible;

    fn notice(&mut self, _notice: &Notice) -> Result<(), Self::Error> {
        Ok(())
    }

    fn hand(&mut self, log_ns: i64, hand: &HandMessages, _fresh: bool) -> Result<(), Self::Error> {
        let topic = &self.config.output.joint_targets_topic;
        self.recorder.output(topic, log_ns, &hand.joint_state);
        Ok(())
    }

    fn arm(&mut self, _log_ns: i64, _arm: &PoseStamped) -> Result<(), Self::Error> {
        Ok(())
    }
}
