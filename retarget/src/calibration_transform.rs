//! The per-user calibration transform: a global scale and a rotation applied to the human key
//! vectors in the human palm frame before retargeting (identity by default; the calibration
//! crate fits it on seven poses).

use nalgebra::{Matrix3, Rotation3, Vector3};
use serde::{Deserialize, Serialize};

use crate::error::Error;

/// `v ↦ scale · R(roll, pitch, yaw) · v`, with R the URDF/ROS fixed-axis roll-pitch-yaw
/// rotation, acting in the human palm frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CalibrationTransform {
    /// Human-to-robot scale (dimensionless, > 0).
    pub scale: f64,
    /// Rotation about the palm x axis, radians.
    pub roll_rad: f64,
    /// Rotation about the palm y axis, radians.
    pub pitch_rad: f64,
    /// Rotation about the palm z axis, radians.
    pub yaw_rad: f64,
}

impl Default for CalibrationTransform {
    fn default() -> Self {
        CalibrationTransform::IDENTITY
    }
}

impl CalibrationTransform {
    /// No scaling, no rotation.
    pub const IDENTITY: CalibrationTransform = CalibrationTransform {
        scale: 1.0,
        roll_rad: 0.0,
        pitch_rad: 0.0,
        yaw_rad: 0.0,
    };

    /// Check the values: scale in (0.2, 5), angles within ±π, all finite.
    pub fn validate(&self) -> Result<(), Error> {
        let bad = |key: &str, value: f64, allowed: &str| Error::ConfigRange {
            key: key.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        };
        if !(self.scale.is_finite() && self.scale > 0.2 && self.scale < 5.0) {
            return Err(bad("calibration.scale", self.scale, "must be in (0.2, 5)"));
        }
        for (key, value) in [
            ("calibration.roll_rad", self.roll_rad),
            ("calibration.pitch_rad", self.pitch_rad),
            ("calibration.yaw_rad", self.yaw_rad),
        ] {
            if !(value.is_finite() && value.abs() <= std::f64::consts::PI) {
                return Err(bad(key, value, "must be in [-π, π]"));
            }
        }
        Ok(())
    }

    /// The rotation part.
    pub fn rotation(&self) -> Rotation3<f64> {
        Rotation3::from_euler_angles(self.roll_rad, self.pitch_rad, self.yaw_rad)
    }

    /// The linear map `scale · R`.
    pub fn matrix(&self) -> Matrix3<f64> {
        self.rotation().into_inner() * self.scale
    }

    /// Apply to one vector.
    pub fn apply(&self, v: &Vector3<f64>) -> Vector3<f64> {
        self.rotation() * v * self.scale
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identity_changes_nothing_and_scale_rotation_compose() {
        let v = Vector3::new(0.01, 0.08, -0.02);
        assert_eq!(CalibrationTransform::IDENTITY.apply(&v), v);
        let t = CalibrationTransform {
            scale: 2.0,
            yaw_rad: std::f64::consts::FRAC_PI_2,
            ..CalibrationTransform::IDENTITY
        };
        let out = t.apply(&Vector3::new(1.0, 0.0, 0.0));
        assert!((out - Vector3::new(0.0, 2.0, 0.0)).norm() < 1e-12);
        assert!((t.matrix() * Vector3::new(1.0, 0.0, 0.0) - out).norm() < 1e-12);
    }

    #[test]
    fn out_of_range_scale_is_named() {
        let t = CalibrationTransform {
            scale: 0.0,
            ..CalibrationTransform::IDENTITY
        };
        assert!(
            t.validate()
                .unwrap_err()
                .to_string()
                .contains("calibration.scale")
        );
    }
}
