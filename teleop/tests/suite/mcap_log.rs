//! Trial logs end to end: write a trial, read it back (with our reader and with the mcap
//! crate's own readers), recover crashed recordings cut at random byte offsets, and read the
//! lab's reference recording written by an independent tool.

use std::collections::{BTreeMap, BTreeSet};
use std::path::PathBuf;

use msgs::{
    Float32MultiArray, Header, JointState, Point, Pose, PoseStamped, Quaternion, RosMessage,
    StringMsg, Time,
};
use teleop::mcap_log::{
    LogError, OfferedQos, QosDurability, QosHistory, RECOVERY_METADATA_NAME, TRIAL_EVENTS_TOPIC,
    TrialReader, TrialWriter, TrialWriterOptions, part_path_for, qos_profiles_from_yaml, recover,
};

const S: i64 = 1_000_000_000;
const MS: i64 = 1_000_000;
/// Seed of the simulated trial's values.
const TRIAL_SEED: u64 = 0x5eed_0f7e_1e0b;
/// Log times start here (2024-11-20, like the reference recording).
const T0: i64 = 1_732_100_000 * S;

/// The ORCA joint names, in orca_core order.
const JOINTS: [&str; 17] = retarget::ORCA_CORE_JOINTS;

/// A scratch directory, emptied first and removed at the end of the test.
struct TestDir(PathBuf);

