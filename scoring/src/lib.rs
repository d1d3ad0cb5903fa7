//! # scoring: POMDAR scores from trial logs
//!
//! Being written for issue 7: the task catalog, baselines, trial scoring
//! (`0.8 · correctness + 0.2 · speed`), aggregation, reports and plots. Pure and synchronous:
//! no I/O, no clocks (checked by `tests/tests/dependency_rule.rs`).

pub mod plot;
