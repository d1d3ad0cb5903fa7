//! The terminal pieces' one error type.

use std::path::PathBuf;

/// The full-screen terminal, the keyboard or stdin reader, or a `--script` file failed.
#[derive(Debug, thiserror::Error)]
pub enum TuiError {
    /// The terminal cannot switch to full-screen mode.
    #[error("cannot open the full-screen console: {source} (use --plain)")]
    FullScreen {
        /// The terminal's error.
        #[source]
        source: std::io::Error,
    },
    /// A frame could not be drawn.
    #[error("{source}")]
    Draw {
        /// The terminal's error.
        #[source]
        source: std::io::Error,
    },
    /// The thread reading the keyboard or stdin could not start.
    #[error("{source}")]
    InputThread {
        /// The thread's name (`console-keys`, `console-stdin`).
        thread: &'static str,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// A signal (SIGINT, SIGTERM) cannot be watched.
    #[error("cannot watch {signal}: {source}")]
    Signal {
        /// The signal's name.
        signal: &'static str,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// A script file cannot be read.
    #[error("cannot read the script {path}: {source}")]
    ReadScript {
        /// The script file.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// A script file does not follow the grammar.
    #[error("{path}:{reason}")]
    Script {
        /// The script file.
        path: PathBuf,
        /// `LINE: reason (line: "...")`.
        reason: String,
    },
}
