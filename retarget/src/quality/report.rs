//! The metrics of [`super`] from the recorded frames.

use serde::{Deserialize, Serialize};

use super::pinch_runs::{PinchPair, pinch_pairs, sustained_mask};
use super::scale_free::{OwnScale, own_scale};
use super::stats::{mean, percentile};
use super::{FrameSample, PINCH_CLOSED_M, flexion};
use crate::finger::Finger;

/// Quality metrics over a recording, overall.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QualityReport {
    /// Frames measured.
    pub frames: usize,
    /// The least-squares global scale `s*` of the human fingertip vectors.
    pub tip_scale: f64,
    /// Mean of `‖r − s*·h‖` over frames and digits, millimetres.
    pub tip_error_mean_mm: f64,
    /// 95th percentile of the same, millimetres.
    pub tip_error_p95_mm: f64,
    /// Frames where the human pinches (thumb tip within 2 cm of another fingertip).
    pub pinch_frames: usize,
    /// Mean robot thumb-tip to pinched fingertip distance over those frames, millimetres.
    pub pinch_gap_mean_mm: Option<f64>,
    /// Share of pinch frames where that distance is under 15 mm, percent.
    pub pinches_closed_pct: Option<f64>,
    /// Pinch frames where that distance is under 15 mm.
    #[serde(default)]
    pub pinch_closed_frames: usize,
    /// Frames of sustained human pinches (runs of at least 2 frames and 40 ms,
    /// `quality::pinch_runs`); a tracker's one-frame outlier is not one.
    #[serde(default)]
    pub sustained_pinch_frames: usize,
    /// Of those, frames where the robot's distance is under 15 mm.
    #[serde(default)]
    pub sustained_pinch_closed_frames: usize,
    /// Their share, percent.
    #[serde(default)]
    pub sustained_pinches_closed_pct: Option<f64>,
    /// Per finger pair (thumb–index, –middle, –ring, –little), under both definitions.
    #[serde(default)]
    pub pinch_pairs: Vec<PinchPair>,
    /// Mean of `‖r − s_i·h‖` over digits and frames, each digit `i` with its own least-squares
    /// scale `s_i` ([`DigitQuality::tip_own_scale`]), millimetres; `None` without a finite
    /// command.
    pub tip_error_own_scale_mean_mm: Option<f64>,
    /// 95th percentile of the same, millimetres.
    pub tip_error_own_scale_p95_mm: Option<f64>,
    /// Mean of the digits' defined [`DigitQuality::flexion_correlation`]s.
    pub flexion_correlation_mean: Option<f64>,
    /// The shift `k` (frames, within ±[`super::LAG_MAX_FRAMES`]) maximising the mean over
    /// digits of the correlation of human flexion at `t` with robot flexion at `t + k`;
    /// positive: the robot is behind the human. `None` when no digit's correlation is defined.
    pub flexion_lag_frames: Option<i64>,
    /// The same in seconds (mean of `t_{t+k} − t_t` over the paired frames), when every frame
    /// was pushed with its time ([`super::QualityRecorder::push_at`]).
    pub flexion_lag_s: Option<f64>,
    /// The mean correlation at that shift.
    pub flexion_lag_correlation: Option<f64>,
    /// Mean absolute third difference of each joint per frame, radians.
    pub jerk_rad: f64,
    /// Largest per-frame change of any joint, radians.
    pub max_step_rad: f64,
    /// Frames with a joint outside its limits (beyond 1e-9 rad) or not finite.
    pub limit_violation_frames: usize,
    /// The same per digit (and "wrist" for joints every chain shares).
    pub per_digit: Vec<DigitQuality>,
}

/// Quality metrics of one digit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DigitQuality {
    /// `thumb`, `index`, `middle`, `ring`, `little`, or `wrist`.
    pub digit: String,
    /// Mean fingertip error, millimetres (`None` for the wrist).
    pub tip_error_mean_mm: Option<f64>,
    /// 95th percentile fingertip error, millimetres (`None` for the wrist).
    pub tip_error_p95_mm: Option<f64>,
    /// Pinch frames with this finger (none for the thumb and the wrist).
    pub pinch_frames: usize,
    /// Share of them closed, percent.
    pub pinches_closed_pct: Option<f64>,
    /// Number of them closed (robot gap under 15 mm).
    #[serde(default)]
    pub pinch_closed_frames: usize,
    /// This digit's own least-squares scale `s_i = Σ_t r·h / Σ_t h·h` (`None` for the wrist).
    pub tip_own_scale: Option<f64>,
    /// Mean of `‖r − s_i·h‖`, millimetres (`None` for the wrist).
    pub tip_error_own_scale_mean_mm: Option<f64>,
    /// 95th percentile of the same, millimetres (`None` for the wrist).
    pub tip_error_own_scale_p95_mm: Option<f64>,
    /// Pearson correlation over frames of human and robot flexion (palm-frame origin to tip
    /// distance); `None` for the wrist, with fewer than 3 frames, or when either side is
    /// constant (a finger the robot holds still).
    pub flexion_correlation: Option<f64>,
    /// Mean absolute third difference of this digit's joints, radians.
    pub jerk_rad: Option<f64>,
    /// Largest per-frame change of this digit's joints, radians.
    pub max_step_rad: Option<f64>,
}

