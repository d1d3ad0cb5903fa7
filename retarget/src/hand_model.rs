//! [`HandModel`]: a validated kinematic tree of revolute and fixed joints with named frames.
//!
//! Frames and units: every link has a frame; the root link's frame is the model's base frame
//! (for ORCA, the URDF `world` link under the tower). Positions are metres, angles radians.
//! A joint's frame is its parent link frame moved by the joint origin, then rotated by the
//! joint angle about the joint axis; the child link frame *is* that joint frame.

use nalgebra::{Isometry3, Unit, Vector3};

use crate::finger::Finger;

/// Index of a link (a frame) in a [`HandModel`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct LinkId(pub(crate) usize);

impl LinkId {
    /// Position of the link in [`HandModel::link_names`].
    pub fn index(self) -> usize {
        self.0
    }
}

/// Closed interval of joint positions, radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Lower bound, radians.
    pub lower_rad: f64,
    /// Upper bound, radians.
    pub upper_rad: f64,
}

impl Limits {
    /// Whether `q` lies within the limits (inclusive).
    pub fn contains(&self, q: f64) -> bool {
        q >= self.lower_rad && q <= self.upper_rad
    }

    /// `q` clamped into the limits.
    pub fn clamp(&self, q: f64) -> f64 {
        q.clamp(self.lower_rad, self.upper_rad)
    }
}

/// How a joint moves.
#[derive(Debug, Clone, PartialEq)]
pub enum JointMotion {
    /// Rigid connection.
    Fixed,
    /// Rotation about `axis` (unit, joint frame) by `multiplier · q[dof] + offset_rad`.
    Revolute {
        /// Rotation axis in the joint frame.
        axis: Unit<Vector3<f64>>,
        /// The degree of freedom driving it.
        dof: usize,
        /// 1 for an independent joint; the coupling gain for a coupled one.
        multiplier: f64,
        /// 0 for an independent joint; the coupling offset for a coupled one, radians.
        offset_rad: f64,
        /// The joint's own limits.
        limits: Limits,
    },
}

/// One joint of the tree.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// Joint name.
    pub name: String,
    /// Parent link.
    pub parent: LinkId,
    /// Child link (its frame is the joint frame).
    pub child: LinkId,
    /// Joint frame in the parent link frame at zero angle.
    pub origin: Isometry3<f64>,
    /// Motion.
    pub motion: JointMotion,
}

/// An independent degree of freedom: an uncoupled revolute joint.
#[derive(Debug, Clone, PartialEq)]
pub struct Dof {
    /// The joint name (as in `sensor_msgs/JointState`).
    pub name: String,
    /// Index of the joint in [`HandModel::joints`].
    pub joint: usize,
    /// Bounds on this variable: the joint's limits intersected with the limits of every
    /// joint coupled to it.
    pub limits: Limits,
}

/// The frames the station uses, as links of the model.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NamedFrames {
    /// The rigid palm link.
    pub palm: LinkId,
    /// A link whose origin lies on the wrist axis.
    pub wrist: LinkId,
    /// Finger base frames, indexed by [`Finger::index`].
    pub bases: [LinkId; 5],
    /// Fingertip frames, indexed by [`Finger::index`].
    pub tips: [LinkId; 5],
    /// Frames matching each human digit's second keypoint (finger PIP, thumb MCP), if the
    /// model names them.
    pub mids: Option<[LinkId; 5]>,
}

impl NamedFrames {
    /// The base frame of `finger`.
    pub fn base(&self, finger: Finger) -> LinkId {
        self.bases[finger.index()]
    }

    /// The fingertip frame of `finger`.
    pub fn tip(&self, finger: Finger) -> LinkId {
        self.tips[finger.index()]
    }
}

