//! The calibration console's session (`pomdar calibrate`) without its I/O: the session pose by
//! pose as a state machine, a capture's quality, the session log's event names and shapes, and
//! what the console shows. `teleop::calibrate` runs it over ROS 2, logs it and fits.

pub mod calibration_view;
pub mod capture_quality;
pub mod pose_session;
pub mod session_events;
