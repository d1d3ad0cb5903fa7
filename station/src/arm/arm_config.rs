//! Arm mapping configuration (TOML), validated on load with errors that name the key and the
//! allowed range. Every key has a default; all vectors are in the robot base frame unless the
//! key says otherwise, lengths in metres, angles in radians.
//!
//! Rotations are written either as `rpy_rad = [roll, pitch, yaw]` (URDF convention: fixed axes
//! x, then y, then z, i.e. `R = Rz(yaw) · Ry(pitch) · Rx(roll)`) or as
//! `quaternion_xyzw = [x, y, z, w]` (ROS order), exactly one of the two.
//!
//! Default step caps: 0.01 m and 0.02 rad per tick. The caps are per tick, so the speed they
//! allow grows with the loop rate: at the fastest loop the station runs (100 Hz) they allow
//! 1.0 m/s and 2.0 rad/s, just under DROID's proven teleop caps (7.5 cm and 0.15 rad per 15 Hz
//! step = 1.125 m/s and 2.25 rad/s) and under libfranka's 2.5 rad/s; at the default 25 Hz
//! they allow 0.25 m/s and 0.5 rad/s, enough for the slow sliding and turning of the POMDAR
//! rod tasks, and a 10 cm glove jump becomes a 0.4 s ramp. A lab running a fast loop with
//! quick grasps may raise them within the validated ranges.

use nalgebra::{Isometry3, Quaternion, Translation3, Unit, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

use super::arm_error::ArmConfigError;
use super::constraint::{Constraint, OrientationPolicy, ResolvedConstraint};
use super::pose_check::QUATERNION_NORM_TOLERANCE;
use super::workspace_box::WorkspaceBox;

/// Allowed `translation_scale` (robot metres per glove metre).
pub const TRANSLATION_SCALE_RANGE: (f64, f64) = (0.01, 10.0);
/// Largest allowed `max_translation_step_m` (DROID's 0.075 m fits).
pub const MAX_TRANSLATION_STEP_LIMIT_M: f64 = 0.1;
/// Largest allowed `max_rotation_step_rad` (DROID's 0.15 rad fits).
pub const MAX_ROTATION_STEP_LIMIT_RAD: f64 = 0.5;
/// Bound on every workspace box coordinate, metres (the Franka reaches 0.855 m).
pub const WORKSPACE_LIMIT_M: f64 = 2.0;
/// Largest allowed deviation of a configured axis's norm from 1.
pub const AXIS_NORM_TOLERANCE: f64 = 1e-3;

/// Everything the arm mapping needs. See the [`arm`](super) module docs for the maths.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ArmConfig {
    /// Task constraint. Default `fixed`: a configuration that forgets the constraint must not
    /// let the arm roam.
    pub constraint: Constraint,
    /// What happens to the glove's relative rotation. Default `hold_when_constrained`.
    pub orientation: OrientationPolicy,
    /// Unit axis of `vertical_axis`, robot base frame. Default `[0, 0, 1]`.
    pub vertical_axis: [f64; 3],
    /// Unit axis of `horizontal_axis`, robot base frame. Default `[1, 0, 0]`.
    pub horizontal_axis: [f64; 3],
    /// Robot metres per glove metre. Default 1.0.
    pub translation_scale: f64,
    /// Fixed rotation from the glove tracker frame to the robot base frame
    /// (`ᴮv = R_BG · ᴳv`). Default identity.
    pub glove_to_base: RotationConfig,
    /// Lower corner of the workspace box, robot base frame, metres.
    /// Default `[0.25, -0.45, 0.05]` (a placeholder: measure it on your table).
    pub workspace_min_m: [f64; 3],
    /// Upper corner of the workspace box, robot base frame, metres.
    /// Default `[0.75, 0.45, 0.75]` (a placeholder: measure it on your table).
    pub workspace_max_m: [f64; 3],
    /// Per-tick translation cap, metres, applied to the norm of the step. Default 0.01.
    pub max_translation_step_m: f64,
    /// Per-tick rotation cap, radians, applied to the rotation angle of the step. Default 0.02.
    pub max_rotation_step_rad: f64,
    /// End-effector pose used at engage when there is no arm pose feedback.
    pub start_pose: StartPose,
}

