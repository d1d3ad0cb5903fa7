//! Human pinches under two definitions, and per finger pair.
//!
//! - **Any frame** (the first definition): a frame where the human thumb tip is within
//!   [`super::PINCH_HUMAN_M`] of another fingertip (the nearest one counts).
//! - **Sustained**: only the frames of a run of consecutive frames pinching the same finger
//!   that holds for at least [`SUSTAINED_PINCH_MIN_FRAMES`] frames and at least
//!   [`SUSTAINED_PINCH_MIN_S`]. A person's pinch outlasts one frame of a 30 fps tracker; a
//!   one-frame dip of one tracked point is a tracker outlier, which the first definition
//!   counted as a pinch the robot should have closed. A run lasts from its first frame's time
//!   to its last frame's plus the recording's median frame step (each frame stands for one
//!   step of time): two frames at 30 fps last 67 ms, four at 100 Hz 40 ms. Frames pushed
//!   without a time are judged by their count alone.
//!
//! Per finger pair (thumb–index, –middle, –ring, –little): the frames under both definitions,
//! how many the robot closed (its thumb-tip to fingertip distance under
//! [`super::PINCH_CLOSED_M`]), and over the sustained frames the robot's distance (mean and
//! 95th percentile) beside the human's (mean).

use serde::{Deserialize, Serialize};

use super::stats::{mean, percentile};
use super::{FrameSample, PINCH_CLOSED_M};
use crate::finger::Finger;

/// Fewest consecutive frames of a sustained pinch.
pub const SUSTAINED_PINCH_MIN_FRAMES: usize = 2;

/// Shortest duration of a sustained pinch, seconds.
pub const SUSTAINED_PINCH_MIN_S: f64 = 0.040;

/// The human's pinches with one finger and how the robot followed them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PinchPair {
    /// The finger the thumb pinches: `index`, `middle`, `ring` or `little`.
    pub finger: String,
    /// Frames where the human pinches with it (any frame under 2 cm).
    pub frames: usize,
    /// Of those, frames where the robot's distance is under 15 mm.
    pub closed_frames: usize,
    /// Frames of sustained pinches with it.
    pub sustained_frames: usize,
    /// Of those, frames where the robot's distance is under 15 mm.
    pub sustained_closed_frames: usize,
    /// Mean robot thumb-tip to fingertip distance over the sustained frames, millimetres.
    pub robot_gap_mean_mm: Option<f64>,
    /// 95th percentile of the same, millimetres.
    pub robot_gap_p95_mm: Option<f64>,
    /// Mean human thumb-tip to fingertip distance over the sustained frames, millimetres.
    pub human_gap_mean_mm: Option<f64>,
}

/// Whether each frame is part of a sustained pinch.
pub(super) fn sustained_mask(samples: &[FrameSample]) -> Vec<bool> {
    let fingers: Vec<Option<Finger>> = samples.iter().map(|s| s.pinch.map(|p| p.finger)).collect();
    let times: Option<Vec<f64>> = samples.iter().map(|s| s.t_s).collect();
    let mut mask = vec![false; samples.len()];
    for run in sustained_pinch_runs(&fingers, times.as_deref()) {
        mask[run.frames].fill(true);
    }
    mask
}

/// A sustained pinch: the frames it spans and the finger.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PinchRun {
    /// Frame indices, end exclusive.
    pub frames: std::ops::Range<usize>,
    /// The finger the thumb pinches.
    pub finger: Finger,
}

/// The sustained pinches of a sequence of frames, given per frame the finger the human's
/// thumb pinches (None: no pinch) and, when known, every frame's time in seconds.
pub fn sustained_pinch_runs(fingers: &[Option<Finger>], times_s: Option<&[f64]>) -> Vec<PinchRun> {
    let step_s = times_s.and_then(median_step_s);
    let mut runs = Vec::new();
    let mut start = 0;
    while start < fingers.len() {
        let Some(finger) = fingers[start] else {
            start += 1;
            continue;
        };
        let end = fingers[start..]
            .iter()
            .position(|f| *f != Some(finger))
            .map_or(fingers.len(), |n| start + n);
        let span = times_s.map(|t| (t[start], t[end - 1]));
        if run_is_sustained(end - start, span, step_s) {
            runs.push(PinchRun {
                frames: start..end,
                finger,
            });
        }
        start = end;
    }
    runs
}

/// Whether a run of `frames` frames pinching one finger, first and last at `span` seconds,
/// holds long enough.
fn run_is_sustained(frames: usize, span: Option<(f64, f64)>, step_s: Option<f64>) -> bool {
    if frames < SUSTAINED_PINCH_MIN_FRAMES {
        return false;
    }
    match (span, step_s) {
        // A microsecond of slack for the rounding of stamps (four 10 ms steps are 40 ms).
        (Some((first, last)), Some(step)) => last - first + step >= SUSTAINED_PINCH_MIN_S - 1e-6,
        _ => true,
    }
}

/// The median step between consecutive frames' times.
fn median_step_s(times_s: &[f64]) -> Option<f64> {
    let mut steps: Vec<f64> = times_s.windows(2).map(|w| w[1] - w[0]).collect();
    if steps.is_empty() {
        return None;
    }
    steps.sort_by(f64::total_cmp);
    Some(steps[steps.len() / 2])
}

/// The per-pair figures, given which frames are sustained.
pub(super) fn pinch_pairs(samples: &[FrameSample], sustained: &[bool]) -> Vec<PinchPair> {
    Finger::OPPOSING
        .into_iter()
        .map(|finger| pinch_pair(samples, sustained, finger))
        .collect()
}

fn pinch_pair(samples: &[FrameSample], sustained: &[bool], finger: Finger) -> PinchPair {
    let with_finger = || {
        samples
            .iter()
            .zip(sustained)
            .filter_map(move |(s, &k)| s.pinch.filter(|p| p.finger == finger).map(|p| (p, k)))
    };
    let closed = |robot_m: Option<f64>| robot_m.is_some_and(|g| g < PINCH_CLOSED_M);
    let held: Vec<_> = with_finger().filter(|(_, k)| *k).map(|(p, _)| p).collect();
    let robot_mm: Vec<f64> = held
        .iter()
        .filter_map(|p| p.robot_m)
        .map(|g| g * 1e3)
        .collect();
    let human_mm: Vec<f64> = held.iter().map(|p| p.human_m * 1e3).collect();
    PinchPair {
        finger: finger.name().into(),
        frames: with_finger().count(),
        closed_frames: with_finger().filter(|(p, _)| closed(p.robot_m)).count(),
        sustained_frames: held.len(),
        sustained_closed_frames: held.iter().filter(|p| closed(p.robot_m)).count(),
        robot_gap_mean_mm: mean(&robot_mm),
        robot_gap_p95_mm: percentile(&robot_mm, 0.95),
        human_gap_mean_mm: mean(&human_mm),
    }
}
