//! The station node's one error type: what stops it starting (the station's setup, its
//! endpoints, its recorder), and its recorder's own failures.

use crate::mcap_log::LogError;
use crate::ros::RosError;
use crate::station_driver::setup::SetupError;

/// The station node could not start, or its recorder failed.
#[derive(Debug, thiserror::Error)]
pub enum NodeError {
    /// The station cannot be set up from its configuration and calibration profile.
    #[error(transparent)]
    Setup(#[from] SetupError),
    /// Joining the DDS domain, or creating the node, a publisher or a subscription, failed.
    #[error(transparent)]
    Ros(#[from] RosError),
    /// A trial log could not be created or finished.
    #[error(transparent)]
    Log(#[from] LogError),
    /// The thread that writes the trial logs could not be started.
    #[error("cannot start the recorder thread: {source}")]
    RecorderThread {
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
    /// A write to a running trial's log failed; the station keeps running.
    #[error("recording: {source} (the station keeps running; the log may be incomplete)")]
    Recording {
        /// The log's error.
        #[source]
        source: LogError,
    },
}
