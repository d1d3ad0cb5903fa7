//! The operator console's one error type.
//!
//! Every variant about a file names it; the words of `--script` lines and stdin commands name
//! the word.

use std::path::PathBuf;

use crate::atomic_file::AtomicWriteError;
use crate::tui::TuiError;
use crate::tui::script::WordError;

/// A name, a session directory, its manifest, a `.part` log's recovery, a script or an
/// operator's command was refused or failed.
#[derive(Debug, thiserror::Error)]
pub enum ConsoleError {
    /// A name used in file names and metadata with characters it must not have.
    #[error(
        "{flag} {value:?}: use 1–64 letters, digits, '_', '-' or '.' (not starting with '.'); it names the session's files"
    )]
    Name {
        /// The flag (`--user`, ...).
        flag: String,
        /// The value given.
        value: String,
    },
    /// The session directory cannot be created.
    #[error("cannot create the session directory {dir}: {source}")]
    CreateSessionDir {
        /// The directory.
        dir: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// The session directory cannot be listed (looking for `.part` logs).
    #[error("{source}")]
    ListSessionDir {
        /// The directory.
        dir: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// A `.part` log that could not be recovered cannot be set aside either.
    #[error("{source}")]
    SetAside {
        /// The `.part` log.
        part: PathBuf,
        /// Where it was to go.
        to: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// The directory holds another session (task, embodiment or user).
    #[error("{manifest}: this session is {field} {found:?}, not {asked:?}; use another --out")]
    OtherSession {
        /// The session's manifest.
        manifest: PathBuf,
        /// `task`, `embodiment` or `user`.
        field: &'static str,
        /// The session's value.
        found: String,
        /// The value asked for.
        asked: String,
    },
    /// The manifest cannot be read.
    #[error("cannot read the session manifest {path}: {source}")]
    ReadManifest {
        /// The manifest.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// The manifest is not a session manifest's JSON.
    #[error("{path}: not a session manifest: {source}")]
    NotAManifest {
        /// The manifest.
        path: PathBuf,
        /// The parser's error.
        #[source]
        source: serde_json::Error,
    },
    /// A name read from the manifest is not one the console writes: it could point outside
    /// the session directory, so nothing is read or renamed.
    #[error(
        "{path}: {field} = {value:?} is refused: {reason} (allowed: {allowed}); the manifest was \
         edited or damaged: nothing in the session directory was touched"
    )]
    ManifestName {
        /// The manifest.
        path: PathBuf,
        /// The field, e.g. `trials[2].file`.
        field: String,
        /// The value found.
        value: String,
        /// What is wrong with it.
        reason: String,
        /// The names allowed there.
        allowed: String,
    },
    /// The manifest is of another format.
    #[error("{path}: format {found:?}, expected {expected:?}")]
    ManifestFormat {
        /// The manifest.
        path: PathBuf,
        /// Its format.
        found: String,
        /// The format this console writes.
        expected: &'static str,
    },
    /// The manifest cannot be written as JSON.
    #[error("{source}")]
    EncodeManifest {
        /// The manifest.
        path: PathBuf,
        /// The encoder's error.
        #[source]
        source: serde_json::Error,
    },
    /// The manifest cannot be written.
    #[error(transparent)]
    WriteManifest(#[from] AtomicWriteError),
    /// A `--script` file cannot be read or does not follow the grammar.
    #[error(transparent)]
    Script(#[from] TuiError),
    /// An unknown command word, or an argument to a word that takes none.
    #[error(transparent)]
    Word(#[from] WordError),
    /// A progress value that is not a number.
    #[error("progress value '{value}' is not a number")]
    ProgressNotANumber {
        /// The value given.
        value: String,
    },
    /// A progress value that is not finite.
    #[error("progress value '{value}' is not finite")]
    ProgressNotFinite {
        /// The value given.
        value: String,
    },
    /// `note` without a text.
    #[error("'note' needs a text: note TEXT")]
    NoteWithoutText,
}
