//! The writer's rules: when it flushes, what it refuses, and what it leaves on disk.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::collections::BTreeMap;

use msgs::{JointState, PoseStamped, RosMessage, StringMsg};

use super::test_dir::TestDir;
use super::*;

const S: i64 = 1_000_000_000;
const MS: i64 = 1_000_000;

fn options() -> TrialWriterOptions {
    TrialWriterOptions {
        sync_on_flush: false,
        ..TrialWriterOptions::default()
    }
}

#[test]
fn flushes_once_per_second_of_log_time() {
    let dir = TestDir::new("auto_flush");
    let mut w = TrialWriter::create(&dir.path().join("t.mcap"), options()).unwrap();
    let t0 = 1_700_000_000 * S;
    let mut durable = Vec::new();
    // 100 ms apart for 2.5 s: flushes after the writes at t0 + 1.0 s and t0 + 2.0 s.
    for i in 0..=25 {
        w.write("/x", t0 + i * 100 * MS, t0, &StringMsg::default())
            .unwrap();
        durable.push(w.durable_message_count());
    }
    assert_eq!(durable[9], 0);
    assert_eq!(durable[10], 11);
    assert_eq!(durable[19], 11);
    assert_eq!(durable[20], 21);
    assert_eq!(durable[25], 21);
    // An idle timer flushes what is pending once due, and only then.
    assert!(!w.flush_if_due(t0 + 2_900 * MS).unwrap());
    assert!(w.flush_if_due(t0 + 3_000 * MS).unwrap());
    assert_eq!(w.durable_message_count(), 26);
    assert!(!w.flush_if_due(t0 + 9 * S).unwrap(), "nothing pending");
    // A clock step back flushes at once rather than waiting for the old anchor.
    w.write("/x", t0, t0, &StringMsg::default()).unwrap();
    assert_eq!(w.durable_message_count(), 27);
    w.finish().unwrap();
}

#[test]
fn events_and_metadata_flush_immediately() {
    let dir = TestDir::new("event_flush");
    let mut w = TrialWriter::create(&dir.path().join("t.mcap"), options()).unwrap();
    w.write("/x", 10, 10, &StringMsg::default()).unwrap();
    assert_eq!(w.durable_message_count(), 0);
    w.write_event(20, &serde_json::json!({"event": "start"}))
        .unwrap();
    assert_eq!(w.durable_message_count(), 2);
    w.write("/x", 30, 30, &StringMsg::default()).unwrap();
    w.write_metadata("m", BTreeMap::new()).unwrap();
    assert_eq!(w.durable_message_count(), 3);
    let done = w.finish().unwrap();
    assert_eq!(done.message_count, 3);
    assert_eq!(done.messages_per_topic[TRIAL_EVENTS_TOPIC], 1);
    assert_eq!(done.log_time_range_ns, Some((10, 30)));
}

#[test]
fn refuses_conflicts_and_bad_input() {
    let dir = TestDir::new("refuse");
    let mut w = TrialWriter::create(&dir.path().join("t.mcap"), options()).unwrap();
    let id = w
        .add_channel::<JointState>("/j", &[OfferedQos::reliable(5)])
        .unwrap();
    assert_eq!(
        w.add_channel::<JointState>("/j", &[OfferedQos::reliable(5)])
            .unwrap(),
        id
    );
    let conflict = |e: LogError| matches!(e, LogError::ChannelConflict { .. });
    assert!(conflict(
        w.add_channel::<JointState>("/j", &[OfferedQos::reliable(6)])
            .unwrap_err()
    ));
    assert!(conflict(
        w.add_channel::<PoseStamped>("/j", &[OfferedQos::reliable(5)])
            .unwrap_err()
    ));
    assert!(conflict(
        w.write("/j", 1, 1, &PoseStamped::default()).unwrap_err()
    ));
    let err = w.write("j", 1, 1, &JointState::default()).unwrap_err();
    assert!(matches!(err, LogError::TopicName { .. }), "{err}");
    assert!(
        err.to_string().contains("t.mcap.part"),
        "errors name the file: {err}"
    );
    let err = w.write("/j", -1, 1, &JointState::default()).unwrap_err();
    assert!(matches!(err, LogError::NegativeTime { .. }), "{err}");
    let text = JointState::schema_text();
    let err = w.write_raw("/r", "sensor_msgs/JointState", &text, 1, 1, &[0, 1, 0, 0]);
    assert!(matches!(err, Err(LogError::TypeName { .. })), "{err:?}");
    let err = w.write_raw("/r", "sensor_msgs/msg/JointState", &text, 1, 1, &[0, 1]);
    assert!(
        matches!(err, Err(LogError::PayloadTooShort { .. })),
        "{err:?}"
    );
    let err = w.write_raw(
        "/r2",
        "sensor_msgs/msg/JointState",
        "float64 x\n",
        1,
        1,
        &[0, 1, 0, 0],
    );
    assert!(
        matches!(err, Err(LogError::SchemaConflict { .. })),
        "{err:?}"
    );
    // After refusals the writer still works and nothing invalid was written.
    w.write("/j", 2, 2, &JointState::default()).unwrap();
    let done = w.finish().unwrap();
    assert_eq!(done.message_count, 1);
}

