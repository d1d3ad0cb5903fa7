//! Which keypoint frames reach the retargeter: repeats are recognised (the lab's ingress
//! republishes each glove frame at 200 Hz), and implausible frames are rejected and counted
//! by reason before the retargeter sees them.
//!
//! Checks, in order: point count for the layout; finite coordinates; bone lengths (distance
//! between consecutive points of each digit chain, and wrist to each digit base) within
//! `[min_bone_m, max_bone_m]`; no point moving more than `max_jump_m` relative to the wrist
//! since the last accepted frame (the arm may move the whole hand freely; a finger may not
//! teleport). Before these, frames stamped by their sender before the newest accepted one are
//! turned away as late ([`source_order`](crate::source_order); the hand control applies it).

use nalgebra::Point3;
use retarget::{Finger, KeypointLayout};
use serde::{Deserialize, Serialize};

use crate::config_error::ConfigError;

/// Limits of a plausible human hand frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GateConfig {
    /// Shortest plausible bone, metres.
    pub min_bone_m: f64,
    /// Longest plausible bone (wrist to a digit base included), metres.
    pub max_bone_m: f64,
    /// Largest plausible motion of any point relative to the wrist between accepted frames,
    /// metres.
    pub max_jump_m: f64,
    /// A frame whose source stamp is at most this much older than the newest accepted frame's
    /// is late (rejected, `out_of_order`); older still means the sender's clock jumped back
    /// (followed). Milliseconds; less than `watchdog.disengage_timeout_ms`.
    pub reorder_window_ms: u64,
}

impl Default for GateConfig {
    fn default() -> Self {
        GateConfig {
            min_bone_m: 0.004,
            max_bone_m: 0.16,
            max_jump_m: 0.12,
            reorder_window_ms: 250,
        }
    }
}

impl GateConfig {
    /// Check the ranges; errors name the key.
    pub fn validate(&self) -> Result<(), ConfigError> {
        if !(self.min_bone_m >= 0.0 && self.min_bone_m < self.max_bone_m && self.max_bone_m <= 1.0)
        {
            return Err(ConfigError::out_of_range(
                "gate.min_bone_m, gate.max_bone_m",
                format!("{}, {}", self.min_bone_m, self.max_bone_m),
                "0 ≤ min < max ≤ 1",
            ));
        }
        if !(self.max_jump_m > 0.0 && self.max_jump_m <= 1.0) {
            return Err(ConfigError::out_of_range(
                "gate.max_jump_m",
                self.max_jump_m,
                "in (0, 1]",
            ));
        }
        if !(1..=10_000).contains(&self.reorder_window_ms) {
            return Err(ConfigError::out_of_range(
                "gate.reorder_window_ms",
                self.reorder_window_ms,
                "in 1..=10000",
            ));
        }
        Ok(())
    }
}

/// Why a frame was turned away.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Rejection {
    /// Wrong number of points for the layout.
    WrongSize,
    /// A NaN or infinite coordinate.
    NonFinite,
    /// A bone shorter or longer than plausible.
    BoneLength,
    /// A point moved implausibly far since the last accepted frame.
    Jump,
    /// The retargeter refused it (collapsed palm).
    Retargeter,
    /// Stamped by its sender before the newest accepted frame (late, reordered).
    OutOfOrder,
}

impl Rejection {
    /// The reason's name in the status and the logs.
    pub fn name(self) -> &'static str {
        match self {
            Rejection::WrongSize => "wrong_size",
            Rejection::NonFinite => "non_finite",
            Rejection::BoneLength => "bone_length",
            Rejection::Jump => "jump",
            Rejection::Retargeter => "retargeter",
            Rejection::OutOfOrder => "out_of_order",
        }
    }

    /// All reasons, for counters.
    pub const ALL: [Rejection; 6] = [
        Rejection::WrongSize,
        Rejection::NonFinite,
        Rejection::BoneLength,
        Rejection::Jump,
        Rejection::Retargeter,
        Rejection::OutOfOrder,
    ];
}

/// What the gate decided about a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// A new, plausible frame.
    New,
    /// The same keypoints as the last accepted frame.
    Repeat,
    /// Not plausible.
    Rejected(Rejection),
}

