//! Deterministic re-simulation of recorded glove data (`pomdar resim`): the same log and
//! configuration give byte-identical outputs; both lab layouts are accepted; independent
//! MCAP readers decode the output.

use std::path::{Path, PathBuf};

use msgs::{Float32MultiArray, JointState};
use pomdar_tests::interop::{assert_readers_agree, independent_readers, reference_file};
use retarget::HandModel;
use station::StationConfig;
use teleop::mcap_log::{TrialReader, TrialWriter, TrialWriterOptions};
use teleop::resim::resim;

fn reference() -> Option<PathBuf> {
    reference_file("rokoko_orca_2024-11-20.mcap")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pomdar-resim-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::remove_file(&path).ok();
    path
}

fn run_resim(input: &Path, out: &Path) -> teleop::resim::ResimStats {
    let reader = TrialReader::open(input).unwrap();
    let mut writer = TrialWriter::create(out, TrialWriterOptions::default()).unwrap();
    let stats = resim(
        &reader,
        &StationConfig::default(),
        HandModel::orca_v1_right(),
        &mut writer,
    )
    .unwrap();
    writer.finish().unwrap();
    stats
}

#[test]
fn resimulating_the_reference_twice_is_byte_identical() {
    let Some(input) = reference() else { return };
    let (a, b) = (scratch("a.mcap"), scratch("b.mcap"));
    let stats = run_resim(&input, &a);
    run_resim(&input, &b);
    assert_eq!(
        std::fs::read(&a).unwrap(),
        std::fs::read(&b).unwrap(),
        "re-simulation is not deterministic"
    );
    assert_eq!(stats.frames_new, 727);
    assert_eq!(stats.rejected.values().sum::<u64>(), 0);
    let targets = TrialReader::open(&a)
        .unwrap()
        .decode_topic::<JointState>("/pomdar/hand/joint_targets")
        .unwrap();
    // 25 Hz over the 30 s recording, once the first frame engaged the station.
    assert!(
        (700..=800).contains(&targets.len()),
        "{} joint targets",
        targets.len()
    );
    let model = HandModel::orca_v1_right();
    assert!(targets.iter().all(|t| model.within_limits(&t.position)));
}

#[test]
fn the_21_point_lab_layout_is_accepted() {
    let Some(input) = reference() else { return };
    // The reference without its forearm point: the lab's 21-point layout.
    let reader = TrialReader::open(&input).unwrap();
    let lab21 = scratch("lab21.mcap");
    let mut writer = TrialWriter::create(&lab21, TrialWriterOptions::default()).unwrap();
    for message in reader.messages() {
        if message.topic == "/ingress/mano" {
            let array: Float32MultiArray = message.decode().unwrap();
            let rows = array.points().unwrap();
            let cut = Float32MultiArray::from_points(&rows[1..]).unwrap();
            writer
                .write(
                    "/ingress/mano",
                    message.log_time_ns,
                    message.publish_time_ns,
                    &cut,
                )
                .unwrap();
        } else {
            let pose: msgs::PoseStamped = message.decode().unwrap();
            writer
                .write(
                    &message.topic,
                    message.log_time_ns,
                    message.publish_time_ns,
                    &pose,
                )
                .unwrap();
        }
    }
    writer.finish().unwrap();
    let (out21, out22) = (scratch("out21.mcap"), scratch("out22.mcap"));
    let stats = run_resim(&lab21, &out21);
    assert_eq!(stats.layout, "lab21");
    assert_eq!(stats.frames_new, 727);
    run_resim(&input, &out22);
    // The forearm point plays no part in retargeting: same targets.
    let a = TrialReader::open(&out21)
        .unwrap()
        .decode_topic::<JointState>("/pomdar/hand/joint_targets")
        .unwrap();
    let b = TrialReader::open(&out22)
        .unwrap()
        .decode_topic::<JointState>("/pomdar/hand/joint_targets")
        .unwrap();
    assert_eq!(a.len(), b.len());
    assert!(a.iter().zip(&b).all(|(x, y)| x.position == y.position));
}

#[test]
fn independent_readers_decode_every_message_of_a_resimulated_log() {
    let Some(input) = reference() else { return };
    let out = scratch("interop.mcap");
    run_resim(&input, &out);
    let Some(report) = independent_readers(&out) else {
        return;
    };
    println!("{report}");
    assert_readers_agree(&report, &TrialReader::open(&out).unwrap());
}
