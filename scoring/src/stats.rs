//! Mean and sample standard deviation.

use serde::{Deserialize, Serialize};

/// Mean ± sample standard deviation of `n` values.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MeanStd {
    /// Arithmetic mean.
    pub mean: f64,
    /// Sample standard deviation (divisor n − 1); `None` for a single value.
    pub std: Option<f64>,
    /// Number of values.
    pub n: usize,
}

impl MeanStd {
    /// Statistics of `values`; `None` if there are none.
    pub fn of(values: &[f64]) -> Option<MeanStd> {
        let n = values.len();
        if n == 0 {
            return None;
        }
        let mean = values.iter().sum::<f64>() / n as f64;
        let std = (n > 1).then(|| {
            let ss: f64 = values.iter().map(|v| (v - mean) * (v - mean)).sum();
            (ss / (n - 1) as f64).sqrt()
        });
        Some(MeanStd { mean, std, n })
    }

    /// `0.72 ± 0.05` with `decimals` decimals (`0.72 ± –` for a single value).
    pub fn format(&self, decimals: usize) -> String {
        match self.std {
            Some(s) => format!("{:.decimals$} ± {:.decimals$}", self.mean, s),
            None => format!("{:.decimals$} ± –", self.mean),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_standard_deviation() {
        let s = MeanStd::of(&[1.0, 2.0, 3.0, 4.0]);
        assert_eq!(s.map(|s| s.mean), Some(2.5));
        let std = s.and_then(|s| s.std).unwrap_or_default();
        assert!((std - (5.0_f64 / 3.0).sqrt()).abs() < 1e-15);
        assert_eq!(MeanStd::of(&[2.0]).and_then(|s| s.std), None);
        assert_eq!(MeanStd::of(&[]), None);
    }
}
