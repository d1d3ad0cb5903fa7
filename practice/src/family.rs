//! A task's family of strategies: its glove script, changed by a few named parameters — what an
//! operator varies over the paper's five practice trials.
//!
//! | parameter | what it changes | as written |
//! |---|---|---|
//! | `start_offset_mm` | where the hand starts: the arm's start placement moved (x, y, z, mm) | 0, 0, 0 |
//! | `approach_yaw_deg` | the approach direction: the wrist's path turned about the vertical | 0 |
//! | `reach_scale` | how far the wrist goes: every wrist offset scaled | 1 |
//! | `grip` | which digits close: the script's closing poses replaced by another named pose | as scripted |
//! | `closure_scale` | how far they close: every closing pose's closure scaled (at most 1) | 1 |
//! | `time_scale` | the timing: every keyframe's time scaled (< 1 faster) | 1 |
//!
//! The script as written is always a member ([`StrategyParams::AS_WRITTEN`]), so practice
//! starts from what a person found and can only keep or improve on it.

use nalgebra::{Rotation3, Vector3};
use retarget::human_hand::{GloveScript, ScriptPose};
use serde::{Deserialize, Serialize};

use crate::error::PracticeError;
use crate::search::{Candidate, Dimension, SearchSpace};

/// How far each parameter may move from the script as written.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrategyBounds {
    /// The start placement's largest move per axis, mm (0–50).
    pub start_offset_mm: f64,
    /// The approach's largest turn about the vertical, degrees (0–45).
    pub approach_yaw_deg: f64,
    /// The wrist path's scale, `[low, high]` around 1 (within 0.5–1.5).
    pub reach_scale: [f64; 2],
    /// The closing poses' closure scale, `[low, high]` around 1 (within 0.5–1.5; the closure
    /// itself stays at most 1).
    pub closure_scale: [f64; 2],
    /// The keyframe times' scale, `[low, high]` around 1 (within 0.3–3).
    pub time_scale: [f64; 2],
}

impl StrategyBounds {
    /// The project's ranges: ±10 mm, ±15°, reach 0.9–1.1, closure 0.85–1.1, time 0.7–1.2.
    pub const DEFAULT: StrategyBounds = StrategyBounds {
        start_offset_mm: 10.0,
        approach_yaw_deg: 15.0,
        reach_scale: [0.9, 1.1],
        closure_scale: [0.85, 1.1],
        time_scale: [0.7, 1.2],
    };

    /// Checks every range; the error names the key and what is allowed.
    pub fn validate(&self) -> Result<(), PracticeError> {
        check_span("bounds.start_offset_mm", self.start_offset_mm, 50.0)?;
        check_span("bounds.approach_yaw_deg", self.approach_yaw_deg, 45.0)?;
        check_scale("bounds.reach_scale", self.reach_scale, [0.5, 1.5])?;
        check_scale("bounds.closure_scale", self.closure_scale, [0.5, 1.5])?;
        check_scale("bounds.time_scale", self.time_scale, [0.3, 3.0])
    }
}

impl Default for StrategyBounds {
    fn default() -> Self {
        StrategyBounds::DEFAULT
    }
}

fn check_span(key: &str, value: f64, max: f64) -> Result<(), PracticeError> {
    if value.is_finite() && (0.0..=max).contains(&value) {
        return Ok(());
    }
    Err(PracticeError::range(key, value, format!("0 to {max}")))
}

fn check_scale(
    key: &str,
    [low, high]: [f64; 2],
    [min, max]: [f64; 2],
) -> Result<(), PracticeError> {
    if low.is_finite() && high.is_finite() && min <= low && low <= 1.0 && 1.0 <= high && high <= max
    {
        return Ok(());
    }
    Err(PracticeError::Range {
        key: key.to_string(),
        value: format!("[{low}, {high}]"),
        allowed: format!("[low, high] with {min} ≤ low ≤ 1 ≤ high ≤ {max}"),
    })
}

/// Which digits close: the script's own poses, or one named pose in place of each closing one.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Grip {
    /// The script's poses.
    AsScripted,
    /// This pose wherever the script closes the hand.
    Pose(ScriptPose),
}

