//! The arm mapping's one error type.
//!
//! `Err` means malformed input: a configuration value out of range, or a pose that cannot be
//! used. A limited command (clamped, capped, constrained) is not an error: it is data in
//! [`ArmCommand`](super::ArmCommand). On a rejected pose the mapper's state is unchanged and
//! the caller holds its last command.

use std::fmt;
use std::path::PathBuf;

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

/// Malformed arm configuration or an unusable input pose.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum ArmError {
    /// The problem was found in this file.
    #[error("{path}: {source}")]
    InFile {
        /// The file that was read.
        path: PathBuf,
        /// What is wrong with it.
        source: Box<ArmError>,
    },
    /// The TOML does not parse, or has an unknown or mistyped key.
    #[error("invalid arm configuration: {reason}")]
    Syntax {
        /// The parser's message, with line, column and key.
        reason: String,
    },
    /// A configuration value out of its allowed range, or inconsistent with another key.
    #[error("config key '{key}' = {value}: {allowed}")]
    ConfigRange {
        /// Dotted key (`start_pose.position_m`).
        key: String,
        /// The value as read.
        value: String,
        /// The allowed range or the rule it breaks.
        allowed: String,
    },
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

impl ArmError {
    /// Attach the file the error was found in.
    pub fn in_file(self, path: impl Into<PathBuf>) -> ArmError {
        ArmError::InFile {
            path: path.into(),
            source: Box::new(self),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_the_key_and_the_file() {
        let e = ArmError::ConfigRange {
            key: "max_translation_step_m".into(),
            value: "0.5".into(),
            allowed: "must be in (0, 0.1]".into(),
        }
        .in_file("launch_configs/arm/lab.toml");
        let text = e.to_string();
        assert!(text.contains("launch_configs/arm/lab.toml"), "{text}");
        assert!(text.contains("max_translation_step_m"), "{text}");
        assert!(text.contains("(0, 0.1]"), "{text}");
    }

    #[test]
    fn pose_errors_say_which_pose() {
        let e = ArmError::NonFinitePose {
            pose: PoseRole::GloveWrist,
            field: "position",
        };
        assert_eq!(e.to_string(), "glove wrist pose: position is not finite");
    }
}
