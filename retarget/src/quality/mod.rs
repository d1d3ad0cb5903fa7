//! Retargeting quality: how closely a sequence of robot commands follows a sequence of human
//! keypoint frames, with definitions fixed so results compare across retargeters.
//!
//! Feed [`QualityRecorder::push`] each distinct human frame (keypoints in the configured
//! layout, metres) with the joint command the retargeter produced for it, in time order
//! ([`QualityRecorder::push_at`] also takes the frame's time); [`QualityRecorder::report`]
//! then gives, overall and per digit:
//!
//! - **tip error**: human fingertips `h_{t,i}` in the human palm frame and robot fingertips
//!   `r_{t,i}` in the robot palm frame (both built as in [`crate::PalmFrame`]; the robot's from
//!   its fixed named frames: wrist on the wrist flexion axis, thumb base at the thumb's first
//!   joint, finger bases at their abduction joints). One global scale
//!   `s* = Σ r·h / Σ h·h` (least squares over every frame and digit), then the mean and p95 of
//!   `‖r_{t,i} − s* h_{t,i}‖`;
//! - **own-scale tip error**: the same with each digit's own least-squares scale
//!   `s_i = Σ_t r_{t,i}·h_{t,i} / Σ_t h_{t,i}·h_{t,i}`: per digit `s_i` and the mean and p95
//!   of `‖r_{t,i} − s_i h_{t,i}‖`, overall the mean and p95 over every digit's frames. The
//!   global `s*` shrinks when the robot cannot reach some digits' targets (the ORCA thumb and
//!   index), which then measures the reachable digits against targets that are too short; the
//!   own scale does not carry one digit's shortfall to another;
//! - **flexion correlation**: a digit's flexion is the distance from the palm-frame origin to
//!   its tip, `‖h_{t,i}‖` and `‖r_{t,i}‖`, rather than from the digit's own base: one
//!   reference point for every digit, the one the tip error already uses; it shrinks as a
//!   finger curls and, for the thumb, as it opposes. Per digit the Pearson correlation over
//!   frames of the human and robot series; `None` with fewer than [`CORRELATION_MIN_FRAMES`]
//!   frames or when either series is constant (standard deviation under
//!   [`FLEXION_MIN_STD_M`]): a finger the robot holds still reads `None`, one opening while
//!   the human's closes reads negative. Overall the mean of the defined per-digit values.
//!   Independent of scale and offset, so a smaller hand is neither rewarded nor punished;
//! - **lag**: the shift `k`, `|k| ≤` [`LAG_MAX_FRAMES`] and at most half the frames, that
//!   maximises the mean over digits (those defined at `k`) of the correlation of human flexion
//!   at frame `t` with robot flexion at frame `t + k`; positive `k`: the robot is behind. Ties
//!   keep the shift nearest 0. In seconds, the mean of `t_{t+k} − t_t` over the paired frames
//!   when every frame was pushed with its time, else `None`;
//! - **pinches**: frames where the human thumb tip is within [`PINCH_HUMAN_M`] of another
//!   fingertip (unscaled; the nearest one counts); the robot's thumb-tip to that fingertip
//!   distance, and the number and share of those frames where it is under [`PINCH_CLOSED_M`].
//!   Also under the second definition, sustained pinches only (runs of at least
//!   [`SUSTAINED_PINCH_MIN_FRAMES`] frames and [`SUSTAINED_PINCH_MIN_S`], which leaves out a
//!   tracker's one-frame outlier), and per finger pair ([`PinchPair`], `pinch_runs`);
//! - **jerk**: mean over joints and frames of `|q_t − 3q_{t−1} + 3q_{t−2} − q_{t−3}|`, radians;
//!   **max step**: largest `|q_t − q_{t−1}|` of any joint;
//! - **limit violations**: frames with a joint outside the model's limits by more than
//!   [`LIMIT_TOLERANCE_RAD`], or not finite.
//!
//! Frames with a non-finite command are left out of the tip, own-scale and flexion metrics
//! (a pinch in one counts as open). Joints belong to the digit whose fingertip chain alone
//! they move; joints shared by every chain (the wrist) are reported as "wrist". Pure: the
//! caller reads files and measures time.

mod flexion;
mod pinch_runs;
mod reachability;
mod report;
mod scale_free;
mod stats;

pub use flexion::{CORRELATION_MIN_FRAMES, FLEXION_MIN_STD_M, LAG_MAX_FRAMES};
pub use pinch_runs::{
    PinchPair, PinchRun, SUSTAINED_PINCH_MIN_FRAMES, SUSTAINED_PINCH_MIN_S, sustained_pinch_runs,
};
pub use reachability::{
    DigitReach, REACH_GRID_MAX_CONFIGURATIONS, Reachability, grid, grid_steps, nearest_distance,
};
pub use report::{DigitQuality, QualityReport};

use nalgebra::{Point3, Vector3};

use crate::error::Error;
use crate::finger::Finger;
use crate::forward_kinematics::FkState;
use crate::hand_model::HandModel;
use crate::human_key_vectors::validate_keypoints;
use crate::keypoint_layout::KeypointLayout;
use crate::palm_frame::PalmFrame;

/// Human thumb-tip to fingertip distance under which a frame is a pinch, metres.
pub const PINCH_HUMAN_M: f64 = 0.02;

/// Robot thumb-tip to fingertip distance under which a pinch counts as closed, metres.
pub const PINCH_CLOSED_M: f64 = 0.015;

/// Slack beyond a joint limit still counted as within it, radians (rounding only).
pub const LIMIT_TOLERANCE_RAD: f64 = 1e-9;

