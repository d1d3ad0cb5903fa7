//! Which keypoint frames reach the retargeter: repeats are recognised (the lab's ingress
//! republishes each glove frame at 200 Hz), and implausible frames are rejected and counted
//! by reason before the retargeter sees them.
//!
//! Checks, in order: point count for the layout; finite coordinates; bone lengths (distance
//! between consecutive points of each digit chain, and wrist to each digit base) within
//! `[min_bone_m, max_bone_m]`; no point moving more than `max_jump_m` per `jump_interval_ms`
//! relative to the wrist since the last accepted frame (the arm may move the whole hand
//! freely; a finger may not teleport). The allowance grows with the time since that frame (up
//! to [`MAX_JUMP_INTERVALS`] intervals; the hand control measures it by the sender's clock, by
//! the receive clock across a jump of the sender's clock): a glove that drops a frame, or a
//! frame rejected for a moment, does not make every later frame look like a jump, which held
//! the last command for 168 of 647 frames of a recording with 10 % of its frames dropped.
//! Last, where `outlier_jump_m` is set (2 cm by default), a frame where one point leapt alone,
//! at least that far off what the points beside it on its digit predict
//! ([`crate::outlier_check`]), is passed on with that point put back where its digit predicts
//! it ([`GateDecision::Repaired`], counted as `frames_repaired`): a tracker's one-frame outlier never
//! reaches the retargeter while the rest of the hand stays current, and a point's real motion
//! that looks like one is accepted with the next frame, that point one frame late.
//! Before these, frames stamped by their sender before the newest accepted one are
//! turned away as late ([`source_order`](crate::source_order); the hand control applies it).

use nalgebra::Point3;
use retarget::{Finger, KeypointLayout};
use serde::{Deserialize, Serialize};

use crate::config_error::ConfigError;
use crate::outlier_check;

/// Limits of a plausible human hand frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GateConfig {
    /// Shortest plausible bone, metres.
    pub min_bone_m: f64,
    /// Longest plausible bone (wrist to a digit base included), metres.
    pub max_bone_m: f64,
    /// Largest plausible motion of any point relative to the wrist in `jump_interval_ms`,
    /// metres.
    pub max_jump_m: f64,
    /// The interval `max_jump_m` is allowed in, milliseconds of the senders' clock (about one
    /// glove frame); a frame further from the last accepted one is allowed proportionally
    /// more, up to `MAX_JUMP_INTERVALS` intervals.
    pub jump_interval_ms: u64,
    /// A frame whose source stamp is at most this much older than the newest accepted frame's
    /// is late (rejected, `out_of_order`); older still means the sender's clock jumped back
    /// (followed). Milliseconds; less than `watchdog.disengage_timeout_ms`.
    pub reorder_window_ms: u64,
    /// A point whose motion relative to the wrist since the last accepted frame is this far
    /// off what the points beside it on its digit predict is a tracker's outlier: the frame is
    /// passed on with that point put back where the rest of the hand predicts it (counted as
    /// `frames_repaired`). Not scaled with the time since the last accepted frame (a point that leapt
    /// after a gap in the frames is still one, and a real motion taken for one costs that
    /// point one frame). Metres; 0 turns the check off. At the default 0.02 it catches 914 of
    /// 920 injected outliers over the shared recordings and their copies, and the live path's
    /// tip error, jerk and pinches on them are within 0.02 mm, 0.6 % and the same as with it
    /// off (README, "The evaluation set").
    pub outlier_jump_m: f64,
}

