//! [`review`]: a trial's facts, its feedback and the series its figure draws.

use std::collections::BTreeMap;

use retarget::{Finger, HandModel, KeypointLayout};

use crate::error::ReviewError;
use crate::facts::{ArmFacts, CountAt, GloveFacts, TrialReview};
use crate::feedback::FeedbackSettings;
use crate::feedback_rules::feedback;
use crate::input::TrialInput;
use crate::pinches::{DistanceSeries, human_distances, pinch_attempts, robot_distances};
use crate::signals::{
    WorkspaceLimits, at_limit_share, count_increases, counts, input_age_ms, longest_glove_gap_ms,
    progress_marks, status_series,
};
use crate::spans::{clutch_spans, drive_spans, holds};
use crate::tracking::{DigitTracking, digit_tracking};
use crate::window::TrialWindow;

/// What the review knows beside the log: the hand, the glove's layout, the arm's box, the
/// thresholds.
#[derive(Debug, Clone)]
pub struct ReviewContext<'a> {
    /// The hand model the joint targets command.
    pub model: &'a HandModel,
    /// The prefix the station put before the model's joint names (`[output]
    /// joint_name_prefix`); without it the names are the model's or its URDF's.
    pub joint_name_prefix: Option<String>,
    /// The glove keypoints' layout.
    pub layout: KeypointLayout,
    /// The arm's workspace box, when the station drives an arm.
    pub workspace: Option<WorkspaceLimits>,
    /// The station's hold timeout (`watchdog.hold_timeout_ms`), milliseconds.
    pub hold_timeout_ms: Option<f64>,
    /// The feedback's thresholds.
    pub settings: &'a FeedbackSettings,
}

/// The dense series the figure draws (not in the JSON).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ReviewSeries {
    /// Glove frames per second, from the status.
    pub glove_rate_hz: Vec<(f64, f64)>,
    /// Age of the newest glove frame, milliseconds.
    pub input_age_ms: Vec<(f64, f64)>,
    /// The human's thumb–finger distances.
    pub human: DistanceSeries,
    /// The robot's.
    pub robot: DistanceSeries,
    /// Per-digit tracking error.
    pub tracking: DigitTracking,
}

/// Review `input`: its facts and feedback, and the series for its figure.
pub fn review(
    input: &TrialInput,
    context: &ReviewContext<'_>,
) -> Result<(TrialReview, ReviewSeries), ReviewError> {
    let window = TrialWindow::of(input)?;
    let model_error = |reason: String| ReviewError::Model {
        file: input.source.clone(),
        reason,
    };
    let joints = (context.model, context.joint_name_prefix.as_deref());
    let robot = robot_distances(&input.joint_targets, joints, &window).map_err(model_error)?;
    // The hand's own state may name its joints otherwise: then no tracking, and a note.
    let mut notes = Vec::new();
    let tracking = digit_tracking(&input.joint_targets, &input.hand_states, joints, &window)
        .unwrap_or_else(|reason| {
            notes.push(format!(
                "no tracking error: the hand's measured state has {reason}"
            ));
            DigitTracking::default()
        });
    let series = ReviewSeries {
        glove_rate_hz: status_series(&input.statuses, &window, |s| s["input_rate_hz"].as_f64()),
        input_age_ms: input_age_ms(&input.glove_frames, &window),
        human: human_distances(&input.glove_frames, context.layout, &window),
        robot,
        tracking,
    };
    let mut facts = TrialReview {
        file: input.source.clone(),
        metadata: input.metadata.clone(),
        duration_s: window.duration_s(),
        ending: ending(input),
        progress: progress_marks(input, &window),
        drive: drive_spans(&input.statuses, &window),
        holds: holds(&input.joint_targets, &input.glove_frames, &window),
        glove: glove_facts(input, &window),
        hold_timeout_ms: context.hold_timeout_ms,
        arm: arm_facts(input, &window, context.workspace.as_ref()),
        // Without hand commands (a human study) no pinch is the robot's to close.
        pinches: match series.robot.t_s.is_empty() {
            true => Vec::new(),
            false => pinch_attempts(&input.glove_frames, context.layout, &window, &series.robot),
        },
        tracking_mean_deg: tracking_means(&series.tracking),
        feedback: Vec::new(),
        settings: context.settings.clone(),
        notes,
    };
    facts.feedback = feedback(&facts, context.settings);
    Ok((facts, series))
}

/// How the trial ended.
fn ending(input: &TrialInput) -> String {
    let has = |name: &str| input.events.iter().any(|(_, e)| e["event"] == name);
    match (has("abort"), has("stop")) {
        (true, _) => "aborted",
        (false, true) => "stopped",
        (false, false) => "unfinished",
    }
    .to_string()
}

fn glove_facts(input: &TrialInput, window: &TrialWindow) -> GloveFacts {
    let rejected = count_increases(&input.statuses, window, |s| {
        counts(&s["counters"]["rejected"])
    });
    GloveFacts {
        frames: input
            .glove_frames
            .iter()
            .filter(|f| window.contains(f.t_ns))
            .count(),
        longest_gap_ms: longest_glove_gap_ms(&input.glove_frames, window),
        rejected: rejected.into_iter().map(count_at).collect(),
    }
}

fn arm_facts(
    input: &TrialInput,
    window: &TrialWindow,
    workspace: Option<&WorkspaceLimits>,
) -> ArmFacts {
    let refusals = count_increases(&input.statuses, window, |s| counts(&s["arm_refused"]));
    ArmFacts {
        constraint: input
            .statuses
            .iter()
            .rev()
            .find_map(|(_, s)| s["arm"]["constraint"].as_str().map(str::to_string)),
        clutch: clutch_spans(&input.statuses, window),
        refusals: refusals.into_iter().map(count_at).collect(),
        at_limit_share: at_limit_share(&input.arm_targets, window, workspace),
    }
}

fn count_at((t_s, count, reasons): (f64, u64, Vec<String>)) -> CountAt {
    CountAt {
        t_s,
        count,
        reasons,
    }
}

fn tracking_means(tracking: &DigitTracking) -> BTreeMap<String, f64> {
    Finger::ALL
        .into_iter()
        .filter_map(|f| tracking.mean_deg[f.index()].map(|m| (f.name().to_string(), m)))
        .collect()
}
