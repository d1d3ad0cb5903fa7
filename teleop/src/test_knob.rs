//! Test-only knobs: a delay a test sets in the environment to slow one step of the real code
//! down (the console's saving steps, `console::test_pause`; a trial log's flushes,
//! `mcap_log::slow_disk`). Each knob reads its variable once.

use std::time::Duration;

/// The delay in the environment variable `name`: whole milliseconds, at most `max_ms`; `None`
/// when it is unset, empty, 0 or not a number.
pub fn delay_from_env(name: &str, max_ms: u64) -> Option<Duration> {
    let ms: u64 = std::env::var(name).ok()?.trim().parse().ok()?;
    (ms > 0).then(|| Duration::from_millis(ms.min(max_ms)))
}
