//! The lab's `/hand/policy_output`: the station's joint vector (URDF zeros, radians) converted
//! for the consumer of that topic by a table of its conventions ([`crate::hand_convention`]).
//!
//! Two ways to configure it:
//!
//! - `[[policy_output.joints]]`, one row a slot of the array (the order of the rows is the order
//!   sent): sign, offset, clamp range, units, where each number comes from and whether it was
//!   checked on a hand. The shipped presets hold the ETH lab's hand-control node
//!   (`launch_configs/station/eth_lab.toml`) and orca_core (`orca_core.toml`).
//! - Without rows (the default): 17 radians, wrist first, then orca_core's order of the finger
//!   joints, each `urdf − offsets_rad[joint]` (0 unless set), not clamped — what the station
//!   has always sent.

use std::collections::BTreeMap;

use retarget::{HandModel, ORCA_CORE_JOINTS};
use serde::{Deserialize, Serialize};

use crate::config_error::ConfigError;
use crate::hand_convention::{JointConvention, RefZero, Units, Verification, validate_joints};
use crate::station_error::StationError;

/// `/hand/policy_output` configuration.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PolicyOutputConfig {
    /// Topic; empty disables the output.
    pub topic: String,
    /// Without `joints`: per joint, URDF zero minus the consumer's zero, radians.
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    pub offsets_rad: BTreeMap<String, f64>,
    /// The consumer the table is for (`eth_hand_control`, `orca_core`).
    #[serde(skip_serializing_if = "String::is_empty")]
    pub consumer: String,
    /// Units of the values sent.
    pub units: Units,
    /// Where the table's facts come from.
    #[serde(skip_serializing_if = "String::is_empty")]
    pub provenance: String,
    /// Where the consumer's zero sits for rows with a `ref_deg`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ref_zero: Option<RefZero>,
    /// Who checked the table on a hand (`pomdar hand-check`).
    #[serde(skip_serializing_if = "String::is_empty")]
    pub verified_by: String,
    /// When (UTC, ISO 8601).
    #[serde(skip_serializing_if = "String::is_empty")]
    pub verified_at: String,
    /// One row a slot, in the order sent; empty: the old fixed layout with `offsets_rad`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub joints: Vec<JointConvention>,
}

