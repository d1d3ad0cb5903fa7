//! The hand check's one error type: what the pure check refuses (options, tables, the check not
//! finished: [`consoles::ConsolesError`]), DDS, scripts and the table file.

use std::path::PathBuf;

use crate::atomic_file::AtomicWriteError;
use crate::ros::RosError;
use crate::tui::TuiError;
use crate::tui::script::{ScriptError, WordError};

/// Why a hand check did not write a verified table.
#[derive(Debug, thiserror::Error)]
pub enum HandCheckError {
    /// The check refused an option or the table, or ended before every joint was confirmed.
    #[error(transparent)]
    Check(#[from] consoles::ConsolesError),
    /// The written table does not load back as the table checked.
    #[error("{path}: the table written would not load back as checked: {reason}")]
    Roundtrip {
        /// The output file.
        path: PathBuf,
        /// What differs, or the loader's error.
        reason: String,
    },
    /// The configuration file is not TOML the table can be written into.
    #[error("{path}: {reason}")]
    ConfigText {
        /// The configuration file.
        path: PathBuf,
        /// The parser's message.
        reason: String,
    },
    /// Writing the table failed.
    #[error(transparent)]
    Write(#[from] AtomicWriteError),
    /// DDS failed.
    #[error(transparent)]
    Ros(#[from] RosError),
    /// A script or the terminal failed.
    #[error(transparent)]
    Tui(#[from] TuiError),
    /// A script line or a typed word was refused.
    #[error(transparent)]
    Word(#[from] WordError),
    /// A `wait` in the script timed out.
    #[error(transparent)]
    Script(#[from] ScriptError),
}
