//! The simulated parts' one error type: the glove node, the mock hand, the mock Franka and the
//! mock robot that starts the last two.

use crate::ros::RosError;

/// A simulated node could not be set up or could not build what it publishes.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// Joining the DDS domain, or creating the node, a publisher or a subscription, failed.
    #[error(transparent)]
    Ros(#[from] RosError),
    /// The glove's scripted motion or its hand shape is not valid.
    #[error("sim glove: {source}")]
    Glove {
        /// What is wrong, by setting.
        #[source]
        source: retarget::Error,
    },
    /// The glove's keypoint noise asked for is outside its range.
    #[error("--glove-jitter-mm {mm} must be in [0, 50] mm")]
    GloveJitter {
        /// The noise asked for, mm.
        mm: f64,
    },
    /// The station configuration's arm start pose is not a valid pose.
    #[error("arm: {source}")]
    ArmStartPose {
        /// What is wrong with it.
        #[source]
        source: station::arm::ArmConfigError,
    },
    /// The simulated robot in a MuJoCo scene failed (`--physics`).
    #[error("simulated robot: {message}")]
    Physics {
        /// What went wrong.
        message: String,
    },
    /// The simulated device's own thread or runtime could not start, or the thread ended
    /// without a result (it panicked).
    #[error("{device} thread: {source}")]
    DeviceThread {
        /// The device.
        device: String,
        /// What failed.
        #[source]
        source: std::io::Error,
    },
    /// A glove frame's keypoints do not fit a ROS point matrix.
    #[error(transparent)]
    Keypoints(#[from] msgs::Error),
}
