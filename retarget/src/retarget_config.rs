//! Retargeting configuration (TOML), validated on load with errors that name the key and the
//! allowed range. Every key has a default; `launch_configs/retarget/orca_full_lab22.toml`
//! spells the defaults out for operators to edit.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::error::Error;
use crate::keypoint_layout::KeypointLayout;
use crate::one_euro::InputFilterConfig;

/// Everything the retargeter needs besides the hand model and the calibration.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RetargetConfig {
    /// Layout of the incoming human keypoints.
    pub layout: KeypointLayout,
    /// Embodiment name from the catalog: which joints may move.
    pub embodiment: String,
    /// Key-vector weights.
    pub weights: KeyVectorWeights,
    /// Pinch and finger-separation terms.
    pub pinch: PinchConfig,
    /// Huber threshold on each key-vector residual, metres: beyond it a residual's pull grows
    /// linearly, so one bad keypoint cannot throw the hand.
    pub huber_delta_m: f64,
    /// Regularisers.
    pub regularisation: Regularisation,
    /// Speed-adaptive low-pass (1€) on the human key points before the energy.
    pub input_filter: InputFilterConfig,
    /// Extra pull toward the previous command on frames the robot cannot reproduce.
    pub smoothing: SmoothingConfig,
    /// Per-frame solver settings.
    pub solver: SolverConfig,
    /// Rest posture of abduction joints, radians, by joint name; the `rest_posture`
    /// regulariser pulls these joints toward it.
    pub rest_posture_rad: BTreeMap<String, f64>,
}

/// Weights of the two families of key vectors (dimensionless, per m² of residual).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct KeyVectorWeights {
    /// The 5 palm-centre → fingertip vectors.
    pub palm_to_tip: f64,
    /// The 10 fingertip → fingertip vectors.
    pub tip_to_tip: f64,
    /// The 5 palm-centre → digit mid point vectors (finger PIP, thumb MCP); 0 disables them.
    /// Ignored for models that name no mid frames.
    pub palm_to_mid: f64,
}

/// Pinch blending: when the human thumb tip nears a fingertip, the robot pair is pulled
/// together; fingers next to a pinching finger are kept apart.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PinchConfig {
    /// Extra weight on a thumb → finger vector at full pinch.
    pub weight: f64,
    /// Human thumb-tip to fingertip distance at or below which the pinch is full, metres.
    pub engage_m: f64,
    /// Distance at or above which there is no pinch, metres (smooth blend in between).
    pub release_m: f64,
    /// Distance under which the thumb approaching its nearest finger weighs their vector more,
    /// up to a fingertip placement's weight at `release_m`, metres; at or under `release_m`
    /// there is no approach (see `energy::approach_weights`).
    pub approach_m: f64,
    /// Robot thumb-tip to fingertip distance aimed for at full pinch, metres.
    pub closed_gap_m: f64,
    /// Extra weight keeping a pinching finger's neighbours at least `separation_m` away.
    pub separation_weight: f64,
    /// Minimum robot fingertip spacing next to a pinching finger, metres.
    pub separation_m: f64,
}

/// Regularisers of the energy (dimensionless weights per rad²).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Regularisation {
    /// Pull toward the previous command (smoothness without an output filter's lag).
    pub previous_command: f64,
    /// Pull of abduction joints toward `rest_posture_rad`.
    pub rest_posture: f64,
    /// Levenberg damping added to the step's Hessian only (not to the energy).
    pub damping: f64,
}

/// Residual-adaptive smoothing: on a frame whose fingertips the robot cannot reach (glove
/// noise, a hand shape outside the robot's range), the solution is ill determined and noise
/// moves it from frame to frame; there the pull toward the previous command grows. A frame
/// the robot can reproduce gets none of it, so reachable motion is tracked without lag.
///
/// Each frame is first solved with `regularisation.previous_command`; with `ē` the mean
/// palm → fingertip residual of that solve and `x = (ē / residual_m)²`, it is solved again
/// from the same previous command with the pull raised by `smoothing.previous_command ·
/// x / (1 + x) / (1 + (v / release_speed_m_s)²)`, `v` the fastest human key point's speed
/// (the input filter's estimate): fast motion is followed without the pull's lag.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SmoothingConfig {
    /// Extra weight toward the previous command at full effect (per rad²); 0 disables the
    /// second solve.
    pub previous_command: f64,
    /// Mean fingertip residual at which half of the extra weight applies, metres.
    pub residual_m: f64,
    /// Speed of the fastest human key point (the input filter's estimate) at which the extra
    /// weight halves, m/s: fast motion is followed without lag. 0 ignores the speed.
    pub release_speed_m_s: f64,
    /// Thumb–finger distance (the human's) under which a closing pinch frees its two digits
    /// from the extra weight, metres (see `pinch_approach`).
    pub approach_range_m: f64,
    /// Closing speed of a pinch at which its two digits keep half of the extra weight, m/s;
    /// 0: a closing pinch frees nothing.
    pub approach_speed_m_s: f64,
}

