//! QoS as configuration: reliability and keep-last depth per topic.
//!
//! RustDDS drops samples silently when a burst exceeds the history depth (even Reliable), so
//! depths are sized above any burst the rates allow (docs/LAB_CONVENTIONS.md §5).

use ros2_client::QosProfile;
use ros2_client::qos::{History, Reliability as RosReliability, WhenFull};
use station::{QosConfig, Reliability};

/// The ros2-client profile of a [`QosConfig`].
pub trait QosProfileOf {
    /// The ros2-client profile.
    fn profile(&self) -> QosProfile;
}

impl QosProfileOf for QosConfig {
    fn profile(&self) -> QosProfile {
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
