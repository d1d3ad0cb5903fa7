//! One pass over an MCAP file's data section, in file order, that stops at the first record it
//! cannot read: the common ground of [`TrialReader`](super::TrialReader) (which insists on a
//! clean ending) and [`recover`](super::recover()) (which keeps what came before the damage).
//!
//! The top-level framing (opcode `u8`, length `u64` LE, body) is walked here so that every
//! stop has an exact byte offset; records are parsed by `mcap::parse_record` and chunks
//! decompressed and CRC-checked by [`chunk_records`]. Checks beyond parsing: the
//! first record is the header; schema ids are not 0; a schema or channel id redefined must
//! have the same content; a channel's schema and a message's channel must already be known.
//! An opcode of 0 (a zero-filled tail after a power cut) is damage.
//!
//! A chunk counts as a whole: if any of it cannot be read, none of it is kept. Records after
//! the data end record (the summary) are not scanned.

use std::collections::HashMap;

use mcap::records::{self, AttachmentHeader, MessageHeader, Record, op};
use mcap::sans_io::{LinearReadEvent, LinearReader, LinearReaderOptions};

use super::decompression_budget::{DecompressionBudget, MAX_CHUNK_BYTES};

/// One record of the data section that the log readers care about.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum DataRecord {
    /// A schema (first definition of its id).
    Schema {
        /// Schema id (not 0).
        id: u16,
        /// `pkg/msg/Type` for ROS 2.
        name: String,
        /// `ros2msg` for ROS 2.
        encoding: String,
        /// The schema text.
        data: Vec<u8>,
    },
    /// A channel (first definition of its id).
    Channel(records::Channel),
    /// A message.
    Message {
        /// Channel, sequence and times.
        header: MessageHeader,
        /// The payload.
        data: Vec<u8>,
    },
    /// A metadata record.
    Metadata(records::Metadata),
    /// An attachment.
    Attachment {
        /// Name, media type and times.
        header: AttachmentHeader,
        /// The attached bytes.
        data: Vec<u8>,
    },
}

/// How the scan ended.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum ScanEnd {
    /// At the data end record: the file was finished (the summary follows).
    DataEnd,
    /// At the end of the file, after a complete record, without a data end record.
    EndOfFile,
    /// At a chunk over the file's decompression budget (not decompressed).
    OverBudget {
        /// Byte offset where that chunk starts.
        offset: u64,
        /// Which limit it breaks.
        reason: String,
    },
    /// At a record that cannot be read.
    Damaged {
        /// Byte offset where that record starts.
        offset: u64,
        /// Why it cannot be read.
        reason: String,
    },
}

/// What [`scan`] found.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ScannedLog {
    /// Header `profile`.
    pub profile: String,
    /// Header `library`.
    pub library: String,
    /// Data records in file order, up to the end of the scan.
    pub records: Vec<DataRecord>,
    /// Offset just past the last record kept (or the data end record).
    pub intact_end: u64,
    /// Why the scan stopped.
    pub end: ScanEnd,
}

/// Largest decompressed chunk accepted (a damaged size field must not exhaust memory); the
/// readers' [`DecompressionBudget`] refuses such a chunk before this is reached.
const MAX_CHUNK_UNCOMPRESSED_BYTES: u64 = MAX_CHUNK_BYTES;
const RECORD_PREFIX: usize = 9;

/// Scans `bytes` up to the data end record, the end of the file or the first damage. `Err`
/// says why it is not an MCAP file at all (no magic, or no readable header record).
pub(crate) fn scan(bytes: &[u8]) -> Result<ScannedLog, String> {
    if bytes.len() < mcap::MAGIC.len() || !bytes.starts_with(mcap::MAGIC) {
        return Err(format!(
            "{} bytes, not starting with the MCAP magic",
            bytes.len()
        ));
    }
    let mut offset = mcap::MAGIC.len();
    let header = match next_frame(bytes, offset) {
        Ok((op::HEADER, body, next)) => match parse(op::HEADER, body) {
            Ok(Record::Header(h)) => {
                offset = next;
                h
            }
            Ok(_) | Err(_) => return Err("header record does not parse".to_string()),
        },
        Ok((opcode, _, _)) => {
            return Err(format!(
                "first record has opcode {opcode:#04x}, not a header"
            ));
        }
        Err(reason) => return Err(format!("header record: {reason}")),
    };
    let mut state = ScanState {
        intact_end: offset,
        ..ScanState::default()
    };
    let mut budget = DecompressionBudget::for_file(bytes.len() as u64);
    let end = loop {
        if offset == bytes.len() {
            break ScanEnd::EndOfFile;
        }
        let damaged = |reason: String| ScanEnd::Damaged {
            offset: offset as u64,
            reason,
        };
        let (opcode, body, next) = match next_frame(bytes, offset) {
            Ok(frame) => frame,
            Err(reason) => break damaged(reason),
        };
        let outcome = match opcode {
            0 => Err("opcode 0 (zero-filled or overwritten bytes)".to_string()),
            op::DATA_END => {
                offset = next;
                break ScanEnd::DataEnd;
            }
            op::CHUNK => {
                let record = &bytes[offset..next];
                match chunk_declared_size(record) {
                    Err(reason) => break damaged(reason),
                    Ok(declared) => {
                        if let Err(reason) = budget.charge(declared) {
                            break ScanEnd::OverBudget {
                                offset: offset as u64,
                                reason,
                            };
                        }
                    }
                }
                state.take_chunk(record)
            }
            op::SCHEMA | op::CHANNEL | op::MESSAGE | op::METADATA => {
                parse(opcode, body).and_then(|record| state.take(record))
            }
            op::ATTACHMENT => parse(opcode, body).and_then(|record| state.take(record)),
            op::HEADER => Err("a second header record".to_string()),
            // Indexes, statistics, private records: nothing to keep.
            _ => Ok(()),
        };
        if let Err(reason) = outcome {
            break damaged(reason);
        }
        offset = next;
        state.intact_end = offset;
    };
    let intact_end = match end {
        ScanEnd::DataEnd => offset,
        _ => state.intact_end,
    } as u64;
    Ok(ScannedLog {
        profile: header.profile,
        library: header.library,
        records: state.records,
        intact_end,
        end,
    })
}

