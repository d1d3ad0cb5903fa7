//! Fuzzing of the trial-log readers on stable Rust: valid logs written by [`TrialWriter`]
//! (zstd, lz4 and uncompressed chunks; finished, and interrupted `.part` files) are mutated
//! at the byte level — bit flips, byte and length-field writes, truncation, extension,
//! insertion, deletion, copied ranges, a splice of another log — and handed to
//! [`TrialReader::from_bytes`], [`read_trial_events`](teleop::mcap_log::read_trial_events)
//! and [`recover`](teleop::mcap_log::recover) through `mcap_oracle`: no panic, errors are
//! `Err`, what succeeds is consistent.
//!
//! The CI budget is a few thousand cases; `PROPTEST_CASES=N` sets a longer run, and `fuzz/`
//! has the same oracle as cargo-fuzz targets (docs/FUZZING.md).

use crate::mcap_oracle;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::sync::atomic::{AtomicU64, Ordering};

use msgs::{Float32MultiArray, Header, JointState, Pose, PoseStamped, Time};
use proptest::prelude::*;
use proptest::sample::Index;
use teleop::mcap_log::{LogCompression, OfferedQos, TrialReader, TrialWriter, TrialWriterOptions};

const MS: i64 = 1_000_000;
/// Log times start here (2024-11-20).
const T0: i64 = 1_732_100_000_000_000_000;

/// Cases per property in CI, unless `PROPTEST_CASES` asks for another number.
fn budget(ci_cases: u32) -> ProptestConfig {
    let mut config = ProptestConfig::default();
    if std::env::var_os("PROPTEST_CASES").is_none() {
        config.cases = ci_cases;
    }
    config.failure_persistence = None;
    config
}

/// This process's scratch directory (removed at the start; files are removed per case). In
/// RAM where there is a tmpfs, so the fsync of every recovered file costs nothing.
fn scratch() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let shm = Path::new("/dev/shm");
        let base = if shm.is_dir() {
            shm.to_path_buf()
        } else {
            std::env::temp_dir()
        };
        let dir = base.join(format!("pomdar-fuzz-mcap-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        std::fs::create_dir_all(&dir).unwrap();
        dir
    })
}

fn unique_name(prefix: &str) -> String {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    format!("{prefix}{}", COUNTER.fetch_add(1, Ordering::Relaxed))
}

/// A short trial as the station writes it: metadata, events, keypoints, wrist poses and joint
/// targets over half a second, small chunks so there are several. With `interrupt`, the
/// writer stops as a killed process does (after a flush, with unflushed writes lost or half
/// written) and the `.part` file is returned.
fn seed_log(compression: LogCompression, interrupt: bool) -> Vec<u8> {
    let path = scratch().join(format!("{}.mcap", unique_name("seed")));
    let options = TrialWriterOptions {
        compression,
        chunk_size_bytes: 1500,
        auto_flush_interval_ns: Some(100 * MS),
        sync_on_flush: false,
        ..TrialWriterOptions::default()
    };
    let mut log = TrialWriter::create(&path, options).unwrap();
    log.write_metadata(
        "pomdar_trial",
        BTreeMap::from([
            ("task".to_string(), "V1".to_string()),
            ("embodiment".to_string(), "orca_full".to_string()),
        ]),
    )
    .unwrap();
    let qos = [OfferedQos::reliable(10)];
    log.add_channel::<Float32MultiArray>("/ingress/mano", &qos)
        .unwrap();
    log.add_channel::<PoseStamped>("/ingress/wrist", &qos)
        .unwrap();
    log.add_channel::<JointState>("/pomdar/hand/joint_targets", &qos)
        .unwrap();
    log.write_event(T0, &serde_json::json!({"event": "start"}))
        .unwrap();
    for i in 0..25_i64 {
        let t = T0 + i * 20 * MS;
        let rows: Vec<[f32; 3]> = (0..22)
            .map(|k| [0.01 * k as f32, 0.002 * i as f32, -0.03])
            .collect();
        log.write(
            "/ingress/mano",
            t,
            t - MS,
            &Float32MultiArray::from_points(&rows).unwrap(),
        )
        .unwrap();
        let header = Header {
            stamp: Time::from_nanos(t),
            frame_id: "world".into(),
        };
        log.write(
            "/ingress/wrist",
            t,
            t - MS,
            &PoseStamped {
                header: header.clone(),
                pose: Pose::default(),
            },
        )
        .unwrap();
        log.write(
            "/pomdar/hand/joint_targets",
            t + MS,
            t + MS,
            &JointState {
                header,
                name: (0..17).map(|j| format!("joint_{j}")).collect(),
                position: (0..17).map(|j| 0.01 * (i + j) as f64).collect(),
                velocity: vec![],
                effort: vec![],
            },
        )
        .unwrap();
        if i == 12 {
            log.write_event(t, &serde_json::json!({"event": "progress", "value": 1}))
                .unwrap();
        }
    }
    if interrupt {
        let part = log.part_path().to_path_buf();
        // A killed process: nothing more is written, the buffered tail is lost.
        std::mem::forget(log);
        let bytes = std::fs::read(&part).unwrap();
        std::fs::remove_file(&part).ok();
        return bytes;
    }
    log.write_event(T0 + 600 * MS, &serde_json::json!({"event": "stop"}))
        .unwrap();
    log.finish().unwrap();
    let bytes = std::fs::read(&path).unwrap();
    std::fs::remove_file(&path).ok();
    bytes
}

