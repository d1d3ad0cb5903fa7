//! The ROS 2 adapter: a DDS participant on the configured domain, and typed publishers and
//! subscriptions for the `msgs` types (ros2-client on RustDDS; no ROS installation needed).

pub mod convert;
pub mod discovery_probe;
mod endpoint;
mod participant;
pub mod probe_command;
mod qos;

pub use endpoint::{RosNode, Stamped};
pub use participant::{NetworkConfig, domain_id};
pub use qos::{QosConfig, Reliability};