/// Per-frame Gauss–Newton settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SolverConfig {
    /// Gauss–Newton steps (one QP each) at most per frame.
    pub steps_per_frame: u32,
    /// A step smaller than this (max-norm, radians) ends the frame as converged.
    pub step_tolerance_rad: f64,
    /// Joint speed limit, rad/s: each frame's command stays within `max_joint_speed_rad_s ×
    /// min(dt, max_rate_dt_s)` of the previous one.
    pub max_joint_speed_rad_s: f64,
    /// Longest time step credited to the rate limit, seconds (a gap in the glove stream does
    /// not allow a jump).
    pub max_rate_dt_s: f64,
    /// Interior-point iterations at most per QP.
    pub qp_max_iterations: u32,
    /// How each step's box QP is solved.
    pub qp_method: QpMethod,
}

/// How a Gauss–Newton step's box QP is solved. Both give the QP's minimiser; they differ in
/// speed (on the reference recording, 34 µs against 148 µs per frame p50).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum QpMethod {
    /// An exact primal active-set method certified by the KKT conditions, with Clarabel for
    /// any step it cannot certify (the default).
    ActiveSet,
    /// Clarabel's interior-point method for every step.
    Clarabel,
}

impl Default for RetargetConfig {
    fn default() -> Self {
        RetargetConfig {
            layout: KeypointLayout::Lab22,
            embodiment: "orca_full".into(),
            weights: KeyVectorWeights::default(),
            pinch: PinchConfig::default(),
            huber_delta_m: 0.02,
            regularisation: Regularisation::default(),
            input_filter: InputFilterConfig::default(),
            smoothing: SmoothingConfig::default(),
            solver: SolverConfig::default(),
            rest_posture_rad: BTreeMap::from([
                ("thumb_mcp".to_string(), 0.0),
                ("thumb_abd".to_string(), -0.5),
                ("index_abd".to_string(), 0.12),
                ("middle_abd".to_string(), 0.0),
                ("ring_abd".to_string(), -0.14),
                ("pinky_abd".to_string(), -0.06),
            ]),
        }
    }
}

impl Default for KeyVectorWeights {
    fn default() -> Self {
        KeyVectorWeights {
            palm_to_tip: 2.0,
            tip_to_tip: 0.5,
            palm_to_mid: 1.0,
        }
    }
}

impl Default for PinchConfig {
    fn default() -> Self {
        PinchConfig {
            weight: 15.0,
            engage_m: 0.022,
            release_m: 0.04,
            approach_m: 0.06,
            closed_gap_m: 0.005,
            separation_weight: 2.0,
            separation_m: 0.03,
        }
    }
}

impl Default for Regularisation {
    fn default() -> Self {
        Regularisation {
            previous_command: 1e-4,
            rest_posture: 1e-5,
            damping: 1e-6,
        }
    }
}

impl SmoothingConfig {
    /// Check every value against its allowed range.
    fn validate(&self) -> Result<(), Error> {
        let sm = self;
        in_range("smoothing.previous_command", sm.previous_command, 0.0, 10.0)?;
        in_range("smoothing.residual_m", sm.residual_m, 1e-4, 1.0)?;
        in_range(
            "smoothing.release_speed_m_s",
            sm.release_speed_m_s,
            0.0,
            10.0,
        )?;
        in_range("smoothing.approach_range_m", sm.approach_range_m, 0.0, 0.5)?;
        in_range(
            "smoothing.approach_speed_m_s",
            sm.approach_speed_m_s,
            0.0,
            10.0,
        )?;
        Ok(())
    }
}

/// `key`'s `value` must be finite and in `[lo, hi]`.
fn in_range(key: &str, value: f64, lo: f64, hi: f64) -> Result<(), Error> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(())
    } else {
        Err(Error::ConfigRange {
            key: key.into(),
            value: value.to_string(),
            allowed: format!("must be in [{lo}, {hi}]"),
        })
    }
}

impl Default for SmoothingConfig {
    fn default() -> Self {
        SmoothingConfig {
            previous_command: 0.03,
            residual_m: 0.01,
            release_speed_m_s: 0.3,
            approach_range_m: 0.06,
            approach_speed_m_s: 0.5,
        }
    }
}

impl Default for SolverConfig {
    fn default() -> Self {
        SolverConfig {
            steps_per_frame: 2,
            step_tolerance_rad: 1e-4,
            max_joint_speed_rad_s: 12.0,
            max_rate_dt_s: 0.0247,
            qp_max_iterations: 50,
            qp_method: QpMethod::ActiveSet,
        }
    }
}

