//! [`TrialWriter`]: one trial's MCAP file, written the way rosbag2 writes it.
//!
//! Records: header (profile `ros2`); one schema per type (`ros2msg`, the full text with its
//! dependencies); one channel per topic (`cdr`, with `offered_qos_profiles`); messages with a
//! per-channel sequence number starting at 1; metadata records. Chunks are zstd-compressed;
//! [`TrialWriter::finish`] writes the summary (schemas, channels, statistics, chunk, metadata
//! indexes) and renames `NAME.part` to `NAME`.
//!
//! ## Durability
//!
//! Schemas, channels and messages go into the open chunk, which is on disk only once closed.
//! [`TrialWriter::flush`] closes it and hands the bytes to the OS (and, with
//! [`sync_on_flush`](super::TrialWriterOptions::sync_on_flush), to the disk). Flushes happen on
//! every [`write_event`](TrialWriter::write_event) and
//! [`write_metadata`](TrialWriter::write_metadata), and whenever a write's log time is
//! [`auto_flush_interval_ns`](super::TrialWriterOptions::auto_flush_interval_ns) past the
//! last flush; a recorder with idle topics calls [`flush_if_due`](TrialWriter::flush_if_due)
//! from its timer. Time is always the caller's log time: this module reads no clock.
//! [`TrialWriter::durable_message_count`] says how many messages a crash now would keep.
//!
//! Dropping a writer without `finish` (an error path, a panic) completes the `.part` file with
//! its summary but does not rename it.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use mcap::records::{MessageHeader, Metadata};
use msgs::{RosMessage, StringMsg};

use super::background_sync::BackgroundSync;
use super::part_file::{
    FINAL_EXISTS_HINT, commit, create_exclusive, part_path_for, refuse_existing,
};
use super::ros_names::{is_type_name, names_definition, topic_problem};
use super::{LogError, OfferedQos, TrialWriterOptions, qos_profiles_to_yaml};

/// Topic of trial events: `std_msgs/msg/String` carrying one JSON object per event.
pub const TRIAL_EVENTS_TOPIC: &str = "/pomdar/trial_events";

/// Header `library` of the files this module writes (no time or host in it, so two runs that
/// write the same messages write the same bytes).
pub const LIBRARY: &str = concat!(
    "pomdar-teleop/",
    env!("CARGO_PKG_VERSION"),
    " mcap-rust/0.26"
);

/// The offered QoS recorded for [`TRIAL_EVENTS_TOPIC`] when the writer creates it.
pub const TRIAL_EVENTS_QOS: OfferedQos = OfferedQos::reliable(100);

const PART_EXISTS_HINT: &str = "an earlier recording to this name was interrupted; \
     repair it with `pomdar recover` or move it away";

struct ChannelState {
    id: u16,
    type_name: String,
    qos_yaml: String,
    next_sequence: u32,
    message_count: u64,
}

/// What [`TrialWriter::finish`] wrote.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FinishedTrial {
    /// The final file.
    pub path: PathBuf,
    /// Messages written.
    pub message_count: u64,
    /// Messages per topic.
    pub messages_per_topic: BTreeMap<String, u64>,
    /// Earliest and latest log time written, ns (`None` without messages).
    pub log_time_range_ns: Option<(i64, i64)>,
}

/// Writes one trial to `NAME.part`, renamed to `NAME` by [`TrialWriter::finish`]. See the
/// module docs.
pub struct TrialWriter {
    mcap: mcap::Writer<BufWriter<File>>,
    /// Second handle on the `.part` file, for `fsync`.
    file: File,
    /// The syncer, with [`sync_in_background`](TrialWriterOptions::sync_in_background).
    background_sync: Option<BackgroundSync>,
    part_path: PathBuf,
    final_path: PathBuf,
    options: TrialWriterOptions,
    /// Type name → (schema id, schema text).
    schemas: BTreeMap<String, (u16, String)>,
    channels: BTreeMap<String, ChannelState>,
    message_count: u64,
    durable_message_count: u64,
    log_time_range_ns: Option<(i64, i64)>,
    /// Latest log time written at the last flush (or the first write), the auto-flush anchor.
    last_flush_log_time_ns: Option<i64>,
    unflushed: bool,
}

