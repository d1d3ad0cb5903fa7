//! The summary-indexed event reader against the whole-file reader, on the station's own logs,
//! and its refusals (truncated, not MCAP).

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use msgs::{Float32MultiArray, StringMsg};
use serde_json::json;

use super::test_dir::TestDir;
use super::*;

const T0: i64 = 1_732_100_000_000_000_000;
const MS: i64 = 1_000_000;

/// 10 s of keypoints at 100 Hz with events at 0, 2.5, 5, 7.5 s and stop at 10 s.
fn write_trial(path: &Path) -> Vec<(i64, String)> {
    let options = TrialWriterOptions {
        sync_on_flush: false,
        ..TrialWriterOptions::default()
    };
    let mut w = TrialWriter::create(path, options).unwrap();
    w.write_metadata(
        "pomdar_trial",
        BTreeMap::from([("task".to_string(), "V1".to_string())]),
    )
    .unwrap();
    let mut events = Vec::new();
    let keypoints = Float32MultiArray {
        data: (0..66).map(|i| i as f32 * 0.01).collect(),
        ..Float32MultiArray::default()
    };
    for i in 0..=1000 {
        let t = T0 + i * 10 * MS;
        if i % 250 == 0 {
            let event = if i == 0 {
                json!({"event": "start"})
            } else if i == 1000 {
                json!({"event": "stop", "summary": {"frames": i}})
            } else {
                json!({"event": "progress", "value": 1})
            };
            w.write_event(t, &event).unwrap();
            events.push((t, event.to_string()));
        }
        w.write("/ingress/mano", t, t, &keypoints).unwrap();
    }
    w.write_metadata("other", BTreeMap::new()).unwrap();
    w.finish().unwrap();
    events
}

#[test]
fn reads_metadata_and_events_from_the_event_chunks_only() {
    let dir = TestDir::new("event_reader");
    let path = dir.path().join("t.mcap");
    let written = write_trial(&path);
    let read = read_trial_events(&path).unwrap();
    assert!(!read.read_whole_file);
    assert_eq!(read.events, written);
    assert_eq!(read.metadata.len(), 2);
    assert_eq!(
        read.metadata_named("pomdar_trial").unwrap()["task"],
        "V1".to_string()
    );
    // 5 event chunks out of (at least) one per second of keypoints.
    assert_eq!(read.chunks_read, 5);
    assert!(read.chunks_total >= 11, "{}", read.chunks_total);

    // The whole-file reader agrees.
    let whole = TrialReader::open(&path).unwrap();
    let via_whole: Vec<(i64, String)> = whole
        .messages_on(TRIAL_EVENTS_TOPIC)
        .map(|m| (m.log_time_ns, m.decode::<StringMsg>().unwrap().data))
        .collect();
    assert_eq!(via_whole, read.events);
}

fn copy_prefix(from: &Path, to: PathBuf, len: usize) -> PathBuf {
    let bytes = std::fs::read(from).unwrap();
    std::fs::write(&to, &bytes[..len]).unwrap();
    to
}

#[test]
fn a_cut_file_is_a_truncated_file_to_recover() {
    let dir = TestDir::new("event_reader_cut");
    let path = dir.path().join("t.mcap");
    write_trial(&path);
    let size = std::fs::metadata(&path).unwrap().len() as usize;
    for len in [size - 1, size / 2, 20] {
        let cut = copy_prefix(&path, dir.path().join(format!("cut{len}.mcap")), len);
        let err = read_trial_events(&cut).unwrap_err().to_string();
        assert!(
            err.contains("truncated file") && err.contains("pomdar recover"),
            "{len}: {err}"
        );
        assert!(err.contains(&format!("cut{len}.mcap")), "{err}");
    }
}

#[test]
fn other_files_are_not_mcap() {
    let dir = TestDir::new("event_reader_other");
    let path = dir.path().join("notes.mcap");
    std::fs::write(&path, b"just some text, long enough").unwrap();
    let err = read_trial_events(&path).unwrap_err().to_string();
    assert!(err.contains("notes.mcap: not an MCAP file"), "{err}");
    std::fs::write(&path, b"tiny").unwrap();
    let err = read_trial_events(&path).unwrap_err().to_string();
    assert!(err.contains("shorter than the MCAP magic"), "{err}");
    let err = read_trial_events(&dir.path().join("missing.mcap"))
        .unwrap_err()
        .to_string();
    assert!(err.contains("missing.mcap: cannot open"), "{err}");
}

