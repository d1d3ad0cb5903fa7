//! What the process that runs a station tells it (the operator's commands), and what the
//! station tells that process back (trial logs, messages), besides its ROS topics.

use std::sync::Arc;
use std::sync::atomic::{AtomicI64, Ordering};

use tokio::sync::{mpsc, watch};

use crate::station_node::recorder::RecordingOptions;
use crate::station_node::tap::Tap;

/// What the operator (console, test, demo) tells a running station.
#[derive(Debug, Clone, PartialEq)]
pub enum OperatorCommand {
    /// Engage: drive hand and arm once input is fresh.
    Engage,
    /// Disengage: stop driving the arm; the hand holds.
    Disengage,
    /// A trial event for the log (`/pomdar/trial_events`, flushed at once), e.g.
    /// `{"event": "progress", "value": 1}`, `{"event": "drop"}`, `{"event": "abort"}`,
    /// `{"event": "note", "text": "..."}`. The station adds the event's time.
    TrialEvent(serde_json::Value),
    /// Start recording a new trial to its own log (finishing the current one, if any).
    StartTrial(RecordingOptions),
    /// Finish the current trial's log (stop event, summary, rename from `.part`).
    StopTrial,
}

/// What a running station reports to the process that runs it (the operator console), besides
/// its ROS topics. Without hooks the messages go to stderr.
#[derive(Debug, Default)]
pub struct StationHooks {
    /// The status JSON, as published on the status topic, at the status rate.
    pub status: Option<watch::Sender<Option<serde_json::Value>>>,
    /// Trial log starts and ends, and messages for the operator.
    pub events: Option<mpsc::UnboundedSender<StationEvent>>,
    /// A copy of every message the station publishes, for a live viewer (`--view`).
    pub tap: Option<Tap>,
    /// The robot's URDF text, published on `/robot_description` (latched) when given.
    pub robot_description: Option<String>,
    /// Set to the receive time of every new glove frame, for a console in this process.
    pub latest_input: Option<LatestInput>,
    /// The trial logs started by [`OperatorCommand::StartTrial`] flush at least this often,
    /// ns of log time (`None`: the log writer's default, 1 s).
    pub trial_log_flush_interval_ns: Option<i64>,
}

/// A station event for the process that runs it.
#[derive(Debug, Clone, PartialEq)]
pub enum StationEvent {
    /// A trial log was created (its final path).
    TrialStarted(std::path::PathBuf),
    /// A trial log could not be created.
    TrialStartFailed {
        /// The log that was asked for.
        path: std::path::PathBuf,
        /// Why.
        error: String,
    },
    /// A trial log was finished and renamed to its final path.
    TrialFinished(std::path::PathBuf),
    /// A trial log could not be finished (its `.part` stays for `pomdar recover`).
    TrialFinishFailed {
        /// The log.
        path: std::path::PathBuf,
        /// Why.
        error: String,
    },
    /// A warning or error for the operator.
    Message(String),
    /// A ROS service asked for a trial action (start, stop, abort): the console carries it
    /// out as the operator's own key (engage and disengage the station does itself).
    ServiceRequest(station::ros_tools::ServiceAction),
}

impl StationHooks {
    /// Send `event` to the hooks, or print it on stderr without them.
    pub fn send(&self, event: StationEvent) {
        match &self.events {
            Some(tx) => {
                tx.send(event).ok();
            }
            None => match event {
                StationEvent::TrialStartFailed { path, error } => {
                    eprintln!("error: cannot start recording {}: {error}", path.display());
                }
                StationEvent::TrialFinishFailed { error, .. } => {
                    eprintln!("error: cannot finish the trial log: {error}");
                }
                StationEvent::Message(text) => eprintln!("{text}"),
                StationEvent::TrialStarted(_)
                | StationEvent::TrialFinished(_)
                | StationEvent::ServiceRequest(_) => {}
            },
        }
    }
}

/// The receive time of the station's newest new glove frame, on the station's clock, shared
/// with a console in the same process. Exact at any moment, where the status's
/// `input_age_ms` is as old as the status (up to one status period, 200 ms at 5 Hz): a
/// console that added the time since the status to it would call a healthy glove stale just
/// before each status.
#[derive(Debug, Clone)]
pub struct LatestInput(Arc<AtomicI64>);

impl Default for LatestInput {
    fn default() -> Self {
        LatestInput(Arc::new(AtomicI64::new(i64::MIN)))
    }
}

impl LatestInput {
    /// A new frame was received at `received_ns`.
    pub fn record(&self, received_ns: i64) {
        self.0.store(received_ns, Ordering::Release);
    }

    /// The newest new frame's receive time; `None` before any.
    pub fn get(&self) -> Option<i64> {
        let ns = self.0.load(Ordering::Acquire);
        (ns != i64::MIN).then_some(ns)
    }
}