/// One frame as the metrics need it.
#[derive(Debug, Clone)]
struct FrameSample {
    /// Human fingertips in the human palm frame, metres.
    human_tips: [Vector3<f64>; 5],
    /// Robot fingertips in the robot palm frame, metres; `None` when the command is not finite.
    robot_tips: Option<[Vector3<f64>; 5]>,
    /// The human's pinch, when the human pinches.
    pinch: Option<HumanPinch>,
    /// The command.
    q: Vec<f64>,
    /// Whether the command is outside the limits or not finite.
    violation: bool,
    /// The frame's time, seconds, when pushed with one.
    t_s: Option<f64>,
}

/// The finger the human's thumb pinches in `keypoints` (the nearest fingertip within
/// [`PINCH_HUMAN_M`] of the thumb tip) and that distance in metres, if any.
pub fn human_pinch(layout: KeypointLayout, keypoints: &[Point3<f64>]) -> Option<(Finger, f64)> {
    let thumb = keypoints[layout.tip(Finger::Thumb)];
    Finger::OPPOSING
        .into_iter()
        .map(|f| (f, (keypoints[layout.tip(f)] - thumb).norm()))
        .filter(|(_, d)| *d < PINCH_HUMAN_M)
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

/// A frame's human pinch.
#[derive(Debug, Clone, Copy)]
struct HumanPinch {
    /// The finger the thumb pinches.
    finger: Finger,
    /// The human thumb-tip to fingertip distance, metres.
    human_m: f64,
    /// The robot's, metres; `None` when the command is not finite.
    robot_m: Option<f64>,
}

/// Collects (human keypoints, robot command) pairs and computes the quality metrics.
#[derive(Debug, Clone)]
pub struct QualityRecorder {
    model: HandModel,
    layout: KeypointLayout,
    fk: FkState,
    /// For each degree of freedom, the digit it moves alone (`None`: shared, the wrist).
    dof_digit: Vec<Option<Finger>>,
    samples: Vec<FrameSample>,
}

impl QualityRecorder {
    /// A recorder for commands of `model` retargeted from keypoints in `layout`.
    pub fn new(model: HandModel, layout: KeypointLayout) -> QualityRecorder {
        let dof_digit = model.dof_digits();
        QualityRecorder {
            fk: model.fk_state(),
            model,
            layout,
            dof_digit,
            samples: Vec::new(),
        }
    }

    /// Number of frames pushed.
    pub fn len(&self) -> usize {
        self.samples.len()
    }

    /// Whether no frame was pushed.
    pub fn is_empty(&self) -> bool {
        self.samples.is_empty()
    }

    /// Add a frame: the human keypoints and the command retargeted from them. `Err` when the
    /// keypoints are malformed (count, not finite, collapsed palm) or `q` has the wrong length;
    /// nothing is recorded then. A non-finite command is recorded as a limit violation.
    pub fn push(&mut self, keypoints: &[Point3<f64>], q: &[f64]) -> Result<(), Error> {
        self.record(None, keypoints, q)
    }

    /// [`QualityRecorder::push`] with the frame's time `t_s` (seconds, any origin), so the lag
    /// is also reported in seconds (when every frame has a time). `Err(InvalidTimeStep)` when
    /// `t_s` is not finite or not after the previous timed frame; nothing is recorded then.
    pub fn push_at(&mut self, t_s: f64, keypoints: &[Point3<f64>], q: &[f64]) -> Result<(), Error> {
        let previous = self.samples.iter().rev().find_map(|s| s.t_s);
        let step_s = previous.map_or(t_s, |p| t_s - p);
        if !t_s.is_finite() || previous.is_some() && step_s <= 0.0 {
            return Err(Error::InvalidTimeStep { dt_s: step_s });
        }
        self.record(Some(t_s), keypoints, q)
    }

    fn record(
        &mut self,
        t_s: Option<f64>,
        keypoints: &[Point3<f64>],
        q: &[f64],
    ) -> Result<(), Error> {
        validate_keypoints(self.layout, keypoints)?;
        if q.len() != self.model.dof() {
            return Err(Error::DofMismatch {
                expected: self.model.dof(),
                got: q.len(),
            });
        }
        let layout = self.layout;
        let human_palm = PalmFrame::from_landmarks(&layout.palm_landmarks(keypoints))?;
        let human_tips = Finger::ALL.map(|f| human_palm.point_to_palm(&keypoints[layout.tip(f)]));
        let finite = q.iter().all(|v| v.is_finite());
        let within = self.model.dofs.iter().zip(q).all(|(d, &v)| {
            v >= d.limits.lower_rad - LIMIT_TOLERANCE_RAD
                && v <= d.limits.upper_rad + LIMIT_TOLERANCE_RAD
        });
        let robot_tips = if finite {
            self.model.forward(q, &mut self.fk)?;
            let palm = self.model.palm_frame(&self.fk)?;
            Some(
                Finger::ALL
                    .map(|f| palm.point_to_palm(&self.fk.position(self.model.frames.tip(f)))),
            )
        } else {
            None
        };
        let pinch = human_pinch(layout, keypoints).map(|(finger, human_m)| HumanPinch {
            finger,
            human_m,
            robot_m: robot_tips.map(|tips| (tips[finger.index()] - tips[0]).norm()),
        });
        self.samples.push(FrameSample {
            human_tips,
            robot_tips,
            pinch,
            q: q.to_vec(),
            violation: !(finite && within),
            t_s,
        });
        Ok(())
    }

    /// The metrics over every frame pushed so far.
    pub fn report(&self) -> QualityReport {
        report::compute(&self.samples, &self.dof_digit)
    }
}

#[cfg(test)]
mod pinch_runs_tests;
#[cfg(test)]
mod scale_free_tests;
#[cfg(test)]
mod tests;
