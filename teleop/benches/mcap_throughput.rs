//! Benchmark: trial log throughput.
//!
//! `cargo bench -p teleop --bench mcap_throughput` writes 200 000 `sensor_msgs/JointState`
//! messages (17 joints, positions and velocities, 1 ms of log time apart) with the station's
//! default writer options (zstd chunks, a flush with fsync per second of log time, so 200
//! flushes), then opens the file with `TrialReader` and decodes every message. Prints one
//! JSON line: messages per second for writing (including `finish`) and for read + decode.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a benchmark fails loudly

use std::time::Instant;

use msgs::{Header, JointState, Time};
use teleop::mcap_log::{OfferedQos, TrialReader, TrialWriter, TrialWriterOptions};

const MESSAGES: usize = 200_000;
const T0_NS: i64 = 1_732_100_000_000_000_000;

fn main() {
    let dir = std::env::temp_dir().join(format!("pomdar_mcap_bench_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bench.mcap");
    let names: Vec<String> = (0..17).map(|i| format!("joint_{i:02}")).collect();

    // Messages are built before timing: the benchmark measures the log, not the caller.
    let messages: Vec<JointState> = (0..MESSAGES)
        .map(|i| {
            let phase = i as f64 * 1e-3;
            JointState {
                header: Header {
                    stamp: Time::from_nanos(T0_NS + i as i64 * 1_000_000),
                    frame_id: String::new(),
                },
                name: names.clone(),
                position: (0..17).map(|j| (phase + j as f64).sin()).collect(),
                velocity: (0..17).map(|j| (phase + j as f64).cos()).collect(),
                effort: Vec::new(),
            }
        })
        .collect();

    let options = TrialWriterOptions::default();
    let start = Instant::now();
    let mut writer = TrialWriter::create(&path, options).unwrap();
    writer
        .add_channel::<JointState>("/hand/joint_targets", &[OfferedQos::reliable(10)])
        .unwrap();
    for (i, message) in messages.iter().enumerate() {
        let t = T0_NS + i as i64 * 1_000_000;
        writer
            .write("/hand/joint_targets", t, t - 200_000, message)
            .unwrap();
    }
    writer.finish().unwrap();
    let write_s = start.elapsed().as_secs_f64();
    let file_bytes = std::fs::metadata(&path).unwrap().len();

    let start = Instant::now();
    let log = TrialReader::open(&path).unwrap();
    let open_s = start.elapsed().as_secs_f64();
    let mut checksum = 0.0;
    for message in log.messages() {
        let joints: JointState = message.decode().unwrap();
        checksum += joints.position[3];
    }
    let read_s = start.elapsed().as_secs_f64();
    assert_eq!(log.message_count(), MESSAGES);
    let chunks = log.statistics().map_or(0, |s| s.chunk_count);
    std::hint::black_box(checksum);

    println!(
        "{{\"bench\":\"mcap_throughput\",\"messages\":{MESSAGES},\"type\":\"sensor_msgs/msg/JointState\",\"joints\":17,\
         \"compression\":\"zstd\",\"chunks\":{chunks},\"file_bytes\":{file_bytes},\
         \"write_s\":{write_s:.3},\"write_msgs_per_s\":{:.0},\
         \"open_s\":{open_s:.3},\"read_decode_s\":{read_s:.3},\"read_decode_msgs_per_s\":{:.0}}}",
        MESSAGES as f64 / write_s,
        MESSAGES as f64 / read_s
    );
    let _ = std::fs::remove_dir_all(&dir);
}
