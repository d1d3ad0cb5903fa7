//! Segments: consecutive 1.5 s windows of a trial, each summarised by the mean (posture)
//! and standard deviation (movement) of every palm-frame coordinate.

use retarget::KeypointLayout;

use crate::motion::TrialMotion;
use crate::palm_coordinates::palm_track;
use crate::settings::StrategySettings;
use crate::skip::SkipReason;

/// Slack on window boundaries, seconds, so a trial of exactly four segments is not cut to
/// three by rounding in its frame times.
const BOUNDARY_SLACK_S: f64 = 1e-9;

/// One segment's summary.
#[derive(Debug, Clone, PartialEq)]
pub struct Segment {
    /// Window start on the trial's clock, seconds (the first frame's time plus a whole
    /// number of segment lengths).
    pub start_s: f64,
    /// Usable frames in the window.
    pub frames: usize,
    /// Per-coordinate means, then per-coordinate standard deviations (see
    /// [`feature_names`]), in hand lengths.
    pub features: Vec<f64>,
}

/// A trial's segments and what was left out on the way.
#[derive(Debug, Clone, PartialEq)]
pub struct TrialSegments {
    /// The kept segments in time order.
    pub segments: Vec<Segment>,
    /// Frames left out because their palm frame collapsed.
    pub collapsed_frames: usize,
    /// Complete windows dropped for having too few usable frames.
    pub dropped_windows: usize,
    /// The hand length the coordinates were divided by, metres.
    pub hand_length_m: f64,
}

/// The feature names of `layout`, in feature order: `{point}_{x|y|z}_mean` for every point,
/// then `{point}_{x|y|z}_std`.
pub fn feature_names(layout: KeypointLayout) -> Vec<String> {
    let coords: Vec<String> = (0..layout.len())
        .flat_map(|i| {
            let name = layout.point_name(i).unwrap_or_else(|| format!("point{i}"));
            ["x", "y", "z"].map(|axis| format!("{name}_{axis}"))
        })
        .collect();
    let means = coords.iter().map(|c| format!("{c}_mean"));
    let stds = coords.iter().map(|c| format!("{c}_std"));
    means.chain(stds).collect()
}

/// The segments of `trial`, or why it has none.
pub fn trial_segments(
    trial: &TrialMotion,
    settings: &StrategySettings,
) -> Result<TrialSegments, SkipReason> {
    let track = palm_track(trial)?;
    let seg = settings.segment_s;
    let windows = ((track.duration_s + BOUNDARY_SLACK_S) / seg).floor() as usize;
    if windows == 0 {
        return Err(SkipReason::TooShort {
            duration_s: track.duration_s,
            segment_s: seg,
        });
    }
    let mut members: Vec<Vec<&[f64]>> = vec![Vec::new(); windows];
    for (t_s, coords) in track.times_s.iter().zip(&track.coords) {
        let k = ((t_s - track.start_s + BOUNDARY_SLACK_S) / seg).floor() as usize;
        if let Some(window) = members.get_mut(k) {
            window.push(coords);
        }
    }
    let most = members.iter().map(Vec::len).max().unwrap_or(0);
    let segments: Vec<Segment> = (members.iter().enumerate())
        .filter(|(_, frames)| frames.len() >= settings.min_frames_per_segment)
        .map(|(k, frames)| Segment {
            start_s: track.start_s + k as f64 * seg,
            frames: frames.len(),
            features: summarise(frames),
        })
        .collect();
    if segments.is_empty() {
        return Err(SkipReason::TooFewFrames {
            windows,
            segment_s: seg,
            min_frames: settings.min_frames_per_segment,
            most,
        });
    }
    Ok(TrialSegments {
        dropped_windows: windows - segments.len(),
        segments,
        collapsed_frames: track.collapsed_frames,
        hand_length_m: track.hand_length_m,
    })
}

/// Per-coordinate mean, then per-coordinate population standard deviation, of `frames`
/// (not empty, all of one length).
fn summarise(frames: &[&[f64]]) -> Vec<f64> {
    let n = frames.len() as f64;
    let width = frames.first().map_or(0, |f| f.len());
    let mut mean = vec![0.0; width];
    for frame in frames {
        mean.iter_mut().zip(*frame).for_each(|(m, v)| *m += v / n);
    }
    let mut var = vec![0.0; width];
    for frame in frames {
        (var.iter_mut().zip(*frame).zip(&mean)).for_each(|((s, v), m)| *s += (v - m).powi(2) / n);
    }
    mean.extend(var.into_iter().map(f64::sqrt));
    mean
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn summary_is_mean_then_standard_deviation() {
        let frames: [&[f64]; 3] = [&[1.0, 0.0], &[2.0, 0.0], &[3.0, 0.0]];
        let f = summarise(&frames);
        assert_eq!(f.len(), 4);
        assert!((f[0] - 2.0).abs() < 1e-15 && f[1] == 0.0);
        assert!((f[2] - (2.0_f64 / 3.0).sqrt()).abs() < 1e-15 && f[3] == 0.0);
    }

    #[test]
    fn names_follow_the_feature_order() {
        let names = feature_names(KeypointLayout::Lab22);
        assert_eq!(names.len(), 22 * 6);
        assert_eq!(names[0], "forearm_x_mean");
        assert_eq!(names[3 * 9 + 2], "index_tip_z_mean");
        assert_eq!(names[66], "forearm_x_std");
    }
}
