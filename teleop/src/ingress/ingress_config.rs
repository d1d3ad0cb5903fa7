//! The Rokoko ingress's configuration (`launch_configs/ingress/rokoko.toml` spells out the
//! defaults).

use std::net::{IpAddr, SocketAddr};
use std::path::Path;

use retarget::KeypointLayout;
use serde::{Deserialize, Serialize};

use crate::ingress::error::IngressError;
use crate::ros::{NetworkConfig, QosConfig};

/// Which glove hand to publish.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "snake_case")]
pub enum Hand {
    /// The `right*` bones.
    Right,
    /// The `left*` bones, published as they are (in the same frame, not mirrored).
    Left,
}

impl Hand {
    /// The bone-name prefix.
    pub fn bone_prefix(self) -> &'static str {
        match self {
            Hand::Right => "right",
            Hand::Left => "left",
        }
    }
}

/// Settings of `pomdar ingress rokoko`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct IngressConfig {
    /// Local address to listen on: the address of the interface Studio's packets arrive on
    /// (127.0.0.1, the default: this computer only; 0.0.0.0: every interface).
    pub bind_address: IpAddr,
    /// Senders whose datagrams are taken, each `"ADDRESS"` or `"ADDRESS:PORT"` (IPv6:
    /// `"[ADDRESS]:PORT"`); datagrams from anyone else are dropped and counted as
    /// `refused.sender`. Empty (the default): any sender that can reach `bind_address`.
    pub allowed_senders: Vec<String>,
    /// UDP port Rokoko Studio streams to (14043 by convention).
    pub port: u16,
    /// The actor to follow, by name; unset: the first actor of each packet.
    pub actor: Option<String>,
    /// Which hand's bones.
    pub hand: Hand,
    /// Keypoint layout published: `lab22` (with the forearm point) or `lab21`.
    pub layout: KeypointLayout,
    /// Multiplier from the stream's position unit to metres (1.0: the stream is in metres,
    /// which the vendor does not confirm: docs/LAB_CONVENTIONS.md §2; 0.01 if a studio streams centimetres).
    pub position_scale_to_m: f64,
    /// Packets larger than this are refused, bytes (one UDP datagram is at most 65507).
    pub max_packet_bytes: usize,
    /// A `scene.timestamp` this much older than the newest one seen is taken for a
    /// restarted stream (accepted, counted) rather than an out-of-order packet (dropped),
    /// seconds.
    pub restart_after_backwards_s: f64,
    /// How many such packets in a row (rising, each within `restart_after_backwards_s` of the
    /// one before, no packet of the current stream between them) confirm a restart; the ones
    /// before the last are dropped (`restart_unconfirmed`). At least 2: one packet never
    /// resets the order.
    pub restart_confirm_packets: u32,
    /// Keypoint topic (`std_msgs/Float32MultiArray`, N × 3 metres).
    pub keypoints_topic: String,
    /// Wrist topic (`geometry_msgs/PoseStamped`, stamped at receipt).
    pub wrist_topic: String,
    /// The wrist pose's `frame_id`: ROS's right-handed version of Rokoko Studio's world.
    pub wrist_frame_id: String,
    /// Status topic (`std_msgs/String`, JSON once a second: rate, counts, drops by kind).
    pub status_topic: String,
    /// QoS of the keypoint and wrist topics.
    pub qos: QosConfig,
    /// DDS domain and interfaces.
    pub network: NetworkConfig,
}

impl Default for IngressConfig {
    fn default() -> Self {
        IngressConfig {
            bind_address: IpAddr::from([127, 0, 0, 1]),
            allowed_senders: Vec::new(),
            port: 14043,
            actor: None,
            hand: Hand::Right,
            layout: KeypointLayout::Lab22,
            position_scale_to_m: 1.0,
            max_packet_bytes: 65_507,
            restart_after_backwards_s: 1.0,
            restart_confirm_packets: 5,
            keypoints_topic: "/ingress/mano".into(),
            wrist_topic: "/ingress/wrist".into(),
            wrist_frame_id: "rokoko_world".into(),
            status_topic: "/ingress/status".into(),
            qos: QosConfig::best_effort(400),
            network: NetworkConfig::default(),
        }
    }
}

