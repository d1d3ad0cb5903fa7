//! Calibration settings (TOML, every key optional): the parameter bounds, the optimiser's
//! budget and seed, the pinch term's weight, the capture thresholds, the transform's model and
//! the check of the fitted poses. Validated on load with errors that name the key and the
//! allowed range.

use serde::{Deserialize, Serialize};

use crate::error::Error;

/// Everything the calibration needs besides the model, the retargeting configuration and the
/// poses.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CalibrationSettings {
    /// Bounds of the fitted parameters.
    pub bounds: ParameterBounds,
    /// The Bayesian optimiser.
    pub optimiser: OptimiserSettings,
    /// Objective: radians of joint RMS error charged per metre of pinch-gap error on the
    /// pinch poses (10 rad/m: 1 cm of gap costs as much as 0.1 rad on every joint).
    pub pinch_weight_rad_per_m: f64,
    /// When a capture is accepted.
    pub capture: CaptureThresholds,
    /// Which transform is fitted: `global` (scale and rotation) or `per_digit` (also a length
    /// factor per digit).
    pub model: CalibrationModel,
    /// When a pose counts as not fitted after the fit (the console offers to redo it).
    pub fit_check: FitCheck,
}

/// The calibration transform's model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum CalibrationModel {
    /// One scale and one rotation for the whole hand (the paper's).
    #[default]
    Global,
    /// The global fit, then a length factor per digit about its base, searched on the
    /// objective one digit at a time; kept only where it lowers the objective.
    PerDigit,
}

impl CalibrationModel {
    /// `global` or `per_digit`: the word in files and tables.
    pub fn name(self) -> &'static str {
        match self {
            CalibrationModel::Global => "global",
            CalibrationModel::PerDigit => "per_digit",
        }
    }
}

/// Box bounds of the four parameters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ParameterBounds {
    /// Smallest human-to-robot scale.
    pub scale_min: f64,
    /// Largest human-to-robot scale.
    pub scale_max: f64,
    /// Largest rotation about each palm axis (roll, pitch, yaw), either sign, degrees.
    pub angle_max_deg: f64,
}

/// The Bayesian optimiser's budget.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OptimiserSettings {
    /// Objective evaluations of the Bayesian optimisation, the initial design included.
    pub evaluations: usize,
    /// Evaluations of each of the two Nelder–Mead polishes after the Bayesian search (0: none).
    pub polish_evaluations: usize,
    /// Points of the space-filling (Latin hypercube) initial design.
    pub initial_design: usize,
    /// Seed of the initial design and of the acquisition's multistart: a fixed seed makes a
    /// calibration repeatable.
    pub seed: u64,
}

/// Thresholds a one-second capture of one pose must meet.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CaptureThresholds {
    /// Fewest valid frames (1 s at 25 Hz is 25).
    pub min_frames: usize,
    /// Largest share of frames that may be invalid (wrong count, non-finite, collapsed palm).
    pub max_invalid_fraction: f64,
    /// Largest RMS deviation of any keypoint from its mean, in the palm frame, metres: above
    /// it the hand moved during the capture.
    pub max_point_sd_m: f64,
}

/// When a pose counts as not fitted, after the fit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FitCheck {
    /// A pinch pose whose robot thumb–finger gap is further than this from the pose's, mm.
    pub pinch_gap_mm: f64,
    /// A pose whose joints are further than this from the pose's (RMS over the free joints),
    /// radians.
    pub joint_rms_rad: f64,
}

impl Default for FitCheck {
    fn default() -> Self {
        FitCheck {
            pinch_gap_mm: 40.0,
            joint_rms_rad: 0.38,
        }
    }
}

impl Default for ParameterBounds {
    fn default() -> Self {
        ParameterBounds {
            scale_min: 0.6,
            scale_max: 1.6,
            angle_max_deg: 30.0,
        }
    }
}

impl Default for OptimiserSettings {
    fn default() -> Self {
        OptimiserSettings {
            evaluations: 60,
            polish_evaluations: 40,
            initial_design: 20,
            seed: 42,
        }
    }
}

