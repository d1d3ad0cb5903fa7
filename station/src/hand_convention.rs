//! A hand's command convention as data: how the station's joint vector (ORCA v1 URDF zeros and
//! directions, radians) becomes the array a consumer of `/hand/policy_output` expects.
//!
//! One row a slot of the array, in the array's order:
//!
//! ```text
//! out_deg = clamp(sign · urdf_deg + offset_deg − r · ref_deg, lower_deg, upper_deg)
//! ```
//!
//! with `r = 1` when the table says `ref_zero = "minus_ref"` (the consumer's zero sits where
//! the URDF's angle is `ref_deg`) and `r = 0` when `ref_zero = "equal"`; the value sent is
//! `out_deg` in degrees or converted to radians (`units`). Every row says where its numbers
//! come from (`basis`), whether they were checked on a hand (`verified`, set by `pomdar
//! hand-check`) and what is still open (`note`). The table also carries its consumer's name and
//! a sentence of provenance. Pure data and checks; the conversion itself is
//! [`crate::policy_output::PolicyOutput`].

use serde::{Deserialize, Serialize};

use crate::config_error::ConfigError;

/// The units of the values sent.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Units {
    /// Radians.
    #[default]
    Rad,
    /// Degrees.
    Deg,
}

/// Where the consumer's zero sits for joints with an MJCF `ref` (`ref_deg` ≠ 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RefZero {
    /// The consumer's zero is the URDF's: `ref_deg` is not applied.
    Equal,
    /// The consumer's angle is the URDF's minus `ref_deg` (its zero is where the URDF reads
    /// `ref_deg`).
    MinusRef,
}

impl RefZero {
    /// The name used in the file.
    pub fn name(self) -> &'static str {
        match self {
            RefZero::Equal => "equal",
            RefZero::MinusRef => "minus_ref",
        }
    }
}

/// Where a row's numbers come from.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Basis {
    /// Stated or derived in the public sources (the table's `provenance`).
    Sources,
    /// Derived from the sources, but only approximately (the `note` says how).
    Approximate,
    /// Not derived: an identity or a guess (the `note` says why).
    #[default]
    Assumed,
}

/// One slot of the consumer's array: which station joint, and how it is converted.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointConvention {
    /// The station joint (`retarget::ORCA_CORE_JOINTS`).
    pub joint: String,
    /// +1 when the consumer's angle grows with the URDF's, −1 when it runs the other way.
    pub sign: i8,
    /// The consumer's angle at URDF zero (before `ref_deg`), degrees.
    #[serde(default)]
    pub offset_deg: f64,
    /// The MJCF `ref` of the joint, degrees; applied as `ref_zero` says.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub ref_deg: f64,
    /// The consumer's range, in its own angle (degrees): values are clamped to it.
    pub lower_deg: f64,
    /// Upper end of the consumer's range, degrees.
    pub upper_deg: f64,
    /// Where the numbers come from.
    #[serde(default)]
    pub basis: Basis,
    /// Checked on a hand (`pomdar hand-check`): the joint moved the named way.
    #[serde(default)]
    pub verified: bool,
    /// What is approximate or open.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub note: String,
}

fn is_zero(value: &f64) -> bool {
    *value == 0.0
}

impl JointConvention {
    /// The offset applied under `ref_zero`: `offset_deg − r · ref_deg`, degrees.
    pub fn effective_offset_deg(&self, ref_zero: Option<RefZero>) -> f64 {
        match ref_zero {
            Some(RefZero::MinusRef) => self.offset_deg - self.ref_deg,
            _ => self.offset_deg,
        }
    }

