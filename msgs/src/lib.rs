//! # msgs: ROS 2 message types for the POMDAR station
//!
//! Not yet populated. Issue 4 adds serde structs with CDR (de)serialisation and their `.msg`
//! schema texts (`std_msgs`, `geometry_msgs`, `sensor_msgs/JointState`, the station status),
//! usable by ros2-client and by the MCAP reader alike. This crate never depends on
//! ros2-client, rustdds or tokio (checked by `tests/tests/dependency_rule.rs`).
