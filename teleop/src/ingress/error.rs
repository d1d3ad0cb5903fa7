//! The glove ingress's one error type: its settings (each error names the key, and the file
//! when read from one), its UDP socket and its ROS node.

use std::net::IpAddr;
use std::path::PathBuf;

use retarget::KeypointLayout;

use crate::ros::RosError;

/// The ingress's settings are not valid, or the node cannot start or run.
#[derive(Debug, thiserror::Error)]
pub enum IngressError {
    /// The settings file cannot be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// The settings in a file are not valid.
    #[error("{path}: {source}")]
    InFile {
        /// The file.
        path: PathBuf,
        /// What is wrong, by key.
        #[source]
        source: Box<IngressError>,
    },
    /// The settings are not TOML of the expected shape (an unknown key, a value of the wrong
    /// type or out of its type's range).
    #[error("{reason}")]
    Syntax {
        /// The parser's message (names the key and the line), trailing whitespace trimmed.
        reason: String,
    },
    /// A keypoint layout this ingress does not produce.
    #[error("layout = '{layout}' is not produced by this ingress (allowed: lab22, lab21)")]
    Layout {
        /// The layout given.
        layout: KeypointLayout,
    },
    /// A position scale out of range.
    #[error("position_scale_to_m = {scale} must be in [0.0001, 10]")]
    PositionScale {
        /// The scale given.
        scale: f64,
    },
    /// A packet size limit out of range.
    #[error("max_packet_bytes = {bytes} must be in 256..=65507")]
    MaxPacketBytes {
        /// The limit given.
        bytes: usize,
    },
    /// A restart threshold out of range.
    #[error("restart_after_backwards_s = {seconds} must be in (0, 3600]")]
    RestartAfterBackwards {
        /// The threshold given, seconds.
        seconds: f64,
    },
    /// A restart confirmation count out of range.
    #[error(
        "restart_confirm_packets = {packets} must be in 2..=1000 (one packet must never reset the order)"
    )]
    RestartConfirmPackets {
        /// The count given.
        packets: u32,
    },
    /// An entry of `allowed_senders` that is not an address.
    #[error(
        "allowed_senders[{index}] = '{value}': {reason} (allowed: an IP address such as \"10.251.0.1\", \
         or address and source port such as \"10.251.0.1:50000\" or \"[fd00::1]:50000\")"
    )]
    AllowedSender {
        /// Its place in the list.
        index: usize,
        /// The entry.
        value: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A topic name that is not absolute.
    #[error("{key} = '{topic}' must be an absolute topic name (start with '/')")]
    RelativeTopic {
        /// The setting.
        key: &'static str,
        /// The topic given.
        topic: String,
    },
    /// A headset address that cannot be used.
    #[error("address '{address}': {reason}")]
    Address {
        /// The address given.
        address: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A duration out of range.
    #[error("{key} = {value} must be in [{}, {}] seconds", range.0, range.1)]
    Seconds {
        /// The setting.
        key: &'static str,
        /// The value given.
        value: f64,
        /// The allowed range.
        range: (f64, f64),
    },
    /// A message size limit out of range.
    #[error("max_message_bytes = {bytes} must be in 1024..=16777216")]
    MaxMessageBytes {
        /// The limit given.
        bytes: usize,
    },
    /// An actor name that is empty.
    #[error("actor = '' must be a name, or be left out to follow the first actor")]
    EmptyActor,
    /// The QoS settings are not valid.
    #[error(transparent)]
    Qos(#[from] station::ConfigError),
    /// The DDS domain id is not valid.
    #[error("network.domain_id: {source}")]
    DomainId {
        /// What is wrong with it.
        #[source]
        source: RosError,
    },
    /// The UDP socket cannot be bound.
    #[error("cannot listen on UDP {address}:{port} (is another ingress running?): {source}")]
    Bind {
        /// The local address.
        address: IpAddr,
        /// The port.
        port: u16,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// The bound socket's local address cannot be read.
    #[error(transparent)]
    LocalAddress {
        /// The OS error.
        source: std::io::Error,
    },
    /// Joining the DDS domain, or creating the node or a publisher, failed.
    #[error(transparent)]
    Ros(#[from] RosError),
    /// A frame's keypoints do not fit a ROS point matrix.
    #[error(transparent)]
    Keypoints(#[from] msgs::Error),
}
