//! The per-user calibration transform: a global scale and a rotation applied to the human key
//! vectors in the human palm frame before retargeting, and optionally a length factor per
//! digit (identity by default; the calibration crate fits it on seven poses).
//!
//! A digit's factor scales its points about the digit's base keypoint (finger MCP, thumb
//! CMC), before the global map: a point `p` of digit `i` with base `b` becomes
//! `s · R · (b + f_i · (p − b))`. The palm's size and the glove's orientation stay global;
//! a thumb longer than the average hand's, relative to the palm, is what `f_thumb` takes up.

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
    /// Length factor per digit about its base (indexed by [`Finger::index`](crate::Finger));
    /// all 1 for the global model, and then not written to a file. Missing in a file: all 1.
    #[serde(default = "unit_digits", skip_serializing_if = "is_unit")]
    pub digit_scale: [f64; 5],
}

fn unit_digits() -> [f64; 5] {
    [1.0; 5]
}

fn is_unit(digits: &[f64; 5]) -> bool {
    *digits == [1.0; 5]
}

/// Allowed range of a digit's length factor (exclusive).
pub const DIGIT_SCALE_RANGE: (f64, f64) = (0.5, 2.0);

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
        digit_scale: [1.0; 5],
    };

    /// Whether it has a length factor per digit (the per-digit model), not only the global map.
    pub fn has_digit_scales(&self) -> bool {
        !is_unit(&self.digit_scale)
    }

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
        let (low, high) = DIGIT_SCALE_RANGE;
        if let Some(&f) = self
            .digit_scale
            .iter()
            .find(|f| !(f.is_finite() && **f > low && **f < high))
        {
            return Err(bad(
                "calibration.digit_scale",
                f,
                "each must be in (0.5, 2)",
            ));
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

    /// A point `p` of digit `digit` (index by [`Finger::index`](crate::Finger)) whose base is
    /// `base`, both in the human palm frame, with the digit's length factor applied:
    /// `b + f · (p − b)` (the global map [`matrix`](CalibrationTransform::matrix) comes after).
    pub fn lengthen_digit(
        &self,
        digit: usize,
        base: &Vector3<f64>,
        p: &Vector3<f64>,
    ) -> Vector3<f64> {
        let f = self.digit_scale.get(digit).copied().unwrap_or(1.0);
        base + f * (p - base)
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
    fn a_digit_factor_scales_about_the_base_and_the_global_model_writes_none() {
        let t = CalibrationTransform {
            digit_scale: [1.2, 1.0, 1.0, 1.0, 1.0],
            ..CalibrationTransform::IDENTITY
        };
        let (base, tip) = (Vector3::new(0.02, 0.03, 0.0), Vector3::new(0.02, 0.08, 0.0));
        assert!((t.lengthen_digit(0, &base, &tip) - Vector3::new(0.02, 0.09, 0.0)).norm() < 1e-12);
        assert_eq!(t.lengthen_digit(1, &base, &tip), tip);
        assert!(t.has_digit_scales() && !CalibrationTransform::IDENTITY.has_digit_scales());
        let global = toml::to_string(&CalibrationTransform::IDENTITY).unwrap();
        assert!(!global.contains("digit_scale"), "{global}");
        let read: CalibrationTransform = toml::from_str(&global).unwrap();
        assert_eq!(read, CalibrationTransform::IDENTITY);
        let per_digit: CalibrationTransform =
            toml::from_str(&toml::to_string(&t).unwrap()).unwrap();
        assert_eq!(per_digit, t);
        let bad = CalibrationTransform {
            digit_scale: [1.0, 3.0, 1.0, 1.0, 1.0],
            ..t
        };
        assert!(
            bad.validate()
                .unwrap_err()
                .to_string()
                .contains("digit_scale")
        );
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
