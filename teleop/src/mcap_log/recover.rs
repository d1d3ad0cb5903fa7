//! [`recover`]: a complete MCAP from an interrupted one.
//!
//! A recorder killed mid-trial leaves `NAME.mcap.part` with every flushed chunk intact, then an
//! unterminated chunk (placeholder length, partial compressed data) and no summary. Readers
//! that need the summary (Python `mcap`, rosbag2) reject it. Recovery reads the file in order
//! up to the first record that cannot be read (see `record_scan`) and writes everything
//! before it to a new file: the same header profile, schemas and channels with their ids and
//! metadata, messages with their sequence numbers and times, metadata records and attachments,
//! followed by a fresh summary with statistics. It adds one metadata record,
//! [`RECOVERY_METADATA_NAME`], saying what was recovered from where.
//!
//! The input is only read. The output is written as `OUT.recovering` and renamed to `OUT`; an
//! existing `OUT` is never replaced.

use std::collections::{BTreeMap, HashMap};
use std::fmt;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use mcap::records::Metadata;

use super::part_file::{FINAL_EXISTS_HINT, commit, create_exclusive, refuse_existing};
use super::record_scan::{DataRecord, ScanEnd, scan};
use super::{LIBRARY, LogError, TrialWriterOptions};

/// Name of the metadata record that [`recover`] adds to its output.
pub const RECOVERY_METADATA_NAME: &str = "pomdar_recovery";

/// What [`recover`] found and wrote.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RecoveryReport {
    /// The damaged file that was read.
    pub input: PathBuf,
    /// The complete file written.
    pub output: PathBuf,
    /// Size of the input, bytes.
    pub input_bytes: u64,
    /// Messages recovered per topic (topics whose channel was recovered, even with 0).
    pub messages_per_topic: BTreeMap<String, u64>,
    /// Messages recovered in total.
    pub message_count: u64,
    /// Latest log time among the recovered messages, ns.
    pub last_log_time_ns: Option<i64>,
    /// Metadata records recovered (not counting the one recovery adds).
    pub metadata_count: usize,
    /// Bytes after the last intact record, which could not be used (0 when nothing is lost).
    pub unrecoverable_bytes: u64,
    /// Whether the file ends in a record that cannot be read (a partial chunk, garbage).
    pub tail_damaged: bool,
    /// Where the damage starts and what it is, when `tail_damaged`.
    pub damage: Option<(u64, String)>,
    /// Whether the input had a data end record (it was finished; only its summary, if
    /// anything, was missing or damaged).
    pub input_was_finished: bool,
}

impl fmt::Display for RecoveryReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "recovered {} -> {}",
            self.input.display(),
            self.output.display()
        )?;
        let last = match self.last_log_time_ns {
            Some(t) => format!(
                "last log time {}.{:09} s",
                t / 1_000_000_000,
                t % 1_000_000_000
            ),
            None => "no messages".to_string(),
        };
        writeln!(
            f,
            "  {} messages, {} metadata records; {last}",
            self.message_count, self.metadata_count
        )?;
        for (topic, count) in &self.messages_per_topic {
            writeln!(f, "    {count:>9}  {topic}")?;
        }
        let share = if self.input_bytes > 0 {
            100.0 * self.unrecoverable_bytes as f64 / self.input_bytes as f64
        } else {
            0.0
        };
        match (&self.damage, self.input_was_finished) {
            (Some((offset, reason)), _) => write!(
                f,
                "  tail damaged at byte {offset}: {reason}\n  {} of {} bytes ({share:.1} %) not recoverable: \
                 what was written after the last flush",
                self.unrecoverable_bytes, self.input_bytes
            ),
            (None, true) => write!(f, "  the input was finished: nothing lost, summary rebuilt"),
            (None, false) => write!(
                f,
                "  the input ends after a complete record: nothing lost, summary added"
            ),
        }
    }
}

