//! Post-trial feedback: short sentences from the trial's measured facts, each said only when
//! its setting's threshold is crossed, so a clean trial gets none. The sentences and their
//! thresholds are here; the rules that say them, in `feedback_rules.rs`.
//!
//! | setting | default | says |
//! |---|---|---|
//! | `holds_min` | 1 | "held 3× (glove gaps 180–420 ms)" |
//! | `pinch_misses_min` | 1 | "index pinch did not close in 4 of 6 attempts (robot 18 mm apart)" |
//! | `wrist_at_limit_share` | 0.10 | "wrist at its limit 22 % of the time" |
//! | `stall_before_drop_s` | 2.0 | "2.4 s without progress before the drop at 9.1 s" |
//! | `rejected_frames_min` | 5 | "7 glove frames rejected (jump, bone_length)" |
//! | `tracking_error_deg` | 5.0 | "ring 7° off its commands on average" |
//! | `arm_refusals_min` | 1 | "arm refused 2× (workspace)" |

use serde::{Deserialize, Serialize};

/// The thresholds of the feedback sentences.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FeedbackSettings {
    /// Say the holds when the station held at least this many times.
    pub holds_min: usize,
    /// Say a finger's pinches when at least this many of them did not close.
    pub pinch_misses_min: usize,
    /// Say the wrist's limit when at least this share of the arm targets were at it.
    pub wrist_at_limit_share: f64,
    /// Say a drop when at least this long passed without progress before it, seconds.
    pub stall_before_drop_s: f64,
    /// Say the rejected glove frames when at least this many were rejected.
    pub rejected_frames_min: u64,
    /// Say a digit's tracking when its mean error reached this, degrees.
    pub tracking_error_deg: f64,
    /// Say the arm's refusals when it refused at least this many steps.
    pub arm_refusals_min: u64,
}

impl Default for FeedbackSettings {
    fn default() -> Self {
        FeedbackSettings {
            holds_min: 1,
            pinch_misses_min: 1,
            wrist_at_limit_share: 0.10,
            stall_before_drop_s: 2.0,
            rejected_frames_min: 5,
            tracking_error_deg: 5.0,
            arm_refusals_min: 1,
        }
    }
}

/// What a sentence is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FeedbackKind {
    /// The station held on a stalled glove.
    Holds,
    /// A finger's pinches did not close.
    PinchNotClosed,
    /// The wrist at its workspace limit.
    WristAtLimit,
    /// No progress for long before a drop.
    StallBeforeDrop,
    /// Glove frames rejected.
    RejectedFrames,
    /// A digit far from its commands.
    TrackingError,
    /// Arm steps refused.
    ArmRefused,
}

/// One sentence of feedback.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Feedback {
    /// What it is about.
    pub kind: FeedbackKind,
    /// The sentence.
    pub text: String,
    /// When it happened, seconds into the trial (each occurrence).
    pub times_s: Vec<f64>,
    /// The setting whose threshold it crossed.
    pub setting: &'static str,
}
