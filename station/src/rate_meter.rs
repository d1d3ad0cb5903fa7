//! Event rates over a sliding window, for the status topic.

use std::collections::VecDeque;

/// Counts events in the last `window_ns` nanoseconds.
#[derive(Debug, Clone)]
pub struct RateMeter {
    window_ns: i64,
    events: VecDeque<i64>,
}

impl RateMeter {
    /// A meter over `window_s` seconds.
    pub fn new(window_s: f64) -> RateMeter {
        RateMeter {
            window_ns: (window_s * 1e9) as i64,
            events: VecDeque::new(),
        }
    }

    /// Record an event at `now_ns`.
    pub fn record(&mut self, now_ns: i64) {
        self.events.push_back(now_ns);
        self.trim(now_ns);
    }

    /// Events per second at `now_ns`.
    pub fn rate_hz(&mut self, now_ns: i64) -> f64 {
        self.trim(now_ns);
        self.events.len() as f64 / (self.window_ns as f64 * 1e-9)
    }

    fn trim(&mut self, now_ns: i64) {
        while self
            .events
            .front()
            .is_some_and(|&t| now_ns - t > self.window_ns)
        {
            self.events.pop_front();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_events_in_the_window() {
        let mut meter = RateMeter::new(1.0);
        for i in 0..50 {
            meter.record(i * 20_000_000);
        }
        assert!((meter.rate_hz(980_000_000) - 50.0).abs() < 1e-9);
        assert_eq!(meter.rate_hz(5_000_000_000), 0.0);
    }
}
