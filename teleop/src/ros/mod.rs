//! The ROS 2 adapter: a DDS participant on the configured domain, and typed publishers and
//! subscriptions for the `msgs` types (ros2-client on RustDDS; no ROS installation needed).

pub mod datagram_guard;
pub mod discovery_probe;
pub mod domain_lease;
mod endpoint;
mod error;
mod network_override;
mod participant;
pub mod participant_guard;
pub mod probe_timing;
mod qos;
pub mod teardown;

pub use endpoint::{RosNode, Stamped, TriggerRequest, TriggerResponse};
pub use error::RosError;
pub use network_override::NetworkOverride;
pub use participant::{NetworkContext, default_domain_id, domain_id};
pub use qos::QosProfileOf;
pub use station::convert;
pub use station::{NetworkConfig, QosConfig, Reliability};
