//! At most one log line per kind per period, with a count of the lines held back: a stream of
//! bad or hostile packets must not flood the operator's terminal. Pure: times are parameters.

use std::collections::BTreeMap;

/// One line per kind per this many seconds.
pub const LOG_PERIOD_S: i64 = 10;

/// Remembers, per kind, when a line was last printed and how many were held back since.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LogLimiter {
    period_ns: i64,
    kinds: BTreeMap<&'static str, (i64, u64)>,
}

impl Default for LogLimiter {
    fn default() -> Self {
        LogLimiter::new(LOG_PERIOD_S * 1_000_000_000)
    }
}

impl LogLimiter {
    /// A limiter allowing one line per kind per `period_ns`.
    pub fn new(period_ns: i64) -> LogLimiter {
        LogLimiter {
            period_ns,
            kinds: BTreeMap::new(),
        }
    }

    /// Whether a line of `kind` may be printed at `now_ns`: `Some(n)` with the number of lines
    /// of that kind held back since the last one printed, or `None` (held back, counted).
    pub fn allow(&mut self, kind: &'static str, now_ns: i64) -> Option<u64> {
        match self.kinds.get_mut(kind) {
            Some((last, held)) if now_ns.saturating_sub(*last) < self.period_ns => {
                *held += 1;
                None
            }
            Some((last, held)) => {
                let n = *held;
                *last = now_ns;
                *held = 0;
                Some(n)
            }
            None => {
                self.kinds.insert(kind, (now_ns, 0));
                Some(0)
            }
        }
    }
}

/// `" (N similar lines held back in the last S s)"`, or nothing when none were.
pub fn held_back(n: u64) -> String {
    if n == 0 {
        String::new()
    } else {
        format!(" ({n} more like it not logged in the last {LOG_PERIOD_S} s)")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_line_per_kind_per_period_with_the_count_held_back() {
        let s = 1_000_000_000;
        let mut l = LogLimiter::new(10 * s);
        assert_eq!(l.allow("sender", 0), Some(0));
        for k in 1..=1000 {
            assert_eq!(l.allow("sender", k * 1_000_000), None);
        }
        // Another kind has its own allowance.
        assert_eq!(l.allow("restart", 5 * s), Some(0));
        assert_eq!(l.allow("sender", 10 * s), Some(1000));
        assert_eq!(l.allow("sender", 11 * s), None);
        assert_eq!(l.allow("sender", 25 * s), Some(1));
        assert_eq!(held_back(0), "");
        assert!(held_back(3).contains("3 more"));
    }
}