/// Jerk terms and steps of the degrees of freedom selected by `keep`.
fn motion(samples: &[FrameSample], keep: impl Fn(usize) -> bool) -> (Vec<f64>, Vec<f64>) {
    let (mut jerks, mut steps) = (Vec::new(), Vec::new());
    let dofs = samples.first().map_or(0, |s| s.q.len());
    for j in (0..dofs).filter(|&j| keep(j)) {
        let q: Vec<f64> = samples.iter().map(|s| s.q[j]).collect();
        steps.extend(
            q.windows(2)
                .map(|w| (w[1] - w[0]).abs())
                .filter(|v| v.is_finite()),
        );
        jerks.extend(
            q.windows(4)
                .map(|w| (w[3] - 3.0 * w[2] + 3.0 * w[1] - w[0]).abs())
                .filter(|v| v.is_finite()),
        );
    }
    (jerks, steps)
}

/// Pinch frames, closed frames, the finite robot gaps and the closed share of some pinches.
struct PinchStats {
    frames: usize,
    closed: usize,
    gaps: Vec<f64>,
    closed_pct: Option<f64>,
}

fn pinch_stats(gaps: impl Iterator<Item = Option<f64>>) -> PinchStats {
    let gaps: Vec<Option<f64>> = gaps.collect();
    let closed = gaps
        .iter()
        .filter(|g| g.is_some_and(|g| g < PINCH_CLOSED_M))
        .count();
    PinchStats {
        frames: gaps.len(),
        closed,
        closed_pct: (!gaps.is_empty()).then(|| 100.0 * closed as f64 / gaps.len() as f64),
        gaps: gaps.into_iter().flatten().collect(),
    }
}

fn max(values: &[f64]) -> Option<f64> {
    values.iter().copied().reduce(f64::max)
}

/// The global scale `s*` and each digit's errors after it, millimetres.
pub(super) fn global_scale(samples: &[FrameSample]) -> (f64, [Vec<f64>; 5]) {
    // Least squares of r ≈ s·h over every frame with a finite command.
    let (mut rh, mut hh) = (0.0, 0.0);
    for s in samples {
        if let Some(robot) = &s.robot_tips {
            for (r, h) in robot.iter().zip(&s.human_tips) {
                rh += r.dot(h);
                hh += h.dot(h);
            }
        }
    }
    let scale = if hh > 0.0 { rh / hh } else { 1.0 };
    let mut errors: [Vec<f64>; 5] = Default::default();
    for s in samples {
        if let Some(robot) = &s.robot_tips {
            for (i, (r, h)) in robot.iter().zip(&s.human_tips).enumerate() {
                errors[i].push((r - h * scale).norm() * 1e3);
            }
        }
    }
    (scale, errors)
}

/// One digit's metrics, given its errors after the global scale, its own scale and its
/// flexion correlation.
fn digit_quality(
    samples: &[FrameSample],
    dof_digit: &[Option<Finger>],
    finger: Finger,
    errors: &[f64],
    own: &OwnScale,
    flexion_correlation: Option<f64>,
) -> DigitQuality {
    let pinches = pinch_stats(
        samples
            .iter()
            .filter_map(|s| s.pinch)
            .filter(|p| p.finger == finger)
            .map(|p| p.robot_m),
    );
    let (jerks, steps) = motion(samples, |j| dof_digit[j] == Some(finger));
    DigitQuality {
        digit: finger.name().into(),
        tip_error_mean_mm: mean(errors),
        tip_error_p95_mm: percentile(errors, 0.95),
        pinch_frames: pinches.frames,
        pinches_closed_pct: pinches.closed_pct,
        pinch_closed_frames: pinches.closed,
        tip_own_scale: own.scale,
        tip_error_own_scale_mean_mm: mean(&own.errors_mm),
        tip_error_own_scale_p95_mm: percentile(&own.errors_mm, 0.95),
        flexion_correlation,
        jerk_rad: mean(&jerks),
        max_step_rad: max(&steps),
    }
}

