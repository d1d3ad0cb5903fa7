//! Reading a trial's log into the review's input: the trial events and the station's status
//! (JSON in `std_msgs/String`), the glove keypoints (either format), the hand commands and
//! measured states (`sensor_msgs/JointState`) and the arm targets' positions. A message that
//! does not decode is left out (the station wrote every one; a damaged log still reviews).

use msgs::{JointState, PoseStamped, StringMsg};
use review::{GloveFrame, JointSample, TrialInput};
use station::StationConfig;

use crate::mcap_log::{LogError, LoggedMessage, TRIAL_EVENTS_TOPIC, TrialReader};

/// The review's input from `reader`, its topics named by `config`. `Err` only when the log
/// cannot be read.
pub fn read_trial_input(
    reader: &TrialReader,
    config: &StationConfig,
) -> Result<TrialInput, LogError> {
    Ok(TrialInput {
        source: reader.path().display().to_string(),
        metadata: reader
            .metadata_named(scoring::TRIAL_METADATA_NAME)
            .cloned()
            .unwrap_or_default(),
        events: json_messages(reader, TRIAL_EVENTS_TOPIC),
        statuses: json_messages(reader, &config.output.status_topic),
        glove_frames: reader
            .messages_on(&config.input.keypoints_topic)
            .filter_map(glove_frame)
            .collect(),
        joint_targets: joint_samples(reader, &config.output.joint_targets_topic),
        hand_states: joint_samples(reader, &config.input.hand_state_topic),
        arm_targets: reader
            .messages_on(&config.output.arm_target_topic)
            .filter_map(|m| {
                let p = m.decode::<PoseStamped>().ok()?.pose.position;
                Some((m.log_time_ns, [p.x, p.y, p.z]))
            })
            .collect(),
    })
}

/// `(log time, JSON)` of the `std_msgs/String` messages on `topic` that hold JSON.
fn json_messages(reader: &TrialReader, topic: &str) -> Vec<(i64, serde_json::Value)> {
    if topic.is_empty() {
        return Vec::new();
    }
    reader
        .messages_on(topic)
        .filter_map(|m| {
            let text = m.decode::<StringMsg>().ok()?.data;
            Some((m.log_time_ns, serde_json::from_str(&text).ok()?))
        })
        .collect()
}

fn glove_frame(message: &LoggedMessage) -> Option<GloveFrame> {
    Some(GloveFrame {
        t_ns: message.log_time_ns,
        points: message.keypoints()?.points(),
    })
}

fn joint_samples(reader: &TrialReader, topic: &str) -> Vec<JointSample> {
    if topic.is_empty() {
        return Vec::new();
    }
    reader
        .messages_on(topic)
        .filter_map(|m| {
            let state = m.decode::<JointState>().ok()?;
            Some(JointSample {
                t_ns: m.log_time_ns,
                stamp_ns: state.header.stamp.to_nanos(),
                names: state.name,
                position: state.position,
            })
        })
        .collect()
}
