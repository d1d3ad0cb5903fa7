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

/// A signed number of milliseconds in the environment variable `name`, clamped to
/// `±max_abs_ms`, in nanoseconds; `None` when it is unset, empty, 0 or not a number.
pub fn offset_ns_from_env(name: &str, max_abs_ms: i64) -> Option<i64> {
    let ms: i64 = std::env::var(name).ok()?.trim().parse().ok()?;
    (ms != 0).then(|| ms.clamp(-max_abs_ms, max_abs_ms) * 1_000_000)
}
