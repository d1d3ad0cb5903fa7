//! Every message type survives encode → decode, little- and big-endian.
//!
//! The strategies here are shared with the hostile-input tests.

use std::fmt::Debug;

use byteorder::BigEndian;
use proptest::prelude::*;

use crate::*;

/// Any `f64` but NaN (which would make `PartialEq` fail on a correct round trip).
pub(crate) fn f64s() -> impl Strategy<Value = f64> {
    use prop::num::f64::{INFINITE, NEGATIVE, NORMAL, POSITIVE, SUBNORMAL, ZERO};
    POSITIVE | NEGATIVE | NORMAL | SUBNORMAL | ZERO | INFINITE
}

/// Any `f32` but NaN.
pub(crate) fn f32s() -> impl Strategy<Value = f32> {
    use prop::num::f32::{INFINITE, NEGATIVE, NORMAL, POSITIVE, SUBNORMAL, ZERO};
    POSITIVE | NEGATIVE | NORMAL | SUBNORMAL | ZERO | INFINITE
}

fn vecs<T: Debug>(s: impl Strategy<Value = T>) -> impl Strategy<Value = Vec<T>> {
    prop::collection::vec(s, 0..6)
}

prop_compose! {
    pub(crate) fn times()(sec in any::<i32>(), nanosec in any::<u32>()) -> Time {
        Time { sec, nanosec }
    }
}
prop_compose! {
    pub(crate) fn headers()(stamp in times(), frame_id in any::<String>()) -> Header {
        Header { stamp, frame_id }
    }
}
prop_compose! {
    pub(crate) fn points()(x in f64s(), y in f64s(), z in f64s()) -> Point {
        Point { x, y, z }
    }
}
prop_compose! {
    pub(crate) fn quaternions()(x in f64s(), y in f64s(), z in f64s(), w in f64s()) -> Quaternion {
        Quaternion { x, y, z, w }
    }
}
prop_compose! {
    pub(crate) fn poses()(position in points(), orientation in quaternions()) -> Pose {
        Pose { position, orientation }
    }
}
prop_compose! {
    pub(crate) fn dims()(label in any::<String>(), size in any::<u32>(), stride in any::<u32>())
        -> MultiArrayDimension {
        MultiArrayDimension { label, size, stride }
    }
}
prop_compose! {
    pub(crate) fn layouts()(dim in vecs(dims()), data_offset in any::<u32>()) -> MultiArrayLayout {
        MultiArrayLayout { dim, data_offset }
    }
}
prop_compose! {
    pub(crate) fn pose_stampeds()(header in headers(), pose in poses()) -> PoseStamped {
        PoseStamped { header, pose }
    }
}
prop_compose! {
    pub(crate) fn joint_states()(
        header in headers(),
        name in vecs(any::<String>()),
        position in vecs(f64s()),
        velocity in vecs(f64s()),
        effort in vecs(f64s()),
    ) -> JointState {
        JointState { header, name, position, velocity, effort }
    }
}
prop_compose! {
    pub(crate) fn float32_arrays()(layout in layouts(), data in vecs(f32s())) -> Float32MultiArray {
        Float32MultiArray { layout, data }
    }
}

fn round_trips<T: RosMessage + PartialEq + Debug>(value: &T) -> Result<(), TestCaseError> {
    let le = to_cdr(value).map_err(|e| TestCaseError::fail(e.to_string()))?;
    prop_assert_eq!(
        &from_cdr::<T>(&le).map_err(|e| TestCaseError::fail(e.to_string()))?,
        value
    );

    let mut be = CDR_BE_ID.to_vec();
    be.extend_from_slice(&[0, 0]);
    be.extend(
        cdr_encoding::to_vec::<T, BigEndian>(value)
            .map_err(|e| TestCaseError::fail(e.to_string()))?,
    );
    prop_assert_eq!(be.len(), le.len());
    prop_assert_eq!(
        &from_cdr::<T>(&be).map_err(|e| TestCaseError::fail(e.to_string()))?,
        value
    );
    Ok(())
}

proptest! {
    #[test]
    fn time(v in times()) { round_trips(&v)?; }

    #[test]
    fn header(v in headers()) { round_trips(&v)?; }

    #[test]
    fn string_msg(data in any::<String>()) { round_trips(&StringMsg { data })?; }

    #[test]
    fn multi_array_dimension(v in dims()) { round_trips(&v)?; }

    #[test]
    fn multi_array_layout(v in layouts()) { round_trips(&v)?; }

    #[test]
    fn float32_multi_array(v in float32_arrays()) { round_trips(&v)?; }

    #[test]
    fn float64_multi_array(layout in layouts(), data in vecs(f64s())) {
        round_trips(&Float64MultiArray { layout, data })?;
    }

    #[test]
    fn point(v in points()) { round_trips(&v)?; }

    #[test]
    fn quaternion(v in quaternions()) { round_trips(&v)?; }

    #[test]
    fn pose(v in poses()) { round_trips(&v)?; }

    #[test]
    fn pose_stamped(v in pose_stampeds()) { round_trips(&v)?; }

    #[test]
    fn pose_array(header in headers(), poses in vecs(poses())) {
        round_trips(&PoseArray { header, poses })?;
    }

    #[test]
    fn joint_state(v in joint_states()) { round_trips(&v)?; }
}

#[test]
fn defaults_round_trip() {
    fn check<T: RosMessage + PartialEq + Debug + Default>() {
        let v = T::default();
        assert_eq!(from_cdr::<T>(&to_cdr(&v).unwrap()).unwrap(), v);
    }
    check::<Time>();
    check::<Header>();
    check::<StringMsg>();
    check::<MultiArrayDimension>();
    check::<MultiArrayLayout>();
    check::<Float32MultiArray>();
    check::<Float64MultiArray>();
    check::<Point>();
    check::<Quaternion>();
    check::<Pose>();
    check::<PoseStamped>();
    check::<PoseArray>();
    check::<JointState>();
    assert_eq!(Pose::default().orientation, Quaternion::identity());
}
