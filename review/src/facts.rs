//! A trial's facts, as the review reports them (and writes as JSON): the glove's part, the
//! arm's, counted things at a time, the pinches, holds and tracking, with the feedback said
//! about them and the thresholds it was judged with. Built by [`crate::review()`].

use std::collections::BTreeMap;

use serde::Serialize;

use crate::feedback::{Feedback, FeedbackSettings};
use crate::pinches::PinchAttempt;
use crate::signals::ProgressMark;
use crate::spans::{Hold, StateSpan};

/// Counted things that happened at a time (rejected frames, refused arm steps).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CountAt {
    /// When the status reported them, seconds into the trial.
    pub t_s: f64,
    /// How many since the status before.
    pub count: u64,
    /// Their reasons.
    pub reasons: Vec<String>,
}

/// The glove's part.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GloveFacts {
    /// Frames received inside the trial.
    pub frames: usize,
    /// The longest gap between frames, milliseconds.
    pub longest_gap_ms: Option<f64>,
    /// Frames the station rejected.
    pub rejected: Vec<CountAt>,
}

/// The arm's part.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ArmFacts {
    /// The task's constraint (`fixed`, `vertical_axis`, …) as the status said it.
    pub constraint: Option<String>,
    /// When the arm clutch was engaged.
    pub clutch: Vec<StateSpan>,
    /// Arm steps the station refused.
    pub refusals: Vec<CountAt>,
    /// Share of the arm targets at a face of the workspace box.
    pub at_limit_share: Option<f64>,
}

/// A trial's review: the short JSON of `pomdar review`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TrialReview {
    /// The file.
    pub file: String,
    /// The trial's metadata (task, embodiment, user, trial index, …).
    pub metadata: BTreeMap<String, String>,
    /// The trial's length, seconds.
    pub duration_s: f64,
    /// How it ended: `stopped`, `aborted` or `unfinished` (no stop in the log).
    pub ending: String,
    /// Progress marks and drops.
    pub progress: Vec<ProgressMark>,
    /// The station's drive state over the trial.
    pub drive: Vec<StateSpan>,
    /// The holds on a stalled glove.
    pub holds: Vec<Hold>,
    /// The glove.
    pub glove: GloveFacts,
    /// The station's hold timeout, milliseconds, when known.
    pub hold_timeout_ms: Option<f64>,
    /// The arm.
    pub arm: ArmFacts,
    /// The human's sustained pinches and whether the robot closed them.
    pub pinches: Vec<PinchAttempt>,
    /// Per digit, the mean tracking error, degrees (empty without the hand's measured state).
    pub tracking_mean_deg: BTreeMap<String, f64>,
    /// The sentences for the operator.
    pub feedback: Vec<Feedback>,
    /// The thresholds they were judged with.
    pub settings: FeedbackSettings,
    /// What the review could not judge, and why.
    pub notes: Vec<String>,
}
