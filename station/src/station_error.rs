//! Why a station could not be built for a configuration and a hand model.

use crate::arm::ArmConfigError;
use crate::config_error::ConfigError;

/// A station that cannot be built: its configuration, the hand model, the calibration.
#[derive(Debug, thiserror::Error)]
pub enum StationError {
    /// The configuration does not validate.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// An output needs a joint the hand model lacks.
    #[error("{output}: model '{model}' has no joint '{joint}'")]
    MissingJoint {
        /// The output (`policy_output`).
        output: &'static str,
        /// The hand model.
        model: String,
        /// The joint it lacks.
        joint: String,
    },
    /// The retargeter refused the model, the configuration or the calibration.
    #[error("retargeter: {0}")]
    Retargeter(#[from] retarget::Error),
    /// The arm mapping refused its configuration.
    #[error("arm: {0}")]
    Arm(#[from] ArmConfigError),
}
