//! What the arm mapper refuses on one step, as data: a closed set of outcomes
//! ([`ArmRefusal`]) the station counts by [`ArmRefusal::name`] and reports as a notice. On a
//! refusal the mapper's state is unchanged and the caller holds its last command.

use std::fmt;

/// Which input pose an error is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PoseRole {
    /// The glove wrist pose, in the glove tracker frame.
    GloveWrist,
    /// The robot end-effector pose, in the robot base frame (arm feedback or start pose).
    RobotEndEffector,
}

impl fmt::Display for PoseRole {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PoseRole::GloveWrist => f.write_str("glove wrist pose"),
            PoseRole::RobotEndEffector => f.write_str("robot end-effector pose"),
        }
    }
}

/// A refused step, engage or constraint change: the input or the moment was unusable.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum ArmRefusal {
    /// A position or quaternion component is NaN or infinite.
    #[error("{pose}: {field} is not finite")]
    NonFinitePose {
        /// The pose.
        pose: PoseRole,
        /// `position` or `orientation`.
        field: &'static str,
    },
    /// A position coordinate further from the frame origin than any lab could be.
    #[error("{pose}: position coordinate {value} m is beyond ±{limit_m} m")]
    ImplausiblePosition {
        /// The pose.
        pose: PoseRole,
        /// The offending coordinate, metres.
        value: f64,
        /// The plausibility bound, metres.
        limit_m: f64,
    },
    /// The orientation quaternion is not of unit length within the tolerance.
    #[error("{pose}: quaternion norm {norm} is not 1 (tolerance {tolerance})")]
    NonUnitQuaternion {
        /// The pose.
        pose: PoseRole,
        /// The norm found.
        norm: f64,
        /// The allowed deviation from 1.
        tolerance: f64,
    },
    /// Engage refused: the robot pose is outside the workspace box, so no target could be both
    /// inside the box and within a step cap of where the robot is.
    #[error(
        "cannot engage: robot end-effector {axis} = {value} m is outside the workspace box [{min_m}, {max_m}] m; move the arm into the box or widen workspace_min_m/workspace_max_m"
    )]
    OutsideWorkspace {
        /// `x`, `y` or `z` of the robot base frame.
        axis: &'static str,
        /// The robot's coordinate, metres.
        value: f64,
        /// The box's lower bound on that axis, metres.
        min_m: f64,
        /// The box's upper bound on that axis, metres.
        max_m: f64,
    },
    /// The task constraint can only change while disengaged: a change while engaged would
    /// move the target without the operator moving.
    #[error("cannot change the arm constraint while engaged: disengage first")]
    ConstraintChangeWhileEngaged,
    /// The computed target is not finite. Unreachable for validated inputs; kept so that a
    /// bug can never reach the robot. The caller holds.
    #[error("the computed arm target is not finite")]
    NonFiniteTarget,
}

impl ArmRefusal {
    /// The refusal's name in the station's status.
    pub fn name(&self) -> &'static str {
        match self {
            ArmRefusal::NonFinitePose { .. } => "non_finite_pose",
            ArmRefusal::ImplausiblePosition { .. } => "implausible_position",
            ArmRefusal::NonUnitQuaternion { .. } => "non_unit_quaternion",
            ArmRefusal::NonFiniteTarget => "non_finite_target",
            ArmRefusal::OutsideWorkspace { .. } => "outside_workspace",
            ArmRefusal::ConstraintChangeWhileEngaged => "constraint_change",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pose_errors_say_which_pose() {
        let e = ArmRefusal::NonFinitePose {
            pose: PoseRole::GloveWrist,
            field: "position",
        };
        assert_eq!(e.to_string(), "glove wrist pose: position is not finite");
        assert_eq!(e.name(), "non_finite_pose");
    }
}
