//! # calibration: fitting a user's glove to the robot hand
//!
//! Pure and synchronous: no I/O, no clocks (checked by `tests/tests/suite/dependency_rule.rs`).
//!
//! A new user performs seven poses ([`PoseSet`]: four pinches, open hand without and with
//! abduction, closed hand), each a ground-truth joint configuration of the robot hand that the
//! station shows on the hand. About a second of glove keypoints per pose is checked and
//! averaged ([`capture_pose`]); a global scale and a rotation
//! ([`retarget::CalibrationTransform`], applied to the human key vectors in the palm frame) are
//! then fitted by Bayesian optimisation ([`calibrate`]) so that the real retargeter's output
//! for the captures lands as close as possible to the ground truth ([`Objective`]). The result
//! is stored per user as a [`CalibrationProfile`].
//!
//! | file | what |
//! |---|---|
//! | `poses.rs` | the seven poses as data |
//! | `schedule.rs` | [`CaptureSchedule`]: slot per pose, capture window |
//! | `capture.rs` | [`capture_pose`]: validity and stability checks, palm-frame average |
//! | `objective.rs` | [`Objective`]: joint error (plus pinch gap) of the retargeter's output |
//! | `search_space.rs` | parameters ↔ transform, bounds, seeded Latin hypercube |
//! | `optimiser.rs` | [`bayesian_optimise`] (Gaussian process + expected improvement), [`polish`], [`random_search`] |
//! | `gaussian_process.rs` | the surrogate: constant mean, Matérn 5/2 ARD, length scales by maximum likelihood; prediction |
//! | `gp_likelihood.rs` | its likelihood: Cholesky with jitter, GLS mean and variance profiled out |
//! | `expected_improvement.rs` | the acquisition: `ln EI`, maximised by a seeded multistart |
//! | `nelder_mead.rs` | the downhill simplex in a box (polish, length scales, acquisition) |
//! | `fit.rs` | [`calibrate`]: before, optimise, after |
//! | `fit_check.rs` | [`poses_that_do_not_fit`]: the poses the fit could not match, in words |
//! | `profile.rs` | [`CalibrationProfile`]: the per-user TOML file |
//! | `test_support.rs` | (feature `test-support`) a profile's text with a chosen transform, for other crates' tests |
//! | `settings.rs` | [`CalibrationSettings`]: bounds, budget, thresholds |
//! | `human_copy.rs` | [`human_copies`]: the human hand model copying each robot pose |
//! | `synthetic_user.rs` | [`SyntheticUser`]: test users with known hand size and misalignment |
//! | `synthetic_study.rs` | [`Study`]: recovery and held-out error over synthetic users |

mod capture;
mod digit_scales;
mod error;
mod expected_improvement;
mod fit;
mod fit_check;
mod gaussian_process;
mod gp_likelihood;
mod held_out_motion;
mod human_copy;
mod nelder_mead;
mod objective;
mod optimiser;
mod poses;
mod profile;
mod schedule;
mod search_space;
mod settings;
mod synthetic_study;
mod synthetic_user;
#[cfg(any(test, feature = "test-support"))]
pub mod test_support;

pub use capture::{CapturedPose, capture_pose};
pub use error::Error;
pub use fit::{BuiltinInputs, Calibration, FitInputs, FitProgress, calibrate};
pub use fit_check::{PoseMisfit, poses_that_do_not_fit};
pub use held_out_motion::{
    HELD_OUT_DURATION_S, HELD_OUT_JITTER_M, HELD_OUT_RATE_HZ, HeldOutFrame, held_out_pinches,
};
pub use human_copy::{human_copies, human_copy};
pub use objective::{Evaluation, Objective, PoseError, cold_solve_config};
pub use optimiser::{ObjectiveFn, Trace, bayesian_optimise, polish, random_search};
pub use poses::{CalibrationPose, ORCA_V1_POSES_TOML, POSE_NAMES, PoseSet};
pub use profile::{CalibrationProfile, ObjectiveSummary, PoseReport, ProfileHeader};
pub use schedule::CaptureSchedule;
pub use search_space::{Parameters, box_bounds, initial_design, parameters, transform};
pub use settings::{
    CalibrationModel, CalibrationSettings, CaptureThresholds, FitCheck, OptimiserSettings,
    ParameterBounds,
};
pub use synthetic_study::{CAPTURE_RATE_HZ, HELD_OUT_POSES, Study, UserOutcome};
pub use synthetic_user::{
    POPULATION_ANGLE_DEG, POPULATION_NOISE_M, POPULATION_SCALE, SyntheticUser, wrongly_held_pose,
};
