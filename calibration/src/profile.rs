//! The calibration profile: one TOML file per user, written after a successful fit and loaded
//! by the station (`--profile` / `calibration_profile`).
//!
//! ```toml
//! user = "alice"
//! date = "2026-11-21T10:32:05Z"
//! glove = "rokoko-smartgloves"
//! model = "orca_v1_right"
//! layout = "lab22"
//! source = "calibration_alice.mcap"
//! calibration_model = "per_digit"   # or "global" (the default when missing)
//!
//! [parameters]          # retarget::CalibrationTransform
//! scale = 1.07
//! roll_rad = 0.01
//! pitch_rad = -0.12
//! yaw_rad = 0.05
//! digit_scale = [0.88, 1.02, 0.97, 1.0, 0.99]   # per_digit only: thumb, index, middle, ring, little
//!
//! [objective]
//! before_rad = 0.21
//! after_rad = 0.06
//! evaluations = 60
//!
//! [[pose]]
//! name = "pinch_index"
//! joint_rms_before_rad = 0.25
//! joint_rms_after_rad = 0.07
//! pinch_gap_before_mm = 14.0
//! pinch_gap_after_mm = 2.1
//! ```

use retarget::{CalibrationTransform, HandModel, KeypointLayout};
use serde::{Deserialize, Serialize};

use crate::error::Error;
use crate::fit::Calibration;
use crate::poses::POSE_NAMES;
use crate::settings::CalibrationModel;

/// A user's calibration.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CalibrationProfile {
    /// Who was calibrated.
    pub user: String,
    /// When, ISO 8601 UTC.
    pub date: String,
    /// Which glove (free text, e.g. its model or serial).
    pub glove: String,
    /// The robot hand model the poses and the fit were made for.
    pub model: String,
    /// The keypoint layout of the glove stream.
    pub layout: KeypointLayout,
    /// Where the captures came from (a session file, or a simulation's description).
    pub source: String,
    /// Which transform was fitted: `global` or `per_digit` (missing in older profiles:
    /// global).
    #[serde(default)]
    pub calibration_model: CalibrationModel,
    /// The fitted transform.
    pub parameters: CalibrationTransform,
    /// The objective before and after.
    pub objective: ObjectiveSummary,
    /// Per-pose errors, in capture order.
    #[serde(rename = "pose")]
    pub poses: Vec<PoseReport>,
}

/// The objective before and after the fit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectiveSummary {
    /// With no calibration, radians.
    pub before_rad: f64,
    /// With the fitted transform, radians.
    pub after_rad: f64,
    /// Evaluations the optimiser made.
    pub evaluations: usize,
}

/// One pose's errors before and after.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PoseReport {
    /// The pose.
    pub name: String,
    /// RMS joint error with no calibration, radians.
    pub joint_rms_before_rad: f64,
    /// RMS joint error with the fitted transform, radians.
    pub joint_rms_after_rad: f64,
    /// Pinch poses: robot gap error with no calibration, mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pinch_gap_before_mm: Option<f64>,
    /// Pinch poses: robot gap error with the fitted transform, mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pinch_gap_after_mm: Option<f64>,
}

/// Who, when and what a profile is for.
#[derive(Debug, Clone, PartialEq)]
pub struct ProfileHeader {
    /// The user.
    pub user: String,
    /// ISO 8601 UTC date (the caller's clock: this crate has none).
    pub date: String,
    /// The glove.
    pub glove: String,
    /// The source of the captures.
    pub source: String,
}

impl CalibrationProfile {
    /// The profile of a finished calibration.
    pub fn new(
        header: ProfileHeader,
        model: &HandModel,
        layout: KeypointLayout,
        calibration: &Calibration,
    ) -> CalibrationProfile {
        let poses = calibration
            .before
            .poses
            .iter()
            .zip(&calibration.after.poses)
            .map(|(b, a)| PoseReport {
                name: b.pose.clone(),
                joint_rms_before_rad: b.joint_rms_rad,
                joint_rms_after_rad: a.joint_rms_rad,
                pinch_gap_before_mm: b.pinch_gap_error_m.map(|m| m * 1e3),
                pinch_gap_after_mm: a.pinch_gap_error_m.map(|m| m * 1e3),
            })
            .collect();
        CalibrationProfile {
            user: header.user,
            date: header.date,
            glove: header.glove,
            model: model.name().to_string(),
            layout,
            source: header.source,
            calibration_model: calibration.model,
            parameters: calibration.transform,
            objective: ObjectiveSummary {
                before_rad: calibration.before.value,
                after_rad: calibration.after.value,
                evaluations: calibration.evaluations(),
            },
            poses,
        }
    }

    /// Parse and validate a profile.
    pub fn from_toml_str(text: &str) -> Result<CalibrationProfile, Error> {
        let profile: CalibrationProfile = toml::from_str(text).map_err(|e| Error::Syntax {
            reason: e.to_string().trim_end().to_string(),
        })?;
        profile.validate()?;
        Ok(profile)
    }

    /// The profile as TOML.
    pub fn to_toml_string(&self) -> Result<String, Error> {
        toml::to_string(self).map_err(|e| Error::Syntax {
            reason: e.to_string(),
        })
    }

    /// Check the values: a user name, the parameters in range, finite non-negative errors,
    /// the seven poses.
    pub fn validate(&self) -> Result<(), Error> {
        let bad = |key: &str, value: String, allowed: &str| Error::Setting {
            key: key.into(),
            value,
            allowed: allowed.into(),
        };
        if self.user.trim().is_empty() {
            return Err(bad("user", "\"\"".into(), "must name the user"));
        }
        self.parameters.validate().map_err(|e| match e {
            retarget::Error::ConfigRange {
                key,
                value,
                allowed,
            } => Error::Setting {
                key: key.replacen("calibration.", "parameters.", 1),
                value,
                allowed,
            },
            other => Error::Retarget(other),
        })?;
        let finite = |key: &str, v: f64| {
            if v.is_finite() && v >= 0.0 {
                Ok(())
            } else {
                Err(bad(key, v.to_string(), "must be finite and ≥ 0"))
            }
        };
        finite("objective.before_rad", self.objective.before_rad)?;
        finite("objective.after_rad", self.objective.after_rad)?;
        let names: Vec<&str> = self.poses.iter().map(|p| p.name.as_str()).collect();
        if names != POSE_NAMES {
            return Err(bad(
                "pose",
                names.join(", "),
                &format!("must report the poses {POSE_NAMES:?} in this order"),
            ));
        }
        for p in &self.poses {
            finite("pose.joint_rms_before_rad", p.joint_rms_before_rad)?;
            finite("pose.joint_rms_after_rad", p.joint_rms_after_rad)?;
            for v in [p.pinch_gap_before_mm, p.pinch_gap_after_mm]
                .into_iter()
                .flatten()
            {
                finite("pose.pinch_gap_mm", v)?;
            }
        }
        Ok(())
    }

    /// Check that the profile was made for `model` and `layout`.
    pub fn check_fits(&self, model: &HandModel, layout: KeypointLayout) -> Result<(), Error> {
        if self.model != model.name() {
            return Err(Error::Setting {
                key: "model".into(),
                value: self.model.clone(),
                allowed: format!("the station runs model '{}'", model.name()),
            });
        }
        if self.layout != layout {
            return Err(Error::Setting {
                key: "layout".into(),
                value: self.layout.name().to_string(),
                allowed: format!("the station expects layout '{}'", layout.name()),
            });
        }
        Ok(())
    }
}
