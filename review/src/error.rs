//! Why a trial cannot be reviewed.

/// A trial that cannot be reviewed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ReviewError {
    /// The log has no `start` event: there is no trial to review.
    #[error("{file}: no trial `start` event on /pomdar/trial_events (is it a trial log?)")]
    NoStart {
        /// The file.
        file: String,
    },
    /// The hand model cannot be posed with the logged joint targets.
    #[error("{file}: the joint targets do not fit the hand model: {reason}")]
    Model {
        /// The file.
        file: String,
        /// What did not fit.
        reason: String,
    },
    /// A figure could not be drawn.
    #[error("{file}: the review figure: {reason}")]
    Figure {
        /// The file.
        file: String,
        /// The plotting error.
        reason: String,
    },
}
