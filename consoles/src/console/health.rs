//! The station's health as the console shows it, read from the station's status (the JSON it
//! publishes on its status topic), and whether a trial may start.

use serde_json::Value;

/// The limits a trial start is held to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StartLimits {
    /// Lowest rate of new glove frames, Hz.
    pub min_glove_rate_hz: f64,
    /// Oldest the last glove frame may be, milliseconds.
    pub max_input_age_ms: f64,
    /// Oldest the station's status may be, milliseconds (else the station is not reporting).
    pub max_status_age_ms: f64,
    /// Whether the station drives a robot, which must be engaged before a trial starts;
    /// false in a human study, where only the glove's health is checked.
    pub drives_robot: bool,
}

impl Default for StartLimits {
    fn default() -> Self {
        StartLimits {
            min_glove_rate_hz: 20.0,
            max_input_age_ms: 200.0,
            max_status_age_ms: 1500.0,
            drives_robot: true,
        }
    }
}

/// A glove gap at least this long is named when the station is not engaged, ms (the
/// station's default hold timeout).
const NOTED_GAP_MS: f64 = 150.0;

/// A turn of the station's loop at least this long is named when the glove is found stale
/// (a 100 Hz glove's frames queue behind it).
const NOTED_TURN_MS: f64 = 50.0;

/// The station's health at one status.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Health {
    /// When the console received this status (console clock, ns); `None` before any.
    pub received_ns: Option<i64>,
    /// `engaged`, `held` or `disengaged`.
    pub state: String,
    /// New glove frames per second.
    pub glove_rate_hz: f64,
    /// Age of the last new glove frame when the status was made, ms.
    pub input_age_ms: Option<f64>,
    /// The newest new glove frame's receive time (the station's clock, ns), kept current
    /// between statuses when the station runs in this process (its `LatestInput` hook).
    pub latest_input_ns: Option<i64>,
    /// The longest gap between new glove frames so far: (as received, as sent), ms.
    pub longest_gap_ms: Option<(f64, f64)>,
    /// The station loop's longest turn so far: ms and its handler.
    pub longest_turn: Option<(f64, String)>,
    /// Frame received → command published, ms (the last one).
    pub latency_ms: Option<f64>,
    /// Hand commands per second.
    pub output_rate_hz: f64,
    /// Frames rejected so far (all reasons).
    pub rejected: u64,
    /// Whether the arm is engaged (driven).
    pub arm_engaged: bool,
    /// A second publisher on the arm command topic (the station refuses to drive the arm).
    pub second_publisher: bool,
    /// Subscribers matched to the hand's joint targets (the robot hand listening).
    pub hand_listeners: Option<u64>,
    /// Subscribers matched to the arm targets, besides the station's own monitor.
    pub arm_listeners: Option<u64>,
    /// What went wrong without stopping the station, counted since it started.
    pub faults: Faults,
    /// The hand's measured state against the command in force, when the hand publishes one.
    pub hand_tracking: Option<HandTracking>,
}

/// The hand's measured state against the command in force (the status's `hand_feedback`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct HandTracking {
    /// Largest |command − measured| over the joints in the last measured state, degrees.
    pub max_error_deg: Option<f64>,
    /// The joint with that error.
    pub worst_joint: Option<String>,
    /// Age of the last measured state, ms.
    pub age_ms: Option<f64>,
}

impl HandTracking {
    /// The tracking part of a status, `None` when the hand has sent no measured state.
    pub fn from_status(status: &Value) -> Option<HandTracking> {
        let feedback = status.get("hand_feedback")?;
        if feedback.get("states").and_then(Value::as_u64).unwrap_or(0) == 0 {
            return None;
        }
        Some(HandTracking {
            max_error_deg: feedback.get("max_error_deg").and_then(Value::as_f64),
            worst_joint: (feedback.get("worst_joint").and_then(Value::as_str)).map(str::to_string),
            age_ms: feedback.get("age_ms").and_then(Value::as_f64),
        })
    }

