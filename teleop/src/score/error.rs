//! The scoring commands' two error types: [`ScoreFileError`] for the run's own files (catalog,
//! rules, baseline in; the report out), which stops the run, and [`TrialFileError`] for a
//! trial file that cannot be scored, which the report lists beside the file and the run goes
//! on.

use std::path::{Path, PathBuf};

use scoring::{ScoringError, TRIAL_METADATA_NAME};

use crate::atomic_file::AtomicWriteError;
use crate::mcap_log::LogError;

/// A file of the scoring run (catalog, rules, baseline, report) that cannot be read, is not
/// valid, or cannot be written.
#[derive(Debug, thiserror::Error)]
pub enum ScoreFileError {
    /// The file cannot be read.
    #[error("cannot read {what} {path}: {source}")]
    Read {
        /// What the file is (`task catalog`, `scoring rules`, `baseline`).
        what: &'static str,
        /// The file.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// The file does not parse or validate (the scoring crate's error names the file, the key
    /// and the allowed values).
    #[error(transparent)]
    Invalid(#[from] ScoringError),
    /// A report file cannot be written (names the file or its directory).
    #[error(transparent)]
    Write(#[from] AtomicWriteError),
}

/// A trial file that cannot be scored. Its message is the reason alone: the report shows the
/// file beside it.
#[derive(Debug, thiserror::Error)]
pub enum TrialFileError {
    /// The file cannot be read as an MCAP trial log.
    #[error("{}", without_path(.path, .source))]
    Log {
        /// The trial file.
        path: PathBuf,
        /// The log's error (its message starts with the file, left out here); boxed, as it is
        /// large and the result of every file is kept.
        #[source]
        source: Box<LogError>,
    },
    /// The log has no trial metadata record.
    #[error("no {TRIAL_METADATA_NAME} metadata record: not a POMDAR trial log (found {found})")]
    NotTrial {
        /// The metadata records found, comma-separated, or `no metadata`.
        found: String,
    },
    /// A trial event that is not JSON.
    #[error("trial event {number} (+{offset_s:.3} s) is not JSON ({source}): {text:?}")]
    EventNotJson {
        /// The event's 1-based number in the log.
        number: usize,
        /// Its log time after the first event, seconds.
        offset_s: f64,
        /// The event's text.
        text: String,
        /// The JSON parser's error.
        #[source]
        source: serde_json::Error,
    },
    /// Scoring refused the trial.
    #[error("{}", scoring_reason(.0))]
    Scoring(#[from] ScoringError),
}

/// `source`'s message without the `path: ` it starts with.
fn without_path(path: &Path, source: &LogError) -> String {
    let message = source.to_string();
    let shown = format!("{}: ", path.display());
    message
        .strip_prefix(&shown)
        .map_or_else(|| message.clone(), str::to_string)
}

/// The reason of a scoring error, without the file name the report shows beside it.
fn scoring_reason(error: &ScoringError) -> String {
    match error {
        ScoringError::Trial { reason, .. } => reason.clone(),
        other => other.to_string(),
    }
}