impl Default for CaptureThresholds {
    fn default() -> Self {
        CaptureThresholds {
            min_frames: 20,
            max_invalid_fraction: 0.2,
            max_point_sd_m: 0.012,
        }
    }
}

impl Default for CalibrationSettings {
    fn default() -> Self {
        CalibrationSettings {
            bounds: ParameterBounds::default(),
            optimiser: OptimiserSettings::default(),
            pinch_weight_rad_per_m: 10.0,
            capture: CaptureThresholds::default(),
            model: CalibrationModel::default(),
            fit_check: FitCheck::default(),
        }
    }
}

fn range(key: &str, value: f64, lo: f64, hi: f64) -> Result<(), Error> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(())
    } else {
        Err(Error::Setting {
            key: key.into(),
            value: value.to_string(),
            allowed: format!("must be in [{lo}, {hi}]"),
        })
    }
}

impl CalibrationSettings {
    /// Parse and validate settings; missing keys take their defaults.
    pub fn from_toml_str(text: &str) -> Result<CalibrationSettings, Error> {
        let settings: CalibrationSettings = toml::from_str(text).map_err(|e| Error::Syntax {
            reason: e.to_string().trim_end().to_string(),
        })?;
        settings.validate()?;
        Ok(settings)
    }

    /// Check every value against its allowed range.
    pub fn validate(&self) -> Result<(), Error> {
        let b = &self.bounds;
        range("bounds.scale_min", b.scale_min, 0.25, 4.0)?;
        range("bounds.scale_max", b.scale_max, 0.25, 4.0)?;
        if b.scale_max <= b.scale_min * 1.01 {
            return Err(Error::Setting {
                key: "bounds.scale_max".into(),
                value: b.scale_max.to_string(),
                allowed: format!("must exceed bounds.scale_min ({}) by 1 %", b.scale_min),
            });
        }
        range("bounds.angle_max_deg", b.angle_max_deg, 1.0, 90.0)?;
        let o = &self.optimiser;
        range("optimiser.evaluations", o.evaluations as f64, 10.0, 1000.0)?;
        range(
            "optimiser.polish_evaluations",
            o.polish_evaluations as f64,
            0.0,
            1000.0,
        )?;
        range(
            "optimiser.initial_design",
            o.initial_design as f64,
            5.0,
            (o.evaluations - 1) as f64,
        )?;
        range(
            "pinch_weight_rad_per_m",
            self.pinch_weight_rad_per_m,
            0.0,
            1000.0,
        )?;
        let c = &self.capture;
        range("capture.min_frames", c.min_frames as f64, 1.0, 10_000.0)?;
        range(
            "capture.max_invalid_fraction",
            c.max_invalid_fraction,
            0.0,
            0.9,
        )?;
        range("capture.max_point_sd_m", c.max_point_sd_m, 1e-4, 0.05)?;
        range(
            "fit_check.pinch_gap_mm",
            self.fit_check.pinch_gap_mm,
            0.5,
            100.0,
        )?;
        range(
            "fit_check.joint_rms_rad",
            self.fit_check.joint_rms_rad,
            0.01,
            2.0,
        )?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_an_empty_file_gives_them() {
        assert_eq!(
            CalibrationSettings::from_toml_str("").unwrap(),
            CalibrationSettings::default()
        );
    }

    #[test]
    fn errors_name_the_key_and_range() {
        let e = CalibrationSettings::from_toml_str("[optimiser]\ninitial_design = 80\n")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("optimiser.initial_design") && e.contains("[5, 59]"),
            "{e}"
        );
        let e = CalibrationSettings::from_toml_str("[bounds]\nscale_min = 1.2\nscale_max = 1.1\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("bounds.scale_max"), "{e}");
        let e = CalibrationSettings::from_toml_str("[capture]\nmax_point_sd = 1\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("max_point_sd"), "{e}");
    }
}