    /// One line for the console: the worst joint's error and how fresh the measurement is.
    pub fn line(&self) -> String {
        let age = self
            .age_ms
            .map_or(String::new(), |a| format!(", measured {a:.0} ms ago"));
        match (self.max_error_deg, &self.worst_joint) {
            (Some(error), Some(joint)) => format!("max {error:.1}° ({joint}){age}"),
            _ => format!("measured, no command yet{age}"),
        }
    }
}

/// The station's fault counts (its status's `node` and `totals`), since it started.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Faults {
    /// Messages the node could not publish (all topics).
    pub publish_failed: u64,
    /// Samples a subscription could not deliver: undecodable or lost in DDS (all topics).
    pub samples_lost: u64,
    /// Arm targets the station refused to send (all reasons).
    pub arm_refused: u64,
    /// Engage requests the arm refused (e.g. no valid wrist pose).
    pub arm_engage_failed: u64,
    /// Messages left out of the trial logs because the disk fell behind (the recorder's
    /// queue was full).
    pub log_dropped: u64,
}

impl Faults {
    /// Reads the counts from the station's status; missing fields count 0.
    pub fn from_status(status: &Value) -> Faults {
        let total = |pointer: &str| {
            status
                .pointer(pointer)
                .and_then(Value::as_object)
                .map_or(0, |m| m.values().filter_map(Value::as_u64).sum())
        };
        Faults {
            publish_failed: total("/node/publish_failed"),
            samples_lost: total("/node/input_errors"),
            arm_refused: total("/totals/arm_refused"),
            arm_engage_failed: status
                .pointer("/totals/arm_engage_failed")
                .and_then(Value::as_u64)
                .unwrap_or(0),
            log_dropped: status
                .pointer("/node/log_dropped")
                .and_then(Value::as_u64)
                .unwrap_or(0),
        }
    }

    /// Whether anything was counted.
    pub fn any(&self) -> bool {
        *self != Faults::default()
    }
}

impl Health {
    /// Reads the station's status JSON received at `received_ns`; missing fields stay empty.
    pub fn from_status(status: &Value, received_ns: i64) -> Health {
        let number = |v: &Value| v.as_f64();
        let rejected = status
            .pointer("/counters/rejected")
            .and_then(Value::as_object)
            .map_or(0, |m| m.values().filter_map(Value::as_u64).sum());
        Health {
            received_ns: Some(received_ns),
            state: status
                .get("state")
                .and_then(Value::as_str)
                .unwrap_or("unknown")
                .to_string(),
            glove_rate_hz: status.get("input_rate_hz").and_then(number).unwrap_or(0.0),
            input_age_ms: status.get("input_age_ms").and_then(number),
            latest_input_ns: None,
            longest_gap_ms: status.get("longest_input_gap").and_then(|gap| {
                Some((
                    gap.get("received_ms").and_then(number)?,
                    gap.get("sent_ms").and_then(number)?,
                ))
            }),
            longest_turn: status.get("longest_turn").and_then(|turn| {
                Some((
                    turn.get("ms").and_then(number)?,
                    turn.get("handler")?.as_str()?.to_string(),
                ))
            }),
            latency_ms: status.get("processing_latency_ms").and_then(number),
            output_rate_hz: status.get("output_rate_hz").and_then(number).unwrap_or(0.0),
            rejected,
            arm_engaged: status
                .pointer("/arm/engaged")
                .and_then(Value::as_bool)
                .unwrap_or(false),
            second_publisher: status
                .pointer("/arm/second_publisher")
                .and_then(Value::as_bool)
                .unwrap_or(false),
            hand_listeners: status.pointer("/listeners/hand").and_then(Value::as_u64),
            arm_listeners: status.pointer("/listeners/arm").and_then(Value::as_u64),
            faults: Faults::from_status(status),
            hand_tracking: HandTracking::from_status(status),
        }
    }

