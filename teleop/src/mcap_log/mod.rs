//! # Trial logs in MCAP, as rosbag2 writes them
//!
//! Each trial is one MCAP file that every ROS 2 tool can read (docs/LAB_CONVENTIONS.md §4):
//!
//! | record | content |
//! |---|---|
//! | header | profile `ros2`, library [`LIBRARY`] |
//! | schema | one per type: name `pkg/msg/Type`, encoding `ros2msg`, the `.msg` text with every nested dependency ([`msgs::RosMessage::schema_text`]) |
//! | channel | one per topic: message encoding `cdr`, metadata `offered_qos_profiles` ([`qos_profile`]) |
//! | message | `log_time` = receive time, `publish_time` = source time (ns since the epoch), data = CDR with its 4-byte encapsulation header |
//! | metadata | the trial's description (task, embodiment, operator, ...), written by the recorder |
//! | summary | schemas, channels, Statistics, chunk and metadata indexes |
//!
//! Trial events (start, progress, drop, stop, abort, note) are `std_msgs/String` messages
//! carrying JSON on [`TRIAL_EVENTS_TOPIC`].
//!
//! ## Parts
//!
//! - [`TrialWriter`]: writes `NAME.part`, chunked and zstd-compressed, flushed on every event
//!   and metadata record and at least once per second of log time; [`TrialWriter::finish`]
//!   writes the summary and renames it to `NAME`.
//! - [`WriterThread`]: a [`TrialWriter`] on a thread of its own, for a loop that must not wait
//!   on the disk.
//! - [`continue_finished`]: a finished log copied into a writer that replaces it when
//!   finished, to add to it.
//! - [`recover()`]: turns an interrupted `.part` into a complete file holding everything up to
//!   the last flush, and says what was lost ([`RecoveryReport`]).
//! - [`TrialReader`]: reads a complete file from any tool into memory; messages in log-time
//!   order as [`LoggedMessage`]s, decoded with the `msgs` types.
//! - [`read_trial_events`]: only the metadata and the trial events, through the summary's
//!   indexes (decompresses only the chunks that hold events): what scoring reads.
//! - [`decompression_budget`]: every reader checks each chunk's declared uncompressed size
//!   against a per-chunk and a per-file limit before decompressing it ([`LogError::OverBudget`]).
//!
//! ```no_run
//! use std::collections::BTreeMap;
//! use std::path::Path;
//!
//! use msgs::JointState;
//! use teleop::mcap_log::{OfferedQos, TrialReader, TrialWriter, TrialWriterOptions};
//!
//! let path = Path::new("/data/trials/V1_0001.mcap");
//! let mut log = TrialWriter::create(path, TrialWriterOptions::default())?;
//! log.write_metadata("pomdar_trial", BTreeMap::from([("task".into(), "V1".into())]))?;
//! log.add_channel::<JointState>("/hand/joint_targets", &[OfferedQos::reliable(10)])?;
//! log.write_event(1_000, &serde_json::json!({"event": "start"}))?;
//! log.write("/hand/joint_targets", 2_000, 1_500, &JointState::default())?;
//! log.finish()?;
//!
//! let trial = TrialReader::open(path)?;
//! for message in trial.messages().filter(|m| m.is::<JointState>()) {
//!     let joints: JointState = message.decode()?;
//!     println!("{} {:?}", message.log_time_ns, joints.position);
//! }
//! # Ok::<(), teleop::mcap_log::LogError>(())
//! ```
//!
//! This module reads no clock: every time is a parameter.

mod background_sync;
mod continue_log;
pub mod decompression_budget;
mod error;
mod event_reader;
mod logged_message;
mod part_file;
pub mod qos_profile;
mod record_scan;
mod recover;
mod ros_names;
pub mod slow_disk;
mod trial_reader;
mod trial_writer;
mod writer_options;
mod writer_thread;

#[cfg(test)]
mod event_reader_tests;
#[cfg(test)]
mod qos_profile_tests;
#[cfg(test)]
mod record_scan_tests;
#[cfg(test)]
mod test_dir;
#[cfg(test)]
mod trial_writer_tests;

pub use continue_log::continue_finished;
pub use error::LogError;
pub use event_reader::{TrialEvents, read_trial_events};
pub use logged_message::{LoggedMessage, decode};
pub use part_file::part_path_for;
pub use qos_profile::{
    OfferedQos, QosDurability, QosHistory, QosLiveliness, QosReliability, RosDuration,
    qos_profiles_from_yaml, qos_profiles_to_yaml,
};
pub use recover::{RECOVERY_METADATA_NAME, RecoveryReport, recover};
pub use trial_reader::{LogStatistics, TopicInfo, TrialReader};
pub use trial_writer::{FinishedTrial, LIBRARY, TRIAL_EVENTS_QOS, TRIAL_EVENTS_TOPIC, TrialWriter};
pub use writer_options::{LogCompression, TrialWriterOptions};
pub use writer_thread::WriterThread;
