//! The node's trial log: starting a trial's log (with the keypoint source in its metadata and
//! the latched messages) and finishing it with the run's totals, the recorder thread's reports
//! turned into events for the operator, copies of inputs and outputs queued for the log, and
//! the node's end: the open trial finished, the recorder thread joined, the summary returned.

use std::sync::Arc;

use serde_json::json;
use station::StationConfig;
use tokio::sync::mpsc;

use super::{StationNode, StationSummary};
use crate::station_node::operator::StationEvent;
use crate::station_node::recorder::RecordingOptions;
use crate::station_node::recorder_thread::LogReport;

impl StationNode {
    /// Start a trial's log (the open one finished first) with the keypoint source in its
    /// metadata and the latched messages in it.
    pub(super) fn start_trial(&mut self, options: &RecordingOptions, now: i64) {
        self.finish_trial(now);
        let options = with_source(options, self.keypoint_source.as_ref(), &self.config);
        let flush = self.hooks.trial_log_flush_interval_ns;
        self.log
            .start(options, Arc::clone(&self.config), now, flush);
        self.record_latched(now);
    }

    /// Finish the current trial's log with the run's totals so far (on the recorder thread:
    /// its outcome comes back as a [`LogReport`]).
    pub(super) fn finish_trial(&mut self, now_ns: i64) {
        if !self.log.is_open() {
            return;
        }
        let totals = self.station.totals();
        let summary = json!({
            "frames_new": self.station.counters().frames_new,
            "hand_commands": totals.hand_commands,
            "arm_targets": totals.arm_targets,
            "held_commands": totals.held_commands,
            "log_dropped": self.log.dropped_in_log(),
        });
        self.log.finish(now_ns, summary);
    }

    /// What the recorder thread did, for the operator.
    pub(super) fn on_log_report(&mut self, report: LogReport) {
        let event = match report {
            LogReport::Started(path) => StationEvent::TrialStarted(path),
            LogReport::StartFailed {
                path,
                started,
                error,
            } => {
                self.log.start_failed(started);
                StationEvent::TrialStartFailed {
                    path,
                    error: error.to_string(),
                }
            }
            LogReport::WriteFailed(error) => StationEvent::Message(format!("error: {error}")),
            LogReport::Finished(finished) => {
                self.recorded.push(finished.path.clone());
                StationEvent::TrialFinished(finished.path)
            }
            LogReport::FinishFailed { path, error } => StationEvent::TrialFinishFailed {
                path,
                error: error.to_string(),
            },
        };
        self.hooks.send(event);
    }

    /// Queue a copy of an input `message` on `topic` for the log.
    pub(super) fn log_input<M: msgs::RosMessage + Clone + Send + 'static>(
        &mut self,
        topic: &str,
        now: i64,
        source_ns: Option<i64>,
        message: &M,
    ) {
        if self.log.is_open() {
            let (topic, message) = (topic.to_string(), message.clone());
            self.log
                .write(move |r| r.input(&topic, now, source_ns, &message));
        }
    }

    /// Queue a copy of an output `message` on `topic` for the log.
    pub(super) fn log_output<M: msgs::RosMessage + Clone + Send + 'static>(
        &mut self,
        topic: &str,
        now: i64,
        message: &M,
    ) {
        if self.log.is_open() {
            let (topic, message) = (topic.to_string(), message.clone());
            self.log.write(move |r| r.output(&topic, now, &message));
        }
    }

    /// Finishes the open trial and waits for the recorder thread to write everything queued.
    pub(super) async fn finish(
        mut self,
        mut log_reports: mpsc::UnboundedReceiver<LogReport>,
    ) -> StationSummary {
        self.finish_trial(self.clock.now_ns());
        if let Some(thread) = self.log.close() {
            // A panic in the thread has already been printed; its log stays a `.part`.
            let _ = tokio::task::spawn_blocking(move || thread.join()).await;
        }
        while let Ok(report) = log_reports.try_recv() {
            self.on_log_report(report);
        }
        self.faults.log_dropped = self.log.dropped_total();
        StationSummary {
            counters: self.station.counters().clone(),
            totals: self.station.totals().clone(),
            faults: self.faults,
            second_publisher_seen: self.second_publisher_seen,
            longest_input_gap: self.station.longest_input_gap(),
            step_time: self.step_time,
            tip_error_mm: self.tip_error_mm,
            recorded: self.recorded,
        }
    }
}

/// `options` with the keypoint source in its metadata (`keypoint_source`, `keypoint_device`),
/// unless the caller set them: `source`, or `unknown` before an ingress named one.
pub(super) fn with_source(
    options: &RecordingOptions,
    source: Option<&(String, String)>,
    config: &StationConfig,
) -> RecordingOptions {
    let mut options = options.clone();
    let (kind, device) = source.cloned().unwrap_or_else(|| {
        let topic = &config.input.ingress_status_topic;
        (
            "unknown".into(),
            format!("no source named on '{topic}' yet"),
        )
    });
    options
        .metadata
        .entry("keypoint_source".into())
        .or_insert(kind);
    options
        .metadata
        .entry("keypoint_device".into())
        .or_insert(device);
    options
}