    /// Whether the station drives the robot.
    pub fn engaged(&self) -> bool {
        self.state == "engaged"
    }

    /// Whether the glove is fit for a trial as of the last status: reported, fresh and fast
    /// enough (the readiness of a human study, which has nothing to engage).
    pub fn glove_ready(&self, limits: &StartLimits) -> bool {
        self.received_ns.is_some()
            && self
                .input_age_ms
                .is_some_and(|age| age <= limits.max_input_age_ms)
            && self.glove_rate_hz >= limits.min_glove_rate_hz
    }

    /// Age of the glove input at `now_ns`, ms: exact from the newest frame's time when the
    /// station shares it, else the status's input age plus the status's own age (an upper
    /// bound, up to one status period over, for a station reporting only through its status).
    pub fn input_age_at(&self, now_ns: i64) -> Option<f64> {
        if let Some(latest) = self.latest_input_ns {
            return Some((now_ns - latest).max(0) as f64 * 1e-6);
        }
        let received = self.received_ns?;
        Some(self.input_age_ms? + (now_ns - received) as f64 * 1e-6)
    }

    /// Why the glove input is stale, with which side the longest gap so far was on.
    fn stale_input(&self, age_ms: f64, limit_ms: f64) -> String {
        let mut why =
            format!("glove input is stale: last frame {age_ms:.0} ms ago (limit {limit_ms:.0} ms)");
        if let Some((received, sent)) = self.longest_gap_ms {
            why.push_str(&format!(
                "; longest gap so far {received:.0} ms as received, {sent:.0} ms as sent"
            ));
        }
        why.push_str(&self.long_turn());
        why
    }

    /// `; the station's longest turn 612 ms (status)` when its loop once spent
    /// [`NOTED_TURN_MS`] or more in one handler (taking no frame meanwhile), else empty.
    fn long_turn(&self) -> String {
        match &self.longest_turn {
            Some((ms, handler)) if *ms >= NOTED_TURN_MS => {
                format!("; the station's longest turn {ms:.0} ms ({handler})")
            }
            _ => String::new(),
        }
    }

    /// Why a trial may not start at `now_ns`, if it may not.
    pub fn refuse_start(&self, limits: &StartLimits, now_ns: i64) -> Option<String> {
        let Some(received) = self.received_ns else {
            return Some("the station has not reported yet".to_string());
        };
        let status_age = (now_ns - received) as f64 * 1e-6;
        if status_age > limits.max_status_age_ms {
            return Some(format!(
                "the station has not reported for {:.1} s",
                status_age / 1e3
            ));
        }
        match self.input_age_at(now_ns) {
            None => return Some("no glove input yet: is the glove streaming?".to_string()),
            Some(age) if age > limits.max_input_age_ms => {
                return Some(self.stale_input(age, limits.max_input_age_ms));
            }
            Some(_) => {}
        }
        if self.glove_rate_hz < limits.min_glove_rate_hz {
            return Some(format!(
                "glove rate {:.1} Hz is below the minimum {:.1} Hz (--min-glove-rate){}",
                self.glove_rate_hz,
                limits.min_glove_rate_hz,
                self.long_turn()
            ));
        }
        if limits.drives_robot && !self.engaged() {
            return Some(format!(
                "the station is {}{}: press e to engage",
                self.state,
                self.gap_note()
            ));
        }
        None
    }

    /// Where the glove's frames once stopped long enough to hold the hand, which side
    /// stalled: the longest gap as received beside the same frames' gap as sent (equal: the
    /// glove stopped sending; longer as received: the network or this machine held them).
    fn gap_note(&self) -> String {
        match self.longest_gap_ms {
            Some((received, sent)) if received >= NOTED_GAP_MS => format!(
                " (longest glove gap so far {received:.0} ms as received, {sent:.0} ms as sent)"
            ),
            _ => String::new(),
        }
    }
}

