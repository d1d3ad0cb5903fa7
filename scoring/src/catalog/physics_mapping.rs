//! Where a task's progress is read in a simulated scene: [`PhysicsMapping`].
//!
//! Pure data, kept in the catalog so that a lab can map the joints of its OWN task files next
//! to the task they belong to (`physics = { joint = "bolt_hinge", direction = "decreasing" }`).
//! The `simulation` crate reads the mapping and turns joint or body readings into the same
//! progress events an operator's keys make; this crate only checks that the mapping fits the
//! task's [`CorrectnessKind`].
//!
//! | kind | `joint` | needs |
//! |---|---|---|
//! | notches, curves | a slide (m) or hinge (rad) | `marks`: one joint position per notch/curve, in passing order |
//! | rotation | a hinge (rad) | `direction`: which way is forward |
//! | distance | a slide (m) | `direction` |
//! | grasp | the object's free joint | `grasp`: lift height and target box |
//!
//! The defaults (`mark_band` 1 mm, `lift_m` 30 mm, `rest_speed_m_s` 0.02,
//! `rest_time_s` 0.2) are this project's choices, not the paper's.

use serde::{Deserialize, Serialize};

use super::CorrectnessKind;

/// The hysteresis half-band around a mark by default (1 mm on a slide, 1 mrad on a hinge).
pub const DEFAULT_MARK_BAND: f64 = 0.001;
/// The lift above the rest height that counts as lifted by default, m.
pub const DEFAULT_LIFT_M: f64 = 0.03;
/// The speed below which an object counts as resting by default, m/s.
pub const DEFAULT_REST_SPEED_M_S: f64 = 0.02;
/// How long an object must stay slower than the rest speed to count as resting by default, s.
pub const DEFAULT_REST_TIME_S: f64 = 0.2;

/// How a task's progress is read from a simulated scene's physics state.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PhysicsMapping {
    /// The progress joint's name in the scene's MJCF: a slide (position in m) or a hinge
    /// (angle in rad) for notches, curves, rotation and distance; the object's free joint for
    /// grasp (its body's position and speed are read).
    pub joint: String,
    /// Notches and curves: the joint positions (m or rad, as the joint) at which each notch or
    /// curve counts as passed, in the order they are passed: strictly increasing, or strictly
    /// decreasing with `direction = "decreasing"`, one per notch or curve. Empty otherwise.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub marks: Vec<f64>,
    /// Notches and curves: the hysteresis half-band around each mark (m or rad, as `marks`): a
    /// mark counts once the joint is this far past it, and is taken back once the joint is
    /// this far back before it. Default [`DEFAULT_MARK_BAND`].
    #[serde(
        default = "default_mark_band",
        skip_serializing_if = "is_default_mark_band"
    )]
    pub mark_band: f64,
    /// Which way of the joint is forward (notches, curves, rotation, distance). Default
    /// increasing.
    #[serde(default, skip_serializing_if = "Direction::is_increasing")]
    pub direction: Direction,
    /// Grasp only: when the object counts as lifted and as relocated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grasp: Option<GraspMapping>,
}

/// Which way of a joint counts as forward.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Direction {
    /// The joint position grows as the task progresses.
    #[default]
    Increasing,
    /// The joint position shrinks as the task progresses (a hinge whose range is negative).
    Decreasing,
}

impl Direction {
    /// +1 for increasing, −1 for decreasing.
    pub fn sign(self) -> f64 {
        match self {
            Direction::Increasing => 1.0,
            Direction::Decreasing => -1.0,
        }
    }

    /// Whether this is [`Direction::Increasing`] (the default).
    pub fn is_increasing(&self) -> bool {
        *self == Direction::Increasing
    }
}

