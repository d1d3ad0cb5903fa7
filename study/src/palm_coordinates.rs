//! Keypoints in the palm frame, in hand lengths: what is left of a frame once the hand's
//! place, orientation and size are taken out.

use retarget::{Finger, PalmFrame};

use crate::motion::TrialMotion;
use crate::skip::SkipReason;

/// A checked trial's usable frames in palm coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct PalmTrack {
    /// Times of the usable frames, seconds.
    pub times_s: Vec<f64>,
    /// Per usable frame: every keypoint's palm-frame x, y, z divided by the hand length
    /// (point-major: point 0 x, y, z, point 1 x, …).
    pub coords: Vec<Vec<f64>>,
    /// First frame time of the trial (usable or not), seconds.
    pub start_s: f64,
    /// The time the trial covers: last − first frame time + the median frame interval.
    pub duration_s: f64,
    /// Frames left out because their palm frame collapsed.
    pub collapsed_frames: usize,
    /// The hand length used (metres): median over the usable frames of the mean wrist to
    /// finger-base distance (index, middle, ring, little).
    pub hand_length_m: f64,
}

/// The palm track of `trial`, or why the trial cannot give one.
pub fn palm_track(trial: &TrialMotion) -> Result<PalmTrack, SkipReason> {
    trial.check()?;
    let layout = trial.layout;
    let mut times_s = Vec::with_capacity(trial.frames.len());
    let mut local = Vec::with_capacity(trial.frames.len());
    let mut lengths = Vec::with_capacity(trial.frames.len());
    let mut first_collapse = None;
    for frame in &trial.frames {
        let landmarks = layout.palm_landmarks(&frame.points);
        match PalmFrame::from_landmarks(&landmarks) {
            Ok(palm) => {
                let coords: Vec<f64> = (frame.points.iter())
                    .map(|p| palm.point_to_palm(p))
                    .flat_map(|v| [v.x, v.y, v.z])
                    .collect();
                let fingers = [Finger::Index, Finger::Middle, Finger::Ring, Finger::Little];
                let length = fingers
                    .iter()
                    .map(|f| (landmarks.bases[f.index()] - landmarks.wrist).norm())
                    .sum::<f64>()
                    / fingers.len() as f64;
                times_s.push(frame.t_s);
                local.push(coords);
                lengths.push(length);
            }
            Err(err) => {
                first_collapse.get_or_insert_with(|| err.to_string());
            }
        }
    }
    let collapsed_frames = trial.frames.len() - local.len();
    let Some(hand_length_m) = median(&mut lengths) else {
        return Err(SkipReason::AllPalmsCollapsed {
            frames: trial.frames.len(),
            first: first_collapse.unwrap_or_default(),
        });
    };
    for coords in &mut local {
        coords.iter_mut().for_each(|v| *v /= hand_length_m);
    }
    let all_times: Vec<f64> = trial.frames.iter().map(|f| f.t_s).collect();
    let mut intervals: Vec<f64> = all_times.windows(2).map(|w| w[1] - w[0]).collect();
    let interval_s = median(&mut intervals).unwrap_or(0.0);
    let start_s = all_times[0];
    Ok(PalmTrack {
        times_s,
        coords: local,
        start_s,
        duration_s: all_times[all_times.len() - 1] - start_s + interval_s,
        collapsed_frames,
        hand_length_m,
    })
}

/// Median of finite `values` (reordered), `None` when empty.
fn median(values: &mut [f64]) -> Option<f64> {
    if values.is_empty() {
        return None;
    }
    values.sort_by(f64::total_cmp);
    let mid = values.len() / 2;
    Some(if values.len().is_multiple_of(2) {
        0.5 * (values[mid - 1] + values[mid])
    } else {
        values[mid]
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(&mut []), None);
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), Some(2.0));
        assert_eq!(median(&mut [4.0, 1.0, 3.0, 2.0]), Some(2.5));
    }
}