/// Repairs the interrupted recording `part_path` into a new complete file `out_path`.
///
/// Fails if `out_path` exists or is `part_path`, or if `part_path` is not an MCAP file at all
/// (no magic or header). A file with no message left still recovers (to a file with its
/// schemas and channels, or none).
pub fn recover(part_path: &Path, out_path: &Path) -> Result<RecoveryReport, LogError> {
    if part_path == out_path {
        return Err(LogError::SameFile {
            path: part_path.to_path_buf(),
        });
    }
    refuse_existing(out_path, FINAL_EXISTS_HINT)?;
    let bytes = std::fs::read(part_path).map_err(|e| LogError::io(part_path, "read", e))?;
    let scanned = scan(&bytes).map_err(|reason| LogError::NotMcap {
        path: part_path.to_path_buf(),
        reason,
    })?;

    let mut report = RecoveryReport {
        input: part_path.to_path_buf(),
        output: out_path.to_path_buf(),
        input_bytes: bytes.len() as u64,
        messages_per_topic: BTreeMap::new(),
        message_count: 0,
        last_log_time_ns: None,
        metadata_count: 0,
        unrecoverable_bytes: 0,
        tail_damaged: false,
        damage: None,
        input_was_finished: scanned.end == ScanEnd::DataEnd,
    };
    if let ScanEnd::Damaged { offset, reason } | ScanEnd::OverBudget { offset, reason } =
        &scanned.end
    {
        report.tail_damaged = true;
        report.damage = Some((*offset, reason.clone()));
        report.unrecoverable_bytes = report.input_bytes.saturating_sub(scanned.intact_end);
    }

    let mut temp_name = out_path.as_os_str().to_os_string();
    temp_name.push(".recovering");
    let temp_path = PathBuf::from(temp_name);
    let file = create_exclusive(
        &temp_path,
        "another recovery to this name is running or was interrupted; remove it first",
    )?;
    let library = format!("{LIBRARY} (recovered from {})", scanned.library);
    let written = write_recovered(
        &temp_path,
        file,
        &scanned.profile,
        &library,
        &scanned.records,
        &mut report,
    )
    .and_then(|()| commit(&temp_path, out_path, false));
    if written.is_err() {
        let _ = std::fs::remove_file(&temp_path);
    }
    written.map(|()| report)
}

/// Writes `records` and the recovery metadata to `file`, fills in the counts of `report`.
fn write_recovered(
    path: &Path,
    file: std::fs::File,
    profile: &str,
    library: &str,
    records: &[DataRecord],
    report: &mut RecoveryReport,
) -> Result<(), LogError> {
    let err = |action: String| move |e| LogError::mcap(path, action, e);
    let mut writer = TrialWriterOptions::default()
        .mcap_options(profile, library)
        .create(BufWriter::new(file))
        .map_err(err("writing the header".into()))?;
    let mut topics: HashMap<u16, String> = HashMap::new();
    for record in records {
        match record {
            DataRecord::Schema {
                id,
                name,
                encoding,
                data,
            } => {
                writer
                    .add_schema_with_id(*id, name, encoding, data)
                    .map_err(err(format!("adding schema {name}")))?;
            }
            DataRecord::Channel(c) => {
                writer
                    .add_channel_with_id(
                        c.id,
                        c.schema_id,
                        &c.topic,
                        &c.message_encoding,
                        &c.metadata,
                    )
                    .map_err(err(format!("adding channel {}", c.topic)))?;
                topics.insert(c.id, c.topic.clone());
                report
                    .messages_per_topic
                    .entry(c.topic.clone())
                    .or_insert(0);
            }
            DataRecord::Message { header, data } => {
                writer
                    .write_to_known_channel(header, data)
                    .map_err(err("writing a message".into()))?;
                if let Some(topic) = topics.get(&header.channel_id) {
                    *report.messages_per_topic.entry(topic.clone()).or_insert(0) += 1;
                }
                report.message_count += 1;
                let t = i64::try_from(header.log_time).unwrap_or(i64::MAX);
                report.last_log_time_ns = Some(report.last_log_time_ns.map_or(t, |l| l.max(t)));
            }
            DataRecord::Metadata(metadata) => {
                writer
                    .write_metadata(metadata)
                    .map_err(err(format!("writing metadata {}", metadata.name)))?;
                report.metadata_count += 1;
            }
            DataRecord::Attachment { header, data } => {
                let attachment = mcap::Attachment {
                    log_time: header.log_time,
                    create_time: header.create_time,
                    name: header.name.clone(),
                    media_type: header.media_type.clone(),
                    data: std::borrow::Cow::Borrowed(data),
                };
                writer
                    .attach(&attachment)
                    .map_err(err(format!("writing attachment {}", header.name)))?;
            }
        }
    }
    writer
        .write_metadata(&recovery_metadata(report))
        .map_err(err("writing the recovery metadata".into()))?;
    writer.finish().map_err(err("writing the summary".into()))?;
    let file = writer
        .into_inner()
        .into_inner()
        .map_err(|e| LogError::io(path, "write", e.into_error()))?;
    file.sync_all().map_err(|e| LogError::io(path, "sync", e))
}

fn recovery_metadata(report: &RecoveryReport) -> Metadata {
    let mut entries = BTreeMap::from([
        (
            "source_file".to_string(),
            report.input.display().to_string(),
        ),
        ("source_bytes".to_string(), report.input_bytes.to_string()),
        (
            "unrecoverable_bytes".to_string(),
            report.unrecoverable_bytes.to_string(),
        ),
        ("tail_damaged".to_string(), report.tail_damaged.to_string()),
        (
            "messages_recovered".to_string(),
            report.message_count.to_string(),
        ),
    ]);
    if let Some((offset, reason)) = &report.damage {
        entries.insert("damage_offset".to_string(), offset.to_string());
        entries.insert("damage".to_string(), reason.clone());
    }
    if let Some(t) = report.last_log_time_ns {
        entries.insert("last_log_time_ns".to_string(), t.to_string());
    }
    Metadata {
        name: RECOVERY_METADATA_NAME.to_string(),
        metadata: entries,
    }
}
