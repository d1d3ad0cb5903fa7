//! # teleop: the POMDAR station application
//!
//! The one crate that does I/O: files, ROS 2 (ros2-client + tokio) and MCAP logs; the
//! operator console arrives with issue 8. The pure crates (`retarget`, `calibration`,
//! `scoring`, `msgs`) compute; this crate reads, writes and talks.

pub mod arm;
pub mod calibrate;
pub mod cli;
pub mod clock;
pub mod demo;
pub mod hand_source;
pub mod launch_config;
pub mod mcap_log;
pub mod model_report;
pub mod replay;
pub mod resim;
pub mod ros;
pub mod sim;
pub mod station;