impl IngressConfig {
    /// Parse and validate.
    pub fn from_toml_str(text: &str) -> Result<IngressConfig, IngressError> {
        let config: IngressConfig = parse_settings(text)?;
        config.validate()?;
        Ok(config)
    }

    /// Read, parse and validate a file; errors name it.
    pub fn from_file(path: &Path) -> Result<IngressConfig, IngressError> {
        read_settings(path, IngressConfig::from_toml_str)
    }

    /// Check every value; errors name the key and the allowed range.
    pub fn validate(&self) -> Result<(), IngressError> {
        if !matches!(self.layout, KeypointLayout::Lab22 | KeypointLayout::Lab21) {
            return Err(IngressError::Layout {
                layout: self.layout,
            });
        }
        let scale = self.position_scale_to_m;
        if !(scale.is_finite() && (1e-4..=10.0).contains(&scale)) {
            return Err(IngressError::PositionScale { scale });
        }
        if !(256..=65_507).contains(&self.max_packet_bytes) {
            return Err(IngressError::MaxPacketBytes {
                bytes: self.max_packet_bytes,
            });
        }
        let seconds = self.restart_after_backwards_s;
        if !(seconds.is_finite() && seconds > 0.0 && seconds <= 3600.0) {
            return Err(IngressError::RestartAfterBackwards { seconds });
        }
        if !(2..=1000).contains(&self.restart_confirm_packets) {
            return Err(IngressError::RestartConfirmPackets {
                packets: self.restart_confirm_packets,
            });
        }
        self.senders()?;
        check_topics([
            ("keypoints_topic", &self.keypoints_topic),
            ("wrist_topic", &self.wrist_topic),
            ("status_topic", &self.status_topic),
        ])?;
        if let Some(actor) = &self.actor
            && actor.trim().is_empty()
        {
            return Err(IngressError::EmptyActor);
        }
        self.qos.validate("qos")?;
        crate::ros::domain_id(self.network.domain_id)
            .map_err(|source| IngressError::DomainId { source })?;
        Ok(())
    }
}

impl IngressConfig {
    /// The allowed senders, parsed; an entry that is not an address names its place.
    pub fn senders(&self) -> Result<Vec<AllowedSender>, IngressError> {
        self.allowed_senders
            .iter()
            .enumerate()
            .map(|(index, text)| {
                AllowedSender::parse(text).map_err(|reason| IngressError::AllowedSender {
                    index,
                    value: text.clone(),
                    reason,
                })
            })
            .collect()
    }
}

/// One entry of `allowed_senders`: an address, and the port when one was given.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AllowedSender {
    /// The sender's address.
    pub address: IpAddr,
    /// The sender's UDP source port; `None`: any port.
    pub port: Option<u16>,
}

impl AllowedSender {
    /// `"10.251.0.1"`, `"10.251.0.1:50000"`, `"::1"` or `"[::1]:50000"`; no host names.
    pub fn parse(text: &str) -> Result<AllowedSender, String> {
        let text = text.trim();
        if let Ok(address) = text.parse::<IpAddr>() {
            return Ok(AllowedSender {
                address,
                port: None,
            });
        }
        match text.parse::<SocketAddr>() {
            Ok(s) if s.port() == 0 => Err("port 0 is no sender's port".to_string()),
            Ok(s) => Ok(AllowedSender {
                address: s.ip(),
                port: Some(s.port()),
            }),
            Err(_) => Err("not an IP address or IP:PORT (host names are not resolved)".to_string()),
        }
    }

