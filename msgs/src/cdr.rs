//! CDR framing of a serialized payload: the 4-byte encapsulation header, then the plain CDR
//! body written and read by `cdr-encoding`.
//!
//! Alignment is counted from the first byte of the body (the byte after the header), which is
//! what `cdr-encoding` does when it is handed the body alone.

use byteorder::{BigEndian, LittleEndian};
use serde::{Serialize, de::DeserializeOwned};

use crate::Error;

/// Encapsulation header of plain CDR, little-endian (`CDR_LE`), with zero options.
pub const CDR_LE_HEADER: [u8; 4] = [0x00, 0x01, 0x00, 0x00];

/// Encapsulation identifier of plain CDR, big-endian (`CDR_BE`).
pub const CDR_BE_ID: [u8; 2] = [0x00, 0x00];

/// Encapsulation identifier of plain CDR, little-endian (`CDR_LE`).
pub const CDR_LE_ID: [u8; 2] = [0x00, 0x01];

/// Trailing bytes tolerated after the body: some writers pad the payload to a multiple of 4
/// (and say so in the options field, which this reader does not interpret).
const MAX_PADDING: usize = 3;

/// Encodes `value` as a serialized payload: `00 01 00 00` then the little-endian CDR body.
///
/// # Errors
/// [`Error::Encode`] if serde reports an error (CDR cannot express, e.g., a sequence of
/// unknown length; none of this crate's messages contain one).
pub fn to_cdr<T: Serialize>(value: &T) -> Result<Vec<u8>, Error> {
    let body = cdr_encoding::to_vec::<T, LittleEndian>(value).map_err(|e| Error::Encode {
        type_name: std::any::type_name::<T>(),
        reason: e.to_string(),
    })?;
    let mut payload = Vec::with_capacity(CDR_LE_HEADER.len() + body.len());
    payload.extend_from_slice(&CDR_LE_HEADER);
    payload.extend_from_slice(&body);
    Ok(payload)
}

/// Decodes a serialized payload (encapsulation header + CDR body) into a `T`.
///
/// Accepts `CDR_LE` (`00 01`) and `CDR_BE` (`00 00`); the two option bytes are ignored. Up to 3
/// trailing padding bytes are allowed after the body; more are an error, as they usually mean
/// the payload is of another type.
///
/// Hostile input is safe: every read is bounds-checked and a sequence's declared length is not
/// used to reserve memory (`cdr-encoding` gives serde no size hint, so a `Vec` grows one decoded
/// element at a time and a huge declared length ends in [`Error::Decode`] at the end of input).
///
/// # Errors
/// [`Error::TooShort`], [`Error::UnknownEncapsulation`], [`Error::Decode`] or
/// [`Error::TrailingBytes`].
pub fn from_cdr<T: DeserializeOwned>(payload: &[u8]) -> Result<T, Error> {
    let Some((header, body)) = payload.split_first_chunk::<4>() else {
        return Err(Error::TooShort { len: payload.len() });
    };
    let id = [header[0], header[1]];
    let decoded = match id {
        CDR_LE_ID => cdr_encoding::from_bytes::<T, LittleEndian>(body),
        CDR_BE_ID => cdr_encoding::from_bytes::<T, BigEndian>(body),
        _ => return Err(Error::UnknownEncapsulation { id }),
    };
    let type_name = std::any::type_name::<T>();
    let (value, consumed) = decoded.map_err(|e| Error::Decode {
        type_name,
        reason: e.to_string(),
    })?;
    let count = body.len().saturating_sub(consumed);
    if count > MAX_PADDING {
        return Err(Error::TrailingBytes { type_name, count });
    }
    Ok(value)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Time;

    #[test]
    fn header_is_cdr_le_and_body_follows() {
        let t = Time { sec: 1, nanosec: 2 };
        assert_eq!(to_cdr(&t).unwrap(), [0, 1, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0]);
    }

    #[test]
    fn big_endian_payloads_decode() {
        let be = [0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 2];
        assert_eq!(from_cdr::<Time>(&be).unwrap(), Time { sec: 1, nanosec: 2 });
    }

    #[test]
    fn short_payloads_and_other_encapsulations_are_rejected() {
        assert_eq!(
            from_cdr::<Time>(&[0, 1, 0]),
            Err(Error::TooShort { len: 3 })
        );
        // PL_CDR_LE and XCDR2 (CDR2_LE) are not plain CDR.
        for id in [[0x00, 0x03], [0x00, 0x07]] {
            let payload = [id[0], id[1], 0, 0, 1, 0, 0, 0, 2, 0, 0, 0];
            assert_eq!(
                from_cdr::<Time>(&payload),
                Err(Error::UnknownEncapsulation { id })
            );
        }
    }

    #[test]
    fn padding_is_tolerated_but_more_is_not() {
        let mut payload = to_cdr(&Time { sec: 1, nanosec: 2 }).unwrap();
        payload.extend_from_slice(&[0, 0, 0]);
        assert!(from_cdr::<Time>(&payload).is_ok());
        payload.push(0);
        assert!(matches!(
            from_cdr::<Time>(&payload),
            Err(Error::TrailingBytes { count: 4, .. })
        ));
    }

    #[test]
    fn truncated_body_is_a_decode_error() {
        let payload = to_cdr(&Time { sec: 1, nanosec: 2 }).unwrap();
        let err = from_cdr::<Time>(&payload[..payload.len() - 1]).unwrap_err();
        assert!(matches!(err, Error::Decode { .. }), "{err}");
    }
}
