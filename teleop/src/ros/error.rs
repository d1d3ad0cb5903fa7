//! The ROS 2 adapter's one error type.
//!
//! Every variant names what was being created (domain, interface address, topic, node) and
//! carries ros2-client's or RustDDS's error as its source, its text in the message.

use std::net::IpAddr;

use ros2_client::dds::rustdds::dds::CreateError as DdsCreateError;
use ros2_client::names::NameError;
use ros2_client::{CreateError, NodeCreateError};

/// Joining the DDS domain, or creating a node, topic, publisher or subscription, failed.
#[derive(Debug, thiserror::Error)]
pub enum RosError {
    /// An interface address that is not a unicast address (`0.0.0.0`, a multicast group).
    #[error(
        "network.interfaces (--interface): {address} is not an interface address; give one of this host's unicast addresses, or none for every interface"
    )]
    InterfaceNotUnicast {
        /// The address given.
        address: IpAddr,
    },
    /// An interface address that no interface of this host holds (a socket cannot bind it).
    #[error(
        "network.interfaces (--interface): {address} is not an address of this host; give one of this host's addresses (`ip -brief address`), or none for every interface: {source}"
    )]
    InterfaceNotOnHost {
        /// The address given.
        address: IpAddr,
        /// The bind error.
        #[source]
        source: std::io::Error,
    },
    /// `ROS_DOMAIN_ID` is set but not a number.
    #[error("ROS_DOMAIN_ID='{text}' is not a number in 0..=232: {source}")]
    DomainIdNotANumber {
        /// The variable's value.
        text: String,
        /// The parse error.
        #[source]
        source: std::num::ParseIntError,
    },
    /// A domain id outside the range ROS 2 allows.
    #[error("ROS domain id {id} is outside 0..=232")]
    DomainIdOutOfRange {
        /// The id given.
        id: u16,
    },
    /// RustDDS could not create the domain participant.
    #[error("cannot create a DDS participant on domain {domain}: {source}")]
    Participant {
        /// The domain id.
        domain: u16,
        /// RustDDS's error.
        #[source]
        source: DdsCreateError,
    },
    /// The datagram guard is required and could not be attached to the participant's sockets
    /// (the participant is dropped: nothing was started).
    #[error(
        "cannot guard the DDS participant on domain {domain} against crafted datagrams: {reason}; nothing was started (--no-datagram-guard runs without the guard, docs/SECURITY.md)"
    )]
    DatagramGuard {
        /// The domain id.
        domain: u16,
        /// Which socket, and why.
        reason: String,
    },
    /// ros2-client could not create its context on the participant.
    #[error("cannot create the ROS 2 context: {source}")]
    Context {
        /// ros2-client's error.
        #[source]
        source: CreateError,
    },
    /// A node name ROS 2 does not accept.
    #[error("'{namespace}/{name}' is not a valid ROS 2 node name: {source}")]
    NodeName {
        /// The namespace given.
        namespace: String,
        /// The node's base name given.
        name: String,
        /// The rule it breaks.
        #[source]
        source: NameError,
    },
    /// ros2-client could not create the node.
    #[error("cannot create the ROS 2 node: {source}")]
    Node {
        /// ros2-client's error.
        #[source]
        source: NodeCreateError,
    },
    /// The node's spinner (its discovery and parameter task) could not start.
    #[error("cannot start the node's spinner: {source}")]
    Spinner {
        /// ros2-client's error.
        #[source]
        source: CreateError,
    },
    /// A topic name ROS 2 does not accept.
    #[error("'{topic}' is not a valid ROS 2 topic name: {source}")]
    TopicName {
        /// The topic as given.
        topic: String,
        /// The rule it breaks.
        #[source]
        source: NameError,
    },
    /// The DDS topic could not be created.
    #[error("cannot create topic {topic}: {source}")]
    Topic {
        /// The topic.
        topic: String,
        /// ros2-client's error.
        #[source]
        source: CreateError,
    },
    /// The publisher could not be created.
    #[error("cannot publish on {topic}: {source}")]
    Publisher {
        /// The topic.
        topic: String,
        /// ros2-client's error.
        #[source]
        source: CreateError,
    },
    /// The subscription could not be created.
    #[error("cannot subscribe to {topic}: {source}")]
    Subscription {
        /// The topic.
        topic: String,
        /// ros2-client's error.
        #[source]
        source: CreateError,
    },
    /// The service server could not be created.
    #[error("cannot offer the service {service}: {source}")]
    Service {
        /// The service.
        service: String,
        /// ros2-client's error.
        #[source]
        source: CreateError,
    },
    /// The discovery probe's sample counter task failed (panicked or was cancelled).
    #[error(transparent)]
    CounterTask {
        /// The task's error.
        #[from]
        source: tokio::task::JoinError,
    },
}