/// The record framed at `offset`: `(opcode, body, offset after it)`.
fn next_frame(bytes: &[u8], offset: usize) -> Result<(u8, &[u8], usize), String> {
    let rest = &bytes[offset..];
    if rest.len() < RECORD_PREFIX {
        return Err(format!(
            "file ends {} bytes into a record prefix",
            rest.len()
        ));
    }
    let opcode = rest[0];
    let mut len_bytes = [0u8; 8];
    len_bytes.copy_from_slice(&rest[1..RECORD_PREFIX]);
    let len = u64::from_le_bytes(len_bytes);
    let available = (rest.len() - RECORD_PREFIX) as u64;
    if len > available {
        return Err(format!(
            "record {opcode:#04x} claims {len} bytes, only {available} remain (unterminated)"
        ));
    }
    let end = RECORD_PREFIX + len as usize;
    Ok((opcode, &rest[RECORD_PREFIX..end], offset + end))
}

/// The uncompressed size a chunk record (as framed in the file) declares: what decompressing
/// it would allocate, read before anything is decompressed.
pub(crate) fn chunk_declared_size(record: &[u8]) -> Result<u64, String> {
    let body = record.get(RECORD_PREFIX..).unwrap_or_default();
    match parse(op::CHUNK, body)? {
        Record::Chunk { header, .. } => Ok(header.uncompressed_size),
        _ => Err("chunk record does not parse as a chunk".to_string()),
    }
}

/// The records inside one chunk record (`record`: opcode, length and body, as framed in the
/// file), decompressed and CRC-checked.
///
/// Not `mcap::read::ChunkReader`, which trusts the length of each record inside a chunk:
/// fuzzing found a compressed chunk whose record claimed 144 PB making it reserve that much
/// memory, and the process aborted. Here the mcap crate's sans-I/O reader runs with a record
/// length limit of the larger of the chunk's uncompressed size (itself at most
/// [`MAX_CHUNK_UNCOMPRESSED_BYTES`]) and the chunk record's own length. Fed the whole chunk record, that reader would read an
/// uncompressed chunk's record on into the padding after it and then subtract with overflow
/// (a panic, also found by fuzzing), so an uncompressed chunk's framing is walked first.
pub(crate) fn chunk_records(record: &[u8]) -> Result<Vec<Record<'static>>, String> {
    let body = record.get(RECORD_PREFIX..).unwrap_or_default();
    let Record::Chunk { header, data } = parse(op::CHUNK, body)? else {
        return Err("chunk record does not parse as a chunk".to_string());
    };
    let uncompressed_size = header.uncompressed_size;
    let too_large = || format!("chunk claims {uncompressed_size} uncompressed bytes");
    if uncompressed_size > MAX_CHUNK_UNCOMPRESSED_BYTES {
        return Err(too_large());
    }
    // Nothing in the chunk is longer than its content or than the chunk itself: the chunk's
    // own header and compressed bytes are checked against the limit too, and compressed data
    // can be longer than its content.
    let limit =
        usize::try_from(uncompressed_size.max(record.len() as u64)).map_err(|_| too_large())?;
    if header.compression.is_empty() {
        let mut offset = 0;
        while offset < data.len() {
            let (_, _, next) =
                next_frame(&data, offset).map_err(|reason| format!("in chunk: {reason}"))?;
            offset = next;
        }
    }
    let mut reader = LinearReader::new_with_options(
        LinearReaderOptions::default()
            .with_skip_start_magic(true)
            .with_skip_end_magic(true)
            .with_validate_chunk_crcs(true)
            .with_record_length_limit(limit),
    );
    let mut rest = record;
    let mut records = Vec::new();
    while let Some(event) = reader.next_event() {
        match event.map_err(|e| format!("chunk: {e}"))? {
            LinearReadEvent::ReadRequest(wanted) => {
                let n = wanted.min(rest.len());
                reader.insert(n).copy_from_slice(&rest[..n]);
                reader.notify_read(n);
                rest = &rest[n..];
            }
            LinearReadEvent::Record { data, opcode } => records.push(
                parse(opcode, data)
                    .map_err(|e| format!("chunk: {e}"))?
                    .into_owned(),
            ),
        }
    }
    Ok(records)
}