impl TrialWriter {
    /// Starts writing the trial that will be `final_path`, in `final_path` + `.part`.
    ///
    /// Fails if the `.part` file exists (an interrupted recording: recover it first), or if
    /// `final_path` exists and [`overwrite`](TrialWriterOptions::overwrite) is off. The
    /// directory must exist. The header is on disk when this returns.
    pub fn create(final_path: &Path, options: TrialWriterOptions) -> Result<TrialWriter, LogError> {
        options.validate(final_path)?;
        if !options.overwrite {
            refuse_existing(final_path, FINAL_EXISTS_HINT)?;
        }
        let part_path = part_path_for(final_path);
        let file = create_exclusive(&part_path, PART_EXISTS_HINT)?;
        let opened = file
            .try_clone()
            .map_err(|e| LogError::io(&part_path, "duplicate file handle", e))
            .and_then(|sync_handle| {
                let mut mcap = options
                    .mcap_options("ros2", LIBRARY)
                    .create(BufWriter::new(file))
                    .map_err(|e| LogError::mcap(&part_path, "writing the header", e))?;
                mcap.flush()
                    .map_err(|e| LogError::mcap(&part_path, "flushing the header", e))?;
                Ok((mcap, sync_handle))
            });
        let opened = opened.and_then(|(mcap, file)| {
            let background_sync = match options.sync_on_flush && options.sync_in_background {
                true => Some(
                    file.try_clone()
                        .and_then(BackgroundSync::spawn)
                        .map_err(|e| LogError::io(&part_path, "start the syncer", e))?,
                ),
                false => None,
            };
            Ok((mcap, file, background_sync))
        });
        let (mcap, file, background_sync) = match opened {
            Ok(x) => x,
            Err(e) => {
                // Our own empty file: leave nothing that looks like an interrupted recording.
                let _ = std::fs::remove_file(&part_path);
                return Err(e);
            }
        };
        Ok(TrialWriter {
            mcap,
            file,
            background_sync,
            part_path,
            final_path: final_path.to_path_buf(),
            options,
            schemas: BTreeMap::new(),
            channels: BTreeMap::new(),
            message_count: 0,
            durable_message_count: 0,
            log_time_range_ns: None,
            last_flush_log_time_ns: None,
            unflushed: false,
        })
    }

    /// The file being written (`NAME.part`).
    pub fn part_path(&self) -> &Path {
        &self.part_path
    }

    /// The name the file gets on [`finish`](TrialWriter::finish).
    pub fn final_path(&self) -> &Path {
        &self.final_path
    }

    /// Messages written so far.
    pub fn message_count(&self) -> u64 {
        self.message_count
    }

    /// Messages that a crash now would keep: those written before the last flush.
    pub fn durable_message_count(&self) -> u64 {
        self.durable_message_count
    }

    /// Creates the channel for `topic` with type `M` and the publishers' offered QoS (one
    /// entry per publisher), and returns its id. Calling it again with the same type and QoS
    /// returns the same id; another type or QoS is a [`LogError::ChannelConflict`].
    pub fn add_channel<M: RosMessage>(
        &mut self,
        topic: &str,
        offered_qos: &[OfferedQos],
    ) -> Result<u16, LogError> {
        let qos_yaml = qos_profiles_to_yaml(offered_qos);
        self.ensure_channel(
            topic,
            &M::ros_type_name(),
            &M::schema_text(),
            Some(qos_yaml),
        )
    }

