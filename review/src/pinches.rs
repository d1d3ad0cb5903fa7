//! Thumb–finger distances of the human (the glove's keypoints) and of the robot (its joint
//! targets through the hand model's forward kinematics), and the human's pinch attempts: each
//! sustained pinch (`retarget::quality::sustained_pinch_runs`: under 20 mm for at least 2
//! frames and 40 ms) and whether the robot closed it (its distance under 15 mm at some command
//! from the pinch's start to [`CLOSE_GRACE_S`] after its end).

use retarget::quality::{PINCH_CLOSED_M, PINCH_HUMAN_M, human_pinch, sustained_pinch_runs};
use retarget::{Finger, HandModel, KeypointLayout};
use serde::Serialize;

use crate::input::{GloveFrame, JointSample};
use crate::joints::JointOrder;
use crate::window::TrialWindow;

/// How long after a human pinch ends the robot may still close it, seconds (the command
/// follows the frame through the control tick and the hand's filter).
pub const CLOSE_GRACE_S: f64 = 0.3;

/// Thumb-tip to fingertip distances over time, per opposing finger (index … little).
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct DistanceSeries {
    /// Times, seconds into the trial.
    pub t_s: Vec<f64>,
    /// Per finger (index, middle, ring, little), millimetres, one per time.
    pub mm: [Vec<f64>; 4],
}

impl DistanceSeries {
    fn push(&mut self, t_s: f64, tips: &[nalgebra::Point3<f64>; 5]) {
        self.t_s.push(t_s);
        for (k, finger) in Finger::OPPOSING.into_iter().enumerate() {
            self.mm[k].push((tips[finger.index()] - tips[0]).norm() * 1e3);
        }
    }
}

/// One of the human's sustained pinches and how the robot followed it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PinchAttempt {
    /// The finger the thumb pinched: `index`, `middle`, `ring` or `little`.
    pub finger: String,
    /// Start, seconds into the trial.
    pub from_s: f64,
    /// End (its last frame), seconds.
    pub to_s: f64,
    /// The human's smallest distance, millimetres.
    pub human_min_mm: f64,
    /// The robot's smallest distance over the pinch and the grace after it, millimetres (NaN
    /// when no command fell in it).
    pub robot_min_mm: f64,
    /// Whether the robot's distance went under 15 mm.
    pub closed: bool,
}

/// The human's distances, per glove frame inside the trial.
pub fn human_distances(
    frames: &[GloveFrame],
    layout: KeypointLayout,
    window: &TrialWindow,
) -> DistanceSeries {
    let mut series = DistanceSeries::default();
    for frame in frames.iter().filter(|f| window.contains(f.t_ns)) {
        if frame.points.len() != layout.len() {
            continue;
        }
        let tips = Finger::ALL.map(|f| frame.points[layout.tip(f)]);
        series.push(window.secs(frame.t_ns), &tips);
    }
    series
}

/// The robot's distances, per joint target inside the trial (joint names read with the
/// station's `prefix`, `JointOrder`). `Err` when a target's joints do not fit the model.
pub fn robot_distances(
    commands: &[JointSample],
    (model, prefix): (&HandModel, Option<&str>),
    window: &TrialWindow,
) -> Result<DistanceSeries, String> {
    let mut series = DistanceSeries::default();
    let mut fk = model.fk_state();
    let mut order: Option<JointOrder> = None;
    for command in commands.iter().filter(|c| window.contains(c.t_ns)) {
        if !order.as_ref().is_some_and(|o| o.fits(&command.names)) {
            order = Some(JointOrder::new(
                model,
                &command.names,
                command.position.len(),
                prefix,
            )?);
        }
        let Some(order) = &order else { continue };
        let q = order.reorder(&command.position);
        if q.iter().any(|v| !v.is_finite()) || model.forward(&q, &mut fk).is_err() {
            continue;
        }
        let tips = Finger::ALL.map(|f| fk.position(model.frames().tip(f)));
        series.push(window.secs(command.t_ns), &tips);
    }
    Ok(series)
}

/// The human's sustained pinches in `frames` (inside the trial), each judged against the
/// robot's distances.
pub fn pinch_attempts(
    frames: &[GloveFrame],
    layout: KeypointLayout,
    window: &TrialWindow,
    robot: &DistanceSeries,
) -> Vec<PinchAttempt> {
    let inside: Vec<&GloveFrame> = frames
        .iter()
        .filter(|f| window.contains(f.t_ns) && f.points.len() == layout.len())
        .collect();
    let pinches: Vec<Option<(Finger, f64)>> = inside
        .iter()
        .map(|f| human_pinch(layout, &f.points))
        .collect();
    let fingers: Vec<Option<Finger>> = pinches.iter().map(|p| p.map(|(f, _)| f)).collect();
    let times: Vec<f64> = inside.iter().map(|f| window.secs(f.t_ns)).collect();
    sustained_pinch_runs(&fingers, Some(&times))
        .into_iter()
        .map(|run| {
            let (from_s, to_s) = (times[run.frames.start], times[run.frames.end - 1]);
            let k = run.finger.index() - 1;
            let robot_min_mm = robot
                .t_s
                .iter()
                .zip(&robot.mm[k])
                .filter(|(t, _)| (from_s..=to_s + CLOSE_GRACE_S).contains(*t))
                .map(|(_, d)| *d)
                .fold(f64::NAN, f64::min);
            let human_min_mm = pinches[run.frames]
                .iter()
                .flatten()
                .map(|(_, d)| d * 1e3)
                .fold(PINCH_HUMAN_M * 1e3, f64::min);
            PinchAttempt {
                finger: run.finger.name().to_string(),
                from_s,
                to_s,
                human_min_mm,
                robot_min_mm,
                closed: robot_min_mm < PINCH_CLOSED_M * 1e3,
            }
        })
        .collect()
}