/// Checks the field lengths of every record of the summary section, which starts at
/// `summary_start` (0: none) and ends at the footer, before `mcap::Summary::read` parses them.
pub(crate) fn check_summary_fields(bytes: &[u8], summary_start: u64) -> Result<(), String> {
    if summary_start == 0 {
        return Ok(());
    }
    let section = usize::try_from(summary_start)
        .ok()
        .and_then(|start| bytes.get(start..))
        .ok_or_else(|| format!("summary start {summary_start} is beyond the file"))?;
    check_summary_section(section, summary_start)
}

/// [`check_summary_fields`] on the bytes from the summary's start (at file offset `at`) to
/// the end of the file.
pub(crate) fn check_summary_section(section: &[u8], at: u64) -> Result<(), String> {
    let mut offset = 0;
    loop {
        let (opcode, body, next) =
            next_frame(section, offset).map_err(|reason| format!("summary: {reason}"))?;
        if opcode == op::FOOTER {
            return Ok(());
        }
        check_field_lengths(opcode, body).map_err(|e| {
            format!(
                "summary record {opcode:#04x} at byte {}: {e}",
                at + offset as u64
            )
        })?;
        offset = next;
    }
}

/// Parses one record body, after [`check_field_lengths`].
pub(crate) fn parse(opcode: u8, body: &[u8]) -> Result<Record<'_>, String> {
    check_field_lengths(opcode, body).map_err(|e| format!("record {opcode:#04x}: {e}"))?;
    mcap::parse_record(opcode, body).map_err(|e| format!("record {opcode:#04x}: {e}"))
}

/// Checks that every length-prefixed field of a record fits in its body.
///
/// `mcap::parse_record` reserves memory for each string, byte array and map a record
/// claims before it reads them (up to 4 GiB for a `u32` length; cargo-fuzz found a damaged
/// channel record asking for 3.7 GB), and slices an attachment assuming its fields fit. The
/// layouts are the MCAP specification's; records this module does not parse pass unchecked.
fn check_field_lengths(opcode: u8, body: &[u8]) -> Result<(), String> {
    let mut fields = Fields { body, at: 0 };
    match opcode {
        op::HEADER => {
            fields.string("profile")?;
            fields.string("library")?;
        }
        op::SCHEMA => {
            fields.skip(2, "id")?;
            fields.string("name")?;
            fields.string("encoding")?;
            fields.bytes(4, "data")?;
        }
        op::CHANNEL => {
            fields.skip(4, "ids")?;
            fields.string("topic")?;
            fields.string("message_encoding")?;
            fields.string_map("metadata")?;
        }
        op::CHUNK => {
            fields.skip(28, "times, size and CRC")?;
            fields.string("compression")?;
            fields.bytes(8, "records")?;
        }
        op::METADATA => {
            fields.string("name")?;
            fields.string_map("metadata")?;
        }
        op::ATTACHMENT => {
            fields.skip(16, "times")?;
            fields.string("name")?;
            fields.string("media_type")?;
            fields.bytes(8, "data")?;
            fields.skip(4, "crc")?;
        }
        // The summary section's records.
        op::MESSAGE_INDEX => {
            fields.skip(2, "channel id")?;
            fields.bytes(4, "records")?;
        }
        op::CHUNK_INDEX => {
            fields.skip(32, "times and offsets")?;
            fields.bytes(4, "message_index_offsets")?;
            fields.skip(8, "message_index_length")?;
            fields.string("compression")?;
            fields.skip(16, "sizes")?;
        }
        op::ATTACHMENT_INDEX => {
            fields.skip(40, "offsets, times and size")?;
            fields.string("name")?;
            fields.string("media_type")?;
        }
        op::STATISTICS => {
            fields.skip(42, "counts and times")?;
            fields.bytes(4, "channel_message_counts")?;
        }
        op::METADATA_INDEX => {
            fields.skip(16, "offset and length")?;
            fields.string("name")?;
        }
        _ => {}
    }
    Ok(())
}

