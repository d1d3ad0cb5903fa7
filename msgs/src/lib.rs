//! # msgs: ROS 2 message types for the POMDAR station
//!
//! Plain serde structs for the ROS 2 messages the station exchanges, with their CDR encoding
//! and their `.msg` schema texts. The same structs are published by ros2-client (which takes
//! any serde type) and decoded from MCAP logs, so this crate needs no ROS dependency: it never
//! depends on ros2-client, rustdds or tokio, and does no I/O (checked by
//! `tests/tests/suite/dependency_rule.rs`).
//!
//! | module | types |
//! |---|---|
//! | [`builtin_interfaces`] | [`Time`] |
//! | [`std_msgs`] | [`Header`], [`StringMsg`], [`MultiArrayDimension`], [`MultiArrayLayout`], [`Float32MultiArray`], [`Float64MultiArray`] |
//! | [`geometry_msgs`] | [`Point`], [`Quaternion`], [`Pose`], [`PoseStamped`], [`PoseArray`] |
//! | [`sensor_msgs`] | [`JointState`], [`CompressedImage`] |
//! | [`tf2_msgs`] | [`TFMessage`] (with `geometry_msgs` [`Vector3`], [`Transform`], [`TransformStamped`]) |
//! | [`visualization_msgs`] | [`Marker`], [`MarkerArray`] (with `std_msgs` [`ColorRGBA`], `builtin_interfaces` [`Duration`]) |
//! | [`diagnostic_msgs`] | [`DiagnosticArray`], [`DiagnosticStatus`], [`KeyValue`] |
//! | [`std_srvs`] | `Trigger`: [`TriggerRequest`], [`TriggerResponse`] |
//!
//! Field order follows the ROS 2 (Humble/Jazzy) `.msg` files exactly: CDR is positional.
//!
//! ## CDR framing
//!
//! A serialized payload, as on the DDS wire and in an MCAP message record with
//! `message_encoding = "cdr"`, is
//!
//! ```text
//! 00 01 00 00   encapsulation header: CDR_LE (00 01), options 00 00
//! ...           CDR body
//! ```
//!
//! In the body every primitive of size `n` (1, 2, 4 or 8 bytes) starts at an offset, counted
//! from the first byte **after** the header, that is a multiple of `n` (zero padding before
//! it); a string is a `u32` length counting a terminating NUL, the bytes and the NUL; a
//! sequence is a `u32` element count then the elements; a nested message is its fields in
//! order, with no alignment of its own. [`to_cdr`] writes little-endian; [`from_cdr`] also
//! reads big-endian (`00 00`), ignores the option bytes, tolerates up to 3 trailing padding
//! bytes, and returns an [`Error`] (never panics) on any other input.
//!
//! ## Schema texts
//!
//! [`RosMessage`] gives each type its names (`pkg/msg/Type`, and the DDS name
//! `pkg::msg::dds_::Type_`) and its complete `ros2msg` schema for MCAP, built as rosbag2
//! builds it: the type's own `.msg` text, then for each transitive dependency (depth first,
//! each once, siblings in lexicographic order)
//!
//! ```text
//!                                     (empty line: rosbag2 writes "\n" before each separator)
//! ================================================================================
//! MSG: pkg/Type
//! <that type's .msg text>
//! ```
//!
//! The `.msg` texts are the ROS 2 files without their comments.
//!
//! ```
//! use msgs::{PoseStamped, RosMessage, from_cdr, to_cdr};
//!
//! let msg = PoseStamped::default();
//! let bytes = to_cdr(&msg)?;
//! assert_eq!(&bytes[..4], [0, 1, 0, 0]);
//! assert_eq!(from_cdr::<PoseStamped>(&bytes)?, msg);
//! assert_eq!(PoseStamped::ros_type_name(), "geometry_msgs/msg/PoseStamped");
//! assert!(PoseStamped::schema_text().contains("\nMSG: builtin_interfaces/Time\n"));
//! # Ok::<(), msgs::Error>(())
//! ```

pub mod builtin_interfaces;
mod cdr;
mod definition;
pub mod diagnostic_msgs;
mod error;
pub mod geometry_msgs;
mod point_matrix;
pub mod sensor_msgs;
pub mod std_msgs;
pub mod std_srvs;
pub mod tf2_msgs;
pub mod visualization_msgs;

#[cfg(test)]
mod golden_tests;
#[cfg(test)]
mod hostile_input_tests;
#[cfg(test)]
mod round_trip_tests;
#[cfg(test)]
mod schema_tests;

pub use builtin_interfaces::{Duration, Time};
pub use cdr::{CDR_BE_ID, CDR_LE_HEADER, CDR_LE_ID, from_cdr, to_cdr};
pub use definition::{MsgDefinition, RosMessage, SCHEMA_SEPARATOR};
pub use diagnostic_msgs::{DiagnosticArray, DiagnosticStatus, KeyValue};
pub use error::Error;
pub use geometry_msgs::{
    Point, Pose, PoseArray, PoseStamped, Quaternion, Transform, TransformStamped, Vector3,
};
pub use sensor_msgs::{CompressedImage, JointState};
pub use std_msgs::ColorRGBA;
pub use std_msgs::{
    Float32MultiArray, Float64MultiArray, Header, MultiArrayDimension, MultiArrayLayout, StringMsg,
};
pub use std_srvs::{TriggerRequest, TriggerResponse};
pub use tf2_msgs::TFMessage;
pub use visualization_msgs::{Marker, MarkerArray};
