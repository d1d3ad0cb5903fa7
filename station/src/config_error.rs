//! What is wrong with a station configuration: the key, the value and what is allowed.

use crate::arm::ArmConfigError;

/// A station configuration that does not parse or does not validate.
#[derive(Debug, thiserror::Error)]
pub enum ConfigError {
    /// The TOML does not parse, or has an unknown or mistyped key (the parser's message names
    /// the line, the column and the key).
    #[error("{reason}")]
    Syntax {
        /// The parser's message.
        reason: String,
    },
    /// A value outside its allowed range, or inconsistent with another key.
    #[error("{key} = {value} must be {allowed}")]
    OutOfRange {
        /// Dotted key (`control.rate_hz`).
        key: String,
        /// The value as read.
        value: String,
        /// The allowed range or the rule it breaks.
        allowed: String,
    },
    /// The retargeting section (or the hand model it names) is not usable.
    #[error("retarget: {0}")]
    Retarget(#[from] retarget::Error),
    /// The arm section is not usable.
    #[error("arm: {0}")]
    Arm(#[from] ArmConfigError),
}

impl ConfigError {
    /// A value of `key` outside what is `allowed`.
    pub fn out_of_range(
        key: impl Into<String>,
        value: impl std::fmt::Display,
        allowed: impl Into<String>,
    ) -> ConfigError {
        ConfigError::OutOfRange {
            key: key.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }
}