/// The seed logs, written once per process.
fn seeds() -> &'static [Vec<u8>] {
    static SEEDS: OnceLock<Vec<Vec<u8>>> = OnceLock::new();
    SEEDS.get_or_init(|| {
        vec![
            seed_log(LogCompression::Zstd, false),
            seed_log(LogCompression::Lz4, false),
            seed_log(LogCompression::None, false),
            seed_log(LogCompression::Zstd, true),
            seed_log(LogCompression::None, true),
        ]
    })
}

/// One edit of a log file.
#[derive(Debug, Clone)]
enum Mutation {
    FlipBit(Index, u8),
    SetByte(Index, u8),
    /// A record length, count or offset field made huge, zero or random.
    SetU64(Index, u64),
    SetU32(Index, u32),
    Truncate(Index),
    Extend(Vec<u8>),
    Insert(Index, Vec<u8>),
    Remove(Index, usize),
    CopyRange(Index, Index, usize),
    /// Replace a range with the same range of another seed (records of another log).
    Splice(Index, Index, usize),
}

fn special_u64() -> impl Strategy<Value = u64> {
    prop_oneof![
        Just(0),
        Just(1),
        Just(u64::MAX),
        Just(u64::from(u32::MAX)),
        Just(1 << 40),
        any::<u64>(),
        0u64..4096,
    ]
}

fn mutations() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (any::<Index>(), 0u8..8).prop_map(|(i, b)| Mutation::FlipBit(i, b)),
        2 => (any::<Index>(), any::<u8>()).prop_map(|(i, b)| Mutation::SetByte(i, b)),
        2 => (any::<Index>(), special_u64()).prop_map(|(i, v)| Mutation::SetU64(i, v)),
        1 => (any::<Index>(), any::<u32>()).prop_map(|(i, v)| Mutation::SetU32(i, v)),
        2 => any::<Index>().prop_map(Mutation::Truncate),
        1 => prop::collection::vec(any::<u8>(), 1..64).prop_map(Mutation::Extend),
        1 => (any::<Index>(), prop::collection::vec(any::<u8>(), 1..32))
            .prop_map(|(i, b)| Mutation::Insert(i, b)),
        1 => (any::<Index>(), 1usize..64).prop_map(|(i, n)| Mutation::Remove(i, n)),
        1 => (any::<Index>(), any::<Index>(), 1usize..256)
            .prop_map(|(a, b, n)| Mutation::CopyRange(a, b, n)),
        1 => (any::<Index>(), any::<Index>(), 1usize..512)
            .prop_map(|(s, a, n)| Mutation::Splice(s, a, n)),
    ]
}