impl PolicyOutputConfig {
    /// Check the table, or the offsets (ORCA joints, within ±π).
    pub fn validate(&self) -> Result<(), ConfigError> {
        if !self.joints.is_empty() {
            if let Some((name, value)) = self.offsets_rad.iter().next() {
                return Err(ConfigError::out_of_range(
                    format!("policy_output.offsets_rad.{name}"),
                    value,
                    "unset when policy_output.joints is given (the rows carry offset_deg)",
                ));
            }
            if self.consumer.trim().is_empty() {
                return Err(ConfigError::out_of_range(
                    "policy_output.consumer",
                    "\"\"",
                    "the name of the consumer the table is for",
                ));
            }
            return validate_joints(&self.joints, self.ref_zero);
        }
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

    /// Whether the table was checked on a hand.
    pub fn verification(&self) -> Verification {
        Verification::of(
            &self.consumer,
            &self.joints,
            &self.verified_by,
            &self.verified_at,
        )
    }
}

/// One slot, resolved on a model: in the output's units.
#[derive(Debug, Clone, PartialEq)]
struct Slot {
    dof: usize,
    sign: f64,
    offset: f64,
    lower: f64,
    upper: f64,
}

/// Maps model joint vectors to policy_output arrays and back.
#[derive(Debug, Clone, PartialEq)]
pub struct PolicyOutput {
    slots: Vec<Slot>,
    units: Units,
}

impl PolicyOutput {
    /// Resolve the slots on `model`; errors name a joint the model lacks, an unknown offset
    /// key, or a row whose range the joint cannot reach.
    pub fn new(
        model: &HandModel,
        config: &PolicyOutputConfig,
    ) -> Result<PolicyOutput, StationError> {
        config.validate()?;
        let dof = |name: &str| {
            model
                .dof_index(name)
                .ok_or_else(|| StationError::MissingJoint {
                    output: "policy_output",
                    model: model.name().to_string(),
                    joint: name.to_string(),
                })
        };
        if config.joints.is_empty() {
            // Wrist first, then orca_core's order of the finger joints.
            let names = std::iter::once("wrist").chain(ORCA_CORE_JOINTS[..16].iter().copied());
            let mut slots = Vec::with_capacity(17);
            for name in names {
                let offset = config.offsets_rad.get(name).copied().unwrap_or(0.0);
                slots.push(Slot {
                    dof: dof(name)?,
                    sign: 1.0,
                    offset: -offset,
                    lower: f64::NEG_INFINITY,
                    upper: f64::INFINITY,
                });
            }
            return Ok(PolicyOutput {
                slots,
                units: Units::Rad,
            });
        }
        let to_units = |deg: f64| match config.units {
            Units::Rad => deg.to_radians(),
            Units::Deg => deg,
        };
        let mut slots = Vec::with_capacity(config.joints.len());
        for (i, row) in config.joints.iter().enumerate() {
            let slot = Slot {
                dof: dof(&row.joint)?,
                sign: f64::from(row.sign),
                offset: to_units(row.effective_offset_deg(config.ref_zero)),
                lower: to_units(row.lower_deg),
                upper: to_units(row.upper_deg),
            };
            let limits = model.dofs()[slot.dof].limits;
            let (a, b) = (
                slot.forward(limits.lower_rad, config.units),
                slot.forward(limits.upper_rad, config.units),
            );
            if a.max(b) <= slot.lower || a.min(b) >= slot.upper {
                return Err(ConfigError::out_of_range(
                    format!("policy_output.joints[{i}].lower_deg"),
                    format!("{}..{}", row.lower_deg, row.upper_deg),
                    format!(
                        "a range overlapping {}'s limits mapped through sign and offset",
                        row.joint
                    ),
                )
                .into());
            }
            slots.push(slot);
        }
        Ok(PolicyOutput {
            slots,
            units: config.units,
        })
    }

    /// The values for joint vector `q` (model order, URDF zeros), clamped to each slot's range.
    pub fn values(&self, q: &[f64]) -> Vec<f32> {
        self.slots
            .iter()
            .map(|s| s.forward(q[s.dof], self.units).clamp(s.lower, s.upper) as f32)
            .collect()
    }

    /// The model's joint values for a received array: `(dof, urdf_rad)` per slot; `None` when
    /// the array's length is not the number of slots or a value is not finite.
    pub fn inverse(&self, values: &[f32]) -> Option<Vec<(usize, f64)>> {
        if values.len() != self.slots.len() || values.iter().any(|v| !v.is_finite()) {
            return None;
        }
        Some(
            self.slots
                .iter()
                .zip(values)
                .map(|(s, v)| (s.dof, s.backward(f64::from(*v), self.units)))
                .collect(),
        )
    }

    /// The URDF range (radians) of slot `i`'s joint that the consumer's range lets through,
    /// within the model's limits; `None` for a slot that does not exist.
    pub fn urdf_range(&self, model: &HandModel, i: usize) -> Option<(f64, f64)> {
        let s = self.slots.get(i)?;
        let limits = model.dofs().get(s.dof)?.limits;
        let (a, b) = (
            s.backward(s.lower, self.units),
            s.backward(s.upper, self.units),
        );
        let (lo, hi) = (a.min(b), a.max(b));
        Some((lo.max(limits.lower_rad), hi.min(limits.upper_rad)))
    }

    /// The model degree of freedom of each slot.
    pub fn dofs(&self) -> Vec<usize> {
        self.slots.iter().map(|s| s.dof).collect()
    }
}

impl Slot {
    fn forward(&self, urdf_rad: f64, units: Units) -> f64 {
        let q = match units {
            Units::Rad => urdf_rad,
            Units::Deg => urdf_rad.to_degrees(),
        };
        self.sign * q + self.offset
    }

