//! Conversions between `msgs` types and the station's nalgebra values.

use msgs::{Float32MultiArray, Header, Point, Pose, PoseArray, Quaternion, Time};
use nalgebra::{Isometry3, Point3, Quaternion as NaQuaternion, Translation3, UnitQuaternion};

/// The pose as an isometry. The quaternion is taken as given (normalised by nalgebra only if
/// its norm is within 1e-6 of 1); a non-unit or non-finite one yields `None` so the caller can
/// count and reject it.
pub fn pose_to_isometry(pose: &Pose) -> Option<Isometry3<f64>> {
    let q = &pose.orientation;
    let raw = NaQuaternion::new(q.w, q.x, q.y, q.z);
    let p = &pose.position;
    let finite = [p.x, p.y, p.z, q.x, q.y, q.z, q.w]
        .iter()
        .all(|v| v.is_finite());
    if !finite || (raw.norm() - 1.0).abs() > 1e-6 {
        return None;
    }
    Some(Isometry3::from_parts(
        Translation3::new(p.x, p.y, p.z),
        UnitQuaternion::new_normalize(raw),
    ))
}

/// The isometry as a pose message.
pub fn isometry_to_pose(iso: &Isometry3<f64>) -> Pose {
    let t = &iso.translation.vector;
    let q = iso.rotation.quaternion();
    Pose {
        position: Point {
            x: t.x,
            y: t.y,
            z: t.z,
        },
        orientation: Quaternion {
            x: q.i,
            y: q.j,
            z: q.k,
            w: q.w,
        },
    }
}

/// Keypoints of an N × 3 array (metres); `None` when the layout is not N × 3.
pub fn array_to_points(array: &Float32MultiArray) -> Option<Vec<Point3<f64>>> {
    let rows = array.points().ok()?;
    Some(
        rows.iter()
            .map(|r| Point3::new(r[0].into(), r[1].into(), r[2].into()))
            .collect(),
    )
}

/// A keypoint message in either supported format, as received or logged.
#[derive(Debug, Clone, PartialEq)]
pub enum KeypointMessage {
    /// The lab's N × 3 `Float32MultiArray`.
    Array(Float32MultiArray),
    /// A stamped `PoseArray` (positions used).
    Poses(PoseArray),
}

impl KeypointMessage {
    /// The keypoints, metres; empty when an array is not N × 3 (the frame gate then rejects
    /// the frame as the wrong size).
    pub fn points(&self) -> Vec<Point3<f64>> {
        match self {
            KeypointMessage::Array(m) => array_to_points(m).unwrap_or_default(),
            KeypointMessage::Poses(m) => pose_array_to_points(m),
        }
    }
}

/// Keypoints of a pose array: the positions.
pub fn pose_array_to_points(array: &PoseArray) -> Vec<Point3<f64>> {
    array
        .poses
        .iter()
        .map(|p| Point3::new(p.position.x, p.position.y, p.position.z))
        .collect()
}

/// A header stamped `stamp_ns` (nanoseconds since the epoch).
pub fn header(stamp_ns: i64, frame_id: &str) -> Header {
    Header {
        stamp: Time::from_nanos(stamp_ns),
        frame_id: frame_id.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn poses_round_trip_and_bad_quaternions_are_refused() {
        let iso = Isometry3::from_parts(
            Translation3::new(0.4, -0.1, 0.3),
            UnitQuaternion::from_euler_angles(0.1, 0.2, 0.3),
        );
        let back = pose_to_isometry(&isometry_to_pose(&iso)).unwrap();
        assert!((back.translation.vector - iso.translation.vector).norm() < 1e-12);
        assert!(back.rotation.angle_to(&iso.rotation) < 1e-12);
        let mut pose = isometry_to_pose(&iso);
        pose.orientation.w *= 2.0;
        assert!(pose_to_isometry(&pose).is_none());
        pose.orientation.w = f64::NAN;
        assert!(pose_to_isometry(&pose).is_none());
    }
}
