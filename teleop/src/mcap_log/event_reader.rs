//! [`read_trial_events`]: a trial's metadata records and its `/pomdar/trial_events` messages,
//! read through the MCAP summary without decompressing the rest of the file.
//!
//! Scoring needs a few hundred bytes of a file that is mostly glove keypoints and joint
//! targets. The reader opens the file, checks the start magic, reads the footer and the
//! summary section (schemas, channels, statistics, chunk and metadata indexes), reads each
//! metadata record at its indexed offset, and reads and decompresses only the chunks whose
//! chunk index lists a message index for the trial-events channel. A station log flushes a
//! chunk at every event, so those are the small chunks that end at an event.
//!
//! A file without footer or end magic was cut short (an interrupted recording, a partial
//! copy): that is [`LogError::Incomplete`] with "truncated file", never a guess. A complete
//! file without a summary, or whose summary lacks the indexes (other writers), is read whole
//! with [`super::TrialReader`].
//!
//! Events are returned in file order (chunks in file order, messages in chunk order), which
//! for the station's writer is the order they were written; checking their log times is
//! the scorer's job. (Files read whole come back in log-time order, as `TrialReader` gives
//! them.)

use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufReader, Read, Seek, SeekFrom};
use std::path::Path;

use mcap::McapError;
use mcap::records::{ChunkIndex, MessageHeader, Record, op};
use mcap::sans_io::summary_reader::{SummaryReadEvent, SummaryReader, SummaryReaderOptions};
use msgs::StringMsg;

use super::decompression_budget::DecompressionBudget;
use super::record_scan::{check_summary_section, chunk_records, parse};
use super::{LogError, TRIAL_EVENTS_TOPIC, TrialReader};

/// What [`read_trial_events`] found.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TrialEvents {
    /// Metadata records `(name, entries)`, in file order.
    pub metadata: Vec<(String, BTreeMap<String, String>)>,
    /// Trial events `(log time ns, the std_msgs/String text)`, in file order.
    pub events: Vec<(i64, String)>,
    /// Chunks decompressed.
    pub chunks_read: usize,
    /// Chunks in the file.
    pub chunks_total: usize,
    /// Whether the file had to be read whole (no usable summary indexes).
    pub read_whole_file: bool,
}

impl TrialEvents {
    /// The entries of the first metadata record called `name`.
    pub fn metadata_named(&self, name: &str) -> Option<&BTreeMap<String, String>> {
        self.metadata
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, entries)| entries)
    }
}

/// Reads the metadata and trial events of the log at `path` (see the module docs).
pub fn read_trial_events(path: &Path) -> Result<TrialEvents, LogError> {
    let (mut file, size) = open_after_magic(path)?;
    check_summary_on_disk(&mut file, size, path)?;
    let Some(summary) = read_summary(&mut file, size, path)? else {
        return read_whole(path);
    };
    if !indexes_cover_everything(&summary) {
        return read_whole(path);
    }

    let mut out = TrialEvents {
        chunks_total: summary.chunk_indexes.len(),
        ..TrialEvents::default()
    };
    out.metadata = read_indexed_metadata(&mut file, size, path, &summary)?;
    let event_channels = trial_event_channels(&summary);
    if event_channels.is_empty() {
        return Ok(out);
    }
    let mut budget = DecompressionBudget::for_file(size);
    for index in chunks_holding_events(&summary, &event_channels) {
        let events =
            read_events_in_chunk(&mut file, (size, path), &mut budget, index, &event_channels)?;
        out.chunks_read += 1;
        out.events.extend(events);
    }
    Ok(out)
}

/// Opens the file, reads its size and checks the start magic; the reader is left just past it.
fn open_after_magic(path: &Path) -> Result<(BufReader<File>, u64), LogError> {
    let file = File::open(path).map_err(|e| LogError::io(path, "open", e))?;
    let size = file
        .metadata()
        .map_err(|e| LogError::io(path, "read the size of", e))?
        .len();
    let mut file = BufReader::with_capacity(64 * 1024, file);
    let mut magic = [0u8; 8];
    if size < magic.len() as u64 {
        return Err(LogError::NotMcap {
            path: path.to_path_buf(),
            reason: format!("{size} bytes, shorter than the MCAP magic"),
        });
    }
    file.read_exact(&mut magic)
        .map_err(|e| LogError::io(path, "read", e))?;
    if magic != mcap::MAGIC {
        return Err(LogError::NotMcap {
            path: path.to_path_buf(),
            reason: "the file does not start with the MCAP magic".to_string(),
        });
    }
    Ok((file, size))
}

