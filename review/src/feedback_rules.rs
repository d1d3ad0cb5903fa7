//! The feedback's rules: one per row of [`crate::feedback`]'s table, each reading the trial's
//! facts and saying its sentence only past its setting's threshold.

use crate::facts::{CountAt, TrialReview};
use crate::feedback::{Feedback, FeedbackKind, FeedbackSettings};

/// The sentences for `review` under `settings`, in the order of the table above.
pub(crate) fn feedback(review: &TrialReview, settings: &FeedbackSettings) -> Vec<Feedback> {
    let mut said = Vec::new();
    said.extend(holds(review, settings));
    said.extend(pinches(review, settings));
    said.extend(wrist(review, settings));
    said.extend(stalls(review, settings));
    said.extend(rejected(review, settings));
    said.extend(tracking(review, settings));
    said.extend(refusals(review, settings));
    said
}

fn holds(review: &TrialReview, settings: &FeedbackSettings) -> Option<Feedback> {
    let holds = &review.holds;
    if holds.is_empty() || holds.len() < settings.holds_min {
        return None;
    }
    let gaps: Vec<f64> = holds
        .iter()
        .map(|h| h.glove_gap_ms)
        .filter(|g| g.is_finite())
        .collect();
    let (low, high) = gaps
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(l, h), g| (l.min(*g), h.max(*g)));
    let text = match (holds.len(), gaps.len()) {
        (1, 1) => format!("held once (glove gap {low:.0} ms)"),
        (1, _) => "held once".to_string(),
        (n, 0) => format!("held {n}×"),
        (n, _) if (high - low) < 1.0 => format!("held {n}× (glove gaps {low:.0} ms)"),
        (n, _) => format!("held {n}× (glove gaps {low:.0}–{high:.0} ms)"),
    };
    Some(Feedback {
        kind: FeedbackKind::Holds,
        text,
        times_s: holds.iter().map(|h| h.from_s).collect(),
        setting: "holds_min",
    })
}

fn pinches(review: &TrialReview, settings: &FeedbackSettings) -> Vec<Feedback> {
    let mut said = Vec::new();
    for finger in ["index", "middle", "ring", "little"] {
        let attempts: Vec<_> = review
            .pinches
            .iter()
            .filter(|p| p.finger == finger)
            .collect();
        let missed: Vec<_> = attempts.iter().filter(|p| !p.closed).collect();
        if missed.is_empty() || missed.len() < settings.pinch_misses_min {
            continue;
        }
        let apart: Vec<f64> = missed
            .iter()
            .map(|p| p.robot_min_mm)
            .filter(|d| d.is_finite())
            .collect();
        let distance = match apart.is_empty() {
            true => "no command followed it".to_string(),
            false => format!(
                "robot {:.0} mm apart",
                apart.iter().sum::<f64>() / apart.len() as f64
            ),
        };
        said.push(Feedback {
            kind: FeedbackKind::PinchNotClosed,
            text: format!(
                "{finger} pinch did not close in {} of {} attempts ({distance})",
                missed.len(),
                attempts.len()
            ),
            times_s: missed.iter().map(|p| p.from_s).collect(),
            setting: "pinch_misses_min",
        });
    }
    said
}

fn wrist(review: &TrialReview, settings: &FeedbackSettings) -> Option<Feedback> {
    let share = review.arm.at_limit_share?;
    (share > 0.0 && share >= settings.wrist_at_limit_share).then(|| Feedback {
        kind: FeedbackKind::WristAtLimit,
        text: format!("wrist at its limit {:.0} % of the time", share * 100.0),
        times_s: Vec::new(),
        setting: "wrist_at_limit_share",
    })
}

fn stalls(review: &TrialReview, settings: &FeedbackSettings) -> Vec<Feedback> {
    let mut last_progress = 0.0;
    let mut said = Vec::new();
    for mark in &review.progress {
        match mark.value {
            Some(_) => last_progress = mark.t_s,
            None => {
                let stalled = mark.t_s - last_progress;
                if stalled >= settings.stall_before_drop_s {
                    said.push(Feedback {
                        kind: FeedbackKind::StallBeforeDrop,
                        text: format!(
                            "{stalled:.1} s without progress before the drop at {:.1} s",
                            mark.t_s
                        ),
                        times_s: vec![mark.t_s],
                        setting: "stall_before_drop_s",
                    });
                }
            }
        }
    }
    said
}

fn rejected(review: &TrialReview, settings: &FeedbackSettings) -> Option<Feedback> {
    let (total, reasons) = counted(&review.glove.rejected, settings.rejected_frames_min)?;
    Some(Feedback {
        kind: FeedbackKind::RejectedFrames,
        text: format!("{total} glove frames rejected ({reasons})"),
        times_s: review.glove.rejected.iter().map(|r| r.t_s).collect(),
        setting: "rejected_frames_min",
    })
}

/// The total of `counts` and their reasons (sorted, once each, comma-separated), when the
/// total reaches `min` (and is not 0).
fn counted(counts: &[CountAt], min: u64) -> Option<(u64, String)> {
    let total: u64 = counts.iter().map(|r| r.count).sum();
    if total == 0 || total < min {
        return None;
    }
    let mut reasons: Vec<&str> = counts
        .iter()
        .flat_map(|r| r.reasons.iter().map(String::as_str))
        .collect();
    reasons.sort_unstable();
    reasons.dedup();
    Some((total, reasons.join(", ")))
}

fn tracking(review: &TrialReview, settings: &FeedbackSettings) -> Vec<Feedback> {
    review
        .tracking_mean_deg
        .iter()
        .filter(|(_, e)| **e >= settings.tracking_error_deg)
        .map(|(digit, e)| Feedback {
            kind: FeedbackKind::TrackingError,
            text: format!("{digit} {e:.0}° off its commands on average"),
            times_s: Vec::new(),
            setting: "tracking_error_deg",
        })
        .collect()
}

fn refusals(review: &TrialReview, settings: &FeedbackSettings) -> Option<Feedback> {
    let (total, reasons) = counted(&review.arm.refusals, settings.arm_refusals_min)?;
    Some(Feedback {
        kind: FeedbackKind::ArmRefused,
        text: format!("arm refused {total}× ({reasons})"),
        times_s: review.arm.refusals.iter().map(|r| r.t_s).collect(),
        setting: "arm_refusals_min",
    })
}
