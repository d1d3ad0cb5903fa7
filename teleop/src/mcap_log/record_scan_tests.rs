//! The scan stops exactly where the readable data ends.

#![allow(clippy::unwrap_used)]

use msgs::StringMsg;

use super::record_scan::{DataRecord, ScanEnd, scan};
use super::test_dir::TestDir;
use super::*;

fn count_messages(records: &[DataRecord]) -> usize {
    records
        .iter()
        .filter(|r| matches!(r, DataRecord::Message { .. }))
        .count()
}

/// A finished file with two flushed chunks of 3 messages each.
fn two_chunk_file(dir: &TestDir) -> Vec<u8> {
    let path = dir.path().join("t.mcap");
    let mut w = TrialWriter::create(
        &path,
        TrialWriterOptions {
            sync_on_flush: false,
            ..TrialWriterOptions::default()
        },
    )
    .unwrap();
    for t in 0..6 {
        w.write(
            "/x",
            t,
            t,
            &StringMsg {
                data: t.to_string(),
            },
        )
        .unwrap();
        if t == 2 {
            w.flush().unwrap();
        }
    }
    w.finish().unwrap();
    std::fs::read(&path).unwrap()
}

#[test]
fn finished_file_ends_at_data_end() {
    let dir = TestDir::new("scan_finished");
    let bytes = two_chunk_file(&dir);
    let scanned = scan(&bytes).unwrap();
    assert_eq!(scanned.end, ScanEnd::DataEnd);
    assert_eq!(scanned.profile, "ros2");
    assert_eq!(count_messages(&scanned.records), 6);
}

#[test]
fn damage_stops_the_scan_at_the_damaged_chunk() {
    let dir = TestDir::new("scan_damage");
    let bytes = two_chunk_file(&dir);
    let summary = mcap::Summary::read(&bytes).unwrap().unwrap();
    let mut chunks = summary.chunk_indexes.clone();
    chunks.sort_by_key(|c| c.chunk_start_offset);
    assert_eq!(chunks.len(), 2);
    let second = chunks[1].chunk_start_offset as usize;

    // A byte flipped inside the second chunk's compressed data: its CRC or zstd fails.
    let mut flipped = bytes.clone();
    let inside = second + chunks[1].chunk_length as usize - 3;
    flipped[inside] ^= 0x5a;
    let scanned = scan(&flipped).unwrap();
    match &scanned.end {
        ScanEnd::Damaged { offset, .. } => assert_eq!(*offset as usize, second),
        other => panic!("expected damage, got {other:?}"),
    }
    assert_eq!(count_messages(&scanned.records), 3);

    // Zeros after the first chunk (a power cut with the file extended but not written).
    let mut zeroed = bytes[..second].to_vec();
    zeroed.extend(std::iter::repeat_n(0u8, 4096));
    let scanned = scan(&zeroed).unwrap();
    assert!(
        matches!(&scanned.end, ScanEnd::Damaged { reason, .. } if reason.contains("opcode 0")),
        "{:?}",
        scanned.end
    );
    assert_eq!(scanned.intact_end as usize, second);
    assert_eq!(count_messages(&scanned.records), 3);

    // Cut exactly at a record boundary: nothing damaged, just no ending.
    let scanned = scan(&bytes[..second]).unwrap();
    assert_eq!(scanned.end, ScanEnd::EndOfFile);

    // Cut a few bytes after the header: the header counts as intact.
    let header_end = 8 + 9 + u64::from_le_bytes(bytes[9..17].try_into().unwrap()) as usize;
    let scanned = scan(&bytes[..header_end + 3]).unwrap();
    assert!(
        matches!(scanned.end, ScanEnd::Damaged { offset, .. } if offset as usize == header_end)
    );
    assert_eq!(scanned.intact_end as usize, header_end);
    assert!(scanned.records.is_empty());
}

#[test]
fn not_mcap_is_an_error() {
    assert!(scan(b"").is_err());
    assert!(scan(b"\x89MCAP0\r\n").is_err(), "no header record");
    assert!(scan(b"PK\x03\x04 a zip file, say").is_err());
}
