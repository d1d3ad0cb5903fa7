//! # Calibration: sessions, fits and profiles (`pomdar calibrate`, `--profile`)
//!
//! The calibration maths is the pure `calibration` crate; this module does its I/O.
//!
//! | file | what |
//! |---|---|
//! | `pose_session`, `capture_quality` | re-exported from the core crate `consoles` (`consoles/src/calibrate/`): the session pose by pose as a pure state machine (settle, capture, judge, accept or retry, fit; after the fit, a pose it could not match captured again alone), and a capture's quality (good / poor / bad) |
//! | `session_node.rs` | the session over ROS 2: its options, `run_session` (the log, the glove's topic in, the hand's out, the console) and its loop's wait (Ctrl-C, glove frames, the pose's resend, keys, the fit's progress and end); its parts in `session_node/`: |
//! | `session_node/session_turn.rs` | the running session and its turn: glove frames logged and judged, keys and `--script` to the session, its effects carried out, Ctrl-C (the log finished as aborted, or the fit cancelled), no glove, the simulated user cued |
//! | `session_node/session_log.rs` | the session's MCAP log: opened before the topics are up (removed if the session cannot start), written on its own thread (the glove recorded with every capture window, its quality and the decisions), finished for the fit, the finished log continued for a redo |
//! | `session_node/hand_command.rs` | the pose the hand is sent to, re-sent every 100 ms; the sends that could not be published |
//! | `session_node/fit_run.rs` | the fit in a blocking task: its progress, its cancellation on Ctrl-C, its outcome |
//! | `session_node/session_end.rs` | how the session ends: interrupted, complete, or failed by its script (the reason and the error naming the log) |
//! | `session_node/session_outcome.rs` | once the session has quit: the log finished, then the report or the error naming the log |
//! | `session_events.rs` | each capture window of a session log with its quality and decision, and each pose's accepted one (the record's and the events' names and shapes: `consoles::calibrate::session_events`, re-exported) |
//! | `session_frames.rs` | reading a session log back: each pose's frames |
//! | `fit_session.rs` | session log → captures → fit → table → profile (atomic write) |
//! | `calibration_console.rs` | the console's front: full-screen or line console, keys, `--script` |
//! | `calibration_view.rs` | the line console's output; what the console shows, as data (`consoles::calibrate::calibration_view`, re-exported) |
//! | `calibration_screen.rs` | drawing the view full-screen (ratatui) |
//! | `calibration_script.rs` | `--script` files: timed accept / retry / quit and `wait STATE` |
//! | `simulated_user.rs` | `--simulate`: a synthetic user's glove on loopback, copying the pose the session is at (shaking through a pose, or holding the previous one, when asked) |
//! | `progress_bar.rs` | the fit's progress on stderr |
//! | `ctrl_c.rs` | the process's one Ctrl-C handler (installed first, works without an async runtime), as a watch channel |
//! | `error.rs` | the one error type, [`CalibrateError`] |

pub mod calibrate_console_run;
pub mod calibrate_report;
pub mod calibrate_request;
pub mod calibrate_run;
pub mod calibrate_run_error;
pub mod calibration_console;
pub mod calibration_screen;
pub mod calibration_script;
pub mod calibration_view;
pub mod ctrl_c;
pub mod error;
pub mod fit_session;
pub mod progress_bar;
pub mod session_events;
pub mod session_frames;
pub mod session_node;
pub mod simulated_user;

pub use consoles::calibrate::{capture_quality, pose_session};
pub use error::CalibrateError;
