//! The trial's signals: progress and drops from the trial events, the glove's rate, input age
//! and rejected frames, and the arm's refusals and time at its workspace limit.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::input::{GloveFrame, TrialInput};
use crate::window::TrialWindow;

/// The input age is sampled at this step, seconds.
pub const AGE_STEP_S: f64 = 0.02;

/// An arm target within this of a face of the workspace box is at its limit, metres.
pub const AT_LIMIT_M: f64 = 0.001;

/// A progress mark or a drop.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ProgressMark {
    /// When, seconds into the trial.
    pub t_s: f64,
    /// The progress in the task's unit; None for a drop.
    pub value: Option<f64>,
}

/// Progress marks and drops, in order.
pub fn progress_marks(input: &TrialInput, window: &TrialWindow) -> Vec<ProgressMark> {
    input
        .events
        .iter()
        .filter(|(t, _)| window.contains(*t))
        .filter_map(|(t, e)| match e["event"].as_str() {
            Some("progress") => Some(ProgressMark {
                t_s: window.secs(*t),
                value: e["value"].as_f64(),
            }),
            Some("drop") => Some(ProgressMark {
                t_s: window.secs(*t),
                value: None,
            }),
            _ => None,
        })
        .collect()
}

/// `(t s, value)` of a numeric status field inside the trial; null values are gaps (NaN).
pub fn status_series(
    statuses: &[(i64, serde_json::Value)],
    window: &TrialWindow,
    value: impl Fn(&serde_json::Value) -> Option<f64>,
) -> Vec<(f64, f64)> {
    statuses
        .iter()
        .filter(|(t, _)| window.contains(*t))
        .map(|(t, s)| (window.secs(*t), value(s).unwrap_or(f64::NAN)))
        .collect()
}

/// Times at which a cumulative status count grew, with the growth and the names that grew:
/// `count` reads `{name: total}` from a status.
pub fn count_increases(
    statuses: &[(i64, serde_json::Value)],
    window: &TrialWindow,
    count: impl Fn(&serde_json::Value) -> BTreeMap<String, u64>,
) -> Vec<(f64, u64, Vec<String>)> {
    let mut previous: Option<BTreeMap<String, u64>> = None;
    let mut increases = Vec::new();
    for (t, status) in statuses.iter().filter(|(t, _)| *t <= window.end_ns) {
        let now = count(status);
        if let Some(before) = &previous
            && window.contains(*t)
        {
            let grown: Vec<(String, u64)> = now
                .iter()
                .map(|(k, v)| (k.clone(), v.saturating_sub(*before.get(k).unwrap_or(&0))))
                .filter(|(_, d)| *d > 0)
                .collect();
            if !grown.is_empty() {
                let total = grown.iter().map(|(_, d)| d).sum();
                let names = grown.into_iter().map(|(k, _)| k).collect();
                increases.push((window.secs(*t), total, names));
            }
        }
        previous = Some(now);
    }
    increases
}

/// The numbers of an object of counts (`{"jump": 2, ...}`).
pub fn counts(value: &serde_json::Value) -> BTreeMap<String, u64> {
    value
        .as_object()
        .map(|o| {
            o.iter()
                .filter_map(|(k, v)| v.as_u64().map(|n| (k.clone(), n)))
                .collect()
        })
        .unwrap_or_default()
}

/// The age of the newest glove frame over the trial, every [`AGE_STEP_S`], milliseconds (NaN
/// before the first frame).
pub fn input_age_ms(frames: &[GloveFrame], window: &TrialWindow) -> Vec<(f64, f64)> {
    let steps = (window.duration_s() / AGE_STEP_S).ceil() as usize;
    let mut next = 0;
    let mut last: Option<i64> = None;
    (0..=steps)
        .map(|k| {
            let t_s = (k as f64 * AGE_STEP_S).min(window.duration_s());
            let t_ns = window.start_ns + (t_s * 1e9) as i64;
            while next < frames.len() && frames[next].t_ns <= t_ns {
                last = Some(frames[next].t_ns);
                next += 1;
            }
            (t_s, last.map_or(f64::NAN, |l| (t_ns - l) as f64 * 1e-6))
        })
        .collect()
}

/// The longest gap between consecutive glove frames inside the trial, milliseconds.
pub fn longest_glove_gap_ms(frames: &[GloveFrame], window: &TrialWindow) -> Option<f64> {
    frames
        .windows(2)
        .filter(|w| window.contains(w[1].t_ns))
        .map(|w| (w[1].t_ns - w[0].t_ns) as f64 * 1e-6)
        .max_by(f64::total_cmp)
}

/// The workspace box of the arm, robot base frame, metres.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WorkspaceLimits {
    /// Lower corner.
    pub min_m: [f64; 3],
    /// Upper corner.
    pub max_m: [f64; 3],
}

impl WorkspaceLimits {
    /// Whether `p` lies within [`AT_LIMIT_M`] of a face of the box.
    pub fn at_limit(&self, p: &[f64; 3]) -> bool {
        (0..3).any(|i| p[i] <= self.min_m[i] + AT_LIMIT_M || p[i] >= self.max_m[i] - AT_LIMIT_M)
    }
}

/// The share of the trial's arm targets at a workspace limit; None without targets or box.
pub fn at_limit_share(
    targets: &[(i64, [f64; 3])],
    window: &TrialWindow,
    limits: Option<&WorkspaceLimits>,
) -> Option<f64> {
    let limits = limits?;
    let inside: Vec<&[f64; 3]> = targets
        .iter()
        .filter(|(t, _)| window.contains(*t))
        .map(|(_, p)| p)
        .collect();
    (!inside.is_empty())
        .then(|| inside.iter().filter(|p| limits.at_limit(p)).count() as f64 / inside.len() as f64)
}