impl Default for GateConfig {
    fn default() -> Self {
        GateConfig {
            min_bone_m: 0.004,
            max_bone_m: 0.16,
            max_jump_m: 0.12,
            jump_interval_ms: 50,
            reorder_window_ms: 250,
            outlier_jump_m: 0.02,
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
        if !(1..=1000).contains(&self.jump_interval_ms) {
            return Err(ConfigError::out_of_range(
                "gate.jump_interval_ms",
                self.jump_interval_ms,
                "in 1..=1000",
            ));
        }
        if !(0.0..=1.0).contains(&self.outlier_jump_m) {
            return Err(ConfigError::out_of_range(
                "gate.outlier_jump_m",
                self.outlier_jump_m,
                "in [0, 1] (0: off)",
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

/// Whether `points` repeat `previous` (the same frame published again, not a new one): the
/// one repeat test of the station's gate and of every tool that counts distinct frames.
pub fn repeats(previous: Option<&[Point3<f64>]>, points: &[Point3<f64>]) -> bool {
    previous == Some(points)
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
pub enum GateDecision {
    /// A new, plausible frame.
    New,
    /// The same keypoints as the last accepted frame.
    Repeat,
    /// A new frame in which one point leapt alone (a tracker's outlier): passed on with that
    /// point put back where its digit predicts it (the gate's last accepted frame).
    Repaired,
    /// Not plausible.
    Rejected(Rejection),
}

/// The gate's memory: the last accepted frame (repaired, if it was), and the frame as sent
/// when it was repaired.
#[derive(Debug, Clone)]
pub struct FrameGate {
    layout: KeypointLayout,
    config: GateConfig,
    last: Option<Vec<Point3<f64>>>,
    /// The accepted frame before `last`.
    before_last: Option<Vec<Point3<f64>>>,
    held: Option<Vec<Point3<f64>>>,
}

/// Most intervals of `max_jump_m` a frame is allowed (a stall longer than this is judged as
/// if it were this long).
pub const MAX_JUMP_INTERVALS: f64 = 10.0;

impl FrameGate {
    /// A gate for `layout`.
    pub fn new(layout: KeypointLayout, config: GateConfig) -> FrameGate {
        FrameGate {
            layout,
            config,
            last: None,
            before_last: None,
            held: None,
        }
    }

    /// The limits.
    pub fn config(&self) -> &GateConfig {
        &self.config
    }

    /// Forget the last accepted frame (after a glove restart the first frame is not a jump).
    #[cfg(test)]
    pub fn reset(&mut self) {
        self.last = None;
        self.before_last = None;
        self.held = None;
    }

    /// Judge `points` as one interval after the last accepted frame; a `New` frame becomes
    /// the reference for the next one.
    #[cfg(test)]
    pub fn judge(&mut self, points: &[Point3<f64>]) -> GateDecision {
        self.judge_after(points, None)
    }

    /// Judge `points` taken `since_last_ns` after the last accepted frame (`None`: one
    /// interval): the jump allowance grows with that time. A `New` frame becomes the reference
    /// for the next.
    pub fn judge_after(
        &mut self,
        points: &[Point3<f64>],
        since_last_ns: Option<i64>,
    ) -> GateDecision {
        if repeats(self.held.as_deref(), points) {
            // The held frame again (the ingress republishes every frame): still held.
            return GateDecision::Repeat;
        }
        let verdict = self.check(points, self.jump_allowance_m(since_last_ns));
        if verdict != GateDecision::New {
            return verdict;
        }
        // One frame repaired at most: the frame after a repaired one is accepted whatever it
        // shows (a real flick is then one frame late, not held for good).
        if self.held.is_none()
            && let Some(fixed) = self.outlier_repaired(points)
        {
            self.held = Some(points.to_vec());
            self.before_last = self.last.replace(fixed);
            return GateDecision::Repaired;
        }
        self.held = None;
        self.before_last = self.last.replace(points.to_vec());
        verdict
    }

    /// The last frame accepted: as sent, or as repaired after [`GateDecision::Repaired`].
    pub fn last_accepted(&self) -> Option<&[Point3<f64>]> {
        self.last.as_deref()
    }

    /// `points` with the point that leapt alone since the last accepted frame (as
    /// [`outlier_check::isolated_leap`] names it) put back ([`outlier_check::repaired`]), or
    /// None: no point leapt, or the frame is back to where it was the frame before (the return
    /// from an outlier the check let through is not one: repairing it would keep the
    /// outlier's command a frame longer).
    fn outlier_repaired(&self, points: &[Point3<f64>]) -> Option<Vec<Point3<f64>>> {
        let last = self.last.as_ref()?;
        let jump_m = self.config.outlier_jump_m;
        if jump_m <= 0.0 {
            return None;
        }
        let flagged = outlier_check::isolated_leap(self.layout, points, last, jump_m)?;
        let from_before = |before: &[Point3<f64>]| {
            outlier_check::isolated_leap(self.layout, points, before, jump_m).is_some()
        };
        if !self.before_last.as_deref().is_none_or(from_before) {
            return None;
        }
        outlier_check::repaired(self.layout, points, last, flagged)
    }

    /// The jump allowed for a frame taken `since_last_ns` after the last accepted one, metres.
    fn jump_allowance_m(&self, since_last_ns: Option<i64>) -> f64 {
        let interval_ns = self.config.jump_interval_ms as f64 * 1e6;
        let intervals = since_last_ns.map_or(1.0, |since| {
            (since as f64 / interval_ns).clamp(1.0, MAX_JUMP_INTERVALS)
        });
        self.config.max_jump_m * intervals
    }

    fn check(&self, points: &[Point3<f64>], max_jump_m: f64) -> GateDecision {
        let layout = self.layout;
        if points.len() != layout.len() {
            return GateDecision::Rejected(Rejection::WrongSize);
        }
        if !points
            .iter()
            .all(|p| p.coords.iter().all(|c| c.is_finite()))
        {
            return GateDecision::Rejected(Rejection::NonFinite);
        }
        if repeats(self.last.as_deref(), points) {
            return GateDecision::Repeat;
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
                return GateDecision::Rejected(Rejection::BoneLength);
            }
        }
        if let Some(last) = &self.last {
            let last_wrist = last[layout.wrist()];
            let jumped = points
                .iter()
                .zip(last)
                .any(|(p, q)| ((p - wrist) - (q - last_wrist)).norm() > max_jump_m);
            if jumped {
                return GateDecision::Rejected(Rejection::Jump);
            }
        }
        GateDecision::New
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
        assert_eq!(gate.judge(&frame), GateDecision::New);
        assert_eq!(gate.judge(&frame), GateDecision::Repeat);

        // The whole hand moving (arm motion) is fine, however far.
        let moved: Vec<_> = frame
            .iter()
            .map(|p| p + Vector3::new(0.5, 0.0, 0.0))
            .collect();
        assert_eq!(gate.judge(&moved), GateDecision::New);

        let mut teleported = moved.clone();
        teleported[9] += Vector3::new(0.0, 0.0, 0.13);
        assert_eq!(
            gate.judge(&teleported),
            GateDecision::Rejected(Rejection::Jump)
        );

        let mut nan = moved.clone();
        nan[3].y = f64::NAN;
        assert_eq!(
            gate.judge(&nan),
            GateDecision::Rejected(Rejection::NonFinite)
        );
        assert_eq!(
            gate.judge(&moved[..21]),
            GateDecision::Rejected(Rejection::WrongSize)
        );

        let giant: Vec<_> = moved
            .iter()
            .map(|p| Point3::from(p.coords * 10.0))
            .collect();
        gate.reset();
        assert_eq!(
            gate.judge(&giant),
            GateDecision::Rejected(Rejection::BoneLength)
        );
    }

    #[test]
    fn the_jump_allowance_grows_with_the_time_since_the_last_accepted_frame() {
        const MS: i64 = 1_000_000;
        // One point moved alone: with the outlier check off, the jump check alone judges it.
        let jump_only = GateConfig {
            outlier_jump_m: 0.0,
            ..GateConfig::default()
        };
        let mut gate = FrameGate::new(KeypointLayout::Lab22, jump_only);
        let frame = hand();
        let moved = |dz: f64| {
            let mut f = frame.clone();
            f[9] += Vector3::new(0.0, 0.0, dz);
            f
        };
        assert_eq!(gate.judge_after(&frame, None), GateDecision::New);
        // 13 cm in one 40 ms frame: a teleport.
        assert_eq!(
            gate.judge_after(&moved(0.13), Some(40 * MS)),
            GateDecision::Rejected(Rejection::Jump)
        );
        // The same 13 cm two frames after the last accepted one (one dropped): 0.12 m × 80/50.
        assert_eq!(
            gate.judge_after(&moved(0.13), Some(80 * MS)),
            GateDecision::New
        );
        // The allowance: one interval for a time going back or none given, the time since
        // the last accepted frame otherwise, at most 10 intervals.
        let allowance = |ns| gate.jump_allowance_m(ns);
        assert!((allowance(Some(-5 * MS)) - 0.12).abs() < 1e-12);
        assert!((allowance(None) - 0.12).abs() < 1e-12);
        assert!((allowance(Some(100 * MS)) - 0.24).abs() < 1e-12);
        assert!((allowance(Some(10_000 * MS)) - 1.2).abs() < 1e-12);
    }

    #[test]
    fn an_outlier_after_a_gap_in_the_frames_is_still_one() {
        let layout = KeypointLayout::Lab22;
        let on = GateConfig {
            outlier_jump_m: 0.02,
            ..GateConfig::default()
        };
        let frame = hand();
        let (tip, joint) = (layout.tip(Finger::Index), layout.chain(Finger::Index)[2]);
        // 3 cm out along the last bone, 100 ms after the last frame (two jump intervals).
        let mut outlier = frame.clone();
        outlier[tip] += (frame[tip] - frame[joint]).normalize() * 0.03;
        let mut gate = FrameGate::new(layout, on);
        assert_eq!(gate.judge(&frame), GateDecision::New);
        assert_eq!(
            gate.judge_after(&outlier, Some(100_000_000)),
            GateDecision::Repaired
        );
    }

    #[test]
    fn a_point_leaping_alone_is_put_back_on_its_digit_for_one_frame() {
        let layout = KeypointLayout::Lab22;
        let on = GateConfig {
            outlier_jump_m: 0.02,
            ..GateConfig::default()
        };
        let mut gate = FrameGate::new(layout, on);
        let frame = hand();
        let tip = layout.tip(Finger::Index);
        let leapt = |f: &[Point3<f64>]| {
            let mut f = f.to_vec();
            f[tip] += Vector3::new(0.0, 0.04, 0.0);
            f
        };
        assert_eq!(gate.judge(&frame), GateDecision::New);
        // One frame with the index tip 4 cm away, then back: the outlier is passed on with the
        // tip put back where it was (the hand was still), its republished copy is a repeat,
        // and the frame after it is new.
        let outlier = leapt(&frame);
        assert_eq!(gate.judge(&outlier), GateDecision::Repaired);
        let passed = gate.last_accepted().unwrap().to_vec();
        assert!((passed[tip] - frame[tip]).norm() < 1e-12);
        assert!((0..passed.len()).all(|i| i == tip || passed[i] == outlier[i]));
        assert_eq!(gate.judge(&outlier), GateDecision::Repeat);
        let mut back = frame.clone();
        back[0] += Vector3::new(0.001, 0.0, 0.0);
        assert_eq!(gate.judge(&back), GateDecision::New);
        // A leap the next frame confirms is accepted with that frame, one frame late.
        let first = leapt(&back);
        assert_eq!(gate.judge(&first), GateDecision::Repaired);
        let mut confirmed = first.clone();
        confirmed[0] += Vector3::new(0.001, 0.0, 0.0);
        assert_eq!(gate.judge(&confirmed), GateDecision::New);
        // Off: the same leap is accepted at once.
        let off = GateConfig {
            outlier_jump_m: 0.0,
            ..GateConfig::default()
        };
        let mut gate = FrameGate::new(layout, off);
        assert_eq!(gate.judge(&frame), GateDecision::New);
        assert_eq!(gate.judge(&leapt(&frame)), GateDecision::New);
    }

    #[test]
    fn an_outlier_jump_out_of_range_is_named() {
        for jump in [-0.01, 1.5, f64::NAN] {
            let config = GateConfig {
                outlier_jump_m: jump,
                ..GateConfig::default()
            };
            let error = config.validate().unwrap_err().to_string();
            assert!(error.contains("gate.outlier_jump_m"), "{error}");
        }
    }

    #[test]
    fn the_return_from_an_outlier_let_through_is_not_repaired() {
        let layout = KeypointLayout::Lab22;
        // The check at 5 cm lets a 4 cm leap through; the point's return is a 4 cm leap from
        // the accepted outlier, but back to where it was the frame before: accepted at once.
        let on = GateConfig {
            outlier_jump_m: 0.05,
            ..GateConfig::default()
        };
        let mut gate = FrameGate::new(layout, on);
        let frame = hand();
        let mut outlier = frame.clone();
        outlier[layout.tip(Finger::Index)] += Vector3::new(0.0, 0.04, 0.0);
        assert_eq!(gate.judge(&frame), GateDecision::New);
        assert_eq!(gate.judge(&outlier), GateDecision::New);
        let mut back = frame.clone();
        back[0] += Vector3::new(0.001, 0.0, 0.0);
        gate.config.outlier_jump_m = 0.02;
        assert_eq!(gate.judge(&back), GateDecision::New);
    }
}
