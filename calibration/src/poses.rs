//! The seven calibration poses as data: four pinches (thumb to index, middle, ring, little),
//! open hand without and with abduction, closed hand. Each is a ground-truth joint
//! configuration of the robot hand plus the instruction the user copies.

use std::collections::BTreeMap;

use retarget::{Finger, HandModel};
use serde::{Deserialize, Serialize};

use crate::error::Error;

/// The built-in pose set for the ORCA v1 hand.
pub const ORCA_V1_POSES_TOML: &str = include_str!("../data/poses_orca_v1.toml");

/// The names of the seven poses, in capture order.
pub const POSE_NAMES: [&str; 7] = [
    "pinch_index",
    "pinch_middle",
    "pinch_ring",
    "pinch_little",
    "open",
    "open_spread",
    "closed",
];

/// One calibration pose.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CalibrationPose {
    /// Name (one of [`POSE_NAMES`]).
    pub name: String,
    /// What the user is asked to do.
    pub instruction: String,
    /// For a pinch pose, the finger the thumb touches.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pinch: Option<Finger>,
    /// Joint values, radians (URDF zeros); joints not named are 0.
    pub joints: BTreeMap<String, f64>,
}

/// A validated set of the seven poses.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PoseSet {
    /// The poses, in capture order.
    #[serde(rename = "pose")]
    pub poses: Vec<CalibrationPose>,
}

impl PoseSet {
    /// The built-in ORCA v1 poses.
    pub fn orca_v1() -> PoseSet {
        #[allow(clippy::expect_used)] // the embedded file is validated by tests
        PoseSet::from_toml_str(ORCA_V1_POSES_TOML).expect("built-in poses are valid")
    }

    /// Parse a pose set: exactly the seven poses, in order, pinches naming their finger.
    pub fn from_toml_str(text: &str) -> Result<PoseSet, Error> {
        let set: PoseSet = toml::from_str(text).map_err(|e| Error::Syntax {
            reason: e.to_string().trim_end().to_string(),
        })?;
        let names: Vec<&str> = set.poses.iter().map(|p| p.name.as_str()).collect();
        if names != POSE_NAMES {
            return Err(Error::BadPose {
                pose: names.join(", "),
                problem: format!("the poses must be exactly {POSE_NAMES:?}, in this order"),
            });
        }
        for (pose, finger) in set.poses.iter().zip(Finger::OPPOSING) {
            if pose.pinch != Some(finger) {
                return Err(Error::BadPose {
                    pose: pose.name.clone(),
                    problem: format!("must have pinch = \"{finger}\""),
                });
            }
        }
        Ok(set)
    }

    /// The pose called `name`.
    pub fn get(&self, name: &str) -> Option<&CalibrationPose> {
        self.poses.iter().find(|p| p.name == name)
    }
}

impl CalibrationPose {
    /// The pose as a joint vector of `model`; errors name an unknown joint or a value outside
    /// its limits.
    pub fn joint_vector(&self, model: &HandModel) -> Result<Vec<f64>, Error> {
        let mut q = vec![0.0; model.dof()];
        for (joint, &value) in &self.joints {
            let bad = |problem: String| Error::BadPose {
                pose: self.name.clone(),
                problem,
            };
            let index = model.dof_index(joint).ok_or_else(|| {
                bad(format!(
                    "'{joint}' is not a joint of model '{}'",
                    model.name()
                ))
            })?;
            let limits = model.dofs()[index].limits;
            if !limits.contains(value) {
                return Err(bad(format!(
                    "{joint} = {value} rad is outside [{}, {}]",
                    limits.lower_rad, limits.upper_rad
                )));
            }
            q[index] = value;
        }
        Ok(q)
    }
}
