//! Commanded against measured joint angles over a trial: how closely the hand followed its
//! commands (`pomdar tracking`).
//!
//! For one joint, with the commands `c_k` logged at times `s_k` and the measured angles `m_i`
//! at times `t_i` (radians; both on the log's clock, nanoseconds):
//!
//! ```text
//! command in force   c(t) = c_k for the last s_k ≤ t            (what the hand was told to hold)
//! compared samples   i with s_0 ≤ t_i                          (a command is in force)
//! error              e_i = |c(t_i) − m_i|                      reported in degrees
//! RMS, max           √(Σ e_i² / n),  max e_i                   over the compared samples
//! share over θ       Σ_i w_i [e_i > θ] / Σ_i w_i,  w_i = t_{i+1} − t_i
//!                    (a measured sample stands until the next one; the last has no duration)
//! lag                τ* = argmax_τ corr(m_i, c(t_i − τ)),  τ ∈ {0, 1, 2, …, max_lag} ms,
//!                    over the samples with s_0 ≤ t_i − max_lag (the same samples for every τ)
//! ```
//!
//! `corr` is Pearson's correlation. The lag is the shift that best aligns the measured angle
//! with the command, so it holds transport, the hand's sampling and its dynamics: a
//! first-order lag of time constant T on a slowly varying command shows as about T. A joint
//! whose command or measurement does not vary over those samples has no lag (nothing to
//! align), nor does one with fewer than [`MIN_LAG_SAMPLES`] of them.

use std::borrow::Cow;

use serde::Serialize;

use crate::plot::{TrackingChart, TrackingPanel};

/// Fewest samples the lag is estimated from.
pub const MIN_LAG_SAMPLES: usize = 10;

/// Nanoseconds per millisecond.
const NS_PER_MS: i64 = 1_000_000;

/// What the comparison looks for.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TrackingSettings {
    /// The largest lag tried, milliseconds (every whole millisecond from 0).
    pub max_lag_ms: u32,
    /// The error counted in [`JointTracking::over_threshold_share`], degrees.
    pub threshold_deg: f64,
}

impl Default for TrackingSettings {
    fn default() -> Self {
        TrackingSettings {
            max_lag_ms: 300,
            threshold_deg: 5.0,
        }
    }
}

/// One joint's two series: `(log time ns, angle rad)`, each in time order (sorted here if
/// not).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct JointTrack {
    /// The joint's name (the model's).
    pub joint: String,
    /// The commands, as sent.
    pub commanded: Vec<(i64, f64)>,
    /// The measured angles, as received.
    pub measured: Vec<(i64, f64)>,
}

/// How closely one joint followed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JointTracking {
    /// The joint's name.
    pub joint: String,
    /// Commands logged.
    pub commanded_samples: usize,
    /// Measured angles logged.
    pub measured_samples: usize,
    /// Measured angles with a command in force (the ones compared).
    pub compared_samples: usize,
    /// RMS of |command in force − measured|, degrees.
    pub rms_error_deg: Option<f64>,
    /// Largest |command in force − measured|, degrees.
    pub max_error_deg: Option<f64>,
    /// The shift that best aligns the measured angle with the command, milliseconds.
    pub lag_ms: Option<f64>,
    /// The correlation at that shift.
    pub lag_correlation: Option<f64>,
    /// Share of the compared time with an error over the threshold, 0–1.
    pub over_threshold_share: Option<f64>,
}

/// Every joint's tracking.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TrackingReport {
    /// What was looked for.
    pub settings: TrackingSettings,
    /// Per joint, in the order given.
    pub joints: Vec<JointTracking>,
}

impl TrackingReport {
    /// The joint with the largest RMS error.
    pub fn worst_joint(&self) -> Option<&JointTracking> {
        self.joints
            .iter()
            .filter(|j| j.rms_error_deg.is_some())
            .max_by(|a, b| {
                let rms = |j: &JointTracking| j.rms_error_deg.unwrap_or(0.0);
                rms(a).total_cmp(&rms(b))
            })
    }
}

/// Every joint of `tracks`, in order.
pub fn tracking_report(tracks: &[JointTrack], settings: TrackingSettings) -> TrackingReport {
    TrackingReport {
        settings,
        joints: tracks.iter().map(|t| track_joint(t, settings)).collect(),
    }
}

/// The figure of `tracks` and their `report` (same order): per joint a panel titled with its
/// name and RMS error, time in seconds from the earliest sample of any joint, angles in
/// degrees.
pub fn tracking_chart(
    tracks: &[JointTrack],
    report: &TrackingReport,
    title: &str,
    note: Option<String>,
) -> TrackingChart {
    let origin = tracks
        .iter()
        .flat_map(|t| t.commanded.iter().chain(&t.measured))
        .map(|(t, _)| *t)
        .min()
        .unwrap_or(0);
    let series = |points: &[(i64, f64)]| -> Vec<(f64, f64)> {
        in_time_order(points)
            .iter()
            .map(|(t, v)| ((t - origin) as f64 * 1e-9, v.to_degrees()))
            .collect()
    };
    let panels = tracks
        .iter()
        .zip(&report.joints)
        .map(|(track, joint)| TrackingPanel {
            title: match joint.rms_error_deg {
                Some(rms) => format!("{}  RMS {rms:.1} deg", track.joint),
                None => format!("{}  RMS -", track.joint),
            },
            commanded: series(&track.commanded),
            measured: series(&track.measured),
        })
        .collect();
    TrackingChart {
        title: title.to_string(),
        note,
        panels,
    }
}

