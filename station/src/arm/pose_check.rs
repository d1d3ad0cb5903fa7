//! Input pose validation: finite, plausible position, unit quaternion.
//!
//! No downstream Franka controller checks NaN or quaternion norms, so every pose entering the
//! mapper passes through [`checked_pose`]. A nearly-unit quaternion (within
//! [`QUATERNION_NORM_TOLERANCE`], e.g. an `f32` round trip) is renormalised; anything further
//! from unit length is a malformed message and is rejected, never silently normalised.

use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion, Vector3};

use super::arm_refusal::{ArmRefusal, PoseRole};

/// Largest allowed deviation of an input quaternion's norm from 1.
///
/// Loose enough for quaternions that went through `f32` (error ~1e-7) or a few decimal places
/// of text, tight enough to catch a zero, a doubled or a garbled quaternion.
pub const QUATERNION_NORM_TOLERANCE: f64 = 1e-3;

/// Bound on every input position coordinate, metres. No tracker or arm base frame in a lab
/// puts the hand 100 m from its origin; the bound also keeps all later arithmetic far from
/// overflow, so the output is provably finite.
pub const MAX_ABS_POSITION_M: f64 = 100.0;

/// Check a pose and return it with an exactly renormalised quaternion.
pub fn checked_pose(pose: &Isometry3<f64>, role: PoseRole) -> Result<Isometry3<f64>, ArmRefusal> {
    let position = checked_position(&pose.translation.vector, role)?;
    let rotation = checked_rotation(pose.rotation.quaternion(), role)?;
    Ok(Isometry3::from_parts(
        Translation3::from(position),
        rotation,
    ))
}

/// Build a pose from message fields (position in metres, quaternion in ROS order x, y, z, w),
/// with the same checks as [`checked_pose`].
///
/// Use this rather than `UnitQuaternion::from_quaternion`, which would normalise a garbled
/// quaternion without complaint.
pub fn pose_from_parts(
    position_m: [f64; 3],
    quaternion_xyzw: [f64; 4],
    role: PoseRole,
) -> Result<Isometry3<f64>, ArmRefusal> {
    let [x, y, z, w] = quaternion_xyzw;
    let position = checked_position(&Vector3::from(position_m), role)?;
    let rotation = checked_rotation(&Quaternion::new(w, x, y, z), role)?;
    Ok(Isometry3::from_parts(
        Translation3::from(position),
        rotation,
    ))
}

fn checked_position(p: &Vector3<f64>, role: PoseRole) -> Result<Vector3<f64>, ArmRefusal> {
    if !p.iter().all(|v| v.is_finite()) {
        return Err(ArmRefusal::NonFinitePose {
            pose: role,
            field: "position",
        });
    }
    if let Some(&value) = p.iter().find(|v| v.abs() > MAX_ABS_POSITION_M) {
        return Err(ArmRefusal::ImplausiblePosition {
            pose: role,
            value,
            limit_m: MAX_ABS_POSITION_M,
        });
    }
    Ok(*p)
}

fn checked_rotation(
    q: &Quaternion<f64>,
    role: PoseRole,
) -> Result<UnitQuaternion<f64>, ArmRefusal> {
    if !q.coords.iter().all(|v| v.is_finite()) {
        return Err(ArmRefusal::NonFinitePose {
            pose: role,
            field: "orientation",
        });
    }
    let norm = q.norm();
    if (norm - 1.0).abs() > QUATERNION_NORM_TOLERANCE {
        return Err(ArmRefusal::NonUnitQuaternion {
            pose: role,
            norm,
            tolerance: QUATERNION_NORM_TOLERANCE,
        });
    }
    Ok(UnitQuaternion::new_normalize(*q))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn accepts_and_renormalises_nearly_unit_quaternions() {
        let pose = pose_from_parts(
            [0.1, 0.2, 0.3],
            [0.0, 0.0, 0.0, 1.0005],
            PoseRole::GloveWrist,
        )
        .unwrap();
        assert!((pose.rotation.quaternion().norm() - 1.0).abs() < 1e-15);
        assert_eq!(pose.translation.vector, Vector3::new(0.1, 0.2, 0.3));
    }

    #[test]
    fn rejects_zero_and_doubled_quaternions() {
        for q in [[0.0; 4], [0.0, 0.0, 0.0, 2.0]] {
            let e = pose_from_parts([0.0; 3], q, PoseRole::GloveWrist).unwrap_err();
            assert!(matches!(e, ArmRefusal::NonUnitQuaternion { .. }), "{e}");
        }
    }

    #[test]
    fn rejects_non_finite_values() {
        let e = pose_from_parts(
            [f64::NAN, 0.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
            PoseRole::RobotEndEffector,
        )
        .unwrap_err();
        assert_eq!(
            e,
            ArmRefusal::NonFinitePose {
                pose: PoseRole::RobotEndEffector,
                field: "position"
            }
        );
        let e = pose_from_parts(
            [0.0; 3],
            [0.0, f64::INFINITY, 0.0, 1.0],
            PoseRole::GloveWrist,
        )
        .unwrap_err();
        assert!(matches!(
            e,
            ArmRefusal::NonFinitePose {
                field: "orientation",
                ..
            }
        ));
    }

    #[test]
    fn rejects_a_garbled_unit_quaternion_inside_an_isometry() {
        // `new_unchecked` is how a careless caller could smuggle in a non-unit quaternion.
        let rotation = UnitQuaternion::new_unchecked(Quaternion::new(0.5, 0.0, 0.0, 0.0));
        let pose = Isometry3::from_parts(Translation3::new(0.0, 0.0, 0.0), rotation);
        assert!(checked_pose(&pose, PoseRole::GloveWrist).is_err());
    }

    #[test]
    fn rejects_implausible_positions() {
        let e = pose_from_parts([0.0, 1e3, 0.0], [0.0, 0.0, 0.0, 1.0], PoseRole::GloveWrist)
            .unwrap_err();
        assert!(matches!(e, ArmRefusal::ImplausiblePosition { value, .. } if value == 1e3));
    }
}
