//! The station's one clock: wall-clock nanoseconds since the Unix epoch at start-up, advanced
//! monotonically. Receive times, log times and timeouts all come from it, so a wall-clock jump
//! (NTP) neither fires the watchdog nor reorders a log.

use std::time::{Instant, SystemTime, UNIX_EPOCH};

/// A monotonic clock anchored to the wall clock once.
#[derive(Debug, Clone, Copy)]
pub struct StationClock {
    start: Instant,
    start_unix_ns: i64,
}

impl Default for StationClock {
    fn default() -> Self {
        StationClock::new()
    }
}

impl StationClock {
    /// Anchor now.
    pub fn new() -> StationClock {
        let start_unix_ns = SystemTime::now()
            .duration_since(UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos() as i64);
        StationClock {
            start: Instant::now(),
            start_unix_ns,
        }
    }

    /// Nanoseconds since the Unix epoch, monotonic.
    pub fn now_ns(&self) -> i64 {
        self.start_unix_ns + self.start.elapsed().as_nanos() as i64
    }
}