/// `series` in time order, borrowed when it already is.
fn in_time_order(series: &[(i64, f64)]) -> Cow<'_, [(i64, f64)]> {
    if series.is_sorted_by_key(|(t, _)| *t) {
        Cow::Borrowed(series)
    } else {
        let mut sorted = series.to_vec();
        sorted.sort_by_key(|(t, _)| *t);
        Cow::Owned(sorted)
    }
}

/// The command in force at each time of `times` (ascending), `None` before the first: a sweep.
fn commands_in_force<'a>(
    commanded: &'a [(i64, f64)],
    times: impl Iterator<Item = i64> + 'a,
) -> impl Iterator<Item = Option<f64>> + 'a {
    let mut next = 0;
    times.map(move |t| {
        while next < commanded.len() && commanded[next].0 <= t {
            next += 1;
        }
        next.checked_sub(1).map(|k| commanded[k].1)
    })
}

/// How closely one joint followed (definitions in the module docs).
pub fn track_joint(track: &JointTrack, settings: TrackingSettings) -> JointTracking {
    let commanded = in_time_order(&track.commanded);
    let measured = in_time_order(&track.measured);
    let in_force: Vec<Option<f64>> =
        commands_in_force(&commanded, measured.iter().map(|(t, _)| *t)).collect();
    let mut errors_deg = Vec::with_capacity(measured.len());
    let (mut over_ns, mut total_ns) = (0_i64, 0_i64);
    for (i, (c, (t, m))) in in_force.iter().zip(measured.iter()).enumerate() {
        let Some(c) = c else { continue };
        let error = (c - m).abs().to_degrees();
        errors_deg.push(error);
        if let Some((next, _)) = measured.get(i + 1) {
            let w = next - t;
            total_ns += w;
            if error > settings.threshold_deg {
                over_ns += w;
            }
        }
    }
    let n = errors_deg.len();
    let rms = (n > 0).then(|| (errors_deg.iter().map(|e| e * e).sum::<f64>() / n as f64).sqrt());
    let max = errors_deg.iter().copied().reduce(f64::max);
    let lag = best_lag(&commanded, &measured, settings.max_lag_ms);
    JointTracking {
        joint: track.joint.clone(),
        commanded_samples: commanded.len(),
        measured_samples: measured.len(),
        compared_samples: n,
        rms_error_deg: rms,
        max_error_deg: max,
        lag_ms: lag.map(|(ms, _)| f64::from(ms)),
        lag_correlation: lag.map(|(_, r)| r),
        over_threshold_share: (total_ns > 0).then(|| over_ns as f64 / total_ns as f64),
    }
}

/// The lag in whole milliseconds with the highest correlation, and that correlation; the
/// smallest such lag on a tie.
fn best_lag(
    commanded: &[(i64, f64)],
    measured: &[(i64, f64)],
    max_lag_ms: u32,
) -> Option<(u32, f64)> {
    let first = commanded.first()?.0;
    let max_lag_ns = i64::from(max_lag_ms) * NS_PER_MS;
    let start = measured.partition_point(|(t, _)| *t - max_lag_ns < first);
    let samples = &measured[start..];
    if samples.len() < MIN_LAG_SAMPLES {
        return None;
    }
    let n = samples.len() as f64;
    let m_mean = samples.iter().map(|(_, m)| m).sum::<f64>() / n;
    let m_var = samples
        .iter()
        .map(|(_, m)| (m - m_mean).powi(2))
        .sum::<f64>();
    if m_var <= f64::EPSILON * n {
        return None;
    }
    let mut best: Option<(u32, f64)> = None;
    for lag_ms in 0..=max_lag_ms {
        let shift = i64::from(lag_ms) * NS_PER_MS;
        let shifted = commands_in_force(commanded, samples.iter().map(|(t, _)| t - shift));
        let (mut sum_c, mut sum_cc, mut sum_cm) = (0.0, 0.0, 0.0);
        for (c, (_, m)) in shifted.zip(samples) {
            // Every sample has a command in force at t − max_lag, so at t − shift.
            let c = c.unwrap_or_default();
            sum_c += c;
            sum_cc += c * c;
            sum_cm += c * (m - m_mean);
        }
        let c_var = sum_cc - sum_c * sum_c / n;
        if c_var <= f64::EPSILON * n {
            continue;
        }
        let r = sum_cm / (c_var * m_var).sqrt();
        if best.is_none_or(|(_, b)| r > b) {
            best = Some((lag_ms, r));
        }
    }
    best
}

#[cfg(test)]
#[path = "tracking_tests.rs"]
mod tests;
