//! Time spans of the trial: the station's drive state, the holds on a stalled glove, the arm's
//! clutch and its refusals, from the status messages and the hand commands.

use serde::Serialize;

use crate::input::{GloveFrame, JointSample};
use crate::window::TrialWindow;

/// A span of one state, seconds into the trial.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StateSpan {
    /// `engaged`, `held` or `disengaged` (drive), `engaged` (clutch).
    pub state: String,
    /// Start, seconds.
    pub from_s: f64,
    /// End, seconds.
    pub to_s: f64,
}

/// The station held its last command: the glove sent no new frame for longer than the hold
/// timeout.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Hold {
    /// The first held command, seconds.
    pub from_s: f64,
    /// After the last held command (one command period on), seconds.
    pub to_s: f64,
    /// Held commands sent.
    pub commands: usize,
    /// The glove's last frame before the hold, seconds into the trial (None: none came).
    pub glove_gap_from_s: Option<f64>,
    /// The glove's gap around it: from the last frame before the hold to the next one after
    /// (to the trial's end when none came), milliseconds.
    pub glove_gap_ms: f64,
}

/// Runs of equal values of a status field as spans over the trial, each to the next status
/// (the last to the trial's end). `value` reads the field (None: skip that status).
pub fn status_spans(
    statuses: &[(i64, serde_json::Value)],
    window: &TrialWindow,
    value: impl Fn(&serde_json::Value) -> Option<String>,
) -> Vec<StateSpan> {
    let mut spans: Vec<StateSpan> = Vec::new();
    // The last status before the start says the state at the start.
    let first = statuses
        .partition_point(|(t, _)| *t < window.start_ns)
        .saturating_sub(1);
    for (t, status) in &statuses[first..] {
        if *t > window.end_ns {
            break;
        }
        let Some(state) = value(status) else { continue };
        let at = window.secs(*t).max(0.0);
        if let Some(last) = spans.last_mut() {
            last.to_s = at;
            if last.state == state {
                continue;
            }
        }
        spans.push(StateSpan {
            state,
            from_s: at,
            to_s: at,
        });
    }
    if let Some(last) = spans.last_mut() {
        last.to_s = window.duration_s();
    }
    spans.retain(|s| s.to_s > s.from_s);
    spans
}

/// The drive state (`state` of the status).
pub fn drive_spans(statuses: &[(i64, serde_json::Value)], window: &TrialWindow) -> Vec<StateSpan> {
    status_spans(statuses, window, |s| {
        s["state"].as_str().map(str::to_string)
    })
}

/// The arm clutch's engaged spans (`arm.engaged` of the status).
pub fn clutch_spans(statuses: &[(i64, serde_json::Value)], window: &TrialWindow) -> Vec<StateSpan> {
    let mut spans = status_spans(statuses, window, |s| {
        s["arm"]["engaged"]
            .as_bool()
            .map(|e| if e { "engaged" } else { "released" }.to_string())
    });
    spans.retain(|s| s.state == "engaged");
    spans
}

/// The holds: runs of held hand commands (stamped with their own send time) inside the trial,
/// with the glove's gap around each.
pub fn holds(commands: &[JointSample], frames: &[GloveFrame], window: &TrialWindow) -> Vec<Hold> {
    let inside: Vec<&JointSample> = commands
        .iter()
        .filter(|c| window.contains(c.t_ns))
        .collect();
    let period_ns = median_step_ns(&inside);
    let mut holds = Vec::new();
    let mut k = 0;
    while k < inside.len() {
        if inside[k].stamp_ns != inside[k].t_ns {
            k += 1;
            continue;
        }
        let end = inside[k..]
            .iter()
            .position(|c| c.stamp_ns != c.t_ns)
            .map_or(inside.len(), |n| k + n);
        let (first, last) = (inside[k].t_ns, inside[end - 1].t_ns);
        let before = frames
            .iter()
            .rev()
            .find(|f| f.t_ns <= first)
            .map(|f| f.t_ns);
        let after = frames
            .iter()
            .find(|f| f.t_ns > last)
            .map_or(window.end_ns, |f| f.t_ns);
        holds.push(Hold {
            from_s: window.secs(first),
            to_s: window.secs(last + period_ns).min(window.duration_s()),
            commands: end - k,
            glove_gap_from_s: before.map(|b| window.secs(b)),
            glove_gap_ms: before.map_or(f64::NAN, |b| (after - b) as f64 * 1e-6),
        });
        k = end;
    }
    holds
}

/// The median step between consecutive commands, nanoseconds (0 with fewer than two).
fn median_step_ns(commands: &[&JointSample]) -> i64 {
    let mut steps: Vec<i64> = commands.windows(2).map(|w| w[1].t_ns - w[0].t_ns).collect();
    steps.sort_unstable();
    steps.get(steps.len() / 2).copied().unwrap_or(0)
}