/// A fixed rotation: exactly one of `rpy_rad` and `quaternion_xyzw`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RotationConfig {
    /// Roll, pitch, yaw, radians (URDF convention).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rpy_rad: Option<[f64; 3]>,
    /// Unit quaternion, ROS order x, y, z, w.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub quaternion_xyzw: Option<[f64; 4]>,
}

/// The end-effector pose assumed at engage without arm feedback, robot base frame; it must lie
/// inside the workspace box. Orientation: exactly one of `rpy_rad` and `quaternion_xyzw`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StartPose {
    /// Position, metres.
    pub position_m: [f64; 3],
    /// Roll, pitch, yaw, radians (URDF convention).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rpy_rad: Option<[f64; 3]>,
    /// Unit quaternion, ROS order x, y, z, w.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub quaternion_xyzw: Option<[f64; 4]>,
}

impl Default for ArmConfig {
    fn default() -> Self {
        ArmConfig {
            constraint: Constraint::Fixed,
            orientation: OrientationPolicy::HoldWhenConstrained,
            vertical_axis: [0.0, 0.0, 1.0],
            horizontal_axis: [1.0, 0.0, 0.0],
            translation_scale: 1.0,
            glove_to_base: RotationConfig::default(),
            workspace_min_m: [0.25, -0.45, 0.05],
            workspace_max_m: [0.75, 0.45, 0.75],
            max_translation_step_m: 0.01,
            max_rotation_step_rad: 0.02,
            start_pose: StartPose::default(),
        }
    }
}

impl Default for RotationConfig {
    fn default() -> Self {
        RotationConfig {
            rpy_rad: Some([0.0; 3]),
            quaternion_xyzw: None,
        }
    }
}

impl Default for StartPose {
    /// In front of the base, flange pointing down (a half turn about x, as Franka's usual
    /// ready pose). A placeholder: set it to your rig's pose.
    fn default() -> Self {
        StartPose {
            position_m: [0.45, 0.0, 0.40],
            rpy_rad: None,
            quaternion_xyzw: Some([1.0, 0.0, 0.0, 0.0]),
        }
    }
}

impl ArmConfig {
    /// Parse and validate a TOML configuration; missing keys take their defaults.
    pub fn from_toml_str(text: &str) -> Result<ArmConfig, ArmConfigError> {
        let config: ArmConfig = toml::from_str(text).map_err(|e| ArmConfigError::Syntax {
            reason: e.to_string().trim_end().to_string(),
        })?;
        config.validate()?;
        Ok(config)
    }

    /// Check every value against its allowed range.
    pub fn validate(&self) -> Result<(), ArmConfigError> {
        let (lo, hi) = TRANSLATION_SCALE_RANGE;
        if !(self.translation_scale >= lo && self.translation_scale <= hi) {
            return Err(range_error(
                "translation_scale",
                self.translation_scale,
                format!("must be in [{lo}, {hi}] (robot metres per glove metre)"),
            ));
        }
        positive_up_to(
            "max_translation_step_m",
            self.max_translation_step_m,
            MAX_TRANSLATION_STEP_LIMIT_M,
        )?;
        positive_up_to(
            "max_rotation_step_rad",
            self.max_rotation_step_rad,
            MAX_ROTATION_STEP_LIMIT_RAD,
        )?;
        unit_axis("vertical_axis", self.vertical_axis)?;
        unit_axis("horizontal_axis", self.horizontal_axis)?;
        rotation_from(
            "glove_to_base",
            self.glove_to_base.rpy_rad,
            self.glove_to_base.quaternion_xyzw,
        )?;
        for (key, corner) in [
            ("workspace_min_m", self.workspace_min_m),
            ("workspace_max_m", self.workspace_max_m),
        ] {
            if !corner.iter().all(|v| v.abs() <= WORKSPACE_LIMIT_M) {
                return Err(range_error(
                    key,
                    format!("{corner:?}"),
                    format!(
                        "every coordinate must be in [-{WORKSPACE_LIMIT_M}, {WORKSPACE_LIMIT_M}] m"
                    ),
                ));
            }
        }
        if !(0..3).all(|i| self.workspace_min_m[i] < self.workspace_max_m[i]) {
            return Err(range_error(
                "workspace_min_m",
                format!("{:?}", self.workspace_min_m),
                format!(
                    "every coordinate must be below workspace_max_m = {:?}",
                    self.workspace_max_m
                ),
            ));
        }
        let start = self.start_pose_isometry()?;
        if let Some(v) = self.workspace().first_violation(&start.translation.vector) {
            return Err(range_error(
                "start_pose.position_m",
                format!("{:?}", self.start_pose.position_m),
                format!(
                    "must lie inside the workspace box: {} must be in [{}, {}] m",
                    v.axis, v.min_m, v.max_m
                ),
            ));
        }
        Ok(())
    }