/// Grasp: when the object counts as lifted (level 0.5) and as relocated (level 1).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GraspMapping {
    /// Height above the object's rest height (its height at the start) that counts as
    /// lifted, m, in (0, 1]. Default [`DEFAULT_LIFT_M`].
    #[serde(default = "default_lift_m")]
    pub lift_m: f64,
    /// The target region's lower corner in the world frame (x, y, z), m: the object's body
    /// origin must rest inside the box.
    pub target_min_m: [f64; 3],
    /// The target region's upper corner in the world frame (x, y, z), m; above `target_min_m`
    /// on every axis.
    pub target_max_m: [f64; 3],
    /// The speed below which the object counts as resting, m/s, > 0. Default
    /// [`DEFAULT_REST_SPEED_M_S`].
    #[serde(default = "default_rest_speed_m_s")]
    pub rest_speed_m_s: f64,
    /// How long the object must stay below `rest_speed_m_s` to count as resting, s, ≥ 0.
    /// Default [`DEFAULT_REST_TIME_S`].
    #[serde(default = "default_rest_time_s")]
    pub rest_time_s: f64,
}

impl GraspMapping {
    /// A grasp mapping with the default thresholds and the target box `min`..`max` (m).
    pub fn with_target(target_min_m: [f64; 3], target_max_m: [f64; 3]) -> GraspMapping {
        GraspMapping {
            lift_m: DEFAULT_LIFT_M,
            target_min_m,
            target_max_m,
            rest_speed_m_s: DEFAULT_REST_SPEED_M_S,
            rest_time_s: DEFAULT_REST_TIME_S,
        }
    }

    /// Whether `position_m` (world, m) lies inside the target box (edges included).
    pub fn in_target(&self, position_m: [f64; 3]) -> bool {
        (0..3)
            .all(|i| self.target_min_m[i] <= position_m[i] && position_m[i] <= self.target_max_m[i])
    }
}

/// A mapping that does not fit its task: the field, the value found and what is allowed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("physics.{field} = {value}: {allowed}")]
pub struct InvalidMapping {
    /// The field under `physics` (`marks`, `grasp.lift_m`).
    pub field: String,
    /// The value found.
    pub value: String,
    /// What is allowed.
    pub allowed: String,
}

fn invalid(field: &str, value: impl std::fmt::Debug, allowed: impl Into<String>) -> InvalidMapping {
    InvalidMapping {
        field: field.to_string(),
        value: format!("{value:?}"),
        allowed: allowed.into(),
    }
}

impl PhysicsMapping {
    /// A mapping of `joint` with no marks, forward increasing, no grasp part.
    pub fn joint(joint: impl Into<String>) -> PhysicsMapping {
        PhysicsMapping {
            joint: joint.into(),
            marks: Vec::new(),
            mark_band: DEFAULT_MARK_BAND,
            direction: Direction::Increasing,
            grasp: None,
        }
    }

    /// Checks the mapping against the task's kind: a joint name; marks exactly for notches
    /// and curves (one per notch or curve, finite, strictly monotonic in `direction`, further
    /// apart than twice the band); a band finite and > 0; a grasp part exactly for grasp tasks,
    /// with finite values in range.
    pub fn validate(&self, kind: &CorrectnessKind) -> Result<(), InvalidMapping> {
        if self.joint.trim().is_empty() {
            return Err(invalid("joint", &self.joint, "the progress joint's name"));
        }
        if !(self.mark_band.is_finite() && self.mark_band > 0.0) {
            return Err(invalid(
                "mark_band",
                self.mark_band,
                "m or rad, finite and > 0",
            ));
        }
        match *kind {
            CorrectnessKind::Notches { count } | CorrectnessKind::Curves { count } => {
                self.validate_marks(count, kind.progress_unit())?;
            }
            _ if !self.marks.is_empty() => {
                return Err(invalid(
                    "marks",
                    &self.marks,
                    format!("no marks for a {} task", kind.describe()),
                ));
            }
            _ => {}
        }
        match (kind, &self.grasp) {
            (CorrectnessKind::Grasp {}, Some(grasp)) => validate_grasp(grasp),
            (CorrectnessKind::Grasp {}, None) => Err(invalid(
                "grasp",
                "none",
                "a grasp part (lift_m, target_min_m, target_max_m) for a grasp task",
            )),
            (_, Some(_)) => Err(invalid(
                "grasp",
                "{..}",
                format!("no grasp part for a {} task", kind.describe()),
            )),
            (_, None) => Ok(()),
        }
    }