    /// [`add_channel`](TrialWriter::add_channel) for a type known only by name and schema text
    /// (`pkg/msg/Type`, `ros2msg` text with dependencies).
    pub fn add_channel_raw(
        &mut self,
        topic: &str,
        type_name: &str,
        schema_text: &str,
        offered_qos: &[OfferedQos],
    ) -> Result<u16, LogError> {
        let qos_yaml = qos_profiles_to_yaml(offered_qos);
        self.ensure_channel(topic, type_name, schema_text, Some(qos_yaml))
    }

    /// Writes `message` on `topic`, received at `log_time_ns` and sent at `publish_time_ns`
    /// (ns since the epoch). Creates the channel with
    /// [`default_qos`](TrialWriterOptions::default_qos) if the topic is new; may flush (see
    /// the module docs).
    pub fn write<M: RosMessage>(
        &mut self,
        topic: &str,
        log_time_ns: i64,
        publish_time_ns: i64,
        message: &M,
    ) -> Result<(), LogError> {
        let known = match self.channels.get(topic) {
            Some(c) if names_definition(&c.type_name, &M::DEFINITION) => true,
            // New topic, or a conflicting type: `ensure_channel` creates or reports.
            _ => false,
        };
        if !known {
            self.ensure_channel(topic, &M::ros_type_name(), &M::schema_text(), None)?;
        }
        let cdr = msgs::to_cdr(message).map_err(|source| LogError::Encode {
            path: self.part_path.clone(),
            topic: topic.to_string(),
            source,
        })?;
        self.write_payload(topic, log_time_ns, publish_time_ns, &cdr)
    }

    /// Writes a CDR payload (with its 4-byte encapsulation header) of type `type_name`
    /// (`pkg/msg/Type`, schema `schema_text`). Otherwise as [`write`](TrialWriter::write).
    pub fn write_raw(
        &mut self,
        topic: &str,
        type_name: &str,
        schema_text: &str,
        log_time_ns: i64,
        publish_time_ns: i64,
        cdr: &[u8],
    ) -> Result<(), LogError> {
        self.ensure_channel(topic, type_name, schema_text, None)?;
        if cdr.len() < 4 {
            return Err(LogError::PayloadTooShort {
                path: self.part_path.clone(),
                topic: topic.to_string(),
                len: cdr.len(),
            });
        }
        self.write_payload(topic, log_time_ns, publish_time_ns, cdr)
    }

    /// Writes a trial event (`std_msgs/String` with `event` as compact JSON) on
    /// [`TRIAL_EVENTS_TOPIC`], publish time = log time, then flushes.
    pub fn write_event(
        &mut self,
        log_time_ns: i64,
        event: &serde_json::Value,
    ) -> Result<(), LogError> {
        if !self.channels.contains_key(TRIAL_EVENTS_TOPIC) {
            self.add_channel::<StringMsg>(TRIAL_EVENTS_TOPIC, &[TRIAL_EVENTS_QOS])?;
        }
        let message = StringMsg {
            data: event.to_string(),
        };
        self.write(TRIAL_EVENTS_TOPIC, log_time_ns, log_time_ns, &message)?;
        self.flush()
    }

    /// Writes an MCAP Metadata record (`name` and string pairs), then flushes.
    pub fn write_metadata(
        &mut self,
        name: &str,
        entries: BTreeMap<String, String>,
    ) -> Result<(), LogError> {
        self.write_metadata_unflushed(name, entries)?;
        self.flush()
    }

    /// Writes an MCAP Metadata record, to reach the disk with the next flush (a trial's
    /// recorder writes its start event right after: one flush takes both to the OS at once,
    /// so a kill during that flush's sync finds the start event in the `.part` too).
    pub fn write_metadata_unflushed(
        &mut self,
        name: &str,
        entries: BTreeMap<String, String>,
    ) -> Result<(), LogError> {
        let record = Metadata {
            name: name.to_string(),
            metadata: entries,
        };
        self.mcap.write_metadata(&record).map_err(|e| {
            LogError::mcap(&self.part_path, format!("writing metadata {name:?}"), e)
        })?;
        self.unflushed = true;
        Ok(())
    }