impl TestDir {
    fn new(name: &str) -> TestDir {
        let dir =
            std::env::temp_dir().join(format!("pomdar_mcap_log_{name}_{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        TestDir(dir)
    }
    fn join(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
}

impl Drop for TestDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// xorshift64*: reproducible pseudo-random numbers without a dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn joint_state(rng: &mut Rng, t: i64) -> JointState {
    JointState {
        header: Header {
            stamp: Time::from_nanos(t),
            frame_id: String::new(),
        },
        name: JOINTS.iter().map(|s| s.to_string()).collect(),
        position: (0..17).map(|_| rng.unit() * 2.0 - 1.0).collect(),
        velocity: Vec::new(),
        effort: Vec::new(),
    }
}

fn keypoints(rng: &mut Rng) -> Float32MultiArray {
    let points: Vec<[f32; 3]> = (0..22)
        .map(|_| [rng.unit() as f32, rng.unit() as f32, rng.unit() as f32])
        .collect();
    Float32MultiArray::from_points(&points).unwrap()
}

fn wrist(rng: &mut Rng, t: i64) -> PoseStamped {
    PoseStamped {
        header: Header {
            stamp: Time::from_nanos(t),
            frame_id: "coil".to_string(),
        },
        pose: Pose {
            position: Point {
                x: rng.unit(),
                y: rng.unit(),
                z: rng.unit(),
            },
            orientation: Quaternion {
                x: 0.0,
                y: 0.0,
                z: 0.0,
                w: 1.0,
            },
        },
    }
}

/// One message as written: topic, log time, publish time, CDR bytes.
type Written = (String, i64, i64, Vec<u8>);

/// A simulated trial: glove keypoints and wrist at 200 Hz, joint targets at 100 Hz, an event
/// every 2.5 s, for `duration_s`. `each` runs after every write (snapshots for crash tests).
fn record_trial(
    writer: &mut TrialWriter,
    duration_s: i64,
    mut each: impl FnMut(&TrialWriter, &[Written]),
) -> Vec<Written> {
    let mut rng = Rng(TRIAL_SEED);
    let mut written: Vec<Written> = Vec::new();
    writer
        .add_channel::<Float32MultiArray>("/ingress/mano", &[OfferedQos::best_effort(100)])
        .unwrap();
    writer
        .add_channel::<PoseStamped>("/ingress/wrist", &[OfferedQos::best_effort(100)])
        .unwrap();
    writer
        .add_channel::<JointState>("/hand/joint_targets", &[OfferedQos::reliable(10)])
        .unwrap();
    writer
        .write_metadata(
            "pomdar_trial",
            BTreeMap::from([
                ("task".to_string(), "V1".to_string()),
                ("embodiment".to_string(), "orca_full".to_string()),
                ("trial_index".to_string(), "3".to_string()),
                ("practice".to_string(), "false".to_string()),
            ]),
        )
        .unwrap();
    let mut push =
        |writer: &TrialWriter, w: &mut Vec<Written>, topic: &str, t: i64, p: i64, cdr| {
            w.push((topic.to_string(), t, p, cdr));
            each(writer, w);
        };
    for step in 0..duration_s * 200 {
        let t = T0 + step * 5 * MS;
        // Receive a little after sending (publish time = source time).
        let sent = t - 300_000;
        let mano = keypoints(&mut rng);
        writer.write("/ingress/mano", t, sent, &mano).unwrap();
        push(
            writer,
            &mut written,
            "/ingress/mano",
            t,
            sent,
            msgs::to_cdr(&mano).unwrap(),
        );
        let pose = wrist(&mut rng, sent);
        writer
            .write("/ingress/wrist", t + 1000, sent, &pose)
            .unwrap();
        push(
            writer,
            &mut written,
            "/ingress/wrist",
            t + 1000,
            sent,
            msgs::to_cdr(&pose).unwrap(),
        );
        if step % 2 == 0 {
            let joints = joint_state(&mut rng, t);
            writer
                .write("/hand/joint_targets", t + 2000, t + 1500, &joints)
                .unwrap();
            let cdr = msgs::to_cdr(&joints).unwrap();
            push(
                writer,
                &mut written,
                "/hand/joint_targets",
                t + 2000,
                t + 1500,
                cdr,
            );
        }
        if step % 500 == 0 {
            let kind = if step == 0 { "start" } else { "progress" };
            let event = serde_json::json!({"event": kind, "value": step / 500});
            writer.write_event(t + 3000, &event).unwrap();
            let cdr = msgs::to_cdr(&StringMsg {
                data: event.to_string(),
            })
            .unwrap();
            push(
                writer,
                &mut written,
                TRIAL_EVENTS_TOPIC,
                t + 3000,
                t + 3000,
                cdr,
            );
        }
    }
    written
}

fn quiet_options() -> TrialWriterOptions {
    // fsync is for power cuts; these tests simulate killed processes.
    TrialWriterOptions {
        sync_on_flush: false,
        ..TrialWriterOptions::default()
    }
}

fn as_written(log: &TrialReader) -> Vec<Written> {
    log.messages()
        .map(|m| {
            (
                m.topic.clone(),
                m.log_time_ns,
                m.publish_time_ns,
                m.data.clone(),
            )
        })
        .collect()
}

#[test]
fn trial_reads_back_with_same_topics_types_counts_and_values() {
    let dir = TestDir::new("round_trip");
    let path = dir.join("V1_0003.mcap");
    let mut writer = TrialWriter::create(&path, quiet_options()).unwrap();
    let part = part_path_for(&path);
    assert_eq!(writer.part_path(), part);
    let written = record_trial(&mut writer, 3, |_, _| {});
    writer
        .write_event(T0 + 3 * S, &serde_json::json!({"event": "stop"}))
        .unwrap();
    assert!(
        part.exists() && !path.exists(),
        "written as .part until finished"
    );
    let done = writer.finish().unwrap();
    assert!(path.exists() && !part.exists(), "renamed on finish");
    assert_eq!(done.path, path);
    assert_eq!(done.message_count, written.len() as u64 + 1);

    let log = TrialReader::open(&path).unwrap();
    assert_eq!(log.profile(), "ros2");
    assert!(log.was_in_log_time_order());
    // Every message, in order, with its times and bytes.
    let mut read = as_written(&log);
    let stop = read.pop().unwrap();
    assert_eq!(read, written);
    assert_eq!(stop.0, TRIAL_EVENTS_TOPIC);

    assert_round_trip_topics(&log);
    assert_round_trip_values(&log);
    assert_round_trip_metadata_and_statistics(&log, written.len() as u64 + 1);
}

/// The 3 s round-trip trial's topics: types, counts, schemas, QoS.
fn assert_round_trip_topics(log: &TrialReader) {
    let expect = [
        (
            "/ingress/mano",
            Float32MultiArray::DEFINITION,
            600,
            OfferedQos::best_effort(100),
        ),
        (
            "/ingress/wrist",
            PoseStamped::DEFINITION,
            600,
            OfferedQos::best_effort(100),
        ),
        (
            "/hand/joint_targets",
            JointState::DEFINITION,
            300,
            OfferedQos::reliable(10),
        ),
        (
            TRIAL_EVENTS_TOPIC,
            StringMsg::DEFINITION,
            3,
            OfferedQos::reliable(100),
        ),
    ];
    assert_eq!(log.topics().len(), expect.len());
    for (topic, def, count, qos) in expect {
        let info = log.topic(topic).unwrap();
        assert_eq!(info.type_name, def.ros_type_name(), "{topic}");
        assert_eq!(info.schema_encoding, "ros2msg");
        assert_eq!(info.schema_text, def.schema_text());
        assert_eq!(info.message_encoding, "cdr");
        assert_eq!(info.message_count, count, "{topic}");
        assert_eq!(info.offered_qos().unwrap().unwrap(), vec![qos], "{topic}");
    }
}

/// The round-trip trial's decoded values, and a decode as the wrong type refused.
fn assert_round_trip_values(log: &TrialReader) {
    let mut rng = Rng(TRIAL_SEED);
    let mano = log
        .decode_topic::<Float32MultiArray>("/ingress/mano")
        .unwrap();
    assert_eq!(mano[0], keypoints(&mut rng));
    assert_eq!(mano[0].points().unwrap().len(), 22);
    let joints = log
        .decode_topic::<JointState>("/hand/joint_targets")
        .unwrap();
    assert_eq!(joints[0].name.len(), 17);
    assert!(
        joints
            .iter()
            .all(|j| j.position.iter().all(|p| p.abs() <= 1.0))
    );
    let wrists = log.decode_topic::<PoseStamped>("/ingress/wrist").unwrap();
    assert!(wrists.iter().all(|w| w.header.frame_id == "coil"));
    let events: Vec<serde_json::Value> = log
        .decode_topic::<StringMsg>(TRIAL_EVENTS_TOPIC)
        .unwrap()
        .iter()
        .map(|s| serde_json::from_str(&s.data).unwrap())
        .collect();
    let kinds: Vec<&str> = events
        .iter()
        .map(|e| e["event"].as_str().unwrap())
        .collect();
    assert_eq!(kinds, ["start", "progress", "stop"][..]);
    let first_joint = log.messages().find(|m| m.is::<JointState>()).unwrap();
    let err = first_joint.decode::<PoseStamped>().unwrap_err();
    assert!(matches!(err, LogError::TypeMismatch { .. }), "{err}");
}

/// The round-trip trial's metadata record and summary statistics.
fn assert_round_trip_metadata_and_statistics(log: &TrialReader, message_count: u64) {
    assert_eq!(log.metadata().len(), 1);
    let trial = log.metadata_named("pomdar_trial").unwrap();
    assert_eq!(trial["task"], "V1");
    assert_eq!(trial["trial_index"], "3");

    let stats = log.statistics().expect("summary with statistics");
    assert_eq!(stats.message_count, message_count);
    assert_eq!(stats.channel_count, 4);
    assert_eq!(stats.schema_count, 4);
    assert_eq!(stats.metadata_count, 1);
    assert!(stats.chunk_count >= 3, "flushed at least once per second");
    assert_eq!(stats.message_start_time_ns, T0 as u64);
}

/// The same file through the mcap crate's own summary and message readers.
#[test]
fn independent_reader_sees_rosbag2_layout() {
    let dir = TestDir::new("independent");
    let path = dir.join("t.mcap");
    let mut writer = TrialWriter::create(&path, quiet_options()).unwrap();
    let written = record_trial(&mut writer, 2, |_, _| {});
    writer.finish().unwrap();
    let bytes = std::fs::read(&path).unwrap();

    let summary = mcap::Summary::read(&bytes).unwrap().expect("summary");
    let stats = summary.stats.as_ref().expect("statistics record");
    assert_eq!(stats.message_count, written.len() as u64);
    assert!(!summary.chunk_indexes.is_empty());
    assert!(
        summary
            .chunk_indexes
            .iter()
            .all(|c| c.compression == "zstd")
    );
    assert_eq!(summary.metadata_indexes.len(), 1);
    assert_eq!(summary.schemas.len(), 4);
    for schema in summary.schemas.values() {
        assert_eq!(schema.encoding, "ros2msg");
        assert!(schema.name.contains("/msg/"), "{}", schema.name);
    }
    for channel in summary.channels.values() {
        assert_eq!(channel.message_encoding, "cdr");
        let yaml = &channel.metadata["offered_qos_profiles"];
        assert!(yaml.starts_with("- history: 1\n  depth: "), "{yaml}");
        assert!(yaml.contains("  deadline:\n    sec: 9223372036\n    nsec: 854775807\n"));
        assert_eq!(qos_profiles_from_yaml(yaml).unwrap().len(), 1);
        let count = stats.channel_message_counts[&channel.id];
        let expected = written.iter().filter(|w| w.0 == channel.topic).count() as u64;
        assert_eq!(count, expected, "{}", channel.topic);
    }
    let header = mcap::read::LinearReader::new(&bytes)
        .unwrap()
        .find_map(|r| match r.unwrap() {
            mcap::records::Record::Header(h) => Some(h),
            _ => None,
        })
        .unwrap();
    assert_eq!(header.profile, "ros2");
    let streamed: Vec<Written> = mcap::MessageStream::new(&bytes)
        .unwrap()
        .map(|m| {
            let m = m.unwrap();
            (
                m.channel.topic.clone(),
                m.log_time as i64,
                m.publish_time as i64,
                m.data.into_owned(),
            )
        })
        .collect();
    assert_eq!(streamed, written);
}

/// A snapshot of the `.part` file as a killed process would leave it.
struct Snapshot {
    bytes: Vec<u8>,
    /// Messages written before the last flush at that moment.
    durable: usize,
    /// Messages written at that moment.
    written: usize,
}

/// The finished crash-test recording, what every recovered cut of a snapshot is checked
/// against.
struct Finished {
    bytes: Vec<u8>,
    /// Every message written, in order.
    written: Vec<Written>,
    /// The message counts the writer reported durable, at every write.
    flush_counts: BTreeSet<usize>,
    /// Where each chunk ends in the file, and how many messages end there: the file as it was
    /// before a kill is a prefix of it up to the last flush.
    boundaries: Vec<(usize, usize)>,
    /// Where the header record ends; a cut before it leaves nothing to recover.
    header_end: usize,
}

impl Finished {
    fn new(bytes: Vec<u8>, written: Vec<Written>, flush_counts: BTreeSet<usize>) -> Finished {
        let summary = mcap::Summary::read(&bytes).unwrap().unwrap();
        let mut chunks = summary.chunk_indexes.clone();
        chunks.sort_by_key(|c| c.chunk_start_offset);
        let mut boundaries = Vec::new(); // (chunk end offset, messages up to it)
        let mut total = 0usize;
        for chunk in &chunks {
            total += summary.stream_chunk(&bytes, chunk).unwrap().count();
            boundaries.push((
                (chunk.chunk_start_offset + chunk.chunk_length) as usize,
                total,
            ));
        }
        let header_end = 8 + 9 + u64::from_le_bytes(bytes[9..17].try_into().unwrap()) as usize;
        Finished {
            bytes,
            written,
            flush_counts,
            boundaries,
            header_end,
        }
    }

    /// The snapshot's bytes up to its last flush are the finished file's.
    fn assert_prefix_of(&self, s: usize, snap: &Snapshot) {
        assert!(snap.bytes.len() <= self.bytes.len());
        let flushed_len = self
            .boundaries
            .iter()
            .filter(|(_, n)| *n <= snap.durable)
            .map(|(end, _)| *end)
            .max()
            .unwrap_or(0);
        assert_eq!(
            snap.bytes[..flushed_len],
            self.bytes[..flushed_len],
            "snapshot {s}"
        );
    }

    /// Where to cut a snapshot: random cuts, the whole snapshot, and the bytes around every
    /// chunk end.
    fn cuts(&self, snap: &Snapshot, rng: &mut Rng) -> BTreeSet<usize> {
        let mut cuts: BTreeSet<usize> = (0..25)
            .map(|_| rng.below(snap.bytes.len() as u64) as usize)
            .collect();
        cuts.insert(snap.bytes.len());
        for (end, _) in &self.boundaries {
            for cut in [end - 1, *end, end + 1] {
                if cut <= snap.bytes.len() {
                    cuts.insert(cut);
                }
            }
        }
        cuts
    }

    /// Recovers snapshot `s` cut at `cut` bytes and checks it holds exactly the messages up
    /// to the last flush the cut keeps whole, with channels, metadata and the recovery note.
    /// Returns whether there was anything to recover (false: the cut leaves no header, and
    /// recovery refused it as not MCAP).
    fn assert_cut_recovers(&self, dir: &TestDir, s: usize, snap: &Snapshot, cut: usize) -> bool {
        let input = dir.join(&format!("s{s}_{cut}.mcap.part"));
        let output = dir.join(&format!("s{s}_{cut}.mcap"));
        std::fs::write(&input, &snap.bytes[..cut]).unwrap();
        let result = recover(&input, &output);
        if cut < self.header_end {
            let err = result.expect_err("no header: nothing to recover");
            assert!(matches!(err, LogError::NotMcap { .. }), "cut {cut}: {err}");
            return false;
        }
        let report = result.unwrap_or_else(|e| panic!("snapshot {s} cut {cut}: {e}"));
        let expected = self
            .boundaries
            .iter()
            .filter(|(end, n)| *end <= cut && *n <= snap.durable)
            .map(|(_, n)| *n)
            .max()
            .unwrap_or(0);
        assert!(self.flush_counts.contains(&expected));
        assert_eq!(
            report.message_count as usize, expected,
            "snapshot {s} cut {cut}\n{report}"
        );
        let log = TrialReader::open(&output).unwrap();
        assert_eq!(
            as_written(&log),
            self.written[..expected],
            "snapshot {s} cut {cut}"
        );
        // Channels and the trial metadata survive with the first flushed chunk.
        if expected > 0 {
            assert_eq!(log.topics().len(), 4);
            assert_eq!(log.metadata_named("pomdar_trial").unwrap()["task"], "V1");
            let qos = log
                .topic("/ingress/mano")
                .unwrap()
                .offered_qos()
                .unwrap()
                .unwrap();
            assert_eq!(qos, vec![OfferedQos::best_effort(100)]);
        }
        let recovery = log.metadata_named(RECOVERY_METADATA_NAME).unwrap();
        assert_eq!(recovery["messages_recovered"], expected.to_string());
        assert!(report.unrecoverable_bytes <= cut as u64);
        assert_eq!(
            report.tail_damaged,
            report.unrecoverable_bytes > 0,
            "{report}"
        );
        true
    }

    /// The whole snapshot loses at most the unflushed second (plus one message period).
    fn assert_whole_snapshot_recovers(&self, dir: &TestDir, s: usize, snap: &Snapshot) {
        let input = dir.join(&format!("whole{s}.mcap.part"));
        let output = dir.join(&format!("whole{s}.mcap"));
        std::fs::write(&input, &snap.bytes).unwrap();
        let report = recover(&input, &output).unwrap();
        assert_eq!(report.message_count as usize, snap.durable);
        let last_written = self.written[..snap.written]
            .iter()
            .map(|w| w.1)
            .max()
            .unwrap();
        let lost_ns = last_written - report.last_log_time_ns.unwrap_or(T0);
        println!(
            "snapshot {s}: {} of {} messages, {:.3} s of log time lost, {} bytes unrecoverable",
            report.message_count,
            snap.written,
            lost_ns as f64 / 1e9,
            report.unrecoverable_bytes
        );
        assert!(lost_ns <= S + 5 * MS, "lost {lost_ns} ns\n{report}");
    }
}

#[test]
fn crashed_recording_recovers_exactly_up_to_the_last_flush() {
    let dir = TestDir::new("crash");
    let path = dir.join("trial.mcap");
    let mut writer = TrialWriter::create(&path, quiet_options()).unwrap();
    let part = writer.part_path().to_path_buf();
    let mut rng = Rng(0xc0ff_ee00_d15c_0bad);
    // Snapshot at random moments; note the message count at every flush.
    let moments: BTreeSet<usize> = (0..8).map(|_| 200 + rng.below(5500) as usize).collect();
    let mut snapshots = Vec::new();
    let mut flush_counts = BTreeSet::from([0usize]);
    let written = record_trial(&mut writer, 12, |w, so_far| {
        flush_counts.insert(w.durable_message_count() as usize);
        if moments.contains(&so_far.len()) {
            snapshots.push(Snapshot {
                bytes: std::fs::read(&part).unwrap(),
                durable: w.durable_message_count() as usize,
                written: so_far.len(),
            });
        }
    });
    writer.finish().unwrap();
    assert_eq!(snapshots.len(), moments.len());

    let finished = Finished::new(std::fs::read(&path).unwrap(), written, flush_counts);
    let mut checked = 0;
    for (s, snap) in snapshots.iter().enumerate() {
        finished.assert_prefix_of(s, snap);
        for cut in finished.cuts(snap, &mut rng) {
            if finished.assert_cut_recovers(&dir, s, snap, cut) {
                checked += 1;
            }
        }
        finished.assert_whole_snapshot_recovers(&dir, s, snap);
    }
    println!("{checked} truncated files recovered and checked");
}

#[test]
fn recovery_never_overwrites_and_reports_in_words() {
    let dir = TestDir::new("recover_safety");
    let path = dir.join("t.mcap");
    let mut writer = TrialWriter::create(&path, quiet_options()).unwrap();
    record_trial(&mut writer, 2, |_, _| {});
    let snapshot = std::fs::read(writer.part_path()).unwrap();
    drop(writer); // completes the .part; use the snapshot as the crashed file

    let input = dir.join("crashed.mcap.part");
    std::fs::write(&input, &snapshot).unwrap();
    let taken = dir.join("taken.mcap");
    std::fs::write(&taken, b"precious").unwrap();
    let err = recover(&input, &taken).unwrap_err();
    assert!(matches!(err, LogError::AlreadyExists { .. }), "{err}");
    assert_eq!(std::fs::read(&taken).unwrap(), b"precious");
    let err = recover(&input, &input).unwrap_err();
    assert!(matches!(err, LogError::SameFile { .. }), "{err}");

    let out = dir.join("crashed.mcap");
    let report = recover(&input, &out).unwrap();
    assert_eq!(std::fs::read(&input).unwrap(), snapshot, "input untouched");
    let text = report.to_string();
    println!("{text}");
    assert!(
        text.contains("/ingress/mano") && text.contains("recovered"),
        "{text}"
    );
    assert!(!dir.join("crashed.mcap.recovering").exists());

    // An interrupted file is not readable as a trial: the error says what to do.
    let err = TrialReader::open(&input).unwrap_err();
    assert!(err.to_string().contains("pomdar recover"), "{err}");
}

fn reference_file() -> Option<PathBuf> {
    let dir = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/reference"
    ));
    if !dir.is_dir() {
        println!(
            "SKIPPED: reference data directory {} is absent",
            dir.display()
        );
        return None;
    }
    Some(dir.join("rokoko_orca_2024-11-20.mcap"))
}

