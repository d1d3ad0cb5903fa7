//! `pomdar eval`'s one error type.

use std::path::PathBuf;

use crate::mcap_log::LogError;
use crate::resim::ResimError;
use crate::station_driver::setup::SetupError;

/// A recording that cannot be evaluated.
#[derive(Debug, thiserror::Error)]
pub enum EvalError {
    /// A keypoint message does not decode as the configured keypoint format.
    #[error("keypoints at log time {log_time_ns} ns: {source}")]
    Keypoints {
        /// The message's log time, ns.
        log_time_ns: i64,
        /// The decoding error (names the topic).
        #[source]
        source: LogError,
    },
    /// The recording has no message on the keypoint topic.
    #[error("{path}: no keypoint messages on {topic}")]
    NoKeypoints {
        /// The recording.
        path: PathBuf,
        /// The configured keypoint topic.
        topic: String,
    },
    /// The calibration profile cannot be loaded.
    #[error(transparent)]
    Setup(#[from] SetupError),
    /// The retargeter refuses the model or the configuration.
    #[error("retargeter: {source}")]
    Retargeter {
        /// The retargeter's error.
        #[source]
        source: retarget::Error,
    },
    /// The retargeter refuses the calibration profile's transform.
    #[error("calibration profile: {source}")]
    Calibration {
        /// The retargeter's error.
        #[source]
        source: retarget::Error,
    },
    /// The reachability grid cannot be evaluated (the model's forward kinematics fails).
    #[error("reachability: {source}")]
    Reachability {
        /// The retargeter's error.
        #[source]
        source: retarget::Error,
    },
    /// A recorded command names a joint the model lacks.
    #[error("command joint {name:?} is not a joint of the model ({known})")]
    UnknownJoint {
        /// The joint named.
        name: String,
        /// The model's joints.
        known: String,
    },
    /// `pomdar tracking`: a joint-state message does not decode.
    #[error("{path}: {source}")]
    JointStates {
        /// The log.
        path: PathBuf,
        /// The decoding error (names the topic and the log time).
        #[source]
        source: Box<LogError>,
    },
    /// `pomdar tracking`: the log holds no measured joint state the model can read.
    #[error(
        "{path}: no measured hand state on {topic} ({found}); was the hand publishing its \
         state there while the station recorded? (`[input] hand_state_topic`, or --measured)"
    )]
    NoMeasuredStates {
        /// The log.
        path: PathBuf,
        /// The topic looked at.
        topic: String,
        /// What the log holds instead.
        found: String,
    },
    /// `pomdar tracking`: the log holds no joint command the model can read.
    #[error(
        "{path}: no joint commands on {topic} ({found}); `[output] joint_targets_topic`, or --commanded"
    )]
    NoCommands {
        /// The log.
        path: PathBuf,
        /// The topic looked at.
        topic: String,
        /// What the log holds instead.
        found: String,
    },
    /// The live path: the recording cannot be re-simulated.
    #[error(transparent)]
    LivePath(#[from] ResimError),
}
