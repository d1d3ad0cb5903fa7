//! `std_msgs`: header, strings and multi-dimensional arrays.

use serde::{Deserialize, Serialize};

use crate::{MsgDefinition, RosMessage, Time};

/// `std_msgs/msg/Header`: when and in which frame a stamped message's data was valid.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct Header {
    /// Time the data refers to.
    pub stamp: Time,
    /// Coordinate frame the data is expressed in (e.g. `coil`).
    pub frame_id: String,
}

impl RosMessage for Header {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "std_msgs",
        name: "Header",
        text: "builtin_interfaces/Time stamp\nstring frame_id\n",
        dependencies: &[&Time::DEFINITION],
    };
}

/// `std_msgs/msg/String`: one string. Named `StringMsg` so it does not shadow [`String`].
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct StringMsg {
    /// The text.
    pub data: String,
}

impl RosMessage for StringMsg {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "std_msgs",
        name: "String",
        text: "string data\n",
        dependencies: &[],
    };
}

/// `std_msgs/msg/MultiArrayDimension`: one axis of a multi-dimensional array.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct MultiArrayDimension {
    /// Name of the axis (e.g. `dim_0`).
    pub label: String,
    /// Number of elements along the axis.
    pub size: u32,
    /// Elements spanned by one step of the enclosing axis: the product of this and all inner
    /// sizes.
    pub stride: u32,
}

impl RosMessage for MultiArrayDimension {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "std_msgs",
        name: "MultiArrayDimension",
        text: "string label\nuint32 size\nuint32 stride\n",
        dependencies: &[],
    };
}

/// `std_msgs/msg/MultiArrayLayout`: the shape of a multi-dimensional array, outermost axis
/// first.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct MultiArrayLayout {
    /// The axes, outermost first.
    pub dim: Vec<MultiArrayDimension>,
    /// Number of padding elements at the front of `data`.
    pub data_offset: u32,
}

impl RosMessage for MultiArrayLayout {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "std_msgs",
        name: "MultiArrayLayout",
        text: "MultiArrayDimension[] dim\nuint32 data_offset\n",
        dependencies: &[&MultiArrayDimension::DEFINITION],
    };
}

/// `std_msgs/msg/Float32MultiArray`: a flat `f32` array with its shape.
///
/// The lab's `/ingress/mano` topic carries hand keypoints as an N×3 matrix in metres; see
/// [`Float32MultiArray::from_points`] and [`Float32MultiArray::points`].
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Float32MultiArray {
    /// Shape of `data`.
    pub layout: MultiArrayLayout,
    /// The elements, row-major.
    pub data: Vec<f32>,
}

impl RosMessage for Float32MultiArray {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "std_msgs",
        name: "Float32MultiArray",
        text: "MultiArrayLayout layout\nfloat32[] data\n",
        dependencies: &[&MultiArrayLayout::DEFINITION],
    };
}

/// `std_msgs/msg/Float64MultiArray`: a flat `f64` array with its shape.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Float64MultiArray {
    /// Shape of `data`.
    pub layout: MultiArrayLayout,
    /// The elements, row-major.
    pub data: Vec<f64>,
}

impl RosMessage for Float64MultiArray {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "std_msgs",
        name: "Float64MultiArray",
        text: "MultiArrayLayout layout\nfloat64[] data\n",
        dependencies: &[&MultiArrayLayout::DEFINITION],
    };
}

/// `std_msgs/msg/ColorRGBA`: a colour, each channel in `[0, 1]` (`a` = opacity).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct ColorRGBA {
    /// Red.
    pub r: f32,
    /// Green.
    pub g: f32,
    /// Blue.
    pub b: f32,
    /// Opacity.
    pub a: f32,
}

impl RosMessage for ColorRGBA {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "std_msgs",
        name: "ColorRGBA",
        text: "float32 r\nfloat32 g\nfloat32 b\nfloat32 a\n",
        dependencies: &[],
    };
}
