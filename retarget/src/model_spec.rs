//! The project's own hand model description format (TOML), also the intermediate form every
//! importer (URDF) produces before [`HandModel::from_spec`](crate::HandModel::from_spec)
//! validates it.
//!
//! ```toml
//! name = "my_hand"
//! name_prefix = "right_"        # optional: the URDF's prefix of joint and link names
//!
//! [frames]                      # link names for the frames the station needs
//! palm = "palm"                 # rigid palm link
//! wrist = "wrist_jointbody"         # a link whose origin is on the wrist axis (or the palm root)
//! thumb_base = "thumb_mp"       # origin at the thumb's first joint
//! index_base = "index_abd_jointbody" # origins at each finger's first (abduction) joint
//! middle_base = "..."
//! ring_base = "..."
//! little_base = "..."
//! thumb_tip = "thumb_fingertip" # fingertip points
//! index_tip = "..."
//! middle_tip = "..."
//! ring_tip = "..."
//! little_tip = "..."
//! thumb_mid = "thumb_ip"        # optional, all five or none: frames matching the human
//! index_mid = "index_ip"        # digit's second keypoint (finger PIP, thumb MCP)
//! # middle_mid, ring_mid, little_mid likewise
//!
//! [[joint]]
//! name = "index_mcp"
//! kind = "revolute"             # revolute | continuous | fixed
//! parent = "index_mp"
//! child = "index_pp"
//! xyz_m = [0.0, 0.0, 0.0]       # origin of the joint frame in the parent link frame
//! rpy_rad = [0.0, 0.0, 0.0]     # URDF roll-pitch-yaw of the joint frame
//! axis = [0.0, -1.0, 0.0]       # rotation axis in the joint frame (normalised on load)
//! lower_rad = -0.35
//! upper_rad = 1.66
//! # coupled = { joint = "index_pip", multiplier = 0.58333, offset_rad = 0.0 }
//! ```
//!
//! A coupled joint follows another joint linearly, `q_j = multiplier · q_i + offset_rad`, and
//! is not a degree of freedom of its own. The degrees of freedom are the uncoupled revolute
//! joints, in the order they are written.

use serde::{Deserialize, Serialize};

/// A whole hand model description.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelSpec {
    /// The model's name (`orca_v1_right`).
    pub name: String,
    /// The prefix the robot's own URDF gives every joint and every link but the root
    /// (ORCA v1 right: `right_`), added back to every name the station publishes
    /// ([`HandModel::ros_dof_names`](crate::HandModel::ros_dof_names)). Empty: none.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub name_prefix: String,
    /// Published names of links and joints that differ from `name_prefix` + name (an
    /// importer records a URDF's original names here); not part of the file format.
    #[serde(skip)]
    pub source_names: std::collections::BTreeMap<String, String>,
    /// Link names of the frames the station uses.
    pub frames: FrameSpec,
    /// The joints; the links are the ones they connect.
    #[serde(rename = "joint")]
    pub joints: Vec<JointSpec>,
}

/// Link names of the frames the station uses (palm frame construction, key vectors).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)] // one field per frame; the module docs describe them
pub struct FrameSpec {
    pub palm: String,
    pub wrist: String,
    pub thumb_base: String,
    pub index_base: String,
    pub middle_base: String,
    pub ring_base: String,
    pub little_base: String,
    pub thumb_tip: String,
    pub index_tip: String,
    pub middle_tip: String,
    pub ring_tip: String,
    pub little_tip: String,
    /// Optional, all five or none: the robot frames matching the human digit's second
    /// keypoint (finger PIP, thumb MCP), for the palm → mid key vectors that keep finger
    /// flexion on the right branch.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thumb_mid: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub index_mid: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub middle_mid: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ring_mid: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub little_mid: Option<String>,
}

impl FrameSpec {
    /// Every frame as `(role, link name)`, in a fixed order.
    pub fn entries(&self) -> [(&'static str, &str); 12] {
        [
            ("palm", &self.palm),
            ("wrist", &self.wrist),
            ("thumb_base", &self.thumb_base),
            ("index_base", &self.index_base),
            ("middle_base", &self.middle_base),
            ("ring_base", &self.ring_base),
            ("little_base", &self.little_base),
            ("thumb_tip", &self.thumb_tip),
            ("index_tip", &self.index_tip),
            ("middle_tip", &self.middle_tip),
            ("ring_tip", &self.ring_tip),
            ("little_tip", &self.little_tip),
        ]
    }

    /// The optional mid frames as `(role, link name)`, thumb first.
    pub fn mid_entries(&self) -> [(&'static str, Option<&str>); 5] {
        [
            ("thumb_mid", self.thumb_mid.as_deref()),
            ("index_mid", self.index_mid.as_deref()),
            ("middle_mid", self.middle_mid.as_deref()),
            ("ring_mid", self.ring_mid.as_deref()),
            ("little_mid", self.little_mid.as_deref()),
        ]
    }
}

/// How a joint moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum JointKindSpec {
    /// Rotation about `axis` within `[lower_rad, upper_rad]`.
    Revolute,
    /// Unlimited rotation; modelled as revolute with limits `[-π, π]`.
    Continuous,
    /// No motion.
    Fixed,
}

/// One joint.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointSpec {
    /// Unique joint name; for a degree of freedom, the name used in `JointState`.
    pub name: String,
    /// Motion type.
    pub kind: JointKindSpec,
    /// Parent link name.
    pub parent: String,
    /// Child link name.
    pub child: String,
    /// Joint frame origin in the parent link frame, metres.
    #[serde(default)]
    pub xyz_m: [f64; 3],
    /// Joint frame orientation (URDF roll, pitch, yaw), radians.
    #[serde(default)]
    pub rpy_rad: [f64; 3],
    /// Rotation axis in the joint frame (revolute and continuous only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axis: Option<[f64; 3]>,
    /// Lower joint limit, radians (revolute only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lower_rad: Option<f64>,
    /// Upper joint limit, radians (revolute only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub upper_rad: Option<f64>,
    /// Linear coupling to another joint (URDF `<mimic>`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coupled: Option<CouplingSpec>,
}

/// `q_this = multiplier · q_joint + offset_rad`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CouplingSpec {
    /// The independent joint this one follows.
    pub joint: String,
    /// Gain (dimensionless, non-zero).
    pub multiplier: f64,
    /// Offset, radians.
    #[serde(default)]
    pub offset_rad: f64,
}