#[cfg(test)]
mod tests {
    use serde_json::json;

    use super::*;

    const MS: i64 = 1_000_000;

    fn status(state: &str, rate: f64, age_ms: Option<f64>) -> Value {
        json!({
            "state": state, "input_rate_hz": rate, "input_age_ms": age_ms,
            "processing_latency_ms": 0.4, "output_rate_hz": 25.0,
            "counters": {"rejected": {"jump": 2, "non_finite": 1}},
            "arm": {"engaged": true, "second_publisher": false},
            "listeners": {"hand": 1, "arm": 0},
            "totals": {"arm_refused": {"outside_workspace": 4}, "arm_engage_failed": 1},
            "node": {"publish_failed": {"/a": 2, "/b": 1}, "input_errors": {"/ingress/mano": 5}, "log_dropped": 7},
        })
    }

    #[test]
    fn reads_the_station_status() {
        let h = Health::from_status(&status("engaged", 99.0, Some(5.0)), 0);
        assert!(h.engaged());
        assert_eq!(h.rejected, 3);
        assert_eq!(h.latency_ms, Some(0.4));
        assert!(h.arm_engaged);
        assert_eq!((h.hand_listeners, h.arm_listeners), (Some(1), Some(0)));
        assert_eq!(
            h.faults,
            Faults {
                publish_failed: 3,
                samples_lost: 5,
                arm_refused: 4,
                arm_engage_failed: 1,
                log_dropped: 7,
            }
        );
        assert!(!Faults::from_status(&json!({})).any());
    }

    #[test]
    fn a_start_is_refused_for_stale_slow_or_disengaged_input() {
        let limits = StartLimits::default();
        let ok = Health::from_status(&status("engaged", 99.0, Some(5.0)), 0);
        assert_eq!(ok.refuse_start(&limits, 10 * MS), None);
        // The status itself goes old: input age grows with it.
        assert!(
            ok.refuse_start(&limits, 400 * MS)
                .is_some_and(|r| r.contains("stale"))
        );
        assert!(
            ok.refuse_start(&limits, 2000 * MS)
                .is_some_and(|r| r.contains("not reported"))
        );
        let slow = Health::from_status(&status("engaged", 12.0, Some(5.0)), 0);
        assert!(
            slow.refuse_start(&limits, 0)
                .is_some_and(|r| r.contains("12.0 Hz"))
        );
        let none = Health::from_status(&status("disengaged", 0.0, None), 0);
        assert!(
            none.refuse_start(&limits, 0)
                .is_some_and(|r| r.contains("no glove input"))
        );
        let off = Health::from_status(&status("disengaged", 99.0, Some(5.0)), 0);
        let why = off.refuse_start(&limits, 0).unwrap();
        assert!(why.contains("engage") && !why.contains("gap"), "{why}");
        // Disengaged after the glove's frames stopped: which side stalled is named.
        let mut stalled = status("disengaged", 99.0, Some(5.0));
        stalled["longest_input_gap"] = json!({"received_ms": 1203.4, "sent_ms": 10.2});
        let why = Health::from_status(&stalled, 0)
            .refuse_start(&limits, 0)
            .unwrap();
        assert!(
            why.contains("1203 ms as received, 10 ms as sent") && why.contains("press e"),
            "{why}"
        );
        assert!(Health::default().refuse_start(&limits, 0).is_some());
    }

    #[test]
    fn a_human_study_start_checks_only_the_glove() {
        let limits = StartLimits {
            drives_robot: false,
            ..StartLimits::default()
        };
        let healthy = Health::from_status(&status("disengaged", 99.0, Some(5.0)), 0);
        assert_eq!(healthy.refuse_start(&limits, 10 * MS), None);
        let slow = Health::from_status(&status("disengaged", 12.0, Some(5.0)), 0);
        assert!(
            slow.refuse_start(&limits, 0)
                .is_some_and(|r| r.contains("12.0 Hz"))
        );
        let stale = Health::from_status(&status("disengaged", 99.0, Some(500.0)), 0);
        assert!(
            stale
                .refuse_start(&limits, 0)
                .is_some_and(|r| r.contains("stale"))
        );
    }

