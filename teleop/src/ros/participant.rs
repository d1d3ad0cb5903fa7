//! The DDS participant: domain id (configuration, else `ROS_DOMAIN_ID`, else 0) and which
//! network interfaces discovery may use.
//!
//! ros2-client does not read `ROS_DOMAIN_ID` itself; the station does, here, as ROS tools do.
//!
//! What RustDDS 0.15 offers for the network side, and so all the station can configure:
//! the domain id, and the local addresses whose interfaces carry SPDP multicast (joined, sent)
//! and are announced as this participant's unicast locators (`with_only_networks`; the
//! unicast sockets still bind to every address). Discovery is SPDP multicast on 239.255.0.1
//! plus loopback unicast to same-host participants; RustDDS has no list of unicast
//! (initial) peers, so hosts on a network that drops multicast do not discover each other
//! (docs/DEPLOYMENT.md).

use std::net::IpAddr;

use ros2_client::Context;
use ros2_client::dds::rustdds::DomainParticipantBuilder;
use station::NetworkConfig;

use crate::ros::{RosError, datagram_guard, domain_lease, participant_guard};

/// Check that `address` can restrict DDS to an interface of this host: a unicast address
/// one of its interfaces holds (a UDP socket binds to it).
pub fn check_interface_address(address: IpAddr) -> Result<(), RosError> {
    if address.is_unspecified() || address.is_multicast() {
        return Err(RosError::InterfaceNotUnicast { address });
    }
    std::net::UdpSocket::bind((address, 0))
        .map_err(|source| RosError::InterfaceNotOnHost { address, source })?;
    Ok(())
}

/// The effective domain id: `configured`, else the `ROS_DOMAIN_ID` environment variable (the
/// ROS convention), else 0. Rejects ids outside 0–232 (the range ROS 2 allows).
pub fn domain_id(configured: Option<u16>) -> Result<u16, RosError> {
    let id = match configured {
        Some(id) => id,
        None => match std::env::var("ROS_DOMAIN_ID") {
            Ok(text) if !text.trim().is_empty() => text
                .trim()
                .parse()
                .map_err(|source| RosError::DomainIdNotANumber { text, source })?,
            _ => 0,
        },
    };
    if id > 232 {
        return Err(RosError::DomainIdOutOfRange { id });
    }
    Ok(id)
}

/// The DDS participant of a [`NetworkConfig`].
pub trait NetworkContext {
    /// Create the ROS 2 context (one DDS participant) for this configuration.
    fn context(&self) -> Result<Context, RosError>;
}

impl NetworkContext for NetworkConfig {
    fn context(&self) -> Result<Context, RosError> {
        let domain = domain_id(self.domain_id)?;
        let mut builder = DomainParticipantBuilder::new(domain);
        for address in &self.interfaces {
            check_interface_address(*address)?;
        }
        if !self.interfaces.is_empty() {
            builder = builder.with_only_networks(self.interfaces.iter().copied());
        }
        let guard = participant_guard::required();
        let before = match guard {
            true => participant_guard::socket_inodes().map_err(|e| RosError::DatagramGuard {
                domain,
                reason: format!("cannot list this process's sockets: {e}"),
            })?,
            false => Default::default(),
        };
        let participant = builder
            .build()
            .map_err(|source| RosError::Participant { domain, source })?;
        if guard {
            let port = datagram_guard::unicast_discovery_port(domain, participant.participant_id());
            let guarded = participant_guard::guard_new_sockets(&before, port)
                .map_err(|reason| RosError::DatagramGuard { domain, reason })?;
            log::debug!("RTPS datagram guard on {guarded} sockets");
        }
        Context::from_domain_participant(participant).map_err(|source| RosError::Context { source })
    }
}

/// The default domain id of an all-in-one run (the demo, a simulated trial or calibration):
/// away from 0 (the lab's usual), leased so that no other run on this machine has it
/// ([`domain_lease`]); where no lease can be taken (an unwritable temporary directory, every
/// id held), one chosen by the process id, with a note on stderr.
pub fn default_domain_id() -> u16 {
    let range = domain_lease::ALL_IN_ONE_DOMAINS;
    domain_lease::lease_domain(range.clone()).unwrap_or_else(|e| {
        let span = u32::from(range.end() - range.start()) + 1;
        let id = range.start() + (std::process::id() % span) as u16;
        eprintln!("note: {e}; using domain {id}");
        id
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn configured_domain_ids_are_checked() {
        assert_eq!(domain_id(Some(232)).unwrap(), 232);
        let err = domain_id(Some(233)).unwrap_err();
        assert_eq!(err.to_string(), "ROS domain id 233 is outside 0..=232");
    }

    #[test]
    fn interface_addresses_must_belong_to_this_host() {
        check_interface_address(IpAddr::from([127, 0, 0, 1])).unwrap();
        // TEST-NET-3 (RFC 5737): documentation only, never assigned to a host.
        let err = check_interface_address(IpAddr::from([203, 0, 113, 77])).unwrap_err();
        let text = err.to_string();
        assert!(text.contains("network.interfaces"), "{text}");
        assert!(
            text.contains("203.0.113.77 is not an address of this host"),
            "{text}"
        );
        let err = check_interface_address(IpAddr::from([0, 0, 0, 0])).unwrap_err();
        assert!(
            err.to_string().contains("not an interface address"),
            "{err}"
        );
        let err = check_interface_address(IpAddr::from([239, 255, 0, 1])).unwrap_err();
        assert!(
            err.to_string().contains("not an interface address"),
            "{err}"
        );
    }
}