    /// Closes the open chunk and hands it to the OS (and the disk, with
    /// [`sync_on_flush`](TrialWriterOptions::sync_on_flush)): a crash after this keeps every
    /// message written before it.
    pub fn flush(&mut self) -> Result<(), LogError> {
        super::slow_disk::stall();
        self.mcap
            .flush()
            .map_err(|e| LogError::mcap(&self.part_path, "flushing", e))?;
        if let Some(syncer) = &self.background_sync {
            syncer.request();
            if let Some(e) = syncer.take_error() {
                return Err(LogError::io(&self.part_path, "sync", e));
            }
        } else if self.options.sync_on_flush {
            self.file
                .sync_data()
                .map_err(|e| LogError::io(&self.part_path, "sync", e))?;
        }
        self.durable_message_count = self.message_count;
        self.unflushed = false;
        if let Some((_, latest)) = self.log_time_range_ns {
            self.last_flush_log_time_ns = Some(latest);
        }
        Ok(())
    }

    /// Flushes if something was written since the last flush and `now_log_time_ns` is
    /// [`auto_flush_interval_ns`](TrialWriterOptions::auto_flush_interval_ns) or more past
    /// it (or before it: a clock step back). Returns whether it flushed. Every write calls
    /// this with its log time; call it from a timer when topics may fall silent.
    pub fn flush_if_due(&mut self, now_log_time_ns: i64) -> Result<bool, LogError> {
        let Some(interval) = self.options.auto_flush_interval_ns else {
            return Ok(false);
        };
        let Some(anchor) = self.last_flush_log_time_ns else {
            self.last_flush_log_time_ns = Some(now_log_time_ns);
            return Ok(false);
        };
        let due = now_log_time_ns.saturating_sub(anchor) >= interval || now_log_time_ns < anchor;
        if due && self.unflushed {
            self.flush()?;
            return Ok(true);
        }
        Ok(false)
    }

    /// Writes the summary, syncs, and renames `NAME.part` to `NAME` (refusing to replace an
    /// existing `NAME` unless [`overwrite`](TrialWriterOptions::overwrite) is set).
    pub fn finish(self) -> Result<FinishedTrial, LogError> {
        let TrialWriter {
            mut mcap,
            file,
            background_sync,
            part_path,
            final_path,
            options,
            channels,
            message_count,
            log_time_range_ns,
            ..
        } = self;
        super::slow_disk::stall();
        mcap.finish()
            .map_err(|e| LogError::mcap(&part_path, "writing the summary", e))?;
        mcap.into_inner()
            .into_inner()
            .map_err(|e| LogError::io(&part_path, "write", e.into_error()))?;
        if let Some(e) = background_sync.and_then(BackgroundSync::stop) {
            return Err(LogError::io(&part_path, "sync", e));
        }
        file.sync_all()
            .map_err(|e| LogError::io(&part_path, "sync", e))?;
        drop(file);
        commit(&part_path, &final_path, options.overwrite)?;
        Ok(FinishedTrial {
            path: final_path,
            message_count,
            messages_per_topic: channels
                .into_iter()
                .map(|(topic, c)| (topic, c.message_count))
                .collect(),
            log_time_range_ns,
        })
    }

