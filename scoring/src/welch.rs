//! The difference of two group means with Welch's t interval (unequal variances).
//!
//! ```text
//! d    = x̄_g − x̄_r                                         group minus reference
//! SE²  = s_g²/n_g + s_r²/n_r                                 s: sample std (divisor n − 1)
//! ν    = SE⁴ / ( (s_g²/n_g)²/(n_g − 1) + (s_r²/n_r)²/(n_r − 1) )     Welch–Satterthwaite
//! CI   = d ± t_ν((1 + level)/2) · SE
//! ```
//!
//! With fewer than two trials in either group there is no sample std, so no interval; with no
//! spread in either group (both std 0) SE = 0 and ν is 0/0: no interval either. Both are said,
//! never papered over with a zero-width interval.

use serde::Serialize;

use crate::stats::MeanStd;
use crate::student_t::student_t_quantile;

/// The confidence level of the comparison's intervals.
pub const CONFIDENCE_LEVEL: f64 = 0.95;

/// A confidence interval for a difference of means, or why there is none.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum DifferenceInterval {
    /// Welch's interval.
    Defined {
        /// Lower bound.
        low: f64,
        /// Upper bound.
        high: f64,
        /// Welch–Satterthwaite degrees of freedom.
        df: f64,
        /// Standard error of the difference.
        std_error: f64,
        /// The Student-t quantile used.
        t: f64,
    },
    /// A group has fewer than two trials: no sample standard deviation.
    TooFewTrials {
        /// Trials of the group.
        n: usize,
        /// Trials of the reference group.
        reference_n: usize,
    },
    /// Neither group varies (both standard deviations are 0): the interval is undefined.
    NoSpread,
}

impl DifferenceInterval {
    /// Whether there is an interval.
    pub fn is_defined(&self) -> bool {
        matches!(self, DifferenceInterval::Defined { .. })
    }

    /// `(low, high)`, if defined.
    pub fn bounds(&self) -> Option<(f64, f64)> {
        match *self {
            DifferenceInterval::Defined { low, high, .. } => Some((low, high)),
            _ => None,
        }
    }

    /// `[-0.12, +0.03]`, or why there is none: `no CI (n < 2)`, `no CI (no spread)`.
    pub fn describe(&self, decimals: usize) -> String {
        match self {
            DifferenceInterval::Defined { low, high, .. } => {
                format!("[{low:+.decimals$}, {high:+.decimals$}]")
            }
            DifferenceInterval::TooFewTrials { .. } => "no CI (n < 2)".to_string(),
            DifferenceInterval::NoSpread => "no CI (no spread)".to_string(),
        }
    }
}

/// A group's mean minus the reference group's, with its confidence interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Difference {
    /// `mean(group) − mean(reference)`.
    pub estimate: f64,
    /// Welch's interval at [`CONFIDENCE_LEVEL`], or why there is none.
    pub ci: DifferenceInterval,
}

impl Difference {
    /// `+0.05 [-0.12, +0.22]` (or with the reason there is no interval).
    pub fn describe(&self, decimals: usize) -> String {
        format!(
            "{:+.decimals$} {}",
            self.estimate,
            self.ci.describe(decimals)
        )
    }
}

/// `group − reference` with Welch's interval at `level` (in (0, 1)).
pub fn welch_difference(group: &MeanStd, reference: &MeanStd, level: f64) -> Difference {
    let estimate = group.mean - reference.mean;
    let ci = match (group.std, reference.std) {
        (Some(s_g), Some(s_r)) if group.n >= 2 && reference.n >= 2 => {
            welch_interval(estimate, (s_g, group.n), (s_r, reference.n), level)
        }
        _ => DifferenceInterval::TooFewTrials {
            n: group.n,
            reference_n: reference.n,
        },
    };
    Difference { estimate, ci }
}