    /// Check one row; `key` is its dotted key (`policy_output.joints[3]`).
    pub fn validate(&self, key: &str, ref_zero: Option<RefZero>) -> Result<(), ConfigError> {
        let joints = retarget::ORCA_CORE_JOINTS;
        if !joints.contains(&self.joint.as_str()) {
            return Err(ConfigError::out_of_range(
                format!("{key}.joint"),
                &self.joint,
                format!("an ORCA joint ({})", joints.join(", ")),
            ));
        }
        if self.sign != 1 && self.sign != -1 {
            return Err(ConfigError::out_of_range(
                format!("{key}.sign"),
                self.sign,
                "1 or -1",
            ));
        }
        let within = |name: &str, value: f64, bound: f64| {
            if value.is_finite() && value.abs() <= bound {
                Ok(())
            } else {
                Err(ConfigError::out_of_range(
                    format!("{key}.{name}"),
                    value,
                    format!("in [-{bound}, {bound}]"),
                ))
            }
        };
        within("offset_deg", self.offset_deg, 360.0)?;
        within("ref_deg", self.ref_deg, 180.0)?;
        within("lower_deg", self.lower_deg, 360.0)?;
        within("upper_deg", self.upper_deg, 360.0)?;
        if self.lower_deg >= self.upper_deg {
            return Err(ConfigError::out_of_range(
                format!("{key}.upper_deg"),
                self.upper_deg,
                format!("greater than {key}.lower_deg ({})", self.lower_deg),
            ));
        }
        if self.ref_deg != 0.0 && ref_zero.is_none() {
            return Err(ConfigError::out_of_range(
                format!("{key}.ref_deg"),
                self.ref_deg,
                "0 unless policy_output.ref_zero says where the consumer's zero is (\"equal\" or \"minus_ref\")",
            ));
        }
        Ok(())
    }
}

/// Check a whole table: every station joint exactly once, each row valid.
pub fn validate_joints(
    joints: &[JointConvention],
    ref_zero: Option<RefZero>,
) -> Result<(), ConfigError> {
    let all = retarget::ORCA_CORE_JOINTS;
    for (i, row) in joints.iter().enumerate() {
        let key = format!("policy_output.joints[{i}]");
        row.validate(&key, ref_zero)?;
        if let Some(first) = joints[..i].iter().position(|r| r.joint == row.joint) {
            return Err(ConfigError::out_of_range(
                format!("{key}.joint"),
                &row.joint,
                format!("a joint not already in policy_output.joints[{first}]"),
            ));
        }
    }
    if joints.len() != all.len() {
        let missing: Vec<&str> = all
            .iter()
            .copied()
            .filter(|name| !joints.iter().any(|r| r.joint == *name))
            .collect();
        return Err(ConfigError::out_of_range(
            "policy_output.joints",
            format!("{} rows", joints.len()),
            format!(
                "one row for each of the {} ORCA joints (missing: {})",
                all.len(),
                missing.join(", ")
            ),
        ));
    }
    Ok(())
}

/// Whether a table was checked on a hand, for the operator.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Verification {
    /// No table: the old `offsets_rad` (or none), never checked.
    NoTable,
    /// Every row was checked on a hand, by whom and when.
    Verified {
        /// The consumer.
        consumer: String,
        /// Who checked it.
        by: String,
        /// When (UTC).
        at: String,
    },
    /// Rows not checked on a hand.
    Unverified {
        /// The consumer.
        consumer: String,
        /// The joints not checked, in slot order.
        joints: Vec<String>,
        /// How many rows the table has.
        of: usize,
    },
}

impl Verification {
    /// Of a table (empty: no table).
    pub fn of(consumer: &str, joints: &[JointConvention], by: &str, at: &str) -> Verification {
        if joints.is_empty() {
            return Verification::NoTable;
        }
        let open: Vec<String> = joints
            .iter()
            .filter(|r| !r.verified)
            .map(|r| r.joint.clone())
            .collect();
        if open.is_empty() {
            Verification::Verified {
                consumer: consumer.to_string(),
                by: by.to_string(),
                at: at.to_string(),
            }
        } else {
            Verification::Unverified {
                consumer: consumer.to_string(),
                joints: open,
                of: joints.len(),
            }
        }
    }

    /// One line: `eth_hand_control — unverified: wrist, thumb_mcp`, or `… — unverified (all 17
    /// joints)`.
    pub fn line(&self) -> String {
        match self {
            Verification::NoTable => "no table (offsets_rad only), unverified".to_string(),
            Verification::Verified { consumer, by, at } => {
                format!("{consumer} — verified by {by} on {at}")
            }
            Verification::Unverified {
                consumer,
                joints,
                of,
            } if joints.len() == *of => {
                format!("{consumer} — unverified (all {of} joints)")
            }
            Verification::Unverified {
                consumer, joints, ..
            } => format!("{consumer} — unverified: {}", joints.join(", ")),
        }
    }