    /// The workspace box.
    pub fn workspace(&self) -> WorkspaceBox {
        WorkspaceBox {
            min_m: Vector3::from(self.workspace_min_m),
            max_m: Vector3::from(self.workspace_max_m),
        }
    }

    /// The configured axis of `constraint` (normalised), or `None` for `fixed` and `free`.
    pub fn axis_of(
        &self,
        constraint: Constraint,
    ) -> Result<Option<Unit<Vector3<f64>>>, ArmConfigError> {
        Ok(match self.resolved_constraint(constraint)? {
            ResolvedConstraint::Axis(axis) => Some(axis),
            ResolvedConstraint::Fixed | ResolvedConstraint::Free => None,
        })
    }

    /// `glove_to_base` as a unit quaternion.
    pub fn glove_to_base_rotation(&self) -> Result<UnitQuaternion<f64>, ArmConfigError> {
        rotation_from(
            "glove_to_base",
            self.glove_to_base.rpy_rad,
            self.glove_to_base.quaternion_xyzw,
        )
    }

    /// `start_pose` as an isometry (robot base frame).
    pub fn start_pose_isometry(&self) -> Result<Isometry3<f64>, ArmConfigError> {
        let p = self.start_pose.position_m;
        if !p.iter().all(|v| v.is_finite()) {
            return Err(range_error(
                "start_pose.position_m",
                format!("{p:?}"),
                "must be finite metres".to_string(),
            ));
        }
        let rotation = rotation_from(
            "start_pose",
            self.start_pose.rpy_rad,
            self.start_pose.quaternion_xyzw,
        )?;
        Ok(Isometry3::from_parts(
            Translation3::from(Vector3::from(p)),
            rotation,
        ))
    }

    /// `constraint` with its configured axis.
    pub(crate) fn resolved_constraint(
        &self,
        constraint: Constraint,
    ) -> Result<ResolvedConstraint, ArmConfigError> {
        Ok(match constraint {
            Constraint::Fixed => ResolvedConstraint::Fixed,
            Constraint::Free => ResolvedConstraint::Free,
            Constraint::VerticalAxis => {
                ResolvedConstraint::Axis(unit_axis("vertical_axis", self.vertical_axis)?)
            }
            Constraint::HorizontalAxis => {
                ResolvedConstraint::Axis(unit_axis("horizontal_axis", self.horizontal_axis)?)
            }
        })
    }
}

fn range_error(key: &str, value: impl ToString, allowed: String) -> ArmConfigError {
    ArmConfigError::ConfigRange {
        key: key.to_string(),
        value: value.to_string(),
        allowed,
    }
}

fn positive_up_to(key: &str, value: f64, max: f64) -> Result<(), ArmConfigError> {
    if value > 0.0 && value <= max {
        Ok(())
    } else {
        Err(range_error(key, value, format!("must be in (0, {max}]")))
    }
}

fn unit_axis(key: &str, axis: [f64; 3]) -> Result<Unit<Vector3<f64>>, ArmConfigError> {
    let v = Vector3::from(axis);
    let norm = v.norm();
    if norm.is_finite() && (norm - 1.0).abs() <= AXIS_NORM_TOLERANCE {
        Ok(Unit::new_unchecked(v / norm))
    } else {
        Err(range_error(
            key,
            format!("{axis:?}"),
            format!(
                "must be a unit vector in the robot base frame (norm within {AXIS_NORM_TOLERANCE} of 1, got {norm})"
            ),
        ))
    }
}

