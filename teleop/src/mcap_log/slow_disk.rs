//! A test-only slow disk, so a test can show that a stalled disk stalls only the log.
//!
//! `POMDAR_TEST_SLOW_DISK_MS=N` (1–10000; off when unset, empty, 0 or not a number) makes every
//! flush of a trial log to the operating system take N ms longer, and so its sync and rename
//! at the end, and every atomic file write (a session's manifest, a profile, a report): what
//! a lab PC's HDD, a network home or a disk busy with something else does. Read by
//! [`TrialWriter`](super::TrialWriter) and [`write_atomically`](crate::atomic_file::write_atomically)
//! only; no test of their own output sets it. Used by the slow-disk tests of the station and
//! the consoles.

use std::sync::OnceLock;
use std::time::Duration;

/// The environment variable: extra milliseconds per flush of a trial log (test-only).
pub const SLOW_DISK_ENV: &str = "POMDAR_TEST_SLOW_DISK_MS";

/// The longest delay taken, ms.
const MAX_DELAY_MS: u64 = 10_000;

/// The delay asked for by [`SLOW_DISK_ENV`], if any (read once).
fn delay() -> Option<Duration> {
    static DELAY: OnceLock<Option<Duration>> = OnceLock::new();
    *DELAY.get_or_init(|| crate::test_knob::delay_from_env(SLOW_DISK_ENV, MAX_DELAY_MS))
}

/// With [`SLOW_DISK_ENV`] set, sleeps its delay (on the calling thread); otherwise nothing.
pub(crate) fn stall() {
    if let Some(delay) = delay() {
        std::thread::sleep(delay);
    }
}
