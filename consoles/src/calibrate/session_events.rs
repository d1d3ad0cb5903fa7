//! What a calibration session log says besides the keypoints: its metadata record and the
//! events on the trial-events channel (`/pomdar/trial_events`, JSON in `std_msgs/String`).
//!
//! | event | meaning |
//! |---|---|
//! | `{"event":"start","session":"calibration"}` | the session's time origin |
//! | `{"event":"calibration_pose","pose":P,"instruction":…,"attempt":N}` | the hand was sent to pose P (again for a retry) |
//! | `{"event":"calibration_capture","pose":P,"phase":"start","attempt":N}` | P's N-th capture window opens |
//! | `{"event":"calibration_capture","pose":P,"phase":"end","attempt":N}` | … and closes |
//! | `{"event":"calibration_capture_quality","pose":P,"attempt":N,"quality":"good"\|"poor"\|"bad",…}` | the capture's measures ([`super::capture_quality`]) |
//! | `{"event":"calibration_capture_decision","pose":P,"attempt":N,"decision":"accepted"\|"retry","by":"auto"\|"operator"}` | what became of it |
//! | `{"event":"calibration_pose_not_sent","topic":T,"count":N}` | N sends of the pose to the hand could not be published (written before the log is finished, only if N > 0) |
//! | `{"event":"abort","reason":…}` | the session was abandoned |
//! | `{"event":"stop","summary":{…}}` | every pose has an accepted capture |
//!
//! A capture's frames are the keypoint messages whose log time lies in `[start, end)` of its
//! capture events. The fit uses each pose's accepted capture. Logs written before captures
//! were judged (no `attempt`, no decision events) have one capture per pose, which is used.
//! Reading them back from a log is `teleop::calibrate::session_events`.

use serde_json::{Value, json};

/// Name of the session's metadata record.
pub const SESSION_METADATA: &str = "pomdar_calibration_session";

/// Event name of a capture window's start or end.
pub const CAPTURE_EVENT: &str = "calibration_capture";

/// Event name of a pose being commanded.
pub const POSE_EVENT: &str = "calibration_pose";

/// Event name of a capture's measured quality.
pub const QUALITY_EVENT: &str = "calibration_capture_quality";

/// Event name of the decision about a capture (accepted, or retried).
pub const DECISION_EVENT: &str = "calibration_capture_decision";

/// Event name of the count of pose sends that could not be published.
pub const POSE_NOT_SENT_EVENT: &str = "calibration_pose_not_sent";

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

/// One capture window of a session log and what became of it.
#[derive(Debug, Clone, PartialEq)]
pub struct CaptureAttempt {
    /// The pose.
    pub pose: String,
    /// 1-based attempt (1 in logs without attempts).
    pub attempt: u64,
    /// Log-time nanoseconds `[start, end)`.
    pub window: (i64, i64),
    /// The measured quality (`good`, `poor`, `bad`), if the log has it.
    pub quality: Option<String>,
    /// `accepted` or `retry`, if the log has a decision.
    pub decision: Option<String>,
}
