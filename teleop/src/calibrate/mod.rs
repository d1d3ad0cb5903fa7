//! # Calibration: sessions, fits and profiles (`pomdar calibrate`, `--profile`)
//!
//! The calibration maths is the pure `calibration` crate; this module does its I/O.
//!
//! | file | what |
//! |---|---|
//! | `session_node.rs` | the session over ROS 2: the hand shows each pose, the glove is recorded with the capture windows |
//! | `session_events.rs` | the session log's metadata record and events |
//! | `session_frames.rs` | reading a session log back: each pose's frames |
//! | `fit_session.rs` | session log → captures → fit → table → profile (atomic write) |
//! | `simulated_user.rs` | `--simulate`: a synthetic user's glove on loopback, time-aligned with the session |
//! | `calibrate_command.rs` | the `pomdar calibrate` flags and modes |
//! | `profile_file.rs` | loading a profile for the station, its one-line description, atomic writes |
//! | `progress_bar.rs` | the fit's progress on stderr |
//! | `utc_date.rs` | ISO 8601 UTC dates |

pub mod calibrate_command;
pub mod calibration_console;
pub mod calibration_screen;
pub mod calibration_script;
pub mod calibration_view;
pub mod capture_quality;
pub mod fit_session;
pub mod pose_session;
pub mod profile_file;
pub mod progress_bar;
pub mod session_events;
pub mod session_frames;
pub mod session_node;
pub mod simulated_user;
pub mod utc_date;
