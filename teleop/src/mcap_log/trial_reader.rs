//! [`TrialReader`]: a finished log in memory, its messages in log-time order.
//!
//! Reads any MCAP with CDR messages, not only ours: chunked or not, zstd, lz4 or uncompressed,
//! with or without a summary (the reference recording was written by `rosbags`). The file must
//! be complete: a data end record, then a footer and the end magic. An interrupted recording
//! is an error that says to run `pomdar recover`; this reader never guesses.
//!
//! ## Order
//!
//! MCAP does not require a file's messages to be in log-time order (a chunked writer writes
//! them in arrival order, and two topics may arrive slightly out of order).
//! [`TrialReader::messages`] yields them sorted by log time; messages with equal log times
//! stay in file order (a stable sort). [`TrialReader::was_in_log_time_order`] says whether
//! the file already was. Files written by [`TrialWriter`](super::TrialWriter) from one clock
//! are, so for them log-time order is file order.

use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};

use mcap::records::{Channel, MessageHeader};
use msgs::RosMessage;

use super::record_scan::{DataRecord, ScanEnd, check_summary_fields, scan};
use super::{LogError, LoggedMessage, OfferedQos, qos_profiles_from_yaml};

/// One channel of a log.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TopicInfo {
    /// MCAP channel id.
    pub channel_id: u16,
    /// Topic name.
    pub topic: String,
    /// Schema name (`pkg/msg/Type`); empty if the channel has no schema.
    pub type_name: String,
    /// Schema encoding (`ros2msg`).
    pub schema_encoding: String,
    /// Schema text (the `.msg` text with its dependencies, for `ros2msg`).
    pub schema_text: String,
    /// Message encoding (`cdr`).
    pub message_encoding: String,
    /// Messages read on this channel.
    pub message_count: u64,
    /// Channel metadata (`offered_qos_profiles`, ...).
    pub metadata: BTreeMap<String, String>,
}

impl TopicInfo {
    /// The publishers' QoS from `offered_qos_profiles`, or `None` if the channel has none.
    pub fn offered_qos(&self) -> Option<Result<Vec<OfferedQos>, LogError>> {
        self.metadata
            .get("offered_qos_profiles")
            .map(|yaml| qos_profiles_from_yaml(yaml))
    }
}

/// The summary's Statistics record.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LogStatistics {
    /// Messages in the file.
    pub message_count: u64,
    /// Earliest message log time, ns.
    pub message_start_time_ns: u64,
    /// Latest message log time, ns.
    pub message_end_time_ns: u64,
    /// Schemas.
    pub schema_count: u16,
    /// Channels.
    pub channel_count: u32,
    /// Chunks.
    pub chunk_count: u32,
    /// Metadata records.
    pub metadata_count: u32,
    /// Attachments.
    pub attachment_count: u32,
    /// Messages per channel id.
    pub channel_message_counts: BTreeMap<u16, u64>,
}

/// A complete log read into memory. See the module docs.
#[derive(Debug, Clone)]
pub struct TrialReader {
    path: PathBuf,
    profile: String,
    library: String,
    messages: Vec<LoggedMessage>,
    topics: Vec<TopicInfo>,
    metadata: Vec<(String, BTreeMap<String, String>)>,
    statistics: Option<LogStatistics>,
    was_in_log_time_order: bool,
}

impl TrialReader {
    /// Reads the log at `path`.
    pub fn open(path: &Path) -> Result<TrialReader, LogError> {
        let bytes = std::fs::read(path).map_err(|e| LogError::io(path, "read", e))?;
        TrialReader::from_bytes(&bytes, path)
    }

    /// Reads a log held in memory; `path` names it in errors.
    pub fn from_bytes(bytes: &[u8], path: &Path) -> Result<TrialReader, LogError> {
        let scanned = scan(bytes).map_err(|reason| LogError::NotMcap {
            path: path.to_path_buf(),
            reason,
        })?;
        check_finished(scanned.end, path)?;
        let damaged = |reason: String| LogError::Damaged {
            path: path.to_path_buf(),
            offset: scanned.intact_end,
            reason,
        };
        let summary = read_checked_summary(bytes, path, damaged)?;
        let DataSection {
            topics,
            mut messages,
            metadata,
            ..
        } = DataSection::gather(scanned.records, damaged)?;
        let statistics = summary.and_then(|s| s.stats).map(LogStatistics::from);
        check_message_count(statistics.as_ref(), messages.len(), damaged)?;
        let was_in_log_time_order = sort_by_log_time(&mut messages);
        Ok(TrialReader {
            path: path.to_path_buf(),
            profile: scanned.profile,
            library: scanned.library,
            messages,
            topics,
            metadata,
            statistics,
            was_in_log_time_order,
        })
    }

