//! QoS as configuration: reliability and keep-last depth per topic.
//!
//! RustDDS drops samples silently when a burst exceeds the history depth (even Reliable), so
//! depths are sized above any burst the rates allow (DOMAIN.md §7).

use ros2_client::QosProfile;
use ros2_client::qos::{History, Reliability as RosReliability, WhenFull};
use serde::{Deserialize, Serialize};

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
    pub fn validate(&self, key: &str) -> anyhow::Result<()> {
        if !(1..=10_000).contains(&self.depth) {
            anyhow::bail!("{key}.depth = {} must be in 1..=10000", self.depth);
        }
        Ok(())
    }

    /// The ros2-client profile.
    pub fn profile(&self) -> QosProfile {
        let profile = QosProfile::publisher_default().history(History::KeepLast {
            depth: self.depth as usize,
        });
        match self.reliability {
            Reliability::BestEffort => profile.reliability_best_effort(),
            Reliability::Reliable => profile.reliability(RosReliability::Reliable {
                when_full: WhenFull::DEFAULT,
            }),
        }
    }
}