/// Welch's interval around `estimate` from two `(std, n)` with `n ≥ 2`.
fn welch_interval(
    estimate: f64,
    (s_g, n_g): (f64, usize),
    (s_r, n_r): (f64, usize),
    level: f64,
) -> DifferenceInterval {
    let v_g = s_g * s_g / n_g as f64;
    let v_r = s_r * s_r / n_r as f64;
    let se2 = v_g + v_r;
    if se2 <= 0.0 {
        return DifferenceInterval::NoSpread;
    }
    let df = se2 * se2 / (v_g * v_g / (n_g - 1) as f64 + v_r * v_r / (n_r - 1) as f64);
    let std_error = se2.sqrt();
    match student_t_quantile(0.5 + level / 2.0, df) {
        Some(t) => DifferenceInterval::Defined {
            low: estimate - t * std_error,
            high: estimate + t * std_error,
            df,
            std_error,
            t,
        },
        // Only for a level outside (0, 1) or a non-finite std: no honest interval.
        None => DifferenceInterval::NoSpread,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stats(values: &[f64]) -> MeanStd {
        MeanStd::of(values).unwrap()
    }

    #[test]
    fn welch_matches_a_worked_example() {
        // By hand: ḡ = 6, s_g² = 10; r̄ = 3, s_r² = 2.5; n = 5 each. SE² = 2 + 0.5 = 2.5,
        // ν = 6.25 / (4/4 + 0.25/4) = 5.882352941…; SciPy 1.17.1's
        // ttest_ind(g, r, equal_var=False).confidence_interval(0.95) gives
        // (-0.887741643736975, 6.887741643736975).
        let d = welch_difference(
            &stats(&[2.0, 4.0, 6.0, 8.0, 10.0]),
            &stats(&[1.0, 2.0, 3.0, 4.0, 5.0]),
            CONFIDENCE_LEVEL,
        );
        assert_eq!(d.estimate, 3.0);
        let DifferenceInterval::Defined {
            low,
            high,
            df,
            std_error,
            ..
        } = d.ci
        else {
            panic!("{d:?}");
        };
        assert!((df - 6.25 / 1.0625).abs() < 1e-12, "{df}");
        assert!((std_error - 2.5_f64.sqrt()).abs() < 1e-15);
        assert!((low + 0.887_741_643_736_975).abs() < 1e-9, "{low}");
        assert!((high - 6.887_741_643_736_975).abs() < 1e-9, "{high}");
    }

    #[test]
    fn with_one_spread_the_degrees_of_freedom_are_the_other_groups() {
        // s_r = 0: ν = (s_g²/n_g)² / ((s_g²/n_g)²/(n_g − 1)) = n_g − 1 = 2; t(0.975, 2) =
        // 4.302652729749462; SE = s_g/√3 with s_g = 1 (values 1, 2, 3).
        let d = welch_difference(
            &stats(&[1.0, 2.0, 3.0]),
            &stats(&[1.0, 1.0]),
            CONFIDENCE_LEVEL,
        );
        let (low, high) = d.ci.bounds().unwrap();
        let half = 4.302_652_729_749_462 / 3.0_f64.sqrt();
        assert!((low - (1.0 - half)).abs() < 1e-9 && (high - (1.0 + half)).abs() < 1e-9);
    }

    #[test]
    fn too_few_trials_or_no_spread_leave_the_interval_undefined() {
        let one = welch_difference(&stats(&[0.5]), &stats(&[0.2, 0.4]), CONFIDENCE_LEVEL);
        assert!((one.estimate - 0.2).abs() < 1e-15);
        assert_eq!(
            one.ci,
            DifferenceInterval::TooFewTrials {
                n: 1,
                reference_n: 2
            }
        );
        assert_eq!(one.ci.describe(2), "no CI (n < 2)");
        let flat = welch_difference(&stats(&[1.0, 1.0]), &stats(&[0.5, 0.5]), CONFIDENCE_LEVEL);
        assert_eq!(flat.ci, DifferenceInterval::NoSpread);
        assert!(!flat.ci.is_defined());
        assert_eq!(flat.describe(2), "+0.50 no CI (no spread)");
    }
}
