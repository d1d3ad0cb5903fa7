//! Turns between the tests that flood the machine and the real-time tests they would starve.
//!
//! The crafted-datagram tests send about 50,000 datagrams a second at a `pomdar` process
//! while reading its memory from `/proc`; at libtest's four threads three of them ran side by
//! side, and on the 2-core CI machine a real-time console test beside them saw its station
//! receive no glove frame for 539 ms while the glove had sent one every 10 ms (the receiving
//! side starved: the console said so), so the watchdog disengaged and the trial could not
//! start. The floods now run one at a time, and never beside a test that holds
//! [`real_time`]; everything else still runs in parallel.

use std::sync::{PoisonError, RwLock, RwLockReadGuard, RwLockWriteGuard};

static TURNS: RwLock<()> = RwLock::new(());

/// Held by a test that floods the machine: it runs alone among the floods and the
/// real-time tests.
pub fn flooding() -> RwLockWriteGuard<'static, ()> {
    TURNS.write().unwrap_or_else(PoisonError::into_inner)
}

/// Held by a real-time test that a flood beside it would starve (real-time tests still run
/// beside each other).
pub fn real_time() -> RwLockReadGuard<'static, ()> {
    TURNS.read().unwrap_or_else(PoisonError::into_inner)
}
