//! The MCAP log's one error type.
//!
//! Every variant that comes from a file names it. Errors about a single decoded message name
//! its topic and log time instead (a [`LoggedMessage`](super::LoggedMessage) does not know its
//! file).

use std::path::PathBuf;

/// Writing, reading or recovering a trial log failed.
#[derive(Debug, thiserror::Error)]
pub enum LogError {
    /// The operating system refused a file operation.
    #[error("{path}: cannot {action}: {source}")]
    Io {
        /// The file or directory.
        path: PathBuf,
        /// What was being done (`create`, `rename to ...`, `sync`, ...).
        action: String,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// The mcap library reported an error while writing.
    #[error("{path}: MCAP writer failed while {action}: {source}")]
    Mcap {
        /// The file being written.
        path: PathBuf,
        /// What was being done.
        action: String,
        /// The library's error.
        #[source]
        source: mcap::McapError,
    },
    /// A file that must not be overwritten exists already.
    #[error("{path} already exists: {hint}")]
    AlreadyExists {
        /// The existing file.
        path: PathBuf,
        /// What to do about it.
        hint: &'static str,
    },
    /// Recovery was asked to write its output over its input.
    #[error("{path}: recovery output must be a different file from its input")]
    SameFile {
        /// The input file.
        path: PathBuf,
    },
    /// A writer option is out of range.
    #[error("trial writer for {path}: option {option} = {value}: {allowed}")]
    InvalidOption {
        /// The file the writer was for.
        path: PathBuf,
        /// The option's field name.
        option: &'static str,
        /// The value given.
        value: String,
        /// The allowed range.
        allowed: &'static str,
    },
    /// A topic name that ROS 2 would not accept.
    #[error("{path}: invalid topic name {topic:?}: {reason}")]
    TopicName {
        /// The file being written.
        path: PathBuf,
        /// The topic as given.
        topic: String,
        /// The rule it breaks.
        reason: &'static str,
    },
    /// A type name not of the form `pkg/msg/Type`.
    #[error("{path}: invalid message type name {type_name:?}: expected pkg/msg/Type")]
    TypeName {
        /// The file being written.
        path: PathBuf,
        /// The type name as given.
        type_name: String,
    },
    /// A topic already has a channel of another type, or with other QoS metadata.
    #[error("{path}: topic {topic} already has a channel ({existing}); cannot add {requested}")]
    ChannelConflict {
        /// The file being written.
        path: PathBuf,
        /// The topic.
        topic: String,
        /// The existing channel's type (and QoS, when that is what differs).
        existing: String,
        /// What was asked for.
        requested: String,
    },
    /// The same type name was given two different schema texts.
    #[error("{path}: type {type_name} was already written with a different schema text")]
    SchemaConflict {
        /// The file being written.
        path: PathBuf,
        /// The type name.
        type_name: String,
    },
    /// A negative timestamp (MCAP times are unsigned nanoseconds since the epoch).
    #[error(
        "{path}: message on {topic} has a negative time (log {log_time_ns} ns, publish {publish_time_ns} ns)"
    )]
    NegativeTime {
        /// The file being written.
        path: PathBuf,
        /// The topic.
        topic: String,
        /// Log (receive) time given, ns.
        log_time_ns: i64,
        /// Publish (source) time given, ns.
        publish_time_ns: i64,
    },
    /// A raw payload too short to hold the 4-byte CDR encapsulation header.
    #[error("{path}: payload for {topic} has {len} bytes, less than the 4-byte CDR header")]
    PayloadTooShort {
        /// The file being written.
        path: PathBuf,
        /// The topic.
        topic: String,
        /// Payload length.
        len: usize,
    },
    /// A message could not be encoded as CDR.
    #[error("{path}: cannot encode message for {topic}: {source}")]
    Encode {
        /// The file being written.
        path: PathBuf,
        /// The topic.
        topic: String,
        /// The encoder's error.
        #[source]
        source: msgs::Error,
    },
    /// The file does not start like an MCAP file.
    #[error("{path}: not an MCAP file: {reason}")]
    NotMcap {
        /// The file.
        path: PathBuf,
        /// What was found instead.
        reason: String,
    },
    /// A record in the data section cannot be read.
    #[error(
        "{path}: damaged at byte {offset}: {reason} (an interrupted recording can be repaired with `pomdar recover`)"
    )]
    Damaged {
        /// The file.
        path: PathBuf,
        /// Byte offset of the first record that cannot be read.
        offset: u64,
        /// What is wrong with it.
        reason: String,
    },
    /// A chunk declares more uncompressed bytes than the file's decompression budget allows
    /// ([`decompression_budget`](super::decompression_budget)); refused before anything
    /// of it is decompressed.
    #[error(
        "{path}: refused: the chunk at byte {offset}: {reason}; nothing of it was decompressed \
         (a crafted or damaged file: trial logs stay far below these limits)"
    )]
    OverBudget {
        /// The file.
        path: PathBuf,
        /// Byte offset of the chunk.
        offset: u64,
        /// Which limit it breaks.
        reason: String,
    },
    /// The data section is intact but the file was never finished (no summary and footer).
    #[error(
        "{path}: incomplete MCAP ({reason}): the recording was interrupted; repair it with `pomdar recover`"
    )]
    Incomplete {
        /// The file.
        path: PathBuf,
        /// What is missing.
        reason: String,
    },
    /// A message was decoded as a type other than its channel's.
    #[error("message on {topic} at {log_time_ns} ns is {recorded}, not {requested}")]
    TypeMismatch {
        /// The topic.
        topic: String,
        /// The message's log time, ns.
        log_time_ns: i64,
        /// The channel's schema name.
        recorded: String,
        /// The type asked for.
        requested: String,
    },
    /// A message's encoding is not CDR.
    #[error("message on {topic} at {log_time_ns} ns has encoding {encoding:?}, not \"cdr\"")]
    NotCdr {
        /// The topic.
        topic: String,
        /// The message's log time, ns.
        log_time_ns: i64,
        /// The channel's message encoding.
        encoding: String,
    },
    /// A message's CDR bytes do not decode as the requested type.
    #[error("message on {topic} at {log_time_ns} ns: {source}")]
    Decode {
        /// The topic.
        topic: String,
        /// The message's log time, ns.
        log_time_ns: i64,
        /// The decoder's error.
        #[source]
        source: msgs::Error,
    },
    /// An `offered_qos_profiles` string that is not the YAML rosbag2 writes.
    #[error("offered_qos_profiles line {line}: {reason}")]
    QosYaml {
        /// 1-based line number in the YAML text.
        line: usize,
        /// What is wrong.
        reason: String,
    },
}

impl LogError {
    /// An [`LogError::Io`] for `path`.
    pub(crate) fn io(
        path: impl Into<PathBuf>,
        action: impl Into<String>,
        source: std::io::Error,
    ) -> Self {
        LogError::Io {
            path: path.into(),
            action: action.into(),
            source,
        }
    }

    /// A [`LogError::Mcap`] for `path`.
    pub(crate) fn mcap(
        path: impl Into<PathBuf>,
        action: impl Into<String>,
        source: mcap::McapError,
    ) -> Self {
        LogError::Mcap {
            path: path.into(),
            action: action.into(),
            source,
        }
    }
}
