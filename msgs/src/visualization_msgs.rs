//! `visualization_msgs`: markers (ROS 2 Humble and later field list).

use serde::{Deserialize, Serialize};

use crate::builtin_interfaces::Duration;
use crate::geometry_msgs::{Point, Pose, Vector3};
use crate::sensor_msgs::CompressedImage;
use crate::std_msgs::ColorRGBA;
use crate::{Header, MsgDefinition, RosMessage};

/// `visualization_msgs/msg/UVCoordinate`: a texture coordinate.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct UVCoordinate {
    /// u.
    pub u: f32,
    /// v.
    pub v: f32,
}

impl RosMessage for UVCoordinate {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "visualization_msgs",
        name: "UVCoordinate",
        text: "float32 u\nfloat32 v\n",
        dependencies: &[],
    };
}

/// `visualization_msgs/msg/MeshFile`: an embedded mesh (unused by the station: it ships none).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct MeshFile {
    /// The file's name (its extension gives the format).
    pub filename: String,
    /// The file's bytes.
    pub data: Vec<u8>,
}

impl RosMessage for MeshFile {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "visualization_msgs",
        name: "MeshFile",
        text: "string filename\nuint8[] data\n",
        dependencies: &[],
    };
}

/// `visualization_msgs/msg/Marker`: one shape to draw in `header.frame_id`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Marker {
    /// Stamp and frame.
    pub header: Header,
    /// Namespace; with `id` names the marker.
    pub ns: String,
    /// Identifier within `ns`.
    pub id: i32,
    /// Shape: [`Marker::ARROW`], [`Marker::CUBE`], [`Marker::SPHERE`], [`Marker::CYLINDER`],
    /// [`Marker::LINE_LIST`], [`Marker::SPHERE_LIST`], ….
    #[serde(rename = "type")]
    pub kind: i32,
    /// [`Marker::ADD`] (= modify), [`Marker::DELETE`] or [`Marker::DELETEALL`].
    pub action: i32,
    /// Pose in the frame.
    pub pose: Pose,
    /// Size, metres (per shape: diameter, length, line width).
    pub scale: Vector3,
    /// Colour of the whole marker.
    pub color: ColorRGBA,
    /// How long it stays; zero: until replaced.
    pub lifetime: Duration,
    /// Whether it moves with its frame after being received.
    pub frame_locked: bool,
    /// Points of list shapes.
    pub points: Vec<Point>,
    /// Per-point colours (empty: `color`).
    pub colors: Vec<ColorRGBA>,
    /// Texture URI (unused).
    pub texture_resource: String,
    /// Texture image (unused).
    pub texture: CompressedImage,
    /// Texture coordinates (unused).
    pub uv_coordinates: Vec<UVCoordinate>,
    /// Text of text markers.
    pub text: String,
    /// Mesh URI (unused: no mesh is shipped).
    pub mesh_resource: String,
    /// Embedded mesh (unused).
    pub mesh_file: MeshFile,
    /// Whether a mesh uses its own materials.
    pub mesh_use_embedded_materials: bool,
}

impl Marker {
    /// Shape: arrow.
    pub const ARROW: i32 = 0;
    /// Shape: box.
    pub const CUBE: i32 = 1;
    /// Shape: sphere (ellipsoid).
    pub const SPHERE: i32 = 2;
    /// Shape: cylinder along the pose's z axis.
    pub const CYLINDER: i32 = 3;
    /// Shape: connected line through `points`.
    pub const LINE_STRIP: i32 = 4;
    /// Shape: a line between each pair of `points`.
    pub const LINE_LIST: i32 = 5;
    /// Shape: a sphere at each of `points`.
    pub const SPHERE_LIST: i32 = 7;
    /// Shape: text facing the viewer.
    pub const TEXT_VIEW_FACING: i32 = 9;
    /// Action: add or replace.
    pub const ADD: i32 = 0;
    /// Action: delete this marker.
    pub const DELETE: i32 = 2;
    /// Action: delete every marker.
    pub const DELETEALL: i32 = 3;
}

impl RosMessage for Marker {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "visualization_msgs",
        name: "Marker",
        text: "int32 ARROW=0\n\
               int32 CUBE=1\n\
               int32 SPHERE=2\n\
               int32 CYLINDER=3\n\
               int32 LINE_STRIP=4\n\
               int32 LINE_LIST=5\n\
               int32 CUBE_LIST=6\n\
               int32 SPHERE_LIST=7\n\
               int32 POINTS=8\n\
               int32 TEXT_VIEW_FACING=9\n\
               int32 MESH_RESOURCE=10\n\
               int32 TRIANGLE_LIST=11\n\
               int32 ADD=0\n\
               int32 MODIFY=0\n\
               int32 DELETE=2\n\
               int32 DELETEALL=3\n\
               std_msgs/Header header\n\
               string ns\n\
               int32 id\n\
               int32 type\n\
               int32 action\n\
               geometry_msgs/Pose pose\n\
               geometry_msgs/Vector3 scale\n\
               std_msgs/ColorRGBA color\n\
               builtin_interfaces/Duration lifetime\n\
               bool frame_locked\n\
               geometry_msgs/Point[] points\n\
               std_msgs/ColorRGBA[] colors\n\
               string texture_resource\n\
               sensor_msgs/CompressedImage texture\n\
               UVCoordinate[] uv_coordinates\n\
               string text\n\
               string mesh_resource\n\
               MeshFile mesh_file\n\
               bool mesh_use_embedded_materials\n",
        dependencies: &[
            &Header::DEFINITION,
            &Pose::DEFINITION,
            &Vector3::DEFINITION,
            &ColorRGBA::DEFINITION,
            &Duration::DEFINITION,
            &Point::DEFINITION,
            &CompressedImage::DEFINITION,
            &UVCoordinate::DEFINITION,
            &MeshFile::DEFINITION,
        ],
    };
}

/// `visualization_msgs/msg/MarkerArray`: markers sent together.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct MarkerArray {
    /// The markers.
    pub markers: Vec<Marker>,
}

impl RosMessage for MarkerArray {
    const DEFINITION: MsgDefinition = MsgDefinition {
        package: "visualization_msgs",
        name: "MarkerArray",
        text: "Marker[] markers\n",
        dependencies: &[&Marker::DEFINITION],
    };
}
