//! How the session ends: interrupted, quit complete, or failed by its script (a wait that timed
//! out, or a script that ended with a capture under review), with what the console and the
//! log's abort event say and the error naming the log.

use std::path::PathBuf;

use crate::calibrate::CalibrateError;
use crate::tui::script::ScriptError;

/// How the session ends.
#[derive(Default)]
pub(super) struct SessionEnd {
    /// Ctrl-C or the shutdown signal.
    pub(super) interrupted: bool,
    /// A script that timed out or ended at a review.
    pub(super) failure: Option<ScriptFailure>,
    /// The session quit complete.
    pub(super) completed: bool,
}

/// Why a script ended the session.
pub(super) enum ScriptFailure {
    /// A wait timed out.
    TimedOut(ScriptError),
    /// The script ended with a capture under review.
    EndedInReview,
}

impl ScriptFailure {
    /// What the console and the log's abort event say.
    pub(super) fn reason(&self) -> String {
        match self {
            ScriptFailure::TimedOut(e) => e.to_string(),
            ScriptFailure::EndedInReview => {
                "the script ended with a capture under review: add 'retry' or 'accept'".to_string()
            }
        }
    }

    /// The session's error, naming its log.
    pub(super) fn error(self, log: PathBuf) -> CalibrateError {
        match self {
            ScriptFailure::TimedOut(source) => CalibrateError::ScriptTimedOut { source, log },
            ScriptFailure::EndedInReview => CalibrateError::ScriptEndedInReview { log },
        }
    }
}
