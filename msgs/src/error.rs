//! The crate's one error type.

/// Everything that can go wrong encoding, decoding or interpreting a message.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum Error {
    /// The payload is shorter than the 4-byte encapsulation header.
    #[error("CDR payload of {len} bytes is shorter than the 4-byte encapsulation header")]
    TooShort {
        /// Length of the payload that was given.
        len: usize,
    },
    /// The encapsulation identifier is not plain CDR (big- or little-endian).
    #[error(
        "unsupported encapsulation {id:02x?}: only CDR_BE [00, 00] and CDR_LE [00, 01] are read"
    )]
    UnknownEncapsulation {
        /// The first two bytes of the payload.
        id: [u8; 2],
    },
    /// The CDR body does not decode as the requested type (truncated, bad UTF-8, ...).
    #[error("CDR body does not decode as {type_name}: {reason}")]
    Decode {
        /// Rust type that was being decoded.
        type_name: &'static str,
        /// What the CDR decoder reported.
        reason: String,
    },
    /// The body decoded, but more bytes follow than alignment padding can explain.
    #[error(
        "{count} bytes left over after decoding {type_name} (at most 3 bytes of padding allowed)"
    )]
    TrailingBytes {
        /// Rust type that was decoded.
        type_name: &'static str,
        /// Number of unread bytes after the message.
        count: usize,
    },
    /// The value could not be written as CDR.
    #[error("cannot encode {type_name} as CDR: {reason}")]
    Encode {
        /// Rust type that was being encoded.
        type_name: &'static str,
        /// What the CDR encoder reported.
        reason: String,
    },
    /// A `Float32MultiArray` does not hold an N×3 matrix of points.
    #[error("Float32MultiArray is not an N×3 point matrix: {reason}")]
    NotPointMatrix {
        /// Which check failed, with the values found.
        reason: String,
    },
}