    #[test]
    fn the_input_age_between_statuses_is_exact_when_the_station_shares_its_newest_frame() {
        let limits = StartLimits::default();
        // A 5 Hz status made 8 ms after a frame of a 100 Hz glove, 199 ms ago: the status alone
        // bounds the age at 207 ms, over the limit, though frames kept coming.
        let mut health = Health::from_status(&status("engaged", 99.0, Some(8.0)), 0);
        let now = 199 * MS;
        assert!(health.input_age_at(now).unwrap() > limits.max_input_age_ms);
        assert!(
            health
                .refuse_start(&limits, now)
                .is_some_and(|r| r.contains("stale"))
        );
        // The station's newest frame, 6 ms ago.
        health.latest_input_ns = Some(193 * MS);
        assert!((health.input_age_at(now).unwrap() - 6.0).abs() < 1e-9);
        assert_eq!(health.refuse_start(&limits, now), None);
        // A glove that stopped: the exact age grows past the limit.
        assert!(
            health
                .refuse_start(&limits, 400 * MS)
                .is_some_and(|r| r.contains("last frame 207 ms ago"))
        );
    }

    #[test]
    fn a_stale_input_refusal_says_on_which_side_the_longest_gap_was() {
        let mut document = status("disengaged", 99.0, Some(500.0));
        document["longest_input_gap"] = json!({"received_ms": 512.4, "sent_ms": 10.1});
        let health = Health::from_status(&document, 0);
        assert_eq!(health.longest_gap_ms, Some((512.4, 10.1)));
        let why = health.refuse_start(&StartLimits::default(), 0).unwrap();
        assert!(
            why.ends_with("longest gap so far 512 ms as received, 10 ms as sent"),
            "{why}"
        );
    }

    #[test]
    fn a_stale_input_refusal_names_a_long_turn_of_the_station() {
        let mut document = status("disengaged", 99.0, Some(500.0));
        document["longest_turn"] = json!({"ms": 612.0, "handler": "status"});
        let why = Health::from_status(&document, 0)
            .refuse_start(&StartLimits::default(), 0)
            .unwrap();
        assert!(
            why.ends_with("the station's longest turn 612 ms (status)"),
            "{why}"
        );
        document["longest_turn"] = json!({"ms": 3.0, "handler": "keypoints"});
        let why = Health::from_status(&document, 0)
            .refuse_start(&StartLimits::default(), 0)
            .unwrap();
        assert!(!why.contains("longest turn"), "{why}");
        let mut slow = status("disengaged", 5.0, Some(5.0));
        slow["longest_turn"] = json!({"ms": 1040.0, "handler": "keypoints"});
        let why = Health::from_status(&slow, 0)
            .refuse_start(&StartLimits::default(), 0)
            .unwrap();
        assert!(
            why.starts_with("glove rate 5.0 Hz")
                && why.ends_with("the station's longest turn 1040 ms (keypoints)"),
            "{why}"
        );
    }

    #[test]
    fn hand_tracking_is_read_from_the_status_only_once_the_hand_has_reported() {
        let silent = json!({"hand_feedback": {"states": 0, "max_error_deg": null}});
        assert_eq!(Health::from_status(&silent, 0).hand_tracking, None);
        let status = json!({"hand_feedback": {
            "states": 12, "max_error_deg": 3.25, "worst_joint": "right_index_mcp", "age_ms": 8.0
        }});
        let tracking = Health::from_status(&status, 0).hand_tracking.unwrap();
        assert_eq!(tracking.max_error_deg, Some(3.25));
        assert_eq!(
            tracking.line(),
            "max 3.2° (right_index_mcp), measured 8 ms ago"
        );
    }
}
