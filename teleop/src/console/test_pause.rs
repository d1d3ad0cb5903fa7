//! A test-only slow-down of the console's saving steps, so a test that kills the console at
//! random moments can land its kills inside them (each step takes a few milliseconds, too
//! short to hit by chance).
//!
//! `POMDAR_CONSOLE_TEST_PAUSE_MS=N` (1–10000; off when unset, empty, 0 or not a number) makes
//! the console print `test pause N ms: STEP` on stderr and sleep N ms at each of these points:
//!
//! - resuming: after a `.part` log is recovered (before the `.part` is removed), and before
//!   the resumed manifest is saved;
//! - a trial's log finished (renamed by the station), before it is scored and entered in the
//!   manifest;
//! - the manifest saved after a trial;
//! - the session complete, before its report is written.
//!
//! Read only by the operator console (`pomdar trial`, and `pomdar study` through it); no
//! other command looks at it. Used by `tests/tests/suite/console_random_kills.rs`. Compiled in
//! only with teleop's `test-hooks` feature (which the integration suite's build turns on):
//! without it [`test_pause`] does nothing and the variable is never read.

#[cfg(feature = "test-hooks")]
use std::sync::OnceLock;
#[cfg(feature = "test-hooks")]
use std::time::Duration;

/// The environment variable: milliseconds to pause at each saving step (test-only).
pub const TEST_PAUSE_ENV: &str = "POMDAR_CONSOLE_TEST_PAUSE_MS";

/// The longest pause taken, ms.
#[cfg(feature = "test-hooks")]
const MAX_PAUSE_MS: u64 = 10_000;

/// The pause asked for by [`TEST_PAUSE_ENV`], if any (read once).
#[cfg(feature = "test-hooks")]
fn pause() -> Option<Duration> {
    static PAUSE: OnceLock<Option<Duration>> = OnceLock::new();
    *PAUSE.get_or_init(|| crate::test_knob::delay_from_env(TEST_PAUSE_ENV, MAX_PAUSE_MS))
}

/// With [`TEST_PAUSE_ENV`] set: says `test pause N ms: STEP` on stderr and sleeps N ms (on a
/// multi-thread runtime, with its other tasks moved off this worker, so the station and the
/// simulated glove keep running). Without it, nothing.
#[cfg(feature = "test-hooks")]
pub fn test_pause(step: &str) {
    let Some(pause) = pause() else { return };
    eprintln!("test pause {} ms: {step}", pause.as_millis());
    let sleep = || std::thread::sleep(pause);
    match tokio::runtime::Handle::try_current() {
        Ok(h) if h.runtime_flavor() == tokio::runtime::RuntimeFlavor::MultiThread => {
            tokio::task::block_in_place(sleep);
        }
        _ => sleep(),
    }
}

/// Without the `test-hooks` feature: nothing.
#[cfg(not(feature = "test-hooks"))]
pub fn test_pause(_step: &str) {}