/// Whether the summary indexes every chunk holding messages and every metadata record;
/// otherwise the file is read whole.
fn indexes_cover_everything(summary: &mcap::Summary) -> bool {
    let has_messages = summary.stats.as_ref().is_none_or(|s| s.message_count > 0);
    let metadata_unindexed = summary
        .stats
        .as_ref()
        .is_none_or(|s| s.metadata_count as usize != summary.metadata_indexes.len());
    !((has_messages && summary.chunk_indexes.is_empty()) || metadata_unindexed)
}

/// A metadata record `(name, entries)`.
type MetadataRecord = (String, BTreeMap<String, String>);

/// The metadata records at the summary's metadata indexes, in index order.
fn read_indexed_metadata(
    file: &mut BufReader<File>,
    size: u64,
    path: &Path,
    summary: &mcap::Summary,
) -> Result<Vec<MetadataRecord>, LogError> {
    let mut metadata = Vec::with_capacity(summary.metadata_indexes.len());
    for index in &summary.metadata_indexes {
        let bytes = read_range(file, path, size, index.offset, index.length)?;
        match parse_at(&bytes, index.offset, path)? {
            Record::Metadata(m) => metadata.push((m.name, m.metadata)),
            _ => {
                return Err(damaged(
                    path,
                    index.offset,
                    "the metadata index does not point at a metadata record",
                ));
            }
        }
    }
    Ok(metadata)
}

/// The ids of the channels on the trial-events topic.
fn trial_event_channels(summary: &mcap::Summary) -> Vec<u16> {
    summary
        .channels
        .values()
        .filter(|c| c.topic == TRIAL_EVENTS_TOPIC)
        .map(|c| c.id)
        .collect()
}

/// The chunks that may hold trial events (those whose index lists an event channel, or
/// lists no channel at all), in file order.
fn chunks_holding_events<'s>(
    summary: &'s mcap::Summary,
    event_channels: &[u16],
) -> Vec<&'s ChunkIndex> {
    let mut chunks: Vec<_> = summary
        .chunk_indexes
        .iter()
        .filter(|c| {
            c.message_index_offsets.is_empty()
                || event_channels
                    .iter()
                    .any(|id| c.message_index_offsets.contains_key(id))
        })
        .collect();
    chunks.sort_by_key(|c| c.chunk_start_offset);
    chunks
}

/// Reads and decompresses the chunk at `index` and decodes its messages on `event_channels`,
/// in chunk order.
fn read_events_in_chunk(
    file: &mut BufReader<File>,
    (size, path): (u64, &Path),
    budget: &mut DecompressionBudget,
    index: &ChunkIndex,
    event_channels: &[u16],
) -> Result<Vec<(i64, String)>, LogError> {
    let offset = index.chunk_start_offset;
    let over_budget = |reason| LogError::OverBudget {
        path: path.to_path_buf(),
        offset,
        reason,
    };
    // The index's size first (before even reading the chunk), then the chunk's own header,
    // which is what decompression would allocate.
    let mut probe = *budget;
    probe.charge(index.uncompressed_size).map_err(over_budget)?;
    let bytes = read_range(file, path, size, offset, index.chunk_length)?;
    let Record::Chunk { header, .. } = parse_at(&bytes, offset, path)? else {
        return Err(damaged(
            path,
            offset,
            "the chunk index does not point at a chunk",
        ));
    };
    budget
        .charge(header.uncompressed_size)
        .map_err(over_budget)?;
    // Bounded decompression (record lengths limited by the chunk's size): a damaged
    // chunk is an error, never a huge allocation.
    let records = chunk_records(&bytes).map_err(|reason| damaged(path, offset, &reason))?;
    let mut events = Vec::new();
    for record in records {
        let Record::Message { header, data } = record else {
            continue;
        };
        if !event_channels.contains(&header.channel_id) {
            continue;
        }
        events.push(decode_trial_event(path, offset, &header, &data)?);
    }
    Ok(events)
}

/// One trial event `(log time ns, text)` from the chunk at `offset`.
fn decode_trial_event(
    path: &Path,
    offset: u64,
    header: &MessageHeader,
    data: &[u8],
) -> Result<(i64, String), LogError> {
    let log_time_ns = i64::try_from(header.log_time).map_err(|_| {
        damaged(
            path,
            offset,
            &format!("trial event log time {} ns is beyond i64", header.log_time),
        )
    })?;
    let text: StringMsg = msgs::from_cdr(data).map_err(|e| {
        damaged(
            path,
            offset,
            &format!("trial event at {log_time_ns} ns is not a std_msgs/String: {e}"),
        )
    })?;
    Ok((log_time_ns, text.data))
}

fn damaged(path: &Path, offset: u64, reason: &str) -> LogError {
    LogError::Damaged {
        path: path.to_path_buf(),
        offset,
        reason: reason.to_string(),
    }
}

