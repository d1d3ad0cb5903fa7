//! The calibration crate's error type.

/// Malformed calibration data.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// The file does not parse or has an unknown key.
    #[error("invalid calibration data: {reason}")]
    Syntax {
        /// The parser's message.
        reason: String,
    },
    /// A pose that cannot be used.
    #[error("calibration pose '{pose}': {problem}")]
    BadPose {
        /// The pose (or the list of poses found).
        pose: String,
        /// What is wrong.
        problem: String,
    },
}