    fn backward(&self, value: f64, units: Units) -> f64 {
        let q = (value - self.offset) / self.sign;
        match units {
            Units::Rad => q,
            Units::Deg => q.to_radians(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hand_convention::Basis;

    #[test]
    fn wrist_first_then_orca_core_order_with_offsets() {
        let model = HandModel::orca_v1_right();
        let config = PolicyOutputConfig {
            topic: "/hand/policy_output".into(),
            offsets_rad: BTreeMap::from([("index_abd".to_string(), 0.25)]),
            ..PolicyOutputConfig::default()
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
            offsets_rad: BTreeMap::from([("index_tip".to_string(), 0.1)]),
            ..PolicyOutputConfig::default()
        };
        let err = PolicyOutput::new(&model, &config).unwrap_err().to_string();
        assert!(err.contains("index_tip"), "{err}");
    }

    fn degree_table(model: &HandModel) -> PolicyOutputConfig {
        let joints = ORCA_CORE_JOINTS
            .iter()
            .map(|name| {
                let l = model.dofs()[model.dof_index(name).unwrap()].limits;
                JointConvention {
                    joint: name.to_string(),
                    sign: if *name == "wrist" { -1 } else { 1 },
                    offset_deg: if *name == "index_abd" { 10.0 } else { 0.0 },
                    ref_deg: 0.0,
                    lower_deg: -l.upper_rad.to_degrees().max(-l.lower_rad.to_degrees()) - 20.0,
                    upper_deg: l.upper_rad.to_degrees().max(-l.lower_rad.to_degrees()) + 20.0,
                    basis: Basis::Assumed,
                    verified: false,
                    note: String::new(),
                }
            })
            .collect();
        PolicyOutputConfig {
            topic: "/x".into(),
            consumer: "test".into(),
            units: Units::Deg,
            joints,
            ..PolicyOutputConfig::default()
        }
    }

    #[test]
    fn a_table_converts_in_its_order_and_units_and_inverts() {
        let model = HandModel::orca_v1_right();
        let output = PolicyOutput::new(&model, &degree_table(&model)).unwrap();
        let mut q = model.zero_pose();
        let wrist = model.dof_index("wrist").unwrap();
        let index_abd = model.dof_index("index_abd").unwrap();
        q[wrist] = 0.5;
        q[index_abd] = -0.2;
        let values = output.values(&q);
        assert_eq!(values.len(), 17);
        assert!((f64::from(values[16]) + 0.5f64.to_degrees()).abs() < 1e-4);
        assert!((f64::from(values[4]) - (10.0 - 0.2f64.to_degrees())).abs() < 1e-4);
        let back = output.inverse(&values).unwrap();
        for (dof, value) in back {
            assert!((value - q[dof]).abs() < 1e-5, "dof {dof}");
        }
        assert_eq!(output.inverse(&values[..16]), None);
    }

    #[test]
    fn values_are_clamped_to_the_consumers_range() {
        let model = HandModel::orca_v1_right();
        let mut config = degree_table(&model);
        config.joints[4].lower_deg = 0.0;
        config.joints[4].upper_deg = 12.0;
        let output = PolicyOutput::new(&model, &config).unwrap();
        let mut q = model.zero_pose();
        q[model.dof_index("index_abd").unwrap()] = 0.2; // 10 + 11.5 deg
        assert_eq!(output.values(&q)[4], 12.0);
        let (lo, hi) = output.urdf_range(&model, 4).unwrap();
        assert!(
            (lo - (-10f64).to_radians()).abs() < 1e-12 && (hi - 2f64.to_radians()).abs() < 1e-12
        );
        config.joints[4].lower_deg = 200.0;
        config.joints[4].upper_deg = 210.0;
        let err = PolicyOutput::new(&model, &config).unwrap_err().to_string();
        assert!(err.contains("policy_output.joints[4].lower_deg = 200..210 must be a range overlapping index_abd's limits"), "{err}");
    }
}
