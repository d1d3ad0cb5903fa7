//! # teleop: the POMDAR station application
//!
//! The one crate that does I/O: files, ROS 2 (ros2-client + tokio), MCAP logs and the
//! operator console (`console`: `pomdar trial`). The pure crates (`retarget`, `calibration`,
//! `scoring`, `msgs`) compute; this crate reads, writes and talks (`score`: the trial files
//! and reports of `pomdar score` and `pomdar baseline`).

pub mod atomic_file;
pub mod calibrate;
pub mod clock;
pub mod command;
pub mod console;
pub mod demo;
pub mod device_thread;
pub mod disk_wait;
pub mod eval;
pub mod eval_modes;
pub mod fnv;
pub mod hand_check;
pub mod hand_source;
pub mod ingress;
pub mod launch_config;
pub mod library_log;
pub mod mcap_log;
pub mod model_report;
#[cfg(feature = "physics")]
pub mod physics;
pub mod progress_bar;
pub mod relay_node;
pub mod replay;
pub mod resim;
pub mod ros;
pub mod samples;
pub mod score;
#[cfg(feature = "physics")]
pub mod sim_bench;
#[cfg(feature = "physics")]
pub mod sim_runs;
pub mod stand_ins;
pub mod station_driver;
pub mod station_node;
pub mod station_topics;
pub mod study_logs;
pub mod test_knob;
pub mod trial_review;
pub mod tui;
pub mod utc_date;
pub mod view;