    /// Whether a datagram from `from` is this sender's (IPv4-mapped IPv6 addresses match
    /// their IPv4 form).
    pub fn matches(&self, from: SocketAddr) -> bool {
        from.ip().to_canonical() == self.address.to_canonical()
            && self.port.is_none_or(|p| p == from.port())
    }
}

/// TOML text to settings of type `T` (unknown keys and wrong types named by the parser).
pub(crate) fn parse_settings<T: serde::de::DeserializeOwned>(
    text: &str,
) -> Result<T, IngressError> {
    toml::from_str(text).map_err(|e| IngressError::Syntax {
        reason: e.to_string().trim_end().to_string(),
    })
}

/// Read `path` and parse it with `parse`; errors name the file.
pub(crate) fn read_settings<T>(
    path: &Path,
    parse: impl FnOnce(&str) -> Result<T, IngressError>,
) -> Result<T, IngressError> {
    let text = std::fs::read_to_string(path).map_err(|source| IngressError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    parse(&text).map_err(|e| IngressError::InFile {
        path: path.to_path_buf(),
        source: Box::new(e),
    })
}

/// Every topic named must be absolute.
pub(crate) fn check_topics<'a>(
    topics: impl IntoIterator<Item = (&'static str, &'a String)>,
) -> Result<(), IngressError> {
    for (key, topic) in topics {
        if !topic.starts_with('/') {
            return Err(IngressError::RelativeTopic {
                key,
                topic: topic.clone(),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shipped_file_is_the_defaults() {
        let text = include_str!("../../../launch_configs/ingress/rokoko.toml");
        assert_eq!(
            IngressConfig::from_toml_str(text).unwrap(),
            IngressConfig::default()
        );
    }

    #[test]
    fn bad_values_name_their_key() {
        for (text, key) in [
            ("layout = \"mediapipe21\"", "layout"),
            ("position_scale_to_m = 0.0", "position_scale_to_m"),
            ("max_packet_bytes = 100000", "max_packet_bytes"),
            ("keypoints_topic = \"mano\"", "keypoints_topic"),
            ("actor = \" \"", "actor"),
            (
                "restart_after_backwards_s = -1.0",
                "restart_after_backwards_s",
            ),
            (
                "qos = { reliability = \"reliable\", depth = 0 }",
                "qos.depth",
            ),
            ("port = 70000", "port"),
            ("restart_confirm_packets = 1", "restart_confirm_packets"),
            ("allowed_senders = [\"studio-pc\"]", "allowed_senders[0]"),
            (
                "allowed_senders = [\"10.251.0.1\", \"10.251.0.1:0\"]",
                "allowed_senders[1]",
            ),
            ("allowed_senders = \"10.251.0.1\"", "allowed_senders"),
            ("bind_address = \"lab\"", "bind_address"),
            ("colour = 1", "colour"),
        ] {
            let e = IngressConfig::from_toml_str(text).unwrap_err().to_string();
            assert!(e.contains(key), "{text}: {e}");
        }
    }

    #[test]
    fn allowed_senders_match_address_and_port() {
        let by_address = AllowedSender::parse("10.251.0.1").unwrap();
        let by_port = AllowedSender::parse("10.251.0.1:50000").unwrap();
        let v6 = AllowedSender::parse("[::1]:7").unwrap();
        let from = |s: &str| s.parse::<SocketAddr>().unwrap();
        assert!(by_address.matches(from("10.251.0.1:1234")));
        assert!(by_address.matches(from("[::ffff:10.251.0.1]:1234")));
        assert!(!by_address.matches(from("10.251.0.9:1234")));
        assert!(by_port.matches(from("10.251.0.1:50000")));
        assert!(!by_port.matches(from("10.251.0.1:50001")));
        assert!(v6.matches(from("[::1]:7")));
        let e = IngressConfig::from_toml_str("allowed_senders = [\"x\"]")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("allowed_senders[0] = 'x'") && e.contains("10.251.0.1"),
            "{e}"
        );
    }
}
