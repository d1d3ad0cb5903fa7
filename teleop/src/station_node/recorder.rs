//! Recording a station run to one MCAP log: every input as received (log time = receive time
//! on the station's clock, publish time = the sender's DDS source time), every output as sent,
//! the status, a metadata record and start/stop events on `/pomdar/trial_events`.
//!
//! The log is written as `NAME.mcap.part`, flushed at least once a second and on every event,
//! and renamed when the run ends; `pomdar recover` repairs a `.part` left by a crash. A write
//! failure is reported once (the station takes it with `take_error`) and recording continues
//! where it can: the hand is never stopped for the log's sake.

use std::collections::BTreeMap;
use std::path::PathBuf;

use msgs::RosMessage;
use serde_json::json;

use crate::mcap_log::{FinishedTrial, LogError, OfferedQos, TrialWriter, TrialWriterOptions};
use crate::station_node::error::NodeError;
use station::StationConfig;
use station::convert::KeypointMessage;

/// Where and what to record.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RecordingOptions {
    /// The final log path (`.part` is appended while recording).
    pub path: PathBuf,
    /// Trial metadata (task, user, operator, calibration_profile, trial_index, practice, ...),
    /// written as the `pomdar_trial` metadata record together with the embodiment, the layout,
    /// the station version and the configuration digest.
    pub metadata: BTreeMap<String, String>,
}

/// FNV-1a 64 of the configuration's canonical JSON: a stable digest that says whether two
/// logs were produced with the same configuration.
pub fn config_digest(config: &StationConfig) -> String {
    let text = serde_json::to_string(config).unwrap_or_default();
    let hash = crate::fnv::fnv1a_64(text.as_bytes());
    format!("fnv1a64:{hash:016x}")
}

/// The recorder of one run.
pub struct StationRecorder {
    writer: TrialWriter,
    path: PathBuf,
    failed: bool,
    /// The first write error, until taken by [`StationRecorder::take_error`].
    error: Option<NodeError>,
}

impl std::fmt::Debug for StationRecorder {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StationRecorder")
            .field("part_path", &self.writer.part_path())
            .field("failed", &self.failed)
            .finish()
    }
}

impl StationRecorder {
    /// Create the log, write the metadata and the start event.
    pub fn start(
        options: &RecordingOptions,
        config: &StationConfig,
        now_ns: i64,
    ) -> Result<StationRecorder, NodeError> {
        StationRecorder::start_flushing(options, config, now_ns, None)
    }

    /// As [`StationRecorder::start`], flushing at least every `flush_interval_ns` of log time
    /// (`None`: the writer's default, 1 s).
    pub fn start_flushing(
        options: &RecordingOptions,
        config: &StationConfig,
        now_ns: i64,
        flush_interval_ns: Option<i64>,
    ) -> Result<StationRecorder, NodeError> {
        // Synced in the background: a slow sync never keeps the messages after it from the OS.
        let mut writer_options = TrialWriterOptions {
            sync_in_background: true,
            ..TrialWriterOptions::default()
        };
        if let Some(interval) = flush_interval_ns {
            writer_options.auto_flush_interval_ns = Some(interval);
        }
        let mut writer = TrialWriter::create(&options.path, writer_options)?;
        let input_qos = OfferedQos::from(config.input.qos);
        let output_qos = OfferedQos::from(config.output.qos);
        for topic in [&config.input.keypoints_topic] {
            match config.input.keypoints_format {
                station::KeypointFormat::Float32MultiArray => {
                    writer.add_channel::<msgs::Float32MultiArray>(topic, &[input_qos])?;
                }
                station::KeypointFormat::PoseArray => {
                    writer.add_channel::<msgs::PoseArray>(topic, &[input_qos])?;
                }
            }
        }
        writer.add_channel::<msgs::PoseStamped>(&config.input.wrist_topic, &[input_qos])?;
        writer
            .add_channel::<msgs::JointState>(&config.output.joint_targets_topic, &[output_qos])?;
        let mut metadata = options.metadata.clone();
        metadata.insert("station_version".into(), env!("CARGO_PKG_VERSION").into());
        metadata.insert("config_digest".into(), config_digest(config));
        metadata.insert("embodiment".into(), config.retarget.embodiment.clone());
        metadata.insert("layout".into(), config.retarget.layout.name().into());
        // One flush for both: the first write to the OS holds the metadata and the start.
        writer.write_metadata_unflushed("pomdar_trial", metadata)?;
        writer.write_event(now_ns, &json!({ "event": "start" }))?;
        Ok(StationRecorder {
            writer,
            path: options.path.clone(),
            failed: false,
            error: None,
        })
    }

    fn check(&mut self, result: Result<(), LogError>) {
        if let Err(source) = result {
            if !self.failed {
                self.error = Some(NodeError::Recording { source });
            }
            self.failed = true;
        }
    }

    /// Record an input message.
    pub fn input<M: RosMessage>(
        &mut self,
        topic: &str,
        received_ns: i64,
        source_ns: Option<i64>,
        message: &M,
    ) {
        let result = self.writer.write(
            topic,
            received_ns,
            source_ns.unwrap_or(received_ns),
            message,
        );
        self.check(result);
    }

    /// Record a keypoint message, in whichever format it came.
    pub fn keypoints(
        &mut self,
        topic: &str,
        received_ns: i64,
        source_ns: Option<i64>,
        message: &KeypointMessage,
    ) {
        match message {
            KeypointMessage::Array(m) => self.input(topic, received_ns, source_ns, m),
            KeypointMessage::Poses(m) => self.input(topic, received_ns, source_ns, m),
        }
    }

    /// Record a control input the station was stepped with at `now_ns`.
    pub fn control(&mut self, now_ns: i64, input: station::ControlInput) {
        let message = crate::station_node::control_input_log::control_message(input);
        let result = self.writer.write(
            crate::station_node::control_input_log::STATION_CONTROL_TOPIC,
            now_ns,
            now_ns,
            &message,
        );
        self.check(result);
    }

    /// Record an output message sent at `now_ns`.
    pub fn output<M: RosMessage>(&mut self, topic: &str, now_ns: i64, message: &M) {
        let result = self.writer.write(topic, now_ns, now_ns, message);
        self.check(result);
    }

    /// Record a trial event (flushes).
    pub fn event(&mut self, now_ns: i64, event: &serde_json::Value) {
        let result = self.writer.write_event(now_ns, event);
        self.check(result);
    }

    /// Flush if a second of log time has passed since the last flush.
    pub fn tick(&mut self, now_ns: i64) {
        let result = self.writer.flush_if_due(now_ns).map(|_| ());
        self.check(result);
    }

    /// The log's final path (written as `.part` until finished).
    pub fn path(&self) -> &std::path::Path {
        &self.path
    }

    /// The first write error, once (the station reports it: stderr or the operator console).
    pub fn take_error(&mut self) -> Option<NodeError> {
        self.error.take()
    }

    /// Whether any write failed.
    pub fn failed(&self) -> bool {
        self.failed
    }

    /// Write the stop event with `summary`, the summary section, and rename the log; if the
    /// stop event cannot be written the log stays a `.part` (for `pomdar recover`). Take an
    /// earlier write error with [`StationRecorder::take_error`] first: it is not returned here.
    pub fn finish(
        mut self,
        now_ns: i64,
        summary: serde_json::Value,
    ) -> Result<FinishedTrial, NodeError> {
        self.writer
            .write_event(now_ns, &json!({ "event": "stop", "summary": summary }))?;
        Ok(self.writer.finish()?)
    }
}