impl RetargetConfig {
    /// Parse and validate a TOML configuration; missing keys take their defaults.
    pub fn from_toml_str(text: &str) -> Result<RetargetConfig, Error> {
        let config: RetargetConfig = toml::from_str(text).map_err(|e| Error::Syntax {
            reason: e.to_string().trim_end().to_string(),
        })?;
        config.validate()?;
        Ok(config)
    }

    /// Check every value against its allowed range.
    pub fn validate(&self) -> Result<(), Error> {
        let range = in_range;
        let w = &self.weights;
        range("weights.palm_to_tip", w.palm_to_tip, 0.0, 1e3)?;
        range("weights.tip_to_tip", w.tip_to_tip, 0.0, 1e3)?;
        range("weights.palm_to_mid", w.palm_to_mid, 0.0, 1e3)?;
        if w.palm_to_tip + w.tip_to_tip <= 0.0 {
            return Err(Error::ConfigRange {
                key: "weights".into(),
                value: "0".into(),
                allowed: "palm_to_tip + tip_to_tip must be positive".into(),
            });
        }
        let p = &self.pinch;
        range("pinch.weight", p.weight, 0.0, 1e4)?;
        range("pinch.engage_m", p.engage_m, 0.0, 0.1)?;
        range("pinch.release_m", p.release_m, 0.0, 0.2)?;
        if p.release_m <= p.engage_m {
            return Err(Error::ConfigRange {
                key: "pinch.release_m".into(),
                value: p.release_m.to_string(),
                allowed: format!("must be greater than pinch.engage_m = {}", p.engage_m),
            });
        }
        range("pinch.approach_m", p.approach_m, 0.0, 0.2)?;
        range("pinch.closed_gap_m", p.closed_gap_m, 0.0, 0.05)?;
        range("pinch.separation_weight", p.separation_weight, 0.0, 1e4)?;
        range("pinch.separation_m", p.separation_m, 0.0, 0.1)?;
        range("huber_delta_m", self.huber_delta_m, 1e-4, 1.0)?;
        let r = &self.regularisation;
        range(
            "regularisation.previous_command",
            r.previous_command,
            0.0,
            10.0,
        )?;
        range("regularisation.rest_posture", r.rest_posture, 0.0, 10.0)?;
        range("regularisation.damping", r.damping, 1e-12, 1.0)?;
        let f = &self.input_filter;
        range("input_filter.min_cutoff_hz", f.min_cutoff_hz, 0.0, 100.0)?;
        range(
            "input_filter.speed_gain_hz_s_per_m",
            f.speed_gain_hz_s_per_m,
            0.0,
            1e4,
        )?;
        range(
            "input_filter.derivative_cutoff_hz",
            f.derivative_cutoff_hz,
            0.01,
            100.0,
        )?;
        self.smoothing.validate()?;
        let s = &self.solver;
        range(
            "solver.steps_per_frame",
            s.steps_per_frame.into(),
            1.0,
            100.0,
        )?;
        range("solver.step_tolerance_rad", s.step_tolerance_rad, 1e-9, 0.1)?;
        range(
            "solver.max_joint_speed_rad_s",
            s.max_joint_speed_rad_s,
            0.01,
            100.0,
        )?;
        range("solver.max_rate_dt_s", s.max_rate_dt_s, 1e-4, 10.0)?;
        range(
            "solver.qp_max_iterations",
            s.qp_max_iterations.into(),
            5.0,
            1000.0,
        )?;
        for (joint, value) in &self.rest_posture_rad {
            range(&format!("rest_posture_rad.{joint}"), *value, -10.0, 10.0)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_file_gives_the_defaults() {
        assert_eq!(
            RetargetConfig::from_toml_str("").unwrap(),
            RetargetConfig::default()
        );
    }

    #[test]
    fn out_of_range_values_name_key_and_range() {
        let err = RetargetConfig::from_toml_str("[pinch]\nengage_m = -0.01\n")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("pinch.engage_m") && err.contains("[0, 0.1]"),
            "{err}"
        );
        let err = RetargetConfig::from_toml_str("[pinch]\nengage_m = 0.05\nrelease_m = 0.04\n")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("pinch.release_m") && err.contains("greater"),
            "{err}"
        );
        let err = RetargetConfig::from_toml_str("[solver]\nsteps = 3\n")
            .unwrap_err()
            .to_string();
        assert!(err.contains("steps"), "{err}");
        let err = RetargetConfig::from_toml_str("[smoothing]\nresidual_m = 0\n")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("smoothing.residual_m") && err.contains("[0.0001, 1]"),
            "{err}"
        );
        let err = RetargetConfig::from_toml_str("layout = \"mano\"\n")
            .unwrap_err()
            .to_string();
        assert!(err.contains("layout") || err.contains("mano"), "{err}");
    }
}
