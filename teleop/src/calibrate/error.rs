//! The calibration's one error type.
//!
//! Errors about a session log name the file, and the pose when one is missing or refused;
//! a session that ends without a profile names the log it kept.

use std::path::PathBuf;

use crate::atomic_file::AtomicWriteError;
use crate::mcap_log::LogError;
use crate::ros::RosError;
use crate::tui::TuiError;
use crate::tui::script::{ScriptError, WordError};

/// A session log could not be read or fitted, a profile not written, a session not run to
/// its end, or a flag, script word or simulated user was refused.
#[derive(Debug, thiserror::Error)]
pub enum CalibrateError {
    /// A log without the session's metadata record.
    #[error("{file}: no '{record}' metadata record: not a calibration session log")]
    NotASession {
        /// The log.
        file: PathBuf,
        /// The metadata record's name.
        record: &'static str,
    },
    /// The session's metadata record lacks a key.
    #[error("{file}: metadata '{record}' has no '{key}'")]
    MissingMetadata {
        /// The log.
        file: PathBuf,
        /// The metadata record's name.
        record: &'static str,
        /// The key.
        key: String,
    },
    /// The session's keypoint layout is not one the station knows.
    #[error("{file}: unknown keypoint layout '{layout}': {source}")]
    UnknownLayout {
        /// The log.
        file: PathBuf,
        /// The layout's name as recorded.
        layout: String,
        /// The parser's error.
        #[source]
        source: serde_json::Error,
    },
    /// A capture window closes without having opened.
    #[error("{file}: capture of pose '{pose}' ends at {at_ns} ns without a start")]
    CaptureWithoutStart {
        /// The log.
        file: PathBuf,
        /// The pose.
        pose: String,
        /// The closing event's log time, ns.
        at_ns: i64,
    },
    /// A pose without an accepted capture (an interrupted session).
    #[error(
        "{file}: no accepted capture window for pose '{pose}' (was the session interrupted?): record the session again"
    )]
    NoCaptureWindow {
        /// The log.
        file: PathBuf,
        /// The pose.
        pose: &'static str,
    },
    /// The session was recorded with another keypoint layout than the station's.
    #[error(
        "{file}: recorded with keypoint layout '{recorded}', but the station configuration uses '{station}': pass the station's --config"
    )]
    LayoutMismatch {
        /// The log.
        file: PathBuf,
        /// The session's layout.
        recorded: &'static str,
        /// The station's layout.
        station: &'static str,
    },
    /// The session was recorded for another hand model.
    #[error("{file}: recorded for model '{recorded}', the station runs '{station}'")]
    ModelMismatch {
        /// The log.
        file: PathBuf,
        /// The session's model.
        recorded: String,
        /// The station's model.
        station: String,
    },
    /// A pose's capture was refused (its message names the pose and what to do).
    #[error("{file}: {source}")]
    CaptureRefused {
        /// The log.
        file: PathBuf,
        /// The capture check's error.
        #[source]
        source: calibration::Error,
    },
    /// The fit failed.
    #[error("{file}: calibration failed: {source}")]
    Fit {
        /// The log.
        file: PathBuf,
        /// The fit's error.
        #[source]
        source: calibration::Error,
    },
    /// The fitted profile does not validate.
    #[error("the fitted profile is invalid: {source}")]
    InvalidProfile {
        /// The validation's error.
        #[source]
        source: calibration::Error,
    },
    /// The profile cannot be written as TOML.
    #[error("cannot write the profile as TOML: {source}")]
    ProfileToml {
        /// The encoder's error.
        #[source]
        source: calibration::Error,
    },
    /// The profile file cannot be written.
    #[error(transparent)]
    WriteProfile(#[from] AtomicWriteError),
    /// `--user` cannot name the default profile file.
    #[error("--user '{user}' cannot name a file (use letters, digits, '_', '-', '.'): give --out")]
    UserNotAFileName {
        /// The user's name.
        user: String,
    },
    /// The capture schedule is out of range.
    #[error("{source}")]
    Schedule {
        /// The check's error.
        #[source]
        source: calibration::Error,
    },
    /// A pose's joint targets cannot be computed for the hand model.
    #[error("{source}")]
    PoseTargets {
        /// The pose set's error.
        #[source]
        source: calibration::Error,
    },
    /// The session log could not be written, finished or read.
    #[error(transparent)]
    Log(#[from] LogError),
    /// The session log could not be finished before the fit.
    #[error("finishing the session log: {source}")]
    FinishLog {
        /// The log's error.
        #[source]
        source: LogError,
    },
    /// The session's node, subscription or publisher could not be created.
    #[error(transparent)]
    Ros(#[from] RosError),
    /// The full-screen console failed, or a `--script` file cannot be read or parsed.
    #[error(transparent)]
    Console(#[from] TuiError),
    /// No glove keypoints arrived in time (the empty log is removed).
    #[error(
        "no glove keypoints on {topic} within {wait_s:.0} s (domain {domain}): is the glove streaming?"
    )]
    NoGlove {
        /// The keypoint topic.
        topic: String,
        /// How long the session waited, s.
        wait_s: f64,
        /// The ROS domain id.
        domain: u16,
    },
    /// Ctrl-C or the shutdown while recording.
    #[error("calibration session interrupted; partial log {log}")]
    Interrupted {
        /// The partial log (finished, with an abort event).
        log: PathBuf,
    },
    /// Ctrl-C or the shutdown during the fit of a session just recorded: no profile written.
    #[error(
        "calibration interrupted (Ctrl-C) during the fit: no profile written; the session is kept in {log}: fit it again with --from"
    )]
    InterruptedFit {
        /// The session log.
        log: PathBuf,
    },
    /// Ctrl-C during the fit of a recorded session (`--from`): no profile written.
    #[error("calibration interrupted (Ctrl-C): no profile written; fit {file} again with --from")]
    FitInterrupted {
        /// The session log being fitted.
        file: PathBuf,
    },
    /// The Ctrl-C handler cannot be installed.
    #[error("cannot install the Ctrl-C handler: {reason}")]
    CtrlC {
        /// The handler crate's error.
        reason: String,
    },
    /// A script's wait timed out.
    #[error("{source}; the session log is kept in {log}")]
    ScriptTimedOut {
        /// The wait that timed out.
        #[source]
        source: ScriptError,
        /// The session log.
        log: PathBuf,
    },
    /// The script ended while a capture waited for a decision.
    #[error(
        "the script ended with a capture under review: add 'retry' or 'accept'; the session log is kept in {log}"
    )]
    ScriptEndedInReview {
        /// The session log.
        log: PathBuf,
    },
    /// The session failed (the fit's message).
    #[error(
        "{reason}; the session log is kept in {log} (once the problem is fixed, fit it again with --from if every pose was accepted)"
    )]
    Failed {
        /// Why.
        reason: String,
        /// The session log.
        log: PathBuf,
    },
    /// The operator quit before the profile was written.
    #[error("calibration session abandoned; its log is kept in {log}")]
    Abandoned {
        /// The session log.
        log: PathBuf,
    },
    /// An unknown word in a calibration script, or an argument to a word that takes none.
    #[error(transparent)]
    Word(#[from] WordError),
    /// `--hand-scale` out of range.
    #[error("--hand-scale {hand_scale} must be in [0.5, 2]")]
    HandScale {
        /// The value given.
        hand_scale: f64,
    },
    /// A `--glove-rpy` angle out of range.
    #[error("--glove-rpy angle {angle}° must be in [-45, 45] degrees")]
    GloveAngle {
        /// The angle given, degrees.
        angle: f64,
    },
    /// The reference hand's calibration (for the simulated user's true transform) failed.
    #[error("calibrating the reference hand: {source}")]
    ReferenceHand {
        /// The fit's error.
        #[source]
        source: calibration::Error,
    },
    /// `--simulate` with a station configuration whose keypoints are not an array.
    #[error(
        "--simulate publishes Float32MultiArray keypoints: the station configuration must use input.keypoints_format = \"float32_multi_array\""
    )]
    SimulateNeedsArray,
    /// The human versions of the poses cannot be made.
    #[error("the human copies of the poses: {source}")]
    HumanCopies {
        /// The error.
        #[source]
        source: calibration::Error,
    },
    /// The simulated glove cannot be made.
    #[error("simulated glove: {source}")]
    SimulatedGlove {
        /// The error.
        #[source]
        source: calibration::Error,
    },
    /// A simulated keypoint frame cannot be made into a message.
    #[error("{source}")]
    KeypointMessage {
        /// The message's error.
        #[source]
        source: msgs::Error,
    },
}

impl CalibrateError {
    /// Whether the session or its fit was interrupted (Ctrl-C or the shutdown), rather than
    /// failing: the command's exit status is then 130.
    pub fn is_interrupted(&self) -> bool {
        matches!(
            self,
            CalibrateError::Interrupted { .. }
                | CalibrateError::InterruptedFit { .. }
                | CalibrateError::FitInterrupted { .. }
        )
    }
}
