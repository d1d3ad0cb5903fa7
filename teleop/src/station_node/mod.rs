//! The station as a ROS 2 node: the shell around [`station::Station`] that subscribes, stamps,
//! records, steps the station and publishes what it returns.

pub mod control_input_log;
mod error;
mod loop_turns;
pub mod operator;
pub mod recorder;
mod recorder_thread;
mod relay_view;
pub mod ros_node;
mod ros_tools_node;
pub mod tap;

pub use error::NodeError;
