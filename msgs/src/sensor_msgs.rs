//! `sensor_msgs`: joint states.

use serde::{Deserialize, Serialize};

use crate::{Header, MsgDefinition, RosMessage};

/// `sensor_msgs/msg/JointState`: the state of named joints.
///
/// `position`, `velocity` and `effort` are either empty or as long as `name`, index `i`
/// belonging to `name[i]`. Units: rad, rad/s, N·m for revolute joints; m, m/s, N for prismatic
/// ones. This type does not enforce the lengths; publishers must.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct JointState {
    /// Stamp; the frame is unused.
    pub header: Header,
    /// Joint names.
    pub name: Vec<String>,
    /// Joint positions.
    pub position: Vec<f64>,
    /// Joint velocities.
    pub velocity: Vec<f64>,
    /// Joint efforts.
    pub effort: Vec<f64>,
}

impl RosMessage for JointState {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "sensor_msgs",
        name: "JointState",
        text: "std_msgs/Header header\n\
               string[] name\n\
               float64[] position\n\
               float64[] velocity\n\
               float64[] effort\n",
        dependencies: &[&Header::DEFINITION],
    };
}

/// `sensor_msgs/msg/CompressedImage`: an encoded image (only as a marker's empty texture here).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct CompressedImage {
    /// Stamp and frame.
    pub header: Header,
    /// `jpeg`, `png`, ….
    pub format: String,
    /// The encoded bytes.
    pub data: Vec<u8>,
}

impl RosMessage for CompressedImage {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "sensor_msgs",
        name: "CompressedImage",
        text: "std_msgs/Header header\nstring format\nuint8[] data\n",
        dependencies: &[&Header::DEFINITION],
    };
}