    /// Whether every row was checked on a hand.
    pub fn is_verified(&self) -> bool {
        matches!(self, Verification::Verified { .. })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(joint: &str) -> JointConvention {
        JointConvention {
            joint: joint.into(),
            sign: 1,
            offset_deg: 0.0,
            ref_deg: 0.0,
            lower_deg: -10.0,
            upper_deg: 10.0,
            basis: Basis::Sources,
            verified: false,
            note: String::new(),
        }
    }

    fn table() -> Vec<JointConvention> {
        retarget::ORCA_CORE_JOINTS.iter().map(|j| row(j)).collect()
    }

    #[test]
    fn errors_name_the_row_the_key_and_the_allowed_range() {
        let err = |rows: &[JointConvention], ref_zero| {
            validate_joints(rows, ref_zero).unwrap_err().to_string()
        };
        let mut rows = table();
        rows[3].sign = 2;
        assert_eq!(
            err(&rows, None),
            "policy_output.joints[3].sign = 2 must be 1 or -1"
        );
        let mut rows = table();
        rows[5].joint = "index_tip".into();
        let e = err(&rows, None);
        assert!(
            e.starts_with(
                "policy_output.joints[5].joint = index_tip must be an ORCA joint (thumb_mcp, "
            ),
            "{e}"
        );
        let mut rows = table();
        rows[2].upper_deg = -20.0;
        assert_eq!(
            err(&rows, None),
            "policy_output.joints[2].upper_deg = -20 must be greater than policy_output.joints[2].lower_deg (-10)"
        );
        let mut rows = table();
        rows[1].offset_deg = f64::NAN;
        assert!(
            err(&rows, None)
                .contains("policy_output.joints[1].offset_deg = NaN must be in [-360, 360]")
        );
        let mut rows = table();
        rows[1].ref_deg = -42.0;
        assert!(err(&rows, None).contains(
            "policy_output.joints[1].ref_deg = -42 must be 0 unless policy_output.ref_zero"
        ));
        assert!(validate_joints(&rows, Some(RefZero::Equal)).is_ok());
        let mut rows = table();
        rows[4].joint = "thumb_mcp".into();
        assert_eq!(
            err(&rows, None),
            "policy_output.joints[4].joint = thumb_mcp must be a joint not already in policy_output.joints[0]"
        );
        let rows = table()[..16].to_vec();
        assert_eq!(
            err(&rows, None),
            "policy_output.joints = 16 rows must be one row for each of the 17 ORCA joints (missing: wrist)"
        );
    }

    #[test]
    fn the_ref_choice_moves_the_offset() {
        let mut r = row("thumb_abd");
        r.offset_deg = 1.0;
        r.ref_deg = -42.0;
        assert_eq!(r.effective_offset_deg(Some(RefZero::Equal)), 1.0);
        assert_eq!(r.effective_offset_deg(Some(RefZero::MinusRef)), 43.0);
    }

    #[test]
    fn verification_lists_the_joints_not_checked() {
        let mut rows = table();
        assert_eq!(
            Verification::of("eth", &rows, "", "").line(),
            "eth — unverified (all 17 joints)"
        );
        assert_eq!(
            Verification::of("x", &[], "", "").line(),
            "no table (offsets_rad only), unverified"
        );
        for r in &mut rows[1..] {
            r.verified = true;
        }
        rows[16].verified = false;
        let v = Verification::of("eth", &rows, "", "");
        assert_eq!(v.line(), "eth — unverified: thumb_mcp, wrist");
        assert!(!v.is_verified());
        for r in &mut rows {
            r.verified = true;
        }
        let v = Verification::of("eth", &rows, "ana", "2026-11-26T10:00:00Z");
        assert_eq!(v.line(), "eth — verified by ana on 2026-11-26T10:00:00Z");
    }
}