/// A validated hand model. Build it with [`HandModel::orca_v1_right`],
/// [`HandModel::from_toml_str`], [`HandModel::from_urdf_str`] or [`HandModel::from_spec`].
#[derive(Debug, Clone, PartialEq)]
pub struct HandModel {
    pub(crate) name: String,
    /// The URDF's prefix of joint and link names (`right_`), or empty.
    pub(crate) name_prefix: String,
    /// Per degree of freedom: its name as the robot's URDF spells it.
    pub(crate) ros_dof_names: Vec<String>,
    /// Per link: its name as the robot's URDF spells it (a `/tf` frame).
    pub(crate) ros_link_names: Vec<String>,
    pub(crate) link_names: Vec<String>,
    /// Joints in topological order: a joint's parent link is posed before its child.
    pub(crate) joints: Vec<Joint>,
    pub(crate) dofs: Vec<Dof>,
    pub(crate) frames: NamedFrames,
    /// Per link: indices of the revolute joints between the root and the link.
    pub(crate) chains: Vec<Vec<usize>>,
}

impl HandModel {
    /// The prefix the robot's URDF gives its joint and link names (`right_` for ORCA v1
    /// right; the import file's `strip_prefix`), or empty.
    pub fn name_prefix(&self) -> &str {
        &self.name_prefix
    }

    /// Each degree of freedom's name as the robot's URDF spells it (ORCA v1 right:
    /// `right_thumb_mcp`, …): what `sensor_msgs/JointState` carries for robot_state_publisher.
    pub fn ros_dof_names(&self) -> &[String] {
        &self.ros_dof_names
    }

    /// Each link's name as the robot's URDF spells it (its `/tf` frame), in
    /// [`HandModel::link_names`] order; the root keeps its own name (ORCA: `world`).
    pub fn ros_link_names(&self) -> &[String] {
        &self.ros_link_names
    }

    /// The model's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Number of independent degrees of freedom (the length of a joint vector `q`).
    pub fn dof(&self) -> usize {
        self.dofs.len()
    }

    /// The degrees of freedom, in the order of the joint vector.
    pub fn dofs(&self) -> &[Dof] {
        &self.dofs
    }

    /// Names of the degrees of freedom, in the order of the joint vector.
    pub fn dof_names(&self) -> impl Iterator<Item = &str> {
        self.dofs.iter().map(|d| d.name.as_str())
    }

    /// Index of the degree of freedom called `name`.
    pub fn dof_index(&self, name: &str) -> Option<usize> {
        self.dofs.iter().position(|d| d.name == name)
    }

    /// Bounds of every degree of freedom, in joint-vector order.
    pub fn limits(&self) -> impl Iterator<Item = Limits> + '_ {
        self.dofs.iter().map(|d| d.limits)
    }

    /// All joints, in topological order.
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// The joint called `name`.
    pub fn joint(&self, name: &str) -> Option<&Joint> {
        self.joints.iter().find(|j| j.name == name)
    }

    /// Link names, indexed by [`LinkId::index`]; the root is first.
    pub fn link_names(&self) -> &[String] {
        &self.link_names
    }

    /// The link called `name`.
    pub fn link(&self, name: &str) -> Option<LinkId> {
        self.link_names.iter().position(|l| l == name).map(LinkId)
    }

    /// Name of a link.
    pub fn link_name(&self, link: LinkId) -> &str {
        &self.link_names[link.0]
    }

    /// The named frames.
    pub fn frames(&self) -> &NamedFrames {
        &self.frames
    }

    /// Per degree of freedom, the digit whose fingertip chain alone it moves; `None` for one
    /// shared by several chains (a wrist) or moving none.
    pub fn dof_digits(&self) -> Vec<Option<Finger>> {
        self.dofs
            .iter()
            .map(|dof| {
                let moves: Vec<Finger> = Finger::ALL
                    .into_iter()
                    .filter(|f| self.chains[self.frames.tip(*f).0].contains(&dof.joint))
                    .collect();
                match moves[..] {
                    [finger] => Some(finger),
                    _ => None,
                }
            })
            .collect()
    }

    /// Number of links.
    pub fn link_count(&self) -> usize {
        self.link_names.len()
    }

    /// A joint vector with every degree of freedom at zero, clamped into its limits.
    pub fn zero_pose(&self) -> Vec<f64> {
        self.dofs.iter().map(|d| d.limits.clamp(0.0)).collect()
    }

    /// Whether every value of `q` lies within its limits and is finite.
    pub fn within_limits(&self, q: &[f64]) -> bool {
        q.len() == self.dofs.len()
            && q.iter()
                .zip(&self.dofs)
                .all(|(&v, d)| v.is_finite() && d.limits.contains(v))
    }
}
