//! Samples of a measured quantity (latencies, step times, errors) and their statistics.

/// Collected samples (the caller's unit, e.g. milliseconds).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Samples {
    samples_ms: Vec<f64>,
}

impl Samples {
    /// Add one sample (ignored if not finite; values below −1, beyond clock noise on a
    /// latency, are ignored and small negatives count as 0).
    pub fn push(&mut self, ms: f64) {
        if ms.is_finite() && ms > -1.0 {
            self.samples_ms.push(ms.max(0.0));
        }
    }

    /// The newest sample.
    pub fn last(&self) -> Option<f64> {
        self.samples_ms.last().copied()
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.samples_ms.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.samples_ms.is_empty()
    }

    /// The mean; `None` without samples.
    pub fn mean(&self) -> Option<f64> {
        (!self.samples_ms.is_empty())
            .then(|| self.samples_ms.iter().sum::<f64>() / self.samples_ms.len() as f64)
    }

    /// The `p` quantile (0–1), nearest rank; `None` without samples.
    pub fn percentile(&self, p: f64) -> Option<f64> {
        if self.samples_ms.is_empty() {
            return None;
        }
        let mut sorted = self.samples_ms.clone();
        sorted.sort_by(f64::total_cmp);
        Some(sorted[((sorted.len() - 1) as f64 * p.clamp(0.0, 1.0)).round() as usize])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentiles_by_nearest_rank() {
        let mut l = Samples::default();
        assert_eq!(l.percentile(0.5), None);
        for i in 1..=100 {
            l.push(f64::from(i));
        }
        l.push(f64::NAN);
        assert_eq!(l.len(), 100);
        assert_eq!(l.percentile(0.5), Some(51.0));
        assert_eq!(l.percentile(0.99), Some(99.0));
        assert_eq!(l.percentile(1.0), Some(100.0));
    }
}