    fn validate_marks(&self, count: u32, unit: &str) -> Result<(), InvalidMapping> {
        if self.marks.len() != count as usize {
            return Err(invalid(
                "marks",
                &self.marks,
                format!("{count} joint positions, one per {unit} (m or rad)"),
            ));
        }
        if self.marks.iter().any(|m| !m.is_finite()) {
            return Err(invalid("marks", &self.marks, "finite joint positions"));
        }
        let sign = self.direction.sign();
        let min_gap = 2.0 * self.mark_band;
        if self
            .marks
            .windows(2)
            .any(|w| sign * (w[1] - w[0]) <= min_gap)
        {
            let order = match self.direction {
                Direction::Increasing => "increasing",
                Direction::Decreasing => "decreasing",
            };
            return Err(invalid(
                "marks",
                &self.marks,
                format!(
                    "strictly {order} (the direction), more than 2 × mark_band ({min_gap}) apart"
                ),
            ));
        }
        Ok(())
    }
}

fn validate_grasp(grasp: &GraspMapping) -> Result<(), InvalidMapping> {
    if !(grasp.lift_m.is_finite() && grasp.lift_m > 0.0 && grasp.lift_m <= 1.0) {
        return Err(invalid("grasp.lift_m", grasp.lift_m, "m, in (0, 1]"));
    }
    let corners = [grasp.target_min_m, grasp.target_max_m];
    if corners.iter().flatten().any(|v| !v.is_finite()) {
        return Err(invalid(
            "grasp.target_min_m",
            corners,
            "finite world coordinates, m",
        ));
    }
    if (0..3).any(|i| grasp.target_min_m[i] >= grasp.target_max_m[i]) {
        return Err(invalid(
            "grasp.target_max_m",
            grasp.target_max_m,
            format!(
                "above target_min_m {:?} on every axis, m",
                grasp.target_min_m
            ),
        ));
    }
    if !(grasp.rest_speed_m_s.is_finite() && grasp.rest_speed_m_s > 0.0) {
        return Err(invalid(
            "grasp.rest_speed_m_s",
            grasp.rest_speed_m_s,
            "m/s, finite and > 0",
        ));
    }
    if !(grasp.rest_time_s.is_finite() && grasp.rest_time_s >= 0.0) {
        return Err(invalid(
            "grasp.rest_time_s",
            grasp.rest_time_s,
            "s, finite and ≥ 0",
        ));
    }
    Ok(())
}

fn default_mark_band() -> f64 {
    DEFAULT_MARK_BAND
}

#[allow(clippy::trivially_copy_pass_by_ref)] // serde's skip_serializing_if passes a reference
fn is_default_mark_band(band: &f64) -> bool {
    *band == DEFAULT_MARK_BAND
}

fn default_lift_m() -> f64 {
    DEFAULT_LIFT_M
}

fn default_rest_speed_m_s() -> f64 {
    DEFAULT_REST_SPEED_M_S
}

fn default_rest_time_s() -> f64 {
    DEFAULT_REST_TIME_S
}

#[cfg(test)]
mod tests {
    use super::*;

    const NOTCHES: CorrectnessKind = CorrectnessKind::Notches { count: 3 };

    fn marked(marks: &[f64]) -> PhysicsMapping {
        PhysicsMapping {
            marks: marks.to_vec(),
            ..PhysicsMapping::joint("slide")
        }
    }

