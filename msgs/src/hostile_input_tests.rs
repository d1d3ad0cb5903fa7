//! Malformed and hostile payloads give `Err`, never a panic or an absurd allocation.

use proptest::prelude::*;
use serde::de::DeserializeOwned;

use crate::round_trip_tests::{float32_arrays, joint_states, pose_stampeds};
use crate::*;

/// Decodes `bytes` as every message type; a panic fails the test.
fn decode_as_everything(bytes: &[u8]) {
    fn one<T: DeserializeOwned>(bytes: &[u8]) {
        let _ = from_cdr::<T>(bytes);
    }
    one::<Time>(bytes);
    one::<Header>(bytes);
    one::<StringMsg>(bytes);
    one::<MultiArrayDimension>(bytes);
    one::<MultiArrayLayout>(bytes);
    one::<Float32MultiArray>(bytes);
    one::<Float64MultiArray>(bytes);
    one::<Point>(bytes);
    one::<Quaternion>(bytes);
    one::<Pose>(bytes);
    one::<PoseStamped>(bytes);
    one::<PoseArray>(bytes);
    one::<JointState>(bytes);
}

/// Every strict prefix of a valid payload is an error.
fn truncations_fail<T: RosMessage + std::fmt::Debug>(value: &T) -> Result<(), TestCaseError> {
    let bytes = to_cdr(value).map_err(|e| TestCaseError::fail(e.to_string()))?;
    for len in 0..bytes.len() {
        let result = from_cdr::<T>(&bytes[..len]);
        prop_assert!(
            result.is_err(),
            "prefix of {} bytes decoded: {:?}",
            len,
            result
        );
    }
    Ok(())
}

proptest! {
    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..256)) {
        decode_as_everything(&bytes);
    }

    #[test]
    fn random_bodies_never_panic(
        little_endian in any::<bool>(),
        body in prop::collection::vec(any::<u8>(), 0..256),
    ) {
        let mut bytes = vec![0, u8::from(little_endian), 0, 0];
        bytes.extend(body);
        decode_as_everything(&bytes);
    }

    #[test]
    fn mutated_payloads_never_panic(
        msg in joint_states(),
        flips in prop::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..8),
    ) {
        let mut bytes = to_cdr(&msg).map_err(|e| TestCaseError::fail(e.to_string()))?;
        for (at, byte) in flips {
            let i = at.index(bytes.len());
            bytes[i] = byte;
        }
        decode_as_everything(&bytes);
    }

    #[test]
    fn truncated_joint_states_fail(msg in joint_states()) { truncations_fail(&msg)?; }

    #[test]
    fn truncated_pose_stampeds_fail(msg in pose_stampeds()) { truncations_fail(&msg)?; }

    #[test]
    fn truncated_float32_arrays_fail(msg in float32_arrays()) { truncations_fail(&msg)?; }
}

#[test]
fn huge_declared_lengths_fail_without_allocating_them() {
    // Float64MultiArray: no dims, offset 0, then 2^32 - 1 doubles declared, one present.
    // Reserving the declared length up front would ask for 32 GiB and abort the test.
    let mut payload = vec![0, 1, 0, 0];
    payload.extend_from_slice(&[0, 0, 0, 0, 0, 0, 0, 0, 0xff, 0xff, 0xff, 0xff]);
    payload.extend_from_slice(&1.0f64.to_le_bytes());
    let err = from_cdr::<Float64MultiArray>(&payload).unwrap_err();
    assert!(matches!(err, Error::Decode { .. }), "{err}");

    // JointState: empty header, then 2^32 - 1 names declared.
    let mut payload = vec![0, 1, 0, 0];
    payload.extend_from_slice(&[0; 8]); // stamp
    payload.extend_from_slice(&[1, 0, 0, 0, 0, 0, 0, 0]); // "" + padding
    payload.extend_from_slice(&[0xff, 0xff, 0xff, 0xff]);
    assert!(from_cdr::<JointState>(&payload).is_err());

    // A string declaring 4 GiB of text.
    let payload = [0, 1, 0, 0, 0xff, 0xff, 0xff, 0xff, b'a', 0];
    assert!(from_cdr::<StringMsg>(&payload).is_err());
}

#[test]
fn invalid_utf8_is_an_error() {
    let payload = [0, 1, 0, 0, 3, 0, 0, 0, 0xc3, 0x28, 0];
    let err = from_cdr::<StringMsg>(&payload).unwrap_err();
    assert!(matches!(err, Error::Decode { .. }), "{err}");
}

#[test]
fn another_type_with_a_longer_body_is_not_silently_accepted() {
    let pose = to_cdr(&PoseStamped::default()).unwrap();
    let err = from_cdr::<Header>(&pose).unwrap_err();
    assert!(matches!(err, Error::TrailingBytes { .. }), "{err}");
}
