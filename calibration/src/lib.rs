//! # calibration: fitting a user's glove to the robot hand
//!
//! Not yet populated. Issue 6 adds the seven calibration poses, capture checks and the
//! Bayesian optimisation of a global scale and rotation. Pure and synchronous: no I/O, no
//! clocks (checked by `tests/tests/dependency_rule.rs`).
