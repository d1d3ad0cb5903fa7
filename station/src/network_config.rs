//! The network side of a station configuration, as data: the DDS domain, the interfaces, and
//! each topic's QoS. The application turns it into a DDS participant and QoS profiles.
//!
//! RustDDS drops samples silently when a burst exceeds the history depth (even Reliable), so
//! depths are sized above any burst the rates allow (docs/LAB_CONVENTIONS.md §5).

use core::net::IpAddr; // an address as data (no socket): the core one

use serde::{Deserialize, Serialize};

use crate::config_error::ConfigError;

/// Highest DDS domain id ROS 2 allows.
pub const MAX_DOMAIN_ID: u16 = 232;

/// DDS domain and interfaces.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct NetworkConfig {
    /// DDS domain id (0–232). Unset: `ROS_DOMAIN_ID`, else 0.
    pub domain_id: Option<u16>,
    /// Restrict discovery to these local addresses (for example `["127.0.0.1"]` for a
    /// loopback-only test, or one interface of a multi-homed lab PC). Empty: all interfaces.
    /// Each must be an address of this host (checked when the participant is created).
    pub interfaces: Vec<IpAddr>,
}

impl NetworkConfig {
    /// Check the domain id's range (the interfaces are checked against the host when the
    /// participant is created).
    pub fn validate(&self) -> Result<(), ConfigError> {
        match self.domain_id {
            Some(id) if id > MAX_DOMAIN_ID => Err(ConfigError::out_of_range(
                "network.domain_id",
                id,
                format!("in 0..={MAX_DOMAIN_ID}"),
            )),
            _ => Ok(()),
        }
    }
}

/// Delivery guarantee.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Reliability {
    /// Newest data wins; nothing is resent (sensor streams).
    BestEffort,
    /// Resent until acknowledged (commands, events).
    Reliable,
}

/// One topic's QoS.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct QosConfig {
    /// Delivery guarantee.
    pub reliability: Reliability,
    /// Keep-last history depth (1–10000).
    pub depth: u32,
}

impl QosConfig {
    /// Reliable, keep last `depth`.
    pub const fn reliable(depth: u32) -> QosConfig {
        QosConfig {
            reliability: Reliability::Reliable,
            depth,
        }
    }

    /// Best effort, keep last `depth`.
    pub const fn best_effort(depth: u32) -> QosConfig {
        QosConfig {
            reliability: Reliability::BestEffort,
            depth,
        }
    }

    /// Check the depth range; the error names `key`.
    pub fn validate(&self, key: &str) -> Result<(), ConfigError> {
        if !(1..=10_000).contains(&self.depth) {
            return Err(ConfigError::out_of_range(
                format!("{key}.depth"),
                self.depth,
                "in 1..=10000",
            ));
        }
        Ok(())
    }
}