#[test]
fn refuses_to_clobber_part_or_final_files() {
    let dir = TestDir::new("clobber");
    let path = dir.path().join("t.mcap");
    let w = TrialWriter::create(&path, options()).unwrap();
    let err = TrialWriter::create(&path, options())
        .err()
        .expect("second writer");
    assert!(err.to_string().contains("pomdar recover"), "{err}");
    w.finish().unwrap();
    let err = TrialWriter::create(&path, options())
        .err()
        .expect("final exists");
    assert!(matches!(err, LogError::AlreadyExists { .. }), "{err}");
    let replace = TrialWriterOptions {
        overwrite: true,
        ..options()
    };
    TrialWriter::create(&path, replace)
        .unwrap()
        .finish()
        .unwrap();

    // The final name appearing while writing is caught at finish, and the .part is kept.
    let other = dir.path().join("u.mcap");
    let mut w = TrialWriter::create(&other, options()).unwrap();
    w.write("/x", 1, 1, &StringMsg::default()).unwrap();
    std::fs::write(&other, b"someone else's").unwrap();
    let err = w.finish().unwrap_err();
    assert!(matches!(err, LogError::AlreadyExists { .. }), "{err}");
    assert_eq!(std::fs::read(&other).unwrap(), b"someone else's");
    assert!(TrialReader::open(&part_path_for(&other)).is_ok());
}

#[test]
fn rejects_bad_options() {
    let dir = TestDir::new("options");
    let path = dir.path().join("t.mcap");
    for bad in [
        TrialWriterOptions {
            auto_flush_interval_ns: Some(0),
            ..options()
        },
        TrialWriterOptions {
            chunk_size_bytes: 0,
            ..options()
        },
    ] {
        let err = TrialWriter::create(&path, bad)
            .err()
            .expect("invalid option");
        assert!(matches!(err, LogError::InvalidOption { .. }), "{err}");
    }
    assert!(!part_path_for(&path).exists());
}

#[test]
fn dropping_without_finish_leaves_a_complete_part_file() {
    let dir = TestDir::new("drop");
    let path = dir.path().join("t.mcap");
    {
        let mut w = TrialWriter::create(&path, options()).unwrap();
        w.write(
            "/x",
            5,
            5,
            &StringMsg {
                data: "kept".into(),
            },
        )
        .unwrap();
    }
    assert!(!path.exists());
    let log = TrialReader::open(&part_path_for(&path)).unwrap();
    assert_eq!(log.decode_topic::<StringMsg>("/x").unwrap()[0].data, "kept");
}

#[test]
fn compression_options_all_read_back() {
    let dir = TestDir::new("compression");
    for (i, compression) in [
        LogCompression::Zstd,
        LogCompression::Lz4,
        LogCompression::None,
    ]
    .into_iter()
    .enumerate()
    {
        let path = dir.path().join(format!("{i}.mcap"));
        let mut w = TrialWriter::create(
            &path,
            TrialWriterOptions {
                compression,
                chunk_size_bytes: 200,
                ..options()
            },
        )
        .unwrap();
        for t in 0..50 {
            w.write(
                "/x",
                t,
                t,
                &StringMsg {
                    data: format!("m{t}"),
                },
            )
            .unwrap();
        }
        w.finish().unwrap();
        let log = TrialReader::open(&path).unwrap();
        let texts: Vec<String> = log
            .decode_topic::<StringMsg>("/x")
            .unwrap()
            .into_iter()
            .map(|m| m.data)
            .collect();
        assert_eq!(texts.len(), 50, "{compression:?}");
        assert_eq!(texts[49], "m49");
        assert!(log.statistics().unwrap().chunk_count > 1, "{compression:?}");
    }
}
