//! The mapper's output: an end-effector target and what limited it.

use nalgebra::Isometry3;

/// One tick's end-effector target, robot base frame, for the arm's pose command topic.
///
/// Invariants (tested as properties): finite; unit quaternion; position inside the workspace
/// box; within the step caps of the previous command; on the constraint axis line through
/// the latched position for the axis constraints.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArmCommand {
    /// Target pose of the end effector in the robot base frame (metres, unit quaternion).
    pub target: Isometry3<f64>,
    /// The task constraint removed part of the requested motion (more than 1e-12 m or rad).
    pub constrained: bool,
    /// The workspace box moved the target (along the axis line under an axis constraint).
    pub clamped_to_workspace: bool,
    /// The translation step exceeded `max_translation_step_m` and was scaled down.
    pub translation_capped: bool,
    /// The rotation step exceeded `max_rotation_step_rad` and was scaled down.
    pub rotation_capped: bool,
}

impl ArmCommand {
    /// Whether the workspace or a step cap kept the target from the constrained request (the
    /// command lags or stops short of where the operator asked). The constraint itself is not
    /// counted: removing motion is what it is for.
    pub fn is_limited(&self) -> bool {
        self.clamped_to_workspace || self.translation_capped || self.rotation_capped
    }

    /// Target position, metres, as a message's `position` (x, y, z).
    pub fn position_m(&self) -> [f64; 3] {
        let v = &self.target.translation.vector;
        [v.x, v.y, v.z]
    }

    /// Target orientation as a message's quaternion, ROS order (x, y, z, w).
    pub fn quaternion_xyzw(&self) -> [f64; 4] {
        let q = self.target.rotation.quaternion();
        [q.i, q.j, q.k, q.w]
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::{Translation3, UnitQuaternion, Vector3};

    use super::*;

    #[test]
    fn message_fields_are_in_ros_order() {
        let command = ArmCommand {
            target: Isometry3::from_parts(
                Translation3::new(0.4, -0.1, 0.3),
                UnitQuaternion::from_scaled_axis(Vector3::x() * std::f64::consts::PI),
            ),
            constrained: true,
            clamped_to_workspace: false,
            translation_capped: false,
            rotation_capped: false,
        };
        assert_eq!(command.position_m(), [0.4, -0.1, 0.3]);
        let q = command.quaternion_xyzw();
        assert!((q[0] - 1.0).abs() < 1e-12 && q[3].abs() < 1e-12, "{q:?}");
        assert!(!command.is_limited());
    }
}
