//! The lab's `/hand/policy_output`: 17 radians, wrist first, then orca_core's joint order, in
//! orca_core's zero convention — the one tested place where the station's URDF-zero joint
//! values are converted for orca_core.
//!
//! `orca_core = urdf − offset`, per joint. orca_core's zeros differ from the URDF's for some
//! abduction joints (DOMAIN.md §3); the offsets are configuration (`[policy_output]
//! offsets_rad`) because their values are not published with the URDF — all zero unless the
//! lab sets them from its hand's calibration.

use std::collections::BTreeMap;

use retarget::{HandModel, ORCA_CORE_JOINTS};
use serde::{Deserialize, Serialize};

use crate::config_error::ConfigError;
use crate::station_error::StationError;

/// `/hand/policy_output` configuration.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PolicyOutputConfig {
    /// Topic; empty disables the output.
    pub topic: String,
    /// Per joint: URDF zero minus orca_core zero, radians.
    pub offsets_rad: BTreeMap<String, f64>,
}

impl PolicyOutputConfig {
    /// Check the offsets: ORCA joints, within ±π.
    pub fn validate(&self) -> Result<(), ConfigError> {
        for (name, value) in &self.offsets_rad {
            if !ORCA_CORE_JOINTS.contains(&name.as_str()) {
                return Err(ConfigError::out_of_range(
                    format!("policy_output.offsets_rad.{name}"),
                    value,
                    format!("keyed by an ORCA joint ({})", ORCA_CORE_JOINTS.join(", ")),
                ));
            }
            if !(value.is_finite() && value.abs() <= std::f64::consts::PI) {
                return Err(ConfigError::out_of_range(
                    format!("policy_output.offsets_rad.{name}"),
                    value,
                    "in [-π, π]",
                ));
            }
        }
        Ok(())
    }
}

/// Maps model joint vectors to policy_output arrays.
#[derive(Debug, Clone, PartialEq)]
pub struct PolicyOutput {
    /// Model degree of freedom for each output slot (wrist first).
    slots: Vec<usize>,
    offsets: Vec<f64>,
}

impl PolicyOutput {
    /// Resolve the 17 slots on `model`; errors name a joint the model lacks or an unknown
    /// offset key.
    pub fn new(
        model: &HandModel,
        config: &PolicyOutputConfig,
    ) -> Result<PolicyOutput, StationError> {
        config.validate()?;
        // Wrist first, then orca_core's order of the finger joints.
        let fingers = &ORCA_CORE_JOINTS[..16];
        let names = std::iter::once("wrist").chain(fingers.iter().copied());
        let mut slots = Vec::with_capacity(17);
        let mut offsets = Vec::with_capacity(17);
        for name in names {
            let Some(dof) = model.dof_index(name) else {
                return Err(StationError::MissingJoint {
                    output: "policy_output",
                    model: model.name().to_string(),
                    joint: name.to_string(),
                });
            };
            slots.push(dof);
            offsets.push(config.offsets_rad.get(name).copied().unwrap_or(0.0));
        }
        Ok(PolicyOutput { slots, offsets })
    }

    /// The 17 values for joint vector `q` (model order, URDF zeros).
    pub fn values(&self, q: &[f64]) -> Vec<f32> {
        self.slots
            .iter()
            .zip(&self.offsets)
            .map(|(&dof, offset)| (q[dof] - offset) as f32)
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrist_first_then_orca_core_order_with_offsets() {
        let model = HandModel::orca_v1_right();
        let config = PolicyOutputConfig {
            topic: "/hand/policy_output".into(),
            offsets_rad: BTreeMap::from([("index_abd".to_string(), 0.25)]),
        };
        let output = PolicyOutput::new(&model, &config).unwrap();
        let q: Vec<f64> = (0..17).map(|i| i as f64 * 0.01).collect();
        let values = output.values(&q);
        assert_eq!(values.len(), 17);
        assert_eq!(values[0], q[model.dof_index("wrist").unwrap()] as f32);
        assert_eq!(values[1], q[model.dof_index("thumb_mcp").unwrap()] as f32);
        let index_abd = model.dof_index("index_abd").unwrap();
        assert_eq!(values[5], (q[index_abd] - 0.25) as f32);
        assert_eq!(values[16], q[model.dof_index("pinky_pip").unwrap()] as f32);
    }

    #[test]
    fn unknown_offsets_are_named() {
        let model = HandModel::orca_v1_right();
        let config = PolicyOutputConfig {
            topic: String::new(),
            offsets_rad: BTreeMap::from([("index_tip".to_string(), 0.1)]),
        };
        let err = PolicyOutput::new(&model, &config).unwrap_err().to_string();
        assert!(err.contains("index_tip"), "{err}");
    }
}
