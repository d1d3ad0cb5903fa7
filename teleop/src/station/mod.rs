//! The station: the synchronous control step and its parts (frame gate, source order,
//! watchdog).

pub mod frame_gate;
pub mod output_stage;
pub mod policy_output;
pub mod rate_meter;
pub mod recorder;
pub mod ros_station;
pub mod source_order;
pub mod station_config;
pub mod station_core;
pub mod watchdog;
