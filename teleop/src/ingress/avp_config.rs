//! The Apple Vision Pro ingress's configuration (`launch_configs/ingress/avp.toml` spells out
//! the defaults).

use std::path::Path;
use std::time::Duration;

use retarget::KeypointLayout;
use serde::{Deserialize, Serialize};

use crate::ingress::error::IngressError;
use crate::ingress::ingress_config::{Hand, check_topics, parse_settings, read_settings};
use crate::ros::{NetworkConfig, QosConfig};

/// The app's gRPC port.
pub const DEFAULT_PORT: u16 = 12345;

/// Settings of `pomdar ingress avp`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AvpConfig {
    /// The headset's address (host name or IP), without the port; empty: must be given with
    /// `--address`.
    pub address: String,
    /// The app's gRPC port (12345).
    pub port: u16,
    /// Which hand to publish.
    pub hand: Hand,
    /// Keypoint layout published: `lab22` (with the forearm point) or `lab21`.
    pub layout: KeypointLayout,
    /// Give up one connection attempt after this long, seconds.
    pub connect_timeout_s: f64,
    /// First wait before reconnecting after the headset went away, seconds (doubles each
    /// failed attempt up to `reconnect_max_s`; back to this after a stream delivered).
    pub reconnect_min_s: f64,
    /// Longest wait between reconnection attempts, seconds.
    pub reconnect_max_s: f64,
    /// A streamed message larger than this ends the stream (counted; reconnected), bytes. One
    /// update with both hands' 27 joints is about 4.6 kB.
    pub max_message_bytes: usize,
    /// Keypoint topic (`std_msgs/Float32MultiArray`, N × 3 metres).
    pub keypoints_topic: String,
    /// Wrist topic (`geometry_msgs/PoseStamped`, stamped at receipt).
    pub wrist_topic: String,
    /// The wrist pose's `frame_id`: ARKit's world turned to ROS axes.
    pub wrist_frame_id: String,
    /// Status topic (`std_msgs/String`, JSON once a second: rate, counts, drops by kind).
    pub status_topic: String,
    /// QoS of the keypoint and wrist topics.
    pub qos: QosConfig,
    /// DDS domain and interfaces.
    pub network: NetworkConfig,
}

impl Default for AvpConfig {
    fn default() -> Self {
        AvpConfig {
            address: String::new(),
            port: DEFAULT_PORT,
            hand: Hand::Right,
            layout: KeypointLayout::Lab22,
            connect_timeout_s: 2.0,
            reconnect_min_s: 0.25,
            reconnect_max_s: 4.0,
            max_message_bytes: 65_536,
            keypoints_topic: "/ingress/mano".into(),
            wrist_topic: "/ingress/wrist".into(),
            wrist_frame_id: "avp_world".into(),
            status_topic: "/ingress/status".into(),
            qos: QosConfig::best_effort(400),
            network: NetworkConfig::default(),
        }
    }
}

impl AvpConfig {
    /// Parse and validate (the address may be left to the command line).
    pub fn from_toml_str(text: &str) -> Result<AvpConfig, IngressError> {
        let config: AvpConfig = parse_settings(text)?;
        config.validate_settings()?;
        Ok(config)
    }

    /// Read, parse and validate a file; errors name it.
    pub fn from_file(path: &Path) -> Result<AvpConfig, IngressError> {
        read_settings(path, AvpConfig::from_toml_str)
    }

    /// Take `HOST` or `HOST:PORT` (an IPv6 address in brackets with a port: `[::1]:12345`).
    pub fn set_address(&mut self, given: &str) -> Result<(), IngressError> {
        let bad = |reason: &str| IngressError::Address {
            address: given.to_string(),
            reason: reason.to_string(),
        };
        let (host, port) = match given.rsplit_once(':') {
            Some((host, port)) if !host.contains(':') || host.ends_with(']') => {
                let port = port
                    .parse::<u16>()
                    .map_err(|_| bad("the port is not in 1..=65535"))?;
                (
                    host.trim_start_matches('[').trim_end_matches(']'),
                    Some(port),
                )
            }
            _ => (given, None),
        };
        if host.is_empty() || host.chars().any(char::is_whitespace) {
            return Err(bad("expected HOST or HOST:PORT"));
        }
        self.address = host.to_string();
        self.port = port.unwrap_or(self.port);
        Ok(())
    }