/// Checks the field lengths of the summary section's records before the mcap crate's summary
/// reader parses them: it reserves whatever a damaged string length claims (cargo-fuzz found a
/// chunk index whose compression name claimed 4 GiB). A file whose footer cannot be found is
/// left to the summary reader to report.
fn check_summary_on_disk(
    file: &mut BufReader<File>,
    size: u64,
    path: &Path,
) -> Result<(), LogError> {
    const FOOTER_AND_MAGIC: u64 = 9 + 20 + 8;
    if size < FOOTER_AND_MAGIC + 8 {
        return Ok(());
    }
    let footer = read_range(file, path, size, size - FOOTER_AND_MAGIC, FOOTER_AND_MAGIC)?;
    if footer[0] != op::FOOTER {
        return Ok(());
    }
    let mut start = [0u8; 8];
    start.copy_from_slice(&footer[9..17]);
    let summary_start = u64::from_le_bytes(start);
    if summary_start == 0 || summary_start >= size - FOOTER_AND_MAGIC {
        return Ok(());
    }
    let section = read_range(file, path, size, summary_start, size - summary_start)?;
    check_summary_section(&section, summary_start).map_err(|e| damaged(path, summary_start, &e))
}

/// The summary section, driving the mcap crate's sans-I/O summary reader with the file;
/// `None` if the footer says there is none.
fn read_summary(
    file: &mut BufReader<File>,
    size: u64,
    path: &Path,
) -> Result<Option<mcap::Summary>, LogError> {
    let mut reader =
        SummaryReader::new_with_options(SummaryReaderOptions::default().with_file_size(size));
    while let Some(event) = reader.next_event() {
        match event.map_err(|e| summary_error(path, e))? {
            SummaryReadEvent::ReadRequest(n) => {
                let read = file
                    .read(reader.insert(n))
                    .map_err(|e| LogError::io(path, "read", e))?;
                reader.notify_read(read);
            }
            SummaryReadEvent::SeekRequest(to) => {
                let pos = file
                    .seek(to)
                    .map_err(|e| LogError::io(path, "seek in", e))?;
                reader.notify_seeked(pos);
            }
        }
    }
    Ok(reader.finish())
}

fn summary_error(path: &Path, error: McapError) -> LogError {
    match error {
        McapError::BadMagic | McapError::BadFooter | McapError::UnexpectedEof => {
            LogError::Incomplete {
                path: path.to_path_buf(),
                reason: "truncated file: no footer and end magic".to_string(),
            }
        }
        other => LogError::Damaged {
            path: path.to_path_buf(),
            offset: 0,
            reason: format!("summary section: {other}"),
        },
    }
}

/// `length` bytes at `offset`, checked against the file size.
fn read_range(
    file: &mut BufReader<File>,
    path: &Path,
    size: u64,
    offset: u64,
    length: u64,
) -> Result<Vec<u8>, LogError> {
    let end = offset.checked_add(length).filter(|&end| end <= size);
    let (Some(_), Ok(len)) = (end, usize::try_from(length)) else {
        return Err(damaged(
            path,
            offset,
            &format!(
                "an index points past the end of the file ({length} bytes at {offset}, file {size} bytes)"
            ),
        ));
    };
    file.seek(SeekFrom::Start(offset))
        .map_err(|e| LogError::io(path, "seek in", e))?;
    let mut bytes = vec![0u8; len];
    file.read_exact(&mut bytes)
        .map_err(|e| LogError::io(path, "read", e))?;
    Ok(bytes)
}

/// Parses one whole record (opcode, length, body) read from `offset`.
fn parse_at<'a>(bytes: &'a [u8], offset: u64, path: &Path) -> Result<Record<'a>, LogError> {
    let (Some(&opcode), Some(body)) = (bytes.first(), bytes.get(9..)) else {
        return Err(damaged(path, offset, "record shorter than its header"));
    };
    if opcode != op::CHUNK && opcode != op::METADATA {
        return Err(damaged(
            path,
            offset,
            &format!("unexpected record opcode {opcode:#04x} at an indexed offset"),
        ));
    }
    // Field lengths checked before parsing: no allocation a damaged length asks for.
    parse(opcode, body).map_err(|e| damaged(path, offset, &e))
}

/// Fallback for files without usable summary indexes: read everything.
fn read_whole(path: &Path) -> Result<TrialEvents, LogError> {
    let log = TrialReader::open(path)?;
    let events = log
        .messages_on(TRIAL_EVENTS_TOPIC)
        .map(|m| {
            let text: StringMsg = m.decode()?;
            Ok((m.log_time_ns, text.data))
        })
        .collect::<Result<Vec<_>, LogError>>()
        .map_err(|e| damaged(path, 0, &e.to_string()))?;
    Ok(TrialEvents {
        metadata: log.metadata().to_vec(),
        events,
        chunks_read: log.statistics().map_or(0, |s| s.chunk_count as usize),
        chunks_total: log.statistics().map_or(0, |s| s.chunk_count as usize),
        read_whole_file: true,
    })
}
