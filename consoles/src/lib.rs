//! # consoles: the consoles' cores as pure state machines
//!
//! Pure and synchronous: no I/O, no clocks (checked by `tests/tests/suite/dependency_rule.rs`).
//! Each console of `teleop` (the hand check, the calibration console, the trial console) is a
//! state machine here: operator actions and measurements come in with the time as a parameter,
//! effects and the lines to show come out. `teleop` runs them on its terminal shell, talks to
//! the station and the hand over ROS 2 and reads and writes the files.
//!
//! ## Files
//!
//! | file | what |
//! |---|---|
//! | `error.rs` | [`ConsolesError`]: what the pure parts refuse |
//! | `hand_check/session.rs` | the hand check as a state machine (time a parameter): phases, answers, the pose and command, the verified table |
//! | `hand_check/directions.rs` | what each joint's motion looks like, checked against the model's kinematics |
//! | `calibrate/pose_session.rs` | the calibration session pose by pose (station-clock nanoseconds a parameter): settle, capture, judge, accept or retry, fit; after the fit, a pose it could not match captured again alone |
//! | `calibrate/capture_quality.rs` | a capture's jitter, invalid frames and frames vs expected: good / poor / bad |
//! | `calibrate/session_events.rs` | a calibration session log's metadata record and events: names and shapes |
//! | `calibrate/calibration_view.rs` | what the calibration console shows, as data |
//! | `console/trial_flow.rs` | the trial console's session (practice, then recorded trials): actions, health and scored logs in, effects out |
//! | `console/health.rs` | the station's health from its status, the fault counts, and whether a trial may start |
//! | `console/health_lines.rs` | the health as the console's rows, each with its level |
//! | `console/view.rs` | what the trial console shows, as data (its screen, the session's settings) |
//! | `console/manifest.rs` | the session manifest's data, and which trial log names it may give |
//! | `console/action.rs` | the operator's actions |
//! | `level.rs` | [`Level`]: how a value on a console reads (ok, warn, bad) |

pub mod calibrate;
pub mod console;
pub mod hand_check;

mod error;
mod level;

pub use error::ConsolesError;
pub use level::Level;
