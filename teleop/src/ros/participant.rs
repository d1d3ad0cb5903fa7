//! The DDS participant: domain id (configuration, else `ROS_DOMAIN_ID`, else 0) and which
//! network interfaces discovery may use.
//!
//! ros2-client does not read `ROS_DOMAIN_ID` itself; the station does, here, as ROS tools do.

use std::net::IpAddr;

use anyhow::{Context as _, bail};
use ros2_client::Context;
use ros2_client::dds::rustdds::DomainParticipantBuilder;
use serde::{Deserialize, Serialize};

/// Network side of the participant.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct NetworkConfig {
    /// DDS domain id (0–232). Unset: `ROS_DOMAIN_ID`, else 0.
    pub domain_id: Option<u16>,
    /// Restrict discovery to these local addresses (for example `["127.0.0.1"]` for a
    /// loopback-only test, or one interface of a multi-homed lab PC). Empty: all interfaces.
    pub interfaces: Vec<IpAddr>,
}

/// The effective domain id: `configured`, else the `ROS_DOMAIN_ID` environment variable (the
/// ROS convention), else 0. Rejects ids outside 0–232 (the range ROS 2 allows).
pub fn domain_id(configured: Option<u16>) -> anyhow::Result<u16> {
    let id = match configured {
        Some(id) => id,
        None => match std::env::var("ROS_DOMAIN_ID") {
            Ok(text) if !text.trim().is_empty() => text
                .trim()
                .parse()
                .with_context(|| format!("ROS_DOMAIN_ID='{text}' is not a number in 0..=232"))?,
            _ => 0,
        },
    };
    if id > 232 {
        bail!("ROS domain id {id} is outside 0..=232");
    }
    Ok(id)
}

impl NetworkConfig {
    /// Create the ROS 2 context (one DDS participant) for this configuration.
    pub fn context(&self) -> anyhow::Result<Context> {
        let domain = domain_id(self.domain_id)?;
        let mut builder = DomainParticipantBuilder::new(domain);
        if !self.interfaces.is_empty() {
            builder = builder.with_only_networks(self.interfaces.iter().copied());
        }
        let participant = builder
            .build()
            .with_context(|| format!("cannot create a DDS participant on domain {domain}"))?;
        Context::from_domain_participant(participant).context("cannot create the ROS 2 context")
    }
}
