//! `geometry_msgs`: points, orientations and poses.

use serde::{Deserialize, Serialize};

use crate::{Header, MsgDefinition, RosMessage};

/// `geometry_msgs/msg/Point`: a position, in metres in the frame of the enclosing message.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Point {
    /// x coordinate.
    pub x: f64,
    /// y coordinate.
    pub y: f64,
    /// z coordinate.
    pub z: f64,
}

impl RosMessage for Point {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "geometry_msgs",
        name: "Point",
        text: "float64 x\nfloat64 y\nfloat64 z\n",
        dependencies: &[],
    };
}

/// `geometry_msgs/msg/Quaternion`: an orientation as `x i + y j + z k + w`.
///
/// The default is the identity (`w = 1`), as in ROS 2, whose `.msg` gives `w` a default of 1.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Quaternion {
    /// i component.
    pub x: f64,
    /// j component.
    pub y: f64,
    /// k component.
    pub z: f64,
    /// Real component.
    pub w: f64,
}

impl Quaternion {
    /// The identity rotation `(0, 0, 0, 1)`.
    pub const fn identity() -> Self {
        Quaternion {
            x: 0.0,
            y: 0.0,
            z: 0.0,
            w: 1.0,
        }
    }
}

impl Default for Quaternion {
    fn default() -> Self {
        Quaternion::identity()
    }
}

impl RosMessage for Quaternion {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "geometry_msgs",
        name: "Quaternion",
        text: "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n",
        dependencies: &[],
    };
}

/// `geometry_msgs/msg/Pose`: a position and an orientation. The default is the origin with the
/// identity orientation.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Pose {
    /// Position.
    pub position: Point,
    /// Orientation (a unit quaternion when well formed).
    pub orientation: Quaternion,
}

impl RosMessage for Pose {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "geometry_msgs",
        name: "Pose",
        text: "Point position\nQuaternion orientation\n",
        dependencies: &[&Point::DEFINITION, &Quaternion::DEFINITION],
    };
}

/// `geometry_msgs/msg/PoseStamped`: a pose in `header.frame_id` at `header.stamp` (the lab's
/// `/ingress/wrist`, frame `coil`).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct PoseStamped {
    /// Stamp and frame.
    pub header: Header,
    /// The pose.
    pub pose: Pose,
}

impl RosMessage for PoseStamped {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "geometry_msgs",
        name: "PoseStamped",
        text: "std_msgs/Header header\nPose pose\n",
        dependencies: &[&Header::DEFINITION, &Pose::DEFINITION],
    };
}

/// `geometry_msgs/msg/PoseArray`: poses sharing one stamp and frame.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct PoseArray {
    /// Stamp and frame.
    pub header: Header,
    /// The poses.
    pub poses: Vec<Pose>,
}

impl RosMessage for PoseArray {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "geometry_msgs",
        name: "PoseArray",
        text: "std_msgs/Header header\nPose[] poses\n",
        dependencies: &[&Header::DEFINITION, &Pose::DEFINITION],
    };
}

/// `geometry_msgs/msg/Vector3`: a free vector (a translation, a marker's scale).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Vector3 {
    /// x component.
    pub x: f64,
    /// y component.
    pub y: f64,
    /// z component.
    pub z: f64,
}

impl RosMessage for Vector3 {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "geometry_msgs",
        name: "Vector3",
        text: "float64 x\nfloat64 y\nfloat64 z\n",
        dependencies: &[],
    };
}

/// `geometry_msgs/msg/Transform`: a child frame's pose in its parent frame.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Transform {
    /// The child frame's origin in the parent frame, metres.
    pub translation: Vector3,
    /// The child frame's orientation in the parent frame.
    pub rotation: Quaternion,
}

impl RosMessage for Transform {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "geometry_msgs",
        name: "Transform",
        text: "Vector3 translation\nQuaternion rotation\n",
        dependencies: &[&Vector3::DEFINITION, &Quaternion::DEFINITION],
    };
}

/// `geometry_msgs/msg/TransformStamped`: frame `child_frame_id` in frame `header.frame_id` at
/// `header.stamp` (one edge of the `/tf` tree).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct TransformStamped {
    /// Stamp and parent frame.
    pub header: Header,
    /// The child frame.
    pub child_frame_id: String,
    /// The child frame in the parent frame.
    pub transform: Transform,
}

impl RosMessage for TransformStamped {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "geometry_msgs",
        name: "TransformStamped",
        text: "std_msgs/Header header\nstring child_frame_id\nTransform transform\n",
        dependencies: &[&Header::DEFINITION, &Transform::DEFINITION],
    };
}
