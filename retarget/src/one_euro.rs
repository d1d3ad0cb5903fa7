//! Speed-adaptive low-pass filtering of the human input (the 1€ filter of Casiez, Roussel and
//! Vogel, CHI 2012), applied to the palm-frame key points before the energy sees them.
//!
//! Each point is smoothed by a first-order low-pass whose cutoff rises with the point's speed:
//! `f_c = min_cutoff + gain · |v̂|`, `v̂` the point's velocity low-passed at
//! `derivative_cutoff`. A hand at rest (where glove noise is all there is) is smoothed
//! hard; a finger closing on a pinch passes almost unfiltered, so fast motion gains no lag.
//! The smoothing factor of a step `dt` is `α = 1 / (1 + 1 / (2π f_c dt))`.
//!
//! **The filter counts frames, not seconds.** Every frame is one step of [`FRAME_DT_S`] (the
//! cutoffs and speeds are quoted at that frame interval, 30 frames per second), whatever the
//! measured time between frames: jitter of the glove stream or the network never changes a
//! command, and a log re-simulated or replayed frame by frame gives the live commands exactly.
//! A gap longer than [`GAP_RESET_S`] starts the filter afresh on the new frame (nothing stale
//! is smoothed in).

use std::f64::consts::TAU;

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use crate::human_key_vectors::HumanKeyVectors;

/// The time step of one frame, seconds: the filter's cutoffs and speeds are per this interval.
pub const FRAME_DT_S: f64 = 1.0 / 30.0;

/// A gap between frames longer than this (seconds) restarts the filter on the new frame.
pub const GAP_RESET_S: f64 = 0.25;

/// Settings of the input filter (`[input_filter]` in the retargeting configuration).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct InputFilterConfig {
    /// Cutoff at rest, Hz (at [`FRAME_DT_S`] per frame); 0 turns the filter off.
    pub min_cutoff_hz: f64,
    /// Cutoff added per m/s of a point's speed (its displacement per frame over
    /// [`FRAME_DT_S`]), Hz·s/m.
    pub speed_gain_hz_s_per_m: f64,
    /// Cutoff of the speed estimate, Hz.
    pub derivative_cutoff_hz: f64,
}

impl Default for InputFilterConfig {
    fn default() -> Self {
        InputFilterConfig {
            min_cutoff_hz: 1.0,
            speed_gain_hz_s_per_m: 30.0,
            derivative_cutoff_hz: 1.0,
        }
    }
}

impl InputFilterConfig {
    /// Whether the filter runs.
    pub fn enabled(&self) -> bool {
        self.min_cutoff_hz > 0.0
    }
}

/// The smoothing factor of a first-order low-pass with cutoff `cutoff_hz` over `dt_s`.
pub fn smoothing_factor(cutoff_hz: f64, dt_s: f64) -> f64 {
    let rate = TAU * cutoff_hz * dt_s;
    rate / (1.0 + rate)
}

/// One 1€ filter over a point (or a scalar, as a point with zero y and z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OneEuroPoint {
    value: Vector3<f64>,
    speed: Vector3<f64>,
}

impl OneEuroPoint {
    /// A filter at rest at `value`.
    pub fn at(value: Vector3<f64>) -> OneEuroPoint {
        OneEuroPoint {
            value,
            speed: Vector3::zeros(),
        }
    }

    /// Filter `x`, measured `dt_s` after the previous sample; returns the filtered value.
    pub fn update(&mut self, x: Vector3<f64>, dt_s: f64, c: &InputFilterConfig) -> Vector3<f64> {
        let raw_speed = (x - self.value) / dt_s;
        let a_d = smoothing_factor(c.derivative_cutoff_hz, dt_s);
        self.speed += a_d * (raw_speed - self.speed);
        let cutoff = c.min_cutoff_hz + c.speed_gain_hz_s_per_m * self.speed.norm();
        let a = smoothing_factor(cutoff, dt_s);
        self.value += a * (x - self.value);
        self.value
    }

    /// The low-passed speed, m/s (or units/s).
    pub fn speed(&self) -> f64 {
        self.speed.norm()
    }
}

/// The 1€ filters of one hand's key points: fingertips and digit mid points, each filtered on
/// its own. The thumb-to-finger pinch distances pass unfiltered: a pinch engages on the frame
/// the glove closes it.
#[derive(Debug, Clone, PartialEq)]
pub struct KeyPointFilter {
    config: InputFilterConfig,
    state: Option<FilterState>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct FilterState {
    tips: [OneEuroPoint; 5],
    mids: [OneEuroPoint; 5],
}

impl KeyPointFilter {
    /// A filter with no history (the next frame passes through unchanged).
    pub fn new(config: InputFilterConfig) -> KeyPointFilter {
        KeyPointFilter {
            config,
            state: None,
        }
    }

    /// Forget the history.
    pub fn reset(&mut self) {
        self.state = None;
    }

    /// The fastest key point's low-passed speed, m/s (0 before the second frame).
    pub fn fastest_speed_m_s(&self) -> f64 {
        self.state.as_ref().map_or(0.0, |s| {
            s.tips
                .iter()
                .chain(&s.mids)
                .map(OneEuroPoint::speed)
                .fold(0.0, f64::max)
        })
    }