#[test]
fn a_damaged_event_chunk_is_an_error_not_an_allocation() {
    let dir = TestDir::new("event_reader_damaged");
    let path = dir.path().join("t.mcap");
    let options = TrialWriterOptions {
        sync_on_flush: false,
        compression: LogCompression::None,
        ..TrialWriterOptions::default()
    };
    let mut w = TrialWriter::create(&path, options).unwrap();
    w.write_metadata("pomdar_trial", BTreeMap::new()).unwrap();
    w.write_event(T0, &json!({"event": "start"})).unwrap();
    w.finish().unwrap();
    let mut bytes = std::fs::read(&path).unwrap();
    let summary = mcap::Summary::read(&bytes).unwrap().unwrap();
    let chunk = &summary.chunk_indexes[0];
    // Chunk body: start, end, uncompressed size (u64 each), CRC (u32), compression (u32 length
    // + text), records length (u64), then the records: opcode u8, length u64.
    let body = chunk.chunk_start_offset as usize + 9;
    let compression_len = 0;
    let crc = body + 24;
    bytes[crc..crc + 4].copy_from_slice(&[0; 4]); // 0: no CRC to check
    let first_record = body + 24 + 4 + 4 + compression_len + 8;
    bytes[first_record + 1..first_record + 9].copy_from_slice(&(u64::MAX - 7).to_le_bytes());
    let damaged = dir.path().join("damaged.mcap");
    std::fs::write(&damaged, &bytes).unwrap();
    let err = read_trial_events(&damaged).unwrap_err().to_string();
    assert!(err.contains("damaged.mcap: damaged at byte"), "{err}");
}

/// `path`'s bytes with every chunk record's declared uncompressed size set to `declared`
/// (the chunk indexes in the summary keep the true sizes).
fn with_declared_chunk_size(path: &Path, declared: u64) -> Vec<u8> {
    let mut bytes = std::fs::read(path).unwrap();
    let summary = mcap::Summary::read(&bytes).unwrap().unwrap();
    for chunk in &summary.chunk_indexes {
        // Record prefix (opcode u8, length u64), then start and end times (u64 each), then
        // the uncompressed size (u64).
        let at = chunk.chunk_start_offset as usize + 9 + 16;
        bytes[at..at + 8].copy_from_slice(&declared.to_le_bytes());
    }
    bytes
}

#[test]
fn a_chunk_declaring_a_gibibyte_is_refused_before_it_is_decompressed() {
    let dir = TestDir::new("event_reader_bomb");
    let path = dir.path().join("t.mcap");
    write_trial(&path);
    let crafted = dir.path().join("crafted.mcap");
    std::fs::write(&crafted, with_declared_chunk_size(&path, 1 << 30)).unwrap();
    // Both readers refuse on the declared size, before decompressing (the decompressor would
    // allocate the declared size; it is never called): the error is the budget's, not a
    // decompression failure.
    let events = read_trial_events(&crafted).unwrap_err();
    let whole = TrialReader::open(&crafted).unwrap_err();
    for e in [events, whole] {
        assert!(matches!(e, LogError::OverBudget { .. }), "{e:?}");
        let text = e.to_string();
        assert!(text.starts_with(&crafted.display().to_string()), "{text}");
        assert!(
            text.contains("declares 1073741824 bytes uncompressed, over the limit of 67108864 bytes (64 MiB) per chunk"),
            "{text}"
        );
        assert!(text.contains("nothing of it was decompressed"), "{text}");
    }
    // A declared size no allocator could give (8 EiB): still a clean refusal, no attempt.
    std::fs::write(&crafted, with_declared_chunk_size(&path, 1 << 63)).unwrap();
    assert!(matches!(
        read_trial_events(&crafted),
        Err(LogError::OverBudget { .. })
    ));
    assert!(matches!(
        TrialReader::open(&crafted),
        Err(LogError::OverBudget { .. })
    ));
    // The untouched file still reads.
    assert!(read_trial_events(&path).is_ok());
}

#[test]
fn a_small_file_of_many_real_chunks_is_refused_at_its_total_budget() {
    let dir = TestDir::new("event_reader_budget");
    let path = dir.path().join("zeros.mcap");
    let options = TrialWriterOptions {
        sync_on_flush: false,
        ..TrialWriterOptions::default()
    };
    let mut w = TrialWriter::create(&path, options).unwrap();
    // 0.96 MB of zeros and an event per chunk (under the writer's 1 MiB chunk size, so both
    // share a chunk, closed by the event): zstd makes each a few hundred bytes; 300 of them
    // declare 288 MB in all.
    let zeros = Float32MultiArray {
        data: vec![0.0; 240_000],
        ..Float32MultiArray::default()
    };
    for i in 0..300 {
        let t = T0 + i * MS;
        w.write("/ingress/mano", t, t, &zeros).unwrap();
        w.write_event(t, &json!({"event": "progress", "value": 1}))
            .unwrap();
    }
    w.finish().unwrap();
    let size = std::fs::metadata(&path).unwrap().len();
    assert!(size < 1 << 20, "{size} bytes");
    let e = read_trial_events(&path).unwrap_err();
    assert!(matches!(e, LogError::OverBudget { .. }), "{e:?}");
    assert!(
        e.to_string()
            .contains("over this file's decompression budget of 268435456 bytes"),
        "{e}"
    );
    let e = TrialReader::open(&path).unwrap_err();
    assert!(matches!(e, LogError::OverBudget { .. }), "{e:?}");
}
