//! A linear axis with round ticks (1, 2 or 5 times a power of ten) around the data.

/// Aimed-for number of steps on an axis (the round step gives 4 to 10).
const TARGET_STEPS: f64 = 6.0;

/// A linear axis from `lo` to `hi` (both multiples of `step`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearAxis {
    /// First tick.
    pub lo: f64,
    /// Last tick.
    pub hi: f64,
    /// Distance between ticks: 1, 2 or 5 times a power of ten.
    pub step: f64,
}

impl LinearAxis {
    /// The axis for data from `min` to `max`: padded by 5 % of the span on both sides (±1
    /// around a single value), then widened to whole steps.
    pub fn spanning(min: f64, max: f64) -> Self {
        let span = max - min;
        let pad = if span > 0.0 {
            0.05 * span
        } else {
            (0.1 * min.abs()).max(1.0)
        };
        let (lo, hi) = (min - pad, max + pad);
        let raw = (hi - lo) / TARGET_STEPS;
        let power = 10_f64.powf(raw.log10().floor());
        let step = match raw / power {
            f if f <= 1.0 => power,
            f if f <= 2.0 => 2.0 * power,
            f if f <= 5.0 => 5.0 * power,
            _ => 10.0 * power,
        };
        Self {
            lo: (lo / step).floor() * step,
            hi: (hi / step).ceil() * step,
            step,
        }
    }

    /// Tick values from `lo` to `hi`, with 0 exactly 0.
    pub fn ticks(&self) -> Vec<f64> {
        let n = ((self.hi - self.lo) / self.step).round() as usize;
        (0..=n)
            .map(|k| self.lo + k as f64 * self.step)
            .map(|v| if v.abs() < 1e-6 * self.step { 0.0 } else { v })
            .collect()
    }

    /// A tick value as text, with as many decimals as the step needs.
    pub fn label(&self, value: f64) -> String {
        // The slack keeps a step of 0.01 computed as 0.00999… at two decimals.
        let decimals = (-(self.step.log10() + 1e-9).floor()).max(0.0) as usize;
        format!("{value:.decimals$}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axes_are_round_padded_and_cover_the_data() {
        let a = LinearAxis::spanning(-2.4, 1.9);
        assert_eq!(a.step, 1.0);
        assert_eq!((a.lo, a.hi), (-3.0, 3.0));
        assert_eq!(a.ticks(), [-3.0, -2.0, -1.0, 0.0, 1.0, 2.0, 3.0]);
        assert_eq!(a.label(-2.0), "-2");
        let b = LinearAxis::spanning(0.012, 0.047);
        assert!(
            b.lo <= 0.012 - 0.05 * 0.035 && b.hi >= 0.047 + 0.05 * 0.035,
            "{b:?}"
        );
        assert!((b.step - 0.01).abs() < 1e-15, "{b:?}");
        assert_eq!(b.label(0.02), "0.02");
        let single = LinearAxis::spanning(3.0, 3.0);
        assert!(single.lo <= 2.0 && single.hi >= 4.0, "{single:?}");
        for axis in [a, b, single] {
            let steps = axis.ticks().len() - 1;
            assert!((4..=10).contains(&steps), "{axis:?}");
        }
    }
}