    /// The URI tonic connects to.
    pub fn uri(&self) -> String {
        if self.address.contains(':') {
            format!("http://[{}]:{}", self.address, self.port)
        } else {
            format!("http://{}:{}", self.address, self.port)
        }
    }

    /// The device as the status and the trial logs name it.
    pub fn device(&self) -> String {
        format!("Apple Vision Pro at {}:{}", self.address, self.port)
    }

    /// The connection timeout.
    pub fn connect_timeout(&self) -> Duration {
        Duration::from_secs_f64(self.connect_timeout_s)
    }

    /// Check every value (an address is required); errors name the key and the range.
    pub fn validate(&self) -> Result<(), IngressError> {
        if self.address.is_empty() {
            return Err(IngressError::Address {
                address: String::new(),
                reason: "no headset address: give --address HOST[:PORT] or address = \"HOST\""
                    .into(),
            });
        }
        self.validate_settings()
    }

    /// Check every value but the address (a file may leave it to the command line).
    fn validate_settings(&self) -> Result<(), IngressError> {
        if !matches!(self.layout, KeypointLayout::Lab22 | KeypointLayout::Lab21) {
            return Err(IngressError::Layout {
                layout: self.layout,
            });
        }
        if self.port == 0 {
            return Err(IngressError::Address {
                address: format!("{}:0", self.address),
                reason: "port must be in 1..=65535".into(),
            });
        }
        for (key, value, range) in [
            ("connect_timeout_s", self.connect_timeout_s, (0.05, 60.0)),
            ("reconnect_min_s", self.reconnect_min_s, (0.01, 60.0)),
            (
                "reconnect_max_s",
                self.reconnect_max_s,
                (self.reconnect_min_s, 600.0),
            ),
        ] {
            if !(value.is_finite() && value >= range.0 && value <= range.1) {
                return Err(IngressError::Seconds { key, value, range });
            }
        }
        if !(1024..=16 << 20).contains(&self.max_message_bytes) {
            return Err(IngressError::MaxMessageBytes {
                bytes: self.max_message_bytes,
            });
        }
        check_topics([
            ("keypoints_topic", &self.keypoints_topic),
            ("wrist_topic", &self.wrist_topic),
            ("status_topic", &self.status_topic),
        ])?;
        self.qos.validate("qos")?;
        crate::ros::domain_id(self.network.domain_id)
            .map_err(|source| IngressError::DomainId { source })?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shipped_file_is_the_defaults() {
        let text = include_str!("../../../launch_configs/ingress/avp.toml");
        assert_eq!(
            AvpConfig::from_toml_str(text).unwrap(),
            AvpConfig::default()
        );
    }

    #[test]
    fn addresses_take_an_optional_port() {
        let mut c = AvpConfig::default();
        c.set_address("10.0.0.7").unwrap();
        assert_eq!(
            (c.address.as_str(), c.port, c.uri().as_str()),
            ("10.0.0.7", 12345, "http://10.0.0.7:12345")
        );
        c.set_address("vision.local:5000").unwrap();
        assert_eq!((c.address.as_str(), c.port), ("vision.local", 5000));
        c.set_address("[::1]:7000").unwrap();
        assert_eq!(
            (c.address.as_str(), c.port, c.uri().as_str()),
            ("::1", 7000, "http://[::1]:7000")
        );
        for bad in ["", "host:99999", "host:x", "a b"] {
            let e = c.set_address(bad).unwrap_err().to_string();
            assert!(e.contains(&format!("'{bad}'")), "{bad}: {e}");
        }
        assert!(
            AvpConfig::default()
                .validate()
                .unwrap_err()
                .to_string()
                .contains("--address")
        );
    }

    #[test]
    fn bad_values_name_their_key() {
        for (text, key) in [
            ("layout = \"mediapipe21\"", "layout"),
            ("connect_timeout_s = 0.0", "connect_timeout_s"),
            ("reconnect_min_s = -1.0", "reconnect_min_s"),
            ("reconnect_max_s = 0.1", "reconnect_max_s"),
            ("max_message_bytes = 10", "max_message_bytes"),
            ("status_topic = \"status\"", "status_topic"),
            (
                "qos = { reliability = \"reliable\", depth = 0 }",
                "qos.depth",
            ),
            ("colour = 1", "colour"),
        ] {
            let e = AvpConfig::from_toml_str(text).unwrap_err().to_string();
            assert!(e.contains(key), "{text}: {e}");
        }
    }
}
