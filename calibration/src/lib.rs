//! # calibration: fitting a user's glove to the robot hand
//!
//! Pure and synchronous: no I/O, no clocks (checked by `tests/tests/dependency_rule.rs`).
//!
//! Today: the seven calibration poses as data ([`PoseSet`]: four pinches, open hand without
//! and with abduction, closed hand), each a ground-truth ORCA joint configuration and an
//! instruction. The capture checks and the Bayesian optimisation of a global scale and
//! rotation (issue 6) build on them.

mod error;
mod poses;

pub use error::Error;
pub use poses::{CalibrationPose, ORCA_V1_POSES_TOML, POSE_NAMES, PoseSet};