    /// The file read.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Header profile (`ros2` for rosbag2-style logs).
    pub fn profile(&self) -> &str {
        &self.profile
    }

    /// Header library (the writing tool).
    pub fn library(&self) -> &str {
        &self.library
    }

    /// All messages in log-time order (equal times in file order).
    pub fn messages(&self) -> std::slice::Iter<'_, LoggedMessage> {
        self.messages.iter()
    }

    /// The messages on `topic`, in log-time order.
    pub fn messages_on<'a>(
        &'a self,
        topic: &'a str,
    ) -> impl Iterator<Item = &'a LoggedMessage> + 'a {
        self.messages.iter().filter(move |m| m.topic == topic)
    }

    /// Decodes every message on `topic` as `M`, in log-time order.
    pub fn decode_topic<M: RosMessage>(&self, topic: &str) -> Result<Vec<M>, LogError> {
        self.messages_on(topic).map(LoggedMessage::decode).collect()
    }

    /// Number of messages.
    pub fn message_count(&self) -> usize {
        self.messages.len()
    }

    /// Whether the file stored its messages in log-time order already.
    pub fn was_in_log_time_order(&self) -> bool {
        self.was_in_log_time_order
    }

    /// The channels, in file order.
    pub fn topics(&self) -> &[TopicInfo] {
        &self.topics
    }

    /// The first channel on `topic`.
    pub fn topic(&self, topic: &str) -> Option<&TopicInfo> {
        self.topics.iter().find(|t| t.topic == topic)
    }

    /// The metadata records `(name, entries)`, in file order.
    pub fn metadata(&self) -> &[(String, BTreeMap<String, String>)] {
        &self.metadata
    }

    /// The entries of the first metadata record called `name`.
    pub fn metadata_named(&self, name: &str) -> Option<&BTreeMap<String, String>> {
        self.metadata
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, entries)| entries)
    }

    /// The summary's statistics, if the file has a summary with a Statistics record.
    pub fn statistics(&self) -> Option<&LogStatistics> {
        self.statistics.as_ref()
    }
}

/// Whether the scan reached the data end record: a file that stops before it was cut short or
/// is damaged.
fn check_finished(end: ScanEnd, path: &Path) -> Result<(), LogError> {
    match end {
        ScanEnd::DataEnd => Ok(()),
        ScanEnd::EndOfFile => Err(LogError::Incomplete {
            path: path.to_path_buf(),
            reason: "no data end record, summary or footer".to_string(),
        }),
        ScanEnd::Damaged { offset, reason } => Err(LogError::Damaged {
            path: path.to_path_buf(),
            offset,
            reason,
        }),
        ScanEnd::OverBudget { offset, reason } => Err(LogError::OverBudget {
            path: path.to_path_buf(),
            offset,
            reason,
        }),
    }
}

/// The summary section after the data end record (`None` if the file has none), its field
/// lengths checked before the mcap crate parses it.
fn read_checked_summary(
    bytes: &[u8],
    path: &Path,
    damaged: impl Fn(String) -> LogError,
) -> Result<Option<mcap::Summary>, LogError> {
    let footer = mcap::read::footer(bytes).map_err(|e| LogError::Incomplete {
        path: path.to_path_buf(),
        reason: format!("after the data end record: {e}"),
    })?;
    check_summary_fields(bytes, footer.summary_start).map_err(&damaged)?;
    mcap::Summary::read(bytes).map_err(|e| damaged(format!("summary: {e}")))
}