fn apply(bytes: &mut Vec<u8>, mutation: &Mutation) {
    let len = bytes.len();
    match mutation {
        Mutation::FlipBit(at, bit) if len > 0 => bytes[at.index(len)] ^= 1 << bit,
        Mutation::SetByte(at, byte) if len > 0 => bytes[at.index(len)] = *byte,
        Mutation::SetU64(at, value) if len >= 8 => {
            let i = at.index(len - 7);
            bytes[i..i + 8].copy_from_slice(&value.to_le_bytes());
        }
        Mutation::SetU32(at, value) if len >= 4 => {
            let i = at.index(len - 3);
            bytes[i..i + 4].copy_from_slice(&value.to_le_bytes());
        }
        Mutation::Truncate(at) => bytes.truncate(at.index(len + 1)),
        Mutation::Extend(tail) => bytes.extend_from_slice(tail),
        Mutation::Insert(at, new) => {
            let i = at.index(len + 1);
            bytes.splice(i..i, new.iter().copied());
        }
        Mutation::Remove(at, n) if len > 0 => {
            let i = at.index(len);
            bytes.drain(i..(i + n).min(len));
        }
        Mutation::CopyRange(from, to, n) if len > 0 => {
            let (f, t) = (from.index(len), to.index(len));
            let n = (*n).min(len - f).min(len - t);
            bytes.copy_within(f..f + n, t);
        }
        Mutation::Splice(seed, at, n) if len > 0 => {
            let other = &seeds()[seed.index(seeds().len())];
            let i = at.index(len.min(other.len()));
            let n = (*n).min(len - i).min(other.len() - i);
            bytes[i..i + n].copy_from_slice(&other[i..i + n]);
        }
        _ => {}
    }
}

#[test]
fn the_seeds_are_what_they_claim() {
    for (i, seed) in seeds().iter().enumerate() {
        let log = mcap_oracle::check_trial_reader(seed);
        if i < 3 {
            let log = log.unwrap_or_else(|| panic!("finished seed {i} does not read"));
            assert_eq!(log.message_count(), 78, "seed {i}");
            assert!(log.statistics().unwrap().chunk_count > 3, "seed {i}");
        } else {
            assert!(log.is_none(), "interrupted seed {i} read as complete");
            mcap_oracle::check_files(seed, scratch(), &unique_name("seed-recover"));
        }
    }
}

proptest! {
    #![proptest_config(budget(2000))]

    #[test]
    fn mutated_logs_read_consistently_or_fail(
        seed in any::<Index>(),
        edits in prop::collection::vec(mutations(), 1..5),
    ) {
        let mut bytes = seeds()[seed.index(seeds().len())].clone();
        for edit in &edits {
            apply(&mut bytes, edit);
        }
        mcap_oracle::check_trial_reader(&bytes);
    }

    #[test]
    fn mutated_logs_give_events_and_recover_to_readable_logs_or_fail(
        seed in any::<Index>(),
        edits in prop::collection::vec(mutations(), 1..5),
    ) {
        let mut bytes = seeds()[seed.index(seeds().len())].clone();
        for edit in &edits {
            apply(&mut bytes, edit);
        }
        mcap_oracle::check_files(&bytes, scratch(), &unique_name("case"));
    }
}

proptest! {
    #![proptest_config(budget(500))]

    /// Random bytes behind a valid magic and header: the readers get past the first checks.
    #[test]
    fn random_records_after_a_valid_header_fail_cleanly(
        keep in 8usize..200,
        tail in prop::collection::vec(any::<u8>(), 0..600),
    ) {
        let mut bytes = seeds()[2][..keep].to_vec();
        bytes.extend(tail);
        mcap_oracle::check_trial_reader(&bytes);
        mcap_oracle::check_files(&bytes, scratch(), &unique_name("random"));
    }
}

fn mcap_string(s: &str) -> Vec<u8> {
    let mut out = (s.len() as u32).to_le_bytes().to_vec();
    out.extend_from_slice(s.as_bytes());
    out
}

fn mcap_record(opcode: u8, body: &[u8]) -> Vec<u8> {
    let mut out = vec![opcode];
    out.extend_from_slice(&(body.len() as u64).to_le_bytes());
    out.extend_from_slice(body);
    out
}

