//! Loading the project's TOML model format, and the built-in ORCA v1 right hand.
//!
//! File reading is the caller's job (the station shell); this module parses text.

use crate::error::Error;
use crate::hand_model::HandModel;
use crate::model_spec::ModelSpec;

/// orca_core's joint order: the built-in ORCA model's degrees of freedom, in this order.
pub const ORCA_CORE_JOINTS: [&str; 17] = [
    "thumb_mcp",
    "thumb_abd",
    "thumb_pip",
    "thumb_dip",
    "index_abd",
    "index_mcp",
    "index_pip",
    "middle_abd",
    "middle_mcp",
    "middle_pip",
    "ring_abd",
    "ring_mcp",
    "ring_pip",
    "pinky_abd",
    "pinky_mcp",
    "pinky_pip",
    "wrist",
];

/// The built-in ORCA v1 right-hand description, in the project's model format.
pub const ORCA_V1_RIGHT_TOML: &str = include_str!("../models/orca_v1_right.toml");

impl ModelSpec {
    /// Parse a TOML model description (unknown keys are rejected).
    pub fn from_toml_str(text: &str) -> Result<ModelSpec, Error> {
        toml::from_str(text).map_err(|e| Error::Syntax {
            reason: e.to_string().trim_end().to_string(),
        })
    }
}

impl HandModel {
    /// Parse and validate a TOML model description.
    pub fn from_toml_str(text: &str) -> Result<HandModel, Error> {
        HandModel::from_spec(&ModelSpec::from_toml_str(text)?)
    }

    /// The built-in ORCA v1 right hand: 17 degrees of freedom in orca_core order
    /// (`thumb_mcp … pinky_pip, wrist`), URDF zero convention, radians.
    pub fn orca_v1_right() -> HandModel {
        #[allow(clippy::expect_used)] // the embedded file is validated by a unit test
        HandModel::from_toml_str(ORCA_V1_RIGHT_TOML).expect("built-in ORCA model is valid")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_orca_parses_with_orca_core_joint_order() {
        let model = HandModel::from_toml_str(ORCA_V1_RIGHT_TOML).unwrap();
        assert_eq!(model.dof_names().collect::<Vec<_>>(), ORCA_CORE_JOINTS);
        assert_eq!(model.name(), "orca_v1_right");
    }

    #[test]
    fn zero_pose_is_inside_every_limit() {
        // The URDF zero convention: q = 0 is a valid pose for every ORCA joint
        // (thumb_abd's upper limit is exactly 0).
        let model = HandModel::orca_v1_right();
        assert_eq!(model.zero_pose(), vec![0.0; 17]);
        assert!(model.within_limits(&model.zero_pose()));
    }

    #[test]
    fn unknown_key_is_named() {
        let text = ORCA_V1_RIGHT_TOML.replace("lower_rad = -0.7944", "lower_deg = -45.0");
        let err = HandModel::from_toml_str(&text).unwrap_err().to_string();
        assert!(err.contains("lower_deg"), "{err}");
    }
}
