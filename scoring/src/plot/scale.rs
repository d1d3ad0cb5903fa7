//! Axis ranges and tick values shared by the charts.

use super::error::ValueProblem;

/// The largest score a figure draws. Speed is unbounded, but a score of 100 would mean a
/// trial 400 times faster than the human baseline: a larger value is a units or parsing
/// mistake, not a result.
pub const MAX_SCORE: f64 = 100.0;

/// Whether `value` can be drawn on a score axis.
pub fn check_score(value: f64) -> Result<(), ValueProblem> {
    if !value.is_finite() {
        Err(ValueProblem::NotFinite)
    } else if value < 0.0 {
        Err(ValueProblem::Negative)
    } else if value > MAX_SCORE {
        Err(ValueProblem::TooLarge)
    } else {
        Ok(())
    }
}

/// A score axis from 0 to `top` in steps of `step`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScoreAxis {
    /// Distance between grid lines.
    pub step: f64,
    /// Number of steps from 0 to the top.
    pub steps: u32,
}

impl ScoreAxis {
    /// The axis' largest value.
    pub fn top(&self) -> f64 {
        f64::from(self.steps) * self.step
    }

    /// Grid values from the first step to the top (0 excluded).
    pub fn ticks(&self) -> impl Iterator<Item = f64> + '_ {
        (1..=self.steps).map(|k| f64::from(k) * self.step)
    }

    /// A tick value as text: one decimal for steps below 1, none above.
    pub fn label(&self, value: f64) -> String {
        if self.step < 1.0 {
            format!("{value:.1}")
        } else {
            format!("{value:.0}")
        }
    }
}

/// The score axis for values up to `max_value` (checked with [`check_score`]): 0.2 steps to
/// 1.0, extended by 0.2 steps past the largest value, with a coarser 1-2-5 step when more
/// than ten grid lines would be needed.
pub fn score_axis(max_value: f64) -> ScoreAxis {
    const MAX_STEPS: f64 = 10.0;
    let max_value = max_value.max(1.0);
    let mut step = 0.2;
    for candidate in [0.2, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0] {
        step = candidate;
        if steps_to_cover(max_value, step) <= MAX_STEPS {
            break;
        }
    }
    ScoreAxis {
        step,
        steps: steps_to_cover(max_value, step) as u32,
    }
}

/// Whole steps from 0 to cover `value`, forgiving floating-point noise (1.2 / 0.2 = 6).
fn steps_to_cover(value: f64, step: f64) -> f64 {
    (value / step - 1e-9).ceil().max(1.0)
}

/// An integer axis from `lo` to `hi` in steps of `step`, padded by at least one unit around
/// the data and with at most ten steps.
pub fn integer_axis(min: u32, max: u32) -> (u64, u64, u64) {
    let (min, max) = (u64::from(min.min(max)), u64::from(min.max(max)));
    let mut step = 1;
    loop {
        for mult in [1, 2, 5] {
            let s = step * mult;
            let lo = min.saturating_sub(1) / s * s;
            let hi = (max + 1).div_ceil(s) * s;
            if (hi - lo) / s <= 10 {
                return (lo, hi, s);
            }
        }
        step *= 10;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scores_up_to_one_get_five_rings_of_0_2() {
        for max in [0.0, 0.3, 0.94, 1.0] {
            let axis = score_axis(max);
            assert_eq!((axis.step, axis.steps), (0.2, 5), "max {max}");
            assert_eq!(axis.label(axis.top()), "1.0");
        }
    }

    #[test]
    fn superhuman_scores_extend_the_axis_by_0_2() {
        assert_eq!(score_axis(1.01).steps, 6);
        assert_eq!(score_axis(1.2).steps, 6);
        assert_eq!(score_axis(1.21).steps, 7);
        let axis = score_axis(1.13);
        let labels: Vec<String> = axis.ticks().map(|t| axis.label(t)).collect();
        assert_eq!(labels, ["0.2", "0.4", "0.6", "0.8", "1.0", "1.2"]);
    }

    #[test]
    fn large_scores_get_coarser_steps() {
        let axis = score_axis(3.7);
        assert_eq!((axis.step, axis.steps), (0.5, 8));
        let axis = score_axis(MAX_SCORE);
        assert!(axis.steps <= 10 && axis.top() >= MAX_SCORE);
    }

    #[test]
    fn bad_scores_are_named() {
        assert_eq!(check_score(f64::NAN), Err(ValueProblem::NotFinite));
        assert_eq!(check_score(-0.1), Err(ValueProblem::Negative));
        assert_eq!(check_score(MAX_SCORE + 1.0), Err(ValueProblem::TooLarge));
        assert_eq!(check_score(1.3), Ok(()));
    }

    #[test]
    fn integer_axis_pads_the_data() {
        assert_eq!(integer_axis(5, 16), (4, 18, 2));
        assert_eq!(integer_axis(16, 16), (15, 17, 1));
        assert_eq!(integer_axis(0, 3), (0, 4, 1));
        let (lo, hi, step) = integer_axis(0, u32::MAX);
        assert!(lo == 0 && hi > u64::from(u32::MAX) && (hi - lo) / step <= 10);
    }
}