/// One member of a family.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrategyParams {
    /// The start placement's move, mm (x, y, z of the arm's frame).
    pub start_offset_mm: [f64; 3],
    /// The wrist path's turn about the vertical, degrees.
    pub approach_yaw_deg: f64,
    /// The wrist path's scale.
    pub reach_scale: f64,
    /// Which digits close.
    pub grip: Grip,
    /// The closing poses' closure scale.
    pub closure_scale: f64,
    /// The keyframe times' scale.
    pub time_scale: f64,
}

impl StrategyParams {
    /// The script as written.
    pub const AS_WRITTEN: StrategyParams = StrategyParams {
        start_offset_mm: [0.0; 3],
        approach_yaw_deg: 0.0,
        reach_scale: 1.0,
        grip: Grip::AsScripted,
        closure_scale: 1.0,
        time_scale: 1.0,
    };
}

/// A task's family: its script, the poses practice may close with instead, and the ranges.
#[derive(Debug, Clone, PartialEq)]
pub struct StrategyFamily {
    /// The task's ID.
    pub task: String,
    /// The script as written.
    pub script: GloveScript,
    /// Poses that may replace the script's closing poses.
    pub grips: Vec<ScriptPose>,
    /// The ranges.
    pub bounds: StrategyBounds,
}

/// A strategy ready to play: the glove's script and the start placement's move.
#[derive(Debug, Clone, PartialEq)]
pub struct Strategy {
    /// The glove's script.
    pub script: GloveScript,
    /// The arm's start placement moved by this, metres.
    pub start_offset_m: [f64; 3],
}

/// Whether a pose closes digits (open, spread and relaxed hands do not).
pub fn closes(pose: ScriptPose) -> bool {
    !matches!(
        pose,
        ScriptPose::Open | ScriptPose::OpenSpread | ScriptPose::Relaxed
    )
}

impl StrategyFamily {
    /// The member `params` names.
    pub fn strategy(&self, params: &StrategyParams) -> Strategy {
        let turn =
            Rotation3::from_axis_angle(&Vector3::z_axis(), params.approach_yaw_deg.to_radians());
        let mut script = self.script.clone();
        for keyframe in &mut script.keyframes {
            keyframe.t_s *= params.time_scale;
            let wrist = turn * (Vector3::from(keyframe.wrist_m) * params.reach_scale);
            keyframe.wrist_m = wrist.into();
            if closes(keyframe.pose) {
                if let Grip::Pose(pose) = params.grip {
                    keyframe.pose = pose;
                }
                keyframe.closure = (keyframe.closure * params.closure_scale).clamp(0.0, 1.0);
            }
        }
        for dropout in &mut script.dropouts {
            dropout.from_s *= params.time_scale;
            dropout.to_s *= params.time_scale;
        }
        Strategy {
            script,
            start_offset_m: params.start_offset_mm.map(|mm| mm * 1e-3),
        }
    }

    /// The search space: seven continuous dimensions (offset x, y, z, yaw, reach, closure,
    /// time) and one category per grip (the first: as scripted).
    pub fn space(&self) -> SearchSpace {
        let b = &self.bounds;
        let span = |half: f64| Dimension::new(-half, half, 0.0);
        let scale = |[low, high]: [f64; 2]| Dimension::new(low, high, 1.0);
        SearchSpace {
            dimensions: vec![
                span(b.start_offset_mm),
                span(b.start_offset_mm),
                span(b.start_offset_mm),
                span(b.approach_yaw_deg),
                scale(b.reach_scale),
                scale(b.closure_scale),
                scale(b.time_scale),
            ],
            categories: 1 + self.grips.len(),
        }
    }

    /// The member a candidate of [`space`](Self::space) names.
    pub fn params(&self, candidate: &Candidate) -> StrategyParams {
        let x = |i: usize| candidate.x.get(i).copied().unwrap_or(0.0);
        StrategyParams {
            start_offset_mm: [x(0), x(1), x(2)],
            approach_yaw_deg: x(3),
            reach_scale: x(4),
            grip: match candidate.category.checked_sub(1) {
                Some(k) => self
                    .grips
                    .get(k)
                    .map_or(Grip::AsScripted, |p| Grip::Pose(*p)),
                None => Grip::AsScripted,
            },
            closure_scale: x(5),
            time_scale: x(6),
        }
    }
}

#[cfg(test)]
#[path = "family_tests.rs"]
mod tests;