/// The gate's memory: the last accepted frame.
#[derive(Debug, Clone)]
pub struct FrameGate {
    layout: KeypointLayout,
    config: GateConfig,
    last: Option<Vec<Point3<f64>>>,
}

impl FrameGate {
    /// A gate for `layout`.
    pub fn new(layout: KeypointLayout, config: GateConfig) -> FrameGate {
        FrameGate {
            layout,
            config,
            last: None,
        }
    }

    /// The limits.
    pub fn config(&self) -> &GateConfig {
        &self.config
    }

    /// Forget the last accepted frame (after a glove restart the first frame is not a jump).
    pub fn reset(&mut self) {
        self.last = None;
    }

    /// Judge `points`; a `New` frame becomes the reference for the next one.
    pub fn judge(&mut self, points: &[Point3<f64>]) -> Verdict {
        let verdict = self.check(points);
        if verdict == Verdict::New {
            self.last = Some(points.to_vec());
        }
        verdict
    }

    fn check(&self, points: &[Point3<f64>]) -> Verdict {
        let layout = self.layout;
        if points.len() != layout.len() {
            return Verdict::Rejected(Rejection::WrongSize);
        }
        if !points
            .iter()
            .all(|p| p.coords.iter().all(|c| c.is_finite()))
        {
            return Verdict::Rejected(Rejection::NonFinite);
        }
        if self.last.as_deref() == Some(points) {
            return Verdict::Repeat;
        }
        let wrist = points[layout.wrist()];
        let bone_ok = |a: Point3<f64>, b: Point3<f64>| {
            let length = (a - b).norm();
            length >= self.config.min_bone_m && length <= self.config.max_bone_m
        };
        for finger in Finger::ALL {
            let chain = layout.chain(finger);
            if !bone_ok(wrist, points[chain[0]])
                || chain
                    .windows(2)
                    .any(|w| !bone_ok(points[w[0]], points[w[1]]))
            {
                return Verdict::Rejected(Rejection::BoneLength);
            }
        }
        if let Some(last) = &self.last {
            let last_wrist = last[layout.wrist()];
            let jumped = points
                .iter()
                .zip(last)
                .any(|(p, q)| ((p - wrist) - (q - last_wrist)).norm() > self.config.max_jump_m);
            if jumped {
                return Verdict::Rejected(Rejection::Jump);
            }
        }
        Verdict::New
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;
    use retarget::HandModel;

    fn hand() -> Vec<Point3<f64>> {
        let model = HandModel::orca_v1_right();
        model.synthetic_keypoints(
            &model.forward_new(&model.zero_pose()).unwrap(),
            KeypointLayout::Lab22,
        )
    }

    #[test]
    fn repeats_new_frames_and_rejections() {
        let mut gate = FrameGate::new(KeypointLayout::Lab22, GateConfig::default());
        let frame = hand();
        assert_eq!(gate.judge(&frame), Verdict::New);
        assert_eq!(gate.judge(&frame), Verdict::Repeat);

        // The whole hand moving (arm motion) is fine, however far.
        let moved: Vec<_> = frame
            .iter()
            .map(|p| p + Vector3::new(0.5, 0.0, 0.0))
            .collect();
        assert_eq!(gate.judge(&moved), Verdict::New);

        let mut teleported = moved.clone();
        teleported[9] += Vector3::new(0.0, 0.0, 0.13);
        assert_eq!(gate.judge(&teleported), Verdict::Rejected(Rejection::Jump));

        let mut nan = moved.clone();
        nan[3].y = f64::NAN;
        assert_eq!(gate.judge(&nan), Verdict::Rejected(Rejection::NonFinite));
        assert_eq!(
            gate.judge(&moved[..21]),
            Verdict::Rejected(Rejection::WrongSize)
        );

        let giant: Vec<_> = moved
            .iter()
            .map(|p| Point3::from(p.coords * 10.0))
            .collect();
        gate.reset();
        assert_eq!(gate.judge(&giant), Verdict::Rejected(Rejection::BoneLength));
    }
}
