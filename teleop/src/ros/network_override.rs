//! The network settings a command line lays over a configuration's: `--domain-id` and
//! `--interface`, each replacing the configuration's only when given.

use std::net::IpAddr;

use super::NetworkConfig;

/// A domain id and interfaces asked for on the command line (none: the configuration's).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct NetworkOverride {
    /// The domain id asked for.
    pub domain_id: Option<u16>,
    /// The interfaces asked for (empty: the configuration's).
    pub interfaces: Vec<IpAddr>,
}

impl NetworkOverride {
    /// `base` with what was asked for laid over it.
    pub fn apply(&self, base: &NetworkConfig) -> NetworkConfig {
        NetworkConfig {
            domain_id: self.domain_id.or(base.domain_id),
            interfaces: if self.interfaces.is_empty() {
                base.interfaces.clone()
            } else {
                self.interfaces.clone()
            },
        }
    }
}
