//! Synthetic trial logs written the way the station records them: the same writer, topics,
//! message types, QoS, zstd chunks and flush policy (a chunk closed at every event and at
//! least once per second of log time), the `pomdar_trial` metadata record and the events on
//! `/pomdar/trial_events`; glove keypoints (22 × 3, a seeded wandering hand) and joint targets
//! (17 joints) in between at their usual rates. For the scoring benchmark and the end-to-end
//! tests: no scoring shortcut knows these files are synthetic.
//!
//! Only `fsync` differs from the station (`sync_on_flush` is off: it changes durability, not
//! a byte of the file).

use std::collections::BTreeMap;
use std::path::Path;

use msgs::{Float32MultiArray, Header, JointState, MultiArrayDimension, MultiArrayLayout, Time};

use crate::mcap_log::{FinishedTrial, LogError, OfferedQos, TrialWriter, TrialWriterOptions};

/// Glove keypoint topic of the station's default configuration.
pub const KEYPOINTS_TOPIC: &str = "/ingress/mano";
/// Joint target topic of the station's default configuration.
pub const JOINT_TARGETS_TOPIC: &str = "/pomdar/hand/joint_targets";

/// One synthetic trial.
#[derive(Debug, Clone, PartialEq)]
pub struct SyntheticTrial {
    /// The `pomdar_trial` metadata record.
    pub metadata: BTreeMap<String, String>,
    /// Log time of the first message, ns since the epoch.
    pub t0_ns: i64,
    /// Length of the recording, seconds (keypoints and joint targets fill it).
    pub duration_s: f64,
    /// Trial events as (seconds after `t0_ns`, JSON), written in this order.
    pub events: Vec<(f64, serde_json::Value)>,
    /// Glove keypoint rate, Hz (the lab's glove: 100).
    pub keypoint_rate_hz: f64,
    /// Joint target rate, Hz (the station's rate control: 25).
    pub joint_rate_hz: f64,
    /// Seed of the hand's motion.
    pub seed: u64,
}

/// The seeded generator of the test data: the workspace's one SplitMix64.
pub use retarget::human_hand::SplitMix64;

fn to_ns(seconds: f64) -> i64 {
    (seconds * 1e9).round() as i64
}

/// Writes `trial` to `path` (via `path.part`, renamed at the end, as the station does).
pub fn write_synthetic_trial(
    path: &Path,
    trial: &SyntheticTrial,
) -> Result<FinishedTrial, LogError> {
    let options = TrialWriterOptions {
        sync_on_flush: false,
        ..TrialWriterOptions::default()
    };
    let mut w = TrialWriter::create(path, options)?;
    w.add_channel::<Float32MultiArray>(KEYPOINTS_TOPIC, &[OfferedQos::best_effort(400)])?;
    w.add_channel::<JointState>(JOINT_TARGETS_TOPIC, &[OfferedQos::reliable(50)])?;
    w.write_metadata(scoring::TRIAL_METADATA_NAME, trial.metadata.clone())?;

    let mut rng = SplitMix64::new(trial.seed);
    let layout = MultiArrayLayout {
        dim: vec![
            MultiArrayDimension {
                label: "keypoints".into(),
                size: 22,
                stride: 66,
            },
            MultiArrayDimension {
                label: "xyz".into(),
                size: 3,
                stride: 3,
            },
        ],
        data_offset: 0,
    };
    let mut hand: Vec<f32> = (0..66).map(|i| 0.02 * (i % 7) as f32).collect();
    let names: Vec<String> = (0..17).map(|i| format!("joint_{i:02}")).collect();
    let key_dt = 1.0 / trial.keypoint_rate_hz;
    let joint_dt = 1.0 / trial.joint_rate_hz;
    let (mut next_key, mut next_joint) = (0.0_f64, 0.0_f64);
    let mut events = trial.events.iter().peekable();
    loop {
        let next_event = events.peek().map_or(f64::INFINITY, |(t, _)| *t);
        let t = next_key.min(next_joint).min(next_event);
        if t > trial.duration_s && next_event.is_infinite() {
            break;
        }
        let log_ns = trial.t0_ns + to_ns(t);
        if t == next_event {
            if let Some((_, event)) = events.next() {
                w.write_event(log_ns, event)?;
            }
        } else if t == next_key {
            for v in &mut hand {
                *v += (rng.next_f64() as f32 - 0.5) * 0.002;
            }
            let message = Float32MultiArray {
                layout: layout.clone(),
                data: hand.clone(),
            };
            w.write(KEYPOINTS_TOPIC, log_ns, log_ns - 2_000_000, &message)?;
            next_key += key_dt;
            if next_key > trial.duration_s {
                next_key = f64::INFINITY;
            }
        } else {
            let message = JointState {
                header: Header {
                    stamp: Time::from_nanos(log_ns),
                    frame_id: String::new(),
                },
                name: names.clone(),
                position: (0..17).map(|i| f64::from(hand[i]) * 10.0).collect(),
                velocity: Vec::new(),
                effort: Vec::new(),
            };
            w.write(JOINT_TARGETS_TOPIC, log_ns, log_ns, &message)?;
            next_joint += joint_dt;
            if next_joint > trial.duration_s {
                next_joint = f64::INFINITY;
            }
        }
    }
    w.finish()
}
