//! What can go wrong starting the live view.

use std::net::SocketAddr;

/// The live view could not start.
#[derive(Debug, thiserror::Error)]
pub enum ViewError {
    /// Another program (perhaps another station, or Foxglove's own bridge) listens there.
    #[error(
        "cannot start the live view on {address}: {source} (another program listens there: pick another port with --view PORT, or --view 0 for a free one)"
    )]
    AddressInUse {
        /// The address asked for.
        address: SocketAddr,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
    /// Binding failed otherwise (an address this host lacks, a privileged port).
    #[error("cannot start the live view on {address}: {source}")]
    Bind {
        /// The address asked for.
        address: SocketAddr,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
    /// The Foxglove server refused to start for another reason.
    #[error("cannot start the live view on {address}: {source}")]
    Start {
        /// The address asked for.
        address: SocketAddr,
        /// The SDK's error.
        #[source]
        source: foxglove::FoxgloveError,
    },
}

impl ViewError {
    /// Classify the SDK's start error for `address`.
    pub(crate) fn starting(address: SocketAddr, error: foxglove::FoxgloveError) -> ViewError {
        match error {
            foxglove::FoxgloveError::Bind(source)
                if source.kind() == std::io::ErrorKind::AddrInUse =>
            {
                ViewError::AddressInUse { address, source }
            }
            foxglove::FoxgloveError::Bind(source) => ViewError::Bind { address, source },
            source => ViewError::Start { address, source },
        }
    }
}
