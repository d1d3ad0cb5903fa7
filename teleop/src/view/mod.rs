//! The live 3D view (`--view [ADDR:]PORT`): what the station publishes, served to the Foxglove
//! app over the Foxglove WebSocket protocol, with no ROS installation on the viewing machine.
//!
//! The station copies every message it sends into its [`Tap`](crate::station_node::tap::Tap)
//! (already CDR-encoded, with its ROS type name and `ros2msg` schema text). The view makes a
//! channel per topic on the topic's first message (message encoding `cdr`, schema encoding
//! `ros2msg`, the schema named by the ROS type, e.g. `tf2_msgs/msg/TFMessage`) and keeps the
//! last latched message of each topic (the hand's drawing, `/tf_static`) to send to a viewer
//! that subscribes later. The server is the Foxglove SDK's (`foxglove` crate, feature
//! `websocket`), built with the teleop feature `view` (on by default).

mod address;
#[cfg(feature = "view")]
mod error;
pub mod live_view;
#[cfg(feature = "view")]
mod server;
#[cfg(feature = "view")]
mod topic_channels;

pub use address::{ViewAddress, ViewAddressError};
#[cfg(feature = "view")]
pub use error::ViewError;
#[cfg(feature = "view")]
pub use server::{ViewReport, ViewServer};
#[cfg(feature = "view")]
pub use topic_channels::{MESSAGE_ENCODING, SCHEMA_ENCODING, ViewCounts};
