//! The station recorder: metadata, inputs and outputs with their times, and trial events in
//! order, in a log that ends up renamed from `.part`.

use std::collections::BTreeMap;

use msgs::{Float32MultiArray, JointState, StringMsg};
use serde_json::json;
use station::StationConfig;
use teleop::mcap_log::{TRIAL_EVENTS_TOPIC, TrialReader, part_path_for};
use teleop::station_node::recorder::{RecordingOptions, StationRecorder, config_digest};

#[test]
fn a_recorded_trial_has_its_metadata_messages_and_events_in_order() {
    let path = std::env::temp_dir().join(format!("pomdar-recorder-{}.mcap", std::process::id()));
    std::fs::remove_file(&path).ok();
    let config = StationConfig::default();
    let options = RecordingOptions {
        path: path.clone(),
        metadata: BTreeMap::from([
            ("task".to_string(), "V1".to_string()),
            ("operator".to_string(), "ana".to_string()),
        ]),
    };
    let mut recorder = StationRecorder::start(&options, &config, 1_000).unwrap();
    assert!(
        part_path_for(&path).exists(),
        "recording goes to .part first"
    );
    let frame = Float32MultiArray::from_points(&[[0.0, 0.1, 0.2]; 22]).unwrap();
    recorder.input("/ingress/mano", 2_000, Some(1_500), &frame);
    let target = JointState {
        name: vec!["index_mcp".into()],
        position: vec![0.5],
        ..JointState::default()
    };
    recorder.output("/pomdar/hand/joint_targets", 3_000, &target);
    recorder.event(4_000, &json!({"event": "progress", "value": 1}));
    recorder.event(5_000, &json!({"event": "drop"}));
    let finished = recorder.finish(6_000, json!({"frames_new": 1})).unwrap();
    assert_eq!(finished.path, path);
    assert!(!part_path_for(&path).exists());

    let log = TrialReader::open(&path).unwrap();
    let trial = log.metadata_named("pomdar_trial").unwrap();
    assert_eq!(trial["task"], "V1");
    assert_eq!(trial["operator"], "ana");
    assert_eq!(trial["config_digest"], config_digest(&config));
    let mano: Vec<_> = log.messages_on("/ingress/mano").collect();
    assert_eq!(
        (mano[0].log_time_ns, mano[0].publish_time_ns),
        (2_000, 1_500)
    );
    assert_eq!(mano[0].decode::<Float32MultiArray>().unwrap(), frame);
    assert_eq!(
        log.decode_topic::<JointState>("/pomdar/hand/joint_targets")
            .unwrap(),
        vec![target]
    );
    let events: Vec<serde_json::Value> = log
        .decode_topic::<StringMsg>(TRIAL_EVENTS_TOPIC)
        .unwrap()
        .iter()
        .map(|m| serde_json::from_str(&m.data).unwrap())
        .collect();
    let kinds: Vec<&str> = events
        .iter()
        .map(|e| e["event"].as_str().unwrap())
        .collect();
    assert_eq!(kinds, ["start", "progress", "drop", "stop"]);
    assert_eq!(events[1]["value"], 1);
    assert_eq!(events[3]["summary"]["frames_new"], 1);
    std::fs::remove_file(&path).ok();
}

#[test]
fn the_config_digest_changes_with_the_configuration() {
    let a = StationConfig::default();
    let mut b = a.clone();
    b.retarget.pinch.weight = 11.0;
    assert_eq!(config_digest(&a), config_digest(&a.clone()));
    assert_ne!(config_digest(&a), config_digest(&b));
}
