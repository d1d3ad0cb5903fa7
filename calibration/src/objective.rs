//! The calibration objective: how far the retargeter's output for a user's captured poses,
//! under a candidate calibration transform, lands from the poses' ground-truth joint
//! configurations.
//!
//! For each of the seven poses the real retargeter (the station's configuration, with the
//! solver allowed to converge: up to 50 Gauss–Newton steps to a 1e-6 rad step, joint limits
//! as the only bounds) solves the averaged capture from the neutral pose, so an evaluation is
//! deterministic.
//!
//! The prior toward the previous command (after the reset: the neutral pose) is set to
//! [`COLD_PRIOR`], the station's default, whatever the live smoothing. Without it the
//! key-vector energy is flat along some joint combinations of the pinch poses, a solve stops
//! wherever its path leaves it in that valley, and the objective is rough at the 1e-3 level:
//! enough to trap the optimiser and to move the minimum by 3° under 2 mm of glove noise (with
//! it, all 50 synthetic users of the acceptance test are within 3 % / 3°; without, 44).
//!
//! The pinch blend and finger separation terms are off: they react to the glove's raw
//! thumb-to-fingertip distances and snap a pinch closed whatever the calibration, which hid
//! the calibration's effect on the pinch poses (with them on, 5 of 12 synthetic users missed
//! 3 % / 3°; without, 3 of 10), so the fit makes pinches close by geometry and the live blend
//! then only finishes them.
//!
//! A pose's error is the RMS over the retargeter's free joints of `q − q_truth`, plus, for a
//! pinch pose, `pinch_weight · |gap − gap_truth|` where `gap` is the robot's thumb-tip to
//! fingertip distance. The objective is the mean over the poses, in radians.

use retarget::{
    CalibrationTransform, EmbodimentCatalog, Finger, HandModel, RetargetConfig, Retargeter,
};

use crate::capture::CapturedPose;
use crate::error::Error;
use crate::poses::PoseSet;

/// One pose's error under a transform.
#[derive(Debug, Clone, PartialEq)]
pub struct PoseError {
    /// The pose's name.
    pub pose: String,
    /// RMS joint error over the free joints, radians.
    pub joint_rms_rad: f64,
    /// For a pinch pose, `|robot gap − ground-truth gap|`, metres.
    pub pinch_gap_error_m: Option<f64>,
    /// This pose's contribution before averaging, radians.
    pub cost: f64,
}

/// The objective's value and its parts.
#[derive(Debug, Clone, PartialEq)]
pub struct Evaluation {
    /// Mean of the poses' costs, radians.
    pub value: f64,
    /// Per pose, in capture order.
    pub poses: Vec<PoseError>,
}

struct PoseTarget {
    name: String,
    keypoints: Vec<nalgebra::Point3<f64>>,
    q_truth: Vec<f64>,
    pinch: Option<(Finger, f64)>,
}

/// The objective for one user's captures.
pub struct Objective {
    retargeter: Retargeter,
    targets: Vec<PoseTarget>,
    pinch_weight: f64,
}

impl std::fmt::Debug for Objective {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Objective")
            .field("poses", &self.targets.len())
            .field("pinch_weight", &self.pinch_weight)
            .finish()
    }
}

/// Time step handed to the retargeter for a cold solve, seconds (with the speed limit below,
/// the joint limits are the only bounds).
const COLD_DT_S: f64 = 1.0;

/// Weight of the cold solve's prior toward the neutral pose (the station's default weight
/// toward the previous command): it makes each pose's solve well posed (module documentation).
const COLD_PRIOR: f64 = 1e-4;

/// The station's configuration changed so one frame converges from neutral, without the
/// pinch blend, the smoothing or the input filter (see the module documentation).
pub fn cold_solve_config(config: &RetargetConfig) -> RetargetConfig {
    let mut cold = config.clone();
    cold.regularisation.previous_command = COLD_PRIOR;
    cold.solver.steps_per_frame = 50;
    cold.solver.step_tolerance_rad = 1e-6;
    cold.solver.max_joint_speed_rad_s = 100.0;
    cold.solver.max_rate_dt_s = COLD_DT_S;
    cold.pinch.weight = 0.0;
    cold.pinch.separation_weight = 0.0;
    // One static frame from neutral: no pull back toward neutral, no input history.
    cold.smoothing.previous_command = 0.0;
    cold.input_filter.min_cutoff_hz = 0.0;
    cold
}

impl Objective {
    /// The objective for `captures` (one per pose of `poses`, matched by name) with the
    /// station's retargeting `config` for `model`.
    pub fn new(
        model: &HandModel,
        config: &RetargetConfig,
        catalog: &EmbodimentCatalog,
        poses: &PoseSet,
        captures: &[CapturedPose],
        pinch_weight: f64,
    ) -> Result<Objective, Error> {
        let mut retargeter = Retargeter::new(model.clone(), cold_solve_config(config), catalog)?;
        let mut targets = Vec::with_capacity(poses.poses.len());
        for pose in &poses.poses {
            let capture = captures
                .iter()
                .find(|c| c.pose == pose.name)
                .ok_or_else(|| Error::BadPose {
                    pose: pose.name.clone(),
                    problem: "no capture of this pose".into(),
                })?;
            let q_truth = pose.joint_vector(model)?;
            let pinch = match pose.pinch {
                Some(finger) => {
                    let tips = retargeter.robot_tips(&q_truth)?;
                    Some((finger, gap(&tips, finger)))
                }
                None => None,
            };
            targets.push(PoseTarget {
                name: pose.name.clone(),
                keypoints: capture.keypoints.clone(),
                q_truth,
                pinch,
            });
        }
        Ok(Objective {
            retargeter,
            targets,
            pinch_weight,
        })
    }

    /// Evaluate the objective under `transform`.
    pub fn evaluate(&mut self, transform: &CalibrationTransform) -> Result<Evaluation, Error> {
        self.retargeter.set_calibration(*transform)?;
        let mut poses = Vec::with_capacity(self.targets.len());
        for target in &self.targets {
            self.retargeter.reset();
            let q = self.retargeter.retarget(&target.keypoints, COLD_DT_S)?.q;
            let free = self.retargeter.free_dofs();
            let sum_sq: f64 = free
                .iter()
                .map(|&i| (q[i] - target.q_truth[i]).powi(2))
                .sum();
            let joint_rms_rad = (sum_sq / free.len().max(1) as f64).sqrt();
            let pinch_gap_error_m = match target.pinch {
                Some((finger, truth)) => {
                    let tips = self.retargeter.robot_tips(&q)?;
                    Some((gap(&tips, finger) - truth).abs())
                }
                None => None,
            };
            let cost = joint_rms_rad + self.pinch_weight * pinch_gap_error_m.unwrap_or(0.0);
            poses.push(PoseError {
                pose: target.name.clone(),
                joint_rms_rad,
                pinch_gap_error_m,
                cost,
            });
        }
        let value = poses.iter().map(|p| p.cost).sum::<f64>() / poses.len().max(1) as f64;
        Ok(Evaluation { value, poses })
    }
}

fn gap(tips: &[nalgebra::Vector3<f64>; 5], finger: Finger) -> f64 {
    (tips[Finger::Thumb.index()] - tips[finger.index()]).norm()
}