    #[test]
    fn marks_must_fit_the_count_and_run_one_way() {
        assert_eq!(marked(&[0.01, 0.02, 0.03]).validate(&NOTCHES), Ok(()));
        let short = marked(&[0.01, 0.02]).validate(&NOTCHES).unwrap_err();
        assert_eq!(short.field, "marks");
        assert!(short.allowed.contains("3 joint positions"), "{short}");
        let back = marked(&[0.01, 0.03, 0.02]).validate(&NOTCHES).unwrap_err();
        assert!(back.allowed.contains("strictly increasing"), "{back}");
        let down = PhysicsMapping {
            direction: Direction::Decreasing,
            ..marked(&[0.03, 0.02, 0.01])
        };
        assert_eq!(down.validate(&NOTCHES), Ok(()));
        let close = marked(&[0.01, 0.0115, 0.03])
            .validate(&NOTCHES)
            .unwrap_err();
        assert!(close.allowed.contains("apart"), "{close}");
    }

    #[test]
    fn each_kind_takes_only_its_own_parts() {
        let rotation = CorrectnessKind::Rotation { full_deg: 360.0 };
        assert_eq!(PhysicsMapping::joint("hinge").validate(&rotation), Ok(()));
        let marks = marked(&[0.1]).validate(&rotation).unwrap_err();
        assert!(marks.allowed.contains("no marks for a rotation"), "{marks}");
        let grasp = CorrectnessKind::Grasp {};
        let missing = PhysicsMapping::joint("free").validate(&grasp).unwrap_err();
        assert_eq!(missing.field, "grasp");
        let with_grasp = PhysicsMapping {
            grasp: Some(GraspMapping::with_target([0.4, 0.1, 0.0], [0.5, 0.2, 0.1])),
            ..PhysicsMapping::joint("free")
        };
        assert_eq!(with_grasp.validate(&grasp), Ok(()));
        assert!(with_grasp.validate(&rotation).is_err());
    }

    #[test]
    fn grasp_values_are_checked_with_their_ranges() {
        let kind = CorrectnessKind::Grasp {};
        let mut grasp = GraspMapping::with_target([0.4, 0.1, 0.0], [0.5, 0.2, 0.1]);
        grasp.target_max_m[2] = 0.0;
        let mapping = PhysicsMapping {
            grasp: Some(grasp.clone()),
            ..PhysicsMapping::joint("free")
        };
        let error = mapping.validate(&kind).unwrap_err();
        assert_eq!(
            error.to_string().split(" = ").next(),
            Some("physics.grasp.target_max_m")
        );
        grasp.target_max_m[2] = 0.1;
        grasp.lift_m = 0.0;
        let mapping = PhysicsMapping {
            grasp: Some(grasp),
            ..PhysicsMapping::joint("free")
        };
        let error = mapping.validate(&kind).unwrap_err();
        assert_eq!(error.field, "grasp.lift_m");
        assert!(error.allowed.contains("(0, 1]"));
    }

    #[test]
    fn the_target_box_includes_its_faces() {
        let grasp = GraspMapping::with_target([0.0; 3], [1.0; 3]);
        assert!(grasp.in_target([0.0, 1.0, 0.5]));
        assert!(!grasp.in_target([0.0, 1.01, 0.5]));
    }

    #[test]
    fn a_mapping_reads_from_toml_with_defaults_and_refuses_unknown_keys() {
        let mapping: PhysicsMapping =
            toml::from_str("joint = \"bolt_hinge\"\ndirection = \"decreasing\"\n").unwrap();
        assert_eq!(mapping.direction, Direction::Decreasing);
        assert_eq!(mapping.mark_band, DEFAULT_MARK_BAND);
        let unknown = toml::from_str::<PhysicsMapping>("joint = \"j\"\nband = 1.0\n");
        assert!(unknown.unwrap_err().to_string().contains("band"));
        let grasp: PhysicsMapping = toml::from_str(
            "joint = \"g\"\ngrasp = { target_min_m = [0, 0, 0], target_max_m = [1, 1, 1] }\n",
        )
        .unwrap();
        assert_eq!(grasp.grasp.map(|g| g.lift_m), Some(DEFAULT_LIFT_M));
    }
}
