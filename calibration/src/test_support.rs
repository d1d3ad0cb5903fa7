//! A calibration profile as `pomdar calibrate` writes it, with a chosen transform, for other
//! crates' tests (feature `test-support`, off in the product): a station loaded with it
//! retargets through that scale and rotation.

use retarget::{CalibrationTransform, HandModel, KeypointLayout};

use crate::error::Error;
use crate::poses::POSE_NAMES;
use crate::profile::{CalibrationProfile, ObjectiveSummary, PoseReport};
use crate::settings::CalibrationModel;

/// The text of a global profile of `user` for the ORCA v1 hand and the lab's 22-point layout
/// with `transform`, every pose reported (the pinches with their gaps); `Err` only for a
/// non-finite transform.
pub fn profile_text(user: &str, transform: CalibrationTransform) -> Result<String, Error> {
    CalibrationProfile {
        user: user.into(),
        date: "2026-11-21T10:32:05Z".into(),
        glove: "rokoko #12".into(),
        model: HandModel::orca_v1_right().name().to_string(),
        layout: KeypointLayout::Lab22,
        source: format!("profiles/{user}-session.mcap"),
        calibration_model: CalibrationModel::Global,
        parameters: transform,
        objective: ObjectiveSummary {
            before_rad: 0.4,
            after_rad: 0.15,
            evaluations: 140,
        },
        poses: POSE_NAMES
            .iter()
            .enumerate()
            .map(|(i, name)| PoseReport {
                name: (*name).to_string(),
                joint_rms_before_rad: 0.4,
                joint_rms_after_rad: 0.1,
                pinch_gap_before_mm: (i < 4).then_some(12.0),
                pinch_gap_after_mm: (i < 4).then_some(4.0),
            })
            .collect(),
    }
    .to_toml_string()
}

/// A transform well away from the identity: scale 1.08 and a rotation with roll, pitch and yaw
/// all non-zero.
pub fn scaled_and_rotated() -> CalibrationTransform {
    CalibrationTransform {
        scale: 1.08,
        roll_rad: 0.05,
        pitch_rad: -0.1,
        yaw_rad: 0.08,
        ..CalibrationTransform::IDENTITY
    }
}