/// A cursor over a record body that checks each field against what is left.
struct Fields<'a> {
    body: &'a [u8],
    at: usize,
}

impl Fields<'_> {
    fn remaining(&self) -> usize {
        self.body.len() - self.at
    }

    fn skip(&mut self, n: usize, what: &str) -> Result<(), String> {
        if n > self.remaining() {
            return Err(format!(
                "{what}: the record ends {} bytes in",
                self.body.len()
            ));
        }
        self.at += n;
        Ok(())
    }

    /// A length prefix of `width` bytes (4 or 8, little-endian), then that many bytes.
    fn bytes(&mut self, width: usize, what: &str) -> Result<(), String> {
        let start = self.at;
        self.skip(width, what)?;
        let mut prefix = [0u8; 8];
        prefix[..width].copy_from_slice(&self.body[start..start + width]);
        let len = u64::from_le_bytes(prefix);
        if len > self.remaining() as u64 {
            return Err(format!(
                "{what} claims {len} bytes, the record has {} left",
                self.remaining()
            ));
        }
        self.at += len as usize;
        Ok(())
    }

    fn string(&mut self, what: &str) -> Result<(), String> {
        self.bytes(4, what)
    }

    /// A map of strings: a `u32` byte length, then key and value strings filling it exactly.
    fn string_map(&mut self, what: &str) -> Result<(), String> {
        let start = self.at + 4;
        self.bytes(4, what)?;
        let mut entries = Fields {
            body: &self.body[start..self.at],
            at: 0,
        };
        while entries.remaining() > 0 {
            entries.string(what)?;
            entries.string(what)?;
        }
        Ok(())
    }
}

#[derive(Default)]
struct ScanState {
    schemas: HashMap<u16, (String, String, Vec<u8>)>,
    channels: HashMap<u16, records::Channel>,
    records: Vec<DataRecord>,
    intact_end: usize,
}

impl ScanState {
    /// Decompresses a whole chunk (`record`, as framed in the file), then takes its records;
    /// on any failure, none of them.
    fn take_chunk(&mut self, record: &[u8]) -> Result<(), String> {
        let inner = chunk_records(record)?;
        let (record_count, schema_ids, channel_ids) = (
            self.records.len(),
            self.schemas.keys().copied().collect::<Vec<_>>(),
            self.channels.keys().copied().collect::<Vec<_>>(),
        );
        for record in inner {
            let kept = match record {
                Record::Schema { .. } | Record::Channel(_) | Record::Message { .. } => {
                    self.take(record)
                }
                _ => Ok(()),
            };
            if let Err(reason) = kept {
                // Roll back the partial chunk.
                self.records.truncate(record_count);
                self.schemas.retain(|id, _| schema_ids.contains(id));
                self.channels.retain(|id, _| channel_ids.contains(id));
                return Err(format!("in chunk: {reason}"));
            }
        }
        Ok(())
    }

    /// Checks one record against what came before and keeps it.
    fn take(&mut self, record: Record<'_>) -> Result<(), String> {
        match record {
            Record::Schema { header, data } => {
                if header.id == 0 {
                    return Err(format!("schema {:?} has id 0", header.name));
                }
                let content = (header.name, header.encoding, data.into_owned());
                match self.schemas.get(&header.id) {
                    Some(existing) if *existing == content => {}
                    Some(_) => return Err(format!("schema {} redefined differently", header.id)),
                    None => {
                        self.records.push(DataRecord::Schema {
                            id: header.id,
                            name: content.0.clone(),
                            encoding: content.1.clone(),
                            data: content.2.clone(),
                        });
                        self.schemas.insert(header.id, content);
                    }
                }
            }
            Record::Channel(channel) => {
                if channel.schema_id != 0 && !self.schemas.contains_key(&channel.schema_id) {
                    return Err(format!(
                        "channel {} ({}) refers to unknown schema {}",
                        channel.id, channel.topic, channel.schema_id
                    ));
                }
                match self.channels.get(&channel.id) {
                    Some(existing) if *existing == channel => {}
                    Some(_) => return Err(format!("channel {} redefined differently", channel.id)),
                    None => {
                        self.records.push(DataRecord::Channel(channel.clone()));
                        self.channels.insert(channel.id, channel);
                    }
                }
            }
            Record::Message { header, data } => {
                if !self.channels.contains_key(&header.channel_id) {
                    return Err(format!(
                        "message refers to unknown channel {}",
                        header.channel_id
                    ));
                }
                self.records.push(DataRecord::Message {
                    header,
                    data: data.into_owned(),
                });
            }
            Record::Metadata(metadata) => self.records.push(DataRecord::Metadata(metadata)),
            Record::Attachment { header, data, .. } => self.records.push(DataRecord::Attachment {
                header,
                data: data.into_owned(),
            }),
            _ => {}
        }
        Ok(())
    }
}
