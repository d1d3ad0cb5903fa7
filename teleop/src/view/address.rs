//! Where the live view listens: `--view [ADDR:]PORT`.

use std::fmt;
use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::str::FromStr;

/// The address the live view's WebSocket server binds: loopback unless an address is given
/// (`0.0.0.0` or `[::]` only when asked for explicitly). Port 0 picks a free port.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ViewAddress(pub SocketAddr);

impl ViewAddress {
    /// The default port of Foxglove WebSocket servers.
    pub const DEFAULT_PORT: u16 = 8765;

    /// `127.0.0.1:port`.
    pub fn loopback(port: u16) -> ViewAddress {
        ViewAddress(SocketAddr::new(IpAddr::V4(Ipv4Addr::LOCALHOST), port))
    }
}

/// Why a `--view` value is not `[ADDR:]PORT`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "`{value}` is not [ADDR:]PORT (a port such as 8765, or an IP address and port such as \
     127.0.0.1:8765, 0.0.0.0:8765 or [::1]:8765)"
)]
pub struct ViewAddressError {
    /// The value given.
    pub value: String,
}

impl FromStr for ViewAddress {
    type Err = ViewAddressError;

    fn from_str(value: &str) -> Result<ViewAddress, ViewAddressError> {
        let error = || ViewAddressError {
            value: value.to_string(),
        };
        let trimmed = value.trim();
        if let Ok(port) = trimmed.parse::<u16>() {
            return Ok(ViewAddress::loopback(port));
        }
        trimmed
            .parse::<SocketAddr>()
            .map(ViewAddress)
            .map_err(|_| error())
    }
}

impl fmt::Display for ViewAddress {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    #[test]
    fn a_bare_port_is_loopback() {
        let a: ViewAddress = "8765".parse().unwrap();
        assert_eq!(a.to_string(), "127.0.0.1:8765");
        assert_eq!(
            "0".parse::<ViewAddress>().unwrap(),
            ViewAddress::loopback(0)
        );
    }

    #[test]
    fn an_address_is_taken_as_given() {
        assert_eq!(
            "0.0.0.0:9000".parse::<ViewAddress>().unwrap().to_string(),
            "0.0.0.0:9000"
        );
        assert_eq!(
            "[::1]:8765".parse::<ViewAddress>().unwrap().to_string(),
            "[::1]:8765"
        );
    }

    #[test]
    fn anything_else_is_refused_with_the_value() {
        for bad in ["", "localhost:8765", "65536", "127.0.0.1", ":8765", "8765x"] {
            let e = bad.parse::<ViewAddress>().unwrap_err();
            assert!(e.to_string().contains(&format!("`{bad}`")), "{e}");
        }
    }
}