    /// Filter one frame's key vectors, `dt_s` after the previous frame (only a gap longer than
    /// [`GAP_RESET_S`] matters: it restarts the filter).
    pub fn apply(&mut self, human: &HumanKeyVectors, dt_s: f64) -> HumanKeyVectors {
        if dt_s > GAP_RESET_S {
            self.state = None;
        }
        let dt_s = FRAME_DT_S;
        let Some(state) = &mut self.state else {
            self.state = Some(FilterState {
                tips: human.tips.map(OneEuroPoint::at),
                mids: human.mids.map(OneEuroPoint::at),
            });
            return *human;
        };
        let c = &self.config;
        let mut out = *human;
        for i in 0..5 {
            out.tips[i] = state.tips[i].update(human.tips[i], dt_s, c);
            out.mids[i] = state.mids[i].update(human.mids[i], dt_s, c);
        }
        // Off, the speeds are still estimated (the smoothing's release reads them).
        if self.config.enabled() { out } else { *human }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scalar(x: f64) -> Vector3<f64> {
        Vector3::new(x, 0.0, 0.0)
    }

    fn still_hand() -> HumanKeyVectors {
        HumanKeyVectors {
            tips: [Vector3::new(0.01, 0.08, 0.0); 5],
            mids: [Vector3::new(0.01, 0.05, 0.0); 5],
            pinch_distances_m: [0.05; 4],
        }
    }

    fn config() -> InputFilterConfig {
        InputFilterConfig::default()
    }

    #[test]
    fn the_smoothing_factor_is_a_first_order_low_pass() {
        // τ = 1 / (2π f_c): at dt = τ the factor is one half.
        let f_c = 2.0;
        let tau = 1.0 / (TAU * f_c);
        assert!((smoothing_factor(f_c, tau) - 0.5).abs() < 1e-12);
        assert!(smoothing_factor(f_c, 10.0) > 0.99);
        assert!(smoothing_factor(f_c, 1e-4) < 0.002);
    }

    #[test]
    fn a_constant_input_is_reproduced_exactly() {
        let x = Vector3::new(0.01, 0.07, 0.03);
        let mut f = OneEuroPoint::at(x);
        for _ in 0..50 {
            assert_eq!(f.update(x, 0.04, &config()), x);
        }
    }

    #[test]
    fn jitter_at_rest_is_smoothed_and_a_fast_move_passes_with_little_lag() {
        let c = config();
        let dt = 1.0 / 30.0;
        // ±2 mm alternating jitter around a point at rest.
        let mut f = OneEuroPoint::at(Vector3::zeros());
        let mut worst: f64 = 0.0;
        for k in 0..60 {
            let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
            let y = f.update(scalar(0.002 * sign), dt, &c);
            worst = worst.max(y.x.abs());
        }
        assert!(worst < 0.0007, "jitter left {worst} m");
        // A 1 m/s ramp: after 0.2 s the filter trails by less than 2 cm (a fixed 1 Hz
        // low-pass trails by about 16 cm).
        let mut f = OneEuroPoint::at(Vector3::zeros());
        let mut last = Vector3::zeros();
        for k in 1..=6 {
            last = f.update(scalar(k as f64 * dt), dt, &c);
        }
        let lag = 6.0 * dt - last.x;
        assert!(lag < 0.02, "trailing by {lag} m");
    }

    #[test]
    fn the_fastest_key_point_sets_the_speed() {
        let human = still_hand();
        let mut filter = KeyPointFilter::new(config());
        filter.apply(&human, 0.04);
        assert_eq!(filter.fastest_speed_m_s(), 0.0);
        let mut moving = human;
        for _ in 0..30 {
            moving.tips[2].y -= 0.02; // 0.5 m/s at 25 Hz
            moving.mids[4].y -= 0.004; // 0.1 m/s
            filter.apply(&moving, 0.04);
        }
        // The estimate differences against the filtered value, which trails a ramp: a little
        // above the true 0.5 m/s, far above the slow point's 0.1.
        let v = filter.fastest_speed_m_s();
        assert!((0.45..0.75).contains(&v), "{v} m/s");
        filter.reset();
        assert_eq!(filter.fastest_speed_m_s(), 0.0);
    }

    #[test]
    fn jitter_in_the_frame_timing_changes_nothing_and_a_long_gap_restarts() {
        let frame = |k: usize| HumanKeyVectors {
            tips: [Vector3::new(0.01, 0.08 + 0.002 * (k % 3) as f64, 0.0); 5],
            mids: [Vector3::new(0.01, 0.05, 0.001 * k as f64); 5],
            pinch_distances_m: [0.05; 4],
        };
        let mut steady = KeyPointFilter::new(config());
        let mut jittery = KeyPointFilter::new(config());
        for k in 0..40 {
            let jitter = if k % 2 == 0 { 0.012 } else { 0.055 };
            assert_eq!(
                steady.apply(&frame(k), 0.033),
                jittery.apply(&frame(k), jitter)
            );
        }
        let after_gap = frame(7);
        assert_ne!(steady.apply(&after_gap, 0.2), after_gap);
        assert_eq!(jittery.apply(&after_gap, 0.3), after_gap);
    }

    #[test]
    fn the_first_frame_passes_and_an_off_filter_changes_nothing() {
        let human = still_hand();
        let mut on = KeyPointFilter::new(config());
        assert_eq!(on.apply(&human, 0.04), human);
        let mut moved = human;
        moved.tips[1].y += 0.01;
        moved.pinch_distances_m[0] = 0.01;
        let filtered = on.apply(&moved, 0.04);
        assert_ne!(filtered.tips, moved.tips);
        assert_eq!(filtered.pinch_distances_m, moved.pinch_distances_m);
        let mut off = KeyPointFilter::new(InputFilterConfig {
            min_cutoff_hz: 0.0,
            ..config()
        });
        assert_eq!(off.apply(&human, 0.04), human);
        assert_eq!(off.apply(&moved, 0.04), moved);
    }
}
