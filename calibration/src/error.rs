//! The calibration crate's error type.

/// Why a calibration input was refused or a calibration failed.
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
    /// A setting or profile value outside its allowed range.
    #[error("{key} = {value}: {allowed}")]
    Setting {
        /// The key, dotted.
        key: String,
        /// The value found.
        value: String,
        /// The allowed range.
        allowed: String,
    },
    /// A capture that cannot be used: what was wrong and what the user should do.
    #[error("capture of pose '{pose}' refused: {problem}. {advice}")]
    Capture {
        /// The pose being captured.
        pose: String,
        /// What is wrong with the capture.
        problem: String,
        /// What to do about it.
        advice: String,
    },
    /// The retargeter refused its model, configuration or a capture.
    #[error("retargeter: {0}")]
    Retarget(#[from] retarget::Error),
    /// The optimiser failed (a value that is not finite, a Gaussian process that cannot be
    /// fitted).
    #[error("Bayesian optimisation failed: {0}")]
    Optimiser(String),
    /// The fit was cancelled before it finished (its caller's cancel check said so): there is
    /// no result, not even a partial one.
    #[error("the fit was interrupted before it finished")]
    Interrupted,
}

impl Error {
    /// Whether this is [`Error::Interrupted`]: the fit was cancelled, nothing failed.
    pub fn is_interrupted(&self) -> bool {
        matches!(self, Error::Interrupted)
    }
}