#[test]
fn reads_the_reference_recording_from_another_tool() {
    let Some(path) = reference_file() else {
        return;
    };
    let log = TrialReader::open(&path).unwrap();
    println!(
        "profile {:?}, library {:?}, in log-time order: {}",
        log.profile(),
        log.library(),
        log.was_in_log_time_order()
    );
    assert_eq!(log.profile(), "ros2");
    for (name, entries) in log.metadata() {
        println!("metadata {name:?}: {} entries", entries.len());
    }
    let bytes = std::fs::read(&path).unwrap();
    let independent = mcap::MessageStream::new(&bytes).unwrap().count();
    assert_eq!(log.message_count(), independent);

    let mano = log.topic("/ingress/mano").unwrap();
    assert_eq!(mano.type_name, "std_msgs/msg/Float32MultiArray");
    let wrist = log.topic("/ingress/wrist").unwrap();
    assert_eq!(wrist.type_name, "geometry_msgs/msg/PoseStamped");
    for info in [mano, wrist] {
        let qos = info.offered_qos().unwrap().unwrap();
        println!(
            "{}: {} messages, QoS {qos:?}",
            info.topic, info.message_count
        );
        assert_eq!(qos[0].history, QosHistory::Unknown);
        assert_eq!(qos[0].durability, QosDurability::Volatile);
        assert!(info.message_count > 1000);
    }
    let points = log
        .decode_topic::<Float32MultiArray>("/ingress/mano")
        .unwrap();
    assert!(points.iter().all(|p| p.points().unwrap().len() == 22));
    let poses = log.decode_topic::<PoseStamped>("/ingress/wrist").unwrap();
    assert_eq!(poses.len() as u64, wrist.message_count);
    let times: Vec<i64> = log.messages().map(|m| m.log_time_ns).collect();
    assert!(times.windows(2).all(|w| w[0] <= w[1]), "sorted by log time");
    if let Some(stats) = log.statistics() {
        assert_eq!(stats.message_count, independent as u64);
    }
}

/// Cutting another tool's file anywhere recovers a prefix of its messages, growing with the cut.
#[test]
fn recovers_a_truncated_copy_of_the_reference_recording() {
    let Some(path) = reference_file() else {
        return;
    };
    let bytes = std::fs::read(&path).unwrap();
    let all = as_written(&TrialReader::open(&path).unwrap());
    let dir = TestDir::new("reference_cut");
    let mut previous = 0;
    for tenth in 1..=10 {
        let cut = bytes.len() * tenth / 10;
        let input = dir.join(&format!("cut{tenth}.mcap.part"));
        let output = dir.join(&format!("cut{tenth}.mcap"));
        std::fs::write(&input, &bytes[..cut]).unwrap();
        let report = recover(&input, &output).unwrap();
        let log = TrialReader::open(&output).unwrap();
        let got = as_written(&log);
        assert_eq!(got[..], all[..got.len()], "cut at {tenth}/10");
        assert!(got.len() >= previous);
        previous = got.len();
        if tenth == 10 {
            assert_eq!(got.len(), all.len());
            assert!(report.input_was_finished && !report.tail_damaged);
            assert_eq!(
                log.metadata().len(),
                1 + TrialReader::open(&path).unwrap().metadata().len()
            );
        }
    }
}