fn rotation_from(
    key: &str,
    rpy_rad: Option<[f64; 3]>,
    quaternion_xyzw: Option<[f64; 4]>,
) -> Result<UnitQuaternion<f64>, ArmConfigError> {
    match (rpy_rad, quaternion_xyzw) {
        (Some(rpy), None) => {
            if rpy.iter().all(|v| v.is_finite()) {
                Ok(UnitQuaternion::from_euler_angles(rpy[0], rpy[1], rpy[2]))
            } else {
                Err(range_error(
                    &format!("{key}.rpy_rad"),
                    format!("{rpy:?}"),
                    "must be finite radians".to_string(),
                ))
            }
        }
        (None, Some(q)) => {
            let quaternion = Quaternion::new(q[3], q[0], q[1], q[2]);
            let norm = quaternion.norm();
            if norm.is_finite() && (norm - 1.0).abs() <= QUATERNION_NORM_TOLERANCE {
                Ok(UnitQuaternion::new_normalize(quaternion))
            } else {
                Err(range_error(
                    &format!("{key}.quaternion_xyzw"),
                    format!("{q:?}"),
                    format!(
                        "must be a unit quaternion [x, y, z, w] (norm within {QUATERNION_NORM_TOLERANCE} of 1, got {norm})"
                    ),
                ))
            }
        }
        (Some(_), Some(_)) | (None, None) => Err(range_error(
            key,
            "(rpy_rad and quaternion_xyzw)",
            "give exactly one of rpy_rad and quaternion_xyzw".to_string(),
        )),
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::FRAC_PI_2;

    use super::*;

    /// An example for `launch_configs/`: the vertical-axis tasks with a Y-up tracker.
    const EXAMPLE_TOML: &str = r#"
# Arm mapping for the POMDAR vertical-axis tasks (V1-V3, C1-C3).
constraint = "vertical_axis"            # fixed | vertical_axis | horizontal_axis | free
orientation = "hold_when_constrained"   # hold_when_constrained | hold | twist_about_axis
vertical_axis = [0.0, 0.0, 1.0]         # unit vector, robot base frame
horizontal_axis = [1.0, 0.0, 0.0]       # unit vector, robot base frame
translation_scale = 1.0                 # robot metres per glove metre
workspace_min_m = [0.25, -0.45, 0.05]   # robot base frame; measure on your table
workspace_max_m = [0.75, 0.45, 0.75]
max_translation_step_m = 0.01           # per tick, on the norm of the step
max_rotation_step_rad = 0.02            # per tick, on the rotation angle of the step

# Tracker frame -> robot base frame (v_base = R * v_tracker): here a Y-up tracker.
[glove_to_base]
rpy_rad = [1.5707963267948966, 0.0, 0.0]

# Used at engage when there is no arm pose feedback; must lie inside the box.
[start_pose]
position_m = [0.45, 0.0, 0.40]
quaternion_xyzw = [1.0, 0.0, 0.0, 0.0]
"#;

    fn error_of(toml_text: &str) -> String {
        ArmConfig::from_toml_str(toml_text).unwrap_err().to_string()
    }

    #[test]
    fn the_example_parses_and_validates() {
        let config = ArmConfig::from_toml_str(EXAMPLE_TOML).unwrap();
        assert_eq!(config.constraint, Constraint::VerticalAxis);
        assert_eq!(config.orientation, OrientationPolicy::HoldWhenConstrained);
        assert_eq!(
            config.axis_of(Constraint::VerticalAxis).unwrap(),
            Some(Vector3::z_axis())
        );
        // The tracker's up (y) is the base's up (z).
        let r = config.glove_to_base_rotation().unwrap();
        assert!((r * Vector3::y() - Vector3::z()).norm() < 1e-12);
        let start = config.start_pose_isometry().unwrap();
        assert_eq!(start.translation.vector, Vector3::new(0.45, 0.0, 0.40));
        assert!(
            (start.rotation.angle_to(&UnitQuaternion::from_euler_angles(
                std::f64::consts::PI,
                0.0,
                0.0
            )))
            .abs()
                < 1e-12
        );
    }

    #[test]
    fn an_empty_file_is_the_validated_default() {
        let config = ArmConfig::from_toml_str("").unwrap();
        assert_eq!(config, ArmConfig::default());
        assert_eq!(config.constraint, Constraint::Fixed);
        assert_eq!(config.max_translation_step_m, 0.01);
        assert_eq!(config.max_rotation_step_rad, 0.02);
    }

    #[test]
    fn the_default_round_trips_through_toml() {
        let text = toml::to_string(&ArmConfig::default()).unwrap();
        assert_eq!(
            ArmConfig::from_toml_str(&text).unwrap(),
            ArmConfig::default()
        );
    }

    #[test]
    fn unknown_keys_are_rejected_by_name() {
        let e = error_of("max_step_m = 0.1");
        assert!(e.contains("max_step_m"), "{e}");
        let e = error_of("[start_pose]\nposition_m = [0.5, 0.0, 0.4]\nyaw = 1.0");
        assert!(e.contains("yaw"), "{e}");
        let e = error_of("constraint = \"diagonal\"");
        assert!(e.contains("diagonal"), "{e}");
    }

    #[test]
    fn out_of_range_values_name_the_key_and_the_range() {
        for (text, key, range) in [
            ("translation_scale = 0.0", "translation_scale", "[0.01, 10]"),
            (
                "max_translation_step_m = 0.5",
                "max_translation_step_m",
                "(0, 0.1]",
            ),
            (
                "max_rotation_step_rad = -0.1",
                "max_rotation_step_rad",
                "(0, 0.5]",
            ),
            (
                "max_rotation_step_rad = nan",
                "max_rotation_step_rad",
                "(0, 0.5]",
            ),
            (
                "vertical_axis = [0.0, 0.0, 2.0]",
                "vertical_axis",
                "unit vector",
            ),
            (
                "horizontal_axis = [0.0, 0.0, 0.0]",
                "horizontal_axis",
                "unit vector",
            ),
            (
                "workspace_max_m = [0.75, 0.45, 3.0]",
                "workspace_max_m",
                "[-2, 2] m",
            ),
            (
                "workspace_min_m = [0.8, -0.45, 0.05]",
                "workspace_min_m",
                "below workspace_max_m",
            ),
            (
                "[start_pose]\nposition_m = [0.45, 0.0, 0.9]\nrpy_rad = [0.0, 0.0, 0.0]",
                "start_pose.position_m",
                "z must be in [0.05, 0.75] m",
            ),
            (
                "[start_pose]\nposition_m = [0.45, 0.0, 0.4]",
                "start_pose",
                "exactly one of rpy_rad and quaternion_xyzw",
            ),
            (
                "[glove_to_base]\nrpy_rad = [0.0, 0.0, 0.0]\nquaternion_xyzw = [0.0, 0.0, 0.0, 1.0]",
                "glove_to_base",
                "exactly one of",
            ),
            (
                "[glove_to_base]\nquaternion_xyzw = [0.0, 0.0, 0.0, 0.5]",
                "glove_to_base.quaternion_xyzw",
                "unit quaternion",
            ),
        ] {
            let e = error_of(text);
            assert!(e.contains(&format!("'{key}'")), "{text}: {e}");
            assert!(e.contains(range), "{text}: {e}");
        }
    }

    #[test]
    fn nearly_unit_axes_are_normalised() {
        let config = ArmConfig::from_toml_str("horizontal_axis = [0.7071, 0.7071, 0.0]").unwrap();
        let axis = config.axis_of(Constraint::HorizontalAxis).unwrap().unwrap();
        assert!((axis.norm() - 1.0).abs() < 1e-15);
        assert!((axis.into_inner() - Vector3::new(1.0, 1.0, 0.0).normalize()).norm() < 1e-12);
        assert_eq!(config.axis_of(Constraint::Free).unwrap(), None);
        assert_eq!(config.axis_of(Constraint::Fixed).unwrap(), None);
    }

    #[test]
    fn rpy_follows_the_urdf_convention() {
        let config =
            ArmConfig::from_toml_str("[glove_to_base]\nrpy_rad = [0.0, 0.0, 1.5707963267948966]")
                .unwrap();
        let r = config.glove_to_base_rotation().unwrap();
        // Yaw +90°: x to y.
        assert!((r * Vector3::x() - Vector3::y()).norm() < 1e-12);
        assert!((r.angle() - FRAC_PI_2).abs() < 1e-12);
    }
}
