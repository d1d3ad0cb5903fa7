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

use std::collections::BTreeMap;

use msgs::StringMsg;
use serde_json::{Value, json};

use crate::calibrate::CalibrateError;
use crate::mcap_log::{TRIAL_EVENTS_TOPIC, TrialReader};

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

/// Every closed capture window of a session log, in log order, with its quality and
/// decision. A window that never closed (an interrupted session) is left out.
pub fn capture_attempts(reader: &TrialReader) -> Result<Vec<CaptureAttempt>, CalibrateError> {
    let mut open: BTreeMap<(String, u64), i64> = BTreeMap::new();
    let mut attempts: Vec<CaptureAttempt> = Vec::new();
    for message in reader.messages_on(TRIAL_EVENTS_TOPIC) {
        let text: StringMsg = message.decode()?;
        let Ok(event) = serde_json::from_str::<Value>(&text.data) else {
            continue;
        };
        let Some(pose) = event["pose"].as_str() else {
            continue;
        };
        let attempt = event["attempt"].as_u64().unwrap_or(1);
        let key = (pose.to_string(), attempt);
        match event["event"].as_str() {
            Some(CAPTURE_EVENT) => match event["phase"].as_str() {
                Some("start") => {
                    open.insert(key, message.log_time_ns);
                }
                Some("end") => {
                    let Some(start) = open.remove(&key) else {
                        return Err(CalibrateError::CaptureWithoutStart {
                            file: reader.path().to_path_buf(),
                            pose: pose.to_string(),
                            at_ns: message.log_time_ns,
                        });
                    };
                    attempts.push(CaptureAttempt {
                        pose: pose.to_string(),
                        attempt,
                        window: (start, message.log_time_ns),
                        quality: None,
                        decision: None,
                    });
                }
                _ => {}
            },
            Some(QUALITY_EVENT) => {
                if let Some(a) = last_attempt(&mut attempts, pose, attempt) {
                    a.quality = event["quality"].as_str().map(str::to_string);
                }
            }
            Some(DECISION_EVENT) => {
                if let Some(a) = last_attempt(&mut attempts, pose, attempt) {
                    a.decision = event["decision"].as_str().map(str::to_string);
                }
            }
            _ => {}
        }
    }
    Ok(attempts)
}

fn last_attempt<'a>(
    attempts: &'a mut [CaptureAttempt],
    pose: &str,
    attempt: u64,
) -> Option<&'a mut CaptureAttempt> {
    attempts
        .iter_mut()
        .rev()
        .find(|a| a.pose == pose && a.attempt == attempt)
}

/// The capture window the fit uses for each pose, log-time nanoseconds `[start, end)`: the
/// accepted capture's, or in a log without decisions (written before captures were judged)
/// the pose's last. A pose without one (an interrupted session) has no entry.
pub fn capture_windows(
    reader: &TrialReader,
) -> Result<BTreeMap<String, (i64, i64)>, CalibrateError> {
    let attempts = capture_attempts(reader)?;
    let judged = attempts.iter().any(|a| a.decision.is_some());
    Ok(attempts
        .into_iter()
        .filter(|a| !judged || a.decision.as_deref() == Some("accepted"))
        .map(|a| (a.pose, a.window))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mcap_log::{TrialWriter, TrialWriterOptions};

    /// Writes a log with these events, one per millisecond, and reads its windows back.
    fn windows_of(
        name: &str,
        events: &[Value],
    ) -> (Vec<CaptureAttempt>, BTreeMap<String, (i64, i64)>) {
        let dir =
            std::env::temp_dir().join(format!("pomdar-session-events-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(format!("{name}.mcap"));
        // A directory named by the process id may be left from an earlier process that had it.
        std::fs::remove_file(&path).ok();
        let mut writer = TrialWriter::create(&path, TrialWriterOptions::default()).unwrap();
        for (i, event) in events.iter().enumerate() {
            writer
                .write_event(1_000_000 * (i as i64 + 1), event)
                .unwrap();
        }
        writer.finish().unwrap();
        let reader = TrialReader::open(&path).unwrap();
        (
            capture_attempts(&reader).unwrap(),
            capture_windows(&reader).unwrap(),
        )
    }

    fn with(mut event: Value, attempt: u64) -> Value {
        event["attempt"] = attempt.into();
        event
    }

    #[test]
    fn the_accepted_capture_is_used_and_old_logs_read_as_before() {
        // A log written before captures were judged: no attempts, no decisions.
        let (attempts, windows) = windows_of(
            "old",
            &[
                capture_event("open", true),
                capture_event("open", false),
                capture_event("closed", true),
                capture_event("closed", false),
            ],
        );
        assert_eq!(attempts.len(), 2);
        assert_eq!(attempts[0].attempt, 1);
        assert_eq!(windows["open"], (1_000_000, 2_000_000));
        assert_eq!(windows["closed"], (3_000_000, 4_000_000));

        // A judged log: the retried first capture of "open" is kept but not used.
        let decision = |pose: &str, attempt: u64, d: &str| json!({"event": DECISION_EVENT, "pose": pose, "attempt": attempt, "decision": d, "by": "operator"});
        let quality = |pose: &str, attempt: u64, q: &str| json!({"event": QUALITY_EVENT, "pose": pose, "attempt": attempt, "quality": q});
        let (attempts, windows) = windows_of(
            "judged",
            &[
                with(capture_event("open", true), 1),
                with(capture_event("open", false), 1),
                quality("open", 1, "bad"),
                decision("open", 1, "retry"),
                with(capture_event("open", true), 2),
                with(capture_event("open", false), 2),
                quality("open", 2, "good"),
                decision("open", 2, "accepted"),
                with(capture_event("closed", true), 1),
                with(capture_event("closed", false), 1),
                quality("closed", 1, "poor"),
            ],
        );
        assert_eq!(attempts.len(), 3);
        assert_eq!(
            (
                attempts[0].quality.as_deref(),
                attempts[0].decision.as_deref()
            ),
            (Some("bad"), Some("retry"))
        );
        assert_eq!(attempts[1].attempt, 2);
        assert_eq!(windows["open"], (5_000_000, 6_000_000));
        // "closed" was never accepted (the session stopped in review): no window for the fit.
        assert!(!windows.contains_key("closed"), "{windows:?}");
    }
}
