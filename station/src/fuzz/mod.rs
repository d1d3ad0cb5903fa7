//! # Fuzzing the whole station
//!
//! A deterministic driver feeds one [`Station`](crate::Station) a long stream of hostile
//! inputs and checks invariants on every output. Pure like the rest of the crate: no threads,
//! no clock, no I/O; a seed replays a run exactly. The CI-sized run is the test
//! `station/tests/suite/fuzz_station.rs`; the long one the example `fuzz_station`.
//!
//! - [`world`]: what is fed — plausible frames of a moving hand (so the station engages,
//!   retargets and drives the arm) mixed with duplicated, restamped, replayed (late), bursty
//!   and hostile frames ([`hostile`]: NaN, infinities, 1e30, wrong sizes, garbage, scaled,
//!   teleported, collapsed); jumps of the sender's clock (hours either way, small steps back,
//!   wild stamps); the station clock monotonic with gaps of up to 5 s; wrist poses and arm
//!   feedback, valid and hostile; engage, disengage, arm blocked and unblocked, ticks, in any
//!   order.
//! - [`checker`] with [`hand_checks`], [`arm_checks`] and the reference [`drive_model`]: the
//!   invariants, each counted in a [`Tally`] with its checks and violations.
//! - [`driver`]: one run.

pub mod arm_checks;
pub mod checker;
pub mod drive_model;
pub mod driver;
pub mod hand_checks;
pub mod hostile;
pub mod plausible_hand;
pub mod rng;
pub mod tally;
pub mod world;

pub use driver::{FuzzOptions, START_NS, config_for_seed, run};
pub use tally::{CheckCount, Tally};
