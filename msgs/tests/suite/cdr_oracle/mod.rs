//! What must hold for any CDR payload, valid or not: decoding it as any message type returns
//! `Ok` or `Err` and never panics, and whatever decodes is consistent — it re-encodes, the
//! re-encoding decodes to the same value (compared as bytes, so NaN payloads count).
//!
//! The re-encoding may be longer than the input: `cdr-encoding` reads strings leniently (a
//! zero-length string without its NUL, as IntercomDDS writes it, and a last byte other than
//! NUL taken as the terminator), and writes them canonically.
//!
//! Shared by the stable proptest fuzzing (`tests/fuzz_cdr.rs`) and the cargo-fuzz target
//! (`fuzz/fuzz_targets/cdr_decode.rs`), so both check the same thing.

use msgs::{
    Float32MultiArray, Float64MultiArray, Header, JointState, MultiArrayDimension,
    MultiArrayLayout, Point, Pose, PoseArray, PoseStamped, Quaternion, RosMessage, StringMsg, Time,
    from_cdr, to_cdr,
};

/// Decode `payload` as every message type of `msgs` and check each outcome.
pub fn check_payload(payload: &[u8]) {
    check_as::<Time>(payload);
    check_as::<Header>(payload);
    check_as::<StringMsg>(payload);
    check_as::<MultiArrayDimension>(payload);
    check_as::<MultiArrayLayout>(payload);
    check_as::<Float64MultiArray>(payload);
    check_as::<Point>(payload);
    check_as::<Quaternion>(payload);
    check_as::<Pose>(payload);
    check_as::<PoseStamped>(payload);
    check_as::<PoseArray>(payload);
    check_as::<JointState>(payload);
    if let Some(array) = check_as::<Float32MultiArray>(payload) {
        // What the station does with a keypoint message: an N×3 matrix or an error.
        if let Ok(points) = array.points() {
            assert_eq!(points.len() * 3, array.data.len(), "point matrix size");
        }
    }
    if let Some(time) = check_as::<Time>(payload) {
        // Any decoded time (even with nanosec ≥ 1e9) has nanoseconds that normalise.
        assert!(Time::from_nanos(time.to_nanos()).nanosec < 1_000_000_000);
    }
}

/// Decode `payload` as `M`; on success check that the value re-encodes consistently.
pub fn check_as<M: RosMessage + std::fmt::Debug>(payload: &[u8]) -> Option<M> {
    match from_cdr::<M>(payload) {
        Ok(value) => {
            let encoded = to_cdr(&value).unwrap_or_else(|e| {
                panic!("{} decoded but does not re-encode: {e}", M::ros_type_name())
            });
            let again: M = from_cdr(&encoded).unwrap_or_else(|e| {
                panic!("{} re-encoding does not decode: {e}", M::ros_type_name())
            });
            let encoded_again = to_cdr(&again).unwrap_or_else(|e| {
                panic!("{} second re-encoding failed: {e}", M::ros_type_name())
            });
            assert_eq!(
                encoded,
                encoded_again,
                "{} is not stable through encode/decode",
                M::ros_type_name()
            );
            Some(value)
        }
        Err(error) => {
            assert!(!error.to_string().is_empty(), "an error says what failed");
            None
        }
    }
}