    /// The channel id for `topic`, creating schema and channel if needed. `qos_yaml` `None`
    /// means "whatever it has, or the default QoS if new".
    fn ensure_channel(
        &mut self,
        topic: &str,
        type_name: &str,
        schema_text: &str,
        qos_yaml: Option<String>,
    ) -> Result<u16, LogError> {
        if let Some(channel) = self.channels.get(topic) {
            let same_type = channel.type_name == type_name;
            let same_qos = qos_yaml.as_ref().is_none_or(|q| *q == channel.qos_yaml);
            if same_type && same_qos {
                return Ok(channel.id);
            }
            return Err(LogError::ChannelConflict {
                path: self.part_path.clone(),
                topic: topic.to_string(),
                existing: if same_type {
                    format!(
                        "{} with offered QoS {:?}",
                        channel.type_name, channel.qos_yaml
                    )
                } else {
                    channel.type_name.clone()
                },
                requested: match (&qos_yaml, same_type) {
                    (Some(q), true) => format!("{type_name} with offered QoS {q:?}"),
                    _ => type_name.to_string(),
                },
            });
        }
        if let Some(reason) = topic_problem(topic) {
            return Err(LogError::TopicName {
                path: self.part_path.clone(),
                topic: topic.to_string(),
                reason,
            });
        }
        if !is_type_name(type_name) {
            return Err(LogError::TypeName {
                path: self.part_path.clone(),
                type_name: type_name.to_string(),
            });
        }
        let schema_id = match self.schemas.get(type_name) {
            Some((_, text)) if text != schema_text => {
                return Err(LogError::SchemaConflict {
                    path: self.part_path.clone(),
                    type_name: type_name.to_string(),
                });
            }
            Some((id, _)) => *id,
            None => {
                let id = self
                    .mcap
                    .add_schema(type_name, "ros2msg", schema_text.as_bytes())
                    .map_err(|e| {
                        LogError::mcap(&self.part_path, format!("adding schema {type_name}"), e)
                    })?;
                self.schemas
                    .insert(type_name.to_string(), (id, schema_text.to_string()));
                id
            }
        };
        let qos_yaml =
            qos_yaml.unwrap_or_else(|| qos_profiles_to_yaml(&[self.options.default_qos]));
        let metadata = BTreeMap::from([("offered_qos_profiles".to_string(), qos_yaml.clone())]);
        let id = self
            .mcap
            .add_channel(schema_id, topic, "cdr", &metadata)
            .map_err(|e| LogError::mcap(&self.part_path, format!("adding channel {topic}"), e))?;
        self.unflushed = true;
        self.channels.insert(
            topic.to_string(),
            ChannelState {
                id,
                type_name: type_name.to_string(),
                qos_yaml,
                next_sequence: 1,
                message_count: 0,
            },
        );
        Ok(id)
    }

    /// Writes one message on an existing channel, then flushes if due.
    fn write_payload(
        &mut self,
        topic: &str,
        log_time_ns: i64,
        publish_time_ns: i64,
        cdr: &[u8],
    ) -> Result<(), LogError> {
        let (Ok(log_time), Ok(publish_time)) =
            (u64::try_from(log_time_ns), u64::try_from(publish_time_ns))
        else {
            return Err(LogError::NegativeTime {
                path: self.part_path.clone(),
                topic: topic.to_string(),
                log_time_ns,
                publish_time_ns,
            });
        };
        let Some(channel) = self.channels.get_mut(topic) else {
            // ensure_channel ran first; reaching here would be a bug in this file.
            return Err(LogError::TopicName {
                path: self.part_path.clone(),
                topic: topic.to_string(),
                reason: "has no channel",
            });
        };
        let header = MessageHeader {
            channel_id: channel.id,
            sequence: channel.next_sequence,
            log_time,
            publish_time,
        };
        self.mcap
            .write_to_known_channel(&header, cdr)
            .map_err(|e| {
                LogError::mcap(&self.part_path, format!("writing a message on {topic}"), e)
            })?;
        channel.next_sequence = channel.next_sequence.wrapping_add(1);
        channel.message_count += 1;
        self.message_count += 1;
        self.unflushed = true;
        self.log_time_range_ns = Some(match self.log_time_range_ns {
            None => (log_time_ns, log_time_ns),
            Some((first, last)) => (first.min(log_time_ns), last.max(log_time_ns)),
        });
        self.flush_if_due(log_time_ns)?;
        Ok(())
    }
}