/// A hand-made MCAP file: magic, header, one chunk holding `records` (as stored, compressed
/// or not) that decompress to `uncompressed_size` bytes, followed inside the chunk record by
/// `padding` zero bytes.
fn file_with_chunk(
    compression: &str,
    uncompressed_size: u64,
    records: &[u8],
    padding: usize,
) -> Vec<u8> {
    let mut chunk = Vec::new();
    chunk.extend_from_slice(&0u64.to_le_bytes()); // message start time
    chunk.extend_from_slice(&0u64.to_le_bytes()); // message end time
    chunk.extend_from_slice(&uncompressed_size.to_le_bytes());
    chunk.extend_from_slice(&0u32.to_le_bytes()); // uncompressed CRC: none
    chunk.extend_from_slice(&mcap_string(compression));
    chunk.extend_from_slice(&(records.len() as u64).to_le_bytes());
    chunk.extend_from_slice(records);
    chunk.resize(chunk.len() + padding, 0);
    let mut header = mcap_string("ros2");
    header.extend_from_slice(&mcap_string("fuzz"));
    let mut file = b"\x89MCAP0\r\n".to_vec();
    file.extend(mcap_record(0x01, &header));
    file.extend(mcap_record(0x06, &chunk));
    file
}

/// Both readers call `file` damaged at its chunk, keeping nothing of it.
fn assert_damaged_chunk(file: &[u8], name: &str) {
    let error = TrialReader::from_bytes(file, Path::new(name)).unwrap_err();
    assert!(error.to_string().contains("chunk"), "{error}");
    let part = scratch().join(format!("{name}.part"));
    std::fs::write(&part, file).unwrap();
    let out = scratch().join(name);
    let report = teleop::mcap_log::recover(&part, &out).unwrap();
    assert!(report.tail_damaged, "{report}");
    assert_eq!(report.message_count, 0);
    std::fs::remove_file(&part).ok();
    std::fs::remove_file(&out).ok();
}

/// A compressed chunk whose one record claims 2^62 bytes. Found by the fuzzing above: the
/// mcap crate's `ChunkReader` reserved memory for the claimed length and the process aborted
/// ("memory allocation of 144680345676188733 bytes failed"). The chunk is a zstd frame with
/// one raw (stored) block, so the record inside needs no compressor to build.
#[test]
fn a_record_in_a_chunk_claiming_petabytes_is_damage_not_an_abort() {
    // A message record (opcode 0x05) claiming 2^62 bytes.
    let mut inner = vec![0x05];
    inner.extend_from_slice(&(1u64 << 62).to_le_bytes());
    // zstd frame: magic, descriptor (single segment, 1-byte content size), the size, then one
    // last raw block holding `inner` verbatim.
    let mut frame = vec![0x28, 0xB5, 0x2F, 0xFD, 0x20, inner.len() as u8];
    let block_header = 1 | ((inner.len() as u32) << 3);
    frame.extend_from_slice(&block_header.to_le_bytes()[..3]);
    frame.extend_from_slice(&inner);
    assert_damaged_chunk(
        &file_with_chunk("zstd", inner.len() as u64, &frame, 0),
        "petabytes.mcap",
    );
}

/// A decompression bomb: a 60-byte chunk declaring 1 GiB uncompressed. The
/// declared size is what decompressing would allocate; the budget refuses it first, naming
/// the limit, and recovery keeps nothing of the chunk.
#[test]
fn a_chunk_declaring_a_gibibyte_is_over_budget_not_an_allocation() {
    let inner = vec![0u8; 16];
    let mut frame = vec![0x28, 0xB5, 0x2F, 0xFD, 0x20, inner.len() as u8];
    let block_header = 1 | ((inner.len() as u32) << 3);
    frame.extend_from_slice(&block_header.to_le_bytes()[..3]);
    frame.extend_from_slice(&inner);
    let file = file_with_chunk("zstd", 1 << 30, &frame, 0);
    let error = TrialReader::from_bytes(&file, Path::new("bomb.mcap")).unwrap_err();
    assert!(
        matches!(error, teleop::mcap_log::LogError::OverBudget { .. }),
        "{error:?}"
    );
    assert!(error.to_string().contains("64 MiB"), "{error}");
    assert_damaged_chunk(&file, "bomb.mcap");
}

/// An uncompressed chunk whose record claims more bytes than the chunk's records hold, with
/// padding after them in the chunk record and an uncompressed size that allows the claim. Found by the fuzzing above (of the first version
/// of the fix for the case before): the reader took the padding as the rest of the record and
/// panicked subtracting its length from what was left of the chunk.
#[test]
fn a_record_overrunning_an_uncompressed_chunk_is_damage_not_a_panic() {
    let mut inner = vec![0x05];
    inner.extend_from_slice(&100u64.to_le_bytes());
    inner.extend_from_slice(&[0; 10]);
    assert_damaged_chunk(&file_with_chunk("", 1000, &inner, 200), "overrun.mcap");
}