/// The joints every chain shares, as a digit row without tip or pinch metrics.
fn wrist_quality(samples: &[FrameSample], dof_digit: &[Option<Finger>]) -> DigitQuality {
    let (jerks, steps) = motion(samples, |j| dof_digit[j].is_none());
    DigitQuality {
        digit: "wrist".into(),
        tip_error_mean_mm: None,
        tip_error_p95_mm: None,
        pinch_frames: 0,
        pinches_closed_pct: None,
        pinch_closed_frames: 0,
        tip_own_scale: None,
        tip_error_own_scale_mean_mm: None,
        tip_error_own_scale_p95_mm: None,
        flexion_correlation: None,
        jerk_rad: mean(&jerks),
        max_step_rad: max(&steps),
    }
}

pub(super) fn compute(samples: &[FrameSample], dof_digit: &[Option<Finger>]) -> QualityReport {
    let (scale, errors) = global_scale(samples);
    let all_errors: Vec<f64> = errors.iter().flatten().copied().collect();
    let own = Finger::ALL.map(|f| own_scale(samples, f));
    let own_errors: Vec<f64> = own.iter().flat_map(|o| &o.errors_mm).copied().collect();
    let flexion = flexion::compute(samples);
    let pinches = pinch_stats(samples.iter().filter_map(|s| s.pinch.map(|p| p.robot_m)));
    let sustained = sustained_mask(samples);
    let held = pinch_stats(
        samples
            .iter()
            .zip(&sustained)
            .filter(|(_, k)| **k)
            .filter_map(|(s, _)| s.pinch.map(|p| p.robot_m)),
    );
    let (jerks, steps) = motion(samples, |_| true);
    let mut per_digit: Vec<DigitQuality> = Finger::ALL
        .into_iter()
        .map(|f| {
            let i = f.index();
            let correlation = flexion.per_digit[i];
            digit_quality(samples, dof_digit, f, &errors[i], &own[i], correlation)
        })
        .collect();
    if dof_digit.iter().any(Option::is_none) {
        per_digit.push(wrist_quality(samples, dof_digit));
    }
    QualityReport {
        frames: samples.len(),
        tip_scale: scale,
        tip_error_mean_mm: mean(&all_errors).unwrap_or(0.0),
        tip_error_p95_mm: percentile(&all_errors, 0.95).unwrap_or(0.0),
        pinch_frames: pinches.frames,
        pinch_gap_mean_mm: mean(&pinches.gaps).map(|g| g * 1e3),
        pinches_closed_pct: pinches.closed_pct,
        pinch_closed_frames: pinches.closed,
        sustained_pinch_frames: held.frames,
        sustained_pinch_closed_frames: held.closed,
        sustained_pinches_closed_pct: held.closed_pct,
        pinch_pairs: pinch_pairs(samples, &sustained),
        tip_error_own_scale_mean_mm: mean(&own_errors),
        tip_error_own_scale_p95_mm: percentile(&own_errors, 0.95),
        flexion_correlation_mean: flexion.mean,
        flexion_lag_frames: flexion.lag.map(|l| l.frames),
        flexion_lag_s: flexion.lag.and_then(|l| l.seconds),
        flexion_lag_correlation: flexion.lag.map(|l| l.correlation),
        jerk_rad: mean(&jerks).unwrap_or(0.0),
        max_step_rad: max(&steps).unwrap_or(0.0),
        limit_violation_frames: samples.iter().filter(|s| s.violation).count(),
        per_digit,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentile_is_nearest_rank() {
        let v: Vec<f64> = (1..=20).map(f64::from).collect();
        assert_eq!(percentile(&v, 0.95), Some(19.0));
        assert_eq!(percentile(&v, 1.0), Some(20.0));
        assert_eq!(percentile(&v, 0.0), Some(1.0));
        assert_eq!(percentile(&[], 0.5), None);
    }

    #[test]
    fn pinch_stats_count_closed_frames_and_keep_unmeasured_ones_open() {
        let gaps = [Some(0.01), Some(0.02), None, Some(0.0149)];
        let stats = pinch_stats(gaps.iter().copied());
        assert_eq!((stats.frames, stats.closed), (4, 2));
        assert_eq!(stats.closed_pct, Some(50.0));
        assert_eq!(stats.gaps, [0.01, 0.02, 0.0149]);
    }
}
