//! How fast the human's thumb closes on each finger, and how much of the smoothing's pull
//! toward the previous command each digit keeps because of it.
//!
//! The smoothing's pull ([`crate::retarget_config::SmoothingConfig`]) holds a hand the robot
//! cannot reproduce steady, and gives way to fast motion by the key points' low-passed speed.
//! That speed rises over several frames, so the first frames of a quick pinch were followed
//! late: on a tracker whose thumb the robot never reproduces, the pull stayed on while the
//! human's thumb–little distance fell 129 → 103 → 86 → 59 → 35 mm over four frames, the robot
//! reached 45 mm on the frame the human reached 19 and closed one frame after. A digit now keeps
//! less of the pull while the thumb closes on it fast (and the thumb while it closes on any):
//! the approach is followed as it happens, and nothing else loses its smoothing.
//!
//! The closing speed is the frame-to-frame fall of the raw thumb–finger distance over one
//! frame of [`FRAME_DT_S`] (as the input filter counts frames), counted only below
//! `approach_range_m`: far apart, the distance says nothing about a pinch. A gap longer than
//! [`GAP_RESET_S`] forgets the previous distances.

use crate::one_euro::{FRAME_DT_S, GAP_RESET_S};

/// The previous frame's thumb–finger distances.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PinchApproach {
    previous_m: Option<[f64; 4]>,
}

impl PinchApproach {
    /// Forget the history.
    pub fn reset(&mut self) {
        self.previous_m = None;
    }

    /// Take this frame's distances (index, middle, ring, little; metres), `dt_s` after the
    /// previous frame, and return per digit (thumb first) the share of the pull it keeps:
    /// `1 / (1 + (v / speed_m_s)²)` with `v` the speed its pinch closes at (the thumb: the
    /// fastest of its four). `speed_m_s` 0 keeps the whole pull.
    pub fn pull_shares(
        &mut self,
        distances_m: [f64; 4],
        dt_s: f64,
        range_m: f64,
        speed_m_s: f64,
    ) -> [f64; 5] {
        let previous = if dt_s > GAP_RESET_S {
            None
        } else {
            self.previous_m
        };
        self.previous_m = Some(distances_m);
        let (Some(previous), true) = (previous, speed_m_s > 0.0) else {
            return [1.0; 5];
        };
        let closing: [f64; 4] = std::array::from_fn(|i| {
            let now = distances_m[i];
            if now < range_m {
                ((previous[i] - now) / FRAME_DT_S).max(0.0)
            } else {
                0.0
            }
        });
        let share = |v: f64| 1.0 / (1.0 + (v / speed_m_s).powi(2));
        let thumb = closing.iter().copied().fold(0.0, f64::max);
        std::array::from_fn(|digit| match digit {
            0 => share(thumb),
            finger => share(closing[finger - 1]),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const RANGE: f64 = 0.06;
    const SPEED: f64 = 1.0;

    #[test]
    fn the_first_frame_and_a_still_hand_keep_the_whole_pull() {
        let mut approach = PinchApproach::default();
        let d = [0.05, 0.05, 0.05, 0.05];
        assert_eq!(approach.pull_shares(d, 0.033, RANGE, SPEED), [1.0; 5]);
        assert_eq!(approach.pull_shares(d, 0.033, RANGE, SPEED), [1.0; 5]);
    }

    #[test]
    fn a_fast_pinch_frees_its_two_digits_only() {
        let mut approach = PinchApproach::default();
        approach.pull_shares([0.06, 0.05, 0.05, 0.05], 0.033, RANGE, SPEED);
        // Index closes 30 mm in one frame: 0.9 m/s.
        let shares = approach.pull_shares([0.03, 0.05, 0.05, 0.05], 0.033, RANGE, SPEED);
        let expected = 1.0 / (1.0 + 0.9_f64.powi(2));
        assert!((shares[0] - expected).abs() < 1e-9, "{shares:?}");
        assert!((shares[1] - expected).abs() < 1e-9, "{shares:?}");
        assert_eq!(&shares[2..], &[1.0; 3]);
    }

    #[test]
    fn opening_far_apart_or_after_a_gap_keeps_the_pull() {
        let mut approach = PinchApproach::default();
        approach.pull_shares([0.02, 0.20, 0.05, 0.05], 0.033, RANGE, SPEED);
        // Index opens, middle closes but stays beyond the range.
        let shares = approach.pull_shares([0.05, 0.10, 0.05, 0.05], 0.033, RANGE, SPEED);
        assert_eq!(shares, [1.0; 5]);
        let after_gap = approach.pull_shares([0.01, 0.10, 0.05, 0.05], 0.5, RANGE, SPEED);
        assert_eq!(after_gap, [1.0; 5]);
        assert_eq!(
            approach.pull_shares([0.01, 0.10, 0.05, 0.05], 0.033, RANGE, 0.0),
            [1.0; 5]
        );
    }
}
