//! Reading a calibration session log's events back: every capture window with its quality and
//! decision, and each pose's accepted capture window. The metadata record's and the events'
//! names and shapes are the core crate's (`consoles::calibrate::session_events`, re-exported
//! here).

use std::collections::BTreeMap;

use msgs::StringMsg;
use serde_json::Value;

pub use consoles::calibrate::session_events::{
    CAPTURE_EVENT, CaptureAttempt, DECISION_EVENT, POSE_EVENT, POSE_NOT_SENT_EVENT, QUALITY_EVENT,
    SESSION_METADATA, capture_event, pose_event,
};

use crate::calibrate::CalibrateError;
use crate::mcap_log::{TRIAL_EVENTS_TOPIC, TrialReader};

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
    use serde_json::json;

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
