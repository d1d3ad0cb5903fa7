//! What a calibration session log says besides the keypoints: its metadata record and the
//! events on the trial-events channel (`/pomdar/trial_events`, JSON in `std_msgs/String`).
//!
//! | event | meaning |
//! |---|---|
//! | `{"event":"start","session":"calibration"}` | the schedule's time origin |
//! | `{"event":"calibration_pose","pose":P,"instruction":…}` | the hand was sent to pose P |
//! | `{"event":"calibration_capture","pose":P,"phase":"start"}` | P's capture window opens |
//! | `{"event":"calibration_capture","pose":P,"phase":"end"}` | P's capture window closes |
//! | `{"event":"stop","summary":{…}}` | the session ended |
//!
//! A pose's captured frames are the keypoint messages whose log time lies in
//! `[start, end)` of its capture events.

use std::collections::BTreeMap;

use anyhow::bail;
use msgs::StringMsg;
use serde_json::{Value, json};

use crate::mcap_log::{TRIAL_EVENTS_TOPIC, TrialReader};

/// Name of the session's metadata record.
pub const SESSION_METADATA: &str = "pomdar_calibration_session";

/// Event name of a capture window's start or end.
pub const CAPTURE_EVENT: &str = "calibration_capture";

/// Event name of a pose being commanded.
pub const POSE_EVENT: &str = "calibration_pose";

/// The event opening (`start = true`) or closing a pose's capture window.
pub fn capture_event(pose: &str, start: bool) -> Value {
    json!({
        "event": CAPTURE_EVENT,
        "pose": pose,
        "phase": if start { "start" } else { "end" },
    })
}

/// The event recording that the hand was sent to `pose`.
pub fn pose_event(pose: &str, instruction: &str) -> Value {
    json!({ "event": POSE_EVENT, "pose": pose, "instruction": instruction })
}

/// Capture windows by pose, log-time nanoseconds `[start, end)`, from a session log's events.
/// A pose whose window never closed (an interrupted session) has no entry.
pub fn capture_windows(reader: &TrialReader) -> anyhow::Result<BTreeMap<String, (i64, i64)>> {
    let mut open: BTreeMap<String, i64> = BTreeMap::new();
    let mut windows = BTreeMap::new();
    for message in reader.messages_on(TRIAL_EVENTS_TOPIC) {
        let text: StringMsg = message.decode()?;
        let Ok(event) = serde_json::from_str::<Value>(&text.data) else {
            continue;
        };
        if event["event"] != CAPTURE_EVENT {
            continue;
        }
        let Some(pose) = event["pose"].as_str() else {
            continue;
        };
        match event["phase"].as_str() {
            Some("start") => {
                open.insert(pose.to_string(), message.log_time_ns);
            }
            Some("end") => {
                let Some(start) = open.remove(pose) else {
                    bail!(
                        "{}: capture of pose '{pose}' ends at {} ns without a start",
                        reader.path().display(),
                        message.log_time_ns
                    );
                };
                windows.insert(pose.to_string(), (start, message.log_time_ns));
            }
            _ => {}
        }
    }
    Ok(windows)
}
