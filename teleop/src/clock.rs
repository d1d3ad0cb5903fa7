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

/// The variable a test sets to shift [`WallClock::from_env`] by whole milliseconds (either
/// sign, at most ±10 s): two computers' clocks out of step, on one computer.
pub const TEST_CLOCK_OFFSET_VAR: &str = "POMDAR_TEST_CLOCK_OFFSET_MS";

/// The system's wall clock read afresh at every call, so a step (NTP, an operator's `date`) is
/// seen: for comparing this computer's time with stamps another computer's wall clock set, as
/// `pomdar relay` does with the station's send times.
#[derive(Debug, Clone, Copy, Default)]
pub struct WallClock {
    offset_ns: i64,
}

impl WallClock {
    /// The system's clock as it is.
    pub fn system() -> WallClock {
        WallClock::default()
    }

    /// The system's clock, shifted by [`TEST_CLOCK_OFFSET_VAR`] when a test set it.
    pub fn from_env() -> WallClock {
        WallClock {
            offset_ns: crate::test_knob::offset_ns_from_env(TEST_CLOCK_OFFSET_VAR, 10_000)
                .unwrap_or(0),
        }
    }

    /// Nanoseconds since the Unix epoch, now.
    pub fn now_ns(&self) -> i64 {
        let now = SystemTime::now()
            .duration_since(UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos() as i64);
        now + self.offset_ns
    }
}