/// A channel record whose topic claims 3.7 GB. Found by cargo-fuzz (`mcap_files`): the mcap
/// crate's record parser reserved the claimed string length before reading it (libFuzzer:
/// "out-of-memory (malloc(3707764739))"; then 4.3 GB for a chunk index's compression name in
/// the event reader's summary). Field lengths are now checked against the record first, in
/// chunks, in the data section and in the summary.
#[test]
fn a_string_claiming_gigabytes_is_damage_not_an_allocation() {
    let mut channel = vec![1, 0, 0, 0]; // channel id 1, no schema
    channel.extend_from_slice(&0xDD00_0000u32.to_le_bytes()); // the topic's claimed length
    channel.extend_from_slice(b"/topic");
    let record = mcap_record(0x04, &channel);
    let in_chunk = file_with_chunk("", record.len() as u64, &record, 0);
    let error = TrialReader::from_bytes(&in_chunk, Path::new("huge.mcap")).unwrap_err();
    assert!(error.to_string().contains("topic claims"), "{error}");
    assert_damaged_chunk(&in_chunk, "huge_topic.mcap");

    // The same in the summary of a finished log: its first channel record.
    let mut log = seeds()[0].clone();
    let footer = log.len() - 8 - 29;
    assert_eq!(log[footer], 0x02, "footer record");
    let summary_start =
        u64::from_le_bytes(log[footer + 9..footer + 17].try_into().unwrap()) as usize;
    let mut at = summary_start;
    while log[at] != 0x04 {
        let len = u64::from_le_bytes(log[at + 1..at + 9].try_into().unwrap()) as usize;
        at += 9 + len;
    }
    log[at + 13..at + 17].copy_from_slice(&0xDD00_0000u32.to_le_bytes());
    let error = TrialReader::from_bytes(&log, Path::new("summary.mcap")).unwrap_err();
    assert!(
        error.to_string().contains("summary record 0x04") && error.to_string().contains("topic"),
        "{error}"
    );
    // Scoring's event reader reads the summary from disk (cargo-fuzz found the same in a
    // chunk index there).
    let path = scratch().join("huge_summary.mcap");
    std::fs::write(&path, &log).unwrap();
    let error = teleop::mcap_log::read_trial_events(&path).unwrap_err();
    std::fs::remove_file(&path).ok();
    assert!(error.to_string().contains("summary record 0x04"), "{error}");
}

/// Small valid chunks still read: one channel record, stored, and in a zstd frame whose raw
/// block makes it larger than its content. (The first bounded reader limited every length to
/// the chunk's uncompressed size, the chunk's own 40-byte header and its compressed bytes
/// included, and refused both.)
#[test]
fn small_chunks_stored_or_compressed_larger_than_their_content_read() {
    let mut channel = vec![1, 0, 0, 0];
    channel.extend_from_slice(&mcap_string("/topic"));
    channel.extend_from_slice(&mcap_string("cdr"));
    channel.extend_from_slice(&0u32.to_le_bytes()); // no metadata
    let record = mcap_record(0x04, &channel);
    let mut frame = vec![0x28, 0xB5, 0x2F, 0xFD, 0x20, record.len() as u8];
    frame.extend_from_slice(&(1 | ((record.len() as u32) << 3)).to_le_bytes()[..3]);
    frame.extend_from_slice(&record);
    for (name, file) in [
        (
            "stored",
            file_with_chunk("", record.len() as u64, &record, 0),
        ),
        (
            "zstd",
            file_with_chunk("zstd", record.len() as u64, &frame, 0),
        ),
    ] {
        let part = scratch().join(format!("small_{name}.mcap.part"));
        std::fs::write(&part, &file).unwrap();
        let out = scratch().join(format!("small_{name}.mcap"));
        let report = teleop::mcap_log::recover(&part, &out).unwrap();
        assert!(!report.tail_damaged, "{name}: {report}");
        assert_eq!(report.messages_per_topic.get("/topic"), Some(&0), "{name}");
        std::fs::remove_file(&part).ok();
        std::fs::remove_file(&out).ok();
    }
}