/// The data section's records sorted into channels (with their schemas), messages in file
/// order and metadata records.
#[derive(Default)]
struct DataSection {
    /// `(name, encoding, text)` per schema id.
    schemas: HashMap<u16, (String, String, String)>,
    /// Index into `topics` per channel id.
    channel_index: HashMap<u16, usize>,
    topics: Vec<TopicInfo>,
    messages: Vec<LoggedMessage>,
    metadata: Vec<(String, BTreeMap<String, String>)>,
}

impl DataSection {
    /// Takes the scanned records in file order; a message time beyond `i64` is `damaged`.
    fn gather(
        records: Vec<DataRecord>,
        damaged: impl Fn(String) -> LogError,
    ) -> Result<DataSection, LogError> {
        let mut section = DataSection::default();
        for record in records {
            match record {
                DataRecord::Schema {
                    id,
                    name,
                    encoding,
                    data,
                } => {
                    let text = String::from_utf8_lossy(&data).into_owned();
                    section.schemas.insert(id, (name, encoding, text));
                }
                DataRecord::Channel(c) => section.add_channel(c),
                DataRecord::Message { header, data } => {
                    section.add_message(&header, data, &damaged)?;
                }
                DataRecord::Metadata(m) => section.metadata.push((m.name, m.metadata)),
                DataRecord::Attachment { .. } => {}
            }
        }
        Ok(section)
    }

    /// A new topic, with its schema if that was defined before it.
    fn add_channel(&mut self, c: Channel) {
        let (type_name, schema_encoding, schema_text) =
            self.schemas.get(&c.schema_id).cloned().unwrap_or_default();
        self.channel_index.insert(c.id, self.topics.len());
        self.topics.push(TopicInfo {
            channel_id: c.id,
            topic: c.topic,
            type_name,
            schema_encoding,
            schema_text,
            message_encoding: c.message_encoding,
            message_count: 0,
            metadata: c.metadata,
        });
    }

    /// A message on a known channel, counted on its topic.
    fn add_message(
        &mut self,
        header: &MessageHeader,
        data: Vec<u8>,
        damaged: impl Fn(String) -> LogError,
    ) -> Result<(), LogError> {
        // The scan checked that the channel exists.
        let Some(info) = self
            .channel_index
            .get(&header.channel_id)
            .and_then(|&i| self.topics.get_mut(i))
        else {
            return Ok(());
        };
        let time = |t: u64, what: &str| {
            i64::try_from(t)
                .map_err(|_| damaged(format!("{what} {t} ns on {} is beyond i64", info.topic)))
        };
        self.messages.push(LoggedMessage {
            topic: info.topic.clone(),
            type_name: info.type_name.clone(),
            message_encoding: info.message_encoding.clone(),
            sequence: header.sequence,
            log_time_ns: time(header.log_time, "log time")?,
            publish_time_ns: time(header.publish_time, "publish time")?,
            data,
        });
        info.message_count += 1;
        Ok(())
    }
}

impl From<mcap::records::Statistics> for LogStatistics {
    fn from(s: mcap::records::Statistics) -> LogStatistics {
        LogStatistics {
            message_count: s.message_count,
            message_start_time_ns: s.message_start_time,
            message_end_time_ns: s.message_end_time,
            schema_count: s.schema_count,
            channel_count: s.channel_count,
            chunk_count: s.chunk_count,
            metadata_count: s.metadata_count,
            attachment_count: s.attachment_count,
            channel_message_counts: s.channel_message_counts,
        }
    }
}

/// The summary's message count, if it has one, must match the messages read.
fn check_message_count(
    statistics: Option<&LogStatistics>,
    messages_read: usize,
    damaged: impl Fn(String) -> LogError,
) -> Result<(), LogError> {
    match statistics {
        Some(stats) if stats.message_count != messages_read as u64 => Err(damaged(format!(
            "the summary counts {} messages, the data section holds {}",
            stats.message_count, messages_read
        ))),
        _ => Ok(()),
    }
}

/// Sorts `messages` by log time, equal times in file order; returns whether they already were.
fn sort_by_log_time(messages: &mut [LoggedMessage]) -> bool {
    let was_in_log_time_order = messages
        .windows(2)
        .all(|w| w[0].log_time_ns <= w[1].log_time_ns);
    if !was_in_log_time_order {
        messages.sort_by_key(|m| m.log_time_ns);
    }
    was_in_log_time_order
}
