//! The timing of a calibration session: one slot per pose, the capture at the end of it.
//!
//! Pose `k` (capture order) owns the slot `[k·T, (k+1)·T)` from the session's start. The robot
//! is sent to the pose at the slot's start, the user moves and settles, and the last
//! `capture_s` seconds of the slot are captured. The simulated glove's
//! [`CalibrationPoses`](retarget::human_hand::MotionKind::CalibrationPoses) motion follows the
//! same slots (move for 35 % of the slot, hold the rest).

use serde::{Deserialize, Serialize};

use crate::error::Error;

/// Slot length and capture length of a session.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CaptureSchedule {
    /// Time per pose, seconds.
    pub slot_s: f64,
    /// Captured time at the end of each slot, seconds.
    pub capture_s: f64,
}

impl Default for CaptureSchedule {
    fn default() -> Self {
        CaptureSchedule {
            slot_s: 2.5,
            capture_s: 1.0,
        }
    }
}

impl CaptureSchedule {
    /// Check the schedule: the capture fits in the slot's hold (after 35 % of the slot) with
    /// 0.2 s to spare, slots of 1–60 s.
    pub fn validate(&self) -> Result<(), Error> {
        if !(self.slot_s.is_finite() && (1.0..=60.0).contains(&self.slot_s)) {
            return Err(Error::Setting {
                key: "schedule.slot_s".into(),
                value: self.slot_s.to_string(),
                allowed: "must be in [1, 60] s".into(),
            });
        }
        let room = 0.65 * self.slot_s - 0.2;
        if !(self.capture_s.is_finite() && self.capture_s >= 0.2 && self.capture_s <= room) {
            return Err(Error::Setting {
                key: "schedule.capture_s".into(),
                value: self.capture_s.to_string(),
                allowed: format!("must be in [0.2, {room:.2}] s for a {} s slot", self.slot_s),
            });
        }
        Ok(())
    }

    /// The capture window of pose `k`, seconds from the session's start: `[start, end)`.
    pub fn capture_window(&self, k: usize) -> (f64, f64) {
        let end = (k + 1) as f64 * self.slot_s;
        (end - self.capture_s, end)
    }

    /// The session's length for `poses` poses, seconds.
    pub fn duration_s(&self, poses: usize) -> f64 {
        poses as f64 * self.slot_s
    }
}
